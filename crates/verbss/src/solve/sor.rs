//! The paper's ball-vertex baseline: scalar SOR over all unknown components
//! of the global system.
//!
//! Row `k` of node `i` reads
//! `Σ_l (K_ii)_kl u_il − (Σ_j B_ij u_j)_k = 0`; its SOR update is
//! `u_ik ← (1 − ω) u_ik + ω ((Σ_j B_ij u_j)_k − Σ_{l≠k} (K_ii)_kl u_il) / (K_ii)_kk`.
//! The components are visited node by node in the sweep order, so the
//! coupling sum `Σ_j B_ij u_j`, which does not involve node `i`, is formed once
//! per node and the node's `D` rows are then relaxed in turn, each with the
//! values just updated. This is exactly scalar SOR on the assembled global
//! matrix in that order, without assembling it. Sliding nodes relax their
//! free components (in their frame) of the projected block.

use super::{coupled, Layout};
use crate::geometry::{packed_index, packed_len, point};
use crate::springs::NodeBlocks;

/// Position `p`'s displacement after relaxing its rows, and the sum of the
/// absolute changes of its unknown components. `blocks.diag` holds `K_ii`.
#[inline]
pub(crate) fn update<const D: usize>(
    blocks: &NodeBlocks,
    layout: &Layout,
    constant: &[f64],
    omega: f64,
    p: usize,
    work: &[f64],
) -> ([f64; D], f64) {
    let r = coupled::<D>(blocks, constant, p, work);
    let old = point::<D>(work, p);
    let k = &blocks.diag[packed_len(D) * p..packed_len(D) * (p + 1)];
    let relax = |b: &[f64; D], x0: &[f64; D], rows: usize| {
        let mut x = *x0;
        for i in 0..rows {
            let off: f64 = (0..D)
                .filter(|&l| l != i)
                .map(|l| k[packed_index(i, l)] * x[l])
                .sum();
            x[i] += omega * ((b[i] - off) / k[packed_index(i, i)] - x[i]);
        }
        std::array::from_fn::<f64, D, _>(|i| x[i] - x0[i])
    };
    let (delta, step) = match layout.frame::<D>(p) {
        None => {
            let delta = relax(&r, &old, D);
            (delta, delta)
        }
        Some(frame) => {
            let delta = relax(&frame.rotate(&r), &frame.rotate(&old), frame.free());
            (delta, frame.unrotate(&delta))
        }
    };
    (
        std::array::from_fn(|i| old[i] + step[i]),
        delta.iter().map(|v| v.abs()).sum(),
    )
}
