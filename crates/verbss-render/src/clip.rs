//! Clipping in picture coordinates, before anything is mapped to pixels: a
//! polygon (Sutherland–Hodgman) or a segment (Liang–Barsky) against a
//! rectangle `[u0, u1, v0, v1]`. The depth (third coordinate) is interpolated
//! with the others, which is exact since pixels are an affine map of the
//! picture's `(u, v)`. What is drawn is then never longer than the window,
//! however deep the zoom.

/// The window `w` grown by `f` of its spans on every side.
pub fn grown(w: [f64; 4], f: f64) -> [f64; 4] {
    let (du, dv) = (f * (w[1] - w[0]), f * (w[3] - w[2]));
    [w[0] - du, w[1] + du, w[2] - dv, w[3] + dv]
}

/// Whether the bounding box of `p` meets rectangle `r`.
fn meets(p: &[[f64; 3]], r: [f64; 4]) -> bool {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in p {
        for d in 0..2 {
            lo[d] = lo[d].min(q[d]);
            hi[d] = hi[d].max(q[d]);
        }
    }
    lo[0] <= r[1] && hi[0] >= r[0] && lo[1] <= r[3] && hi[1] >= r[2]
}

/// The part of polygon `p` inside rectangle `r` into `out` (cleared; empty
/// when nothing is inside).
pub fn polygon(p: &[[f64; 3]], r: [f64; 4], out: &mut Vec<[f64; 3]>) {
    out.clear();
    if p.is_empty() || !meets(p, r) {
        return;
    }
    out.extend_from_slice(p);
    let mut next = Vec::with_capacity(p.len() + 4);
    // (axis, bound, keep the side above the bound)
    for (d, bound, above) in [
        (0, r[0], true),
        (0, r[1], false),
        (1, r[2], true),
        (1, r[3], false),
    ] {
        let inside = |q: &[f64; 3]| if above { q[d] >= bound } else { q[d] <= bound };
        next.clear();
        for (i, b) in out.iter().enumerate() {
            let a = out[(i + out.len() - 1) % out.len()];
            match (inside(&a), inside(b)) {
                (true, true) => next.push(*b),
                (true, false) => next.push(cross(a, *b, d, bound)),
                (false, true) => {
                    next.push(cross(a, *b, d, bound));
                    next.push(*b);
                }
                (false, false) => {}
            }
        }
        std::mem::swap(out, &mut next);
        if out.is_empty() {
            return;
        }
    }
    // Rounding of far-away corners cannot carry a point out of `r`.
    for q in out.iter_mut() {
        *q = clamp(*q, r);
    }
}

/// `p` with its `(u, v)` clamped into rectangle `r`.
fn clamp(p: [f64; 3], r: [f64; 4]) -> [f64; 3] {
    [p[0].clamp(r[0], r[1]), p[1].clamp(r[2], r[3]), p[2]]
}

/// The point of segment `a → b` where coordinate `d` equals `bound`, the
/// same whichever way the segment runs (neighbours share their cuts).
fn cross(a: [f64; 3], b: [f64; 3], d: usize, bound: f64) -> [f64; 3] {
    let (a, b) = if (a[0], a[1]) <= (b[0], b[1]) {
        (a, b)
    } else {
        (b, a)
    };
    let t = ((bound - a[d]) / (b[d] - a[d])).clamp(0.0, 1.0);
    let mut p = [0.0; 3];
    for k in 0..3 {
        p[k] = a[k] + t * (b[k] - a[k]);
    }
    p[d] = bound;
    p
}

/// The part of segment `a → b` inside rectangle `r`, if any. A cut end lies
/// exactly on its side of `r`, however long the segment.
pub fn segment(a: [f64; 3], b: [f64; 3], r: [f64; 4]) -> Option<[[f64; 3]; 2]> {
    if !a.iter().chain(&b).all(|x| x.is_finite()) {
        return None;
    }
    // Each end: its parameter and the side it was cut at (axis, bound).
    let (mut start, mut end) = ((0.0f64, None), (1.0f64, None));
    for (d, lo, hi) in [(0, r[0], r[1]), (1, r[2], r[3])] {
        let delta = b[d] - a[d];
        if delta == 0.0 {
            if a[d] < lo || a[d] > hi {
                return None;
            }
            continue;
        }
        let (enter, leave) = if delta > 0.0 { (lo, hi) } else { (hi, lo) };
        let (te, tl) = ((enter - a[d]) / delta, (leave - a[d]) / delta);
        if te > start.0 {
            start = (te, Some((d, enter)));
        }
        if tl < end.0 {
            end = (tl, Some((d, leave)));
        }
        if start.0 > end.0 {
            return None;
        }
    }
    let at = |(t, side): (f64, Option<(usize, f64)>)| {
        let mut p = [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
        if let Some((d, bound)) = side {
            p[d] = bound;
        }
        clamp(p, r)
    };
    Some([at(start), at(end)])
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNIT: [f64; 4] = [0.0, 1.0, 0.0, 1.0];

    #[test]
    fn a_huge_triangle_is_cut_to_the_window() {
        let mut out = Vec::new();
        let big = [
            [-1e300, -1e300, 0.0],
            [1e300, -1e300, 0.0],
            [0.0, 1e300, 0.0],
        ];
        polygon(&big, UNIT, &mut out);
        assert_eq!(out.len(), 4);
        assert!(out
            .iter()
            .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
        polygon(
            &[[2.0, 2.0, 0.0], [3.0, 2.0, 0.0], [2.0, 3.0, 0.0]],
            UNIT,
            &mut out,
        );
        assert!(out.is_empty());
    }

    #[test]
    fn a_square_across_a_corner_keeps_the_overlap_and_its_depth() {
        let mut out = Vec::new();
        let sq = [
            [0.5, 0.5, 2.0],
            [1.5, 0.5, 2.0],
            [1.5, 1.5, 2.0],
            [0.5, 1.5, 2.0],
        ];
        polygon(&sq, UNIT, &mut out);
        let area: f64 = (0..out.len())
            .map(|i| {
                let (p, q) = (out[i], out[(i + 1) % out.len()]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            / 2.0;
        assert!((area - 0.25).abs() < 1e-12, "{area}");
        assert!(out.iter().all(|p| p[2] == 2.0));
    }

    #[test]
    fn segments_are_cut_to_the_window_or_dropped() {
        let s = segment([-1e300, 0.5, 0.0], [1e300, 0.5, 4.0], UNIT).unwrap();
        assert_eq!(s[0][..2], [0.0, 0.5]);
        assert_eq!(s[1][..2], [1.0, 0.5]);
        assert!((s[0][2] - 2.0).abs() < 1e-9);
        assert!(segment([2.0, 0.0, 0.0], [3.0, 1.0, 0.0], UNIT).is_none());
        assert!(segment([f64::NAN, 0.0, 0.0], [0.5, 0.5, 0.0], UNIT).is_none());
        assert_eq!(
            segment([0.2, 0.2, 0.0], [0.8, 0.3, 0.0], UNIT),
            Some([[0.2, 0.2, 0.0], [0.8, 0.3, 0.0]])
        );
    }
}
