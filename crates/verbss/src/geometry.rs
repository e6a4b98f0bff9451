//! Small fixed-size geometric kernels over `[f64; D]`.

/// `b - a`.
#[inline]
pub fn sub<const D: usize>(b: &[f64; D], a: &[f64; D]) -> [f64; D] {
    std::array::from_fn(|k| b[k] - a[k])
}

/// Dot product.
#[inline]
pub fn dot<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    (0..D).map(|k| a[k] * b[k]).sum()
}

/// Euclidean norm.
#[inline]
pub fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    dot(a, a).sqrt()
}

/// Cross product in 3D.
#[inline]
pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The point `p` of a flat coordinate array with dimension `D`.
#[inline(always)]
pub fn point<const D: usize>(coords: &[f64], i: usize) -> [f64; D] {
    std::array::from_fn(|k| coords[D * i + k])
}

/// Determinant of the `D` edge vectors `e[0..D]` (signed area ×2 in 2D,
/// signed volume ×6 in 3D).
#[inline]
pub fn det<const D: usize>(e: &[[f64; D]]) -> f64 {
    match D {
        2 => e[0][0] * e[1][1] - e[0][1] * e[1][0],
        3 => {
            e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1])
                - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0])
                + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])
        }
        _ => unreachable!("dimension {D}"),
    }
}

/// Corner Jacobian `det(x[c1]-x[c0], …, x[cD]-x[c0])` of corner `corner`
/// (local indices into `nodes`, as in [`crate::mesh::KindTable::corners`]).
#[inline]
pub fn corner_jacobian<const D: usize>(
    coords: &[f64],
    nodes: &[usize],
    corner: &[usize; 4],
) -> f64 {
    let x0 = point::<D>(coords, nodes[corner[0]]);
    let e: [[f64; D]; D] =
        std::array::from_fn(|k| sub(&point::<D>(coords, nodes[corner[k + 1]]), &x0));
    det::<D>(&e)
}

/// Number of stored entries of a packed symmetric `D×D` matrix: `D(D+1)/2`.
#[inline(always)]
pub const fn packed_len(d: usize) -> usize {
    d * (d + 1) / 2
}

/// Position of entry `(r, c)` in a packed symmetric matrix: the lower triangle
/// row by row, `[a00, a10, a11]` in 2D, `[a00, a10, a11, a20, a21, a22]` in 3D.
#[inline(always)]
pub const fn packed_index(r: usize, c: usize) -> usize {
    if r >= c {
        r * (r + 1) / 2 + c
    } else {
        c * (c + 1) / 2 + r
    }
}

/// `a += s · n nᵀ` for a packed symmetric `a`.
#[inline]
pub fn add_outer<const D: usize>(a: &mut [f64], s: f64, n: &[f64; D]) {
    for r in 0..D {
        for c in 0..=r {
            a[packed_index(r, c)] += s * n[r] * n[c];
        }
    }
}

/// `A x` for a packed symmetric `A`.
#[inline(always)]
pub fn packed_mul<const D: usize>(a: &[f64], x: &[f64; D]) -> [f64; D] {
    let a = &a[..packed_len(D)];
    std::array::from_fn(|r| (0..D).map(|c| a[packed_index(r, c)] * x[c]).sum())
}

/// LDLᵀ factorisation of a symmetric positive definite packed matrix
/// (the paper's appendix): `A = L D Lᵀ` with `L` unit lower triangular,
/// `d_j = a_jj − Σ_{k<j} l_jk² d_k`, `l_ij = (a_ij − Σ_{k<j} l_ik l_jk d_k) / d_j`.
///
/// The factor is written in the packed layout of [`packed_index`]: `l_ij`
/// below the diagonal, `1/d_j` on it. Returns `false` (and leaves `f`
/// partly written) when a pivot is not positive: `d_j ≤ 64 ε a_jj`, i.e. the
/// matrix is singular or indefinite to working precision.
pub fn ldlt_factor<const D: usize>(a: &[f64], f: &mut [f64]) -> bool {
    let mut d = [0.0; D];
    for j in 0..D {
        let ajj = a[packed_index(j, j)];
        let dj = ajj
            - (0..j)
                .map(|k| f[packed_index(j, k)].powi(2) * d[k])
                .sum::<f64>();
        if !(dj.is_finite() && dj > 64.0 * f64::EPSILON * ajj.abs()) {
            return false;
        }
        d[j] = dj;
        f[packed_index(j, j)] = 1.0 / dj;
        for i in j + 1..D {
            let s: f64 = (0..j)
                .map(|k| f[packed_index(i, k)] * f[packed_index(j, k)] * d[k])
                .sum();
            f[packed_index(i, j)] = (a[packed_index(i, j)] - s) / dj;
        }
    }
    true
}

/// Solves `A x = b` with the packed LDLᵀ factor of [`ldlt_factor`]:
/// `L y = b` forward, `z = D⁻¹ y`, `Lᵀ x = z` backward (paper eq. 13).
#[inline(always)]
pub fn ldlt_solve<const D: usize>(f: &[f64], b: &[f64; D]) -> [f64; D] {
    let f = &f[..packed_len(D)];
    let mut x = *b;
    for i in 0..D {
        for k in 0..i {
            x[i] -= f[packed_index(i, k)] * x[k];
        }
    }
    for i in 0..D {
        x[i] *= f[packed_index(i, i)];
    }
    for i in (0..D).rev() {
        for k in i + 1..D {
            x[i] -= f[packed_index(k, i)] * x[k];
        }
    }
    x
}

/// `A x` from the packed LDLᵀ factor of [`ldlt_factor`]: `y = Lᵀ x`,
/// `z = D y`, `A x = L z`.
#[inline]
pub fn ldlt_mul<const D: usize>(f: &[f64], x: &[f64; D]) -> [f64; D] {
    let f = &f[..packed_len(D)];
    let mut y = *x;
    for i in 0..D {
        for k in i + 1..D {
            y[i] += f[packed_index(k, i)] * x[k];
        }
        y[i] /= f[packed_index(i, i)];
    }
    let mut z = y;
    for i in (0..D).rev() {
        for k in 0..i {
            z[i] += f[packed_index(i, k)] * y[k];
        }
    }
    z
}

/// The point of segment `[a, b]` nearest to `x` and its weights `(w_a, w_b)`:
/// `t = (x−a)·(b−a)/|b−a|²` clamped to `[0, 1]`, `p = a + t (b−a)`, `w = (1−t, t)`.
pub fn nearest_on_segment<const D: usize>(
    x: &[f64; D],
    a: &[f64; D],
    b: &[f64; D],
) -> ([f64; D], [f64; 2]) {
    let ab = sub(b, a);
    let len2 = dot(&ab, &ab);
    let t = if len2 > 0.0 {
        (dot(&sub(x, a), &ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (std::array::from_fn(|k| a[k] + t * ab[k]), [1.0 - t, t])
}

/// The point of triangle `abc` nearest to `x` and its barycentric weights
/// (Ericson, *Real-Time Collision Detection*, §5.1.5): the orthogonal
/// projection when it falls inside, otherwise the nearest point of the
/// nearest edge or corner. A degenerate (zero-area) triangle whose nearest
/// point is interior gives non-finite values.
pub fn nearest_on_triangle<const D: usize>(
    x: &[f64; D],
    a: &[f64; D],
    b: &[f64; D],
    c: &[f64; D],
) -> ([f64; D], [f64; 3]) {
    let at = |wa: f64, wb: f64, wc: f64| {
        (
            std::array::from_fn(|k| wa * a[k] + wb * b[k] + wc * c[k]),
            [wa, wb, wc],
        )
    };
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ax = sub(x, a);
    let (d1, d2) = (dot(&ab, &ax), dot(&ac, &ax));
    if d1 <= 0.0 && d2 <= 0.0 {
        return at(1.0, 0.0, 0.0);
    }
    let bx = sub(x, b);
    let (d3, d4) = (dot(&ab, &bx), dot(&ac, &bx));
    if d3 >= 0.0 && d4 <= d3 {
        return at(0.0, 1.0, 0.0);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return at(1.0 - v, v, 0.0);
    }
    let cx = sub(x, c);
    let (d5, d6) = (dot(&ab, &cx), dot(&ac, &cx));
    if d6 >= 0.0 && d5 <= d6 {
        return at(0.0, 0.0, 1.0);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return at(1.0 - w, 0.0, w);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return at(0.0, 1.0 - w, w);
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    at(1.0 - v - w, v, w)
}

/// The ball-vertex point of quadrilateral `q` (cyclic node order) for `x`,
/// and its weights.
///
/// The face and `x` are projected onto the plane through the face's centroid
/// whose normal is the cross product of the diagonals; `(s, t)` are the
/// bilinear coordinates of `x`'s projection in that planar quad
/// (`x = a + s e + t f + s t g` with `e = b−a`, `f = d−a`, `g = a−b+c−d`,
/// solved in closed form: `t` from `k₂t² + k₁t + k₀ = 0`, the root whose
/// `(s, t)` lies nearest to the unit square), clamped to `[0,1]²`;
/// `p` is the planar quad's point at `(s, t)` and the weights are
/// `((1−s)(1−t), s(1−t), st, (1−s)t)`. `None` when the diagonals are parallel
/// (a degenerate face).
pub fn nearest_on_quad(x: &[f64; 3], q: &[[f64; 3]; 4]) -> Option<([f64; 3], [f64; 4])> {
    let normal = cross(&sub(&q[2], &q[0]), &sub(&q[3], &q[1]));
    let len = norm(&normal);
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let n = normal.map(|v| v / len);
    let centroid: [f64; 3] = std::array::from_fn(|k| q.iter().map(|v| v[k]).sum::<f64>() / 4.0);
    let project = |v: &[f64; 3]| {
        let h = dot(&n, &sub(v, &centroid));
        std::array::from_fn::<f64, 3, _>(|k| v[k] - h * n[k])
    };
    let [a, b, c, d] = q.map(|v| project(&v));
    let e = sub(&b, &a);
    let f = sub(&d, &a);
    let g: [f64; 3] = std::array::from_fn(|k| a[k] - b[k] + c[k] - d[k]);
    let h = sub(&project(x), &a);
    let cr = |u: &[f64; 3], v: &[f64; 3]| dot(&n, &cross(u, v));
    let (k2, k1, k0) = (cr(&g, &f), cr(&e, &f) + cr(&h, &g), cr(&h, &e));
    // Numerically stable roots of k2 t² + k1 t + k0 = 0 (a linear equation when k2 = 0).
    let sq = (k1 * k1 - 4.0 * k0 * k2).max(0.0).sqrt();
    let qq = -0.5 * (k1 + sq.copysign(k1));
    let roots = [
        if qq != 0.0 { k0 / qq } else { 0.0 },
        if k2 != 0.0 { qq / k2 } else { f64::NAN },
    ];
    let st_of = |t: f64| {
        let m: [f64; 3] = std::array::from_fn(|k| e[k] + t * g[k]);
        let mm = dot(&m, &m);
        let s = if mm > 0.0 {
            dot(&sub(&h, &f.map(|v| v * t)), &m) / mm
        } else {
            0.0
        };
        (s, t)
    };
    let outside = |(s, t): (f64, f64)| {
        let o = |v: f64| (-v).max(v - 1.0).max(0.0);
        o(s).powi(2) + o(t).powi(2)
    };
    let mut best = st_of(roots[0]);
    if roots[1].is_finite() {
        let other = st_of(roots[1]);
        if outside(other) < outside(best) || !outside(best).is_finite() {
            best = other;
        }
    }
    let (s, t) = (best.0.clamp(0.0, 1.0), best.1.clamp(0.0, 1.0));
    let w = [(1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t];
    let p = std::array::from_fn(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k] + w[3] * d[k]);
    Some((p, w))
}

/// Node `i` of `coords` (`D` numbers a node) as a 3D point (`z = 0` in 2D).
pub fn lifted<const D: usize>(coords: &[f64], i: usize) -> [f64; 3] {
    let p = point::<D>(coords, i);
    [p[0], p[1], if D == 3 { p[2] } else { 0.0 }]
}

/// The mean of nodes `nodes` of `coords` as a 3D point ([`lifted`]).
pub fn mean_of<const D: usize>(coords: &[f64], nodes: impl Iterator<Item = usize>) -> [f64; 3] {
    let (mut sum, mut n) = ([0.0; 3], 0.0);
    for i in nodes {
        let p = lifted::<D>(coords, i);
        (0..3).for_each(|k| sum[k] += p[k]);
        n += 1.0;
    }
    sum.map(|v| v / n)
}

/// The point of polygon `v` (`m ≥ 3` points in cyclic order) nearest to `x`
/// on its decomposition into the triangles `(v_k, v_{k+1}, c)` about its
/// centre `c = Σ v_k / m`, and its weights on the `m` points, written into
/// `w` (resized to `m`): the triangle's barycentric weights `(α, β, γ)` put
/// `α` on `v_k`, `β` on `v_{k+1}` and `γ/m` on every point, so that each
/// weight lies in `[0, 1]` and they sum to 1. The first nearest triangle
/// wins a tie.
pub fn nearest_on_polygon<const D: usize>(
    x: &[f64; D],
    v: &[[f64; D]],
    w: &mut Vec<f64>,
) -> [f64; D] {
    let m = v.len();
    let c: [f64; D] = std::array::from_fn(|k| v.iter().map(|p| p[k]).sum::<f64>() / m as f64);
    let mut best = (f64::INFINITY, 0, [0.0; 3], c);
    for k in 0..m {
        let (p, t) = nearest_on_triangle(x, &v[k], &v[(k + 1) % m], &c);
        let d = norm(&sub(&p, x));
        if d < best.0 {
            best = (d, k, t, p);
        }
    }
    let (_, k, t, p) = best;
    w.clear();
    w.resize(m, t[2] / m as f64);
    w[k] += t[0];
    w[(k + 1) % m] += t[1];
    p
}

/// An orthonormal frame whose last row is the unit normal `n`: rows
/// `t₁ … t_{D−1}, n`. In 2D `t = (−n_y, n_x)`; in 3D `t₁` is the coordinate
/// axis least aligned with `n` made orthogonal to it, `t₂ = n × t₁`.
pub fn normal_frame<const D: usize>(n: &[f64; D]) -> [[f64; D]; D] {
    let mut r = [[0.0; D]; D];
    r[D - 1] = *n;
    if D == 2 {
        r[0][0] = -n[1];
        r[0][1] = n[0];
    } else {
        let k = (0..D)
            .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
            .unwrap_or(0);
        let mut t = [0.0; D];
        t[k] = 1.0;
        let along = n[k];
        for i in 0..D {
            t[i] -= along * n[i];
        }
        let len = norm(&t);
        let t1: [f64; 3] = std::array::from_fn(|i| t[i] / len);
        let n3: [f64; 3] = std::array::from_fn(|i| n[i]);
        let t2 = cross(&n3, &t1);
        r[0] = std::array::from_fn(|i| t1[i]);
        r[1] = std::array::from_fn(|i| t2[i]);
    }
    r
}

/// Each node's position on a Z-order (Morton) curve through the bounding box
/// of `coords` (`dim` ≤ 3 numbers per point): the coordinates scaled to
/// `⌊2²¹ (x − x_min) / (x_max − x_min)⌋` per axis, their bits interleaved
/// (axis 0 lowest). Nearby keys are nearby points.
pub fn morton_keys(dim: usize, coords: &[f64]) -> Vec<u64> {
    const BITS: u32 = 21;
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in coords.chunks_exact(dim) {
        for k in 0..dim {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let cells = f64::from(1u32 << BITS);
    let scale: [f64; 3] = std::array::from_fn(|k| {
        let span = hi[k] - lo[k];
        if span > 0.0 {
            (cells - 1.0) / span
        } else {
            0.0
        }
    });
    coords
        .chunks_exact(dim)
        .map(|p| {
            let mut key = 0u64;
            for k in 0..dim {
                let c = ((p[k] - lo[k]) * scale[k]) as u64;
                for b in 0..BITS {
                    key |= ((c >> b) & 1) << (dim as u32 * b + k as u32);
                }
            }
            key
        })
        .collect()
}

#[cfg(test)]
mod tests;
