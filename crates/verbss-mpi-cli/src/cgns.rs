//! The CGNS input of `verbss-mpi deform … -o OUT.pvtu`: every rank reads
//! its own blocks of the file ([`verbss_mpi::cgns_read`]), PT-Scotch cuts it
//! and every rank gets its part (`verbss_mpi::repartition`), as for an SU2
//! input ([`crate::su2`]). A build without PT-Scotch refuses it (exit code 2).

use std::path::Path;

use verbss::io::gmsh::partitioned::Share;
use verbss_mpi::Comm;

/// This rank's part of the CGNS file at `path` (collective), and what its
/// line says of where it comes from.
#[cfg(with_ptscotch)]
pub fn read(world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
    let scattered = verbss_mpi::cgns_read::read(world, path)?;
    let share = verbss_mpi::repartition::repartition(world, &scattered)?;
    let from = format!(
        "PT-Scotch part {} of {} (the file's {} cells read in blocks by every rank)",
        world.rank() + 1,
        world.size(),
        scattered.elements
    );
    Ok((share, from))
}

/// Refuses: this build has no PT-Scotch.
#[cfg(not(with_ptscotch))]
pub fn read(_world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
    Err(crate::su2::without_ptscotch(path, "a CGNS input"))
}
