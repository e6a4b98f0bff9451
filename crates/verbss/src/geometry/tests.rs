use super::*;

#[test]
fn determinants() {
    assert_eq!(det::<2>(&[[1.0, 0.0], [0.0, 1.0]]), 1.0);
    assert_eq!(
        det::<3>(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
        1.0
    );
    assert_eq!(
        det::<3>(&[[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
        -1.0
    );
    assert_eq!(cross(&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
}

#[test]
fn ldlt_mul_multiplies_by_the_factored_matrix() {
    let a = [4.0, 1.0, 3.0, -0.5, 0.25, 2.0];
    let mut f = [0.0; 6];
    assert!(ldlt_factor::<3>(&a, &mut f));
    let x = [0.3, -1.2, 2.5];
    let want = packed_mul::<3>(&a, &x);
    let got = ldlt_mul::<3>(&f, &x);
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() < 1e-14, "{got:?} vs {want:?}");
    }
    let back = ldlt_solve::<3>(&f, &got);
    for k in 0..3 {
        assert!((back[k] - x[k]).abs() < 1e-14);
    }
}

#[test]
fn corner_jacobians_of_reference_elements_are_positive() {
    use crate::mesh::CellKind;
    let refs: [(CellKind, Vec<f64>); 6] = [
        (CellKind::Triangle, vec![0., 0., 1., 0., 0., 1.]),
        (CellKind::Quad, vec![0., 0., 1., 0., 1., 1., 0., 1.]),
        (
            CellKind::Tetra,
            vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.],
        ),
        (
            CellKind::Hexahedron,
            vec![
                0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 0., 0., 1., 1., 0., 1., 1., 1., 1.,
                0., 1., 1.,
            ],
        ),
        (
            CellKind::Wedge,
            vec![
                0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 0., 1., 0., 1., 1.,
            ],
        ),
        (
            CellKind::Pyramid,
            vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 0.5, 0.5, 1.],
        ),
    ];
    for (kind, coords) in refs {
        let t = kind.table();
        let nodes: Vec<usize> = (0..t.nodes).collect();
        for c in t.corners {
            let j = if t.dim == 2 {
                corner_jacobian::<2>(&coords, &nodes, c)
            } else {
                corner_jacobian::<3>(&coords, &nodes, c)
            };
            assert!(j > 0.0, "{kind:?} corner {c:?}: {j}");
        }
        // Facets point outward: their normal points away from the centroid.
        if t.dim == 3 {
            let centroid: [f64; 3] = std::array::from_fn(|k| {
                (0..t.nodes).map(|i| coords[3 * i + k]).sum::<f64>() / t.nodes as f64
            });
            for f in t.facets {
                let p = |i: usize| point::<3>(&coords, f[i]);
                let n = cross(&sub(&p(1), &p(0)), &sub(&p(f.len() - 1), &p(0)));
                assert!(
                    dot(&n, &sub(&p(0), &centroid)) > 0.0,
                    "{kind:?} facet {f:?}"
                );
            }
        }
    }
}

fn close<const N: usize>(a: &[f64; N], b: &[f64; N]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-14)
}

fn weights_ok(w: &[f64]) {
    assert!(w.iter().all(|&v| (0.0..=1.0).contains(&v)), "{w:?}");
    assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{w:?}");
}

#[test]
fn segment_nearest_points() {
    let (a, b) = ([0.0, 0.0], [2.0, 0.0]);
    let cases = [
        ([0.5, 1.0], [0.5, 0.0], [0.75, 0.25]),
        ([3.0, 1.0], [2.0, 0.0], [0.0, 1.0]),
        ([-1.0, -1.0], [0.0, 0.0], [1.0, 0.0]),
    ];
    for (x, p, w) in cases {
        let (q, v) = nearest_on_segment(&x, &a, &b);
        assert!(close(&q, &p) && close(&v, &w), "{x:?}: {q:?} {v:?}");
        weights_ok(&v);
    }
}

#[test]
fn triangle_nearest_points() {
    let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let cases = [
        // inside: the orthogonal projection
        ([0.25, 0.25, 1.0], [0.25, 0.25, 0.0], [0.5, 0.25, 0.25]),
        // beyond edge bc
        ([2.0, 2.0, 0.0], [0.5, 0.5, 0.0], [0.0, 0.5, 0.5]),
        // beyond edge ab
        ([0.5, -1.0, 0.0], [0.5, 0.0, 0.0], [0.5, 0.5, 0.0]),
        // beyond edge ca
        ([-1.0, 0.25, -2.0], [0.0, 0.25, 0.0], [0.75, 0.0, 0.25]),
        // corner regions
        ([-1.0, -1.0, 3.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ([3.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([-1.0, 3.0, 0.5], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
    ];
    for (x, p, w) in cases {
        let (q, v) = nearest_on_triangle(&x, &a, &b, &c);
        assert!(close(&q, &p) && close(&v, &w), "{x:?}: {q:?} {v:?}");
        weights_ok(&v);
    }
}

#[test]
fn quad_nearest_points() {
    let square = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let trapezoid = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let cases = [
        (
            square,
            [0.25, 0.5, 2.0],
            [0.25, 0.5, 0.0],
            [0.375, 0.125, 0.125, 0.375],
        ),
        // x = s(2 − t), y = t: (0.75, 0.5) is s = 0.5, t = 0.5
        (
            trapezoid,
            [0.75, 0.5, 1.0],
            [0.75, 0.5, 0.0],
            [0.25, 0.25, 0.25, 0.25],
        ),
        // outside: s clamped to 1
        (
            square,
            [3.0, 0.5, -1.0],
            [1.0, 0.5, 0.0],
            [0.0, 0.5, 0.5, 0.0],
        ),
        // outside two sides: the corner
        (
            square,
            [-2.0, -3.0, 0.5],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
        ),
    ];
    for (q, x, p, w) in cases {
        let (r, v) = nearest_on_quad(&x, &q).unwrap();
        assert!(close(&r, &p) && close(&v, &w), "{x:?}: {r:?} {v:?}");
        weights_ok(&v);
    }
    // A warped face: p lies in the mean plane and reproduces its own weights.
    let warped = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.1],
        [1.2, 1.0, 0.0],
        [0.0, 0.9, 0.2],
    ];
    let (p, w) = nearest_on_quad(&[0.3, 0.6, 1.0], &warped).unwrap();
    weights_ok(&w);
    let (p2, w2) = nearest_on_quad(&p, &warped).unwrap();
    assert!(close(&p, &p2) && close(&w, &w2));
    let degenerate = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
    assert!(nearest_on_quad(&[0.0, 1.0, 0.0], &degenerate).is_none());
}

#[test]
fn ldlt_2x2_and_3x3() {
    // [[4, 2], [2, 3]]: l10 = 0.5, d = (4, 2); x = (0.5, 0) for b = (2, 1).
    let a = [4.0, 2.0, 3.0];
    let mut f = [0.0; 3];
    assert!(ldlt_factor::<2>(&a, &mut f));
    assert_eq!(f, [0.25, 0.5, 0.5]);
    assert_eq!(ldlt_solve::<2>(&f, &[2.0, 1.0]), [0.5, 0.0]);
    // [[4, 2, 0], [2, 5, 1], [0, 1, 3]]: d = (4, 4, 2.75), l = (0.5, 0, 0.25);
    // x = (1, −1, 2) for b = (2, −1, 5).
    let a = [4.0, 2.0, 5.0, 0.0, 1.0, 3.0];
    let mut f = [0.0; 6];
    assert!(ldlt_factor::<3>(&a, &mut f));
    assert!(close(&f, &[0.25, 0.5, 0.25, 0.0, 0.25, 1.0 / 2.75]));
    assert!(close(
        &ldlt_solve::<3>(&f, &[2.0, -1.0, 5.0]),
        &[1.0, -1.0, 2.0]
    ));
    assert_eq!(packed_mul::<3>(&a, &[1.0, -1.0, 2.0]), [2.0, -1.0, 5.0]);
    // Singular and indefinite matrices are refused.
    assert!(!ldlt_factor::<2>(&[1.0, 1.0, 1.0], &mut [0.0; 3]));
    assert!(!ldlt_factor::<2>(&[1.0, 2.0, 1.0], &mut [0.0; 3]));
}

#[test]
fn normal_frames_are_orthonormal() {
    let n2 = [0.6, 0.8];
    let r2 = normal_frame(&n2);
    assert_eq!(r2, [[-0.8, 0.6], [0.6, 0.8]]);
    let n3 = [0.0, 0.6, 0.8];
    let r = normal_frame(&n3);
    for i in 0..3 {
        for j in 0..3 {
            let e = if i == j { 1.0 } else { 0.0 };
            assert!((dot(&r[i], &r[j]) - e).abs() < 1e-15);
        }
    }
    assert_eq!(r[2], n3);
    assert!(det::<3>(&r) > 0.0);
}
