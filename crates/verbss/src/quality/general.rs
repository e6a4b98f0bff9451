//! Orientation and quality of a polygon or polyhedron, from its
//! decomposition into simplices on its centres (docs/method.md, "Polygons
//! and polyhedra").
//!
//! With `c` the mean of the cell's nodes and, in 3D, `x_F` the mean of the
//! nodes of face `F`: a polygon is the triangles `(v_k, v_{k+1}, c)`, a
//! polyhedron the tetrahedra `(a, b, x_F, c)` for every side `a → b` of
//! every face (outward). Each simplex's Jacobian `J` (twice its area, six
//! times its volume) is positive for a positively oriented cell:
//! `J = (b−a)×(c−a)` in 2D, `J = ((b−a)×(x_F−a))·(a−c)` in 3D.
//!
//! - **orientation**: the sign of `Σ J`, 0 when `|Σ J| ≤ ε Σ Π` (`Π` the
//!   product of the simplex's edges from `a`; ε = [`super::ZERO`]);
//! - **quality** relative to `s`: over the simplices, the height of the
//!   centre over the simplex's outer side (the segment `ab`, the triangle
//!   `(a, b, x_F)`), `h = s·J / |b−a|` in 2D and `h = s·J / |(b−a)×(x_F−a)|`
//!   in 3D, over the largest distance `R` from the centre to that side's
//!   points; the quality is `min (h/R) / (h/R)₀` clamped to `[0, 1]`, with
//!   `(h/R)₀` the value of the unit square (`1/√2`) or cube (`1/√3`), and 0
//!   when some simplex has `s·J / Π ≤ ε`. A square or cube read as a
//!   polygon or polyhedron measures 1, and so does one whose faces are cut
//!   into several (a split face, a refinement transition's hanging nodes):
//!   the pieces lie in the same planes at the same distances.

use super::measures;
use super::ZERO;
use crate::geometry::{cross, dot, lifted, mean_of, norm, sub};
use crate::mesh::Local;

/// `h/R` of the unit square.
const SQUARE: f64 = std::f64::consts::FRAC_1_SQRT_2;
/// `h/R` of the unit cube.
const CUBE: f64 = 0.577_350_269_189_625_8;

/// Calls `f(J, Π, side, R)` for every simplex of the decomposition: its
/// Jacobian, the product of its edges from `a`, the length (area vector
/// length) of its outer side and the largest distance from the centre to
/// that side's points.
fn simplices<const D: usize>(
    nodes: &[usize],
    local: Local,
    coords: &[f64],
    mut f: impl FnMut(f64, f64, f64, f64),
) {
    let at = |l: usize| lifted::<D>(coords, nodes[l]);
    let c = mean_of::<D>(coords, nodes.iter().copied());
    if D == 2 {
        let n = nodes.len();
        for k in 0..n {
            let (a, b) = (at(k), at((k + 1) % n));
            let (ab, ac) = (sub(&b, &a), sub(&c, &a));
            let j = ab[0] * ac[1] - ab[1] * ac[0];
            let far = norm(&ac).max(norm(&sub(&b, &c)));
            f(j, norm(&ab) * norm(&ac), norm(&ab), far);
        }
        return;
    }
    local.facets(|face| {
        let xf = mean_of::<D>(coords, face.iter().map(|&l| nodes[l]));
        for k in 0..face.len() {
            let (a, b) = (at(face[k]), at(face[(k + 1) % face.len()]));
            let (ab, af, ca) = (sub(&b, &a), sub(&xf, &a), sub(&a, &c));
            let n = cross(&ab, &af);
            let j = dot(&n, &ca);
            let far = norm(&ca).max(norm(&sub(&b, &c))).max(norm(&sub(&xf, &c)));
            f(j, norm(&ab) * norm(&af) * norm(&ca), norm(&n), far);
        }
    });
}

/// Orientation of a polygon or polyhedron (see the module docs).
pub(super) fn orientation<const D: usize>(nodes: &[usize], local: Local, coords: &[f64]) -> i8 {
    let (mut sum, mut scale) = (0.0, 0.0);
    simplices::<D>(nodes, local, coords, |j, lengths, _, _| {
        sum += j;
        scale += lengths;
    });
    if sum.abs() <= ZERO * scale {
        0
    } else if sum > 0.0 {
        1
    } else {
        -1
    }
}

/// Quality of a polygon or polyhedron relative to orientation `s`, and
/// whether a simplex of its decomposition is inverted (see the module
/// docs).
pub(super) fn quality<const D: usize>(
    nodes: &[usize],
    local: Local,
    coords: &[f64],
    s: f64,
) -> (f64, bool) {
    let reference = if D == 2 { SQUARE } else { CUBE };
    let mut q = f64::INFINITY;
    let mut inverted = false;
    simplices::<D>(nodes, local, coords, |j, lengths, side, far| {
        if measures::scaled(s * j, lengths) <= ZERO || j.is_nan() {
            inverted = true;
        } else {
            q = q.min(s * j / side / far / reference);
        }
    });
    if inverted {
        (0.0, true)
    } else {
        (q.clamp(0.0, 1.0), false)
    }
}
