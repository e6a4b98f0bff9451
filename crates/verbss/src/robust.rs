//! Near-wall treatments for boundary-layer meshes (beyond the paper).
//!
//! The paper's springs spread a moving wall's motion from the wall itself, so
//! the thin cells glued to the wall take the shear first: on a RANS mesh
//! (first cell 10⁻⁵ chord, cells of aspect ratio 100–1000) a rigid pitch
//! inverts them within a few degrees. Two treatments keep the paper's kernel
//! and survive such meshes ([`Robust`]):
//!
//! * the **rigid layer** ([`Layer`]): the free nodes within a distance `t` of
//!   a moving wall — and nearer to it than half their distance to any other
//!   boundary, so that a gap between two bodies keeps free nodes — move with
//!   the wall and become prescribed nodes of the spring system. A node takes
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
/// other boundary (another body, a fixed wall) away from its own wall.
pub const GAP_SHARE: f64 = 0.5;

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
    let edges = topology::edges(&mesh.cells);
    let graph = Csr::from_pairs(
        n,
        edges
            .iter()
            .flat_map(|&[a, b]| [(a, b), (b, a)].into_iter()),
    );
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
        if !matches!(roles[i], NodeRole::Free | NodeRole::Slide(_)) {
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
        for &j in graph.row(i) {
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
        for &c in node_cells.row(i) {
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
fn size(mesh: &Mesh, seeds: &[usize]) -> f64 {
    let (lo, hi) = bounds(mesh, seeds);
    (0..mesh.dim)
        .map(|d| (hi[d] - lo[d]).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deform::{Deformer, Settings};
    use crate::motion::{Attachment, Motion, PositionSource};
    use std::path::Path;

    const NACA: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/su2/mesh_NACA0012_inv.su2"
    );
    const RAE: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/su2/mesh_RAE2822_turb_ffd.su2"
    );
    const THREE: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../cases/meshes/three-element.msh"
    );
    const BUMP: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/su2/surface_bump.dat"
    );

    fn attach(groups: &[&str], motion: Motion) -> Attachment {
        Attachment {
            groups: groups.iter().map(|g| g.to_string()).collect(),
            motion,
        }
    }

    fn rotation(center: [f64; 2], degrees: f64) -> Motion {
        Motion::Rotation {
            center: [center[0], center[1], 0.0],
            axis: [0.0, 0.0, 1.0],
            angle: degrees.to_radians(),
        }
    }

    fn settings(steps: usize, robust: Robust) -> Settings {
        let mut s = Settings::new(steps);
        s.robust = robust;
        s
    }

    /// Interior nodes the deformer prescribes: the rigid layer.
    fn layer_nodes(mesh: &Mesh, d: &Deformer) -> Vec<usize> {
        let boundary = topology::boundary_nodes(mesh);
        (0..mesh.node_count())
            .filter(|&i| !boundary[i] && d.roles()[i] == NodeRole::Fixed)
            .collect()
    }

    #[test]
    fn the_layer_turns_rigidly_with_its_body_and_lies_within_its_thickness() {
        let mesh = crate::io::read(Path::new(NACA)).unwrap();
        let robust = Robust {
            layer: Layer::Auto,
            ..Robust::off()
        };
        let mut d = Deformer::new(
            &mesh,
            &[attach(&["airfoil"], rotation([0.25, 0.0], 10.0))],
            settings(2, robust),
        )
        .unwrap();
        let layer = layer_nodes(&mesh, &d);
        let (count, thickness) = d.rigid_layer();
        assert_eq!(count, layer.len());
        assert!(count > 100, "{count} layer nodes");
        // The airfoil's chord is 1: the layer is at least 5% of its size thick.
        assert!(thickness[0] >= INNER_FRACTION, "{thickness:?}");
        let wall = mesh.group("airfoil").unwrap().nodes();
        for &i in &layer {
            let d_wall = wall
                .iter()
                .map(|&w| distance(mesh.point(i), mesh.point(w)))
                .fold(f64::INFINITY, f64::min);
            assert!(d_wall <= thickness[0] + 1e-12, "node {i} at {d_wall}");
        }
        d.step(1).unwrap();
        d.step(2).unwrap();
        let (s, c) = 10f64.to_radians().sin_cos();
        let x = &d.current().coords;
        for &i in &layer {
            let p = mesh.point(i);
            let (dx, dy) = (p[0] - 0.25, p[1]);
            assert!((x[2 * i] - (0.25 + c * dx - s * dy)).abs() < 1e-12);
            assert!((x[2 * i + 1] - (s * dx + c * dy)).abs() < 1e-12);
        }
    }

    #[test]
    fn no_cell_joins_the_layers_of_two_bodies_or_a_layer_and_the_far_field() {
        let mesh = crate::io::read(Path::new(THREE)).unwrap();
        let attachments = [
            attach(&["slat"], rotation([0.0, 0.0], -5.0)),
            attach(&["main"], rotation([0.25, 0.0], 2.0)),
            attach(&["flap"], rotation([1.0, 0.0], 5.0)),
        ];
        let plan_roles = Deformer::new(&mesh, &attachments, settings(1, Robust::off()))
            .unwrap()
            .roles()
            .to_vec();
        let mut moving = Vec::new();
        for (k, name) in ["slat", "main", "flap"].iter().enumerate() {
            for i in mesh.group(name).unwrap().nodes() {
                moving.push((i, vec![k]));
            }
        }
        let robust = Robust {
            layer: Layer::Thickness(0.5),
            ..Robust::off()
        };
        let t = prepare(&mesh, &plan_roles, &moving, &robust).unwrap();
        assert!(!t.nodes.is_empty());
        // The body each node moves with: its own, or its layer's.
        let mut body = vec![usize::MAX; mesh.node_count()];
        for (i, chain) in &moving {
            body[*i] = chain[0];
        }
        for &(i, k) in &t.nodes {
            body[i] = moving[k.expect("every element moves")].1[0];
        }
        let far: Vec<bool> = {
            let mut f = vec![false; mesh.node_count()];
            for i in mesh.group("farfield").unwrap().nodes() {
                f[i] = true;
            }
            f
        };
        for (_, nodes) in mesh.cells.iter() {
            let bodies: Vec<usize> = nodes
                .iter()
                .map(|&i| body[i])
                .filter(|&b| b != usize::MAX)
                .collect();
            assert!(
                bodies.windows(2).all(|w| w[0] == w[1]),
                "a cell joins bodies {bodies:?}"
            );
            let in_layer = nodes.iter().any(|&i| t.nodes.iter().any(|&(j, _)| j == i));
            assert!(!(in_layer && nodes.iter().any(|&i| far[i])));
        }
    }

    #[test]
    fn a_fixed_element_keeps_its_layer_in_place_while_the_others_move() {
        let mesh = crate::io::read(Path::new(THREE)).unwrap();
        let attachments = [
            attach(&["slat"], rotation([0.0, 0.0], -5.0)),
            attach(&["flap"], rotation([1.0, 0.0], 5.0)),
        ];
        let robust = Robust {
            layer: Layer::Auto,
            ..Robust::off()
        };
        let mut d = Deformer::new(&mesh, &attachments, settings(1, robust)).unwrap();
        d.step(1).unwrap();
        let x = &d.current().coords;
        let nearest = |i: usize, group: &str| {
            mesh.group(group)
                .unwrap()
                .nodes()
                .iter()
                .map(|&w| distance(mesh.point(i), mesh.point(w)))
                .fold(f64::INFINITY, f64::min)
        };
        let staying: Vec<usize> = layer_nodes(&mesh, &d)
            .into_iter()
            .filter(|&i| nearest(i, "main") < nearest(i, "slat").min(nearest(i, "flap")))
            .collect();
        assert!(staying.len() > 50, "{} nodes", staying.len());
        for i in staying {
            assert_eq!(&x[2 * i..2 * i + 2], mesh.point(i), "node {i}");
        }
    }

    #[test]
    fn stiffening_is_one_within_the_layer_and_falls_as_a_power_of_the_distance() {
        let mesh = crate::io::read(Path::new(NACA)).unwrap();
        let d = Deformer::new(
            &mesh,
            &[attach(&["airfoil"], rotation([0.25, 0.0], 1.0))],
            settings(1, Robust::off()),
        )
        .unwrap();
        let moving: Vec<(usize, Vec<usize>)> = mesh
            .group("airfoil")
            .unwrap()
            .nodes()
            .into_iter()
            .map(|i| (i, vec![0]))
            .collect();
        let robust = Robust {
            layer: Layer::Thickness(0.1),
            stiffening: 2.0,
            ..Robust::off()
        };
        let t = prepare(&mesh, d.roles(), &moving, &robust).unwrap();
        let graph = Csr::from_pairs(
            mesh.node_count(),
            topology::edges(&mesh.cells)
                .iter()
                .flat_map(|&[a, b]| [(a, b), (b, a)].into_iter()),
        );
        let seeds: Vec<usize> = moving.iter().map(|m| m.0).collect();
        let (dist, _) = nearest_seed(&graph, mesh.dim, &mesh.coords, &seeds);
        for (phi, d) in t.stiffness.iter().zip(&dist) {
            let expected = if *d <= 0.1 { 1.0 } else { (0.1 / d).powi(2) };
            assert!((phi - expected).abs() < 1e-15 * expected.max(1.0));
        }
        let off = prepare(&mesh, d.roles(), &moving, &Robust::off()).unwrap();
        assert_eq!(off, Treatment::default());
    }

    #[test]
    fn sub_steps_take_a_step_that_inverts_in_one_increment() {
        let mesh = crate::io::read(Path::new(NACA)).unwrap();
        let turn = [attach(&["airfoil"], rotation([0.25, 0.0], 40.0))];
        let mut plain = Deformer::new(&mesh, &turn, settings(1, Robust::off())).unwrap();
        assert!(matches!(plain.step(1), Err(Error::Inverted { .. })));
        let robust = Robust {
            substeps: 6,
            ..Robust::off()
        };
        let mut d = Deformer::new(&mesh, &turn, settings(1, robust)).unwrap();
        let r = d.step(1).unwrap();
        assert!(
            r.substeps > 1 && r.substeps <= 64,
            "{} increments",
            r.substeps
        );
        assert_eq!(r.inverted, 0);
        let (s, c) = 40f64.to_radians().sin_cos();
        let x = &d.current().coords;
        for i in mesh.group("airfoil").unwrap().nodes() {
            let p = mesh.point(i);
            let (dx, dy) = (p[0] - 0.25, p[1]);
            assert!((x[2 * i] - (0.25 + c * dx - s * dy)).abs() < 1e-12);
            assert!((x[2 * i + 1] - (s * dx + c * dy)).abs() < 1e-12);
        }
    }

    #[test]
    fn the_recommended_treatments_pitch_a_boundary_layer_mesh_three_times_further() {
        // The RAE2822 RANS mesh (quads near the wall) in 3° steps: the paper's
        // method inverts a cell within 15°; the treatments reach 45°.
        let mesh = crate::io::read(Path::new(RAE)).unwrap();
        let turn = [attach(&["AIRFOIL"], rotation([0.25, 0.0], 45.0))];
        let mut plain = Deformer::new(&mesh, &turn, settings(15, Robust::off())).unwrap();
        let failed = (1..=15).find(|&n| plain.step(n).is_err());
        assert!(matches!(failed, Some(n) if n <= 5), "{failed:?}");
        let mut d = Deformer::new(&mesh, &turn, settings(15, Robust::recommended())).unwrap();
        for n in 1..=15 {
            let r = d.step(n).unwrap();
            assert_eq!(r.inverted, 0);
        }
    }

    #[test]
    fn prescribed_positions_carry_the_nearest_wall_displacement_into_the_layer() {
        let mesh = crate::io::read(Path::new(NACA)).unwrap();
        let source = PositionSource::from_file(Path::new(BUMP), mesh.node_count(), 2).unwrap();
        let robust = Robust {
            layer: Layer::Auto,
            ..Robust::off()
        };
        let mut d = Deformer::new(
            &mesh,
            &[attach(&["airfoil"], Motion::Positions(source))],
            settings(1, robust),
        )
        .unwrap();
        d.step(1).unwrap();
        let u = d.displacement();
        let wall: Vec<[f64; 2]> = mesh
            .group("airfoil")
            .unwrap()
            .nodes()
            .into_iter()
            .map(|w| [u[2 * w], u[2 * w + 1]])
            .collect();
        let layer = layer_nodes(&mesh, &d);
        assert!(!layer.is_empty());
        for i in layer {
            assert!(
                wall.iter()
                    .any(|w| (w[0] - u[2 * i]).abs() < 1e-12 && (w[1] - u[2 * i + 1]).abs() < 1e-12),
                "node {i}"
            );
        }
    }

    #[test]
    fn invalid_settings_are_named() {
        let mesh = crate::io::read(Path::new(NACA)).unwrap();
        let turn = [attach(&["airfoil"], rotation([0.25, 0.0], 1.0))];
        for (robust, message) in [
            (
                Robust {
                    layer: Layer::Thickness(-1.0),
                    ..Robust::off()
                },
                "invalid setting: the rigid layer's thickness must be positive (got -1)",
            ),
            (
                Robust {
                    stiffening: f64::NAN,
                    ..Robust::off()
                },
                "invalid setting: the stiffening exponent must be zero or positive (got NaN)",
            ),
        ] {
            let e = Deformer::new(&mesh, &turn, settings(1, robust))
                .err()
                .unwrap();
            assert_eq!(e.to_string(), message);
        }
    }
}
