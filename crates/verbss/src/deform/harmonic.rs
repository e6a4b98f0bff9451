//! The translation's weight of the blended rigid motion: the scalar
//! problem `Σ_j k_ij (w_j − w_i) = 0`, `k_ij = 1/L_ij`, at every unknown
//! node, `w` given at the prescribed ones (the Laplacian smoother's system;
//! docs/method.md, "Blended rigid motion"). Short edges couple strongly, so
//! small and compressed cells take less of the change. Solved by conjugate
//! gradients with a Jacobi preconditioner, from the previous increment's
//! weights.

use std::sync::Arc;

use crate::topology::{self, Csr};

/// Conjugate gradients stop at this reduction of the residual…
const REDUCTION: f64 = 1e-8;
/// …or after this many iterations (the guard judges the mesh a weight makes).
const MAX_ITERATIONS: usize = 4000;

/// The edges of a mesh: as a list for the products (each edge once,
/// `[a, b]` with `a < b`, sorted) and as a graph for the distances.
pub(super) struct Laplace {
    dim: usize,
    edges: Vec<[u32; 2]>,
    graph: Arc<Csr>,
}

impl Laplace {
    /// The problem on the edges of a mesh in `dim` dimensions, its edge
    /// graph `graph` ([`topology::edge_graph`]).
    pub(super) fn new(dim: usize, graph: Arc<Csr>) -> Laplace {
        let mut edges = Vec::with_capacity(graph.targets.len() / 2);
        edges.extend(topology::upper_edges(&graph).map(|[a, b]| [a as u32, b as u32]));
        Laplace { dim, edges, graph }
    }

    /// The edges as a graph (both directions).
    pub(super) fn graph(&self) -> &Csr {
        &self.graph
    }

    /// Solves for `w` on `coords` with unknowns where `unknown` is set (and
    /// the node is on an edge): on entry the prescribed values and the
    /// unknowns' initial guess, on exit the solution (clamped to `[0, 1]`).
    pub(super) fn solve(&self, coords: &[f64], unknown: &[bool], w: &mut [f64]) {
        let dim = self.dim;
        let unknown: Vec<bool> = unknown
            .iter()
            .enumerate()
            .map(|(i, u)| *u && !self.graph.row(i).is_empty())
            .collect();
        let k: Vec<f64> = self
            .edges
            .iter()
            .map(|&[a, b]| {
                let (a, b) = (a as usize, b as usize);
                let squared: f64 = (0..dim)
                    .map(|d| (coords[dim * a + d] - coords[dim * b + d]).powi(2))
                    .sum();
                1.0 / squared.sqrt()
            })
            .collect();
        let n = w.len();
        let mut diag = vec![0.0; n];
        for (&[a, b], &ke) in self.edges.iter().zip(&k) {
            diag[a as usize] += ke;
            diag[b as usize] += ke;
        }
        // A x over the unknowns, prescribed entries of x taken as they are.
        let apply = |x: &[f64], y: &mut [f64]| {
            y.fill(0.0);
            for (&[a, b], &ke) in self.edges.iter().zip(&k) {
                let (a, b) = (a as usize, b as usize);
                let f = ke * (x[a] - x[b]);
                y[a] += f;
                y[b] -= f;
            }
        };
        // r, z and p stay 0 at the prescribed entries, so their dot products
        // need no mask (the sums add the same terms, in the same order).
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
        let scale = (0..n)
            .filter(|&i| unknown[i])
            .map(|i| pull[i] * pull[i])
            .sum::<f64>()
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
        for d in diag.iter_mut() {
            *d = d.max(f64::MIN_POSITIVE);
        }
        let mut z: Vec<f64> = r.iter().zip(&diag).map(|(ri, di)| ri / di).collect();
        let mut p = z.clone();
        let mut q = vec![0.0; n];
        let mut rz = dot(&r, &z);
        let mut rr = dot(&r, &r);
        for _ in 0..MAX_ITERATIONS {
            if rr.sqrt() <= REDUCTION * scale {
                break;
            }
            apply(&p, &mut q);
            let pq = dot(&p, &q);
            if pq <= 0.0 {
                break;
            }
            let alpha = rz / pq;
            let (mut next, mut next_rr) = (0.0, 0.0);
            for i in 0..n {
                w[i] += alpha * p[i];
                r[i] -= alpha * q[i] * mask[i];
                z[i] = r[i] / diag[i];
                next += r[i] * z[i];
                next_rr += r[i] * r[i];
            }
            let beta = next / rz;
            rz = next;
            rr = next_rr;
            for (pi, zi) in p.iter_mut().zip(&z) {
                *pi = zi + beta * *pi;
            }
        }
        for wi in w.iter_mut() {
            *wi = wi.clamp(0.0, 1.0);
        }
    }
}

/// `x · y`, summed in order.
fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}
