//! `verbss convert IN OUT`: read one format, write another.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use verbss::io;

use crate::msh::MshArgs;
use crate::overwrite::{note_lost_su2_blocks, refuse_input_as_output};

/// Arguments of `verbss convert`.
#[derive(Args)]
pub struct ConvertArgs {
    /// Input mesh (.msh, .su2, .vtu).
    input: PathBuf,
    /// Output mesh; its extension chooses the format.
    output: PathBuf,
    #[command(flatten)]
    msh: MshArgs,
    /// Allow the output to be the input file.
    #[arg(long)]
    overwrite: bool,
}

/// Runs `verbss convert`.
pub fn run(args: ConvertArgs) -> anyhow::Result<ExitCode> {
    refuse_input_as_output(&args.input, &args.output, args.overwrite)?;
    let mesh = io::read(&args.input)?;
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
