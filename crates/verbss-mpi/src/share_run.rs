//! `verbss-mpi deform` with a `.pvtu` output or `--pieces`, from a
//! partitioned MSH 4.1 input, where every rank reads only its own partitions
//! ([`verbss_mpi::share::read_rank_share`]; with `--split`, only its
//! partitions' files of a split set, [`verbss_mpi::share::read_rank_split`]),
//! or from a single-zone SU2
//! input, which rank 0 reads in one pass and scatters and PT-Scotch cuts
//! ([`verbss_mpi::scatter`], `verbss_mpi::repartition`), or from a
//! single-zone CGNS input, of which every rank reads its own blocks
//! ([`verbss_mpi::cgns_read`]) before the same cut. Then the ghost layer is
//! added ([`verbss_mpi::coupled::Ghosts`]), the rigid layer and the
//! wall-distance stiffening found on it when `--rigid-layer` or
//! `--stiffening` asks (both with the default `--method robust`,
//! [`verbss_mpi::near_wall`]), the blended rigid motion set up on each
//! part ([`crate::share_blend`]), and the flow-solver
//! entry ([`verbss_mpi::coupled::LocalSolver`]) sweeps,
//! and every rank checks and writes its own cells, as a `.vtu` piece (rank 0
//! the `.pvtu` joining them) or as its partition of a split MSH 4.1 set
//! (the form of `gmsh -part_split`) — no rank holds the
//! whole mesh (docs/distributed.md).
//!
//! Step `n` of `N` prescribes the moving nodes where the motion puts their
//! input positions at `n/N`, the rigid-layer nodes next to them where the
//! motion puts theirs (as `verbss deform` does for a translation or a
//! rotation), the other boundary nodes and the layer nodes next to a fixed
//! wall where they are; with
//! `--reference updated` the springs are on the current mesh and the solve
//! is for the increment, with `fixed` on the input mesh for the total
//! displacement. With `--substeps K` and the updated reference, a step that
//! inverts a cell or whose solve does not converge is redone in increments
//! (the step's prescribed displacements spread linearly, the springs on
//! each increment's start), halved after a failure and doubled after a
//! success down to `2^-K` of the step, as `verbss deform` does. With the
//! blend, an increment starts from its reference configuration (the
//! current mesh, or the input mesh with the fixed and anchored references)
//! moved by the blend and the springs solve what is left; where that start
//! is weak (an inverted cell, or a minimum quality below
//! [`QUALITY_DROP`] of the reference's) the plain start is solved too and
//! the better kept, as `verbss deform` does. A converged
//! solve that inverts a cell is solved again to round-off
//! ([`LocalSolver::solve_exact`]) and judged on that where it converges. A
//! step that inverts a cell (in the smallest increment) stops the run with
//! exit code 3 (the worst cell named as one process names it, the pieces
//! holding the last valid mesh and the failed state written beside them,
//! [`crate::share_write`]), a step that the
//! sweeps, GMRES preconditioned by the sweep and the safe sweeps do not
//! solve with exit code 4: without the whole mesh there is no multigrid or
//! direct solve to escalate to. Unless `--quiet`, every rank says what it holds, rank 0 the
//! rigid layer's node count and thickness, and rank 0 prints
//! the single-process progress line of each step, its quality reduced over
//! the ranks ([`verbss_mpi::step_quality`]); `--report` writes the
//! single-process report from rank 0 (`share_report`), `--gather` the
//! whole moved mesh as one `.vtu` from rank 0 (`gather`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::bail;
use verbss::deform::{Reference, QUALITY_DROP};
use verbss::io::gmsh::partitioned::{partition_count, Share};
use verbss::motion::{Clock, Frame, Motion};
use verbss::quality;
use verbss::robust::{Bounds, Layer};
use verbss::solve::{NodeRole, Stage};
use verbss_cli::deform::DeformArgs;
use verbss_cli::progress::Progress;
use verbss_mpi::coupled::{Ghosts, LocalSolver};
use verbss_mpi::near_wall::near_wall;
use verbss_mpi::ranks::Ranks;
use verbss_mpi::share::{
    global_numbers, partitions_of, prescribe, read_rank_share, read_rank_split,
};
use verbss_mpi::step_quality::inverted_error;
use verbss_mpi::Comm;

use crate::cgns;
use crate::gather;
use crate::run::told;
use crate::share_attempt::{attempt, Attempt, Solve};
use crate::share_blend::{nothing_left, PartBlend};
use crate::share_report::StepLog;
use crate::share_write::{has_extension, prepare_output, write, write_failed, written_name};
use crate::su2;

/// Whether `verbss-mpi deform` takes this path without `--pieces`: a
/// `.pvtu` output, which only a partitioned MSH 4.1, an SU2 or a CGNS
/// input is written to.
pub fn applies(args: &DeformArgs) -> bool {
    args.output().extension().is_some_and(|e| e == "pvtu")
}

/// Fails unless `input` is a partitioned MSH 4.1 file.
fn check_partitioned(input: &Path, output: &Path) -> anyhow::Result<()> {
    if has_extension(input, "msh") && partition_count(input)? > 0 {
        return Ok(());
    }
    bail!(
        "{}: a .pvtu output or --pieces is written rank by rank, from a partitioned MSH \
         4.1 input (`gmsh -part N -format msh41`), an SU2 input or a CGNS input, and {} is \
         none of them: give another output format, or partition the mesh",
        output.display(),
        input.display()
    )
}

/// This rank's share of the input, and what it says of where the share
/// comes from (the start of its line).
fn read_input(
    world: &Comm,
    input: &Path,
    output: &Path,
    split: bool,
) -> anyhow::Result<(Share, String)> {
    let share = if split {
        told(read_rank_split(world, input))?
    } else if has_extension(input, "su2") {
        return su2::read(world, input);
    } else if has_extension(input, "cgns") {
        return cgns::read(world, input);
    } else {
        check_partitioned(input, output)?;
        told(read_rank_share(world, input))?
    };
    let size = world.size() as usize;
    let partitions = partitions_of(share.partitions, size, world.rank() as usize, input)?;
    let from = format!(
        "partitions {}-{} of {}",
        partitions.start(),
        partitions.end(),
        share.partitions
    );
    Ok((share, from))
}

/// Where the motion puts input position `p` at step `step` of `steps`.
fn moved_to(motion: &Motion, p: &[f64], step: usize, steps: usize) -> verbss::Result<Vec<f64>> {
    let clock = Clock {
        step,
        steps,
        dt: 1.0,
    };
    let mut x = p.to_vec();
    motion.apply(0, &mut x, clock, &Frame::default())?;
    Ok(x)
}

/// Per node of `share`: body 0 for the nodes of the moving groups `moving`
/// (one motion moves them all: one chain, one body), none for the others.
fn moving_body(share: &Share, moving: &[String]) -> Vec<Option<usize>> {
    let mut body = vec![None; share.mesh.node_count()];
    for (_, nodes) in share.group_nodes.iter().filter(|(g, _)| moving.contains(g)) {
        for &i in nodes {
            body[i] = Some(0);
        }
    }
    body
}

/// Runs the job on every rank (see the module documentation); with
/// `gather`, rank 0 also writes the whole moved mesh there ([`gather`]).
/// With `split`, the input is the first file of a split set.
pub fn run_shares(
    args: DeformArgs,
    gather: Option<PathBuf>,
    split: bool,
) -> anyhow::Result<ExitCode> {
    let world = Comm::world();
    let root = world.rank() == 0;
    if let Some(path) = gather.as_ref().filter(|p| !has_extension(p, "vtu")) {
        bail!(
            "--gather {}: the gathered mesh is written as one .vtu file",
            path.display()
        );
    }
    let (share, from) = read_input(&world, args.mesh(), args.output(), split)?;
    let job = args.share_job(share.mesh.dim)?;
    let outputs = (&job, gather.as_deref());
    prepare_output(&world, outputs, args.mesh(), split, share.partitions)?;
    if let Some(path) = &gather {
        gather::check_tags(&world, path, &share.mesh)?;
    }
    let mesh = &share.mesh;
    job.settings.validate()?;
    let steps = job.settings.steps;
    let global = global_numbers(&share);
    let ghosts = Ghosts::new(&world, mesh, &global)?;
    let robust = &job.settings.robust;
    let near = {
        let (roles, _) = prescribe(&share, &job.moving, |_| Ok(vec![0.0; mesh.dim]))?;
        let body = moving_body(&share, &job.moving);
        near_wall(
            &world,
            mesh,
            &ghosts,
            &roles,
            &body,
            &share.group_nodes,
            robust,
        )?
    };
    let moving = moving_body(&share, &job.moving);
    // The roles, and where each node is at step `step`: the moving nodes
    // and the layer nodes next to them where the motion puts them (the
    // single process's targets, to the last bit), the others at rest.
    let at = |step| -> verbss::Result<(Vec<NodeRole>, Vec<f64>)> {
        let place = |p: &[f64]| moved_to(&job.motion, p, step, steps);
        let (mut roles, placed) = prescribe(&share, &job.moving, place)?;
        let dim = mesh.dim;
        let mut goal = mesh.coords.clone();
        for i in 0..mesh.node_count() {
            let span = dim * i..dim * (i + 1);
            if moving[i].is_some() {
                goal[span.clone()].copy_from_slice(&placed[span.clone()]);
            }
            // The layer is empty without the near-wall treatments.
            if let Some(Some(body)) = near.layer.get(i) {
                roles[i] = NodeRole::Fixed;
                if body.is_some() {
                    goal[span].copy_from_slice(&place(mesh.point(i))?);
                }
            }
        }
        Ok((roles, goal))
    };
    let (roles, _) = at(0)?;
    let orientation = quality::orientation(mesh);
    let blend = (robust.blend && comm_any(&world, moving.iter().any(Option::is_some))).then(|| {
        let moving: Vec<bool> = moving.iter().map(Option::is_some).collect();
        let follows: Vec<bool> = near
            .layer
            .iter()
            .map(|l| matches!(l, Some(Some(_))))
            .collect();
        PartBlend::new(&world, mesh, &ghosts, &roles, &moving, &follows)
    });
    let size = {
        let all: Vec<usize> = (0..mesh.node_count()).collect();
        let ranks = Ranks::of(&world, &ghosts.part, &ghosts.halo);
        Bounds::of(mesh.dim, &mesh.coords, &all)
            .reduced(&ranks)
            .diagonal()
    };
    let part_nodes = ghosts.part.node_count();
    let part_cells = ghosts.part.cells.len();
    let mut solver = LocalSolver::with_ghosts(&world, ghosts, &roles, &[])?;
    solver.set_stiffness(&near.stiffness)?;
    let mut blend = blend;
    if !job.quiet {
        println!(
            "rank {}: {from}: {} nodes and {} cells read; with the ghost layer {part_nodes} \
             nodes and {part_cells} cells",
            world.rank(),
            mesh.node_count(),
            mesh.cell_count(),
        );
        if root && robust.layer != Layer::Off {
            let t: Vec<String> = near.thickness.iter().map(|t| format!("{t:.6e}")).collect();
            println!(
                "rigid layer: {} nodes, {} thick around each body",
                near.layer_nodes,
                t.join(", ")
            );
        }
    }
    let mut coords = mesh.coords.clone();
    let mut report = StepLog::new(&world, &job, mesh, solver.part(), &orientation);
    let input_quality = report.last().min_quality;
    let progress = Progress::new(steps, job.quiet || !root);
    let mut sweeps = 0;
    let reference = job.settings.reference;
    let settings = &job.settings.solve;
    let mut solve = |springs: &[f64], base: &[f64], u: Vec<f64>, goal: &[f64], nothing: bool| {
        let to = Solve {
            springs,
            base,
            goal,
            roles: &roles,
            nothing,
        };
        attempt(&world, &mut solver, mesh, &orientation, settings, to, u)
    };
    // Every rank writes its piece of the mesh at `coords`.
    let write_at = |coords: &[f64]| {
        let output = (job.output.as_path(), job.binary);
        write(&world, output, &share, coords, &orientation)
    };
    for step in 1..=steps {
        let start = Instant::now();
        let (_, target) = at(step)?;
        // Increments of the step, halved after a failure down to `floor`
        // and doubled after a success (with a total unknown, none).
        let floor = match reference {
            Reference::Updated => 0.5f64.powi(job.settings.robust.substeps as i32),
            _ => 1.0,
        };
        let (mut done, mut h) = (0.0, 1.0);
        let mut current = coords.clone();
        let mut current_quality = report.last().min_quality;
        let mut solves = Vec::new();
        let mut increments = 0;
        let mut check_seconds = 0.0;
        // Whether the springs solved anything (else the blend moved the mesh).
        let mut swept = false;
        let (moved, mut r) = loop {
            let end = if done + h >= 1.0 { 1.0 } else { done + h };
            // Where the prescribed nodes are at the increment's end (as one
            // process puts them: `end` of the way from the step's start),
            // the configuration the increment starts from, and the
            // prescribed displacement from a configuration (zero at the
            // free nodes).
            let goal: Vec<f64> = if end == 1.0 {
                target.clone()
            } else {
                coords
                    .iter()
                    .zip(&target)
                    .map(|(a, b)| a + end * (b - a))
                    .collect()
            };
            let from: &[f64] = match reference {
                Reference::Updated => &current,
                _ => &mesh.coords,
            };
            let offset = |base: &[f64]| -> Vec<f64> {
                let dim = mesh.dim;
                let mut u = vec![0.0; base.len()];
                for i in (0..roles.len()).filter(|&i| roles[i] == NodeRole::Fixed) {
                    for k in dim * i..dim * (i + 1) {
                        u[k] = goal[k] - base[k];
                    }
                }
                u
            };
            // The springs are on the start of the increment, with the fixed
            // reference on the input mesh.
            let springs_on = |start: &'_ [f64]| -> Vec<f64> {
                match reference {
                    Reference::Fixed => mesh.coords.clone(),
                    _ => start.to_vec(),
                }
            };
            let plain_springs = springs_on(from);
            let chosen = match blend.as_mut() {
                None => solve(&plain_springs, from, offset(from), &goal, false)?,
                Some(b) => {
                    let start = b.start(&world, from, &goal);
                    let nothing = nothing_left(&world, &roles, &start, &goal, size);
                    let blended =
                        solve(&springs_on(&start), &start, offset(&start), &goal, nothing)?;
                    let reference_quality = match reference {
                        Reference::Updated => current_quality,
                        _ => input_quality,
                    };
                    let weak = blended.report.inverted > 0
                        || blended.report.min_quality < QUALITY_DROP * reference_quality;
                    if weak {
                        let plain = solve(&plain_springs, from, offset(from), &goal, false)?;
                        let (kept, mut dropped) = if plain.better_than(&blended) {
                            (plain, blended)
                        } else {
                            (blended, plain)
                        };
                        check_seconds += dropped.check_seconds;
                        swept |= dropped.swept;
                        solves.append(&mut dropped.solves);
                        kept
                    } else {
                        blended
                    }
                }
            };
            let Attempt {
                moved,
                report: r,
                solves: mut made,
                check_seconds: checked,
                swept: solved,
            } = chosen;
            check_seconds += checked;
            swept |= solved;
            let info = made.last().expect("a solve per attempt").clone();
            solves.append(&mut made);
            let failed = !info.converged || r.inverted > 0;
            if failed && h * 0.5 >= floor {
                h *= 0.5;
                continue;
            }
            increments += 1;
            if failed || end >= 1.0 {
                break (moved, r);
            }
            current_quality = r.min_quality;
            current = moved;
            done = end;
            h = (2.0 * h).min(1.0 - done);
        };
        let info = solves.pop().expect("a solve per step");
        r.check_seconds = check_seconds;
        r.step = step;
        r.substeps = increments;
        if swept {
            r.stages.push(Stage::Sweeps);
        }
        for earlier in &solves {
            r.add(earlier);
        }
        r.add(&info);
        r.converged = info.converged;
        r.true_residual = f64::NAN;
        // Estimated only where an escalating solve accepted the step.
        r.error_ratio = if job.settings.solve.escalate && info.converged {
            info.error_ratio
        } else {
            f64::NAN
        };
        r.seconds = start.elapsed().as_secs_f64();
        let inverted = r.inverted;
        report.push(r);
        if !info.converged || inverted > 0 {
            progress.finish();
            // Where the failed state cannot be written, the step's failure is
            // still said and the last valid mesh still written.
            let failed = match write_failed(&world, &job.output, mesh, &moved, &orientation) {
                Ok(path) => format!("the failed state in {}", path.display()),
                Err(e) => format!("the failed state could not be written ({e})"),
            };
            let (what, code) = if info.converged {
                let named = inverted_error(&world, mesh, &moved, &orientation, step).map_or_else(
                    || format!("step {step} inverts {inverted} cells"),
                    |e| e.to_string(),
                );
                (format!("{named}{}", smallest(floor)), 3)
            } else {
                let what = format!(
                    "step {step}: the stages {} did not converge ({} iterations in all, the \
                     last value {:e}){}; a partitioned input has no multigrid or direct solve \
                     to escalate to: raise --max-iterations, or take more --steps",
                    Stage::names(&[&[Stage::Sweeps], &info.stages[..]].concat()),
                    info.iterations,
                    info.residual,
                    smallest(floor)
                );
                (what, 4)
            };
            let message = format!(
                "{what}; the last valid mesh (step {}) is in {}; {failed}",
                step - 1,
                written_name(&job.output, world.size()),
            );
            return report.stop(&message, code, || write_at(&coords));
        }
        progress.step(report.last());
        coords = moved;
        sweeps += report.last().iterations;
    }
    progress.finish();
    write_at(&coords)?;
    if let Some(path) = &gather {
        gather::gather(&world, path, &share, solver.part(), &coords)?;
    }
    report.finish("completed")?;
    if root && !job.quiet {
        let gathered = match &gather {
            Some(path) => format!(" and the whole mesh {}", path.display()),
            None => String::new(),
        };
        println!(
            "wrote {}{gathered} ({}, {sweeps} sweeps in all)",
            written_name(&job.output, world.size()),
            match world.size() {
                1 => "1 piece".to_string(),
                p => format!("{p} pieces"),
            }
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Whether any rank says `yes` (collective).
fn comm_any(world: &Comm, yes: bool) -> bool {
    world.max(u64::from(yes)) == 1
}

/// What a failed step's message says of its increments: nothing without
/// sub-steps, else the smallest one tried, `floor` of the step.
fn smallest(floor: f64) -> String {
    if floor < 1.0 {
        format!(
            " in increments down to 1/{} of the step",
            (1.0 / floor).round()
        )
    } else {
        String::new()
    }
}
