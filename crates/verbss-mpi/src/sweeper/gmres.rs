//! The distributed `gmres` stage (docs/method.md, "Accepting a step"): GMRES
//! preconditioned by one symmetric VerBSS sweep, where a step goes when its
//! sweeps stall or diverge, as on one process. It builds nothing: a few
//! vectors of the rank's unknowns.
//!
//! The Krylov vectors hold every local unknown position (owned, then ghost);
//! the inner products sum the owned ones and are all-reduced, so every rank
//! takes the same decisions. The preconditioner exchanges the ghosts of
//! each colour after sweeping it, so the vectors it makes carry their
//! owners' ghost values, and GMRES only combines such vectors linearly:
//! every basis vector and iterate keeps them.

use verbss::solve::gmres::{self, Outcome, Workspace};
use verbss::solve::{krylov_stop, residual, GMRES_ITERATIONS, GMRES_RESTART};

use super::{Built, Sweeper};

/// The iterations of a solve to round-off ([`Sweeper::solve_exact`]): four
/// times the stage's, since without the whole mesh there is no multigrid or
/// direct solve to do it (400 left the NACA0012 of `assets/meshes/su2` at
/// a residual of 4e-11 of the move, 1,600 brought it to 1e-12).
pub const EXACT_ITERATIONS: usize = 4 * GMRES_ITERATIONS;
use crate::halo::swap;

impl Sweeper<'_> {
    /// GMRES on the owned unknowns of `work` (the initial guess on entry,
    /// its ghosts from their owners; the result on return), with right-hand
    /// side `constant`, stopped at [`krylov_stop`] of `threshold` and the
    /// smallest cell height of all ranks, after at most [`GMRES_ITERATIONS`];
    /// or when `exact` (a solve to round-off) at `threshold` itself, after
    /// at most [`EXACT_ITERATIONS`] (collective).
    pub(super) fn gmres<const D: usize>(
        &self,
        b: &Built,
        constant: &[f64],
        work: &mut [f64],
        threshold: f64,
        exact: bool,
    ) -> Outcome {
        let owned = b.frames.len();
        let local = b.heights.iter().fold(f64::INFINITY, |a, &h| a.min(h));
        let smallest = -self.comm.max(-local);
        let zeros = vec![0.0; D * owned];
        // `out = sign · ρ(x)` with right-hand side `c` on the owned positions.
        let residual_into = |c: &[f64], x: &[f64], out: &mut [f64], sign: f64| {
            for p in 0..owned {
                let r = residual::<D>(&b.blocks, b.frames.get::<D>(p), c, p, x);
                for (o, v) in out[D * p..D * (p + 1)].iter_mut().zip(r) {
                    *o = sign * v;
                }
            }
            out[D * owned..].fill(0.0);
        };
        let owned_dot = |x: &[f64], y: &[f64]| {
            let local: f64 = x[..D * owned]
                .iter()
                .zip(&y[..D * owned])
                .map(|(a, b)| a * b)
                .sum();
            self.comm.sum(local)
        };
        gmres::solve(
            &mut Workspace::new(work.len(), GMRES_RESTART),
            work,
            b.dofs as usize,
            if exact {
                threshold
            } else {
                krylov_stop(threshold, smallest)
            },
            if exact {
                EXACT_ITERATIONS
            } else {
                GMRES_ITERATIONS
            },
            |x, out| residual_into(constant, x, out, 1.0),
            |v, out| residual_into(&zeros, v, out, -1.0),
            |r, e| self.symmetric_sweep::<D>(b, r, e),
            owned_dot,
            None,
        )
    }

    /// `e ≈ A⁻¹ r`: from `e = 0` one VerBSS sweep with ω = 1 through the
    /// colours and one back, the ghosts of each colour exchanged after it.
    fn symmetric_sweep<const D: usize>(&self, b: &Built, r: &[f64], e: &mut [f64]) {
        e.fill(0.0);
        let colours = b.colour_starts.len() - 1;
        for c in (0..colours).chain((0..colours).rev()) {
            for p in b.colour_starts[c]..b.colour_starts[c + 1] {
                let (value, _) = self.update::<D>(b, r, 1.0, p, e);
                e[D * p..D * (p + 1)].copy_from_slice(&value);
            }
            let (send, recv) = &b.exchanges[c];
            swap(self.comm, &self.halo.ranks, send, recv, e, D);
        }
    }
}
