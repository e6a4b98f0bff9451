//! Near-wall treatments for boundary-layer meshes (beyond the paper).
//!
//! The paper's springs spread a moving wall's motion from the wall itself, so
//! the thin cells glued to the wall take the shear first: on a RANS mesh
//! (first cell 10⁻⁵ chord, cells of aspect ratio 100–1000) a rigid pitch
//! inverts them within a few degrees. Two treatments keep the paper's kernel
//! and survive such meshes ([`Robust`]):
//!
//! * the **rigid layer** ([`Layer`]): the free nodes within a distance `t` of
//!   a moving wall — and nearer to it than [`GAP_SHARE`] of their distance
//!   to any other boundary, so that a gap between two bodies keeps most of
//!   its width free to close — move with the wall and become prescribed
//!   nodes of the spring system. A node takes
//!   the motion of its nearest wall node: that motion evaluated at the node
//!   itself for the analytic motions (exactly rigid for a rigid body), or the
//!   nearest wall node's displacement for prescribed positions (carried along
//!   the wall normal). The springs then spread the motion from the layer's
//!   outer edge, where the cells are larger and isotropic;
//! * **adaptive sub-steps**: an updated-reference step that inverts an
//!   element is redone in smaller increments — the prescribed nodes
//!   interpolated linearly between their positions at the step's start and
//!   end, the springs rebuilt on each increment — halving the increment
//!   after a failure and doubling it after a success, down to `2^-k` of the
//!   step.
//!
//! `t` by default ([`Layer::Auto`]): per body (the moving nodes sharing one
//! chain of motions), the larger of the boundary layer's thickness — the
//! largest wall distance reached from the wall through cells of aspect ratio
//! at least [`ANISOTROPIC`], at most [`BL_CAP`] of the body's size — and
//! [`INNER_FRACTION`] of the body's size (the diagonal of its bounding box).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::solve::NodeRole;
use crate::topology::{self, Csr};

/// Cells at least this stretched (longest over shortest edge) belong to a
/// boundary layer.
pub const ANISOTROPIC: f64 = 4.0;

/// The boundary layer's thickness is taken at most this fraction of the body's size.
pub const BL_CAP: f64 = 0.2;

/// The automatic rigid layer is at least this fraction of the body's size thick.
pub const INNER_FRACTION: f64 = 0.05;

/// A rigid-layer node must be at most this fraction of its distance to any
/// other boundary (another body, a fixed wall) away from its own wall. In a
/// gap of width `g` each side's layer then takes at most `g/11`, and the free
/// nodes between keep `9/11` of it to absorb a gap that closes: with `1/2`
/// (a third of the gap each) the paper's three-element airfoil inverted in
/// its slat's slot at step 27 of 40 (docs/robustness.md, "The layer in a
/// closing slot").
pub const GAP_SHARE: f64 = 0.1;

/// The thickness of the rigid layer around moving walls.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Layer {
    /// No rigid layer: the paper's method.
    #[default]
    Off,
    /// From the mesh: the boundary layer or [`INNER_FRACTION`] of the body's size.
    Auto,
    /// A given wall distance.
    Thickness(f64),
}

impl serde::Serialize for Layer {
    /// `"off"`, `"auto"` or the thickness as a number.
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Layer::Off => serializer.serialize_str("off"),
            Layer::Auto => serializer.serialize_str("auto"),
            Layer::Thickness(t) => serializer.serialize_f64(*t),
        }
    }
}

impl std::str::FromStr for Layer {
    type Err = Error;

    /// `off`, `auto` or a positive wall distance.
    fn from_str(s: &str) -> Result<Layer> {
        match s {
            "off" => Ok(Layer::Off),
            "auto" => Ok(Layer::Auto),
            _ => match s.parse::<f64>() {
                Ok(t) if t > 0.0 && t.is_finite() => Ok(Layer::Thickness(t)),
                _ => Err(Error::InvalidSetting(format!(
                    "the rigid layer must be off, auto or a positive wall distance (got '{s}')"
                ))),
            },
        }
    }
}

/// The near-wall treatments of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
#[non_exhaustive]
pub struct Robust {
    /// The rigid layer.
    pub layer: Layer,
    /// Adaptive sub-steps: at most `2^substeps` increments per step (0: off).
    pub substeps: u32,
    /// Wall-distance stiffening: the springs at wall distance `d` are
    /// scaled by `(t / max(d, t))^p` with `t` the rigid layer's thickness
    /// (or [`INNER_FRACTION`] of the body's size without a layer), so that
    /// cells near a moving wall deform less (0: off).
    pub stiffening: f64,
    /// The blended rigid motion: each body's best rigid motion carried into
    /// the mesh with a harmonic weight before the springs solve what is left
    /// (`deform/blend.rs`).
    pub blend: bool,
}

impl Robust {
    /// Checks the treatments: a stiffening exponent ≥ 0, a positive layer
    /// thickness, at most 30 sub-step halvings.
    pub fn validate(&self) -> Result<()> {
        let p = self.stiffening;
        if !(p >= 0.0 && p.is_finite()) {
            return Err(Error::InvalidSetting(format!(
                "the stiffening exponent must be zero or positive (got {p})"
            )));
        }
        if let Layer::Thickness(t) = self.layer {
            if !(t > 0.0 && t.is_finite()) {
                return Err(Error::InvalidSetting(format!(
                    "the rigid layer's thickness must be positive (got {t})"
                )));
            }
        }
        if self.substeps > 30 {
            return Err(Error::InvalidSetting(format!(
                "substeps must be at most 30 (got {})",
                self.substeps
            )));
        }
        Ok(())
    }

    /// The paper's method: no treatment.
    pub fn off() -> Robust {
        Robust::default()
    }

    /// The recommended treatments: the automatic rigid layer, inverse
    /// wall-distance stiffening (`p = 1`), sub-steps down to 1/64 of a step
    /// and the blended rigid motion.
    pub fn recommended() -> Robust {
        Robust {
            layer: Layer::Auto,
            substeps: 6,
            stiffening: 1.0,
            blend: true,
        }
    }
}

/// What the treatments need of a mesh: the rigid layer and the stiffness factors.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Treatment {
    /// Each layer node and the moving node it follows (an index into the
    /// deformer's list of moving nodes), or `None` near a fixed wall: the
    /// node stays.
    pub nodes: Vec<(usize, Option<usize>)>,
    /// The layer's thickness around each body, in order of the bodies' first
    /// moving node.
    pub thickness: Vec<f64>,
    /// Per-node spring stiffness factors (empty: no stiffening).
    pub stiffness: Vec<f64>,
}

/// The rigid layer and stiffness factors of `mesh` around the moving nodes
/// `moving` (node and the chain of motions it follows); `roles` are the
/// nodes' roles before the layer (moving nodes and other boundary nodes
/// fixed, sliding nodes, free).
pub fn prepare(
    mesh: &Mesh,
    roles: &[NodeRole],
    moving: &[(usize, Vec<usize>)],
    robust: &Robust,
) -> Result<Treatment> {
    robust.validate()?;
    let p = robust.stiffening;
    let given = match robust.layer {
        Layer::Off if p == 0.0 => return Ok(Treatment::default()),
        Layer::Off | Layer::Auto => None,
        Layer::Thickness(t) => Some(t),
    };
    let n = mesh.node_count();
    let graph = topology::edge_graph_from(&mesh.cells, &topology::node_cells(&mesh.cells, n));
    // Bodies: moving nodes sharing a chain of motions.
    let mut body_of_chain: HashMap<&[usize], usize> = HashMap::new();
    let mut body_seeds: Vec<Vec<usize>> = Vec::new();
    let mut anchor_index = vec![usize::MAX; n];
    for (k, (node, chain)) in moving.iter().enumerate() {
        let next = body_of_chain.len();
        let b = *body_of_chain.entry(chain.as_slice()).or_insert(next);
        if b == body_seeds.len() {
            body_seeds.push(Vec::new());
        }
        body_seeds[b].push(*node);
        anchor_index[*node] = k;
    }
    // Fixed walls inside the domain (a fixed element of a multi-element
    // airfoil) are bodies that stay; the outer boundary is not.
    let mut in_fixed_wall = vec![false; n];
    for nodes in fixed_walls(mesh, roles, &anchor_index) {
        for &i in &nodes {
            in_fixed_wall[i] = true;
        }
        body_seeds.push(nodes);
    }
    let fixed: Vec<usize> = (0..n)
        .filter(|&i| {
            roles[i] == NodeRole::Fixed && anchor_index[i] == usize::MAX && !in_fixed_wall[i]
        })
        .collect();
    let fields: Vec<(Vec<f64>, Vec<usize>)> = body_seeds
        .iter()
        .map(|seeds| nearest_seed(&graph, mesh.dim, &mesh.coords, seeds))
        .collect();
    let to_fixed = nearest_seed(&graph, mesh.dim, &mesh.coords, &fixed).0;
    let thickness: Vec<f64> = match (given, robust.layer) {
        (Some(t), _) => vec![t; body_seeds.len()],
        (None, Layer::Auto) => body_seeds
            .iter()
            .zip(&fields)
            .map(|(seeds, (dist, _))| auto_thickness(mesh, seeds, dist))
            .collect(),
        _ => body_seeds
            .iter()
            .map(|seeds| INNER_FRACTION * size(mesh, seeds))
            .collect(),
    };
    let mut stiffness = Vec::new();
    // A body of no extent (a single moving node) has no thickness: it
    // stiffens nothing.
    if p > 0.0 && thickness.iter().any(|&t| t > 0.0) {
        stiffness = (0..n)
            .map(|i| {
                fields
                    .iter()
                    .zip(&thickness)
                    .filter(|(_, &t)| t > 0.0)
                    .map(|((dist, _), t)| (t / dist[i].max(*t)).powf(p))
                    .fold(f64::MIN_POSITIVE, f64::max)
            })
            .collect();
    }
    let mut nodes = Vec::new();
    for i in 0..n {
        if robust.layer == Layer::Off {
            break;
        }
        if !matches!(
            roles[i],
            NodeRole::Free | NodeRole::Slide(_) | NodeRole::Line(_)
        ) {
            continue;
        }
        let Some((b, (dist, seed))) = fields
            .iter()
            .enumerate()
            .min_by(|x, y| x.1 .0[i].total_cmp(&y.1 .0[i]))
        else {
            break;
        };
        let d = dist[i];
        let other = fields
            .iter()
            .enumerate()
            .filter(|&(c, _)| c != b)
            .map(|(_, f)| f.0[i])
            .fold(to_fixed[i], f64::min);
        if d <= thickness[b] && d <= GAP_SHARE * other {
            let anchor = anchor_index[seed[i]];
            nodes.push((i, (anchor != usize::MAX).then_some(anchor)));
        }
    }
    Ok(Treatment {
        nodes,
        thickness,
        stiffness,
    })
}

/// The nodes of each group that is a fixed wall inside the domain: all its
/// nodes prescribed, none moving, and its bounding box inside the mesh's
/// (so that the outer boundary is not one).
fn fixed_walls(mesh: &Mesh, roles: &[NodeRole], anchor: &[usize]) -> Vec<Vec<usize>> {
    let all: Vec<usize> = (0..mesh.node_count()).collect();
    let outer = bounds(mesh, &all);
    mesh.groups
        .iter()
        .map(|g| g.nodes())
        .filter(|nodes| {
            !nodes.is_empty()
                && nodes
                    .iter()
                    .all(|&i| roles[i] == NodeRole::Fixed && anchor[i] == usize::MAX)
                && {
                    let (lo, hi) = bounds(mesh, nodes);
                    (0..mesh.dim).all(|d| lo[d] > outer.0[d] && hi[d] < outer.1[d])
                }
        })
        .collect()
}

/// For every node of `coords` the distance to its nearest seed and that seed, found by
/// spreading the seeds along the mesh edges (a node takes the nearest, in
/// straight line, of its neighbours' seeds, until nothing changes). Nodes
/// no seed reaches keep an infinite distance.
pub(crate) fn nearest_seed(
    graph: &Csr,
    dim: usize,
    coords: &[f64],
    seeds: &[usize],
) -> (Vec<f64>, Vec<usize>) {
    let n = graph.rows();
    let mut dist = vec![f64::INFINITY; n];
    let mut seed = vec![usize::MAX; n];
    let mut heap = BinaryHeap::new();
    for &s in seeds {
        dist[s] = 0.0;
        seed[s] = s;
        heap.push(Reverse((0u64, s)));
    }
    // Non-negative f64s order like their bit patterns.
    while let Some(Reverse((bits, i))) = heap.pop() {
        if f64::from_bits(bits) > dist[i] {
            continue;
        }
        let s = seed[i];
        for j in graph.entries(i) {
            let d = distance(
                &coords[dim * j..dim * (j + 1)],
                &coords[dim * s..dim * (s + 1)],
            );
            if d < dist[j] {
                dist[j] = d;
                seed[j] = s;
                heap.push(Reverse((d.to_bits(), j)));
            }
        }
    }
    (dist, seed)
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// A body's automatic layer thickness (see the module documentation);
/// `dist` is every node's distance to the body's wall nodes `seeds`.
fn auto_thickness(mesh: &Mesh, seeds: &[usize], dist: &[f64]) -> f64 {
    let size = size(mesh, seeds);
    let n = mesh.node_count();
    let node_cells = topology::node_cells(&mesh.cells, n);
    let mut reached = vec![false; n];
    let mut queue: Vec<usize> = seeds.to_vec();
    for &s in seeds {
        reached[s] = true;
    }
    let mut seen_cell = vec![false; mesh.cell_count()];
    let mut layer: f64 = 0.0;
    while let Some(i) = queue.pop() {
        for c in node_cells.entries(i) {
            if seen_cell[c] {
                continue;
            }
            seen_cell[c] = true;
            if aspect_ratio(mesh, c) < ANISOTROPIC {
                continue;
            }
            for &j in mesh.cells.cell(c) {
                if !reached[j] && dist[j] <= BL_CAP * size {
                    reached[j] = true;
                    layer = layer.max(dist[j]);
                    queue.push(j);
                }
            }
        }
    }
    layer.max(INNER_FRACTION * size)
}

/// Longest over shortest edge of cell `c`.
fn aspect_ratio(mesh: &Mesh, c: usize) -> f64 {
    let nodes = mesh.cells.cell(c);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for &[a, b] in mesh.cells.kinds[c].table().edges {
        let l = distance(mesh.point(nodes[a]), mesh.point(nodes[b]));
        lo = lo.min(l);
        hi = hi.max(l);
    }
    hi / lo
}

/// The corners of the bounding box of nodes `nodes`.
fn bounds(mesh: &Mesh, nodes: &[usize]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &s in nodes {
        for (d, x) in mesh.point(s).iter().enumerate() {
            lo[d] = lo[d].min(*x);
            hi[d] = hi[d].max(*x);
        }
    }
    (lo, hi)
}

/// The diagonal of the bounding box of nodes `seeds`.
pub(crate) fn size(mesh: &Mesh, seeds: &[usize]) -> f64 {
    let (lo, hi) = bounds(mesh, seeds);
    (0..mesh.dim)
        .map(|d| (hi[d] - lo[d]).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests;
