//! The stepper of `verbss-mpi deform`: [`verbss::deform::Deformer`]'s steps
//! with the solve distributed.
//!
//! Every rank reads the whole mesh and builds the same
//! [`Deformer`](verbss::deform::Deformer), which resolves the node roles,
//! the slide planes, the rigid layer and each step's boundary targets
//! exactly as `verbss deform` does. Rank 0 cuts the nodes with METIS and
//! broadcasts the cut; each rank keeps its [`Part`] and sweeps its rows
//! ([`Sweeper`]) with the engine's colours ([`engine_colours`], computed
//! from the whole graph on every rank), so the solution is the
//! single-process one. After each solve one all-gather gives every rank the
//! whole displacement, from which the new coordinates, the inversion check
//! and the adaptive sub-steps follow as in the single-process stepper. The
//! near-wall treatments come along: rigid-layer nodes are prescribed nodes
//! with targets, and the stiffened springs are the Deformer's factors.

use std::time::Instant;

use verbss::deform::{Deformer, Reference, Settings, Snapshot, StepReport};
use verbss::motion::Attachment;
use verbss::quality::{self, Inversion, Summary};
use verbss::solve::{clear_prescribed, SolveInfo};
use verbss::topology::{self, Csr};
use verbss::{Error, Mesh, Result};

use crate::colouring::{engine_colours, is_seed};
use crate::part::Part;
use crate::partition::partition;
use crate::sweeper::Sweeper;
use crate::Comm;

/// A mesh in motion over the ranks of a communicator (see the module documentation).
pub struct Stepper<'c> {
    comm: &'c Comm,
    deformer: Deformer,
    sweeper: Sweeper<'c>,
    graph: Csr,
    /// Global numbers of every rank's owned nodes, rank by rank.
    owned: Vec<Vec<u64>>,
    orientation: Vec<i8>,
    /// The last increment per unit step fraction, every node.
    guess: Vec<f64>,
    /// The reference coordinates the colours were made for, and the colours:
    /// like the engine, a new colouring only with new springs.
    colouring: Option<(Vec<f64>, Vec<u32>)>,
    current: Snapshot,
    failed: Option<Snapshot>,
}

impl<'c> Stepper<'c> {
    /// Prepares `mesh` for `attachments` on every rank of `comm`
    /// (collective; every rank passes the same arguments).
    pub fn new(
        comm: &'c Comm,
        mesh: &Mesh,
        attachments: &[Attachment],
        settings: Settings,
    ) -> Result<Stepper<'c>> {
        let deformer = Deformer::new(mesh, attachments, settings)?;
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
            .map(|&g| deformer.roles()[g as usize])
            .collect();
        let mine: Vec<u64> = (0..part.node_count())
            .filter(|&i| part.owns(i))
            .map(|i| part.global[i])
            .collect();
        let owned = comm.all_gather(&mine);
        let stiffness = deformer.stiffness();
        let factors = if stiffness.is_empty() {
            Vec::new()
        } else {
            part.global.iter().map(|&g| stiffness[g as usize]).collect()
        };
        let mut sweeper = Sweeper::new(comm, part, roles, deformer.normals())?;
        sweeper.set_stiffness(factors);
        Ok(Stepper {
            comm,
            graph: topology::node_graph(&mesh.cells, mesh.node_count()),
            owned,
            orientation: quality::orientation(mesh),
            guess: vec![0.0; mesh.coords.len()],
            colouring: None,
            current: deformer.current().clone(),
            failed: None,
            sweeper,
            deformer,
        })
    }

    /// This rank's part.
    pub fn part(&self) -> &Part {
        self.sweeper.part()
    }

    /// The input mesh.
    pub fn initial(&self) -> &Mesh {
        self.deformer.initial()
    }

    /// The last accepted configuration (the whole mesh, on every rank).
    pub fn current(&self) -> &Snapshot {
        &self.current
    }

    /// The configuration of the step that failed the inversion check, if any.
    pub fn failed(&self) -> Option<&Snapshot> {
        self.failed.as_ref()
    }

    /// The input mesh with the current coordinates.
    pub fn mesh(&self) -> Mesh {
        let mut mesh = self.deformer.initial().clone();
        mesh.coords.clone_from(&self.current.coords);
        mesh
    }

    /// [`Deformer::step`] over the ranks (collective): moves the boundary to
    /// its position at step `n`, the interior with it, in sub-steps when
    /// [`Settings::robust`] asks for them.
    pub fn step(&mut self, n: usize) -> Result<StepReport> {
        let start = Instant::now();
        let dim = self.deformer.initial().dim;
        let targets = self.deformer.targets(n)?;
        let settings = self.deformer.settings().clone();
        let substeps = match settings.reference {
            Reference::Updated => settings.robust.substeps.min(30),
            Reference::Fixed => 0,
        };
        let floor = 0.5f64.powi(substeps as i32);
        let from = self.current.coords.clone();
        let mut coords = from.clone();
        let (mut done, mut h) = (0.0, 1.0);
        let mut report = StepReport::default();
        report.step = n;
        report.converged = true;
        loop {
            let end = if done + h >= 1.0 { 1.0 } else { done + h };
            let at: Vec<(usize, Vec<f64>)> = targets
                .iter()
                .map(|(i, p)| {
                    let x0 = &from[dim * i..dim * (i + 1)];
                    let q = if end == 1.0 {
                        p.clone()
                    } else {
                        x0.iter().zip(p).map(|(a, b)| a + end * (b - a)).collect()
                    };
                    (*i, q)
                })
                .collect();
            let (trial, u, info, inversions) = self.attempt(&coords, &at, end - done)?;
            report.iterations += info.iterations;
            report.residual = info.residual;
            report.converged &= info.converged;
            report.form_seconds += info.form_seconds;
            report.solve_seconds += info.solve_seconds;
            report.history = info.history;
            if let Some(worst) = inversions
                .iter()
                .min_by(|a, b| a.volume.total_cmp(&b.volume))
            {
                if h * 0.5 >= floor {
                    h *= 0.5;
                    continue;
                }
                report.substeps += 1;
                let err = Error::Inverted {
                    step: n,
                    count: inversions.len(),
                    element: self.deformer.initial().cell_tags[worst.cell],
                    centroid: worst.centroid.clone(),
                    volume: worst.volume,
                };
                self.failed = Some(self.snapshot(trial, &inversions, report, start));
                return Err(err);
            }
            report.substeps += 1;
            let fraction = end - done;
            self.guess = u.iter().map(|v| v / fraction).collect();
            coords = trial;
            done = end;
            if done >= 1.0 {
                self.current = self.snapshot(coords, &inversions, report, start);
                return Ok(self.current.report.clone());
            }
            h = (2.0 * h).min(1.0 - done);
        }
    }

    /// One distributed solve from `coords` with the prescribed nodes at
    /// `targets`, an increment of `fraction` of a step: the new coordinates,
    /// the solved displacement, the solver's account and the inverted cells.
    #[allow(clippy::type_complexity)]
    fn attempt(
        &mut self,
        coords: &[f64],
        targets: &[(usize, Vec<f64>)],
        fraction: f64,
    ) -> Result<(Vec<f64>, Vec<f64>, SolveInfo, Vec<Inversion>)> {
        let start = self.deformer.blended(coords, targets);
        let dim = self.deformer.initial().dim;
        let mut u: Vec<f64> = self.guess.iter().map(|v| v * fraction).collect();
        clear_prescribed(dim, self.deformer.roles(), self.deformer.normals(), &mut u);
        for (node, p) in targets {
            for d in 0..dim {
                u[dim * node + d] = p[d] - start[dim * node + d];
            }
        }
        let info = if self.deformer.nothing_left(&start, targets) {
            // The blend put every prescribed node on its target: every rank
            // knows it and skips the solve.
            u.fill(0.0);
            let mut info = SolveInfo::default();
            info.converged = true;
            info
        } else {
            self.solve_distributed(&start, &mut u)?
        };
        let mut next: Vec<f64> = start.iter().zip(&u).map(|(x, d)| x + d).collect();
        for (node, p) in targets {
            next[dim * node..dim * (node + 1)].copy_from_slice(p);
        }
        let inversions = quality::inversions(self.deformer.initial(), &next, &self.orientation);
        Ok((next, u, info, inversions))
    }

    /// Solves for the unknowns of `u` over the ranks, the springs built on
    /// `start` (on the input mesh with the fixed reference), and gives every
    /// rank the whole solution.
    fn solve_distributed(&mut self, start: &[f64], u: &mut [f64]) -> Result<SolveInfo> {
        let mesh = self.deformer.initial();
        let dim = mesh.dim;
        let base: &[f64] = match self.deformer.settings().reference {
            Reference::Updated => start,
            Reference::Fixed => &mesh.coords,
        };
        let roles = self.deformer.roles();
        if self.colouring.as_ref().is_none_or(|(x, _)| x != base) {
            let normals = unit_normals(self.deformer.normals(), dim);
            let seeds: Vec<usize> = (0..roles.len())
                .filter(|&i| match dim {
                    2 => is_seed::<2>(roles[i], &normals, u, i),
                    _ => is_seed::<3>(roles[i], &normals, u, i),
                })
                .collect();
            let colours = engine_colours(&self.graph, roles, &seeds);
            self.colouring = Some((base.to_vec(), colours));
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
        let local_base = pick(base, dim);
        let mut local_u = pick(u, dim);
        let local_colours: Vec<u32> = part.global.iter().map(|&g| colours[g as usize]).collect();
        let params = self.deformer.settings().solve.clone();
        let info = self
            .sweeper
            .solve(&local_base, &local_colours, &mut local_u, &params)?;
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

    /// The configuration `coords` with its quality, for the step of `report`.
    fn snapshot(
        &self,
        coords: Vec<f64>,
        inversions: &[Inversion],
        mut report: StepReport,
        start: Instant,
    ) -> Snapshot {
        let mesh = self.deformer.initial();
        let quality = quality::qualities(mesh, &coords, &self.orientation);
        let summary = Summary::new(&quality);
        report.min_quality = summary.min;
        report.mean_quality = summary.mean;
        report.inverted = inversions.len();
        for (b, bin) in report.bins.iter_mut().zip(&summary.bins) {
            *b = bin.count;
        }
        report.seconds = start.elapsed().as_secs_f64();
        let mut inverted = vec![false; quality.len()];
        for inv in inversions {
            inverted[inv.cell] = true;
        }
        Snapshot {
            coords,
            quality,
            inverted,
            report,
        }
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
