//! The solvers of the node-block spring system (DESIGN §2).
//!
//! API CONTRACT (to be implemented by the engine; the motion/stepper layer codes
//! against these types):
//!
//! ```text
//! let mut engine = Engine::new(&mesh, &roles)?;              // topology, once per mesh
//! let info = engine.solve(&coords, &mut displacement, &params)?;  // once per step
//! ```
//! `coords`: reference coordinates of this step (D·N). `displacement`: D·N; on
//! entry the prescribed values of Fixed nodes (and the initial guess of the
//! others: the previous step's solution); on return the solution.

/// What a node's displacement is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NodeRole {
    /// An unknown: moved by the springs.
    Free,
    /// Prescribed: the displacement given on entry is kept.
    Fixed,
    /// Slides within a plane with this unit normal (index into [`Engine::new`]'s `normals`):
    /// the normal component of the displacement is prescribed, the tangential ones are unknowns.
    Slide(usize),
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
    /// Worker threads of the sweeps (1: serial). Results do not depend on it.
    pub threads: usize,
    /// Record the eq.-8 value of every sweep in [`SolveInfo::history`].
    pub record_history: bool,
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
            threads: 1,
            record_history: false,
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
}
