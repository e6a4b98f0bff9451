//! The stepper: boundary motion → spring system → solve → update → check.
//!
//! A [`Deformer`] holds a mesh in motion. Each call of [`Deformer::step`]
//! moves the boundary to where its motions put it at that step, moves the
//! interior nodes by the springs and checks that no element inverted relative
//! to the input mesh's orientation; it is the call a flow solver makes once per
//! time step.
//!
//! Which node does what is decided once, in `deform/roles.rs`.
//!
//! Three ways to step (paper §3.2, step 6, and docs/method.md, "Time stepping"):
//! - [`Reference::Updated`] (option 1, the paper's): the springs are rebuilt
//!   on the current coordinates `x` and the step solves for the increment
//!   `Δu`, `x ← x + Δu`.
//! - [`Reference::Fixed`] (option 2): the springs stay those of the input mesh
//!   `X` and each step solves for the total displacement `u`, `x = X + u`.
//! - [`Reference::Anchored`] ([`Settings::robust`]'s): the input mesh moved
//!   by the blended rigid motion to the boundary's position, `B(X)`, carries
//!   the springs and the step solves for the rest, `x = B(X) + u`: `x`
//!   depends on the boundary's position only.
//!
//! Either way the previous step's solution is the next step's initial guess
//! ([`Predictor::Previous`]; [`Predictor::Linear`] extrapolates from the two
//! previous steps instead), and prescribed nodes are set exactly to their
//! motion's positions.
//!
//! [`Settings::robust`] adds the near-wall treatments of [`crate::robust`]:
//! a rigid layer of nodes that move with their wall, and adaptive sub-steps.

use std::sync::Arc;
use std::time::Instant;

use serde::Serialize;

use crate::collective::Whole;
use crate::error::{format_point, Error, Result, Unconverged};
use crate::mesh::Mesh;
use crate::motion::{Attachment, Clock, Motion};
use crate::quality::{self, Inversion, Summary};
use crate::robust;
use crate::solve::{Engine, NodeRole, SolveInfo, SolverSetup, SpringSolver, Stage};
use crate::topology;

mod attempt;
pub mod blend;
mod distances;
mod harmonic;
mod roles;
mod settings;
#[cfg(test)]
mod tests;

use self::attempt::Attempt;
pub use self::attempt::QUALITY_DROP;
use self::blend::Blend;
use self::roles::{duplicate_nodes, plan_roles};
pub use self::settings::{Predictor, Preset, Reference, Settings};

/// What one step did (one line of `report.json`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct StepReport {
    /// The step `n` (0: the input mesh).
    pub step: usize,
    /// The increments the step was taken in (1 unless sub-steps were needed).
    pub substeps: usize,
    /// Solver sweeps (of all increments, the rejected ones too).
    pub iterations: usize,
    /// The final eq.-8 value (mean absolute change in the last sweep).
    pub residual: f64,
    /// Whether the solver's stop test was met.
    pub converged: bool,
    /// Wall seconds of the whole step (motion, solve, update, check).
    pub seconds: f64,
    /// Seconds forming the system (paper's Part I).
    pub form_seconds: f64,
    /// Seconds solving it (paper's Part II).
    pub solve_seconds: f64,
    /// Seconds assembling the springs (part of `form_seconds`).
    pub springs_seconds: f64,
    /// Seconds of the quality and inversion check of the new coordinates.
    pub check_seconds: f64,
    /// The smallest element quality.
    pub min_quality: f64,
    /// The number of inverted elements.
    pub inverted: usize,
    /// Element counts in the paper's quality bins 0–0.02, 0.02–0.1, 0.1–0.4, 0.4–0.7, 0.7–1.
    pub bins: [usize; 5],
    /// The mean element quality.
    pub mean_quality: f64,
    /// The solvers the step used, in order of first use (`sweeps`,
    /// `multigrid`, `safe-sweeps`, `direct`).
    pub stages: Vec<Stage>,
    /// Root-mean-square true residual of the accepted solve.
    pub true_residual: f64,
    /// The worst node's estimated error relative to its local cell height
    /// in the accepted solve (docs/method.md, "Accepting a step").
    pub error_ratio: f64,
    /// The eq.-8 value of every sweep, when [`crate::solve::SolveParams::record_history`] is set.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub history: Vec<f64>,
}

impl StepReport {
    /// Adds one solve's account: sweeps, seconds, stages; the residuals and
    /// the error ratio are the last solve's.
    pub fn add(&mut self, info: &SolveInfo) {
        self.iterations += info.iterations;
        self.residual = info.residual;
        self.true_residual = info.true_residual;
        self.error_ratio = info.error_ratio;
        self.form_seconds += info.form_seconds;
        self.solve_seconds += info.solve_seconds;
        self.springs_seconds += info.springs_seconds;
        self.history.clone_from(&info.history);
        for stage in &info.stages {
            if !self.stages.contains(stage) {
                self.stages.push(*stage);
            }
        }
    }
}

/// A configuration of the mesh with its check. The quality of each cell is
/// not kept (8 bytes a cell for the whole run): [`Snapshot::qualities`]
/// measures it again, as the check did.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Node coordinates (D·N).
    pub coords: Vec<f64>,
    /// Whether each cell is inverted relative to the input mesh.
    pub inverted: Vec<bool>,
    /// The step's report.
    pub report: StepReport,
}

impl Snapshot {
    /// The quality of each cell of `mesh`, the input mesh this configuration
    /// moves, relative to its orientation ([`quality::qualities`]).
    pub fn qualities(&self, mesh: &Mesh) -> Vec<f64> {
        quality::qualities(mesh, &self.coords, &quality::orientation(mesh))
    }
}

/// A mesh in motion (see the module documentation), its springs solved
/// by `S`: the [`Engine`] in one process, another [`SpringSolver`] (over
/// MPI ranks) through [`Deformer::with_solver`].
pub struct Deformer<S = Engine> {
    mesh: Arc<Mesh>,
    settings: Settings,
    solver: S,
    /// Per-node spring stiffness factors of the wall-distance stiffening (empty: none).
    stiffness: Vec<f64>,
    roles: Vec<NodeRole>,
    normals: Vec<[f64; 3]>,
    motions: Vec<Motion>,
    /// Moving nodes and the motions (indices into `motions`) they follow, in order.
    moving: Vec<(usize, Vec<usize>)>,
    /// Rigid-layer nodes, the moving node (index into `moving`) each follows
    /// (`None`: it stays, near a fixed wall), and its role before it was
    /// prescribed (a sliding node keeps to its plane or line).
    layer: Vec<(usize, Option<usize>, NodeRole)>,
    /// The rigid layer's thickness around each body.
    layer_thickness: Vec<f64>,
    /// The blended rigid motion, when [`crate::robust::Robust::blend`] is on.
    blend: Option<Blend>,
    /// The input mesh's minimum quality.
    input_quality: f64,
    orientation: Vec<i8>,
    /// The last solution per unit step fraction (increment, or the total
    /// displacement from the start with the fixed and anchored references):
    /// the next step's guess.
    guess: Vec<f64>,
    /// The solution before [`Deformer::guess`], kept for
    /// [`Predictor::Linear`] once there is one.
    earlier: Option<Vec<f64>>,
    /// Whether [`Deformer::guess`] is a solution: always with a total
    /// unknown (the input mesh's `u = 0`), after the first step with the
    /// updated reference (whose start has no increment).
    guess_is_solution: bool,
    /// Prescribed displacements at most this far (10⁻¹² of the input
    /// mesh's bounding-box diagonal) are round-off.
    round_off: f64,
    current: Snapshot,
    failed: Option<Snapshot>,
}

impl Deformer {
    /// Prepares `mesh` for the motions in `attachments`: resolves each node's
    /// role, builds the solver's topology and checks the input mesh (which
    /// must have no degenerate element and no two nodes at the same position).
    pub fn new(mesh: &Mesh, attachments: &[Attachment], settings: Settings) -> Result<Deformer> {
        Deformer::shared(Arc::new(mesh.clone()), attachments, settings)
    }

    /// [`Deformer::new`] on a mesh the caller shares rather than copies.
    pub fn shared(
        mesh: Arc<Mesh>,
        attachments: &[Attachment],
        settings: Settings,
    ) -> Result<Deformer> {
        Deformer::with_solver(mesh, attachments, settings, Engine::from_setup)
    }
}

impl<S: SpringSolver> Deformer<S> {
    /// [`Deformer::new`] with the springs solved by the solver `make`
    /// builds once the node roles are decided.
    pub fn with_solver(
        shared: Arc<Mesh>,
        attachments: &[Attachment],
        settings: Settings,
        make: impl FnOnce(&SolverSetup) -> Result<S>,
    ) -> Result<Deformer<S>> {
        let mesh: &Mesh = &shared;
        settings.validate()?;
        let motions: Vec<Motion> = attachments.iter().map(|a| a.motion.clone()).collect();
        for m in &motions {
            m.validate(mesh.dim)?;
        }
        if let Some((a, b)) = duplicate_nodes(mesh) {
            return Err(Error::InvalidMesh(format!(
                "nodes {} and {} are at the same position {}: duplicate nodes",
                mesh.node_tags[a],
                mesh.node_tags[b],
                format_point(mesh.point(a))
            )));
        }
        let mut plan = plan_roles(mesh, attachments)?;
        // The edge graph, built once for the near-wall treatments, the
        // blend and the springs, where the treatments or the blend need it.
        let blending = settings.robust.blend && !plan.moving.is_empty();
        let edge_graph = (settings.robust.treats() || blending)
            .then(|| Arc::new(topology::edge_graph(&mesh.cells, mesh.node_count())));
        let rigid = robust::prepare(
            mesh,
            edge_graph.as_deref(),
            &plan.roles,
            &plan.moving,
            &settings.robust,
        )?;
        let layer = rigid
            .nodes
            .iter()
            .map(|&(i, k)| {
                let role = plan.roles[i];
                plan.roles[i] = NodeRole::Fixed;
                (i, k, role)
            })
            .collect();
        let blend = edge_graph.as_ref().filter(|_| blending).map(|graph| {
            Blend::new(
                mesh.dim,
                &mesh.coords,
                &mesh.node_tags,
                Arc::clone(graph),
                &plan.roles,
                &plan.normals,
                blend::bodies(&plan.moving, &rigid.nodes),
                &Whole,
            )
        });
        let solver = make(&SolverSetup {
            mesh,
            roles: &plan.roles,
            normals: &plan.normals,
            stiffness: &rigid.stiffness,
            edge_graph: edge_graph.as_ref(),
        })?;
        let orientation = quality::orientation(mesh);
        let start = Instant::now();
        let (quality, inversions) =
            quality::qualities_and_inversions(mesh, &mesh.coords, &orientation);
        if let Some(first) = inversions.first() {
            return Err(Error::InvalidMesh(format!(
                "element {} is inverted or degenerate (tangled, or of zero area or volume) at {}",
                mesh.cell_tags[first.cell],
                format_point(&first.centroid)
            )));
        }
        let mut report = summarize(&quality, &inversions);
        report.converged = true;
        report.seconds = start.elapsed().as_secs_f64();
        let round_off =
            blend::ROUND_OFF * robust::size(mesh, &(0..mesh.node_count()).collect::<Vec<_>>());
        let current = Snapshot {
            coords: mesh.coords.clone(),
            inverted: vec![false; quality.len()],
            report,
        };
        Ok(Deformer {
            input_quality: current.report.min_quality,
            guess: vec![0.0; mesh.coords.len()],
            earlier: None,
            guess_is_solution: settings.reference != Reference::Updated,
            round_off,
            current,
            mesh: shared,
            settings,
            solver,
            stiffness: rigid.stiffness,
            roles: plan.roles,
            normals: plan.normals,
            motions,
            moving: plan.moving,
            layer,
            layer_thickness: rigid.thickness,
            blend,
            orientation,
            failed: None,
        })
    }

    /// The run's settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The role of each node in the spring system (rigid-layer nodes are
    /// prescribed: [`NodeRole::Fixed`]).
    pub fn roles(&self) -> &[NodeRole] {
        &self.roles
    }

    /// The unit directions of the sliding nodes: [`NodeRole::Slide`]`(k)`
    /// slides in the plane of normal `normals()[k]`, [`NodeRole::Line`]`(k)`
    /// along the line of direction `normals()[k]`.
    pub fn normals(&self) -> &[[f64; 3]] {
        &self.normals
    }

    /// The per-node spring stiffness factors of the wall-distance stiffening
    /// (empty: none).
    pub fn stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// The solver of the springs.
    pub fn solver(&self) -> &S {
        &self.solver
    }

    /// The number of rigid-layer nodes and the layer's thickness around each
    /// body (moving nodes sharing a chain of motions).
    pub fn rigid_layer(&self) -> (usize, &[f64]) {
        (self.layer.len(), &self.layer_thickness)
    }

    /// The last accepted step (0 before the first).
    pub fn current_step(&self) -> usize {
        self.current.report.step
    }

    /// The last accepted configuration.
    pub fn current(&self) -> &Snapshot {
        &self.current
    }

    /// The configuration of the step that failed the inversion check, if any.
    pub fn failed(&self) -> Option<&Snapshot> {
        self.failed.as_ref()
    }

    /// The input mesh.
    pub fn initial(&self) -> &Mesh {
        &self.mesh
    }

    /// The displacement of every node from the input mesh, `x − X` (D·N).
    pub fn displacement(&self) -> Vec<f64> {
        displacement(&self.current.coords, &self.mesh.coords)
    }

    /// The input mesh with the current coordinates.
    pub fn mesh(&self) -> Mesh {
        let mut mesh = Mesh::clone(&self.mesh);
        mesh.coords.clone_from(&self.current.coords);
        mesh
    }

    /// Moves the boundary to its position at step `n` and the interior with
    /// it, from the last accepted configuration. On success the new
    /// configuration is accepted and its report returned. When an element
    /// inverts — in the smallest increment [`Settings::robust`] allows — the
    /// configuration is rejected (kept in [`Deformer::failed`], the current
    /// one stays) and [`Error::Inverted`] names the worst element.
    pub fn step(&mut self, n: usize) -> Result<StepReport> {
        let start = Instant::now();
        let targets = self.targets(n)?;
        // The step starts from the current coordinates, lent to it rather
        // than copied, and given back when it fails.
        let from = std::mem::take(&mut self.current.coords);
        let stepped = self.step_from(n, &targets, &from, start);
        if stepped.is_err() {
            self.current.coords = from;
        }
        stepped
    }

    /// [`Deformer::step`] from coordinates `from` to `targets`, in adaptive
    /// sub-steps: the new current snapshot, or the error.
    fn step_from(
        &mut self,
        n: usize,
        targets: &[(usize, Vec<f64>)],
        from: &[f64],
        start: Instant,
    ) -> Result<StepReport> {
        // With a total unknown the accepted mesh does not depend on the
        // increments taken to reach it: no sub-steps.
        let substeps = match self.settings.reference {
            Reference::Updated => self.settings.robust.substeps.min(30),
            Reference::Fixed | Reference::Anchored => 0,
        };
        let floor = 0.5f64.powi(substeps as i32);
        let mut reference_quality = match self.settings.reference {
            Reference::Updated => self.current.report.min_quality,
            Reference::Fixed | Reference::Anchored => self.input_quality,
        };
        // The last accepted sub-step's coordinates (`None`: `from`).
        let mut coords: Option<Vec<f64>> = None;
        let (mut done, mut h) = (0.0, 1.0);
        let mut report = StepReport {
            step: n,
            converged: true,
            ..StepReport::default()
        };
        loop {
            let end = if done + h >= 1.0 { 1.0 } else { done + h };
            let at: Vec<(usize, Vec<f64>)> = targets
                .iter()
                .map(|(i, p)| {
                    let x0 = &from[self.mesh.dim * i..self.mesh.dim * (i + 1)];
                    let q = if end == 1.0 {
                        p.clone()
                    } else {
                        x0.iter().zip(p).map(|(a, b)| a + end * (b - a)).collect()
                    };
                    (*i, q)
                })
                .collect();
            let at_start = coords.as_deref().unwrap_or(from);
            let attempt = self.chosen(at_start, &at, end - done, reference_quality, &mut report)?;
            let attempt_quality = attempt.min_quality();
            let Attempt {
                coords: trial,
                u,
                info,
                quality,
                inversions,
                ..
            } = attempt;
            report.add(&info);
            if !info.converged || !inversions.is_empty() {
                if h * 0.5 >= floor {
                    h *= 0.5;
                    continue;
                }
                report.converged = info.converged;
                report.substeps += 1;
                let err = match inversions
                    .iter()
                    .min_by(|a, b| a.volume.total_cmp(&b.volume))
                {
                    Some(worst) if info.converged => Error::Inverted {
                        step: n,
                        count: inversions.len(),
                        element: self.mesh.cell_tags[worst.cell],
                        centroid: worst.centroid.clone(),
                        volume: worst.volume,
                        failure: worst.failure,
                    },
                    _ => Error::NotConverged {
                        step: n,
                        what: Box::new(Unconverged {
                            stages: Stage::names(&info.stages),
                            true_residual: info.true_residual,
                            error_ratio: info.error_ratio,
                            node: self.mesh.node_tags[info.worst_node],
                            diverged: info.diverged,
                        }),
                    },
                };
                self.failed = Some(self.snapshot(trial, &quality, &inversions, report, start));
                return Err(err);
            }
            report.substeps += 1;
            let fraction = end - done;
            let solved = u.iter().map(|v| v / fraction).collect();
            let kept = std::mem::replace(&mut self.guess, solved);
            if self.settings.predictor == Predictor::Linear && self.guess_is_solution {
                self.earlier = Some(kept);
            }
            self.guess_is_solution = true;
            if self.settings.reference == Reference::Updated {
                reference_quality = attempt_quality;
            }
            done = end;
            if done >= 1.0 {
                self.current = self.snapshot(trial, &quality, &inversions, report, start);
                return Ok(self.current.report.clone());
            }
            coords = Some(trial);
            h = (2.0 * h).min(1.0 - done);
        }
    }

    /// Where the prescribed nodes (moving and rigid-layer) are at step `n`.
    pub fn targets(&self, n: usize) -> Result<Vec<(usize, Vec<f64>)>> {
        let clock = Clock {
            step: n,
            steps: self.settings.steps,
            dt: self.settings.dt,
        };
        let dim = self.mesh.dim;
        let frames = self
            .motions
            .iter()
            .map(|m| m.frame(clock, self.mesh.node_count(), dim))
            .collect::<Result<Vec<_>>>()?;
        let mut targets = Vec::with_capacity(self.moving.len() + self.layer.len());
        for (node, chain) in &self.moving {
            let mut p = self.mesh.point(*node).to_vec();
            for &m in chain {
                self.motions[m].apply(*node, &mut p, clock, &frames[m])?;
            }
            targets.push((*node, p));
        }
        for &(node, k, role) in &self.layer {
            let mut p = self.mesh.point(node).to_vec();
            if let Some(k) = k {
                let (anchor, chain) = &self.moving[k];
                if chain.iter().all(|&m| self.motions[m].is_field()) {
                    for &m in chain {
                        self.motions[m].apply(node, &mut p, clock, &frames[m])?;
                    }
                } else {
                    let x = self.mesh.point(*anchor);
                    for d in 0..dim {
                        p[d] += targets[k].1[d] - x[d];
                    }
                }
            }
            let x = &self.current.coords[dim * node..dim * (node + 1)];
            role.keep_on(&self.normals, &mut p, x);
            targets.push((node, p));
        }
        Ok(targets)
    }

    /// The configuration `coords` with its cells' `quality`, for the step of
    /// `report`.
    fn snapshot(
        &self,
        coords: Vec<f64>,
        quality: &[f64],
        inversions: &[Inversion],
        mut report: StepReport,
        start: Instant,
    ) -> Snapshot {
        let summary = summarize(quality, inversions);
        report.min_quality = summary.min_quality;
        report.mean_quality = summary.mean_quality;
        report.inverted = summary.inverted;
        report.bins = summary.bins;
        report.seconds = start.elapsed().as_secs_f64();
        let mut inverted = vec![false; quality.len()];
        for inv in inversions {
            inverted[inv.cell] = true;
        }
        Snapshot {
            coords,
            inverted,
            report,
        }
    }

    /// Replaces the motion of attachment `k` (in the order given to
    /// [`Deformer::new`]) from the next step on: how a coupled solver feeds
    /// each step's boundary positions
    /// ([`crate::motion::PositionSource::Given`]). The node roles were fixed
    /// by [`Deformer::new`], so only a moving motion can be replaced, and
    /// only by a moving one.
    pub fn set_motion(&mut self, k: usize, motion: Motion) -> Result<()> {
        let count = self.motions.len();
        let Some(old) = self.motions.get(k) else {
            return Err(Error::InvalidSetting(format!(
                "there is no attachment {k} (the deformer has {count})"
            )));
        };
        if !(old.moves() && motion.moves()) {
            return Err(Error::InvalidSetting(format!(
                "attachment {k}: only a moving motion can replace a moving motion"
            )));
        }
        motion.validate(self.mesh.dim)?;
        self.motions[k] = motion;
        Ok(())
    }

    /// [`Deformer::step`] to the step after the current one.
    pub fn advance(&mut self) -> Result<StepReport> {
        self.step(self.current_step() + 1)
    }
}

/// `x − X`.
fn displacement(x: &[f64], reference: &[f64]) -> Vec<f64> {
    x.iter().zip(reference).map(|(a, b)| a - b).collect()
}

/// Minimum quality, inverted count and the paper's bins.
fn summarize(quality: &[f64], inversions: &[Inversion]) -> StepReport {
    let summary = Summary::new(quality);
    let mut bins = [0; 5];
    for (b, bin) in bins.iter_mut().zip(&summary.bins) {
        *b = bin.count;
    }
    StepReport {
        min_quality: summary.min,
        mean_quality: summary.mean,
        inverted: inversions.len(),
        bins,
        ..StepReport::default()
    }
}
