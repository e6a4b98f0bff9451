//! The sweeps: colour by colour, each colour's nodes in parallel chunks
//! (`docs/method.md`, "Order and parallelism"), repeated until the eq.-8
//! test holds, and watched for divergence and stagnation.

use rayon::prelude::*;

use super::{Layout, SolveInfo, SolveParams, CHUNK, SUM_CHUNK};

/// Sweeps between two looks at the convergence rate.
const WINDOW: usize = 50;

/// The sweeps have diverged when the eq.-8 value exceeds this multiple of
/// the smallest value seen (or is not finite).
const GROWTH: f64 = 1e3;

/// Sweeps until the eq.-8 value is below `threshold` or `max_iterations`
/// sweeps. `update(p, work)` returns position `p`'s new displacement and the
/// sum of the absolute changes of its unknown components.
///
/// Stops early, not converged, when the sweeps diverge (an eq.-8 value that
/// is not finite or [`GROWTH`] times the smallest so far: `diverged` is set)
/// and, when `params.escalate` is set, when they stall: every [`WINDOW`]
/// sweeps the rate `ρ = (v_k / v_{k−W})^{1/W}` is measured, and the sweeps
/// stop when `ρ ≥ 0.999` or when `k + ln(threshold / v_k) / ln ρ` exceeds
/// `max_iterations` (the stop would not be reached).
#[allow(clippy::too_many_arguments)]
pub(crate) fn iterate<const D: usize, F>(
    pool: &rayon::ThreadPool,
    layout: &Layout,
    work: &mut [f64],
    next: &mut [f64],
    partials: &mut [f64],
    params: &SolveParams,
    threshold: f64,
    update: F,
) -> SolveInfo
where
    F: Fn(usize, &[f64]) -> ([f64; D], f64) + Sync,
{
    let mut info = SolveInfo::default();
    let mut smallest = f64::INFINITY;
    let mut window_start = f64::NAN;
    pool.install(|| {
        while info.iterations < params.max_iterations {
            let value =
                sweep::<D, F>(layout, work, next, partials, &update, false) / layout.dofs as f64;
            info.iterations += 1;
            info.residual = value;
            if params.record_history {
                info.history.push(value);
            }
            smallest = smallest.min(value);
            if !value.is_finite() || value > GROWTH * smallest {
                info.diverged = true;
                return;
            }
            if value < threshold {
                info.converged = true;
                return;
            }
            if params.escalate && info.iterations % WINDOW == 0 {
                if info.iterations > WINDOW
                    && stalled(
                        window_start,
                        value,
                        threshold,
                        info.iterations,
                        params.max_iterations,
                    )
                {
                    return;
                }
                window_start = value;
            }
        }
    });
    info
}

/// Whether sweeps whose eq.-8 value went from `before` to `now` over the
/// last [`WINDOW`] sweeps, `done` in all, will not reach `threshold` within
/// `limit` sweeps.
fn stalled(before: f64, now: f64, threshold: f64, done: usize, limit: usize) -> bool {
    let rate = (now / before).powf(1.0 / WINDOW as f64);
    if rate.is_nan() || rate >= 0.999 {
        return true;
    }
    let needed = (threshold / now).ln() / rate.ln();
    done as f64 + needed > limit as f64
}

/// One sweep, colour by colour (last colour first when `reverse`), each
/// colour's nodes in parallel chunks. Returns the sum of absolute changes,
/// added chunk by chunk in order.
pub(crate) fn sweep<const D: usize, F>(
    layout: &Layout,
    work: &mut [f64],
    next: &mut [f64],
    partials: &mut [f64],
    update: &F,
    reverse: bool,
) -> f64
where
    F: Fn(usize, &[f64]) -> ([f64; D], f64) + Sync,
{
    let colours = layout.colour_starts.len() - 1;
    for k in 0..colours {
        let c = if reverse { colours - 1 - k } else { k };
        let (start, end) = (layout.colour_starts[c], layout.colour_starts[c + 1]);
        let sums = &mut partials[layout.chunk_starts[c]..layout.chunk_starts[c + 1]];
        let current: &[f64] = work;
        next[D * start..D * end]
            .par_chunks_mut(D * CHUNK)
            .zip(sums.par_iter_mut())
            .enumerate()
            .for_each(|(k, (out, sum))| {
                let first = start + k * CHUNK;
                *sum = 0.0;
                for (m, u) in out.chunks_exact_mut(D).enumerate() {
                    let (value, change) = update(first + m, current);
                    u.copy_from_slice(&value);
                    *sum += change;
                }
            });
        work[D * start..D * end].copy_from_slice(&next[D * start..D * end]);
    }
    partials.iter().sum()
}

/// `Σ f(x_i)`, summed in fixed chunks and then chunk by chunk in order, so
/// that the result is the same for every number of threads.
pub(crate) fn chunked_sum(x: &[f64], f: impl Fn(f64) -> f64 + Sync) -> f64 {
    x.par_chunks(SUM_CHUNK)
        .map(|c| c.iter().map(|&v| f(v)).sum::<f64>())
        .collect::<Vec<_>>()
        .iter()
        .sum()
}

/// `Σ a_i b_i`, summed like [`chunked_sum`].
pub(crate) fn chunked_dot(a: &[f64], b: &[f64]) -> f64 {
    a.par_chunks(SUM_CHUNK)
        .zip(b.par_chunks(SUM_CHUNK))
        .map(|(x, y)| x.iter().zip(y).map(|(u, v)| u * v).sum::<f64>())
        .collect::<Vec<_>>()
        .iter()
        .sum()
}
