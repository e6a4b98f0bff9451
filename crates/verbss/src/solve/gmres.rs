//! Restarted GMRES with left preconditioning (Saad & Schultz 1986), for the
//! non-symmetric ball-vertex system.
//!
//! It minimises `‖M⁻¹ (b − A x)‖₂` over the Krylov space of `M⁻¹A`; with the
//! multigrid cycle as `M⁻¹`, `M⁻¹ r ≈ A⁻¹ r` is an estimate of the error
//! itself, so the stop test `‖M⁻¹ r‖₂ / √n < threshold` bounds the
//! root-mean-square error of the unknowns rather than one sweep's change.
//! The inner product is the caller's: summed in fixed chunks on one process
//! (so the iterates do not depend on the number of threads), over the owned
//! unknowns and all-reduced over MPI ranks (`verbss-mpi`), where every rank
//! then takes the same decisions.

use rayon::prelude::*;

/// What a GMRES solve did.
pub struct Outcome {
    /// Krylov iterations (preconditioner applications after the first).
    pub iterations: usize,
    /// The last `‖M⁻¹ r‖₂ / √n`.
    pub estimate: f64,
    /// Whether it fell below the threshold.
    pub converged: bool,
    /// Whether the estimate became non-finite or grew 10⁶-fold (`x` keeps
    /// the last iterate of a completed restart).
    pub diverged: bool,
}

/// The Krylov basis and Hessenberg storage, kept between solves.
pub struct Workspace {
    basis: Vec<Vec<f64>>,
    scratch: Vec<f64>,
}

impl Workspace {
    /// Storage for vectors of length `n` and restarts every `restart` iterations.
    pub fn new(n: usize, restart: usize) -> Workspace {
        Workspace {
            basis: (0..=restart).map(|_| vec![0.0; n]).collect(),
            scratch: vec![0.0; n],
        }
    }
}

/// Solves `A x = b` from the initial guess `x`: `residual(x, out)` sets
/// `out = b − A x`, `operator(v, out)` sets `out = A v`,
/// `precondition(r, out)` sets `out = M⁻¹ r`. Stops when
/// `‖M⁻¹ r‖₂ / √dofs < threshold` or after `max_iterations` iterations;
/// `dot(a, b)` is the inner product; `history` receives that value after
/// every iteration.
#[allow(clippy::too_many_arguments)]
pub fn solve<R, A, M, S>(
    work: &mut Workspace,
    x: &mut [f64],
    dofs: usize,
    threshold: f64,
    max_iterations: usize,
    residual: R,
    operator: A,
    mut precondition: M,
    dot: S,
    mut history: Option<&mut Vec<f64>>,
) -> Outcome
where
    R: Fn(&[f64], &mut [f64]),
    A: Fn(&[f64], &mut [f64]),
    M: FnMut(&[f64], &mut [f64]),
    S: Fn(&[f64], &[f64]) -> f64,
{
    let restart = work.basis.len() - 1;
    let scale = 1.0 / (dofs.max(1) as f64).sqrt();
    let mut outcome = Outcome {
        iterations: 0,
        estimate: f64::INFINITY,
        converged: false,
        diverged: false,
    };
    let mut h = vec![vec![0.0; restart]; restart + 1];
    let mut rotations = vec![(0.0, 0.0); restart];
    let mut g = vec![0.0; restart + 1];
    let mut first = None;
    loop {
        let Workspace { basis, scratch } = work;
        residual(x, scratch);
        precondition(scratch, &mut basis[0]);
        let beta = dot(&basis[0], &basis[0]).sqrt();
        outcome.estimate = beta * scale;
        let first = *first.get_or_insert(outcome.estimate);
        if !outcome.estimate.is_finite() || outcome.estimate > 1e6 * first.max(threshold) {
            outcome.diverged = true;
            return outcome;
        }
        if outcome.estimate < threshold {
            outcome.converged = true;
            return outcome;
        }
        if outcome.iterations >= max_iterations {
            return outcome;
        }
        scale_in_place(&mut basis[0], 1.0 / beta);
        g.iter_mut().for_each(|v| *v = 0.0);
        g[0] = beta;
        let mut k = 0;
        while k < restart && outcome.iterations < max_iterations {
            operator(&basis[k], scratch);
            let (done, rest) = basis.split_at_mut(k + 1);
            let w = &mut rest[0];
            precondition(scratch, w);
            for (i, v) in done.iter().enumerate() {
                let d = dot(w, v);
                h[i][k] = d;
                w.par_iter_mut()
                    .zip(v.par_iter())
                    .for_each(|(a, b)| *a -= d * b);
            }
            let len = dot(w, w).sqrt();
            h[k + 1][k] = len;
            if len > 0.0 {
                scale_in_place(w, 1.0 / len);
            }
            for (i, &(c, s)) in rotations.iter().enumerate().take(k) {
                let (a, b) = (h[i][k], h[i + 1][k]);
                h[i][k] = c * a + s * b;
                h[i + 1][k] = -s * a + c * b;
            }
            let (a, b) = (h[k][k], h[k + 1][k]);
            let r = a.hypot(b);
            let (c, s) = if r == 0.0 { (1.0, 0.0) } else { (a / r, b / r) };
            rotations[k] = (c, s);
            h[k][k] = r;
            h[k + 1][k] = 0.0;
            g[k + 1] = -s * g[k];
            g[k] *= c;
            k += 1;
            outcome.iterations += 1;
            outcome.estimate = g[k].abs() * scale;
            if let Some(hist) = history.as_deref_mut() {
                hist.push(outcome.estimate);
            }
            if !outcome.estimate.is_finite() {
                outcome.diverged = true;
                return outcome;
            }
            if outcome.estimate < threshold || len == 0.0 {
                break;
            }
        }
        let mut y = vec![0.0; k];
        for i in (0..k).rev() {
            let s: f64 = (i + 1..k).map(|j| h[i][j] * y[j]).sum();
            y[i] = (g[i] - s) / h[i][i];
        }
        for (v, yi) in basis.iter().zip(&y) {
            x.par_iter_mut()
                .zip(v.par_iter())
                .for_each(|(a, b)| *a += yi * b);
        }
        if outcome.estimate < threshold {
            outcome.converged = true;
            return outcome;
        }
    }
}

/// `x ← s x`.
fn scale_in_place(x: &mut [f64], s: f64) {
    x.par_iter_mut().for_each(|v| *v *= s);
}
