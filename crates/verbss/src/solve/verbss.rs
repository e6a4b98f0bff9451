//! VerBSS: the node-by-node block-SOR sweep (paper §3, appendix).
//!
//! Each unknown node's `D×D` block `K_ii` (projected on its tangent frame for
//! a sliding node) is factored once per build as LDLᵀ; a sweep then sets, node
//! by node, `u_i ← ω K_ii⁻¹ (Σ_j B_ij u_j) + (1 − ω) u_i` with two
//! triangular solves and a diagonal scaling per node (paper eq. 13).

use super::{coupled, Frame, Layout};
use crate::geometry::{ldlt_mul, ldlt_solve, packed_len, point};
use crate::springs::NodeBlocks;

/// Position `p`'s relaxed block solution and the sum of the absolute changes
/// of its unknown components. `blocks.diag` holds the LDLᵀ factors.
#[inline(always)]
pub(crate) fn update<const D: usize>(
    blocks: &NodeBlocks,
    layout: &Layout,
    constant: &[f64],
    omega: f64,
    p: usize,
    work: &[f64],
) -> ([f64; D], f64) {
    relax::<D>(
        &blocks.diag[packed_len(D) * p..],
        &coupled::<D>(blocks, constant, p, work),
        &point::<D>(work, p),
        layout.frame::<D>(p),
        omega,
    )
}

/// The residual of position `p` at `x`: `ρ_p = c_p + Σ_j B_pj x_j − K_pp x_p`
/// (`blocks.diag` holding the LDLᵀ factors of `K_pp`); for a sliding node
/// (`frame`) in its frame, the given components cleared, turned back to
/// mesh axes: its normal part never changes. With `x` a correction and
/// `constant = r`, this is `r − A x`, the residual the Krylov stages use.
pub fn residual<const D: usize>(
    blocks: &NodeBlocks,
    frame: Option<Frame<D>>,
    constant: &[f64],
    p: usize,
    x: &[f64],
) -> [f64; D] {
    let s = packed_len(D);
    let b = coupled::<D>(blocks, constant, p, x);
    let factor = &blocks.diag[s * p..s * (p + 1)];
    let xp = point::<D>(x, p);
    match frame {
        None => {
            let kx = ldlt_mul::<D>(factor, &xp);
            std::array::from_fn(|k| b[k] - kx[k])
        }
        Some(frame) => {
            let mut rb = frame.rotate(&b);
            let ka = ldlt_mul::<D>(factor, &frame.rotate(&xp));
            for k in 0..frame.free() {
                rb[k] -= ka[k];
            }
            frame.clear_given(&mut rb);
            frame.unrotate(&rb)
        }
    }
}

/// One node's update (paper eq. 13) from its LDLᵀ factor `factor`, its
/// right-hand side `r = c_i + Σ_j B_ij u_j` ([`coupled`]) and its old value:
/// `u_i ← old + ω (K_ii⁻¹ r − old)`, in the frame `frame` of a sliding
/// node, whose given components stay.
/// Returns the new value and the sum of the absolute changes.
#[inline(always)]
pub fn relax<const D: usize>(
    factor: &[f64],
    r: &[f64; D],
    old: &[f64; D],
    frame: Option<Frame<D>>,
    omega: f64,
) -> ([f64; D], f64) {
    match frame {
        None => {
            let x = ldlt_solve::<D>(factor, r);
            let delta: [f64; D] = std::array::from_fn(|k| omega * (x[k] - old[k]));
            (
                std::array::from_fn(|k| old[k] + delta[k]),
                delta.iter().map(|v| v.abs()).sum(),
            )
        }
        Some(frame) => {
            let mut b = frame.rotate(r);
            frame.clear_given(&mut b);
            let x = ldlt_solve::<D>(factor, &b);
            let a = frame.rotate(old);
            let mut delta: [f64; D] = std::array::from_fn(|k| omega * (x[k] - a[k]));
            frame.clear_given(&mut delta);
            let step = frame.unrotate(&delta);
            (
                std::array::from_fn(|k| old[k] + step[k]),
                delta.iter().map(|v| v.abs()).sum(),
            )
        }
    }
}
