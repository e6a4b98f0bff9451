//! Running a `verbss deform` job over the ranks of `MPI_COMM_WORLD`:
//! `verbss`'s own runner ([`verbss_cli::run::execute`]) with the
//! distributed stepper, rank 0 writing the outputs, and the per-rank pieces
//! added.

use std::process::ExitCode;

use verbss_cli::run::{execute, Prepared};
use verbss_mpi::pieces::{write_piece, write_pvtu};
use verbss_mpi::stepper::stepper;
use verbss_mpi::Comm;

/// Whether this process is rank 0 of `MPI_COMM_WORLD` (the one that prints).
pub fn is_root() -> bool {
    Comm::world().rank() == 0
}

/// Runs a prepared job on every rank: the steps of `verbss`, rank 0 writing
/// its outputs; after a completed run every rank writes its piece of the
/// final state and rank 0 the `.pvtu` joining them.
pub fn run_distributed(mut prepared: Prepared) -> anyhow::Result<ExitCode> {
    let world = Comm::world();
    let root = world.rank() == 0;
    let job = &prepared.job;
    let mut stepper = stepper(
        &world,
        &job.mesh,
        &job.attachments,
        job.deformer_settings(&prepared.recorder),
    )?;
    let quiet = prepared.quiet || !root;
    let mut summary = execute(job, &mut stepper, quiet, root, &mut prepared.recorder)?;
    summary.ranks = Some(world.size() as usize);
    if summary.failure.is_none() {
        let current = stepper.current();
        write_piece(
            &job.dir,
            &job.name,
            stepper.solver().part(),
            &job.mesh,
            &current.coords,
            &current.quality,
        )?;
        world.barrier();
        if root {
            write_pvtu(&job.dir, &job.name, world.size())?;
        }
    }
    Ok(summary.print(job, root))
}
