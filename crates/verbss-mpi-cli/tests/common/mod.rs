//! What the MPI tests share: whether they can run, and `mpirun`.

pub use verbss_testkit::mpirun;

/// Whether this build has its MPI parts and `mpirun` runs; otherwise the
/// test skips with a notice (`verbss_testkit::mpi_ready`).
pub fn mpi_ready() -> bool {
    verbss_testkit::mpi_ready(verbss_mpi::missing())
}
