//! The stepper of `verbss-mpi deform`: [`verbss::deform::Deformer`] itself,
//! its springs solved over the ranks by [`Distributed`].
//!
//! Every rank reads the whole mesh and builds the same
//! [`Deformer`], which resolves the node roles, the slide planes, the rigid
//! layer, each step's boundary targets, the sub-steps, the predictor and
//! the inversion guard exactly as `verbss deform` does: the step loop exists
//! once, in the library. Only the solve differs. Rank 0 cuts the nodes with
//! METIS and broadcasts the cut; each rank keeps its [`Part`] and sweeps its
//! rows ([`Sweeper`]) with the engine's colours ([`engine_colours`],
//! computed from the whole graph on every rank), so the solution is the
//! single-process one; one all-gather then gives every rank the whole
//! displacement. The exact solve (the step loop's last word before it
//! rejects a step, and where the sweeps do not converge) is rank 0's
//! [`Engine`], its solution broadcast.

use std::sync::Arc;

use verbss::deform::Deformer;
use verbss::motion::Attachment;
use verbss::settings::Settings;
use verbss::solve::{Engine, NodeRole, SolveInfo, SolveParams, SolverSetup, SpringSolver, Stage};
use verbss::topology::{self, Csr};
use verbss::{Error, Mesh, Result};

use crate::colouring::{engine_colours, is_seed};
use crate::part::Part;
use crate::partition::partition;
use crate::sweeper::Sweeper;
use crate::Comm;

/// A mesh in motion over the ranks of a communicator.
pub type Stepper<'c> = Deformer<Distributed<'c>>;

/// Prepares `mesh` for `attachments` on every rank of `comm` (collective;
/// every rank passes the same arguments). Settings the distributed sweeps
/// cannot do are refused here, before any step.
pub fn stepper<'c>(
    comm: &'c Comm,
    mesh: Arc<Mesh>,
    attachments: &[Attachment],
    settings: Settings,
) -> Result<Stepper<'c>> {
    Sweeper::supports(&settings.solve)?;
    Deformer::with_solver(mesh, attachments, settings, |setup| {
        Distributed::new(comm, setup)
    })
}

/// The spring system of a step solved over the ranks of a communicator
/// (see the module documentation).
pub struct Distributed<'c> {
    comm: &'c Comm,
    sweeper: Sweeper<'c>,
    graph: Csr,
    dim: usize,
    roles: Vec<NodeRole>,
    /// The slide planes' unit normals, as the engine keeps them.
    normals: Vec<[f64; 3]>,
    /// Global numbers of every rank's owned nodes, rank by rank.
    owned: Vec<Vec<u64>>,
    /// The reference coordinates the colours were made for, and the colours:
    /// like the engine, a new colouring only with new springs.
    colouring: Option<(Vec<f64>, Vec<u32>)>,
    /// Rank 0's engine, for the exact solves.
    exact: Option<Engine>,
}

impl<'c> Distributed<'c> {
    /// Cuts the mesh of `setup` over the ranks of `comm` and sets up this
    /// rank's sweeper (collective).
    pub fn new(comm: &'c Comm, setup: &SolverSetup) -> Result<Distributed<'c>> {
        let mesh = setup.mesh;
        if let Some(c) = mesh.cells.first_general() {
            return Err(Error::InvalidMesh(format!(
                "element {} is a {}: verbss-mpi does not cut polygons or polyhedra over its \
                 ranks (move this mesh with verbss, one process)",
                mesh.cell_tags[c],
                mesh.cells.kinds[c].name()
            )));
        }
        let mut owner = if comm.rank() == 0 {
            partition(mesh, comm.size() as usize)?
        } else {
            vec![0; mesh.node_count()]
        };
        comm.broadcast(0, &mut owner);
        let part = Part::extract(mesh, &owner, comm.rank());
        let roles = part
            .global
            .iter()
            .map(|&g| setup.roles[g as usize])
            .collect();
        let mine: Vec<u64> = (0..part.node_count())
            .filter(|&i| part.owns(i))
            .map(|i| part.global[i])
            .collect();
        let owned = comm.all_gather(&mine);
        let factors = if setup.stiffness.is_empty() {
            Vec::new()
        } else {
            part.global
                .iter()
                .map(|&g| setup.stiffness[g as usize])
                .collect()
        };
        let mut sweeper = Sweeper::new(comm, part, roles, setup.normals)?;
        sweeper.set_stiffness(factors);
        let exact = if comm.rank() == 0 {
            Some(Engine::from_setup(setup)?)
        } else {
            None
        };
        Ok(Distributed {
            comm,
            sweeper,
            graph: topology::node_graph(&mesh.cells, mesh.node_count()),
            dim: mesh.dim,
            roles: setup.roles.to_vec(),
            normals: unit_normals(setup.normals, mesh.dim),
            owned,
            colouring: None,
            exact,
        })
    }

    /// This rank's part.
    pub fn part(&self) -> &Part {
        self.sweeper.part()
    }

    /// The distributed sweeps: every rank sweeps its rows, then gets the
    /// whole solution.
    fn sweep(&mut self, coords: &[f64], u: &mut [f64], params: &SolveParams) -> Result<SolveInfo> {
        let dim = self.dim;
        if self.colouring.as_ref().is_none_or(|(x, _)| x != coords) {
            let seeds: Vec<usize> = (0..self.roles.len())
                .filter(|&i| match dim {
                    2 => is_seed::<2>(self.roles[i], &self.normals, u, i),
                    _ => is_seed::<3>(self.roles[i], &self.normals, u, i),
                })
                .collect();
            let colours = engine_colours(&self.graph, &self.roles, &seeds);
            self.colouring = Some((coords.to_vec(), colours));
        }
        let colours = &self.colouring.as_ref().expect("coloured above").1;
        let part = self.sweeper.part();
        let pick = |a: &[f64], width: usize| -> Vec<f64> {
            let mut out = Vec::with_capacity(width * part.node_count());
            for &g in &part.global {
                let g = g as usize;
                out.extend_from_slice(&a[width * g..width * (g + 1)]);
            }
            out
        };
        let local_coords = pick(coords, dim);
        let mut local_u = pick(u, dim);
        let local_colours: Vec<u32> = part.global.iter().map(|&g| colours[g as usize]).collect();
        let mut info = self
            .sweeper
            .solve(&local_coords, &local_colours, &mut local_u, params)?;
        if let Some(&g) = self.sweeper.part().global.get(info.worst_node) {
            info.worst_node = g as usize;
        }
        self.gather(&local_u, u);
        Ok(info)
    }

    /// Every rank's owned values of `local` (`D` per local node) into the
    /// whole-mesh vector `u`, on every rank (one all-gather).
    fn gather(&self, local: &[f64], u: &mut [f64]) {
        let part = self.sweeper.part();
        let dim = part.dim;
        let mine: Vec<f64> = (0..part.node_count())
            .filter(|&i| part.owns(i))
            .flat_map(|i| local[dim * i..dim * (i + 1)].iter().copied())
            .collect();
        for (nodes, values) in self.owned.iter().zip(self.comm.all_gather(&mine)) {
            for (k, &g) in nodes.iter().enumerate() {
                let g = g as usize;
                u[dim * g..dim * (g + 1)].copy_from_slice(&values[dim * k..dim * (k + 1)]);
            }
        }
    }
}

impl SpringSolver for Distributed<'_> {
    /// The distributed sweeps; where they stop unconverged and the settings
    /// escalate, the exact solve.
    fn solve(&mut self, coords: &[f64], u: &mut [f64], params: &SolveParams) -> Result<SolveInfo> {
        let guess = u.to_vec();
        let swept = self.sweep(coords, u, params)?;
        if swept.converged || !params.escalate {
            return Ok(swept);
        }
        u.copy_from_slice(&guess);
        let mut info = self.solve_exact(coords, u, params)?;
        info.iterations += swept.iterations;
        info.form_seconds += swept.form_seconds;
        info.solve_seconds += swept.solve_seconds;
        info.stages.insert(0, Stage::Sweeps);
        Ok(info)
    }

    /// Rank 0's exact solve, broadcast: every rank gets the same solution
    /// and account, or the same failure.
    fn solve_exact(
        &mut self,
        coords: &[f64],
        u: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        let solved = self
            .exact
            .as_mut()
            .map(|engine| engine.solve_exact(coords, u, params));
        let mut failed = [u8::from(matches!(solved, Some(Err(_))))];
        self.comm.broadcast(0, &mut failed);
        if failed[0] != 0 {
            return Err(match solved {
                Some(Err(e)) => e,
                _ => Error::InvalidMesh("rank 0's exact solve of the step failed".into()),
            });
        }
        let mut info = solved.and_then(Result::ok).unwrap_or_default();
        self.comm.broadcast(0, u);
        let mut numbers = [
            info.iterations as f64,
            info.residual,
            f64::from(u8::from(info.converged)),
            info.form_seconds,
            info.solve_seconds,
            info.true_residual,
            info.error_ratio,
            info.worst_node as f64,
        ];
        self.comm.broadcast(0, &mut numbers);
        let mut stages: Vec<u8> = info.stages.iter().map(|&s| s as u8).collect();
        let mut count = [stages.len() as u64];
        self.comm.broadcast(0, &mut count);
        stages.resize(count[0] as usize, 0);
        self.comm.broadcast(0, &mut stages);
        info.iterations = numbers[0] as usize;
        info.residual = numbers[1];
        info.converged = numbers[2] != 0.0;
        info.form_seconds = numbers[3];
        info.solve_seconds = numbers[4];
        info.true_residual = numbers[5];
        info.error_ratio = numbers[6];
        info.worst_node = numbers[7] as usize;
        info.stages = stages
            .into_iter()
            .map(|k| Stage::ALL[usize::from(k)])
            .collect();
        Ok(info)
    }
}

/// The plane normals as the engine keeps them: the first `dim` numbers,
/// divided by their length.
fn unit_normals(normals: &[[f64; 3]], dim: usize) -> Vec<[f64; 3]> {
    normals
        .iter()
        .map(|v| {
            let len = verbss::geometry::norm(&[v[0], v[1], if dim == 3 { v[2] } else { 0.0 }]);
            let mut u = [v[0] / len, v[1] / len, 0.0];
            if dim == 3 {
                u[2] = v[2] / len;
            }
            u
        })
        .collect()
}
