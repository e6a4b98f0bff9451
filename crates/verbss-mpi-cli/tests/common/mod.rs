//! What the MPI tests share: whether they can run, and `mpirun`.

use std::path::Path;
use std::process::Command;

use verbss_testkit::{needs, program};

/// Whether this build has its MPI parts and `mpirun` runs; otherwise the
/// test skips with a notice (`verbss_testkit::needs`).
pub fn mpi_ready() -> bool {
    needs(
        "Open MPI and METIS when verbss-mpi is built (Debian: libopenmpi-dev libmetis-dev, \
         then cargo clean -p verbss-mpi)",
        verbss_mpi::missing().map_or(Ok(()), |why| Err(why.into())),
    ) && needs(
        "mpirun (Debian: openmpi-bin)",
        program("mpirun", &["--version"]),
    )
}

/// `mpirun --oversubscribe -np NP` (root allowed, as in containers), with
/// the session directory `session` of its own: two mpiruns started at once
/// race for the shared one under /tmp.
pub fn mpirun(np: usize, session: &Path) -> Command {
    let mut command = Command::new("mpirun");
    command
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_orte_tmpdir_base", session)
        .args(["--oversubscribe", "-np", &np.to_string()]);
    command
}
