//! The blended rigid motion (docs/method.md, "Blended rigid motion").
//!
//! Each body's best rigid motion over an increment — a rotation `R` by `θ`
//! about a centre `c` and a translation `t`, fitted to the wall nodes'
//! moves by least squares (in 3D Horn's quaternion method), `c` the point
//! nearest the rotation's axis within half the body's size of the wall
//! nodes' centroid, so that `t` is as small as it can be (a flap turns
//! about its hinge) — is carried into the mesh with two weights in
//! `[0, 1]`, one for the translation and one for the angle:
//!
//! `x_i ← x_i + w_i t + R(v_i θ)(x_i − c) − (x_i − c)`,
//!
//! so a cell moves by a rigid motion plus a smooth stretch and twist and
//! keeps its shape however thin it is. Both weights are 1 on the body and
//! its rigid layer and 0 on every other prescribed node (fixed walls, the
//! far field, other bodies):
//!
//! * `w` solves a Laplacian on the mesh the increment starts from
//!   (`harmonic.rs`), sliding nodes free (their move is then projected
//!   onto their plane by the springs' remainder): [`Weighting::Directional`]
//!   (2D meshes) couples the edges across the translation in the body's
//!   shadow along it up to [`super::harmonic::ACROSS`] times more than
//!   those along it, so the cells ahead of a body are compressed along the
//!   motion, not sheared; [`Weighting::Isotropic`] (and 3D meshes) takes
//!   `k = 1/L`. Recomputed every increment, it follows a gap that
//!   closes: compressed edges couple more strongly and the compression
//!   spreads over the gap;
//! * `v = 1 − ln(1 + d/ρ) / ln(1 + (d + e)/ρ)`, with `d` the distance to the
//!   body's held nodes, `e` the distance to the other prescribed nodes and
//!   `ρ` twice the body's radius about the centre it turns about: the angle
//!   changes by `θ/((ρ + d) ln(1 + (d + e)/ρ))` per unit distance, so a
//!   ring of cells at radius `r ≈ ρ + d` is sheared by about
//!   `θ / ln(1 + (d + e)/ρ)`, nearly the same everywhere — a harmonic weight
//!   would shear the cells next to a sharp trailing edge without bound.
//!
//! The springs then solve only for what the blend leaves: nothing for a
//! rigid body, its deformation otherwise.

use std::sync::Arc;

use rayon::prelude::*;

use super::distances::Nearest;
use super::harmonic::{Laplace, Shadow};
use super::rigid_fit::fit;
use crate::collective::Collective;
use crate::geometry::{dot, norm};
use crate::near_wall::{Bounds, Follows};
use crate::solve::{Frame, NodeRole};
use crate::threads::Workers;
use crate::topology::Csr;

/// Prescribed nodes this fraction of the mesh's size from their targets
/// are there: what the fit of an exactly rigid motion leaves.
pub const ROUND_OFF: f64 = 1e-12;

/// The angle's weight falls off over `ρ =` this many times the body's
/// radius about the centre it turns about: the best minimum quality of 0.5,
/// 1, 2, 3 and 5 on two airfoils of the test set of docs/robustness.md
/// (CHANGELOG.md, 2026-11-23).
const ANGLE_SCALE: f64 = 2.0;

/// A body: the moving nodes its rigid motion is fitted to (indices into the
/// step's targets) and every node held at `w = 1` (mesh indices).
struct Body {
    fitted: Vec<usize>,
    /// Whether its angle is scaled by how rigidly it moves
    /// ([`super::rigid_fit::Rigid::rigidity`]): a body moved by given positions.
    given: bool,
    held: Vec<usize>,
    /// Half the body's size (its wall nodes' bounding-box diagonal).
    radius: f64,
    /// The translation's last weights of each [`Weighting`], the next
    /// increment's initial guesses: sliding nodes held at 0, and sliding
    /// nodes free.
    held_slides: [Vec<f64>; 2],
    free_slides: [Vec<f64>; 2],
    /// The angle's weight's nearest held node and nearest other
    /// prescribed node of every node.
    near_held: Nearest,
    near_others: Nearest,
    /// The other prescribed nodes (fixed walls, the far field, other bodies).
    others: Vec<usize>,
}

/// The bodies of a run and the problem their weights solve, on a whole
/// mesh or on one process's part of it (its local nodes, owned and ghosts,
/// with every cell around the owned ones).
pub struct Blend {
    dim: usize,
    /// The diagonal of the input mesh's bounding box.
    extent: f64,
    laplace: Laplace,
    bodies: Vec<Body>,
    /// The unknowns of the translation's weight with sliding nodes held
    /// at 0, and with them free.
    unknown: Vec<bool>,
    unknown_slides: Vec<bool>,
    /// The projection on the directions every sliding node may move in
    /// (the planes' tangents when they are parallel, their common line when
    /// two meet, zero when no node slides or no direction is common):
    /// sliding nodes move with the translation's part in it and stay for
    /// the rest.
    slide_along: [[f64; 3]; 3],
}

/// The dimension whose meshes take the directional weight: on the
/// tetrahedra of the sphere moved toward the cube's wall (docs/robustness.md,
/// "Squeezed gaps") it inverted cells the isotropic weight keeps, the
/// radius ratio seeing the compression along the motion that a
/// quadrilateral's scaled Jacobian does not.
const DIRECTIONAL_DIMENSION: usize = 2;

/// How the translation's weight couples the edges (`harmonic.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Weighting {
    /// `k = 1/L`.
    Isotropic,
    /// `k = (cos²α + A sin²α)/L`, `α` the edge's angle to the translation.
    Directional,
}

/// A blended configuration.
pub struct Blended {
    /// The coordinates.
    pub coords: Vec<f64>,
    /// Whether a body translated with the directional weight (the
    /// [`Weighting`]s give different configurations only then).
    pub translated: bool,
}

impl Blend {
    /// The blend for bodies given as `(targets fitted, nodes held)` of
    /// the local nodes at `coords` (`dim` numbers each), numbered `ids`
    /// (the same number for a node on every process), held nodes owned
    /// or not, shared by the processes `on` (collective): `roles` are the
    /// deformer's (rigid-layer nodes prescribed), `edge_graph` the local
    /// cells' ([`crate::topology::edge_graph`]); `given` says which bodies
    /// are moved by given positions.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        dim: usize,
        coords: &[f64],
        ids: &[u64],
        edge_graph: Arc<Csr>,
        roles: &[NodeRole],
        normals: &[[f64; 3]],
        bodies: Vec<(Vec<usize>, Vec<usize>)>,
        given: &[bool],
        on: &dyn Collective,
    ) -> Blend {
        let n = roles.len();
        let laplace = Laplace::new(dim, edge_graph);
        let slide_along = common_slide_directions(roles, normals, on);
        let size = |nodes: &[usize]| Bounds::of(dim, coords, nodes).reduced(on).diagonal();
        let extent = size(&(0..n).collect::<Vec<_>>());
        let bodies = bodies
            .into_iter()
            .zip(given)
            .map(|((fitted, mut held), &given)| {
                let mut is_held = vec![false; n];
                for &i in &held {
                    is_held[i] = true;
                }
                // A ghost is held where its owner holds it (a ghost on a
                // moving wall may lack the facet that makes it one here).
                let mut owners: Vec<f64> =
                    is_held.iter().map(|&h| f64::from(u8::from(h))).collect();
                on.refresh(&mut owners, 1);
                for i in 0..n {
                    if owners[i] == 1.0 && !is_held[i] {
                        is_held[i] = true;
                        held.push(i);
                    }
                }
                let others: Vec<usize> = (0..n)
                    .filter(|&i| roles[i] == NodeRole::Fixed && !is_held[i])
                    .collect();
                let wall: Vec<usize> = held[..fitted.len()].to_vec();
                let graph = laplace.graph();
                Body {
                    near_held: Nearest::new(on, graph, dim, coords, ids, &held),
                    near_others: Nearest::new(on, graph, dim, coords, ids, &others),
                    others,
                    radius: 0.5 * size(&wall),
                    fitted,
                    given,
                    held,
                    held_slides: [vec![0.0; n], vec![0.0; n]],
                    free_slides: [vec![0.0; n], vec![0.0; n]],
                }
            })
            .collect();
        Blend {
            unknown: roles.iter().map(|r| *r == NodeRole::Free).collect(),
            unknown_slides: roles.iter().map(|r| *r != NodeRole::Fixed).collect(),
            slide_along,
            laplace,
            dim,
            extent,
            bodies,
        }
    }

    /// `coords` moved by every body's blended rigid motion towards
    /// `targets` (the prescribed nodes' positions, moving nodes first), the
    /// translation's weight coupled as `weighting` says, over the processes
    /// `on` (collective), the nodes' work on `workers` (each node on its own,
    /// sums in fixed chunks: the same bits on any number of them).
    pub fn apply(
        &mut self,
        coords: &[f64],
        targets: &[(usize, Vec<f64>)],
        on: &dyn Collective,
        weighting: Weighting,
        workers: &Workers,
    ) -> Blended {
        let dim = self.dim;
        let mut moved = coords.to_vec();
        let mut translated = false;
        // The directional weight in 2D only (see `DIRECTIONAL_DIMENSION`).
        let directional = weighting == Weighting::Directional && dim == DIRECTIONAL_DIMENSION;
        let slot = usize::from(directional);
        for body in &mut self.bodies {
            let mut moving = [f64::from(u8::from(body.fitted.iter().any(|&k| {
                let (i, q) = &targets[k];
                q.as_slice() != &coords[dim * i..dim * (i + 1)]
            })))];
            on.max(&mut moving);
            if moving[0] == 0.0 {
                continue;
            }
            let fitted = fit(on, dim, coords, targets, &body.fitted);
            let rigidity = if body.given {
                fitted.rigidity(on, dim, coords, targets, &body.fitted, self.extent)
            } else {
                1.0
            };
            let rigid = fitted.turned_by(rigidity).about_axis(body.radius);
            // The translation's part across the sliding planes and along them.
            let t = rigid.translation;
            let along: [f64; 3] = std::array::from_fn(|r| dot(&self.slide_along[r], &t));
            let across: [f64; 3] = std::array::from_fn(|r| t[r] - along[r]);
            let moves = |v: &[f64; 3]| norm(v) > ROUND_OFF * self.extent;
            for (w, unknown, part) in [
                (&mut body.held_slides[slot], &self.unknown, &across),
                (&mut body.free_slides[slot], &self.unknown_slides, &along),
            ] {
                if !moves(part) {
                    continue;
                }
                translated |= directional;
                for (wi, &u) in w.iter_mut().zip(unknown.iter()) {
                    if !u {
                        *wi = 0.0;
                    }
                }
                for &i in &body.held {
                    w[i] = 1.0;
                }
                let l = norm(part);
                let direction = [part[0] / l, part[1] / l, part[2] / l];
                let fitted: Vec<usize> = body.fitted.iter().map(|&k| targets[k].0).collect();
                let shadow = directional.then(|| {
                    Shadow::of(
                        dim,
                        direction,
                        coords,
                        &fitted,
                        &body.others,
                        body.radius,
                        on,
                    )
                });
                self.laplace
                    .solve(on, coords, unknown, w, shadow.as_ref(), workers);
            }
            // The body's radius about the centre it turns about.
            let mut reach = [body
                .fitted
                .iter()
                .map(|&k| {
                    let i = targets[k].0;
                    (0..dim)
                        .map(|d| (coords[dim * i + d] - rigid.centre[d]).powi(2))
                        .sum::<f64>()
                        .sqrt()
                })
                .fold(0.0, f64::max)];
            on.max(&mut reach);
            let graph = self.laplace.graph();
            let to_held = body.near_held.distances(on, graph, coords, workers);
            let to_others = body.near_others.distances(on, graph, coords, workers);
            let rotation = workers.install(|| angle_weights(&to_held, &to_others, reach[0]));
            let held = if moves(&across) {
                Some(&body.held_slides[slot])
            } else {
                None
            };
            let free = if moves(&along) {
                Some(&body.free_slides[slot])
            } else {
                None
            };
            let weight = |w: Option<&Vec<f64>>, i: usize| w.map_or(0.0, |w| w[i]);
            workers.install(|| {
                moved
                    .par_chunks_mut(dim)
                    .enumerate()
                    .for_each(|(i, moved)| {
                        let (wa, wb, wr) = (weight(held, i), weight(free, i), rotation[i]);
                        if wa == 0.0 && wb == 0.0 && wr == 0.0 {
                            return;
                        }
                        let x = &coords[dim * i..dim * (i + 1)];
                        let mut p = x.to_vec();
                        crate::motion::rotate(&mut p, &rigid.centre, &rigid.axis, wr * rigid.angle);
                        for d in 0..dim {
                            moved[d] += p[d] - x[d] + wa * across[d] + wb * along[d];
                        }
                    });
            });
        }
        Blended {
            coords: moved,
            translated,
        }
    }
}

/// The bodies of the blended rigid motion (`count` of them, the run's
/// chains of motions), each as the indices (into `moving`, the order of the
/// step's targets) its rigid motion is fitted to and the mesh nodes it
/// holds at weight 1 — its moving nodes and the rigid-layer nodes that
/// follow them (`layer`, with their bodies).
pub fn bodies(
    count: usize,
    moving: &[(usize, usize)],
    layer: &[(usize, Follows)],
) -> Vec<(Vec<usize>, Vec<usize>)> {
    let mut bodies: Vec<(Vec<usize>, Vec<usize>)> = vec![Default::default(); count];
    for (k, &(node, b)) in moving.iter().enumerate() {
        bodies[b].0.push(k);
        bodies[b].1.push(node);
    }
    for &(node, body) in layer {
        if let Some((b, _)) = body {
            bodies[b].1.push(node);
        }
    }
    bodies
}

/// `I − Σ_b b bᵀ` over an orthonormal basis `b` of the normals of every
/// sliding node's plane or line (`directions`: [`NodeRole::Slide`] normals,
/// [`NodeRole::Line`] directions); zero when no node slides.
fn common_slide_directions(
    roles: &[NodeRole],
    directions: &[[f64; 3]],
    on: &dyn Collective,
) -> [[f64; 3]; 3] {
    // The roles any process's nodes have, in the order of their directions.
    let mut used = vec![0.0; 2 * directions.len()];
    for role in roles {
        match role {
            NodeRole::Slide(k) => used[2 * k] = 1.0,
            NodeRole::Line(k) => used[2 * k + 1] = 1.0,
            _ => {}
        }
    }
    on.max(&mut used);
    let seen: Vec<NodeRole> = (0..used.len())
        .filter(|&k| used[k] == 1.0)
        .map(|k| match k % 2 {
            0 => NodeRole::Slide(k / 2),
            _ => NodeRole::Line(k / 2),
        })
        .collect();
    let mut basis: Vec<[f64; 3]> = Vec::new();
    for &role in &seen {
        let Some(frame) = Frame::<3>::of_role(role, directions) else {
            continue;
        };
        for g in &frame.rows()[frame.free()..] {
            let mut v = *g;
            for b in &basis {
                let d = dot(b, g);
                for c in 0..3 {
                    v[c] -= d * b[c];
                }
            }
            let l = norm(&v);
            if l > 1e-9 {
                basis.push([v[0] / l, v[1] / l, v[2] / l]);
            }
        }
    }
    if seen.is_empty() {
        return [[0.0; 3]; 3];
    }
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            f64::from(u8::from(r == c)) - basis.iter().map(|b| b[r] * b[c]).sum::<f64>()
        })
    })
}

/// Removes from the move `moved − reference` of every sliding node its
/// components along the normals of its plane or line.
pub fn keep_in_planes(
    dim: usize,
    roles: &[NodeRole],
    normals: &[[f64; 3]],
    reference: &[f64],
    moved: &mut [f64],
) {
    for (i, role) in roles.iter().enumerate() {
        let span = dim * i..dim * (i + 1);
        role.keep_on(normals, &mut moved[span.clone()], &reference[span]);
    }
}

/// The angle's weight `v` of every node (see the module documentation),
/// from its distances to the body's held nodes and to the other prescribed
/// nodes, the body's radius about its centre `rho`; node by node on the
/// current pool.
fn angle_weights(to_body: &[f64], to_others: &[f64], rho: f64) -> Vec<f64> {
    let rho = ANGLE_SCALE * rho.max(f64::MIN_POSITIVE);
    to_body
        .par_iter()
        .zip(to_others)
        .map(|(&d, &e): (&f64, &f64)| {
            if e == 0.0 || d.is_infinite() {
                0.0
            } else {
                (1.0 - (d / rho).ln_1p() / ((d + e) / rho).ln_1p()).clamp(0.0, 1.0)
            }
        })
        .collect()
}
