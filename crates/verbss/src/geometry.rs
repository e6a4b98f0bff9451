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
#[inline]
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

#[cfg(test)]
mod tests {
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
                    0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 0., 0., 1., 1., 0., 1., 1., 1.,
                    1., 0., 1., 1.,
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
}
