//! The Laplacian smoother (Löhner type): each displacement component on its
//! own, `Σ_j k_ij (u_j − u_i) = 0` over the edge neighbours `j` of node `i`,
//! `k_ij = 1/L_ij`. A sweep sets `u_i ← ω (Σ_j k_ij u_j)/(Σ_j k_ij) + (1 − ω) u_i`;
//! a sliding node moves only along its plane, by the tangential part of that
//! change (the projected equation `Tᵀ (Σ_j k_ij) T a = Tᵀ Σ_j k_ij (u_j − d n)`
//! has this solution since `Tᵀ n = 0`).
//!
//! One scalar weight per coupling instead of a `D×D` block.

use super::Layout;
use crate::error::{Error, Result};
use crate::geometry::{norm, packed_index, packed_len, point, sub};
use crate::springs::{Connectivity, NodeBlocks};

/// Edge weights of the unknown nodes, one row per position.
pub(crate) struct Weights {
    /// `Σ_j k_ij` per position.
    sums: Vec<f64>,
    /// Row `p`'s couplings to unknowns are entries `offsets[p]..offsets[p + 1]`.
    offsets: Vec<usize>,
    /// Position of each coupled unknown.
    neighbours: Vec<u32>,
    /// `k_ij` of each entry.
    weights: Vec<f64>,
    /// Row `p`'s couplings to prescribed nodes: `fixed_offsets[p]..fixed_offsets[p + 1]`.
    fixed_offsets: Vec<usize>,
    /// Mesh index of each coupled prescribed node.
    fixed_nodes: Vec<usize>,
    /// `k_ij` of each prescribed coupling.
    fixed_weights: Vec<f64>,
}

impl Weights {
    /// Weights `1/L` of the element edges at `coords`.
    pub(crate) fn new<const D: usize>(
        conn: &Connectivity,
        coords: &[f64],
        layout: &Layout,
    ) -> Result<Weights> {
        let mut w = Weights {
            sums: Vec::with_capacity(layout.order.len()),
            offsets: vec![0],
            neighbours: Vec::new(),
            weights: Vec::new(),
            fixed_offsets: vec![0],
            fixed_nodes: Vec::new(),
            fixed_weights: Vec::new(),
        };
        for &i in &layout.order {
            let xi = point::<D>(coords, i);
            let mut sum = 0.0;
            for j in conn.edge_graph.entries(i) {
                let len = norm(&sub(&point::<D>(coords, j), &xi));
                if !(len > 0.0 && len.is_finite()) {
                    return Err(Error::InvalidMesh(format!(
                        "nodes {} and {} coincide (an edge of zero length)",
                        conn.node_tags[i], conn.node_tags[j]
                    )));
                }
                sum += 1.0 / len;
                if layout.position[j] == u32::MAX {
                    w.fixed_nodes.push(j);
                    w.fixed_weights.push(1.0 / len);
                } else {
                    w.neighbours.push(layout.position[j]);
                    w.weights.push(1.0 / len);
                }
            }
            if sum == 0.0 {
                return Err(Error::InvalidMesh(format!(
                    "node {} has no edge",
                    conn.node_tags[i]
                )));
            }
            w.sums.push(sum);
            w.offsets.push(w.neighbours.len());
            w.fixed_offsets.push(w.fixed_nodes.len());
        }
        Ok(w)
    }

    /// `c_p = Σ_{j prescribed} k_pj u_j`.
    pub(crate) fn constants<const D: usize>(
        &self,
        layout: &Layout,
        displacement: &[f64],
        constant: &mut [f64],
    ) {
        for p in 0..layout.order.len() {
            let mut c = [0.0; D];
            for e in self.fixed_offsets[p]..self.fixed_offsets[p + 1] {
                let u = point::<D>(displacement, self.fixed_nodes[e]);
                for k in 0..D {
                    c[k] += self.fixed_weights[e] * u[k];
                }
            }
            constant[D * p..D * (p + 1)].copy_from_slice(&c);
        }
    }

    /// Position `p`'s relaxed value and the sum of the absolute changes of
    /// its unknown components.
    // The counter `e`: as in [`super::coupled`].
    #[allow(clippy::explicit_counter_loop)]
    #[inline]
    pub(crate) fn update<const D: usize>(
        &self,
        layout: &Layout,
        constant: &[f64],
        omega: f64,
        p: usize,
        work: &[f64],
    ) -> ([f64; D], f64) {
        let (a, b) = (self.offsets[p], self.offsets[p + 1]);
        let points = work.as_chunks::<D>().0;
        let mut r = point::<D>(constant, p);
        let mut e = a;
        for (&w, &j) in self.weights[a..b].iter().zip(&self.neighbours[a..b]) {
            super::prefetch::ahead::<D>(work, &self.neighbours, e);
            e += 1;
            let u = &points[j as usize];
            for k in 0..D {
                r[k] += w * u[k];
            }
        }
        let old = point::<D>(work, p);
        let delta: [f64; D] = std::array::from_fn(|k| omega * (r[k] / self.sums[p] - old[k]));
        let (delta, step) = match layout.frame::<D>(p) {
            None => (delta, delta),
            Some(frame) => {
                let mut a = frame.rotate(&delta);
                frame.clear_given(&mut a);
                (a, frame.unrotate(&a))
            }
        };
        (
            std::array::from_fn(|k| old[k] + step[k]),
            delta.iter().map(|v| v.abs()).sum(),
        )
    }

    /// The same system as node blocks, `K_pp = (Σ_j k_pj) I` and
    /// `B_pj = k_pj I` (a sliding node's `K_pp` in its tangent frame, padded
    /// with 1 for the normal, as [`super::Engine`] prepares spring blocks),
    /// for the direct solve.
    pub(crate) fn blocks<const D: usize>(&self, layout: &Layout) -> NodeBlocks {
        let s = packed_len(D);
        let identity = |w: f64| -> Vec<f64> {
            let mut b = vec![0.0; s];
            for k in 0..D {
                b[packed_index(k, k)] = w;
            }
            b
        };
        let mut diag = Vec::with_capacity(s * self.sums.len());
        for (p, &sum) in self.sums.iter().enumerate() {
            let mut k = identity(sum);
            if let Some(frame) = layout.frame::<D>(p) {
                for d in frame.free()..D {
                    k[packed_index(d, d)] = 1.0;
                }
            }
            diag.extend(k);
        }
        NodeBlocks {
            diag,
            offsets: self.offsets.clone(),
            neighbours: self.neighbours.clone(),
            blocks: self.weights.iter().flat_map(|&w| identity(w)).collect(),
            ..NodeBlocks::default()
        }
    }

    /// `Σ_j k_pj`: position `p`'s diagonal.
    pub(crate) fn sum(&self, p: usize) -> f64 {
        self.sums[p]
    }

    /// Row offsets and neighbour positions of the couplings to unknowns.
    pub(crate) fn rows(&self) -> (&[usize], &[u32]) {
        (&self.offsets, &self.neighbours)
    }

    /// Bytes the sweep reads: sums, offsets, neighbour indices and weights.
    pub(crate) fn sweep_bytes(&self) -> usize {
        (self.sums.len() + self.weights.len()) * std::mem::size_of::<f64>()
            + self.neighbours.len() * std::mem::size_of::<u32>()
            + self.offsets.len() * std::mem::size_of::<usize>()
    }
}
