//! `mpirun -np N verbss-mpi deform MESH -o OUT …`: `verbss deform` with the
//! sweeps spread over N MPI ranks.
//!
//! The arguments are those of `verbss deform`, parsed and prepared by the
//! command line's library ([`verbss_cli::deform`]), so every option of
//! `verbss deform` is an option here (settings the distributed sweeps cannot
//! do are refused with exit 2 before the first step). Only the stepper
//! differs ([`run::run_distributed`]): the steps go through
//! [`verbss_mpi::stepper::Stepper`]. Rank 0 prints and writes OUT and the
//! report; every rank writes its piece `OUT-STEM_RANK.vtu` beside OUT, and
//! rank 0 the `OUT-STEM.pvtu` joining them.
//!
//! Exit codes as `verbss`: 0 success, 2 bad input, 3 an inverted element.

#![forbid(unsafe_code)]

mod run;

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use verbss_cli::deform;

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
    Deform(Box<deform::DeformArgs>),
}

fn main() -> ExitCode {
    let Some(universe) = mpi::initialize() else {
        eprintln!("error: MPI could not be initialised");
        return ExitCode::from(2);
    };
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Deform(args) => deform::prepare(*args).and_then(run::run_distributed),
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
