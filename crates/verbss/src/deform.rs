//! The stepper: boundary motion → spring system → solve → update → check.
//!
//! A [`Deformer`] holds a mesh in motion. Each call of [`Deformer::step`]
//! moves the boundary to where its motions put it at that step, moves the
//! interior nodes by the springs and checks every cell
//! (`deform/accept.rs`); it is the call a flow solver makes once per time
//! step.
//!
//! The same deformer runs on a whole mesh or on one process's part of it
//! (its nodes, owned and ghosts, with every cell around the owned ones:
//! [`Domain`]): every sum, maximum and ghost value goes through the
//! processes' [`Collective`], so that each process finds one process's
//! answer on its nodes. One step loop, one near-wall set-up, one check, on
//! every domain.
//!
//! Which node does what is decided once, in `deform/roles.rs`.
//!
//! Three ways to step (paper §3.2, step 6, and docs/method.md, "Time stepping"):
//! - [`Reference::Updated`] (option 1, the paper's): the springs are rebuilt
//!   on the current coordinates `x` and the step solves for the increment
//!   `Δu`, `x ← x + Δu`.
//! - [`Reference::Fixed`] (option 2): the springs stay those of the input mesh
//!   `X` and each step solves for the total displacement `u`, `x = X + u`.
//! - [`Reference::Anchored`]: the input mesh moved by the blended rigid
//!   motion to the boundary's position, `B(X)`, carries the springs and the
//!   step solves for the rest, `x = B(X) + u`: `x` depends on the
//!   boundary's position only.
//!
//! ([`Reference::Auto`] is one of them, chosen by the motions when the
//! deformer is made.) Either way the previous step's solution is the next
//! step's initial guess ([`Predictor::Previous`](crate::settings::Predictor::Previous);
//! [`Predictor::Linear`](crate::settings::Predictor::Linear)
//! extrapolates from the two previous steps instead), and prescribed nodes
//! are set exactly to their motion's positions.
//!
//! [`Settings::robust`] adds the near-wall treatments of [`crate::near_wall`]:
//! a rigid layer of nodes that move with their wall, and adaptive sub-steps.

use std::sync::Arc;
use std::time::Instant;

use crate::collective::{agree, Collective, Whole};
use crate::error::{format_point, Error, Result};
use crate::mesh::Mesh;
use crate::motion::{Attachment, Motion};
use crate::near_wall::{self, Bounds, Follows};
use crate::settings::{Reference, Settings};
use crate::solve::{Engine, NodeRole, SolverSetup, SpringSolver};
use crate::threads::Workers;
use crate::topology;

mod accept;
#[cfg(test)]
mod amplification_tests;
mod attempt;
mod coincident;
#[cfg(test)]
mod interface_tests;
mod periodic;
mod relocate;
mod report;
mod roles;
mod step;
mod targets;
#[cfg(test)]
mod tests;

pub use self::report::{Snapshot, StepReport};
use self::roles::plan_roles;
use crate::near_wall::blend::{self, Blend};

/// What one process holds of the mesh a deformer moves ([`Deformer::on`]):
/// a whole mesh, or one rank's part — its nodes, owned and ghosts, every
/// cell around its owned nodes, and every group of the mesh (empty or not,
/// in the same order on every rank) with each of its facets around an
/// owned node — with the processes that share the mesh.
pub struct Domain<C> {
    /// The local mesh.
    pub mesh: Arc<Mesh>,
    /// The global number of each local node, the node ids of a positions
    /// file (empty: the local index).
    pub global: Vec<u64>,
    /// The processes sharing the mesh.
    pub on: C,
}

impl Domain<Whole> {
    /// A whole mesh on one process.
    pub fn whole(mesh: Arc<Mesh>) -> Domain<Whole> {
        Domain {
            mesh,
            global: Vec::new(),
            on: Whole,
        }
    }
}

/// A mesh in motion (see the module documentation), its springs solved by
/// `S` (the [`Engine`] in one process, another [`SpringSolver`] over MPI
/// ranks through [`Deformer::with_solver`] or [`Deformer::on`]), on the
/// domain of the processes `C` ([`Whole`]: the whole mesh).
pub struct Deformer<S = Engine, C = Whole> {
    mesh: Arc<Mesh>,
    on: C,
    /// The global number of each local node (empty: its index).
    global: Vec<u64>,
    /// The whole mesh's node and cell counts.
    size: (usize, usize),
    settings: Settings,
    solver: S,
    /// Per-node spring stiffness factors of the wall-distance stiffening (empty: none).
    stiffness: Vec<f64>,
    roles: Vec<NodeRole>,
    normals: Vec<[f64; 3]>,
    motions: Vec<Motion>,
    /// The chains of motions (indices into `motions`) of each body.
    bodies: Vec<Vec<usize>>,
    /// Moving nodes and their bodies, in order.
    moving: Vec<(usize, usize)>,
    /// Rigid-layer nodes, the body each follows with the tag of its nearest
    /// node of it (`None`: it stays, near a fixed wall), and its role
    /// before it was prescribed (a sliding node keeps to its plane or line).
    layer: Vec<(usize, Follows, NodeRole)>,
    /// Where the layer nodes that follow a body moved by given positions
    /// find their nearest node's displacement ([`targets::Anchors`]).
    anchors: targets::Anchors,
    /// The rigid layer's thickness around each body and fixed wall.
    layer_thickness: Vec<f64>,
    /// The number of rigid-layer nodes of every process.
    layer_nodes: usize,
    /// The blended rigid motion, when [`crate::near_wall::Robust::blend`] is on.
    blend: Option<Blend>,
    /// The relocation of the worst cells' nodes, when
    /// [`crate::near_wall::Robust::relocate`] is on.
    relocation: Option<relocate::Relocation>,
    /// The input mesh's minimum quality.
    input_quality: f64,
    orientation: Vec<i8>,
    /// The last solution per unit step fraction (increment, or the total
    /// displacement from the start with the fixed and anchored references):
    /// the next step's guess.
    guess: Vec<f64>,
    /// The solution before [`Deformer::guess`], kept for
    /// [`crate::settings::Predictor::Linear`] once there is one.
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
    /// The periodic pairs, checked at every step where both sides move.
    periodic: Vec<periodic::Periodic>,
    /// The workers of the step's parallel work (`threads` of the settings),
    /// shared with the solver.
    workers: Workers,
}

impl Deformer {
    /// Prepares `mesh` for the motions in `attachments`: resolves each node's
    /// role, builds the solver's topology and checks the input mesh (which
    /// must have no invalid element, and no two nodes at the same position
    /// but the two sides of an interface or of a baffle moving together).
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
        mesh: Arc<Mesh>,
        attachments: &[Attachment],
        settings: Settings,
        make: impl FnOnce(&SolverSetup) -> Result<S>,
    ) -> Result<Deformer<S>> {
        Deformer::on(Domain::whole(mesh), attachments, settings, make)
    }
}

impl<S: SpringSolver, C: Collective> Deformer<S, C> {
    /// [`Deformer::with_solver`] on the `domain` of one process
    /// (collective: every process of `domain.on` makes its deformer with
    /// the same attachments and settings).
    pub fn on(
        domain: Domain<C>,
        attachments: &[Attachment],
        settings: Settings,
        make: impl FnOnce(&SolverSetup) -> Result<S>,
    ) -> Result<Deformer<S, C>> {
        let Domain {
            mesh: shared,
            global,
            on,
        } = domain;
        let mesh: &Mesh = &shared;
        let mut settings = settings;
        settings.validate()?;
        let motions: Vec<Motion> = attachments.iter().map(|a| a.motion.clone()).collect();
        for m in &motions {
            m.validate(mesh.dim)?;
        }
        settings.reference = settings.reference.resolved(&motions);
        let workers = Workers::new(settings.solve.threads)?;
        let baffles = agree(&on, coincident::baffles(mesh))?;
        let mut plan = agree(&on, plan_roles(mesh, attachments, &on))?;
        agree(&on, coincident::check_baffles(mesh, &plan, &baffles))?;
        let periodic = agree(&on, periodic::pairs(mesh, &plan))?;
        // The edge graph, built once for the near-wall treatments, the
        // blend and the springs, where the treatments or the blend need it.
        let blending = settings.robust.blend && !plan.bodies.is_empty();
        let edge_graph = (settings.robust.treats() || blending)
            .then(|| Arc::new(topology::edge_graph(&mesh.cells, mesh.node_count())));
        // The bodies moved by given positions (a deformation the blend does
        // not turn and the stiffening does not grade: docs/method.md,
        // "Amplification").
        let given: Vec<bool> = plan
            .bodies
            .iter()
            .map(|chain| chain.iter().any(|&a| !motions[a].is_field()))
            .collect();
        let rigid = near_wall::prepare(
            mesh,
            edge_graph.as_deref(),
            &plan.roles,
            (&given, &plan.moving),
            &settings.robust,
            &on,
        )?;
        let layer: Vec<(usize, Follows, NodeRole)> = rigid
            .nodes
            .iter()
            .map(|&(i, body)| {
                let role = plan.roles[i];
                plan.roles[i] = NodeRole::Fixed;
                (i, body, role)
            })
            .collect();
        let mut layer_nodes = [layer.iter().filter(|(i, ..)| on.owns(*i)).count() as f64];
        on.sum(&mut layer_nodes);
        let blend = edge_graph.as_ref().filter(|_| blending).map(|graph| {
            Blend::new(
                mesh.dim,
                &mesh.coords,
                &mesh.node_tags,
                Arc::clone(graph),
                &plan.roles,
                &plan.normals,
                blend::bodies(plan.bodies.len(), &plan.moving, &rigid.nodes),
                &given,
                &on,
            )
        });
        let anchors = targets::Anchors::new(mesh, &plan, &layer, &on);
        let solver = make(&SolverSetup {
            mesh,
            roles: &plan.roles,
            normals: &plan.normals,
            stiffness: &rigid.stiffness,
            edge_graph: edge_graph.as_ref(),
            workers: &workers,
        })?;
        let orientation = crate::quality::orientation(mesh);
        let start = Instant::now();
        let check = accept::check(mesh, &mesh.coords, &orientation, &on, &workers);
        if let Some(worst) = &check.summary.worst {
            return Err(Error::InvalidMesh(format!(
                "element {} is inverted or degenerate (tangled, or of zero area or volume) at {}",
                worst.element,
                format_point(&worst.centroid)
            )));
        }
        let relocation = settings
            .robust
            .relocate
            .then(|| relocate::Relocation::new(mesh, check.quality.clone()));
        let mut report = report::summarize(&check.summary);
        report.converged = true;
        report.seconds = start.elapsed().as_secs_f64();
        let all: Vec<usize> = (0..mesh.node_count()).collect();
        let extent = Bounds::of(mesh.dim, &mesh.coords, &all)
            .reduced(&on)
            .diagonal();
        let mut nodes = [(0..mesh.node_count()).filter(|&i| on.owns(i)).count() as f64];
        on.sum(&mut nodes);
        let current = Snapshot {
            coords: mesh.coords.clone(),
            inverted: vec![false; check.quality.len()],
            report,
        };
        Ok(Deformer {
            input_quality: current.report.min_quality,
            size: (nodes[0] as usize, current.report.bins.iter().sum()),
            guess: vec![0.0; mesh.coords.len()],
            earlier: None,
            guess_is_solution: settings.reference != Reference::Updated,
            round_off: blend::ROUND_OFF * extent,
            current,
            mesh: shared,
            on,
            global,
            settings,
            solver,
            stiffness: rigid.stiffness,
            roles: plan.roles,
            normals: plan.normals,
            motions,
            bodies: plan.bodies,
            moving: plan.moving,
            layer,
            periodic,
            anchors,
            layer_thickness: rigid.thickness,
            layer_nodes: layer_nodes[0] as usize,
            blend,
            relocation,
            orientation,
            failed: None,
            workers,
        })
    }

    /// The run's settings ([`Reference::Auto`] chosen).
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The processes sharing the mesh.
    pub fn processes(&self) -> &C {
        &self.on
    }

    /// The whole mesh's dimension, node count and cell count (over every
    /// process).
    pub fn size(&self) -> (usize, usize, usize) {
        (self.mesh.dim, self.size.0, self.size.1)
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

    /// The number of rigid-layer nodes (over every process) and the layer's
    /// thickness around each body (moving nodes sharing a chain of motions)
    /// and each fixed wall.
    pub fn rigid_layer(&self) -> (usize, &[f64]) {
        (self.layer_nodes, &self.layer_thickness)
    }

    /// The last accepted step (0 before the first).
    pub fn current_step(&self) -> usize {
        self.current.report.step
    }

    /// The last accepted configuration.
    pub fn current(&self) -> &Snapshot {
        &self.current
    }

    /// The configuration of the step that failed the check, if any.
    pub fn failed(&self) -> Option<&Snapshot> {
        self.failed.as_ref()
    }

    /// The input mesh (this process's part of it).
    pub fn initial(&self) -> &Mesh {
        &self.mesh
    }

    /// The displacement of every node from the input mesh, `x − X` (D·N).
    pub fn displacement(&self) -> Vec<f64> {
        self.current
            .coords
            .iter()
            .zip(&self.mesh.coords)
            .map(|(a, b)| a - b)
            .collect()
    }

    /// The input mesh with the current coordinates.
    pub fn mesh(&self) -> Mesh {
        let mut mesh = Mesh::clone(&self.mesh);
        mesh.coords.clone_from(&self.current.coords);
        mesh
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
