//! The per-kind measures, on a cell's points gathered in node order.
//!
//! Every function here assumes the cell is not inverted relative to the sign
//! `s` it is given (the caller checks the corners first), so the Jacobians it
//! divides by are positive after multiplying by `s`.

use crate::geometry::{cross, det, dot, norm, sub};

/// `2/√3`: Verdict's normalisation of the wedge scaled Jacobian (a right
/// corner of the equilateral wedge has scaled Jacobian `√3/2`).
const WEDGE_SCALE: f64 = 1.154_700_538_379_251_5;

/// The corner Jacobian `J = det(p[c1]-p[c0], …, p[cD]-p[c0])` and the product
/// of the lengths of the corner's `D` edges.
#[inline]
pub(super) fn corner<const D: usize>(p: &[[f64; D]], c: &[usize; 4]) -> (f64, f64) {
    let e: [[f64; D]; D] = std::array::from_fn(|k| sub(&p[c[k + 1]], &p[c[0]]));
    (det::<D>(&e), e.iter().map(norm).product())
}

/// `j / lengths`, or 0 when an edge has zero length.
#[inline]
pub(super) fn scaled(j: f64, lengths: f64) -> f64 {
    if lengths > 0.0 {
        j / lengths
    } else {
        0.0
    }
}

/// A point with its missing coordinates set to zero.
#[inline]
fn lift<const D: usize>(a: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|k| if k < D { a[k] } else { 0.0 })
}

/// Triangle `ρ = 2r/R = 16A²/(P·abc) = 4J²/(P·abc)`, with `J = 2A` the corner
/// Jacobian, `P = a+b+c` the perimeter (`r = 2A/P`, `R = abc/4A`).
pub(super) fn triangle<const D: usize>(p: &[[f64; D]]) -> f64 {
    let (j, _) = corner(p, &[0, 1, 2, 0]);
    let a = norm(&sub(&p[1], &p[0]));
    let b = norm(&sub(&p[2], &p[1]));
    let c = norm(&sub(&p[0], &p[2]));
    4.0 * j * j / ((a + b + c) * a * b * c)
}

/// Tetrahedron `ρ = 3r/R = 3J²/(S·|n|)`, with edges `a, b, c` from node 0,
/// `J = a·(b×c) = 6V`, `S` the total face area (`r = 3V/S`) and
/// `n = |a|²(b×c) + |b|²(c×a) + |c|²(a×b)` (`R = |n|/(2J)`).
pub(super) fn tetra<const D: usize>(p: &[[f64; D]]) -> f64 {
    let x: [[f64; 3]; 4] = std::array::from_fn(|k| lift(&p[k]));
    let (a, b, c) = (sub(&x[1], &x[0]), sub(&x[2], &x[0]), sub(&x[3], &x[0]));
    let (bc, ca, ab) = (cross(&b, &c), cross(&c, &a), cross(&a, &b));
    let j = dot(&a, &bc);
    let n: [f64; 3] =
        std::array::from_fn(|k| dot(&a, &a) * bc[k] + dot(&b, &b) * ca[k] + dot(&c, &c) * ab[k]);
    let opposite = cross(&sub(&b, &a), &sub(&c, &a));
    let area = 0.5 * (norm(&bc) + norm(&ca) + norm(&ab) + norm(&opposite));
    3.0 * j * j / (area * norm(&n))
}

/// Scaled Jacobian of a hexahedron at its centre, from the principal axes
/// `a = (x1+x2+x5+x6) − (x0+x3+x4+x7)`, `b = (x2+x3+x6+x7) − (x0+x1+x4+x5)`,
/// `c = (x4+x5+x6+x7) − (x0+x1+x2+x3)`: `s·det(a,b,c)/(|a||b||c|)`.
pub(super) fn hexahedron_centre<const D: usize>(p: &[[f64; D]], s: f64) -> f64 {
    let x: [[f64; 3]; 8] = std::array::from_fn(|k| lift(&p[k]));
    let axis = |plus: [usize; 4], minus: [usize; 4]| -> [f64; 3] {
        std::array::from_fn(|k| {
            plus.iter().map(|&i| x[i][k]).sum::<f64>() - minus.iter().map(|&i| x[i][k]).sum::<f64>()
        })
    };
    let a = axis([1, 2, 5, 6], [0, 3, 4, 7]);
    let b = axis([2, 3, 6, 7], [0, 1, 4, 5]);
    let c = axis([4, 5, 6, 7], [0, 1, 2, 3]);
    scaled(s * dot(&a, &cross(&b, &c)), norm(&a) * norm(&b) * norm(&c))
}

/// Wedge: `2/√3 ·` the minimum corner scaled Jacobian `worst`.
pub(super) fn wedge(worst: f64) -> f64 {
    WEDGE_SCALE * worst
}

/// Pyramid, as Verdict: each base corner `c` spans a tetrahedron `T_c` (corner
/// node, its two base neighbours, apex) whose scaled Jacobian is
/// `√2·s·J_c / max(max over the 4 vertices v of T_c of Π |edges of T_c at v|, |J_c|)`;
/// with `m` the minimum over the four, `v = √2·m` and the quality is `v` when
/// `v ≤ 1` and `2 − v` above (a pyramid taller than the one with equilateral
/// faces is as bad as the equally flatter one).
pub(super) fn pyramid<const D: usize>(p: &[[f64; D]], corners: &[[usize; 4]], s: f64) -> f64 {
    let mut m = f64::INFINITY;
    for c in corners {
        let (j, _) = corner(p, c);
        let len = |u: usize, w: usize| norm(&sub(&p[c[u]], &p[c[w]]));
        let longest = (0..4)
            .map(|u| {
                (0..4)
                    .filter(|&w| w != u)
                    .map(|w| len(u, w))
                    .product::<f64>()
            })
            .fold(0.0, f64::max);
        m = m.min(std::f64::consts::SQRT_2 * scaled(s * j, longest.max(j.abs())));
    }
    let v = std::f64::consts::SQRT_2 * m;
    if v <= 1.0 {
        v
    } else {
        2.0 - v
    }
}
