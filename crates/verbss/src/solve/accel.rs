//! The accelerated solve ([`super::Accel::Amg`]): GMRES on the node-block
//! system, preconditioned by one multigrid V-cycle whose finest-level
//! smoother is the VerBSS sweep (docs/acceleration.md).
//!
//! The unknowns are the `D` components of each unknown node in mesh axes; a
//! sliding node's normal component never changes (its residual and every
//! correction are projected on its plane), so the prescribed normal
//! displacement stays exact. The residual of node `p` is
//! `ρ_p = c_p + Σ_j B_pj u_j − K_pp u_p`, projected for a sliding node.
//!
//! The multigrid hierarchy is the expensive part of the setup. It is kept
//! while the unknowns keep their order and the method its springs, and
//! reused for the next steps even when the springs are rebuilt on moved
//! coordinates (updated reference): the fine level always uses the current
//! springs, so the answer is unchanged and only the preconditioner ages. It
//! is rebuilt when the iterations a solve needs beyond the first solve after
//! the last build cost more than [`1/PAYBACK_STEPS`](PAYBACK_STEPS) of the
//! set-up: a rebuild then pays for itself within that many such steps.

use std::time::Instant;

use rayon::prelude::*;

use super::amg::Hierarchy;
use super::gmres::{self, Workspace};
use super::{
    chunked_dot, sweep, verbss, Accel, Built, Layout, Method, SolveInfo, SolveParams, CHUNK,
    GMRES_RESTART,
};
use crate::error::Result;
use crate::mesh::CellKind;
use crate::springs::NodeBlocks;

/// Krylov iterations between GMRES restarts.
const RESTART: usize = 20;
/// Relaxation factor of the finest level's VerBSS smoothing sweeps.
const SMOOTHING_OMEGA: f64 = 1.0;
/// What a hierarchy takes a node, at most (3.3–3.6 KB measured on
/// tetrahedra, BENCHMARKS.md).
const HIERARCHY_BYTES_PER_NODE: u64 = 4_096;
/// The hierarchy is rebuilt when a solve's iterations beyond its first
/// solve's cost more than its set-up over this many steps.
const PAYBACK_STEPS: f64 = 4.0;

/// What the engine keeps for the accelerated solve: the accelerator of the
/// last system, and what [`Accel::Auto`] decides by.
pub(crate) struct AccelState {
    accelerator: Option<Accelerator>,
    /// At least half the cells are triangles or tetrahedra.
    simplicial: bool,
    /// [`Accel::Auto`] could not build a multigrid for this mesh.
    declined: bool,
    /// [`Accel::Auto`] handed a step to the multigrid: it solves every later one.
    switched: bool,
}

impl AccelState {
    /// Nothing built yet, for a mesh of cells of `kinds`.
    pub(crate) fn new(kinds: &[CellKind]) -> AccelState {
        let simplices = kinds
            .iter()
            .filter(|k| matches!(k, CellKind::Triangle | CellKind::Tetra))
            .count();
        AccelState {
            accelerator: None,
            simplicial: 2 * simplices >= kinds.len(),
            declined: false,
            switched: false,
        }
    }

    /// Under [`Accel::Auto`], whether a step's plain sweeps stop after
    /// [`super::AUTO_SWEEPS`] to hand the step to the multigrid: on a mesh
    /// of mostly triangles or tetrahedra, until the multigrid took over or
    /// was declined.
    pub(crate) fn may_switch(&self) -> bool {
        self.simplicial && !self.declined && !self.switched
    }

    /// Whether a multigrid hierarchy is kept (for the order of the unknowns
    /// it was built on).
    pub(crate) fn has_hierarchy(&self) -> bool {
        self.accelerator
            .as_ref()
            .is_some_and(|a| matches!(a.preconditioner, Preconditioner::Multigrid { .. }))
    }

    /// Under [`Accel::Auto`], the multigrid of `unknowns` nodes solves this
    /// step and the next, unless its hierarchy would take more than half
    /// the memory available: then the sweeps go on, for the rest of the run.
    pub(crate) fn switch(&mut self, unknowns: usize) {
        let fits = available_memory()
            .is_none_or(|bytes| HIERARCHY_BYTES_PER_NODE * unknowns as u64 <= bytes / 2);
        self.switched = fits;
        self.declined = !fits;
    }

    /// Whether the solve of `built` with `params` uses the multigrid: the
    /// accelerator to use (`None`: plain sweeps), built first when the kept
    /// one does not fit, with the seconds that took (`None`: nothing built).
    /// Under [`Accel::Auto`] it is used once [`AccelState::switch`]ed, and a
    /// hierarchy that cannot be built means plain sweeps for the rest of
    /// the run.
    pub(crate) fn prepare(
        &mut self,
        built: &Built,
        pool: &rayon::ThreadPool,
        params: &SolveParams,
        dim: usize,
    ) -> Result<(Option<&mut Accelerator>, Option<f64>)> {
        let unknowns = built.layout.order.len();
        let wanted = unknowns > 0
            && matches!(params.method, Method::Verbss | Method::Spring)
            && match params.accel {
                Accel::None => false,
                Accel::Amg => true,
                Accel::Auto => self.switched && !self.declined,
            };
        if !wanted {
            return Ok((None, None));
        }
        let mut seconds = None;
        if !self
            .accelerator
            .as_ref()
            .is_some_and(|a| a.fits(params.method, &built.layout))
        {
            self.accelerator = None;
            let started = Instant::now();
            let method = params.method;
            match pool.install(|| match dim {
                2 => Accelerator::new::<2>(built, method),
                _ => Accelerator::new::<3>(built, method),
            }) {
                Ok(mut a) => {
                    let built_in = started.elapsed().as_secs_f64();
                    a.set_up_in(built_in);
                    self.accelerator = Some(a);
                    seconds = Some(built_in);
                }
                Err(_) if params.accel == Accel::Auto => {
                    self.declined = true;
                    return Ok((None, None));
                }
                Err(e) => return Err(e),
            }
        }
        Ok((self.accelerator.as_mut(), seconds))
    }
}

/// What preconditions GMRES.
enum Preconditioner {
    /// One multigrid V-cycle.
    Multigrid {
        hierarchy: Box<Hierarchy>,
        /// Iterations of the first solve after the hierarchy was built.
        baseline: Option<usize>,
        /// Seconds the hierarchy took to build.
        setup_seconds: f64,
        /// Rebuild before the next solve.
        stale: bool,
    },
    /// One symmetric VerBSS sweep for `A e = r` from `e = 0` (forward, then
    /// backward): the V-cycle's finest smoothing alone, no hierarchy
    /// ([`super::Stage::Gmres`]).
    Sweep,
}

/// The preconditioner and the vectors the accelerated solve keeps between steps.
pub(crate) struct Accelerator {
    preconditioner: Preconditioner,
    method: Method,
    workspace: Workspace,
    /// A zero right-hand side, for the product `A v = −ρ(v)` with `c = 0`.
    zeros: Vec<f64>,
}

impl Accelerator {
    /// Whether this accelerator can serve a solve of `method` on `layout`.
    fn fits(&self, method: Method, layout: &Layout) -> bool {
        self.method == method
            && matches!(&self.preconditioner, Preconditioner::Multigrid { hierarchy, stale: false, .. }
                if hierarchy.order == layout.order)
    }

    /// Builds the hierarchy for the system of `built` (on its pool).
    fn new<const D: usize>(built: &Built, method: Method) -> Result<Accelerator> {
        let super::System::Blocks { blocks, .. } = &built.system else {
            unreachable!("the accelerated solve works on spring blocks")
        };
        let hierarchy = Hierarchy::new::<D>(blocks, &built.layout, &built.coords)?;
        let n = D * built.layout.order.len();
        Ok(Accelerator {
            preconditioner: Preconditioner::Multigrid {
                hierarchy: Box::new(hierarchy),
                baseline: None,
                setup_seconds: 0.0,
                stale: false,
            },
            method,
            workspace: Workspace::new(n, RESTART),
            zeros: vec![0.0; n],
        })
    }

    /// Records that the hierarchy took `seconds` to build.
    fn set_up_in(&mut self, seconds: f64) {
        if let Preconditioner::Multigrid { setup_seconds, .. } = &mut self.preconditioner {
            *setup_seconds = seconds;
        }
    }

    /// GMRES preconditioned by one symmetric VerBSS sweep, for `unknowns`
    /// values: [`GMRES_RESTART`] + 3 vectors, built in no time.
    pub(crate) fn sweep(method: Method, unknowns: usize) -> Accelerator {
        Accelerator {
            preconditioner: Preconditioner::Sweep,
            method,
            workspace: Workspace::new(unknowns, GMRES_RESTART),
            zeros: vec![0.0; unknowns],
        }
    }

    /// Solves the system of `built` for `work` (the initial guess on entry)
    /// with right-hand side `constant`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve<const D: usize>(
        &mut self,
        blocks: &NodeBlocks,
        layout: &Layout,
        constant: &[f64],
        work: &mut [f64],
        next: &mut [f64],
        partials: &mut [f64],
        max_iterations: usize,
        threshold: f64,
        record_history: bool,
    ) -> SolveInfo {
        let started = Instant::now();
        let mut history = Vec::new();
        let Accelerator {
            preconditioner,
            workspace,
            zeros,
            ..
        } = self;
        let zeros: &[f64] = zeros;
        let mut smooth = |e: &mut [f64], r: &[f64], reverse: bool| {
            sweep::<D, _>(
                layout,
                e,
                next,
                partials,
                &|p, w| verbss::update::<D>(blocks, layout, r, SMOOTHING_OMEGA, p, w),
                reverse,
            );
        };
        let outcome = gmres::solve(
            workspace,
            work,
            layout.dofs,
            threshold,
            max_iterations,
            |x, out| residual::<D>(blocks, layout, constant, x, out),
            |v, out| {
                residual::<D>(blocks, layout, zeros, v, out);
                out.par_iter_mut().for_each(|x| *x = -*x);
            },
            |rhs, out| match preconditioner {
                Preconditioner::Multigrid { hierarchy, .. } => hierarchy.vcycle(
                    rhs,
                    out,
                    &mut smooth,
                    |r: &[f64], e: &[f64], out: &mut [f64]| {
                        residual::<D>(blocks, layout, r, e, out);
                    },
                ),
                Preconditioner::Sweep => {
                    out.fill(0.0);
                    smooth(out, rhs, false);
                    smooth(out, rhs, true);
                }
            },
            chunked_dot,
            record_history.then_some(&mut history),
        );
        let seconds = started.elapsed().as_secs_f64();
        if let Preconditioner::Multigrid {
            baseline,
            setup_seconds,
            stale,
            ..
        } = &mut self.preconditioner
        {
            match *baseline {
                None => *baseline = Some(outcome.iterations),
                Some(b) => {
                    let extra = outcome.iterations.saturating_sub(b) as f64;
                    let per_iteration = seconds / outcome.iterations.max(1) as f64;
                    *stale = extra * per_iteration > *setup_seconds / PAYBACK_STEPS;
                }
            }
        }
        SolveInfo {
            iterations: outcome.iterations,
            residual: outcome.estimate,
            converged: outcome.converged,
            diverged: outcome.diverged,
            solve_seconds: seconds,
            history,
            levels: match &self.preconditioner {
                Preconditioner::Multigrid { hierarchy, .. } => hierarchy.levels(),
                Preconditioner::Sweep => 1,
            },
            ..SolveInfo::default()
        }
    }
}

/// `out_p = ρ_p(x)` for every position ([`verbss::residual`]). With `x` a
/// correction and `constant = r`, this is `r − A x`.
fn residual<const D: usize>(
    blocks: &NodeBlocks,
    layout: &Layout,
    constant: &[f64],
    x: &[f64],
    out: &mut [f64],
) {
    out.par_chunks_mut(D * CHUNK)
        .enumerate()
        .for_each(|(t, chunk)| {
            for (k, o) in chunk.chunks_exact_mut(D).enumerate() {
                let p = t * CHUNK + k;
                o.copy_from_slice(&verbss::residual::<D>(
                    blocks,
                    layout.frame::<D>(p),
                    constant,
                    p,
                    x,
                ));
            }
        });
}

/// The memory the system says is available (`MemAvailable` of
/// `/proc/meminfo`, Linux), in bytes; `None` where it cannot tell.
fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
