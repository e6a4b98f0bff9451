//! One step's solve, watched and escalated (docs/method.md, "Accepting a
//! step").
//!
//! The configured solver runs first (the VerBSS sweeps, or the multigrid
//! when [`Accel`] picks it). Under [`SolveParams::escalate`] its result is
//! accepted only when the eq.-8 test held and every node's estimated error
//! is below [`ERROR_FRACTION`] of its local cell height (`verify.rs`);
//! otherwise the next stage starts from the best iterate so far (from the
//! initial guess again when the sweeps diverged):
//!
//! * block systems (`verbss`, `spring`): on 3D meshes of at least
//!   [`GMRES_FIRST_NODES_3D`] nodes first GMRES preconditioned by one
//!   symmetric sweep ([`Stage::Gmres`]: no hierarchy, so a step it solves
//!   needs no memory beyond the sweeps' but six vectors), then
//!   GMRES around the multigrid V-cycle ([`Stage::Multigrid`]), then the
//!   sparse direct solve ([`Stage::Direct`]) where it fits
//!   ([`DIRECT_NODES_2D`], [`DIRECT_NODES_3D`]), then sweeps with ω = 1
//!   ([`Stage::SafeSweeps`]);
//! * `ball-vertex` with SOR: the direct solve;
//! * `laplacian`: the direct solve of its system, then sweeps with ω = 1,
//!   which converge on its symmetric, diagonally dominant system.
//!
//! A step no stage could solve comes back with `converged = false`; the
//! stepper turns it into [`crate::Error::NotConverged`].

use std::time::Instant;

use super::accel::Accelerator;
use super::{
    prescribed_scale, run, verify, Accel, Engine, Method, SolveInfo, SolveParams, Solver, Stage,
    System, AUTO_SWEEPS, ERROR_FRACTION,
};
use crate::error::Result;
use crate::geometry::{ldlt_factor, packed_len, point};
use crate::threads::Workers;

/// The direct solve is tried on 2D systems of at most this many unknown nodes.
pub const DIRECT_NODES_2D: usize = 400_000;
/// The same in 3D, where the factors fill in much more.
pub const DIRECT_NODES_3D: usize = 20_000;
/// GMRES iterations of the multigrid stage.
const MULTIGRID_ITERATIONS: usize = 60;
/// GMRES iterations of the sweep-preconditioned stage ([`Stage::Gmres`]),
/// each about three sweeps' work.
pub const GMRES_ITERATIONS: usize = 400;
/// Its iterations between restarts: five basis vectors, so that a step it
/// solves needs little more memory than the sweeps.
pub const GMRES_RESTART: usize = 4;
/// From this many nodes a 3D block system escalates to [`Stage::Gmres`]
/// before the multigrid, whose hierarchy would take 3–5 KB a node (more
/// than 0.6 GB here) where the sweep-preconditioned GMRES takes 0.15 KB.
/// Below it the multigrid goes first: it solves a stalled step in fewer
/// seconds (CHANGELOG.md, 2026-11-24).
pub const GMRES_FIRST_NODES_3D: usize = 150_000;
/// The multigrid stage's stop, as a fraction of the error it must reach:
/// [`ERROR_FRACTION`] of the smallest local size.
const MULTIGRID_MARGIN: f64 = 0.1;
/// An exact solve's iterative stages stop at this fraction of the step's
/// largest prescribed displacement.
pub const ROUND_OFF: f64 = 1e-12;

/// [`run`] for one dimension.
type RunIn = fn(
    &mut super::Built,
    &rayon::ThreadPool,
    Option<&mut super::accel::Accelerator>,
    &mut [f64],
    &SolveParams,
    f64,
    Stage,
) -> Result<SolveInfo>;

impl Engine {
    /// One step: solves for the unknowns of `displacement` (see the module
    /// documentation of [`crate::solve`]) on reference coordinates `coords`,
    /// escalating as [`SolveParams::escalate`] says, and says what it did.
    ///
    /// Fails with [`crate::Error::InvalidSetting`] for arrays of the wrong length,
    /// non-finite input or parameters out of range, and with
    /// [`crate::Error::InvalidMesh`] when `coords` collapse a cell (a spring of zero
    /// length) or make a node's springs singular. A solve that did not
    /// converge is not an error: `converged` is false.
    pub fn solve(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        let chain = chain(self.conn.dim, self.roles.len(), params);
        // The stage that solved the last step is where the next one starts:
        // a mesh on which the sweeps diverge does not pay for them every step.
        let from = match self.escalation {
            Some((method, k)) if method == params.method && params.escalate => k,
            _ => 0,
        };
        let info = self.solve_in_stages(
            coords,
            displacement,
            params,
            &chain[from.min(chain.len() - 1)..],
            false,
        )?;
        if params.escalate && info.converged {
            let k = info
                .stages
                .last()
                .and_then(|s| chain.iter().position(|c| c == s));
            self.escalation = Some((params.method, k.unwrap_or(0)));
        }
        Ok(info)
    }

    /// The step solved to round-off: the direct solve where it fits, else
    /// the multigrid (block systems) or ω = 1 sweeps (Laplacian) to
    /// a relative 1e-12 (`ROUND_OFF`). What the stepper does before it rejects a step for an
    /// inverted element: an inversion is never the solver's fault.
    pub fn solve_exact(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        let stages = exact_chain(self.conn.dim, self.roles.len(), params.method);
        self.solve_in_stages(coords, displacement, params, stages, true)
    }

    /// Runs each of `stages` in turn until one is accepted.
    fn solve_in_stages(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
        stages: &[Stage],
        exact: bool,
    ) -> Result<SolveInfo> {
        let start = Instant::now();
        self.check(coords, displacement, params)?;
        let rebuilt = self.prepare(coords, displacement, params)?;
        let form_seconds = start.elapsed().as_secs_f64();
        let guess = (stages.len() > 1).then(|| displacement.to_vec());
        let mut total = SolveInfo::default();
        let mut hierarchy_seconds = 0.0;
        for (k, &stage) in stages.iter().enumerate() {
            let (info, seconds, label) = match self.stage(displacement, params, stage, exact) {
                Ok(Some(done)) => done,
                Ok(None) => continue,
                Err(e) if k == 0 => return Err(e),
                // A later stage that cannot run (a hierarchy or factorisation
                // that fails) leaves the next one to try.
                Err(_) => continue,
            };
            hierarchy_seconds += seconds.unwrap_or(0.0);
            total.iterations += info.iterations;
            total.residual = info.residual;
            total.diverged |= info.diverged;
            total.history.extend(info.history);
            total.levels = total.levels.max(info.levels);
            total.hierarchy_built |= seconds.is_some();
            total.stages.push(label);
            if info.diverged {
                // What is left is the initial guess: its residual and error
                // are what a failed solve reports.
                if let Some(guess) = &guess {
                    displacement.copy_from_slice(guess);
                }
                self.verify(displacement, &mut total);
                total.converged = false;
                continue;
            }
            self.verify(displacement, &mut total);
            total.converged = info.converged
                && (stage == Stage::Direct
                    || !params.escalate
                    || total.error_ratio <= ERROR_FRACTION);
            if total.converged {
                break;
            }
        }
        total.form_seconds = form_seconds + hierarchy_seconds;
        total.seconds = start.elapsed().as_secs_f64();
        total.solve_seconds = total.seconds - total.form_seconds;
        total.rebuilt = rebuilt;
        total.hierarchy_seconds = hierarchy_seconds;
        if rebuilt {
            total.springs_seconds = self.built.as_ref().map_or(0.0, |b| b.springs_seconds);
        }
        Ok(total)
    }

    /// Starts the thread pool and (re)builds the system when `coords` or the
    /// method changed. Returns whether it was rebuilt.
    fn prepare(
        &mut self,
        coords: &[f64],
        displacement: &[f64],
        params: &SolveParams,
    ) -> Result<bool> {
        let threads = params.threads;
        if self.pool.as_ref().map(Workers::threads) != Some(threads) {
            self.pool = Some(Workers::new(threads)?);
        }
        let reuse = self
            .built
            .as_ref()
            .is_some_and(|b| b.method == params.method && b.coords == coords);
        if !reuse {
            let kept = self.built.take().and_then(|b| match b.system {
                System::Blocks { blocks, .. } if b.method == params.method => Some(blocks),
                _ => None,
            });
            let pool = self.pool.clone().expect("started above");
            let built = pool.install(|| match self.conn.dim {
                2 => self.build::<2>(coords, displacement, params.method, kept),
                _ => self.build::<3>(coords, displacement, params.method, kept),
            });
            self.built = Some(built?);
        }
        Ok(!reuse)
    }

    /// Runs one stage from `displacement`; `None` when the stage does not
    /// apply (no multigrid for the system, or too large a direct solve).
    /// Gives the solve, when a multigrid was built its seconds, and what
    /// solved it ([`Stage::Multigrid`] for sweeps the multigrid replaced).
    fn stage(
        &mut self,
        displacement: &mut [f64],
        params: &SolveParams,
        stage: Stage,
        exact: bool,
    ) -> Result<Option<(SolveInfo, Option<f64>, Stage)>> {
        let dim = self.conn.dim;
        let Engine {
            conn,
            roles,
            normals,
            built,
            pool,
            accel,
            ..
        } = self;
        let built = built.as_mut().expect("prepared");
        let pool = pool.as_ref().expect("prepared").pool();
        let scale = prescribed_scale(dim, roles, normals, displacement);
        let mut threshold = params.threshold(scale, exact);
        let factored = matches!(built.system, System::Blocks { factored: true, .. });
        let mut stage_params = params.clone();
        let mut hierarchy = None;
        let mut sweep_gmres;
        // Under `auto`, sweeps that have not converged after AUTO_SWEEPS
        // hand the step to the multigrid.
        let switching =
            stage == Stage::Sweeps && params.accel == Accel::Auto && factored && accel.may_switch();
        if switching {
            stage_params.max_iterations = params.max_iterations.min(AUTO_SWEEPS);
        }
        let mut label = stage;
        let accelerator = match stage {
            Stage::Sweeps => {
                let (a, seconds) = accel.prepare(built, pool, params, dim)?;
                hierarchy = seconds;
                if a.is_some() {
                    label = Stage::Multigrid;
                }
                a
            }
            Stage::Multigrid => {
                if !factored || built.layout.len() == 0 {
                    return Ok(None);
                }
                stage_params.accel = Accel::Amg;
                stage_params.max_iterations = MULTIGRID_ITERATIONS;
                if !exact {
                    threshold = krylov_stop(threshold, smallest(built));
                }
                match accel.prepare(built, pool, &stage_params, dim) {
                    Ok((a, seconds)) => {
                        hierarchy = seconds;
                        a
                    }
                    Err(_) => return Ok(None),
                }
            }
            Stage::Gmres => {
                if !factored || built.layout.len() == 0 {
                    return Ok(None);
                }
                stage_params.accel = Accel::None;
                stage_params.max_iterations = GMRES_ITERATIONS;
                if !exact {
                    threshold = krylov_stop(threshold, smallest(built));
                }
                sweep_gmres = Accelerator::sweep(params.method, dim * built.layout.len());
                Some(&mut sweep_gmres)
            }
            Stage::SafeSweeps => {
                stage_params.omega = 1.0;
                stage_params.accel = Accel::None;
                stage_params.max_iterations = params.max_iterations.saturating_mul(4);
                None
            }
            Stage::Direct => {
                let limit = if dim == 2 {
                    DIRECT_NODES_2D
                } else {
                    DIRECT_NODES_3D
                };
                if built.layout.len() > limit {
                    return Ok(None);
                }
                if built.lu.is_none() && built.layout.len() > 0 {
                    built.lu = Some(match dim {
                        2 => lu::<2>(built)?,
                        _ => lu::<3>(built)?,
                    });
                }
                None
            }
        };
        let run_in: RunIn = if conn.dim == 2 { run::<2> } else { run::<3> };
        let mut info = run_in(
            built,
            pool,
            accelerator,
            displacement,
            &stage_params,
            threshold,
            stage,
        )?;
        if switching && !info.converged {
            accel.switch(built.layout.len());
            let (a, seconds) = accel.prepare(built, pool, params, dim)?;
            hierarchy = seconds;
            if a.is_some() {
                label = Stage::Multigrid;
            }
            let mut rest = params.clone();
            rest.max_iterations = params.max_iterations.saturating_sub(info.iterations);
            let after = run_in(built, pool, a, displacement, &rest, threshold, stage)?;
            info = SolveInfo {
                iterations: info.iterations + after.iterations,
                history: [info.history, after.history].concat(),
                ..after
            };
        }
        Ok(Some((info, hierarchy, label)))
    }

    /// Fills the true residual and the worst estimated error of `total`
    /// from the solution in `displacement` (`verify.rs`).
    fn verify(&mut self, displacement: &[f64], total: &mut SolveInfo) {
        let Some(built) = self.built.as_mut() else {
            return;
        };
        let pool = self.pool.as_ref().expect("prepared");
        let check = pool.install(|| match self.conn.dim {
            2 => check::<2>(built, displacement),
            _ => check::<3>(built, displacement),
        });
        total.true_residual = check.true_residual;
        total.error_ratio = check.error_ratio;
        total.worst_node = built.layout.order.get(check.worst).copied().unwrap_or(0);
    }
}

/// The stages of a step's solve on a `dim`-D mesh of `nodes` nodes, in
/// order (see the module documentation).
fn chain(dim: usize, nodes: usize, params: &SolveParams) -> Vec<Stage> {
    let first = if params.method == Method::BallVertex && params.solver == Solver::Direct {
        Stage::Direct
    } else {
        Stage::Sweeps
    };
    let then: &[Stage] = match (params.escalate, params.method, params.solver) {
        (false, ..) | (_, Method::BallVertex, Solver::Direct) => &[],
        (_, Method::Verbss | Method::Spring, _) if gmres_first(dim, nodes) => &[
            Stage::Gmres,
            Stage::Multigrid,
            Stage::Direct,
            Stage::SafeSweeps,
        ],
        (_, Method::Verbss | Method::Spring, _) => {
            &[Stage::Multigrid, Stage::Direct, Stage::SafeSweeps]
        }
        (_, Method::BallVertex, Solver::Sor) => &[Stage::Direct],
        (_, Method::Laplacian, _) => &[Stage::Direct, Stage::SafeSweeps],
    };
    std::iter::once(first).chain(then.iter().copied()).collect()
}

/// The stages of a solve to round-off ([`Engine::solve_exact`]) on a
/// `dim`-D mesh of `nodes` nodes.
fn exact_chain(dim: usize, nodes: usize, method: Method) -> &'static [Stage] {
    let fits = nodes
        <= if dim == 2 {
            DIRECT_NODES_2D
        } else {
            DIRECT_NODES_3D
        };
    match method {
        Method::Laplacian if fits => &[Stage::Direct, Stage::SafeSweeps],
        Method::Laplacian => &[Stage::SafeSweeps],
        _ if fits => &[Stage::Direct, Stage::Multigrid],
        Method::BallVertex => &[Stage::Direct],
        _ if gmres_first(dim, nodes) => &[Stage::Gmres, Stage::Multigrid],
        _ => &[Stage::Multigrid, Stage::Direct],
    }
}

/// Whether a block system escalates to [`Stage::Gmres`] before the
/// multigrid: in 3D from [`GMRES_FIRST_NODES_3D`] nodes.
fn gmres_first(dim: usize, nodes: usize) -> bool {
    dim == 3 && nodes >= GMRES_FIRST_NODES_3D
}

/// The stop of a Krylov stage ([`Stage::Gmres`], [`Stage::Multigrid`]):
/// the sweeps' `threshold`, or a tenth of the error bound ([`ERROR_FRACTION`]
/// of the cell height) at the smallest cell height `smallest` if lower.
pub fn krylov_stop(threshold: f64, smallest: f64) -> f64 {
    threshold.min(MULTIGRID_MARGIN * ERROR_FRACTION * smallest)
}

/// The smallest local size of the unknowns of `built`.
fn smallest(built: &super::Built) -> f64 {
    built.heights.iter().fold(f64::INFINITY, |a, &b| a.min(b))
}

/// The LU factors of the system of `built` (the Laplacian's as blocks).
fn lu<const D: usize>(built: &super::Built) -> Result<super::direct::Lu> {
    match &built.system {
        System::Blocks {
            blocks, factored, ..
        } => super::direct::Lu::new::<D>(&built.layout, blocks, *factored),
        System::Laplacian(w) => {
            super::direct::Lu::new::<D>(&built.layout, &w.blocks::<D>(&built.layout), false)
        }
    }
}

/// [`verify::check`] of the system of `built` at `displacement`.
fn check<const D: usize>(built: &mut super::Built, displacement: &[f64]) -> verify::Check {
    let super::Built {
        layout,
        system,
        scratch,
        heights,
        ..
    } = built;
    let super::Scratch { constant, work, .. } = scratch;
    super::gather::<D>(layout, displacement, work);
    let (constant, work): (&[f64], &[f64]) = (constant, work);
    let layout: &super::Layout = layout;
    let s = packed_len(D);
    match system {
        System::Blocks {
            blocks, factored, ..
        } => {
            let factored = *factored;
            verify::check::<D, _>(work, heights, |p, w| {
                let rhs = super::coupled::<D>(blocks, constant, p, w);
                let mut factor = [0.0; 6];
                let f = &blocks.diag[s * p..s * (p + 1)];
                if factored {
                    factor[..s].copy_from_slice(f);
                } else if !ldlt_factor::<D>(f, &mut factor[..s]) {
                    return ([f64::INFINITY; D], f64::INFINITY);
                }
                verify::block_estimate::<D>(&factor, &rhs, &point::<D>(w, p), layout.frame::<D>(p))
            })
        }
        System::Laplacian(weights) => verify::check::<D, _>(work, heights, |p, w| {
            let old = point::<D>(w, p);
            let (new, _) = weights.update::<D>(layout, constant, 1.0, p, w);
            let e: [f64; D] = std::array::from_fn(|k| new[k] - old[k]);
            let sum = weights.sum(p);
            (e, e.iter().map(|v| (sum * v).powi(2)).sum())
        }),
    }
}

#[cfg(test)]
mod tests;
