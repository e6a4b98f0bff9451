//! # verbss-mpi — VerBSS mesh motion over MPI
//!
//! The library of the `verbss-mpi` command (crate `verbss-mpi-cli`) and of
//! flow solvers that run on MPI: it depends on the core `verbss` only.
//!
//! Two ways to spread one deformer ([`verbss::deform::Deformer`], the one
//! step loop) over the ranks:
//!
//! * **Every rank holds the whole mesh** ([`stepper`]): the same deformer
//!   on every rank, its springs solved over the ranks
//!   ([`stepper::Distributed`]: METIS parts, [`sweeper::Sweeper`]'s
//!   colour-by-colour sweeps with the single-process engine's colours, so
//!   the iterates are one process's).
//! * **No rank holds the whole mesh** ([`domain`]): each rank's share is
//!   read on its own ([`share`] for partitioned MSH 4.1 files, [`scatter`]
//!   and `repartition` for SU2, [`cgns_read`] for CGNS), its ghost layer
//!   added ([`ghosts`]), and the deformer runs on that part with the ranks
//!   as its [`verbss::collective::Collective`] ([`ranks::Ranks`]) and the
//!   part's sweeps as its spring solver ([`coupled::LocalSolver`]).
//!
//! [`coupled::LocalSolver`] is also the entry point of a flow solver that
//! already has its partition and communicator; [`cost`] counts what one
//! sweep sends on a given partition; [`pieces`] writes a rank's cells.
//!
//! The MPI parts are built when `build.rs` finds MPI and METIS
//! ([`missing`] says why they were not), `repartition` when it also finds
//! PT-Scotch ([`ptscotch_missing`]); [`colouring`], [`cost`], [`part`],
//! [`pieces`] and [`share`] (except [`share::read_rank_share`]) need
//! neither. The crate's only `unsafe` code calls MPI and METIS (the private
//! module `sys`).
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
pub mod domain;
#[cfg(with_mpi)]
pub mod ghosts;
#[cfg(with_mpi)]
pub mod halo;
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
