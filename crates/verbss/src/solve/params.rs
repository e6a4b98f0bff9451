//! The settings of one solve and what it reports: node roles, methods,
//! solvers, the multigrid choice, [`SolveParams`] and [`SolveInfo`].

use super::frame::Frame;
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::settings::check_value;
use crate::topology;

/// What a node's displacement is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NodeRole {
    /// An unknown: moved by the springs.
    Free,
    /// Prescribed: the displacement given on entry is kept.
    Fixed,
    /// Slides within a plane with this unit normal (index into [`crate::solve::Engine::new`]'s `normals`):
    /// the normal component of the displacement is prescribed, the tangential ones are unknowns.
    Slide(usize),
    /// Slides along a line with this unit direction (index into the same
    /// `normals`), as where two slide planes meet: the component along the
    /// line is the unknown, the two across it are prescribed.
    Line(usize),
}

impl NodeRole {
    /// The prescribed part of the displacement `u` of a node of this role:
    /// none of it for a free node, all of it for a fixed one, and for a
    /// sliding one its components along the normals of its plane or line
    /// (`directions`, unit: [`Frame::given_part`]).
    pub fn prescribed<const D: usize>(self, directions: &[[f64; 3]], u: &[f64; D]) -> [f64; D] {
        match self {
            NodeRole::Free => [0.0; D],
            NodeRole::Fixed => *u,
            NodeRole::Slide(_) | NodeRole::Line(_) => {
                Frame::<D>::of_role(self, directions).map_or(*u, |f| f.given_part(u))
            }
        }
    }

    /// [`NodeRole::prescribed`] for `u` of `u.len()` (2 or 3) components;
    /// the first `u.len()` numbers of the result are used.
    pub fn prescribed_dyn(self, directions: &[[f64; 3]], u: &[f64]) -> [f64; 3] {
        if u.len() == 2 {
            let [a, b] = self.prescribed::<2>(directions, &[u[0], u[1]]);
            [a, b, 0.0]
        } else {
            self.prescribed::<3>(directions, &[u[0], u[1], u[2]])
        }
    }

    /// Moves `x` back onto the plane or line through `base` that a sliding
    /// node keeps to (`x ← x − given part of (x − base)`); other roles leave
    /// `x` alone.
    pub fn keep_on(self, directions: &[[f64; 3]], x: &mut [f64], base: &[f64]) {
        if let NodeRole::Slide(_) | NodeRole::Line(_) = self {
            let mut off = [0.0; 3];
            for ((o, a), b) in off.iter_mut().zip(&*x).zip(base) {
                *o = a - b;
            }
            let given = self.prescribed_dyn(directions, &off[..x.len()]);
            for (xd, g) in x.iter_mut().zip(given) {
                *xd -= g;
            }
        }
    }
}

/// Which system to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Edge + ball-vertex springs, solved node by node (block SOR with per-node LDLᵀ).
    #[default]
    Verbss,
    /// Edge + ball-vertex springs, solved as one global system ([`Solver`]).
    BallVertex,
    /// Edge springs only (Batina), solved node by node.
    Spring,
    /// Component-wise Laplacian with `k = 1/L`, solved node by node.
    Laplacian,
}

/// How `ball-vertex` solves its global system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Solver {
    /// Scalar SOR over all D·N unknowns (the paper's baseline).
    #[default]
    Sor,
    /// Exact sparse LU (the reference).
    Direct,
}

/// How the block systems of [`Method::Verbss`] and [`Method::Spring`] are solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Accel {
    /// Plain VerBSS sweeps (block SOR) until the eq.-8 test: the paper's method.
    #[default]
    None,
    /// GMRES preconditioned by a smoothed-aggregation multigrid V-cycle with
    /// the VerBSS sweep as its finest smoother; stops when the estimated
    /// root-mean-square error of the unknowns is below the threshold
    /// (`docs/acceleration.md`).
    Amg,
    /// Plain sweeps while they converge within [`AUTO_SWEEPS`]; on a mesh
    /// of mostly triangles or tetrahedra, the first step whose sweeps do not
    /// is handed to the multigrid (amg) from where they stopped, and the
    /// multigrid, its hierarchy kept, solves every later step. A multigrid
    /// that cannot be built or a solve it cannot finish falls back to plain
    /// sweeps. The robust default's solver: a rigid motion, which the blend
    /// leaves the springs almost nothing to solve, never pays for a
    /// hierarchy; a deforming wall, whose sweeps grow with the mesh, gets
    /// iterations that do not.
    Auto,
}

crate::names::named!(Method, "method", [
    Verbss => "verbss",
    BallVertex => "ball-vertex",
    Spring => "spring",
    Laplacian => "laplacian",
]);
crate::names::named!(Solver, "solver", [Sor => "sor", Direct => "direct"]);
crate::names::named!(Accel, "accel", [None => "none", Amg => "amg", Auto => "auto"]);

/// The sweeps after which [`Accel::Auto`] hands an unconverged step to the
/// multigrid: about the cost of one step solved by it with its hierarchy
/// kept (5–14 GMRES iterations, each with its V-cycle about 17 sweeps'
/// time on the 105,570-node bending wing; BENCHMARKS.md), so that a step
/// the sweeps finish sooner never pays for a hierarchy.
pub const AUTO_SWEEPS: usize = 200;

/// Settings of one solve (one time step).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SolveParams {
    /// The system and its solution strategy.
    pub method: Method,
    /// The global solver of [`Method::BallVertex`].
    pub solver: Solver,
    /// Over-relaxation factor ω of the sweeps (paper: 1.5–1.7).
    pub omega: f64,
    /// Stop when the eq.-8 value (mean absolute change of all unknown components
    /// in one sweep) is below `tolerance × max |prescribed displacement of the step|`,
    /// or below `tolerance` itself when `absolute_tolerance` is set.
    pub tolerance: f64,
    /// Use `tolerance` as the paper's absolute eq.-8 threshold.
    pub absolute_tolerance: bool,
    /// Maximum number of sweeps k_max.
    pub max_iterations: usize,
    /// Worker threads of the sweeps (0: one per available core, the
    /// default). Results do not depend on it.
    pub threads: usize,
    /// Record the eq.-8 value of every sweep in [`SolveInfo::history`].
    pub record_history: bool,
    /// Plain sweeps or the multigrid-accelerated solve.
    pub accel: Accel,
    /// Watch the solve and escalate when it stalls, grows or leaves a node's
    /// estimated error above [`ERROR_FRACTION`] of its local cell height
    /// (sweeps → multigrid GMRES → sparse direct solve; `solve/escalate.rs`).
    /// Off: the configured solver alone, stopped by the eq.-8 test.
    pub escalate: bool,
}

/// A step is accepted (under [`SolveParams::escalate`]) only when every
/// unknown node's estimated error `|K_ii⁻¹ r_i|` is below this fraction of
/// its smallest adjacent cell height (docs/method.md, "Accepting a step").
pub const ERROR_FRACTION: f64 = 0.01;

/// One solver tried on a step, in the order tried.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stage {
    /// The configured sweeps (or the configured multigrid solve).
    Sweeps,
    /// GMRES preconditioned by the multigrid V-cycle.
    Multigrid,
    /// Sweeps with ω = 1 (where no multigrid applies).
    SafeSweeps,
    /// The sparse direct (LU) solve.
    Direct,
    /// GMRES preconditioned by one symmetric VerBSS sweep (forward, then
    /// backward): the multigrid's finest smoothing without its hierarchy,
    /// a few vectors of memory (3D escalation before the multigrid).
    Gmres,
}

impl Stage {
    /// Every stage, in declaration order (`Stage::ALL[s as usize] == s`).
    pub const ALL: [Stage; 5] = [
        Stage::Sweeps,
        Stage::Multigrid,
        Stage::SafeSweeps,
        Stage::Direct,
        Stage::Gmres,
    ];

    /// The name reports and messages use.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Sweeps => "sweeps",
            Stage::Multigrid => "multigrid",
            Stage::SafeSweeps => "safe-sweeps",
            Stage::Direct => "direct",
            Stage::Gmres => "gmres",
        }
    }

    /// The names of `stages`, comma separated (for messages).
    pub fn names(stages: &[Stage]) -> String {
        let names: Vec<&str> = stages.iter().map(|s| s.name()).collect();
        names.join(", ")
    }
}

impl Default for SolveParams {
    fn default() -> Self {
        SolveParams {
            method: Method::Verbss,
            solver: Solver::Sor,
            omega: 1.6,
            tolerance: 1e-6,
            absolute_tolerance: false,
            max_iterations: 2000,
            threads: 0,
            record_history: false,
            accel: Accel::None,
            escalate: true,
        }
    }
}

impl SolveParams {
    /// Checks the settings: each number in its range ([`crate::settings::TABLE`]),
    /// and the multigrid only for the block systems.
    pub fn validate(&self) -> Result<()> {
        use crate::settings::Value;
        check_value("omega", Value::Number(self.omega))?;
        check_value("tolerance", Value::Number(self.tolerance))?;
        check_value("max_iterations", Value::Count(self.max_iterations as u64))?;
        check_value("threads", Value::Count(self.threads as u64))?;
        if self.accel == Accel::Amg && !matches!(self.method, Method::Verbss | Method::Spring) {
            return Err(Error::InvalidSetting(
                "accel amg solves the block systems of method verbss and spring \
                 (not ball-vertex or laplacian)"
                    .into(),
            ));
        }
        Ok(())
    }
}

impl SolveParams {
    /// The stop of a solve whose largest prescribed displacement is
    /// `scale`: the eq.-8 `tolerance × scale` (or `tolerance` itself when
    /// absolute, or when nothing moves), or for a solve to round-off
    /// (`exact`) `ROUND_OFF × scale` (docs/method.md, "Accepting a step").
    pub fn threshold(&self, scale: f64, exact: bool) -> f64 {
        if exact {
            super::escalate::ROUND_OFF * if scale == 0.0 { 1.0 } else { scale }
        } else if self.absolute_tolerance || scale == 0.0 {
            self.tolerance
        } else {
            self.tolerance * scale
        }
    }
}

/// What a solve did.
#[derive(Debug, Clone, Default, PartialEq)]
#[non_exhaustive]
pub struct SolveInfo {
    /// Sweeps done (1 for the direct solver).
    pub iterations: usize,
    /// The final eq.-8 value (mean absolute change in the last sweep; 0 for the direct solver).
    pub residual: f64,
    /// Whether the stop test was met (always true for the direct solver).
    pub converged: bool,
    /// Seconds forming the system (springs, factors), paper's "Part I".
    pub form_seconds: f64,
    /// Seconds solving, paper's "Part II".
    pub solve_seconds: f64,
    /// Total seconds.
    pub seconds: f64,
    /// Eq.-8 value after each sweep, when asked for.
    pub history: Vec<f64>,
    /// Whether this call (re)built the springs and factors.
    pub rebuilt: bool,
    /// Levels of the multigrid of an accelerated solve (0: plain sweeps or direct).
    pub levels: usize,
    /// Whether this call (re)built the multigrid hierarchy.
    pub hierarchy_built: bool,
    /// Seconds building the multigrid hierarchy (part of `form_seconds`).
    pub hierarchy_seconds: f64,
    /// Seconds assembling the springs (part of `form_seconds`; 0 when the
    /// system was kept).
    pub springs_seconds: f64,
    /// Whether the configured solver's iterates grew (ω too large for the mesh).
    pub diverged: bool,
    /// The solvers tried, in order (the last one gave the result).
    pub stages: Vec<Stage>,
    /// Root-mean-square of the true residual `r_i = c_i + Σ_j B_ij u_j − K_ii u_i`
    /// over the unknown nodes.
    pub true_residual: f64,
    /// The largest estimated error of a node relative to its local cell
    /// height, `max_i |K_ii⁻¹ r_i| / h_i`.
    pub error_ratio: f64,
    /// The node (mesh index) where [`SolveInfo::error_ratio`] is largest.
    /// A solver over several processes' parts sets it on the one process
    /// holding that node and to `usize::MAX` on the others.
    pub worst_node: usize,
}

/// The default roles of a mesh: [`NodeRole::Fixed`] on every boundary node
/// ([`topology::boundary_nodes`]: nodes of boundary facets and of named
/// groups), [`NodeRole::Free`] elsewhere.
pub fn default_roles(mesh: &Mesh) -> Vec<NodeRole> {
    topology::boundary_nodes(mesh)
        .into_iter()
        .map(|b| if b { NodeRole::Fixed } else { NodeRole::Free })
        .collect()
}

/// Clears the prescribed parts ([`NodeRole::prescribed`]) of the
/// displacement `u` (`dim` per node; `normals` unit) — what is left of a
/// guess for the unknowns.
pub fn clear_prescribed(dim: usize, roles: &[NodeRole], normals: &[[f64; 3]], u: &mut [f64]) {
    for (i, role) in roles.iter().enumerate() {
        let ui = &mut u[dim * i..dim * (i + 1)];
        let given = role.prescribed_dyn(normals, ui);
        for (v, g) in ui.iter_mut().zip(given) {
            *v -= g;
        }
    }
}
