//! The solvers of the node-block spring system (docs/method.md, "The node equation and the methods").
//!
//! ```text
//! let mut engine = Engine::new(&mesh, &roles, &normals)?;          // topology, once per mesh
//! let info = engine.solve(&coords, &mut displacement, &params)?;  // once per step
//! ```
//!
//! `coords` are the reference coordinates `X` of the step (`D·N` numbers);
//! `displacement` (`D·N`) holds on entry the prescribed values of
//! [`NodeRole::Fixed`] nodes (and the normal component of
//! [`NodeRole::Slide`] nodes) and the initial guess of the unknowns (the
//! previous step's solution); on return the solution. The springs
//! ([`crate::springs`]) and the per-node factors are rebuilt only when `coords`
//! or the method changed since the last call, so a "fixed reference" run
//! (paper, option 2) forms them once.
//!
//! # Methods
//!
//! Every method solves, for every unknown node `i`, `K_ii u_i = Σ_j B_ij u_j`:
//!
//! * [`Method::Verbss`]: edge + ball-vertex springs, node by node: each
//!   `K_ii` is factored once as LDLᵀ, then each sweep sets
//!   `u_i ← ω K_ii⁻¹ (Σ_j B_ij u_j) + (1 − ω) u_i` (block SOR, `solve/verbss.rs`);
//! * [`Method::BallVertex`]: the same system as one global system:
//!   [`Solver::Sor`], scalar SOR over all unknown components (`solve/sor.rs`), or
//!   [`Solver::Direct`], an exact sparse LU (`solve/direct.rs`; the system is not
//!   symmetric), the reference the sweeps are checked against;
//! * [`Method::Spring`]: edge springs only, swept like `Verbss`;
//! * [`Method::Laplacian`]: `Σ_j k_ij (u_j − u_i) = 0` per component with
//!   `k_ij = 1/L_ij` (`solve/laplacian.rs`).
//!
//! # Sliding nodes
//!
//! A node sliding in a plane of unit normal `n` keeps the normal component
//! `d = n·u` it was given and has the tangential components as unknowns; a
//! node sliding along a line ([`NodeRole::Line`], where two slide planes
//! meet) keeps both components across the line and has the one along it as
//! its unknown. With `T` the basis of the directions it moves in (`D×(D−1)`
//! or `D×1`, orthonormal, [`Frame`]), `f` the given part and `u = f + T a`,
//! its equation is the projected one, `Tᵀ K_ii T a = Tᵀ (Σ_j B_ij u_j − K_ii f)`.
//! The sweeps solve it per node, the global solvers use the same unknowns `a`.
//!
//! # Order and parallelism
//!
//! The unknowns are ordered by breadth-first layers from the moving boundary
//! (the prescribed nodes with a nonzero prescribed displacement; all prescribed
//! nodes when none moves), coloured greedily in that order so that no two
//! coupled nodes share a colour, and renumbered colour by colour so that each
//! colour is one contiguous block of memory; within a colour the nodes follow a
//! Z-order (Morton) curve of the input mesh's coordinates, so that the
//! neighbours a node reads lie close together in every other colour's block
//! (nodes of one colour do not couple, so this order does not change a sweep's
//! displacements). A sweep visits the colours in turn and updates all nodes of
//! one colour in parallel; as nodes of one colour do not couple, this is
//! exactly a Gauss–Seidel (SOR) sweep in colour order — the colour order, not
//! the layer order, is the Gauss–Seidel order. Each colour is cut into fixed
//! chunks of nodes whose changes are summed on their own and then added in
//! chunk order, so the results, eq.-8 value included, are bit-identical for
//! every thread count.
//!
//! # Stopping (paper eq. 8)
//!
//! After each sweep, the eq.-8 value is the mean over all unknown components
//! (`D` per free node, `D − 1` per node sliding in a plane and 1 per node
//! sliding along a line, in its frame) of the
//! absolute change made *by that sweep*. The sweeps stop when it falls below
//! `tolerance × max |prescribed displacement|` (the largest prescribed
//! displacement vector, or normal component, of the step; `tolerance` itself
//! when [`SolveParams::absolute_tolerance`] is set or when nothing moves), or
//! after [`SolveParams::max_iterations`] sweeps. The eq.-8 value measures the
//! last sweep's change, not the error: with ω close to 2 or a slowly
//! converging mesh the error can be many times larger.
//!
//! # Pieces for a distributed sweeper
//!
//! [`gmres`] (restarted GMRES over any operator: the escalation's Krylov
//! stage) and [`verify`] (the true residual, the per-node error estimate
//! and the cell heights that decide whether a solve can be trusted) are
//! public for `verbss-mpi`'s sweeper, which runs them on one rank's part
//! with its sums over the ranks, rather than keeping a copy.

mod accel;
mod amg;
mod bsr;
mod direct;
mod escalate;
mod frame;
pub mod gmres;
mod laplacian;
mod params;
mod pass;
mod prefetch;
mod sor;
mod spring_solver;
mod sweep;
mod verbss;
pub mod verify;
pub use self::escalate::{
    krylov_stop, DIRECT_NODES_2D, DIRECT_NODES_3D, GMRES_FIRST_NODES_3D, GMRES_ITERATIONS,
    GMRES_RESTART, ROUND_OFF,
};
pub use self::frame::{unit_directions, Frame, Frames};
pub use self::params::{
    clear_prescribed, default_roles, Accel, Method, NodeRole, SolveInfo, SolveParams, Solver,
    Stage, AUTO_SWEEPS, ERROR_FRACTION,
};
use self::pass::{gather, prescribed_scale, run};
pub use self::spring_solver::{SolverSetup, SpringSolver};
pub use self::verbss::{relax, residual};
pub(crate) use sweep::{chunked_dot, chunked_sum, sweep};

use std::sync::Arc;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::geometry::{ldlt_factor, packed_len, packed_mul, point};
use crate::mesh::Mesh;
use crate::springs::{self, Connectivity, NodeBlocks, Springs};
use crate::threads::Workers;
use crate::topology;

/// Nodes of one colour are updated in chunks of this many; each chunk sums its
/// changes on its own and the chunks are added in order, whatever the threads.
/// Small enough that the colours of a small mesh still split evenly over the
/// threads: with 256, a colour of 1,200 nodes made 5 chunks, 3 for one
/// thread and 2 for the other (CHANGELOG.md, 2026-11-22).
pub(crate) const CHUNK: usize = 64;

/// [`chunked_sum`] and [`chunked_dot`] add up fixed pieces of this many numbers.
pub(crate) const SUM_CHUNK: usize = 1024;

/// The mesh-motion engine: topology once per mesh, springs and factors once per
/// reference configuration, one [`Engine::solve`] per step.
pub struct Engine {
    conn: Connectivity,
    roles: Vec<NodeRole>,
    /// Unit plane normals of the sliding nodes (first `D` numbers used).
    normals: Vec<[f64; 3]>,
    built: Option<Built>,
    /// The workers (the deformer's, shared, or started at the first solve).
    pool: Option<Workers>,
    accel: accel::AccelState,
    /// The last layout and the moving nodes it was ordered from: a rebuild
    /// with the same moving nodes (every step of a run) reuses it.
    layout: Option<(Vec<usize>, Arc<Layout>)>,
    /// The method of the last escalated solve and the index, in its chain
    /// of stages, of the stage that solved it (`escalate.rs`).
    escalation: Option<(Method, usize)>,
}

/// What one reference configuration and method need: the system and scratch.
struct Built {
    coords: Vec<f64>,
    method: Method,
    layout: Arc<Layout>,
    system: System,
    lu: Option<direct::Lu>,
    scratch: Scratch,
    /// Each unknown position's local size ([`verify::heights`]).
    heights: Vec<f64>,
    /// Seconds the springs took to assemble.
    springs_seconds: f64,
}

/// The system swept or factored.
enum System {
    /// Spring blocks. `diag` holds per position the (projected, for sliding
    /// nodes) `K_ii`, as its LDLᵀ factor when `factored`; `unprojected` holds the
    /// unprojected `K_ii` per sliding node ([`Frames::project_diagonal`]).
    Blocks {
        blocks: NodeBlocks,
        unprojected: Vec<f64>,
        factored: bool,
    },
    /// Scalar Laplacian weights.
    Laplacian(laplacian::Weights),
}

/// Per-solve arrays, allocated once per build.
struct Scratch {
    /// Right-hand side from the prescribed nodes, `D` per position.
    constant: Vec<f64>,
    /// Displacements of the unknowns by position.
    work: Vec<f64>,
    /// New values of the colour being swept.
    next: Vec<f64>,
    /// Change summed per chunk.
    partials: Vec<f64>,
}

/// The numbering of the unknowns for the sweeps.
#[derive(Clone)]
pub(crate) struct Layout {
    /// Position → node.
    pub(crate) order: Vec<usize>,
    /// Node → position (`u32::MAX` for prescribed nodes).
    pub(crate) position: Vec<u32>,
    /// Colour `c` holds positions `colour_starts[c]..colour_starts[c + 1]`.
    colour_starts: Vec<usize>,
    /// Colour `c`'s chunk sums are `partials[chunk_starts[c]..chunk_starts[c + 1]]`.
    chunk_starts: Vec<usize>,
    /// The frames of the sliding positions.
    pub(crate) frames: Frames,
    /// Unknown components ([`Frames::unknowns`]).
    pub(crate) dofs: usize,
}

impl Layout {
    /// The frame of position `p`, if it slides.
    #[inline(always)]
    pub(crate) fn frame<const D: usize>(&self, p: usize) -> Option<Frame<D>> {
        self.frames.get::<D>(p)
    }

    /// Number of unknown nodes.
    fn len(&self) -> usize {
        self.order.len()
    }
}

/// `c_p + Σ_j B_pj u_j` over the unknown neighbours of position `p`
/// (`constant` and `work` hold `D` numbers per position).
// The counter `e` beside the zip: zipping `a..` in as clippy suggests
// compiles to a loop that keeps its state in memory, with slower sweeps
// (CHANGELOG.md, 2026-11-22, "Tried and not adopted").
#[allow(clippy::explicit_counter_loop)]
#[inline(always)]
pub fn coupled<const D: usize>(
    blocks: &NodeBlocks,
    constant: &[f64],
    p: usize,
    work: &[f64],
) -> [f64; D] {
    let s = packed_len(D);
    let (a, b) = (blocks.offsets[p], blocks.offsets[p + 1]);
    let points = work.as_chunks::<D>().0;
    let mut r = point::<D>(constant, p);
    let mut e = a;
    let couplings = blocks.blocks[s * a..s * b].chunks_exact(s);
    for (block, &j) in couplings.zip(&blocks.neighbours[a..b]) {
        prefetch::ahead::<D>(work, &blocks.neighbours, e);
        prefetch::block(block);
        e += 1;
        let v = packed_mul::<D>(block, &points[j as usize]);
        for k in 0..D {
            r[k] += v[k];
        }
    }
    r
}

impl Engine {
    /// Topology once per mesh. `roles`: one per node. `normals`: unit plane
    /// normals for [`NodeRole::Slide`]`(k)` (3 numbers each; the first `D`
    /// are used, and normalised).
    ///
    /// Fails with [`Error::InvalidSetting`] when the roles do not match the
    /// nodes, a sliding node names a missing or zero normal, or an unknown node
    /// is not connected (through cells) to any [`NodeRole::Fixed`] node, which
    /// would leave its displacement undetermined.
    pub fn new(mesh: &Mesh, roles: &[NodeRole], normals: &[[f64; 3]]) -> Result<Engine> {
        Engine::with_connectivity(Connectivity::new(mesh), mesh, roles, normals)
    }

    /// [`Engine::new`] on the connectivity `conn` of `mesh`.
    pub(crate) fn with_connectivity(
        conn: Connectivity,
        mesh: &Mesh,
        roles: &[NodeRole],
        normals: &[[f64; 3]],
    ) -> Result<Engine> {
        let n = mesh.node_count();
        let dim = mesh.dim;
        if roles.len() != n {
            return Err(Error::InvalidSetting(format!(
                "{} node roles for {n} nodes",
                roles.len()
            )));
        }
        let unit = unit_directions(dim, roles, normals, |i| mesh.node_tags[i])?;
        let accel = accel::AccelState::new(&conn.cells.kinds);
        let fixed: Vec<usize> = (0..n).filter(|&i| roles[i] == NodeRole::Fixed).collect();
        let reach = topology::bfs_layers(&conn.graph, &fixed);
        if let Some(i) = (0..n).find(|&i| reach[i] == u32::MAX && roles[i] != NodeRole::Fixed) {
            return Err(Error::InvalidSetting(format!(
                "node {} is not connected to any fixed node (its displacement would be \
                 undetermined)",
                mesh.node_tags[i]
            )));
        }
        Ok(Engine {
            conn,
            roles: roles.to_vec(),
            normals: unit,
            built: None,
            pool: None,
            accel,
            layout: None,
            escalation: None,
        })
    }

    /// Sets per-node spring stiffness factors (see
    /// [`Connectivity::stiffness`]; empty: all 1); the system is rebuilt at
    /// the next solve.
    pub fn set_stiffness(&mut self, factors: Vec<f64>) {
        self.conn.stiffness = factors;
        self.built = None;
    }

    /// The per-node spring stiffness factors (empty: all 1).
    pub fn stiffness(&self) -> &[f64] {
        &self.conn.stiffness
    }

    /// Bytes of the sweep's stored data per unknown node: diagonal factors,
    /// coupling blocks and neighbour indices, offsets, sliding frames,
    /// right-hand side and displacement arrays (0 before the first solve).
    pub fn bytes_per_node(&self) -> f64 {
        let Some(b) = &self.built else { return 0.0 };
        let f = std::mem::size_of::<f64>();
        let u = std::mem::size_of::<u32>();
        let z = std::mem::size_of::<usize>();
        let l = &b.layout;
        let common = (b.scratch.constant.len() + b.scratch.work.len() + b.scratch.next.len()) * f
            + l.frames.bytes();
        let system = match &b.system {
            System::Blocks {
                blocks,
                unprojected,
                ..
            } => {
                (blocks.diag.len() + blocks.blocks.len() + unprojected.len()) * f
                    + blocks.neighbours.len() * u
                    + blocks.offsets.len() * z
            }
            System::Laplacian(w) => w.sweep_bytes(),
        };
        (common + system) as f64 / l.len().max(1) as f64
    }

    /// Bytes of the displacement array that the colour passes of one sweep
    /// read, per unknown node (0 before the first solve): whole 64-byte
    /// cache lines (the array taken to start on one), each counted once per
    /// colour pass that reads it. A pass reads its own nodes and their
    /// neighbours, which lie in every other colour's block; where no line
    /// stays cached from one pass to the next, a sweep reads this much of the
    /// displacements, against the `8 D` bytes per node that
    /// [`Engine::bytes_per_node`] counts once.
    pub fn colour_pass_read_bytes(&self) -> f64 {
        const LINE: usize = 64;
        let per_line = LINE / std::mem::size_of::<f64>();
        let Some(b) = &self.built else { return 0.0 };
        let (offsets, neighbours) = match &b.system {
            System::Blocks { blocks, .. } => (&blocks.offsets[..], &blocks.neighbours[..]),
            System::Laplacian(w) => w.rows(),
        };
        let (d, l) = (self.conn.dim, &b.layout);
        let mut read_in = vec![usize::MAX; (d * l.len()).div_ceil(per_line)];
        let mut lines = 0;
        for (c, colour) in l.colour_starts.windows(2).enumerate() {
            for p in colour[0]..colour[1] {
                let row = neighbours[offsets[p]..offsets[p + 1]].iter();
                for j in std::iter::once(p).chain(row.map(|&j| j as usize)) {
                    let first = d * j / per_line;
                    let last = (d * j + d - 1) / per_line;
                    for pass in &mut read_in[first..=last] {
                        if *pass != c {
                            *pass = c;
                            lines += 1;
                        }
                    }
                }
            }
        }
        (lines * LINE) as f64 / l.len().max(1) as f64
    }

    /// Validates the arrays and settings of [`Engine::solve`].
    fn check(&self, coords: &[f64], displacement: &[f64], params: &SolveParams) -> Result<()> {
        let dim = self.conn.dim;
        let want = dim * self.roles.len();
        for (name, a) in [("coordinates", coords), ("displacements", displacement)] {
            if a.len() != want {
                return Err(Error::InvalidSetting(format!(
                    "{} {name} for {} nodes in {dim}D (expected {want})",
                    a.len(),
                    self.roles.len()
                )));
            }
            if let Some(k) = a.iter().position(|v| !v.is_finite()) {
                return Err(Error::InvalidSetting(format!(
                    "{name} of node {} are not finite",
                    self.conn.node_tags[k / dim]
                )));
            }
        }
        params.validate()?;
        Ok(())
    }

    /// Orders the unknowns, assembles the springs and prepares the diagonal;
    /// the springs are written over `kept`, the blocks of the last build of
    /// the same method, when the order is the same
    /// ([`springs::assemble_reusing`]). The order follows the moving nodes
    /// ([`Engine::layout`]) except while a multigrid hierarchy is kept.
    fn build<const D: usize>(
        &mut self,
        coords: &[f64],
        displacement: &[f64],
        method: Method,
        kept: Option<NodeBlocks>,
    ) -> Result<Built> {
        let seeds = self.moving::<D>(displacement);
        // A multigrid hierarchy is built on the order of the unknowns: while
        // one is kept, so is the order, even when the moving nodes change.
        let hierarchy = self.accel.has_hierarchy();
        let (layout, kept) = match &self.layout {
            Some((same, layout)) if *same == seeds || hierarchy => (Arc::clone(layout), kept),
            _ => {
                let layout = Arc::new(self.layout::<D>(&seeds));
                self.layout = Some((seeds, Arc::clone(&layout)));
                (layout, None)
            }
        };
        let mut springs_seconds = 0.0;
        let system = match method {
            Method::Laplacian => {
                System::Laplacian(laplacian::Weights::new::<D>(&self.conn, coords, &layout)?)
            }
            Method::Spring | Method::Verbss | Method::BallVertex => {
                let kind = if method == Method::Spring {
                    Springs::Edge
                } else {
                    Springs::BallVertex
                };
                let started = std::time::Instant::now();
                let mut blocks = springs::assemble_reusing(
                    &self.conn,
                    coords,
                    &layout.order,
                    &layout.position,
                    kind,
                    kept,
                )?;
                springs_seconds = started.elapsed().as_secs_f64();
                let factored = method != Method::BallVertex;
                let unprojected = self.prepare_diag::<D>(&mut blocks, &layout, factored)?;
                System::Blocks {
                    blocks,
                    unprojected,
                    factored,
                }
            }
        };
        let m = layout.len();
        let chunks = *layout.chunk_starts.last().unwrap_or(&0);
        let heights = verify::heights::<D>(&self.conn, coords, &layout.order);
        Ok(Built {
            heights,
            springs_seconds,
            coords: coords.to_vec(),
            method,
            layout,
            system,
            lu: None,
            scratch: Scratch {
                constant: vec![0.0; D * m],
                work: vec![0.0; D * m],
                next: vec![0.0; D * m],
                partials: vec![0.0; chunks],
            },
        })
    }

    /// Projects the diagonal blocks of sliding nodes on their frame
    /// ([`Frames::project_diagonal`]) and, when `factored`, replaces every
    /// diagonal block by its LDLᵀ factor. Returns the unprojected blocks of
    /// the sliding nodes.
    fn prepare_diag<const D: usize>(
        &self,
        blocks: &mut NodeBlocks,
        layout: &Layout,
        factored: bool,
    ) -> Result<Vec<f64>> {
        let s = packed_len(D);
        let unprojected = layout.frames.project_diagonal::<D>(&mut blocks.diag);
        if factored {
            // Block by block on the current pool; the first singular one named.
            let singular = blocks.diag[..s * layout.len()]
                .par_chunks_mut(s)
                .enumerate()
                .filter_map(|(p, diag)| {
                    let a = diag.to_vec();
                    (!ldlt_factor::<D>(&a, diag)).then_some(p)
                })
                .min();
            if let Some(p) = singular {
                return Err(Error::InvalidMesh(format!(
                    "node {}: its springs do not hold it in every direction \
                     (singular stiffness block)",
                    self.conn.node_tags[layout.order[p]]
                )));
            }
        }
        Ok(unprojected)
    }

    /// The seeds of the breadth-first order: the prescribed nodes with a
    /// nonzero prescribed displacement (all prescribed nodes when none moves).
    fn moving<const D: usize>(&self, displacement: &[f64]) -> Vec<usize> {
        let n = self.roles.len();
        let moving = |i: usize| {
            self.roles[i]
                .prescribed::<D>(&self.normals, &point::<D>(displacement, i))
                .iter()
                .any(|&v| v != 0.0)
        };
        let seeds: Vec<usize> = (0..n).filter(|&i| moving(i)).collect();
        if seeds.is_empty() {
            (0..n)
                .filter(|&i| self.roles[i] != NodeRole::Free)
                .collect()
        } else {
            seeds
        }
    }

    /// Orders the unknowns by breadth-first layers from the moving boundary,
    /// colours them greedily in that order and numbers them colour by colour,
    /// along the Z-order curve of the input mesh (`Connectivity::locality`) within a
    /// colour.
    fn layout<const D: usize>(&self, seeds: &[usize]) -> Layout {
        let n = self.roles.len();
        let layer = topology::bfs_layers(&self.conn.graph, seeds);
        let mut by_layer: Vec<usize> = (0..n)
            .filter(|&i| self.roles[i] != NodeRole::Fixed)
            .collect();
        by_layer.sort_by_key(|&i| (layer[i], i));
        let (colour, colours) = topology::colour(&self.conn.graph, &by_layer);
        let mut order = by_layer;
        order.sort_by_key(|&i| (colour[i], self.conn.locality[i]));
        let mut colour_starts = vec![0usize; colours as usize + 1];
        for &i in &order {
            colour_starts[colour[i] as usize + 1] += 1;
        }
        let mut chunk_starts = vec![0; colours as usize + 1];
        for c in 0..colours as usize {
            colour_starts[c + 1] += colour_starts[c];
            let len = colour_starts[c + 1] - colour_starts[c];
            chunk_starts[c + 1] = chunk_starts[c] + len.div_ceil(CHUNK);
        }
        let mut position = vec![u32::MAX; n];
        for (p, &i) in order.iter().enumerate() {
            position[i] = p as u32;
        }
        let frames = Frames::new::<D>(order.iter().map(|&i| self.roles[i]), &self.normals);
        let dofs = frames.unknowns::<D>();
        Layout {
            order,
            position,
            colour_starts,
            chunk_starts,
            frames,
            dofs,
        }
    }
}
