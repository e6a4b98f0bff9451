//! What the stepper needs of a solver: the seam between the step loop
//! (sub-steps, predictor, the inversion guard: [`crate::deform::Deformer`])
//! and whoever solves the spring system — the [`Engine`] in one process,
//! a distributed sweeper over MPI ranks.

use std::sync::Arc;

use crate::error::Result;
use crate::mesh::Mesh;
use crate::springs::Connectivity;
use crate::threads::Workers;
use crate::topology::Csr;

use super::{Engine, NodeRole, SolveInfo, SolveParams};

/// A solver of the node-block spring system of one (sub-)step.
///
/// Both calls take the reference coordinates `coords` the springs are built
/// on and `displacement` (`D·N`, every node): on entry the prescribed values
/// and the initial guess of the unknowns, on return the solution, as
/// [`Engine::solve`] documents.
pub trait SpringSolver {
    /// Solves with the configured solver, escalating as
    /// [`SolveParams::escalate`] says; an unconverged solve is not an error
    /// (`converged` is false).
    fn solve(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo>;

    /// Solves to round-off (what the step loop does before it rejects a
    /// step for an inverted element: an inversion is never the solver's
    /// fault).
    fn solve_exact(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo>;
}

/// What a [`SpringSolver`] is built from, once the deformer has decided
/// each node's role.
pub struct SolverSetup<'a> {
    /// The input mesh.
    pub mesh: &'a Mesh,
    /// Each node's role (rigid-layer nodes are [`NodeRole::Fixed`]).
    pub roles: &'a [NodeRole],
    /// The slide planes' normals ([`NodeRole::Slide`]`(k)` is `normals[k]`).
    pub normals: &'a [[f64; 3]],
    /// Per-node spring stiffness factors (empty: none).
    pub stiffness: &'a [f64],
    /// The mesh's edge graph when the deformer built it already (for the
    /// blended rigid motion): shared, not built again.
    pub edge_graph: Option<&'a Arc<Csr>>,
    /// The deformer's workers: the solver's parallel work runs on them
    /// while the settings ask for as many.
    pub workers: &'a Workers,
}

impl Engine {
    /// The engine of `setup`: its topology, with the stiffness factors set.
    pub fn from_setup(setup: &SolverSetup) -> Result<Engine> {
        let conn = Connectivity::with_edge_graph(setup.mesh, setup.edge_graph.cloned());
        let mut engine = Engine::with_connectivity(conn, setup.mesh, setup.roles, setup.normals)?;
        engine.set_stiffness(setup.stiffness.to_vec());
        engine.pool = Some(setup.workers.clone());
        Ok(engine)
    }
}

impl SpringSolver for Engine {
    fn solve(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        Engine::solve(self, coords, displacement, params)
    }

    fn solve_exact(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        Engine::solve_exact(self, coords, displacement, params)
    }
}
