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
//! * [`cost`] counts what one sweep sends on a given partition.
//!
//! See `docs/distributed.md`.

#![warn(missing_docs)]

pub mod colouring;
pub mod cost;
pub mod coupled;
pub mod halo;
pub mod part;
pub mod partition;
pub mod pieces;
pub mod stepper;
pub mod sweeper;
