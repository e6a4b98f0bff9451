//! One stage's run over the unknowns: the right-hand side from the
//! prescribed nodes, the sweeps, multigrid or direct solve, and the
//! unknowns written back.

use super::{
    accel, laplacian, sor, sweep, verbss, Accel, Built, Layout, NodeRole, Scratch, SolveInfo,
    SolveParams, Stage, System,
};
use crate::error::Result;
use crate::geometry::point;
use crate::springs::NodeBlocks;

/// The largest prescribed displacement: `|u_i|` of fixed nodes, `|n·u_i|` of
/// sliding nodes.
pub(super) fn prescribed_scale(
    dim: usize,
    roles: &[NodeRole],
    normals: &[[f64; 3]],
    u: &[f64],
) -> f64 {
    let mut scale: f64 = 0.0;
    for (i, role) in roles.iter().enumerate() {
        let given = role.prescribed_dyn(normals, &u[dim * i..dim * (i + 1)]);
        scale = scale.max(given.iter().map(|v| v * v).sum::<f64>().sqrt());
    }
    scale
}

/// Forms the right-hand side, runs `stage` (the multigrid when
/// `accelerator` is given, for [`Stage::Sweeps`] and [`Stage::Multigrid`])
/// and writes the unknowns back.
pub(super) fn run<const D: usize>(
    built: &mut Built,
    pool: &rayon::ThreadPool,
    accelerator: Option<&mut accel::Accelerator>,
    displacement: &mut [f64],
    params: &SolveParams,
    threshold: f64,
    stage: Stage,
) -> Result<SolveInfo> {
    let Built {
        layout,
        system,
        lu,
        scratch,
        ..
    } = built;
    let Scratch {
        constant,
        work,
        next,
        partials,
    } = scratch;
    gather::<D>(layout, displacement, work);
    match system {
        System::Blocks {
            blocks,
            unprojected,
            ..
        } => block_constants::<D>(blocks, unprojected, layout, displacement, constant),
        System::Laplacian(w) => w.constants::<D>(layout, displacement, constant),
    }
    let omega = params.omega;
    let constant: &[f64] = constant;
    let info = if layout.len() == 0 {
        SolveInfo {
            converged: true,
            ..SolveInfo::default()
        }
    } else {
        match (&*system, stage) {
            (System::Blocks { blocks, .. }, Stage::Direct) => {
                let lu = lu.as_ref().expect("factored before the solve");
                lu.solve::<D>(layout, blocks, constant, work)?;
                SolveInfo {
                    iterations: 1,
                    converged: true,
                    ..SolveInfo::default()
                }
            }
            (
                System::Blocks {
                    blocks, factored, ..
                },
                _,
            ) => {
                let blocks: &NodeBlocks = blocks;
                let accelerated = accelerator.and_then(|accelerator| {
                    let info = pool.install(|| {
                        accelerator.solve::<D>(
                            blocks,
                            layout,
                            constant,
                            work,
                            next,
                            partials,
                            params.max_iterations,
                            threshold,
                            params.record_history,
                        )
                    });
                    // Under `auto`, a solve the multigrid could not finish is
                    // redone by plain sweeps from the same initial guess.
                    let keep = params.accel != Accel::Auto || info.converged;
                    if !keep {
                        gather::<D>(layout, displacement, work);
                    }
                    keep.then_some(info)
                });
                if let Some(info) = accelerated {
                    info
                } else if *factored {
                    sweep::iterate::<D, _>(
                        pool,
                        layout,
                        work,
                        next,
                        partials,
                        params,
                        threshold,
                        |p, w| verbss::update::<D>(blocks, layout, constant, omega, p, w),
                    )
                } else {
                    sweep::iterate::<D, _>(
                        pool,
                        layout,
                        work,
                        next,
                        partials,
                        params,
                        threshold,
                        |p, w| sor::update::<D>(blocks, layout, constant, omega, p, w),
                    )
                }
            }
            (System::Laplacian(weights), Stage::Direct) => {
                let lu = lu.as_ref().expect("factored before the solve");
                lu.solve::<D>(layout, &weights.blocks::<D>(layout), constant, work)?;
                SolveInfo {
                    iterations: 1,
                    converged: true,
                    ..SolveInfo::default()
                }
            }
            (System::Laplacian(weights), _) => {
                let weights: &laplacian::Weights = weights;
                sweep::iterate::<D, _>(
                    pool,
                    layout,
                    work,
                    next,
                    partials,
                    params,
                    threshold,
                    |p, w| weights.update::<D>(layout, constant, omega, p, w),
                )
            }
        }
    };
    if !info.diverged {
        for (p, &i) in layout.order.iter().enumerate() {
            displacement[D * i..D * (i + 1)].copy_from_slice(&work[D * p..D * (p + 1)]);
        }
    }
    Ok(info)
}

/// The initial guess by position: `work_p = displacement_{order[p]}`.
pub(super) fn gather<const D: usize>(layout: &Layout, displacement: &[f64], work: &mut [f64]) {
    for (p, &i) in layout.order.iter().enumerate() {
        work[D * p..D * (p + 1)].copy_from_slice(&displacement[D * i..D * (i + 1)]);
    }
}

/// `c_p = Σ_{j prescribed} B_pj u_j`, minus `K_pp f` for a sliding node
/// with given part `f` (`unprojected`: [`super::Frames::project_diagonal`]).
pub(super) fn block_constants<const D: usize>(
    blocks: &NodeBlocks,
    unprojected: &[f64],
    layout: &Layout,
    displacement: &[f64],
    constant: &mut [f64],
) {
    for p in 0..layout.len() {
        let mut c = blocks.prescribed_pull::<D>(p, displacement);
        let u = point::<D>(displacement, layout.order[p]);
        if let Some(kf) = layout.frames.given_pull::<D>(unprojected, p, &u) {
            for k in 0..D {
                c[k] -= kf[k];
            }
        }
        constant[D * p..D * (p + 1)].copy_from_slice(&c);
    }
}
