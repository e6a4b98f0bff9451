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
