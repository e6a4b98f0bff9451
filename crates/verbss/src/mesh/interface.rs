//! Interfaces a file declares between groups: the two sides of a sliding
//! interface (OpenFOAM's `cyclicAMI`, `cyclicACMI`, `mapped*` patches),
//! whose coincident nodes move each with its own side, and the two sides of
//! a periodic pair (OpenFOAM's `cyclic`, Gmsh's `$Periodic`), each node of
//! one side the image of a node of the other by the pair's transform.

use crate::geometry::{cross, dot, norm};

/// Two sides of one interface, each a list of group names.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// The groups of each side (a `cyclicACMI` side: its coupled patch and
    /// its non-overlapping patch).
    pub sides: [Vec<String>; 2],
    /// How the two sides are coupled.
    pub coupling: Coupling,
}

/// How the two sides of an interface are coupled.
#[derive(Debug, Clone, PartialEq)]
pub enum Coupling {
    /// They may slide along each other: their coincident nodes are two
    /// nodes, each moving with its own side.
    Sliding,
    /// Each node of the second side is the image of one of the first by
    /// the transform.
    Periodic(Transform),
    /// As [`Coupling::Periodic`], the nodes paired by the file: each
    /// `(first, second)` with `second` the image of `first` (Gmsh's
    /// `$Periodic`: master, slave), by the transform or, without one, by
    /// the mean translation between the pairs.
    Linked {
        /// The transform, if the file gives one.
        transform: Option<Transform>,
        /// The node pairs.
        pairs: Vec<(usize, usize)>,
    },
}

/// The transform of a periodic pair, taking the first side onto the second.
#[derive(Debug, Clone, PartialEq)]
pub enum Transform {
    /// A translation by this vector.
    Translation([f64; 3]),
    /// A rotation about the axis through `centre`, by `angle` radians (right
    /// hand about `axis`).
    Rotation {
        /// The axis (any length but zero).
        axis: [f64; 3],
        /// A point of the axis.
        centre: [f64; 3],
        /// The angle.
        angle: f64,
    },
    /// `x' = A x + b`, the 3 × 4 matrix `[A | b]` by rows.
    Affine([f64; 12]),
}

impl Transform {
    /// The image of `p`.
    pub fn apply(&self, p: &[f64; 3]) -> [f64; 3] {
        match self {
            Transform::Translation(t) => [p[0] + t[0], p[1] + t[1], p[2] + t[2]],
            Transform::Rotation {
                axis,
                centre,
                angle,
            } => {
                let l = norm(axis);
                let k = [axis[0] / l, axis[1] / l, axis[2] / l];
                let v = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
                let (s, c) = angle.sin_cos();
                let kv = cross(&k, &v);
                let kd = dot(&k, &v) * (1.0 - c);
                std::array::from_fn(|d| centre[d] + v[d] * c + kv[d] * s + k[d] * kd)
            }
            Transform::Affine(m) => std::array::from_fn(|r| {
                m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3]
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotation_turns_about_its_axis_through_its_centre() {
        let quarter = Transform::Rotation {
            axis: [0.0, 0.0, 2.0],
            centre: [1.0, 0.0, 0.0],
            angle: std::f64::consts::FRAC_PI_2,
        };
        let q = quarter.apply(&[2.0, 0.0, 5.0]);
        for (a, b) in q.iter().zip([1.0, 1.0, 5.0]) {
            assert!((a - b).abs() < 1e-15, "{q:?}");
        }
        assert_eq!(
            Transform::Translation([0.5, 0.0, -1.0]).apply(&[1.0, 2.0, 3.0]),
            [1.5, 2.0, 2.0]
        );
        let shear = [1.0, 0.5, 0.0, 2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, -1.0];
        assert_eq!(
            Transform::Affine(shear).apply(&[1.0, 2.0, 3.0]),
            [4.0, 2.0, 2.0]
        );
    }
}
