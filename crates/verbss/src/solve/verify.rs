//! Whether a solution can be trusted (docs/method.md, "Accepting a step").
//!
//! The eq.-8 value measures one sweep's change, not the error: on stretched
//! cells (a wake cut of cells 10⁻⁵ high and a chord long) the sweeps can
//! stop, or stall, with nodes far enough from their equilibrium to invert a
//! thin cell. Each unknown node's error is estimated from its true residual
//! `r_i = c_i + Σ_j B_ij u_j − K_ii u_i` and its own block:
//! `e_i = K_ii⁻¹ r_i`, the distance from `u_i` to where the node's springs
//! put it given its neighbours (one Jacobi step). A smooth error moves a
//! node and its neighbours together and inverts nothing; `e_i` measures the
//! error's variation across the node's cells, which is what inverts them.
//! It is compared with the node's local size `h_i`, the smallest height of
//! its cells ([`cell_height`]).

use rayon::prelude::*;

use super::{relax, Frame, CHUNK};
use crate::geometry::{cross, det, ldlt_mul, lifted, mean_of, norm, point, sub};
use crate::mesh::{CellKind, Local};
use crate::springs::Connectivity;

/// The result of [`check`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Check {
    /// Root-mean-square of `|r_i|` over the unknown nodes.
    pub true_residual: f64,
    /// `max_i |e_i| / h_i`.
    pub error_ratio: f64,
    /// The position where the ratio is largest.
    pub worst: usize,
}

/// The smallest height of a cell at `coords`: over its corners, the
/// corner's parallelogram (parallelepiped) measure over its largest side,
/// `|det(e₁, e₂)| / max |e_k|` in 2D and `|det(e₁, e₂, e₃)| / max |e_k × e_l|`
/// in 3D, with `e_k` the corner's edges. For a rectangle (box) this is its
/// shortest side; for a simplex, a height over one of its largest facets.
/// A polygon or polyhedron (no corners) measures twice the smallest
/// distance from the mean of its nodes to the line or plane of one of its
/// facets (`general_height`).
pub fn cell_height<const D: usize>(
    kind: CellKind,
    nodes: &[usize],
    local: Local,
    coords: &[f64],
) -> f64 {
    if kind.is_general() {
        return general_height::<D>(nodes, local, coords);
    }
    let mut height = f64::INFINITY;
    for corner in kind.table().corners {
        let x0 = point::<D>(coords, nodes[corner[0]]);
        let e: [[f64; D]; D] =
            std::array::from_fn(|k| sub(&point::<D>(coords, nodes[corner[k + 1]]), &x0));
        let volume = det::<D>(&e).abs();
        let side = if D == 2 {
            norm(&e[0]).max(norm(&e[1]))
        } else {
            let v = |k: usize| [e[k][0], e[k][1], e[k][2]];
            norm(&cross(&v(0), &v(1)))
                .max(norm(&cross(&v(1), &v(2))))
                .max(norm(&cross(&v(2), &v(0))))
        };
        height = height.min(if side > 0.0 { volume / side } else { 0.0 });
    }
    height
}

/// `2 min_F |n_F · (x_F − c)|`: twice the smallest distance from the mean
/// `c` of the cell's nodes to the line (plane) of a facet `F`, with `x_F`
/// the mean of its nodes and `n_F` its unit normal (the sum of the normals
/// of its triangles about `x_F`).
fn general_height<const D: usize>(nodes: &[usize], local: Local, coords: &[f64]) -> f64 {
    let at = |l: usize| lifted::<D>(coords, nodes[l]);
    let c = mean_of::<D>(coords, nodes.iter().copied());
    let mut height = f64::INFINITY;
    local.facets(|facet| {
        let xf = mean_of::<D>(coords, facet.iter().map(|&l| nodes[l]));
        let normal = if D == 2 {
            let d = sub(&at(facet[1]), &at(facet[0]));
            [-d[1], d[0], 0.0]
        } else {
            let mut n = [0.0; 3];
            for k in 0..facet.len() {
                let (a, b) = (at(facet[k]), at(facet[(k + 1) % facet.len()]));
                let t = cross(&sub(&a, &xf), &sub(&b, &xf));
                (0..3).for_each(|j| n[j] += t[j]);
            }
            n
        };
        let len = norm(&normal);
        let d = sub(&xf, &c);
        let distance = if len > 0.0 {
            (normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2]).abs() / len
        } else {
            0.0
        };
        height = height.min(2.0 * distance);
    });
    height
}

/// The local size `h_i` of each node of `order` (an unknown position's
/// node): the smallest [`cell_height`] of the node's cells at `coords`.
pub fn heights<const D: usize>(conn: &Connectivity, coords: &[f64], order: &[usize]) -> Vec<f64> {
    let cells: Vec<f64> = (0..conn.cells.len())
        .into_par_iter()
        .map(|c| {
            let nodes = conn.cells.cell(c);
            cell_height::<D>(conn.cells.kinds[c], &nodes, conn.cells.local(c), coords)
        })
        .collect();
    order
        .par_iter()
        .map(|&i| {
            conn.node_cells
                .entries(i)
                .map(|c| cells[c])
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

/// Position `p`'s error estimate and squared true residual for [`check`],
/// from its factored block `factor` (LDLᵀ of `K_pp`, projected for a
/// sliding node), `rhs = c_p + Σ_j B_pj u_j` and its value `old`: the
/// Jacobi step `e_p = K_pp⁻¹ rhs − u_p` (in its `frame` when it slides)
/// and `|r_p|² = |K_pp e_p|²`.
pub fn block_estimate<const D: usize>(
    factor: &[f64],
    rhs: &[f64; D],
    old: &[f64; D],
    frame: Option<Frame<D>>,
) -> ([f64; D], f64) {
    let (new, _) = relax::<D>(factor, rhs, old, frame, 1.0);
    let e: [f64; D] = std::array::from_fn(|k| new[k] - old[k]);
    let r = match frame {
        None => ldlt_mul::<D>(factor, &e),
        Some(frame) => frame.unrotate(&ldlt_mul::<D>(factor, &frame.rotate(&e))),
    };
    (e, r.iter().map(|v| v * v).sum())
}

/// Checks the unknowns `work` against their local sizes `heights`.
/// `estimate(p, work)` gives position `p`'s error estimate `e_p` and the
/// squared norm of its true residual `|r_p|²`.
pub fn check<const D: usize, F>(work: &[f64], heights: &[f64], estimate: F) -> Check
where
    F: Fn(usize, &[f64]) -> ([f64; D], f64) + Sync,
{
    let m = heights.len();
    let parts: Vec<(f64, f64, usize)> = (0..m.div_ceil(CHUNK))
        .into_par_iter()
        .map(|t| {
            let mut sum = 0.0;
            let (mut worst, mut at) = (0.0f64, t * CHUNK);
            let first = t * CHUNK;
            for (k, &height) in heights[first..(first + CHUNK).min(m)].iter().enumerate() {
                let (e, r2) = estimate(first + k, work);
                sum += r2;
                let size = norm(&e);
                let ratio = if size == 0.0 {
                    0.0
                } else if height > 0.0 && !size.is_nan() {
                    size / height
                } else {
                    f64::INFINITY
                };
                if ratio > worst {
                    (worst, at) = (ratio, first + k);
                }
            }
            (sum, worst, at)
        })
        .collect();
    let mut check = Check {
        true_residual: 0.0,
        error_ratio: 0.0,
        worst: 0,
    };
    let mut sum = 0.0;
    for (s, worst, at) in parts {
        sum += s;
        if worst > check.error_ratio {
            (check.error_ratio, check.worst) = (worst, at);
        }
    }
    check.true_residual = (sum / m.max(1) as f64).sqrt();
    check
}
