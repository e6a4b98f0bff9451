//! The SU2 input of `verbss-mpi deform … -o OUT.pvtu`: rank 0 reads the
//! file once in chunks and scatters it ([`verbss_mpi::scatter`]), PT-Scotch
//! cuts it and every rank gets its part (`verbss_mpi::repartition`). A build
//! without PT-Scotch refuses it (exit code 2).
//!
//! `VERBSS_MPI_CHUNK_LINES` sets the lines of a chunk (default
//! [`CHUNK_LINES`]): what rank 0 holds at most of the file at once.

use std::path::Path;

use anyhow::Context;
use verbss::io::gmsh::partitioned::Share;
use verbss_mpi::Comm;

/// The lines rank 0 reads at a time unless `VERBSS_MPI_CHUNK_LINES` says otherwise.
pub const CHUNK_LINES: usize = 262_144;

/// The lines of a chunk: `VERBSS_MPI_CHUNK_LINES` (a whole number ≥ 1) or [`CHUNK_LINES`].
fn chunk_lines() -> anyhow::Result<usize> {
    match std::env::var("VERBSS_MPI_CHUNK_LINES") {
        Err(_) => Ok(CHUNK_LINES),
        Ok(text) => text
            .trim()
            .parse::<usize>()
            .ok()
            .filter(|&n| n >= 1)
            .with_context(|| {
                format!(
                    "VERBSS_MPI_CHUNK_LINES={text} (expected a whole number of lines, at least 1)"
                )
            }),
    }
}

/// This rank's part of the SU2 file at `path` (collective), and what its
/// line says of where it comes from.
#[cfg(with_ptscotch)]
pub fn read(world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
    let lines = chunk_lines()?;
    let scattered = verbss_mpi::scatter::scatter(world, path, lines)?;
    let share = verbss_mpi::repartition::repartition(world, &scattered)?;
    let from = format!(
        "PT-Scotch part {} of {} (the file's {} cells read by rank 0 in {} chunks of at most \
         {lines} lines)",
        world.rank() + 1,
        world.size(),
        scattered.elements,
        scattered.chunks
    );
    Ok((share, from))
}

/// Refuses: this build has no PT-Scotch.
#[cfg(not(with_ptscotch))]
pub fn read(_world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
    chunk_lines()?;
    Err(without_ptscotch(path, "an SU2 input"))
}

/// The error for `input` (`an SU2 input`, `a CGNS input`) at `path` with a
/// `.pvtu` output in a build without PT-Scotch.
#[cfg(not(with_ptscotch))]
pub fn without_ptscotch(path: &Path, input: &str) -> anyhow::Error {
    anyhow::anyhow!(
        "{}: {input} with a .pvtu output is cut by PT-Scotch, and verbss-mpi was built \
         without it ({}): install PT-Scotch (Debian: libptscotch-dev libscotchparmetis-dev), \
         then `cargo clean -p verbss-mpi` and build again; or give another output format",
        path.display(),
        verbss_mpi::ptscotch_missing().unwrap_or("unknown reason")
    )
}
