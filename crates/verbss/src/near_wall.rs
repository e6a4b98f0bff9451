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

use crate::collective::{mark_sync, Collective};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::solve::NodeRole;
use crate::topology::{self, Csr};

pub(crate) mod blend;
mod distances;
mod harmonic;
mod rigid_fit;
pub(crate) mod spread;

pub use self::spread::Seeds;

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
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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
    /// (`near_wall/blend.rs`).
    pub blend: bool,
    /// The relocation of the worst cells' nodes after the springs: the
    /// free and sliding nodes of a cell below half its input quality moved
    /// to raise its cells' least quality ratio (`deform/relocate.rs`).
    pub relocate: bool,
}

impl Robust {
    /// Whether a rigid layer or a stiffening is asked for: what needs the
    /// wall distances ([`prepare`]).
    pub fn treats(&self) -> bool {
        self.layer != Layer::Off || self.stiffening != 0.0
    }

    /// Checks the treatments against their ranges
    /// ([`crate::settings::TABLE`]): a stiffening exponent ≥ 0, a positive
    /// layer thickness, at most 30 sub-step halvings.
    pub fn validate(&self) -> Result<()> {
        use crate::settings::{check_value, Value};
        check_value("stiffening", Value::Number(self.stiffening))?;
        if let Layer::Thickness(t) = self.layer {
            check_value("rigid_layer", Value::Number(t))?;
        }
        check_value("substeps", Value::Count(u64::from(self.substeps)))
    }

    /// The paper's method: no treatment.
    pub fn off() -> Robust {
        Robust::default()
    }

    /// The recommended treatments: the automatic rigid layer, inverse
    /// wall-distance stiffening (`p = 1`), sub-steps down to 1/64 of a step,
    /// the blended rigid motion and the relocation of the worst cells' nodes.
    pub fn recommended() -> Robust {
        Robust {
            layer: Layer::Auto,
            substeps: 6,
            stiffening: 1.0,
            blend: true,
            relocate: true,
        }
    }
}

/// What a rigid-layer node moves with: a body (an index into the run's
/// bodies) with the tag of its nearest node of that body (whose
/// displacement it takes where the body moves by given positions), or
/// `None` near a fixed wall: the node stays.
pub type Follows = Option<(usize, u64)>;

/// What the treatments need of a mesh: the rigid layer and the stiffness factors.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Treatment {
    /// Each layer node and what it moves with.
    pub nodes: Vec<(usize, Follows)>,
    /// The layer's thickness around each body, then around each fixed wall.
    pub thickness: Vec<f64>,
    /// Per-node spring stiffness factors (empty: no stiffening).
    pub stiffness: Vec<f64>,
}

/// The rigid layer and stiffness factors of the local mesh `mesh` (a whole
/// mesh, or one process's part with its ghosts) around the moving nodes
/// `moving` (node and body, of the bodies numbered alike on every process
/// moved by given positions where `given` says so: no stiffening around
/// those, see [`stiffness_factor`]), collective over the processes
/// `on`: every node gets one process's answer on any cut, the walks' seeds gathered from their
/// owners and their reach made global by ghost refreshes. `roles` are the
/// nodes' roles before the layer (moving nodes and other boundary nodes
/// fixed, sliding nodes, free); `graph` the local cells' edge graph
/// ([`topology::edge_graph`]) where the caller has it, built here otherwise.
pub fn prepare(
    mesh: &Mesh,
    graph: Option<&Csr>,
    roles: &[NodeRole],
    (given, moving): (&[bool], &[(usize, usize)]),
    robust: &Robust,
    on: &dyn Collective,
) -> Result<Treatment> {
    robust.validate()?;
    let p = robust.stiffening;
    if !robust.treats() {
        return Ok(Treatment::default());
    }
    let (n, dim, bodies) = (mesh.node_count(), mesh.dim, given.len());
    let built;
    let graph = match graph {
        Some(graph) => graph,
        None => {
            built = topology::edge_graph(&mesh.cells, n);
            &built
        }
    };
    let mut seeds: Vec<Vec<usize>> = vec![Vec::new(); bodies];
    let mut is_moving = vec![false; n];
    for &(i, b) in moving {
        seeds[b].push(i);
        is_moving[i] = true;
    }
    // Fixed walls inside the domain (a fixed element of a multi-element
    // airfoil) are bodies that stay: groups whose nodes are all prescribed,
    // none moving, and whose box is strictly inside the mesh's (so that
    // the outer boundary is not one).
    let all: Vec<usize> = (0..n).collect();
    let outer = Bounds::of(dim, &mesh.coords, &all).reduced(on);
    let mut in_wall = vec![false; n];
    for group in &mesh.groups {
        let nodes = group.nodes();
        let prescribed = nodes
            .iter()
            .all(|&i| roles[i] == NodeRole::Fixed && !is_moving[i]);
        let mut counts = [nodes.len() as f64, f64::from(u8::from(!prescribed))];
        on.sum(&mut counts);
        let bounds = Bounds::of(dim, &mesh.coords, &nodes).reduced(on);
        if counts[0] == 0.0 || counts[1] > 0.0 || !bounds.inside(&outer) {
            continue;
        }
        for &i in &nodes {
            in_wall[i] = true;
        }
        seeds.push(nodes);
    }
    let tags = &mesh.node_tags;
    // Every process's owned seeds, gathered: each node's nearest one.
    let nearest = |seeds: &[usize], limit: &dyn Fn(usize) -> f64| -> (Vec<f64>, Vec<u64>) {
        let owned: Vec<usize> = seeds.iter().copied().filter(|&s| on.owns(s)).collect();
        let points: Vec<f64> = owned
            .iter()
            .flat_map(|&s| &mesh.coords[dim * s..dim * (s + 1)])
            .copied()
            .collect();
        let ids: Vec<f64> = owned.iter().map(|&s| tags[s] as f64).collect();
        let ids: Vec<u64> = on.gather(&ids).into_iter().map(|t| t as u64).collect();
        let all = Seeds::new(dim, &on.gather(&points), &ids);
        spread::nearest_connected(&all, graph, &mesh.coords, seeds, limit, mark_sync(on))
    };
    let fields: Vec<(Vec<f64>, Vec<u64>)> = seeds
        .iter()
        .map(|s| nearest(s, &|_| f64::INFINITY))
        .collect();
    let thickness: Vec<f64> = seeds
        .iter()
        .zip(&fields)
        .map(|(seeds, (dist, _))| {
            let size = Bounds::of(dim, &mesh.coords, seeds).reduced(on).diagonal();
            thickness(robust.layer, size, |cap| {
                let mut reached = vec![false; n];
                for &s in seeds {
                    reached[s] = true;
                }
                let mut layer = [spread::reach(
                    &mesh.cells,
                    &mesh.coords,
                    dim,
                    dist,
                    cap,
                    &mut reached,
                    mark_sync(on),
                )];
                on.max(&mut layer);
                layer[0]
            })
        })
        .collect();
    let free = |i: usize| {
        robust.layer != Layer::Off
            && matches!(
                roles[i],
                NodeRole::Free | NodeRole::Slide(_) | NodeRole::Line(_)
            )
    };
    let limits = fixed_limits(n, &fields, &thickness, free);
    let fixed: Vec<usize> = (0..n)
        .filter(|&i| roles[i] == NodeRole::Fixed && !is_moving[i] && !in_wall[i])
        .collect();
    let to_fixed = nearest(&fixed, &|i| limits[i]).0;
    // A body of no extent (a single moving node) has no thickness: it
    // stiffens nothing, nor does a body moved by given positions.
    let stiffening: Vec<f64> = thickness
        .iter()
        .enumerate()
        .map(|(b, &t)| if b < bodies && given[b] { 0.0 } else { t })
        .collect();
    let stiffen = p > 0.0 && stiffening.iter().any(|&t| t > 0.0);
    let mut stiffness = Vec::new();
    let mut nodes = Vec::new();
    let mut at = vec![0.0; fields.len()];
    for i in 0..n {
        for (a, (dist, _)) in at.iter_mut().zip(&fields) {
            *a = dist[i];
        }
        if stiffen {
            stiffness.push(stiffness_factor(&at, &stiffening, p));
        }
        if !free(i) {
            continue;
        }
        if let Some(b) = layer_body(&at, to_fixed[i], &thickness) {
            nodes.push((i, (b < bodies).then(|| (b, fields[b].1[i]))));
        }
    }
    Ok(Treatment {
        nodes,
        thickness,
        stiffness,
    })
}

/// A body's layer thickness `t` (see the module documentation): the given
/// one, or with [`Layer::Auto`] the larger of the boundary layer's
/// thickness `reached(cap)` (the largest wall distance reached through
/// anisotropic cells, at most `cap = BL_CAP · size`) and
/// `INNER_FRACTION · size`, or without a layer `INNER_FRACTION · size` (the
/// stiffening's `t`); `size` is the diagonal of the body's bounding box.
pub fn thickness(layer: Layer, size: f64, reached: impl FnOnce(f64) -> f64) -> f64 {
    match layer {
        Layer::Thickness(t) => t,
        Layer::Auto => reached(BL_CAP * size).max(INNER_FRACTION * size),
        Layer::Off => INNER_FRACTION * size,
    }
}

/// The stiffness factor of a node at distance `dist[b]` from body `b` of
/// thickness `thickness[b]`: `max_b (t_b / max(d_b, t_b))^p` over the
/// bodies with `t_b > 0` (a body of no extent stiffens nothing), at least
/// the smallest positive number. [`prepare`] gives a body moved by given
/// positions `t_b = 0`: the springs spread its deformation, and graded
/// springs carry it farther than the wall moves (docs/method.md,
/// "Amplification": the aft part of an airfoil drooped 0.15 chord moved
/// the wake 7 chords behind it 0.26 chord). A bending and an undulation
/// keep it: without it the bending wing of docs/robustness.md inverted at
/// step 25, not 38.
pub fn stiffness_factor(dist: &[f64], thickness: &[f64], p: f64) -> f64 {
    dist.iter()
        .zip(thickness)
        .filter(|(_, &t)| t > 0.0)
        .map(|(d, t)| (t / d.max(*t)).powf(p))
        .fold(f64::MIN_POSITIVE, f64::max)
}

/// The body whose rigid layer a free node at distance `dist[b]` from each
/// body `b` and `to_fixed` from the other fixed boundary joins: its nearest
/// body `b`, when `d_b ≤ t_b` and `d_b ≤ GAP_SHARE ·` its distance to any
/// other body or the fixed boundary; `None` otherwise.
pub fn layer_body(dist: &[f64], to_fixed: f64, thickness: &[f64]) -> Option<usize> {
    let (b, &d) = dist.iter().enumerate().min_by(|x, y| x.1.total_cmp(y.1))?;
    let other = dist
        .iter()
        .enumerate()
        .filter(|&(c, _)| c != b)
        .map(|(_, &e)| e)
        .fold(to_fixed, f64::min);
    (d <= thickness[b] && d <= GAP_SHARE * other).then_some(b)
}

/// Per node `i` of `n`, given the bodies' distance fields `fields` (distance, seed),
/// the squared distance to the other fixed boundary that can still change
/// [`layer_body`]'s answer, none (−1) where `free(i)` is false (a node that
/// joins no layer) (`fixed_limit`). So the distance to the outer
/// boundary, often equally far from every node near a body, is sought only
/// where it counts.
pub fn fixed_limits(
    n: usize,
    fields: &[(Vec<f64>, Vec<u64>)],
    thickness: &[f64],
    free: impl Fn(usize) -> bool,
) -> Vec<f64> {
    let mut at = vec![0.0; fields.len()];
    (0..n)
        .map(|i| {
            if !free(i) {
                return -1.0;
            }
            for (a, (dist, _)) in at.iter_mut().zip(fields) {
                *a = dist[i];
            }
            fixed_limit(&at, thickness)
        })
        .collect()
}

/// For a node at distance `dist[b]` from each body `b`: `(d_b /
/// GAP_SHARE)²` (widened by 1e-9, above any rounding) for a node within
/// its nearest body's thickness, and none (−1) for another node, which
/// joins no layer whatever its distance to the other fixed boundary.
fn fixed_limit(dist: &[f64], thickness: &[f64]) -> f64 {
    match dist.iter().enumerate().min_by(|x, y| x.1.total_cmp(y.1)) {
        Some((b, &d)) if d <= thickness[b] => {
            let r = d / GAP_SHARE * (1.0 + 1e-9);
            r * r
        }
        _ => -1.0,
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The bounding box of some nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// The dimension.
    pub dim: usize,
    /// The smallest coordinates (`+∞` for no node).
    pub lo: [f64; 3],
    /// The largest coordinates (`−∞` for no node).
    pub hi: [f64; 3],
}

impl Bounds {
    /// The box of nodes `nodes` of `coords`.
    pub fn of(dim: usize, coords: &[f64], nodes: &[usize]) -> Bounds {
        let mut b = Bounds {
            dim,
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
        };
        for &s in nodes {
            for d in 0..dim {
                b.lo[d] = b.lo[d].min(coords[dim * s + d]);
                b.hi[d] = b.hi[d].max(coords[dim * s + d]);
            }
        }
        b
    }

    /// The length of its diagonal.
    pub fn diagonal(&self) -> f64 {
        (0..self.dim)
            .map(|d| (self.hi[d] - self.lo[d]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// The box of every process's box (collective).
    pub fn reduced(self, on: &dyn Collective) -> Bounds {
        let mut values: Vec<f64> = self.hi.to_vec();
        values.extend(self.lo.iter().map(|x| -x));
        on.max(&mut values);
        Bounds {
            dim: self.dim,
            lo: [-values[3], -values[4], -values[5]],
            hi: [values[0], values[1], values[2]],
        }
    }

    /// Whether it lies strictly inside `outer`.
    pub fn inside(&self, outer: &Bounds) -> bool {
        (0..self.dim).all(|d| self.lo[d] > outer.lo[d] && self.hi[d] < outer.hi[d])
    }
}

#[cfg(test)]
mod tests;
