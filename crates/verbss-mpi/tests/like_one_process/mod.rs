//! What the tests of `verbss-mpi deform` with a `.pvtu` output share: the
//! run under `mpirun`, the single-process run it is compared with, and the
//! comparison. Each test file uses what it needs of it.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::Path;

use verbss::deform::{Deformer, Preset, Reference, StepReport};
use verbss::motion::{Attachment, Motion};
use verbss::Mesh;

use crate::common;

/// `mpirun -np NP verbss-mpi ARGS…` with the environment variables `env`
/// (`mpirun -x` passes them to every rank).
pub fn verbss_mpi_with(
    np: usize,
    args: &[&str],
    session: &Path,
    env: &[(&str, &str)],
) -> std::process::Output {
    let mut command = common::mpirun(np, session);
    for (key, value) in env {
        command.env(key, value).args(["-x", key]);
    }
    command
        .arg(env!("CARGO_BIN_EXE_verbss-mpi"))
        .args(args)
        .output()
        .expect("run mpirun (Debian: openmpi-bin)")
}

/// The single-process run of the paper's method (the stepper of `verbss
/// deform --method verbss`, without escalation: the sweeps converge): the
/// moved mesh and the report of each step, 0 to `steps`, as `verbss deform
/// --report` writes them.
pub fn single(
    whole: &Mesh,
    group: &str,
    motion: Motion,
    steps: usize,
    reference: Reference,
) -> (Mesh, Vec<StepReport>) {
    let mut settings = Preset::Verbss.settings(steps);
    settings.reference = reference;
    settings.solve.tolerance = TOLERANCE;
    settings.solve.escalate = false;
    settings.solve.max_iterations = 100_000;
    let attachments = [Attachment {
        groups: vec![group.into()],
        motion,
    }];
    let mut d = Deformer::new(whole, &attachments, settings).unwrap();
    let mut reports = vec![d.current().report.clone()];
    for n in 1..=steps {
        reports.push(d.step(n).unwrap());
    }
    (d.mesh(), reports)
}

/// The `--gather` file of a distributed run holds every node once, at the
/// single-process coordinates to 1e-10 of the largest displacement
/// `scale`, and every cell once, on the nodes of the same tags.
fn gathered_like_one_process(
    path: &Path,
    whole: &Mesh,
    one: &Mesh,
    index: &HashMap<u64, usize>,
    scale: f64,
    np: usize,
) {
    let all = verbss::io::read(path).unwrap();
    let dim = whole.dim;
    let mut tags = all.node_tags.clone();
    tags.sort_unstable();
    let mut want = whole.node_tags.clone();
    want.sort_unstable();
    assert_eq!(tags, want, "{np} ranks");
    let mut worst = 0.0f64;
    for (i, t) in all.node_tags.iter().enumerate() {
        let g = index[t];
        for d in 0..dim {
            worst = worst.max((all.coords[dim * i + d] - one.coords[dim * g + d]).abs());
        }
    }
    assert!(worst < 1e-10 * scale, "{np} ranks: {worst:e}");
    let cells: HashMap<u64, Vec<u64>> = all
        .cell_tags
        .iter()
        .enumerate()
        .map(|(c, &t)| {
            (
                t,
                all.cells
                    .cell(c)
                    .iter()
                    .map(|&v| all.node_tags[v])
                    .collect(),
            )
        })
        .collect();
    assert_eq!(cells.len(), whole.cell_count(), "{np} ranks");
    for (c, t) in whole.cell_tags.iter().enumerate() {
        let nodes: Vec<u64> = whole
            .cells
            .cell(c)
            .iter()
            .map(|&v| whole.node_tags[v])
            .collect();
        assert_eq!(cells[t], nodes, "{np} ranks, cell {t}");
    }
}

/// The `--report` of a distributed run states the single-process steps'
/// quality: per step the cell count (the sum of the bins), the bins and the
/// inverted count exactly, the minimum quality to 1e-10, the mean to
/// rounding; the header the whole mesh's node and cell counts; the solver's
/// numbers the sweeps do not compute are `null`.
fn reports_like_one_process(path: &Path, whole: &Mesh, one: &[StepReport], np: usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(report["outcome"], "completed", "{np} ranks");
    assert_eq!(report["nodes"], whole.node_count(), "{np} ranks");
    assert_eq!(report["cells"], whole.cell_count(), "{np} ranks");
    let steps = report["steps"].as_array().unwrap();
    assert_eq!(steps.len(), one.len(), "{np} ranks");
    for (got, want) in steps.iter().zip(one) {
        let n = want.step;
        assert_eq!(got["step"], n, "{np} ranks");
        let bins: Vec<usize> = got["bins"]
            .as_array()
            .unwrap()
            .iter()
            .map(|b| b.as_u64().unwrap() as usize)
            .collect();
        assert_eq!(bins, want.bins, "{np} ranks, step {n}");
        assert_eq!(bins.iter().sum::<usize>(), whole.cell_count());
        assert_eq!(got["inverted"], want.inverted, "{np} ranks, step {n}");
        let min = got["min_quality"].as_f64().unwrap();
        assert!(
            (min - want.min_quality).abs() < 1e-10,
            "{np} ranks, step {n}: {min} against {}",
            want.min_quality
        );
        let mean = got["mean_quality"].as_f64().unwrap();
        assert!(
            (mean - want.mean_quality).abs() < 1e-10,
            "{np} ranks, step {n}: mean {mean} against {}",
            want.mean_quality
        );
        if n > 0 {
            // Escalating (no --omega): the accepted step's estimated error.
            assert!(got["true_residual"].is_null());
            let ratio = got["error_ratio"].as_f64().unwrap();
            assert!(
                ratio <= verbss::solve::ERROR_FRACTION,
                "{np} ranks, step {n}: {ratio}"
            );
        }
    }
}

/// Whether MPI and PT-Scotch are here (an SU2 input's path needs both);
/// otherwise the test skips.
pub fn ptscotch_ready() -> bool {
    common::mpi_ready()
        && verbss_testkit::needs(
            "PT-Scotch when verbss-mpi is built (Debian: libptscotch-dev \
             libscotchparmetis-dev, then cargo clean -p verbss-mpi)",
            verbss_mpi::ptscotch_missing().map_or(Ok(()), |why| Err(why.into())),
        )
}

/// Each node's index in `mesh` by its tag (the pieces keep the tags).
pub fn node_index(mesh: &Mesh) -> HashMap<u64, usize> {
    mesh.node_tags
        .iter()
        .enumerate()
        .map(|(i, &t)| (t, i))
        .collect()
}

/// The eq.-8 tolerance of both runs.
pub const TOLERANCE: f64 = 1e-12;

/// `verbss-mpi deform` on `mesh` with a `.pvtu` output on 1, 2 and 3 ranks
/// (the environment variables `env` set on every rank): the pieces hold
/// every cell of the file once, at the single-process run's coordinates to
/// 1e-10 of the largest displacement `scale`, its `--report` states the
/// single-process steps' quality and its `--gather` file is the
/// single-process mesh. The standard output of each run, 1 to 3
/// ranks.
pub fn deforms_like_one_process(
    mesh: &Path,
    group: &str,
    motion: &[&str],
    reference: Reference,
    scale: f64,
    env: &[(&str, &str)],
) -> Vec<String> {
    let whole = verbss::io::read(mesh).unwrap();
    let name = mesh.display();
    let motion_of = match motion[0] {
        "--translate" => {
            let d: Vec<f64> = motion[1].split(',').map(|x| x.parse().unwrap()).collect();
            Motion::Translation {
                displacement: [d[0], d[1], d.get(2).copied().unwrap_or(0.0)],
            }
        }
        _ => Motion::Rotation {
            center: [0.5, 0.5, 0.5],
            axis: [0.0, 0.0, 1.0],
            angle: motion[1].parse::<f64>().unwrap().to_radians(),
        },
    };
    let (one, reports) = single(&whole, group, motion_of, 2, reference);
    let index = node_index(&whole);
    let dim = whole.dim;
    let reference = match reference {
        Reference::Fixed => "fixed",
        _ => "updated",
    };
    let mut stdouts = Vec::new();
    for np in 1..=3 {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("moved.pvtu");
        let report = dir.path().join("report.json");
        let gathered = dir.path().join("all.vtu");
        let tolerance = TOLERANCE.to_string();
        let mut args = vec![
            "deform",
            mesh.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            group,
            "--method",
            "verbss",
            "--steps",
            "2",
            "--reference",
            reference,
            "--tolerance",
            &tolerance,
            "--max-iterations",
            "100000",
            "--report",
            report.to_str().unwrap(),
            "--gather",
            gathered.to_str().unwrap(),
        ];
        args.extend_from_slice(motion);
        let o = verbss_mpi_with(np, &args, dir.path(), env);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut cells = Vec::new();
        let mut worst = 0.0f64;
        for r in 0..np {
            let piece = verbss::io::read(&dir.path().join(format!("moved_{r}.vtu"))).unwrap();
            cells.extend_from_slice(&piece.cell_tags);
            for (i, t) in piece.node_tags.iter().enumerate() {
                let g = index[t];
                for d in 0..dim {
                    worst = worst.max((piece.coords[dim * i + d] - one.coords[dim * g + d]).abs());
                }
            }
        }
        cells.sort_unstable();
        let mut all = whole.cell_tags.clone();
        all.sort_unstable();
        assert_eq!(cells, all, "{name}: {np} ranks");
        assert!(worst < 1e-10 * scale, "{name}: {np} ranks: {worst:e}");
        let pvtu = std::fs::read_to_string(&out).unwrap();
        assert_eq!(pvtu.matches("<Piece ").count(), np);
        reports_like_one_process(&report, &whole, &reports, np);
        gathered_like_one_process(&gathered, &whole, &one, &index, scale, np);
        let stderr = String::from_utf8_lossy(&o.stderr);
        for step in ["step 1/2: sweeps (", "step 2/2: sweeps ("] {
            assert_eq!(stderr.matches(step).count(), 1, "{stderr}");
        }
        stdouts.push(String::from_utf8_lossy(&o.stdout).into_owned());
    }
    stdouts
}
