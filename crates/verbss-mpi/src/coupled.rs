//! The entry point of a flow solver that already runs on MPI with its own
//! partition: each rank passes its local mesh, the global number of each of
//! its nodes and the communicator, and gets the displacements of its nodes
//! back. verbss does not re-partition.
//!
//! ```text
//! let mut solver = LocalSolver::new(&comm, &local_mesh, &global_ids, &roles, &normals)?;  // once
//! let info = solver.solve(&coords, &mut displacement, &params)?;                          // per step
//! ```
//!
//! `comm` is the flow solver's communicator as a [`Comm`]:
//! [`Comm::world`], or [`Comm::from_fortran`] of its Fortran handle (from
//! C, `MPI_Comm_c2f(comm)`).
//! MPI is initialised by the flow solver or by [`crate::Mpi::init`].
//!
//! The local meshes may be any split of the cells (each cell on one rank or
//! on several, as with halo cells); a node on several ranks has the same
//! global number, role and coordinates on each. Setup (collective, once):
//!
//! 1. every node gets one owner, the lowest rank holding it (a directory
//!    keyed by `global mod ranks`, two all-to-all exchanges);
//! 2. every rank sends each cell to the owners of its nodes, so that each
//!    owner has every cell around its nodes and one ghost layer ([`Part`]);
//!    steps 1 and 2 are [`Ghosts::new`], which a caller may run first
//!    (to find the roles on the ghost layer) and hand to
//!    [`LocalSolver::with_ghosts`];
//! 3. the unknowns are coloured in parallel, Jones–Plassmann style: a node
//!    whose hashed global number beats those of all its uncoloured unknown
//!    neighbours takes the smallest colour none of its neighbours has,
//!    round after round with a ghost exchange in between. The colours depend
//!    only on the mesh and the global numbers, not on the number of ranks.
//!
//! Each solve then sweeps colour by colour like [`crate::sweeper`]. With
//! these colours (not the single-process engine's layer-ordered ones) the
//! sweeps converge to the same solution as one process, but the iterates
//! differ: compare converged results, not sweep counts. Results for
//! different numbers of ranks agree to rounding.

use verbss::solve::{NodeRole, SolveInfo, SolveParams};
use verbss::topology;
use verbss::{Error, Mesh, Result};

pub use crate::ghosts::Ghosts;
use crate::halo::Halo;
use crate::part::Part;
use crate::sweeper::Sweeper;
use crate::Comm;

/// A flow-solver rank's deformer (see the module documentation).
pub struct LocalSolver<'c> {
    sweeper: Sweeper<'c>,
    /// Part index of each of the caller's local nodes.
    local: Vec<usize>,
    colours: Vec<u32>,
}

impl<'c> LocalSolver<'c> {
    /// Sets up rank `comm.rank()` (collective): `mesh` is its local mesh,
    /// `global[i]` the global number of local node `i` (distinct within the
    /// rank), `roles` per local node, `normals` the sliding planes' normals
    /// (as [`verbss::solve::Engine::new`]).
    pub fn new(
        comm: &'c Comm,
        mesh: &Mesh,
        global: &[u64],
        roles: &[NodeRole],
        normals: &[[f64; 3]],
    ) -> Result<LocalSolver<'c>> {
        if roles.len() != mesh.node_count() {
            return Err(Error::InvalidSetting(format!(
                "{} roles for {} local nodes",
                roles.len(),
                mesh.node_count()
            )));
        }
        let ghosts = Ghosts::new(comm, mesh, global)?;
        LocalSolver::with_ghosts(comm, ghosts, roles, normals)
    }

    /// [`LocalSolver::new`] on a ghost layer already built (collective):
    /// `roles` per local node of the mesh `ghosts` was built from.
    pub fn with_ghosts(
        comm: &'c Comm,
        ghosts: Ghosts,
        roles: &[NodeRole],
        normals: &[[f64; 3]],
    ) -> Result<LocalSolver<'c>> {
        let Ghosts { part, local, halo } = ghosts;
        if roles.len() != local.len() {
            return Err(Error::InvalidSetting(format!(
                "{} roles for {} local nodes",
                roles.len(),
                local.len()
            )));
        }
        let m = part.node_count();
        // Roles of the new nodes from their owners: Free −1, Fixed −2,
        // Slide(k) k, Line(k) −3 − k.
        let mut codes = vec![0.0; m];
        for (i, r) in roles.iter().enumerate() {
            codes[local[i]] = match r {
                NodeRole::Free => -1.0,
                NodeRole::Fixed => -2.0,
                NodeRole::Slide(k) => *k as f64,
                NodeRole::Line(k) => -3.0 - *k as f64,
            };
        }
        halo.exchange(comm, &mut codes, 1);
        let part_roles: Vec<NodeRole> = codes
            .iter()
            .map(|&c| match c {
                -1.0 => NodeRole::Free,
                -2.0 => NodeRole::Fixed,
                k if k < 0.0 => NodeRole::Line((-3.0 - k) as usize),
                k => NodeRole::Slide(k as usize),
            })
            .collect();
        let colours = jones_plassmann(comm, &part, &part_roles, &halo);
        let sweeper = Sweeper::new(comm, part, part_roles, normals)?;
        Ok(LocalSolver {
            sweeper,
            local,
            colours,
        })
    }

    /// One step (collective): `coords` are the local nodes' reference
    /// coordinates, `displacement` their prescribed values and initial
    /// guesses on entry and the solution on return (`D` numbers per local
    /// node each). Settings as [`verbss::solve::Engine::solve`], with the
    /// methods of [`Sweeper::solve`].
    pub fn solve(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        self.solve_with(coords, displacement, params, false)
    }

    /// The step solved to round-off from the guess in `displacement`
    /// ([`Sweeper::solve_exact`]), as [`LocalSolver::solve`] takes its
    /// arrays (collective).
    pub fn solve_exact(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        self.solve_with(coords, displacement, params, true)
    }

    /// [`LocalSolver::solve`], or [`LocalSolver::solve_exact`] when `exact`.
    fn solve_with(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
        exact: bool,
    ) -> Result<SolveInfo> {
        let dim = self.sweeper.part().dim;
        let n = self.local.len();
        if coords.len() != dim * n || displacement.len() != dim * n {
            return Err(Error::InvalidSetting(format!(
                "{} coordinates and {} displacements for {n} local nodes in {dim}D",
                coords.len(),
                displacement.len()
            )));
        }
        let m = self.sweeper.part().node_count();
        let mut x = vec![0.0; dim * m];
        let mut u = vec![0.0; dim * m];
        for (i, &p) in self.local.iter().enumerate() {
            x[dim * p..dim * (p + 1)].copy_from_slice(&coords[dim * i..dim * (i + 1)]);
            u[dim * p..dim * (p + 1)].copy_from_slice(&displacement[dim * i..dim * (i + 1)]);
        }
        self.sweeper.exchange(&mut x, dim);
        let mut info = if exact {
            self.sweeper
                .solve_exact(&x, &self.colours, &mut u, params)?
        } else {
            self.sweeper.solve(&x, &self.colours, &mut u, params)?
        };
        let worst = std::mem::replace(&mut info.worst_node, usize::MAX);
        for (i, &p) in self.local.iter().enumerate() {
            displacement[dim * i..dim * (i + 1)].copy_from_slice(&u[dim * p..dim * (p + 1)]);
            if p == worst {
                info.worst_node = i;
            }
        }
        Ok(info)
    }

    /// Sets per-local-node spring stiffness factors (as
    /// [`verbss::solve::Engine::set_stiffness`], one per local node of the
    /// caller's mesh; empty: all 1); the ghosts take their owners' factors
    /// (collective).
    pub fn set_stiffness(&mut self, factors: &[f64]) -> Result<()> {
        let n = self.local.len();
        if factors.is_empty() {
            self.sweeper.set_stiffness(Vec::new());
            return Ok(());
        }
        if factors.len() != n {
            return Err(Error::InvalidSetting(format!(
                "{} stiffness factors for {n} local nodes",
                factors.len()
            )));
        }
        let mut all = vec![1.0; self.sweeper.part().node_count()];
        for (i, &p) in self.local.iter().enumerate() {
            all[p] = factors[i];
        }
        self.sweeper.exchange(&mut all, 1);
        self.sweeper.set_stiffness(all);
        Ok(())
    }

    /// This rank's part: its cells, its nodes and their ghosts.
    pub fn part(&self) -> &Part {
        self.sweeper.part()
    }

    /// The number of colours of the unknowns.
    pub fn colours(&self) -> u32 {
        self.colours
            .iter()
            .filter(|&&c| c != u32::MAX)
            .map(|&c| c + 1)
            .max()
            .unwrap_or(0)
    }
}

/// Parallel greedy colouring of the unknown nodes of `part` (see the
/// module documentation); `u32::MAX` for prescribed nodes.
fn jones_plassmann(comm: &Comm, part: &Part, roles: &[NodeRole], halo: &Halo) -> Vec<u32> {
    let n = part.node_count();
    let graph = topology::node_graph(&part.cells, n);
    let unknown = |i: usize| roles[i] != NodeRole::Fixed;
    let priority = |i: usize| (mix(part.global[i]), part.global[i]);
    let mut colour = vec![f64::NAN; n];
    let mut used: Vec<u32> = Vec::new();
    loop {
        let mut chosen = Vec::new();
        for i in (0..n).filter(|&i| part.owns(i) && unknown(i) && colour[i].is_nan()) {
            let wins = graph
                .entries(i)
                .all(|j| !unknown(j) || !colour[j].is_nan() || priority(j) < priority(i));
            if wins {
                used.clear();
                used.extend(
                    graph
                        .entries(i)
                        .filter(|&j| !colour[j].is_nan())
                        .map(|j| colour[j] as u32),
                );
                used.sort_unstable();
                let mut c = 0;
                for &u in &used {
                    if u == c {
                        c += 1;
                    } else if u > c {
                        break;
                    }
                }
                chosen.push((i, c));
            }
        }
        for (i, c) in chosen {
            colour[i] = f64::from(c);
        }
        halo.exchange(comm, &mut colour, 1);
        let left = (0..n)
            .filter(|&i| part.owns(i) && unknown(i) && colour[i].is_nan())
            .count() as u64;
        if comm.sum(left) == 0 {
            break;
        }
    }
    colour
        .iter()
        .map(|&c| if c.is_nan() { u32::MAX } else { c as u32 })
        .collect()
}

/// A fixed 64-bit mix (SplitMix64's finaliser): priorities that look random
/// but are the same on every rank and every run.
fn mix(g: u64) -> u64 {
    let mut z = g.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
