//! # verbss-mpi — VerBSS mesh motion over MPI
//!
//! The mesh is cut into parts by METIS ([`partition`]); each rank owns the
//! nodes of its part and holds one ghost layer ([`part::Part`]); the VerBSS
//! sweeps go colour by colour with a neighbour-to-neighbour ghost exchange
//! after each colour ([`sweeper::Sweeper`], [`halo`]), and the eq.-8 stop
//! test is an all-reduce. With the single-process engine's colours
//! ([`colouring::engine_colours`]) the iterates are those of one process.
//!
//! * `verbss-mpi deform …` (the binary) takes the arguments of `verbss deform`;
//! * [`coupled::LocalSolver`] is the entry point of a flow solver that
//!   already has its partition and communicator;
//! * [`cost`] counts what one sweep sends on a given partition;
//! * [`share`] reads a rank's own partitions of a partitioned MSH 4.1 file,
//!   for [`coupled::LocalSolver`], without any rank holding the whole mesh;
//! * [`scatter`] reads an SU2 file on rank 0 in one pass and scatters it in
//!   blocks, and `repartition` (built with PT-Scotch) cuts it with PT-Scotch
//!   and gives each rank its part's share, again without any rank holding
//!   the whole mesh;
//! * [`cgns_read`] reads a CGNS file in blocks on every rank, into the same
//!   scattered blocks for the same cut;
//! * [`ghosts`] adds a rank's ghost layer, and [`near_wall`] finds the
//!   rigid layer and the wall-distance stiffening on it;
//! * [`step_quality`] reduces a step's quality report over the ranks;
//! * [`ranks::Ranks`] gives the computations written once for a whole mesh
//!   or a part ([`verbss::collective::Collective`]: the blended rigid
//!   motion, the wall distances' walks) their sums and ghost values.
//!
//! The MPI parts ([`Comm`], [`cgns_read`], [`coupled`], [`ghosts`], [`halo`],
//! [`near_wall`], [`partition`], [`ranks`],
//! [`scatter`], [`step_quality`], [`stepper`], [`sweeper`]) are built when `build.rs` finds
//! MPI and METIS ([`missing`] says why they were not), `repartition` when it
//! also finds PT-Scotch ([`ptscotch_missing`]); [`colouring`], [`cost`], [`part`],
//! [`pieces`] and [`share`] (except [`share::read_rank_share`]) need neither. The crate's only `unsafe` code calls MPI and
//! METIS (the private module `sys`).
//!
//! See `docs/distributed.md`.

#![warn(missing_docs)]
#![deny(unsafe_code)]

#[cfg(with_mpi)]
pub mod cgns_read;
pub mod colouring;
pub mod cost;
#[cfg(with_mpi)]
pub mod coupled;
#[cfg(with_mpi)]
pub mod directory;
#[cfg(with_mpi)]
pub mod ghosts;
#[cfg(with_mpi)]
pub mod halo;
#[cfg(with_mpi)]
pub mod near_wall;
pub mod part;
#[cfg(with_mpi)]
pub mod partition;
pub mod pieces;
#[cfg(with_mpi)]
pub mod ranks;
#[cfg(with_ptscotch)]
pub mod repartition;
#[cfg(with_mpi)]
pub mod scatter;
pub mod share;
#[cfg(with_mpi)]
pub mod step_quality;
#[cfg(with_mpi)]
pub mod stepper;
#[cfg(with_mpi)]
pub mod sweeper;
#[cfg(with_mpi)]
#[allow(unsafe_code)]
mod sys;

#[cfg(with_mpi)]
pub use sys::{Comm, Mpi, Scalar};

/// Why this build cannot partition with PT-Scotch (no MPI, or no PT-Scotch
/// was found when it was compiled), which the distributed read of SU2
/// files needs (`scatter`, `repartition`); `None` when it can.
pub fn ptscotch_missing() -> Option<&'static str> {
    let why = env!("VERBSS_PTSCOTCH_MISSING");
    (!why.is_empty()).then_some(why)
}

/// Why this build has no MPI parts (no MPI or no METIS was found when it
/// was compiled); `None` when it has them.
pub fn missing() -> Option<&'static str> {
    let why = env!("VERBSS_MPI_MISSING");
    (!why.is_empty()).then_some(why)
}
