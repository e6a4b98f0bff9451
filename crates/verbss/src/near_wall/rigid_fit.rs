//! A body's best rigid motion over an increment (`blend.rs`): the fit to
//! its wall nodes' moves by least squares (in 3D Horn's quaternion
//! method), how rigidly the nodes move under it, and the same motion about
//! the point nearest its axis.

use super::blend::ROUND_OFF;
use crate::collective::{exact_sums, Collective};
use crate::geometry::{cross, dot, norm};

/// A body moved by given positions whose fitted rigid motion misses a wall
/// node by this fraction of the largest wall move or more is not turned by
/// the blend (its angle is
/// scaled by `1 − miss / (RIGID_MISS · move)`, clamped to `[0, 1]`): a
/// rotation fitted to a body that deforms (the aft part of an airfoil
/// drooped, which the fit misses by half its move) would carry the nodes
/// far from it along an arc that no wall node takes. A bending and an
/// undulation are turned as fitted: scaled, and unstiffened, the bending
/// wing of docs/robustness.md inverted at step 14 (at step 25 unstiffened
/// alone), not 38.
const RIGID_MISS: f64 = 0.1;

/// One body's fitted rigid motion: `x ↦ c + t + R(θ)(x − c)`.
pub(super) struct Rigid {
    pub(super) centre: [f64; 3],
    pub(super) translation: [f64; 3],
    pub(super) axis: [f64; 3],
    pub(super) angle: f64,
}

/// The rigid motion that best maps the nodes `fitted` (indices into
/// `targets`) from `coords` to their targets, the sums over the nodes
/// every process owns (collective).
pub(super) fn fit(
    on: &dyn Collective,
    dim: usize,
    coords: &[f64],
    targets: &[(usize, Vec<f64>)],
    fitted: &[usize],
) -> Rigid {
    let owned: Vec<&(usize, Vec<f64>)> = fitted
        .iter()
        .map(|&k| &targets[k])
        .filter(|(i, _)| on.owns(*i))
        .collect();
    let p = |k: usize, d: usize| {
        if d < dim {
            coords[dim * owned[k].0 + d]
        } else {
            0.0
        }
    };
    let q = |k: usize, d: usize| if d < dim { owned[k].1[d] } else { 0.0 };
    // The count, Σ p and Σ q, then the cross-covariance
    // S_ab = Σ (p − c)_a (q − c')_b: exact sums, the same on any cut.
    let sums = exact_sums(on, owned.len(), |k| {
        [1.0, p(k, 0), p(k, 1), p(k, 2), q(k, 0), q(k, 1), q(k, 2)]
    });
    let c: [f64; 3] = std::array::from_fn(|d| sums[1 + d] / sums[0]);
    let c_moved: [f64; 3] = std::array::from_fn(|d| sums[4 + d] / sums[0]);
    let flat: [f64; 9] = exact_sums(on, owned.len(), |k| {
        std::array::from_fn(|ab| (p(k, ab / 3) - c[ab / 3]) * (q(k, ab % 3) - c_moved[ab % 3]))
    });
    let s: [[f64; 3]; 3] = std::array::from_fn(|a| std::array::from_fn(|b| flat[3 * a + b]));
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
        centre: c,
        translation,
        axis,
        angle,
    }
}

impl Rigid {
    /// How rigidly the nodes `fitted` (indices into `targets`) move from
    /// `coords` under this motion, over the processes `on` (collective): 1
    /// where it puts each on its target to within [`ROUND_OFF`] of `extent`,
    /// otherwise `1 − e / (RIGID_MISS · m)` clamped to `[0, 1]`, with `e` the
    /// largest distance between a node's image and its target and `m` the
    /// largest move of a node.
    pub(super) fn rigidity(
        &self,
        on: &dyn Collective,
        dim: usize,
        coords: &[f64],
        targets: &[(usize, Vec<f64>)],
        fitted: &[usize],
        extent: f64,
    ) -> f64 {
        // [largest miss, largest move]
        let mut largest = [0.0f64; 2];
        for (i, q) in fitted.iter().map(|&k| &targets[k]) {
            if !on.owns(*i) {
                continue;
            }
            let x = &coords[dim * i..dim * (i + 1)];
            let mut image = x.to_vec();
            crate::motion::rotate(&mut image, &self.centre, &self.axis, self.angle);
            let miss = (0..dim).map(|d| (image[d] + self.translation[d] - q[d]).powi(2));
            let moved = (0..dim).map(|d| (q[d] - x[d]).powi(2));
            largest[0] = largest[0].max(miss.sum::<f64>().sqrt());
            largest[1] = largest[1].max(moved.sum::<f64>().sqrt());
        }
        on.max(&mut largest);
        let [miss, moved] = largest;
        if miss <= ROUND_OFF * extent {
            1.0
        } else {
            (1.0 - miss / (RIGID_MISS * moved)).clamp(0.0, 1.0)
        }
    }

    /// The motion with its angle scaled by `share`, about the same centre
    /// (the fitted nodes' centroid) with the same translation (the
    /// centroid's move): `x ↦ c + t + R(share · θ)(x − c)`.
    pub(super) fn turned_by(mut self, share: f64) -> Rigid {
        self.angle *= share;
        self
    }

    /// The same motion about the point nearest its axis within `radius`
    /// of the centroid: the translation left is the least there, so a hinged
    /// flap turns about its hinge. With `y ⊥ a` the way from the centroid
    /// to the axis, `(I − R) y = t⊥` gives
    /// `y = ((1 − cos θ) t⊥ + sin θ a × t⊥) / (2 − 2 cos θ)`; moving the
    /// centre by `s y` leaves `t − s t⊥`.
    pub(super) fn about_axis(mut self, radius: f64) -> Rigid {
        let (sin, cos) = self.angle.sin_cos();
        if 1.0 - cos <= f64::EPSILON {
            return self;
        }
        let a = self.axis;
        let t = self.translation;
        let along = dot(&t, &a);
        let perp = [
            t[0] - along * a[0],
            t[1] - along * a[1],
            t[2] - along * a[2],
        ];
        let turn = cross(&a, &perp);
        let y: [f64; 3] =
            std::array::from_fn(|d| ((1.0 - cos) * perp[d] + sin * turn[d]) / (2.0 - 2.0 * cos));
        let length = norm(&y);
        let s = if length > radius {
            radius / length
        } else {
            1.0
        };
        for d in 0..3 {
            self.centre[d] += s * y[d];
            self.translation[d] -= s * perp[d];
        }
        self
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
                for row in m.iter_mut() {
                    let (mka, mkb) = (row[a], row[b]);
                    row[a] = c * mka - s * mkb;
                    row[b] = s * mka + c * mkb;
                }
                let (row_a, row_b) = (m[a], m[b]);
                for (k, (mak, mbk)) in row_a.iter().zip(row_b).enumerate() {
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
    use crate::collective::Whole;

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
        let rigid = fit(&Whole, 3, &coords, &targets, &[0, 1, 2, 3]);
        assert!((rigid.angle - 0.7).abs() < 1e-12, "{}", rigid.angle);
        assert!(dot(&rigid.axis, &axis) > 1.0 - 1e-12);
        // The fitted motion maps every node onto its target.
        for (i, q) in &targets {
            let mut p = coords[3 * i..3 * i + 3].to_vec();
            crate::motion::rotate(&mut p, &rigid.centre, &rigid.axis, rigid.angle);
            for d in 0..3 {
                assert!((p[d] + rigid.translation[d] - q[d]).abs() < 1e-12);
            }
        }
        assert!(norm(&cross(&rigid.axis, &axis)) < 1e-6);
    }

    #[test]
    fn a_flap_turns_about_its_hinge() {
        // A plate from (0, 0) to (1, 0) turned 10° about its end (1, 0).
        let coords = [0.0, 0.0, 0.5, 0.0, 1.0, 0.0];
        let targets: Vec<(usize, Vec<f64>)> = (0..3)
            .map(|i| {
                let mut p = coords[2 * i..2 * i + 2].to_vec();
                crate::motion::rotate(&mut p, &[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0], 0.2);
                (i, p)
            })
            .collect();
        let rigid = fit(&Whole, 2, &coords, &targets, &[0, 1, 2]).about_axis(0.6);
        assert!((rigid.centre[0] - 1.0).abs() < 1e-12 && rigid.centre[1].abs() < 1e-12);
        assert!(norm(&rigid.translation) < 1e-12);
        // Within a smaller radius the centre stops on the way there.
        let near = fit(&Whole, 2, &coords, &targets, &[0, 1, 2]).about_axis(0.25);
        assert!((near.centre[0] - 0.75).abs() < 1e-12);
        for (i, q) in &targets {
            let mut p = coords[2 * i..2 * i + 2].to_vec();
            crate::motion::rotate(&mut p, &near.centre, &near.axis, near.angle);
            assert!((p[0] + near.translation[0] - q[0]).abs() < 1e-12);
            assert!((p[1] + near.translation[1] - q[1]).abs() < 1e-12);
        }
    }

    #[test]
    fn a_body_is_turned_as_far_as_it_moves_rigidly() {
        // A plate from (0, 0) to (1, 0) turned 0.2 about its end moves rigidly.
        let coords = [0.0, 0.0, 0.5, 0.0, 1.0, 0.0];
        let turned: Vec<(usize, Vec<f64>)> = (0..3)
            .map(|i| {
                let mut p = coords[2 * i..2 * i + 2].to_vec();
                crate::motion::rotate(&mut p, &[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0], 0.2);
                (i, p)
            })
            .collect();
        let all = [0, 1, 2];
        let rigid = fit(&Whole, 2, &coords, &turned, &all);
        assert_eq!(rigid.rigidity(&Whole, 2, &coords, &turned, &all, 1.0), 1.0);
        // Its end alone moved down 0.1: the fit (down 1/30, turned by
        // −0.1 about the centroid) misses the middle node by 1/30, a third
        // of the largest move, so the body is not turned.
        let bent = vec![
            (0, vec![0.0, 0.0]),
            (1, vec![0.5, 0.0]),
            (2, vec![1.0, -0.1]),
        ];
        let fitted = fit(&Whole, 2, &coords, &bent, &all);
        assert!((fitted.angle + 0.1).abs() < 1e-3, "{}", fitted.angle);
        let share = fitted.rigidity(&Whole, 2, &coords, &bent, &all, 1.0);
        assert_eq!(share, 0.0);
        let unturned = fitted.turned_by(share);
        assert_eq!(unturned.angle, 0.0);
        assert!((unturned.translation[1] + 0.1 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn the_fit_of_a_single_node_is_its_translation() {
        let targets = vec![(0, vec![3.0, 4.0])];
        let rigid = fit(&Whole, 2, &[1.0, 1.0], &targets, &[0]);
        assert_eq!(rigid.angle, 0.0);
        assert_eq!(&rigid.translation[..2], &[2.0, 3.0]);
    }
}
