//! `mpirun -np N verbss-mpi deform MESH -o OUT …`: `verbss deform` with the
//! sweeps spread over N MPI ranks.
//!
//! The arguments are those of `verbss deform`, parsed by the very same
//! source file (`crates/verbss-cli/src/deform.rs`, compiled into this binary
//! too), so every option of `verbss deform` is an option here. Only the
//! running of the job differs ([`run::execute`]): the steps go through
//! [`verbss_mpi::stepper::Stepper`]. Rank 0 prints and writes OUT and the
//! report; every rank writes its piece `OUT-STEM_RANK.vtu` beside OUT, and
//! rank 0 the `OUT-STEM.pvtu` joining them.
//!
//! Exit codes as `verbss`: 0 success, 2 bad input, 3 an inverted element.

#![forbid(unsafe_code)]

#[path = "../../verbss-cli/src/deform.rs"]
mod deform;
#[path = "../../verbss-cli/src/overwrite.rs"]
mod overwrite;
#[path = "../../verbss-cli/src/progress.rs"]
mod progress;
// Only the picture recorder of `--html`/`--gif` is used here, not the
// `verbss render` command that shares its file.
#[allow(dead_code)]
#[path = "../../verbss-cli/src/render.rs"]
mod render;
mod run;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Mesh motion by Vertex-Ball Spring Smoothing over MPI ranks (run under mpirun).
#[derive(Parser)]
#[command(name = "verbss-mpi", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Move groups by a translation, a rotation or given positions, in N steps.
    Deform(deform::DeformArgs),
}

fn main() -> ExitCode {
    let Some(universe) = mpi::initialize() else {
        eprintln!("error: MPI could not be initialised");
        return ExitCode::from(2);
    };
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Deform(args) => deform::run(args),
    };
    let code = match result {
        Ok(code) => code,
        Err(e) => {
            if run::is_root() {
                eprintln!("error: {e}");
            }
            ExitCode::from(2)
        }
    };
    drop(universe);
    code
}
