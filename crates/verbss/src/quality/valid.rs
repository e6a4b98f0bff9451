//! Validity for the flow solver: the tests OpenFOAM's `checkMesh` applies
//! to each cell (docs/method.md, "Validity"), on the cell's faces.
//!
//! With the cell's faces outward (the kind's facets, or a polyhedron's
//! faces, their normals times the reference orientation `s`):
//!
//! - each face's centre `x_F` and area vector `A_F` are OpenFOAM's: a
//!   triangle's centroid and `½ (b−a)×(c−a)`; a larger face is cut into the
//!   triangles `(v_k, v_{k+1}, v̄)` about the mean `v̄` of its points,
//!   `A_F = ½ Σ n_k` with `n_k = (v_{k+1}−v_k)×(v̄−v_k)`, and
//!   `x_F = Σ |n_k| (v_k+v_{k+1}+v̄)/3 / Σ |n_k|`;
//! - the cell's estimated centre `c̃` is the mean of its face centres, each
//!   face's pyramid on it has `3V_F = A_F·(x_F − c̃)`; the cell's volume is
//!   `V = Σ V_F` and its centre `c = Σ V_F (¾ x_F + ¼ c̃) / Σ V_F` (`c̃`
//!   when `|3V| ≤ 10⁻³⁰⁰`);
//! - **volume**: `V ≥ 10⁻³⁰⁰` (`checkCellVolumes`);
//! - **face pyramids**: `A_F·(x_F − c)/3 ≥ −10⁻¹⁵` for every face
//!   (`checkFacePyramids`: a face whose pyramid on the cell centre points
//!   inward is "incorrectly oriented");
//! - **closedness**: the openness `max_k |Σ_F A_F,k| / (Σ_F |A_F,k| + 10⁻¹⁵⁰)`
//!   at most `10⁻⁶` (`checkClosedCells`);
//! - **aspect ratio** (`checkClosedCells` too): with `m_k = Σ_F |A_F,k|`
//!   over the mesh's directions (x, y, and z in 3D),
//!   `max_k m_k / (min_k m_k + 10⁻¹⁵⁰)`, in 3D at least
//!   `Σ_k m_k / 6 / max(V, 10⁻¹⁵⁰)^(2/3)`, at most 1000. checkMesh fails a
//!   mesh with a larger one, though its solvers run on it (boundary layers
//!   of larger ratios are common) and the measure changes when a mesh
//!   merely turns (it is taken along the axes). So it judges a step only on
//!   an OpenFOAM case, where checkMesh is the user's test, and only for a
//!   cell it did not fail in the input mesh.
//!
//! A 2D cell is the prism OpenFOAM would hold for it, one unit thick: its
//! polygon (nodes in cyclic order) as the back and front faces, one
//! rectangle per side. The same formulas reduce to the plane: a side
//! `a → b` has `A = (b_y−a_y, a_x−b_x)` and centre `(a+b)/2`, the front and
//! back faces the polygon's area `S` and centre as above, each pyramid of
//! front and back `S/2` (three times its volume); the in-plane centre and
//! volume follow as in 3D. Such a prism is closed by construction (its side
//! vectors sum to zero, its front and back cancel), so openness is not
//! measured in 2D.

use std::fmt;

use crate::geometry::{cross, dot, norm, point, sub};
use crate::mesh::Local;

/// OpenFOAM's `closedThreshold_`: the largest openness of a closed cell.
pub const CLOSED: f64 = 1e-6;
/// OpenFOAM's `aspectThreshold_`: the largest aspect ratio checkMesh passes.
pub const ASPECT: f64 = 1000.0;
/// OpenFOAM's `SMALL`: a face pyramid down to `−SMALL` is accepted.
const SMALL: f64 = 1e-15;
/// OpenFOAM's `VSMALL`: the smallest valid cell volume.
const VSMALL: f64 = 1e-300;
/// OpenFOAM's `ROOTVSMALL`.
const ROOTVSMALL: f64 = 1e-150;

/// Why a cell is not valid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Failure {
    /// A corner Jacobian of the wrong sign, or zero (the corner test of a
    /// triangle, quadrilateral, tetrahedron, hexahedron, prism or pyramid).
    Corner,
    /// Its volume from the face decomposition is zero or negative.
    Volume,
    /// The pyramid of its face `face` (local index among its facets) on
    /// the cell centre has a negative volume: the face is wrongly oriented.
    Pyramid {
        /// The face.
        face: usize,
    },
    /// Its faces do not close it within [`CLOSED`].
    Open {
        /// Its openness.
        openness: f64,
    },
    /// Its aspect ratio went above [`ASPECT`] (it was not in the input).
    Stretched {
        /// Its aspect ratio.
        aspect_ratio: f64,
    },
}

impl Failure {
    /// The failure as two numbers (a code and its value), to send between
    /// processes; [`Failure::from_numbers`] reads it back.
    pub fn to_numbers(self) -> [f64; 2] {
        match self {
            Failure::Corner => [0.0, 0.0],
            Failure::Volume => [1.0, 0.0],
            Failure::Pyramid { face } => [2.0, face as f64],
            Failure::Open { openness } => [3.0, openness],
            Failure::Stretched { aspect_ratio } => [4.0, aspect_ratio],
        }
    }

    /// The failure [`Failure::to_numbers`] wrote.
    pub fn from_numbers(n: [f64; 2]) -> Failure {
        match n[0] as u8 {
            1 => Failure::Volume,
            2 => Failure::Pyramid {
                face: n[1] as usize,
            },
            3 => Failure::Open { openness: n[1] },
            4 => Failure::Stretched { aspect_ratio: n[1] },
            _ => Failure::Corner,
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Failure::Corner => write!(f, "inverted"),
            Failure::Volume => write!(f, "has a zero or negative volume (checkMesh)"),
            Failure::Pyramid { face } => write!(
                f,
                "has an incorrectly oriented face (face {face}: negative pyramid on the cell \
                 centre, checkMesh)"
            ),
            Failure::Open { openness } => write!(
                f,
                "is open (openness {openness:.3e} over checkMesh's {CLOSED:.0e})"
            ),
            Failure::Stretched { aspect_ratio } => write!(
                f,
                "is stretched (aspect ratio {aspect_ratio:.1} over checkMesh's {ASPECT})"
            ),
        }
    }
}

/// The faces of a cell (points of a face) held in place; more go to the
/// heap.
const FACES: usize = 16;

/// A face's centre and (outward) area vector.
type FaceGeometry = ([f64; 3], [f64; 3]);

/// OpenFOAM's centre and area vector of the face through points `v`.
fn face_geometry(v: &[[f64; 3]]) -> FaceGeometry {
    let n = v.len();
    if n == 3 {
        let c = std::array::from_fn(|k| (v[0][k] + v[1][k] + v[2][k]) / 3.0);
        let a = cross(&sub(&v[1], &v[0]), &sub(&v[2], &v[0])).map(|x| 0.5 * x);
        return (c, a);
    }
    let mean: [f64; 3] = std::array::from_fn(|k| v.iter().map(|p| p[k]).sum::<f64>() / n as f64);
    let (mut sum_n, mut sum_a, mut sum_ac) = ([0.0; 3], 0.0, [0.0; 3]);
    for k in 0..n {
        let (p, next) = (&v[k], &v[(k + 1) % n]);
        let t = cross(&sub(next, p), &sub(&mean, p));
        let a = norm(&t);
        for j in 0..3 {
            sum_n[j] += t[j];
            sum_ac[j] += a * (p[j] + next[j] + mean[j]);
        }
        sum_a += a;
    }
    if sum_a < ROOTVSMALL {
        (mean, [0.0; 3])
    } else {
        (sum_ac.map(|x| x / (3.0 * sum_a)), sum_n.map(|x| 0.5 * x))
    }
}

/// What the tests of the module docs find on one cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict {
    /// The cell's volume from its face decomposition.
    pub volume: f64,
    /// How many of its face pyramids are below `−10⁻¹⁵` (checkMesh's
    /// "incorrectly oriented" faces, counted per cell).
    pub bad_pyramids: usize,
    /// The face of the smallest pyramid and that pyramid's volume.
    pub worst_pyramid: (usize, f64),
    /// Its openness (0 in 2D).
    pub openness: f64,
    /// Its aspect ratio.
    pub aspect_ratio: f64,
}

impl Verdict {
    /// Whether its volume is below OpenFOAM's `VSMALL` (or not a number):
    /// checkMesh's "zero or negative cell volume".
    pub fn negative_volume(&self) -> bool {
        self.volume.is_nan() || self.volume < VSMALL
    }

    /// The first test failed (volume, then pyramids, then closedness) with
    /// the cell's volume (the failing pyramid's for a pyramid), or `None`;
    /// the aspect ratio is judged against the input's by the caller.
    pub fn failure(&self) -> Option<(Failure, f64)> {
        if self.negative_volume() {
            Some((Failure::Volume, self.volume))
        } else if self.bad_pyramids > 0 {
            let (face, v) = self.worst_pyramid;
            Some((Failure::Pyramid { face }, v))
        } else if self.openness > CLOSED {
            Some((
                Failure::Open {
                    openness: self.openness,
                },
                self.volume,
            ))
        } else {
            None
        }
    }
}

/// The tests of the module docs on a cell with faces `faces` (centres and
/// outward area vectors); `closed`: whether to measure openness (3D).
fn judge(faces: &[FaceGeometry], closed: bool) -> Verdict {
    let m = faces.len() as f64;
    let estimate: [f64; 3] = std::array::from_fn(|k| faces.iter().map(|f| f.0[k]).sum::<f64>() / m);
    let (mut vol3, mut weighted) = (0.0, [0.0; 3]);
    for (x, a) in faces {
        let p = dot(a, &sub(x, &estimate));
        vol3 += p;
        for k in 0..3 {
            weighted[k] += p * (0.75 * x[k] + 0.25 * estimate[k]);
        }
    }
    let centre = if vol3.abs() > VSMALL {
        weighted.map(|w| w / vol3)
    } else {
        estimate
    };
    let mut verdict = Verdict {
        volume: vol3 / 3.0,
        bad_pyramids: 0,
        worst_pyramid: (0, f64::INFINITY),
        openness: 0.0,
        aspect_ratio: 0.0,
    };
    for (face, (x, a)) in faces.iter().enumerate() {
        let v = dot(a, &sub(x, &centre)) / 3.0;
        if v.is_nan() || v < -SMALL {
            verdict.bad_pyramids += 1;
        }
        if v < verdict.worst_pyramid.1 || v.is_nan() {
            verdict.worst_pyramid = (face, v);
        }
    }
    let (mut sum, mut mag) = ([0.0; 3], [0.0; 3]);
    for (_, a) in faces {
        for k in 0..3 {
            sum[k] += a[k];
            mag[k] += a[k].abs();
        }
    }
    let dims = if closed { 3 } else { 2 };
    let (lo, hi) = mag[..dims]
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &m| {
            (lo.min(m), hi.max(m))
        });
    verdict.aspect_ratio = hi / (lo + ROOTVSMALL);
    if closed {
        verdict.openness = (0..3)
            .map(|k| sum[k].abs() / (mag[k] + ROOTVSMALL))
            .fold(0.0, f64::max);
        let v = verdict.volume.max(ROOTVSMALL);
        verdict.aspect_ratio = verdict
            .aspect_ratio
            .max(mag.iter().sum::<f64>() / 6.0 / v.powf(2.0 / 3.0));
    }
    verdict
}

/// Up to `N` values held in place, more on the heap: a cell's faces or a
/// face's points, measured without an allocation for the paper's kinds.
struct Buffer<T: Copy, const N: usize> {
    inline: [T; N],
    len: usize,
    heap: Vec<T>,
}

impl<T: Copy, const N: usize> Buffer<T, N> {
    fn new(zero: T) -> Self {
        Buffer {
            inline: [zero; N],
            len: 0,
            heap: Vec::new(),
        }
    }

    fn clear(&mut self) {
        self.len = 0;
        self.heap.clear();
    }

    fn push(&mut self, v: T) {
        if self.len < N {
            self.inline[self.len] = v;
        } else {
            if self.len == N {
                self.heap.extend_from_slice(&self.inline);
            }
            self.heap.push(v);
        }
        self.len += 1;
    }

    fn as_slice(&self) -> &[T] {
        if self.len > N {
            &self.heap
        } else {
            &self.inline[..self.len]
        }
    }
}

/// The tests of the module docs on the 3D cell with nodes `nodes` and
/// topology `local` at `coords`, relative to orientation `s`.
pub(super) fn check_3d(nodes: &[usize], local: Local, coords: &[f64], s: f64) -> Verdict {
    let mut faces: Buffer<FaceGeometry, FACES> = Buffer::new(([0.0; 3], [0.0; 3]));
    let mut points: Buffer<[f64; 3], FACES> = Buffer::new([0.0; 3]);
    local.facets(|facet| {
        points.clear();
        for &l in facet {
            points.push(point::<3>(coords, nodes[l]));
        }
        let (x, a) = face_geometry(points.as_slice());
        faces.push((x, a.map(|v| s * v)));
    });
    judge(faces.as_slice(), true)
}

/// [`check_3d`] for a 2D cell whose nodes `nodes` are its polygon in cyclic
/// order (the prism of the module docs).
pub(super) fn check_2d(nodes: &[usize], coords: &[f64], s: f64) -> Verdict {
    let n = nodes.len();
    let mut polygon: Buffer<[f64; 3], FACES> = Buffer::new([0.0; 3]);
    for k in 0..n {
        let k = if s < 0.0 { n - 1 - k } else { k };
        let p = point::<2>(coords, nodes[k]);
        polygon.push([p[0], p[1], 0.0]);
    }
    let polygon = polygon.as_slice();
    let (centre, area) = face_geometry(polygon);
    let mut faces: Buffer<FaceGeometry, FACES> = Buffer::new(([0.0; 3], [0.0; 3]));
    for k in 0..n {
        let (a, b) = (polygon[k], polygon[(k + 1) % n]);
        faces.push((
            [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5],
            [b[1] - a[1], a[0] - b[0], 0.0],
        ));
    }
    faces.push(([centre[0], centre[1], 1.0], [0.0, 0.0, area[2]]));
    faces.push(([centre[0], centre[1], 0.0], [0.0, 0.0, -area[2]]));
    judge(faces.as_slice(), false)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hexahedron's six faces, outward, at points `x`.
    fn cube(x: &[[f64; 3]; 8]) -> Vec<FaceGeometry> {
        crate::mesh::CellKind::Hexahedron
            .table()
            .facets
            .iter()
            .map(|f| face_geometry(&f.iter().map(|&l| x[l]).collect::<Vec<_>>()))
            .collect()
    }

    /// The unit cube of the samples, its 8 points in the hexahedron's order.
    fn unit_cube() -> [[f64; 3]; 8] {
        let c = &crate::mesh::samples::hex_wedge_pyramid_tet().coords[..24];
        std::array::from_fn(|k| [c[3 * k], c[3 * k + 1], c[3 * k + 2]])
    }

    #[test]
    fn a_cube_passes_and_its_mirror_fails_on_volume() {
        assert_eq!(judge(&cube(&unit_cube()), true).failure(), None);
        let mirrored = unit_cube().map(|p| [-p[0], p[1], p[2]]);
        let (failure, volume) = judge(&cube(&mirrored), true).failure().unwrap();
        assert_eq!(failure, Failure::Volume);
        assert!((volume + 1.0).abs() < 1e-14, "{volume}");
    }

    #[test]
    fn a_face_pushed_through_the_centre_is_incorrectly_oriented() {
        // The top face's nodes pushed down below the centre but keeping a
        // positive total volume: the pyramid of the top face turns over.
        let mut x = unit_cube();
        x[6] = [1.0, 1.0, -3.0];
        let r = judge(&cube(&x), true).failure();
        assert!(
            matches!(r, Some((Failure::Pyramid { .. } | Failure::Volume, _))),
            "{r:?}"
        );
    }

    #[test]
    fn a_square_prism_has_the_square_s_area_as_volume() {
        let coords = [0., 0., 2., 0., 2., 1., 0., 1.];
        assert_eq!(check_2d(&[0, 1, 2, 3], &coords, 1.0).failure(), None);
        let (failure, volume) = check_2d(&[0, 3, 2, 1], &coords, 1.0).failure().unwrap();
        assert_eq!(failure, Failure::Volume);
        assert!((volume + 2.0).abs() < 1e-14, "{volume}");
        assert_eq!(check_2d(&[0, 3, 2, 1], &coords, -1.0).failure(), None);
    }
}
