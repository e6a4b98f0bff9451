//! `verbss convert IN OUT`: read one format, write another.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, ValueEnum};
use verbss::io::{self, MshVersion, WriteOptions};

use crate::overwrite::{note_lost_su2_blocks, refuse_input_as_output};
use crate::zone::{self, ZoneArg};

/// Arguments of `verbss convert`.
#[derive(Args)]
pub struct ConvertArgs {
    /// Input mesh (.msh, .su2, .vtu, .cgns, an OpenFOAM case directory).
    input: PathBuf,
    /// Output mesh; its extension chooses the format (none: an OpenFOAM case).
    output: PathBuf,
    /// Gmsh file-format version of a .msh output.
    #[arg(long, value_enum, default_value = "4.1")]
    msh_version: MshVersionArg,
    /// Write a binary .msh.
    #[arg(long)]
    binary: bool,
    #[command(flatten)]
    zone: ZoneArg,
    /// Allow the output to be the input file.
    #[arg(long)]
    overwrite: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum MshVersionArg {
    #[value(name = "2.2")]
    V22,
    #[value(name = "4.1")]
    V41,
}

/// Runs `verbss convert`.
pub fn run(args: ConvertArgs) -> anyhow::Result<ExitCode> {
    refuse_input_as_output(&args.input, &args.output, args.overwrite, false)?;
    let su2_out = matches!(io::Format::from_path(&args.output), Ok(io::Format::Su2));
    let mesh = zone::read(&args.input, args.zone.zone, "--zone K", su2_out)?;
    let mut options = WriteOptions::default();
    options.msh_version = match args.msh_version {
        MshVersionArg::V22 => MshVersion::V22,
        MshVersionArg::V41 => MshVersion::V41,
    };
    options.binary = args.binary;
    io::write(&args.output, &mesh, &options)?;
    note_lost_su2_blocks(&mesh, &args.output);
    println!(
        "wrote {} ({} nodes, {} elements, {} groups)",
        args.output.display(),
        mesh.node_count(),
        mesh.cell_count(),
        mesh.groups.len()
    );
    Ok(ExitCode::SUCCESS)
}
