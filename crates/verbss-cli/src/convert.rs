//! `verbss convert IN OUT`: read one format, write another.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use verbss::io;

use crate::msh::MshArgs;
use crate::overwrite::{mesh_inputs, mesh_outputs, note_lost_su2_blocks};
use crate::zone::{self, ZoneArg};

/// Arguments of `verbss convert`.
#[derive(Args)]
pub struct ConvertArgs {
    /// Input mesh (.msh, .su2, .vtu, .cgns, an OpenFOAM case directory).
    input: PathBuf,
    /// Output mesh; its extension chooses the format (none: an OpenFOAM case).
    output: PathBuf,
    #[command(flatten)]
    msh: MshArgs,
    #[command(flatten)]
    zone: ZoneArg,
    /// Allow the output to be the input file.
    #[arg(long)]
    overwrite: bool,
}

/// Runs `verbss convert`.
pub fn run(args: ConvertArgs) -> anyhow::Result<ExitCode> {
    io::outputs::check(
        &mesh_inputs(&args.input),
        &mesh_outputs("the output", &args.output, args.overwrite),
    )?;
    // SU2 to SU2 keeps every zone: no note that only one is used. Any other
    // input keeps its notes (a CGNS file's zones among them).
    let is_su2 = |p: &std::path::Path| matches!(io::Format::from_path(p), Ok(io::Format::Su2));
    let every_zone_kept = is_su2(&args.input) && is_su2(&args.output);
    let mesh = zone::read(&args.input, args.zone.zone, "--zone K", every_zone_kept)?;
    io::write(&args.output, &mesh, &args.msh.options(&mesh))?;
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
