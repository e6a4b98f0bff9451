//! The translation's weight of the blended rigid motion: the scalar
//! problem `Σ_j k_ij (w_j − w_i) = 0` at every unknown node, `w` given at
//! the prescribed ones (docs/method.md, "Blended rigid motion"), with
//! `k_ij = 1/L_ij` (the Laplacian smoother's system: short edges couple
//! strongly, so small and compressed cells take less of the change) or,
//! along a translation `t̂`, the directional
//!
//! `k_ij = (cos²α_ij + A sin²α_ij) / L_ij`,
//!
//! `α_ij` the angle between the edge and `t̂`, `A` [`ACROSS`], on the edges
//! in the body's shadow along the motion (their midpoint's projection
//! across `t̂` within the body's: [`Shadow`]), `1/L_ij` on the others: edges
//! across the motion couple `A` times more than edges along it, so a
//! column of nodes ahead of or behind a body moves nearly as one, and its
//! cells are compressed along the motion rather than sheared (OpenFOAM's
//! `directional` diffusivity, which its movingCone tutorial gives as
//! `(1 200 0)`), while beside the body, where a fixed wall along the
//! motion may be near, the shear spreads as before (the shadow's fade is
//! pulled inside it next to a fixed wall beside the body). Solved by conjugate gradients with a Jacobi
//! preconditioner, from the previous increment's weights, on a whole mesh
//! or on one process's part: the products are exact on the owned nodes
//! (every edge around them is local), the ghosts take their owners' values
//! after each update, and the dot products sum the owned nodes over the
//! processes.

use std::sync::Arc;

use rayon::prelude::*;

use crate::collective::Collective;
use crate::threads::{chunked_sums, Workers};
use crate::topology::Csr;

/// Conjugate gradients stop at this reduction of the residual (so that
/// processes summing in another order agree to about this much of the
/// move; with the fixed and anchored references the weights are solved
/// once a run)…
const REDUCTION: f64 = 1e-8;
/// …or after this many iterations (the guard judges the mesh a weight makes).
const MAX_ITERATIONS: usize = 4000;

/// The directional weight's coupling across the motion over along it,
/// `A`: on OpenFOAM's movingCone (the cone pushed 3 mm in 30 steps, the
/// weight directional everywhere) 10 kept a minimum quality of 0.63, 20
/// kept 0.87, 30 0.92, 50 and more the input's 0.9416 (docs/robustness.md,
/// "Squeezed gaps"); 100 sits between those and OpenFOAM's 200.
pub(super) const ACROSS: f64 = 100.0;

/// A body's shadow along its translation: the points whose coordinates
/// across the unit direction `along` (on the orthonormal `across`, one
/// vector in 2D, two in 3D) lie within the body's nodes', and the fade of
/// its depth on each side.
///
/// On a side the depth falls linearly to 0 over a width `f` (the body's
/// radius) outside the shadow's edge; where a fixed node lies beside the
/// body (within its extent along the motion) a gap `g < 2f` outside the
/// edge, the fall ends `clamp(g − f, 0, f)` outside the edge and is
/// `min(g, f)` wide. A column across the motion that ends on a fixed wall
/// cannot move as one: coupled strongly into it, the column would be held
/// near the wall's 0 and the cells just ahead of the body take the whole
/// translation (docs/method.md, "Blended rigid motion").
pub(super) struct Shadow {
    pub(super) along: [f64; 3],
    pub(super) across: Vec<[f64; 3]>,
    /// Per side (`−across[r]` for `r`, then `across[r]` for `m + r`, `m`
    /// vectors across): where the depth reaches 0 along that side's
    /// coordinate, and the width it falls over.
    pub(super) ramps: Vec<[f64; 2]>,
}

impl Shadow {
    /// The shadow along the unit vector `along` in `dim` dimensions of the
    /// nodes `nodes` of `coords`, faded over `fade` and pulled inside on a
    /// side a node of `fixed` lies beside, over the processes `on`
    /// (collective).
    pub(super) fn of(
        dim: usize,
        along: [f64; 3],
        coords: &[f64],
        nodes: &[usize],
        fixed: &[usize],
        fade: f64,
        on: &dyn Collective,
    ) -> Shadow {
        let across: Vec<[f64; 3]> = if dim == 2 {
            vec![[-along[1], along[0], 0.0]]
        } else {
            // The axis least along the motion, made normal to it, and the
            // third vector of the frame.
            let k = (0..3)
                .min_by(|&a, &b| along[a].abs().total_cmp(&along[b].abs()))
                .unwrap_or(0);
            let mut u = [0.0; 3];
            u[k] = 1.0;
            let d = u[0] * along[0] + u[1] * along[1] + u[2] * along[2];
            let u: [f64; 3] = std::array::from_fn(|c| u[c] - d * along[c]);
            let l = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
            let u = [u[0] / l, u[1] / l, u[2] / l];
            let v = [
                along[1] * u[2] - along[2] * u[1],
                along[2] * u[0] - along[0] * u[2],
                along[0] * u[1] - along[1] * u[0],
            ];
            vec![u, v]
        };
        // The coordinate of node `i` along `b`.
        let project =
            |i: usize, b: &[f64; 3]| (0..dim).map(|d| coords[dim * i + d] * b[d]).sum::<f64>();
        // [−lo…, hi…], the larger over the processes.
        let m = across.len();
        let mut bounds = vec![f64::NEG_INFINITY; 2 * m];
        for &i in nodes {
            for (r, b) in across.iter().enumerate() {
                let s = project(i, b);
                bounds[r] = bounds[r].max(-s);
                bounds[m + r] = bounds[m + r].max(s);
            }
        }
        on.max(&mut bounds);
        // The body's extent along the motion, [−start, end].
        let mut extent = [f64::NEG_INFINITY; 2];
        for &i in nodes {
            let s = project(i, &along);
            extent[0] = extent[0].max(-s);
            extent[1] = extent[1].max(s);
        }
        on.max(&mut extent);
        // On each side (−lo…, hi…), minus the gap to the nearest fixed node
        // beside the body, the larger over the processes.
        let mut gaps = vec![f64::NEG_INFINITY; 2 * m];
        for &i in fixed {
            let s = project(i, &along);
            if s < -extent[0] || s > extent[1] {
                continue;
            }
            for (r, b) in across.iter().enumerate() {
                let s = project(i, b);
                for (k, sigma) in [(r, -s), (m + r, s)] {
                    let out = sigma - bounds[k];
                    if out > 0.0 {
                        gaps[k] = gaps[k].max(-out);
                    }
                }
            }
        }
        on.max(&mut gaps);
        let ramps: Vec<[f64; 2]> = (0..2 * m)
            .map(|k| {
                let (edge, gap) = (bounds[k], -gaps[k]);
                [edge + (gap - fade).clamp(0.0, fade), fade.min(gap)]
            })
            .collect();
        Shadow {
            along,
            ramps,
            across,
        }
    }

    /// How deep the point `p` is in the shadow: 1 within it, falling
    /// linearly to 0 across the motion on each side.
    fn depth(&self, p: &[f64; 3]) -> f64 {
        let m = self.across.len();
        self.across
            .iter()
            .enumerate()
            .map(|(r, b)| {
                let s = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
                [(r, -s), (m + r, s)]
                    .iter()
                    .map(|&(k, sigma)| {
                        let [end, width] = self.ramps[k];
                        ((end - sigma) / width.max(f64::MIN_POSITIVE)).clamp(0.0, 1.0)
                    })
                    .product::<f64>()
            })
            .product()
    }
}

/// The edge graph of a mesh: the products run row by row over it.
pub(super) struct Laplace {
    dim: usize,
    graph: Arc<Csr>,
}

impl Laplace {
    /// The problem on the edges of a mesh in `dim` dimensions, its edge
    /// graph `graph` ([`crate::topology::edge_graph`]).
    pub(super) fn new(dim: usize, graph: Arc<Csr>) -> Laplace {
        Laplace { dim, graph }
    }

    /// The edges as a graph (both directions).
    pub(super) fn graph(&self) -> &Csr {
        &self.graph
    }

    /// Solves for `w` on `coords` with unknowns where `unknown` is set (and
    /// the node is on an edge), directional in the shadow `along` when
    /// given (isotropic otherwise): on entry the prescribed values and
    /// the unknowns' initial guess, on exit the solution (clamped to
    /// `[0, 1]`), over the processes `on` (collective; the ghosts' values
    /// on entry their owners'). The products and sums run on `workers`,
    /// node by node (`(A x)_i = Σ_j k_ij (x_i − x_j)` over row `i`, in its
    /// order) and in fixed chunks: the same bits for any number of them.
    pub(super) fn solve(
        &self,
        on: &dyn Collective,
        coords: &[f64],
        unknown: &[bool],
        w: &mut [f64],
        along: Option<&Shadow>,
        workers: &Workers,
    ) {
        let graph = &*self.graph;
        let n = w.len();
        // The coupling of every entry of the graph, in its order, and the
        // diagonal, each row's sum.
        let (unknown, k, diag) = workers.install(|| {
            let unknown: Vec<bool> = (0..n)
                .into_par_iter()
                .map(|i| unknown[i] && !graph.row(i).is_empty())
                .collect();
            let k: Vec<f64> = (0..n)
                .into_par_iter()
                .flat_map_iter(|i| {
                    graph
                        .entries(i)
                        .map(move |j| coupling(self.dim, coords, i.min(j), i.max(j), along))
                })
                .collect();
            let diag: Vec<f64> = (0..n)
                .into_par_iter()
                .map(|i| {
                    k[graph.offsets[i]..graph.offsets[i + 1]]
                        .iter()
                        .sum::<f64>()
                        .max(f64::MIN_POSITIVE)
                })
                .collect();
            (unknown, k, diag)
        });
        // A x over the unknowns, prescribed entries of x taken as they are.
        let apply = |x: &[f64], y: &mut [f64]| {
            workers.install(|| {
                y.par_iter_mut().enumerate().for_each(|(i, yi)| {
                    let (lo, hi) = (graph.offsets[i], graph.offsets[i + 1]);
                    *yi = graph.targets[lo..hi]
                        .iter()
                        .zip(&k[lo..hi])
                        .map(|(&j, &kij)| kij * (x[i] - x[j as usize]))
                        .sum();
                });
            });
        };
        // r, z and p stay 0 at the prescribed entries; the dot products
        // take the owned entries (all of them on one process).
        let owned: Vec<f64> = (0..n).map(|i| f64::from(u8::from(on.owns(i)))).collect();
        let sums = |term: &(dyn Fn(usize) -> [f64; 2] + Sync)| {
            let mut sum = workers.install(|| chunked_sums(n, term));
            on.sum(&mut sum);
            sum
        };
        let mut r = vec![0.0; n];
        apply(w, &mut r);
        for (ri, &u) in r.iter_mut().zip(&unknown) {
            *ri = if u { -*ri } else { 0.0 };
        }
        // The scale of the residual: the prescribed values' pull on the
        // unknowns with the unknowns at zero.
        let mut pull = vec![0.0; n];
        let prescribed: Vec<f64> = (0..n)
            .map(|i| if unknown[i] { 0.0 } else { w[i] })
            .collect();
        apply(&prescribed, &mut pull);
        let scale = sums(&|i| {
            let u = f64::from(u8::from(unknown[i]));
            [pull[i] * pull[i] * u * owned[i], 0.0]
        })[0]
            .sqrt();
        if scale == 0.0 {
            for i in (0..n).filter(|&i| unknown[i]) {
                w[i] = 0.0;
            }
            return;
        }
        // 1 at the unknowns, 0 at the prescribed: keeps `A p` off the
        // prescribed entries of r.
        let mask: Vec<f64> = unknown.iter().map(|&u| f64::from(u)).collect();
        let mut z: Vec<f64> = r.iter().zip(&diag).map(|(ri, di)| ri / di).collect();
        let mut p = z.clone();
        on.refresh(&mut p, 1);
        let mut q = vec![0.0; n];
        let [mut rz, mut rr] = sums(&|i| [r[i] * z[i] * owned[i], r[i] * r[i] * owned[i]]);
        for _ in 0..MAX_ITERATIONS {
            if rr.sqrt() <= REDUCTION * scale {
                break;
            }
            apply(&p, &mut q);
            let pq = sums(&|i| [p[i] * q[i] * owned[i], 0.0])[0];
            if pq <= 0.0 {
                break;
            }
            let alpha = rz / pq;
            workers.install(|| {
                (w.par_iter_mut(), r.par_iter_mut(), z.par_iter_mut())
                    .into_par_iter()
                    .enumerate()
                    .for_each(|(i, (wi, ri, zi))| {
                        *wi += alpha * p[i];
                        *ri -= alpha * q[i] * mask[i];
                        *zi = *ri / diag[i];
                    });
            });
            let next = sums(&|i| [r[i] * z[i] * owned[i], r[i] * r[i] * owned[i]]);
            let beta = next[0] / rz;
            [rz, rr] = next;
            workers.install(|| {
                p.par_iter_mut()
                    .zip(&z)
                    .for_each(|(pi, zi)| *pi = zi + beta * *pi);
            });
            on.refresh(&mut p, 1);
        }
        for wi in w.iter_mut() {
            *wi = wi.clamp(0.0, 1.0);
        }
    }
}

/// The coupling `k_ab` of the edge from node `a` to node `b > a` at
/// `coords` (`dim` numbers a node): `1/L`, or in the shadow `along` the
/// directional one (see the module documentation).
fn coupling(dim: usize, coords: &[f64], a: usize, b: usize, along: Option<&Shadow>) -> f64 {
    let e: [f64; 3] = std::array::from_fn(|d| {
        if d < dim {
            coords[dim * b + d] - coords[dim * a + d]
        } else {
            0.0
        }
    });
    let squared: f64 = e.iter().map(|v| v * v).sum();
    let middle: [f64; 3] = std::array::from_fn(|d| {
        if d < dim {
            0.5 * (coords[dim * a + d] + coords[dim * b + d])
        } else {
            0.0
        }
    });
    let across = match along {
        Some(shadow) => {
            let t = &shadow.along;
            let cos2 = (e[0] * t[0] + e[1] * t[1] + e[2] * t[2]).powi(2) / squared;
            let a = 1.0 + (ACROSS - 1.0) * shadow.depth(&middle);
            cos2 + a * (1.0 - cos2)
        }
        None => 1.0,
    };
    across / squared.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collective::Whole;
    use crate::mesh::Mesh;

    #[test]
    fn the_weights_are_the_same_on_any_workers_and_solve_the_edge_by_edge_system() {
        for directional in [false, true] {
            let (w, mesh, unknown) = solved(48, directional, 1);
            for threads in [2, 3] {
                let (other, ..) = solved(48, directional, threads);
                assert!(other
                    .iter()
                    .zip(&w)
                    .all(|(a, b)| a.to_bits() == b.to_bits()));
            }
            // The residual and the prescribed values' pull, edge by edge.
            let body: Vec<usize> = (0..=24).map(|j| j * 49).collect();
            let shadow = Shadow::of(2, [1.0, 0.0, 0.0], &mesh.coords, &body, &[], 0.25, &Whole);
            let along = directional.then_some(&shadow);
            let (mut residual, mut pull) = (vec![0.0; w.len()], vec![0.0; w.len()]);
            for [a, b] in crate::topology::edges(&mesh.cells, mesh.node_count()) {
                let k = coupling(2, &mesh.coords, a, b, along);
                residual[a] += k * (w[a] - w[b]);
                residual[b] += k * (w[b] - w[a]);
                let given = |i: usize| if unknown[i] { 0.0 } else { w[i] };
                pull[a] += k * (given(a) - given(b));
                pull[b] += k * (given(b) - given(a));
            }
            let norm = |v: &[f64]| {
                (0..v.len())
                    .filter(|&i| unknown[i])
                    .map(|i| v[i] * v[i])
                    .sum::<f64>()
                    .sqrt()
            };
            assert!(
                norm(&residual) <= 10.0 * REDUCTION * norm(&pull),
                "{} against {}",
                norm(&residual),
                norm(&pull)
            );
        }
    }

    /// The weights on the unit square of `n × n` quadrilaterals, solved on
    /// `threads` workers: `w = 1` on the lower half of the left side (a
    /// body's face pushed along x), 0 on the right side (a fixed wall), the
    /// rest free; with the mesh and the unknowns.
    fn solved(n: usize, directional: bool, threads: usize) -> (Vec<f64>, Mesh, Vec<bool>) {
        let node = |i: usize, j: usize| j * (n + 1) + i;
        let mesh = crate::mesh::samples::square_of_quads(n);
        let graph = Arc::new(crate::topology::edge_graph(&mesh.cells, mesh.node_count()));
        let laplace = Laplace::new(2, graph);
        let mut unknown = vec![true; mesh.node_count()];
        let mut w = vec![0.0; mesh.node_count()];
        for j in 0..=n {
            unknown[node(n, j)] = false;
            if j <= n / 2 {
                unknown[node(0, j)] = false;
                w[node(0, j)] = 1.0;
            }
        }
        let body: Vec<usize> = (0..=n / 2).map(|j| node(0, j)).collect();
        let shadow = Shadow::of(2, [1.0, 0.0, 0.0], &mesh.coords, &body, &[], 0.25, &Whole);
        laplace.solve(
            &Whole,
            &mesh.coords,
            &unknown,
            &mut w,
            directional.then_some(&shadow),
            &Workers::new(threads).unwrap(),
        );
        (w, mesh, unknown)
    }

    /// On 16 × 16 cells ([`solved`]): the largest spread of the weights
    /// across the motion of a column's nodes in the body's shadow
    /// (`y ≤ 0.5`), and the weight at the top-right corner's neighbour, far
    /// from the shadow.
    fn weights(directional: bool) -> (f64, f64) {
        let n = 16;
        let node = |i: usize, j: usize| j * (n + 1) + i;
        let (w, ..) = solved(n, directional, 1);
        let spread = (1..n)
            .map(|i| {
                let column = (0..=n / 2).map(|j| w[node(i, j)]);
                let (lo, hi) = column.fold((1.0f64, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
                hi - lo
            })
            .fold(0.0, f64::max);
        (spread, w[node(n - 1, n)])
    }

    #[test]
    fn the_directional_weight_moves_a_column_of_the_shadow_nearly_as_one() {
        let (isotropic, far) = weights(false);
        let (directional, far_directional) = weights(true);
        assert!(
            directional < 0.2 * isotropic,
            "{directional} against {isotropic}"
        );
        // Outside the shadow and its fade the coupling is the isotropic one.
        assert!(
            (far_directional - far).abs() < 0.5 * far,
            "{far_directional} against {far}"
        );
    }

    /// A unit-square body moving along x, its shadow across `y ∈ [0, 1]`
    /// faded over 1, with fixed nodes `fixed` of `coords` after its four
    /// corners: the depth at `y` above the body's middle.
    fn depth_above(fixed: &[[f64; 2]], y: f64) -> f64 {
        let mut coords = vec![0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
        coords.extend(fixed.iter().flatten());
        let others: Vec<usize> = (4..4 + fixed.len()).collect();
        let shadow = Shadow::of(
            2,
            [1.0, 0.0, 0.0],
            &coords,
            &[0, 1, 2, 3],
            &others,
            1.0,
            &Whole,
        );
        shadow.depth(&[0.5, y, 0.0])
    }

    #[test]
    fn a_fixed_wall_beside_the_body_pulls_the_fade_inside_its_shadow() {
        // No wall: 1 on the body's side, 0 a fade beyond it.
        assert_eq!(depth_above(&[], 1.0), 1.0);
        assert!((depth_above(&[], 1.5) - 0.5).abs() < 1e-12);
        // A fixed wall 0.5 above the body along its extent: the edges
        // between them keep 1/L, the fade falls to 0 at the body's side.
        let wall = [[0.0, 1.5], [0.5, 1.5], [1.0, 1.5]];
        assert_eq!(depth_above(&wall, 1.0), 0.0);
        assert!((depth_above(&wall, 0.75) - 0.5).abs() < 1e-12);
        assert_eq!(depth_above(&wall, 0.4), 1.0);
        // Between one and two fades away the fade ends short of the wall
        // by a fade: continuous with the two cases above.
        let far = [[0.5, 2.5]];
        assert!((depth_above(&far, 1.25) - 0.25).abs() < 1e-12);
        assert_eq!(depth_above(&far, 1.5), 0.0);
        // The same wall ahead of the body (past its extent along the
        // motion) is where the compression goes: no change.
        let ahead = [[3.0, 1.5], [4.0, 1.5]];
        assert!((depth_above(&ahead, 1.5) - 0.5).abs() < 1e-12);
    }
}
