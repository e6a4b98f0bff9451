//! Running a `verbss deform` job over the ranks of `MPI_COMM_WORLD`, every
//! rank holding the whole mesh:
//! `verbss`'s own runner ([`verbss_cli::run::execute`]) with the
//! distributed stepper, rank 0 writing the outputs, and the per-rank pieces
//! added.

use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;

use verbss::io::outputs::Output;
use verbss_cli::overwrite::{check_outputs, whole_files};
use verbss_cli::run::{execute, Files, Prepared};
use verbss_mpi::pieces::{piece_path, write_piece, write_pvtu};
use verbss_mpi::share::agree;
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
    let mut files = whole_files(job);
    files.extend(
        (0..world.size())
            .map(|r| Output::new("a rank's piece", piece_path(&job.dir, &job.name, r))),
    );
    files.push(Output::new(
        "a rank's piece",
        job.dir.join(format!("{}.pvtu", job.name)),
    ));
    let checked = check_outputs(job, &prepared.recorder, files);
    told(agree(&world, checked, "refused its outputs"))?;
    let mut stepper = stepper(
        &world,
        Arc::clone(&job.mesh),
        &job.attachments,
        job.deformer_settings(&prepared.recorder),
    )?;
    let quiet = prepared.quiet || !root;
    let mut summary = execute(
        job,
        &mut stepper,
        quiet,
        root,
        &mut prepared.recorder,
        &mut Files::new(root),
    )?;
    summary.ranks = Some(world.size() as usize);
    if summary.failure.is_none() {
        let current = stepper.current();
        let written = write_piece(
            &job.dir,
            &job.name,
            stepper.solver().part(),
            &job.mesh,
            &current.coords,
            &current.qualities(&job.mesh),
        );
        join_pieces(&world, &job.dir, &job.name, written)?;
    }
    Ok(summary.print(job, root))
}

/// After every rank wrote its piece `dir/NAME_RANK.vtu` (`written`, its
/// outcome), rank 0 writes `dir/NAME.pvtu` joining them (collective). Every
/// rank learns of a failure, the lowest failing rank's message, so that
/// none waits for the others.
pub fn join_pieces(
    world: &Comm,
    dir: &Path,
    name: &str,
    written: verbss::Result<()>,
) -> anyhow::Result<()> {
    told(agree(world, written, "could not write its piece"))?;
    let joined = match world.rank() {
        0 => write_pvtu(dir, name, world.size()),
        _ => Ok(()),
    };
    told(agree(world, joined, "could not write the .pvtu"))
}

/// A collective outcome ([`agree`]) as the program says it: another
/// rank's failure told as it is, not as a mesh or setting error.
pub fn told<T>(result: verbss::Result<T>) -> anyhow::Result<T> {
    result.map_err(|e| match e {
        verbss::Error::InvalidMesh(told) | verbss::Error::InvalidSetting(told) => {
            anyhow::anyhow!(told)
        }
        own => own.into(),
    })
}
