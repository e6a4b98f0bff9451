//! The blended rigid motion (docs/method.md, "Blended rigid motion").
//!
//! Each body's best rigid motion over an increment — a rotation `R` by `θ`
//! about the centroid `c` of its wall nodes and the centroid's translation
//! `t`, fitted to the wall nodes' moves by least squares (in 3D Horn's
//! quaternion method) — is carried into the mesh with two weights in
//! `[0, 1]`, one for the translation and one for the angle:
//!
//! `x_i ← x_i + w_i t + R(v_i θ)(x_i − c) − (x_i − c)`,
//!
//! so a cell moves by a rigid motion plus a smooth stretch and twist and
//! keeps its shape however thin it is. Both weights are 1 on the body and
//! its rigid layer and 0 on every other prescribed node (fixed walls, the
//! far field, other bodies):
//!
//! * `w` solves the Laplacian with `k = 1/L` on the mesh the increment
//!   starts from (`harmonic.rs`), sliding nodes free (their move is then
//!   projected onto their plane by the springs' remainder); recomputed
//!   every increment, it follows a gap that closes: compressed edges couple
//!   more strongly and the compression spreads over the gap;
//! * `v = 1 − ln(1 + d/ρ) / ln(1 + (d + e)/ρ)`, with `d` the distance to the
//!   body's held nodes, `e` the distance to the other prescribed nodes and
//!   `ρ` half the body's size: in a ring around the body at distance `r`
//!   the angle changes by `θ/((ρ + d) ln(1 + (d + e)/ρ))` per unit length,
//!   so every ring of cells is sheared by about `θ / ln(1 + (d + e)/ρ)`,
//!   the same everywhere — a harmonic weight would shear the cells next to a
//!   sharp trailing edge without bound.
//!
//! The springs then solve only for what the blend leaves: nothing for a
//! rigid body, its deformation otherwise.

use super::harmonic::Laplace;
use crate::geometry::norm;
use crate::mesh::Mesh;
use crate::robust::nearest_seed;
use crate::solve::NodeRole;
use crate::topology::Csr;

/// Prescribed nodes this fraction of the mesh's size from their targets
/// are there: what the fit of an exactly rigid motion leaves.
const ROUND_OFF: f64 = 1e-12;

/// A body: the moving nodes its rigid motion is fitted to (indices into the
/// step's targets) and every node held at `w = 1` (mesh indices).
struct Body {
    fitted: Vec<usize>,
    held: Vec<usize>,
    /// The prescribed nodes not held: where both weights are 0.
    others: Vec<usize>,
    /// Half the body's size (its wall nodes' bounding-box diagonal).
    radius: f64,
    /// The translation's last weights, the next increment's initial guess.
    translation: Vec<f64>,
}

/// The bodies of a run and the problem their weights solve.
pub(super) struct Blend {
    mesh: Mesh,
    /// The diagonal of the input mesh's bounding box.
    extent: f64,
    laplace: Laplace,
    graph: Csr,
    bodies: Vec<Body>,
}

/// One body's fitted rigid motion: `x ↦ c + t + R(θ)(x − c)`.
struct Rigid {
    centroid: [f64; 3],
    translation: [f64; 3],
    axis: [f64; 3],
    angle: f64,
}

impl Blend {
    /// The blend for bodies given as `(targets fitted, nodes held)`;
    /// `roles` are the deformer's (rigid-layer nodes prescribed).
    pub(super) fn new(
        mesh: &Mesh,
        roles: &[NodeRole],
        bodies: Vec<(Vec<usize>, Vec<usize>)>,
    ) -> Blend {
        let unknown = roles.iter().map(|r| *r != NodeRole::Fixed).collect();
        let n = mesh.node_count();
        let laplace = Laplace::new(mesh, unknown);
        let extent = diagonal(mesh.dim, &mesh.coords, &(0..n).collect::<Vec<_>>());
        let bodies = bodies
            .into_iter()
            .map(|(fitted, held)| {
                let mut is_held = vec![false; n];
                for &i in &held {
                    is_held[i] = true;
                }
                let others = (0..n)
                    .filter(|&i| roles[i] == NodeRole::Fixed && !is_held[i])
                    .collect();
                let wall: Vec<usize> = held[..fitted.len()].to_vec();
                Body {
                    radius: 0.5 * diagonal(mesh.dim, &mesh.coords, &wall),
                    fitted,
                    held,
                    others,
                    translation: vec![0.0; n],
                }
            })
            .collect();
        Blend {
            graph: laplace.graph(n),
            laplace,
            mesh: mesh.clone(),
            extent,
            bodies,
        }
    }

    /// Whether a blended start that leaves the prescribed nodes at most
    /// `left` from their targets leaves nothing to solve: `left` is
    /// round-off of the coordinates ([`ROUND_OFF`] of the mesh's size).
    pub(super) fn leaves_nothing(&self, left: f64) -> bool {
        left <= ROUND_OFF * self.extent
    }

    /// `coords` moved by every body's blended rigid motion towards
    /// `targets` (the prescribed nodes' positions, moving nodes first).
    pub(super) fn apply(&mut self, coords: &[f64], targets: &[(usize, Vec<f64>)]) -> Vec<f64> {
        let dim = self.mesh.dim;
        let mut moved = coords.to_vec();
        for body in &mut self.bodies {
            let still = body.fitted.iter().all(|&k| {
                let (i, q) = &targets[k];
                q.as_slice() == &coords[dim * i..dim * (i + 1)]
            });
            if still {
                continue;
            }
            let rigid = fit(dim, coords, targets, &body.fitted);
            let w = &mut body.translation;
            for (i, wi) in w.iter_mut().enumerate() {
                if !self.laplace.is_unknown(i) {
                    *wi = 0.0;
                }
            }
            for &i in &body.held {
                w[i] = 1.0;
            }
            self.laplace.solve(coords, w);
            let rotation = angle_weights(&self.graph, dim, coords, body);
            for i in 0..coords.len() / dim {
                let (wt, wr) = (body.translation[i], rotation[i]);
                if wt == 0.0 && wr == 0.0 {
                    continue;
                }
                let x = &coords[dim * i..dim * (i + 1)];
                let mut p = x.to_vec();
                crate::motion::rotate(&mut p, &rigid.centroid, &rigid.axis, wr * rigid.angle);
                for d in 0..dim {
                    moved[dim * i + d] += p[d] + wt * rigid.translation[d] - x[d];
                }
            }
        }
        moved
    }
}

/// The angle's weight `v` of every node (see the module documentation).
fn angle_weights(graph: &Csr, dim: usize, coords: &[f64], body: &Body) -> Vec<f64> {
    let (to_body, _) = nearest_seed(graph, dim, coords, &body.held);
    let (to_others, _) = nearest_seed(graph, dim, coords, &body.others);
    let rho = body.radius.max(f64::MIN_POSITIVE);
    to_body
        .iter()
        .zip(&to_others)
        .map(|(&d, &e)| {
            if e == 0.0 || d.is_infinite() {
                0.0
            } else {
                (1.0 - (d / rho).ln_1p() / ((d + e) / rho).ln_1p()).clamp(0.0, 1.0)
            }
        })
        .collect()
}

/// The diagonal of the bounding box of `nodes`.
fn diagonal(dim: usize, coords: &[f64], nodes: &[usize]) -> f64 {
    (0..dim)
        .map(|d| {
            let axis = nodes.iter().map(|&i| coords[dim * i + d]);
            let lo = axis.clone().fold(f64::INFINITY, f64::min);
            let hi = axis.fold(f64::NEG_INFINITY, f64::max);
            (hi - lo).powi(2)
        })
        .sum::<f64>()
        .sqrt()
}

/// The rigid motion that best maps the nodes `fitted` (indices into
/// `targets`) from `coords` to their targets.
fn fit(dim: usize, coords: &[f64], targets: &[(usize, Vec<f64>)], fitted: &[usize]) -> Rigid {
    let count = fitted.len() as f64;
    let (mut c, mut c_moved) = ([0.0; 3], [0.0; 3]);
    for &k in fitted {
        let (i, q) = &targets[k];
        for d in 0..dim {
            c[d] += coords[dim * i + d] / count;
            c_moved[d] += q[d] / count;
        }
    }
    // Cross-covariance S_ab = Σ (p − c)_a (q − c')_b.
    let mut s = [[0.0; 3]; 3];
    for &k in fitted {
        let (i, q) = &targets[k];
        for a in 0..dim {
            for b in 0..dim {
                s[a][b] += (coords[dim * i + a] - c[a]) * (q[b] - c_moved[b]);
            }
        }
    }
    let translation = [c_moved[0] - c[0], c_moved[1] - c[1], c_moved[2] - c[2]];
    let (axis, angle) = if dim == 2 {
        (
            [0.0, 0.0, 1.0],
            (s[0][1] - s[1][0]).atan2(s[0][0] + s[1][1]),
        )
    } else {
        rotation_3d(&s)
    };
    Rigid {
        centroid: c,
        translation,
        axis,
        angle,
    }
}

/// Horn's method: the unit quaternion maximizing `Σ q'·R p` is the
/// eigenvector of the largest eigenvalue of a symmetric 4 × 4 matrix built
/// from the cross-covariance `s`. Gives the rotation's axis and angle in `[0, π]`.
fn rotation_3d(s: &[[f64; 3]; 3]) -> ([f64; 3], f64) {
    let [[xx, xy, xz], [yx, yy, yz], [zx, zy, zz]] = *s;
    let m = [
        [xx + yy + zz, yz - zy, zx - xz, xy - yx],
        [yz - zy, xx - yy - zz, xy + yx, zx + xz],
        [zx - xz, xy + yx, -xx + yy - zz, yz + zy],
        [xy - yx, zx + xz, yz + zy, -xx - yy + zz],
    ];
    let q = largest_eigenvector(m);
    let (w, v) = if q[0] < 0.0 {
        (-q[0], [-q[1], -q[2], -q[3]])
    } else {
        (q[0], [q[1], q[2], q[3]])
    };
    let sin_half = norm(&v);
    if sin_half < 1e-15 {
        return ([0.0, 0.0, 1.0], 0.0);
    }
    let axis = [v[0] / sin_half, v[1] / sin_half, v[2] / sin_half];
    (axis, 2.0 * sin_half.atan2(w))
}

/// The unit eigenvector of the largest eigenvalue of a symmetric 4 × 4
/// matrix (cyclic Jacobi rotations; identity's first column when `m` is zero).
fn largest_eigenvector(mut m: [[f64; 4]; 4]) -> [f64; 4] {
    let mut v = [[0.0; 4]; 4];
    for (k, row) in v.iter_mut().enumerate() {
        row[k] = 1.0;
    }
    for _ in 0..50 {
        let off: f64 = (0..4)
            .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
            .map(|(a, b)| m[a][b] * m[a][b])
            .sum();
        let diag: f64 = (0..4).map(|a| m[a][a] * m[a][a]).sum();
        if off <= 1e-30 * diag.max(f64::MIN_POSITIVE) {
            break;
        }
        for a in 0..4 {
            for b in a + 1..4 {
                if m[a][b] == 0.0 {
                    continue;
                }
                let theta = (m[b][b] - m[a][a]) / (2.0 * m[a][b]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..4 {
                    let (mka, mkb) = (m[k][a], m[k][b]);
                    m[k][a] = c * mka - s * mkb;
                    m[k][b] = s * mka + c * mkb;
                }
                for k in 0..4 {
                    let (mak, mbk) = (m[a][k], m[b][k]);
                    m[a][k] = c * mak - s * mbk;
                    m[b][k] = s * mak + c * mbk;
                }
                for row in v.iter_mut() {
                    let (va, vb) = (row[a], row[b]);
                    row[a] = c * va - s * vb;
                    row[b] = s * va + c * vb;
                }
            }
        }
    }
    let best = (0..4)
        .max_by(|&a, &b| m[a][a].total_cmp(&m[b][b]))
        .unwrap_or(0);
    [v[0][best], v[1][best], v[2][best], v[3][best]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{cross, dot};

    fn rotated(p: [f64; 3], axis: [f64; 3], angle: f64) -> Vec<f64> {
        let mut x = p.to_vec();
        crate::motion::rotate(&mut x, &[0.0; 3], &axis, angle);
        x
    }

    #[test]
    fn the_fit_recovers_a_rigid_motion_in_3d() {
        let axis = {
            let a = [1.0, 2.0, -0.5];
            let l = norm(&a);
            [a[0] / l, a[1] / l, a[2] / l]
        };
        let points = [
            [0.0, 0.0, 0.0],
            [1.0, 0.2, 0.0],
            [0.3, 1.0, 0.1],
            [0.1, -0.4, 0.9],
        ];
        let shift = [0.5, -0.25, 2.0];
        let coords: Vec<f64> = points.iter().flatten().copied().collect();
        let targets: Vec<(usize, Vec<f64>)> = points
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut q = rotated(*p, axis, 0.7);
                for d in 0..3 {
                    q[d] += shift[d];
                }
                (i, q)
            })
            .collect();
        let rigid = fit(3, &coords, &targets, &[0, 1, 2, 3]);
        assert!((rigid.angle - 0.7).abs() < 1e-12, "{}", rigid.angle);
        assert!(dot(&rigid.axis, &axis) > 1.0 - 1e-12);
        // The fitted motion maps every node onto its target.
        for (i, q) in &targets {
            let mut p = coords[3 * i..3 * i + 3].to_vec();
            crate::motion::rotate(&mut p, &rigid.centroid, &rigid.axis, rigid.angle);
            for d in 0..3 {
                assert!((p[d] + rigid.translation[d] - q[d]).abs() < 1e-12);
            }
        }
        assert!(norm(&cross(&rigid.axis, &axis)) < 1e-6);
    }

    #[test]
    fn the_fit_of_a_single_node_is_its_translation() {
        let targets = vec![(0, vec![3.0, 4.0])];
        let rigid = fit(2, &[1.0, 1.0], &targets, &[0]);
        assert_eq!(rigid.angle, 0.0);
        assert_eq!(&rigid.translation[..2], &[2.0, 3.0]);
    }
}
