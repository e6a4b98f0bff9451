//! The exact solution of the ball-vertex system: a sparse LU factorisation
//! (faer, row pivoting with a fill-reducing column order). The system is not
//! symmetric, so neither Cholesky nor LDLᵀ apply globally.
//!
//! Unknowns are the components of the free nodes and the tangent components
//! `a` of the sliding nodes (`u = d n + T a`). With `P_i = I` for a free node
//! and `P_i = T_i` for a sliding one, the row block of node `i` is
//! `P_iᵀ K_ii P_i δ_i − Σ_j P_iᵀ B_ij P_j δ_j = P_iᵀ ρ_i(u⁰)`, solved for the
//! correction `δ` of the initial guess `u⁰`, where
//! `ρ_i(u) = Σ_j B_ij u_j − K_ii u_i` is the residual of node `i`'s equation.
//! Working on the correction keeps the prescribed normal components exact.
//!
//! faer parallelises its factorisation and solve over the calling rayon pool,
//! and their rounding depends on how the work is split; both run on a
//! one-thread pool of their own so that the reference solution is the same
//! bit for bit whatever `--threads` says.

use std::panic::AssertUnwindSafe;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers;
use faer::sparse::{SparseColMat, Triplet};

use super::{coupled, Frame, Layout};
use crate::error::{Error, Result};
use crate::geometry::{ldlt_mul, packed_index, packed_len, packed_mul, point};
use crate::springs::NodeBlocks;

/// The LU factors of the global matrix and the first unknown of each node.
pub(crate) struct Lu {
    lu: solvers::Lu<usize, f64>,
    /// `K_ii` per position, packed (projected for a sliding node).
    diag: Vec<f64>,
    start: Vec<usize>,
    /// The one-thread pool faer runs on.
    serial: rayon::ThreadPool,
}

/// The frame of position `p`, the identity for a free node.
fn frame<const D: usize>(layout: &Layout, p: usize) -> Frame<D> {
    layout.frame::<D>(p).unwrap_or_else(Frame::identity)
}

impl Lu {
    /// Assembles and factors the global matrix. `blocks.diag` holds `K_ii`
    /// (projected on the tangent frame for sliding nodes), as its LDLᵀ
    /// factor when `factored`.
    pub(crate) fn new<const D: usize>(
        layout: &Layout,
        blocks: &NodeBlocks,
        factored: bool,
    ) -> Result<Lu> {
        let s = packed_len(D);
        let m = layout.order.len();
        let diag = if factored {
            unfactor::<D>(&blocks.diag)
        } else {
            blocks.diag.clone()
        };
        let mut start = Vec::with_capacity(m + 1);
        start.push(0);
        for p in 0..m {
            start.push(start[p] + frame::<D>(layout, p).free());
        }
        let n = start[m];
        let mut entries = Vec::new();
        for p in 0..m {
            let rows = start[p + 1] - start[p];
            let k = &diag[s * p..s * (p + 1)];
            for a in 0..rows {
                for b in 0..rows {
                    entries.push(Triplet::new(
                        start[p] + a,
                        start[p] + b,
                        k[packed_index(a, b)],
                    ));
                }
            }
            let rp = frame::<D>(layout, p);
            for e in blocks.offsets[p]..blocks.offsets[p + 1] {
                let q = blocks.neighbours[e] as usize;
                let rq = frame::<D>(layout, q);
                let b = &blocks.blocks[s * e..s * (e + 1)];
                // (R_p B R_qᵀ)_ab = r_p,a · B r_q,b
                let cols = start[q + 1] - start[q];
                for (c, rqc) in rq.rows().iter().enumerate().take(cols) {
                    let bc = packed_mul::<D>(b, rqc);
                    for (a, rpa) in rp.rows().iter().enumerate().take(rows) {
                        let v: f64 = (0..D).map(|l| rpa[l] * bc[l]).sum();
                        entries.push(Triplet::new(start[p] + a, start[q] + c, -v));
                    }
                }
            }
        }
        let matrix =
            SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &entries).map_err(|e| {
                Error::InvalidMesh(format!("cannot assemble the ball-vertex matrix: {e:?}"))
            })?;
        let serial = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .map_err(|e| Error::InvalidSetting(format!("cannot start a thread: {e}")))?;
        // faer returns an error for a structurally singular matrix but panics on
        // an exact zero pivot; both mean a singular system (e.g. a sliding face
        // that nothing holds in its plane), reported as an error.
        let lu = serial
            .install(|| std::panic::catch_unwind(AssertUnwindSafe(|| matrix.sp_lu())))
            .map_err(|_| {
                Error::InvalidMesh(
                    "the ball-vertex system is singular (an exact zero pivot in its LU factorisation)"
                        .into(),
                )
            })?
            .map_err(|e| Error::InvalidMesh(format!("the ball-vertex system is singular ({e})")))?;
        Ok(Lu {
            lu,
            diag,
            start,
            serial,
        })
    }

    /// Replaces the initial guess `work` by the exact solution.
    pub(crate) fn solve<const D: usize>(
        &self,
        layout: &Layout,
        blocks: &NodeBlocks,
        constant: &[f64],
        work: &mut [f64],
    ) -> Result<()> {
        let s = packed_len(D);
        let m = layout.order.len();
        let mut rhs = vec![0.0; self.start[m]];
        for p in 0..m {
            let r = frame::<D>(layout, p);
            let b = r.rotate(&coupled::<D>(blocks, constant, p, work));
            let a0 = r.rotate(&point::<D>(work, p));
            let ka = packed_mul::<D>(&self.diag[s * p..], &a0);
            for k in 0..self.start[p + 1] - self.start[p] {
                rhs[self.start[p] + k] = b[k] - ka[k];
            }
        }
        self.serial.install(|| {
            self.lu
                .solve_in_place(faer::MatMut::from_column_major_slice_mut(
                    &mut rhs,
                    self.start[m],
                    1,
                ))
        });
        if rhs.iter().any(|v| !v.is_finite()) {
            return Err(Error::InvalidMesh(
                "the ball-vertex system is singular (its LU solve gave non-finite values)".into(),
            ));
        }
        for p in 0..m {
            let r = frame::<D>(layout, p);
            let mut delta = [0.0; D];
            let rows = self.start[p + 1] - self.start[p];
            delta[..rows].copy_from_slice(&rhs[self.start[p]..self.start[p + 1]]);
            let step = r.unrotate(&delta);
            for k in 0..D {
                work[D * p + k] += step[k];
            }
        }
        Ok(())
    }
}

/// The packed blocks `K = L D Lᵀ` of packed LDLᵀ factors ([`ldlt_mul`] on
/// the unit vectors).
fn unfactor<const D: usize>(factors: &[f64]) -> Vec<f64> {
    let s = packed_len(D);
    let mut diag = vec![0.0; factors.len()];
    for (k, f) in diag.chunks_exact_mut(s).zip(factors.chunks_exact(s)) {
        for c in 0..D {
            let column = ldlt_mul::<D>(f, &std::array::from_fn(|r| f64::from(u8::from(r == c))));
            for r in c..D {
                k[packed_index(r, c)] = column[r];
            }
        }
    }
    diag
}
