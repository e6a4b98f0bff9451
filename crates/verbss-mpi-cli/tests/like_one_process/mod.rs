//! What the tests of `verbss-mpi deform` with a `.pvtu` output share: the
//! run under `mpirun`, the single-process run it is compared with, and the
//! comparison. Each test file uses what it needs of it.
#![allow(dead_code)]

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

use verbss::deform::{Deformer, StepReport};
use verbss::motion::{Attachment, Motion};
use verbss::near_wall::Robust;
use verbss::settings::{Preset, Reference};
use verbss::Mesh;

use crate::common;

/// The mesh `path` of the repository's `assets/meshes`.
pub fn asset(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes")
        .join(path)
}

/// From each `rank R: …` line of `stdout`, sorted: the numbers that stand
/// just before each of `before` (the first, `": …"`, gives the rank).
pub fn rank_lines<const N: usize>(stdout: &str, before: [&str; N]) -> Vec<[usize; N]> {
    let number = |line: &str, before: &str| -> usize {
        let at = line
            .find(before)
            .unwrap_or_else(|| panic!("'{before}' in '{line}'"));
        let head = &line[..at];
        let start = head
            .rfind(|c: char| !c.is_ascii_digit())
            .map_or(0, |k| k + 1);
        head[start..].parse().unwrap()
    };
    let mut ranks: Vec<[usize; N]> = stdout
        .lines()
        .filter(|l| l.starts_with("rank "))
        .map(|l| before.map(|b| number(l, b)))
        .collect();
    ranks.sort_unstable();
    ranks
}

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
    let (mesh, reports, _) = single_with(
        whole,
        (group, &[]),
        motion,
        steps,
        reference,
        Robust::off(),
        Preset::Verbss,
    );
    (mesh, reports)
}

/// [`single`] with the groups `slides` sliding in their planes, the
/// near-wall treatments `robust` and the preset `preset`; also the number
/// of rigid-layer nodes.
pub fn single_with(
    whole: &Mesh,
    (group, slides): (&str, &[&str]),
    motion: Motion,
    steps: usize,
    reference: Reference,
    robust: Robust,
    preset: Preset,
) -> (Mesh, Vec<StepReport>, usize) {
    let mut settings = preset.settings(steps);
    settings.reference = reference;
    settings.robust = robust;
    settings.solve.tolerance = TOLERANCE;
    settings.solve.escalate = false;
    settings.solve.max_iterations = 100_000;
    let mut attachments: Vec<Attachment> = slides
        .iter()
        .map(|g| Attachment::slide(g, None, whole.dim).unwrap())
        .collect();
    attachments.push(Attachment {
        groups: vec![group.into()],
        motion,
    });
    let mut d = Deformer::new(whole, &attachments, settings).unwrap();
    let mut reports = vec![d.current().report.clone()];
    for n in 1..=steps {
        reports.push(d.step(n).unwrap());
    }
    (d.mesh(), reports, d.rigid_layer().0)
}

/// The motion of the arguments `motion`: `--translate D` or `--rotate A`
/// (about the axis z through `--center C` when it follows, else through
/// (0.5, 0.5, 0.5)).
fn motion_of(motion: &[&str]) -> Motion {
    match motion[0] {
        "--translate" => {
            let d: Vec<f64> = motion[1].split(',').map(|x| x.parse().unwrap()).collect();
            Motion::Translation {
                displacement: [d[0], d[1], d.get(2).copied().unwrap_or(0.0)],
            }
        }
        _ => Motion::Rotation {
            center: match motion.get(2..4) {
                Some(["--center", c]) => {
                    let c: Vec<f64> = c.split(',').map(|x| x.parse().unwrap()).collect();
                    [c[0], c[1], c.get(2).copied().unwrap_or(0.0)]
                }
                _ => [0.5, 0.5, 0.5],
            },
            axis: [0.0, 0.0, 1.0],
            angle: motion[1].parse::<f64>().unwrap().to_radians(),
        },
    }
}

/// `verbss-mpi deform MESH -o OUT --moving GROUP --method METHOD
/// --reference REFERENCE` on `np` ranks with the tests' tolerance and
/// `extra` arguments (the steps among them); asserts that it succeeds.
#[allow(clippy::too_many_arguments)]
fn run(
    np: usize,
    mesh: &Path,
    out: &Path,
    group: &str,
    method: &str,
    reference: Reference,
    extra: &[&str],
    env: &[(&str, &str)],
) -> std::process::Output {
    let reference = match reference {
        Reference::Fixed => "fixed",
        _ => "updated",
    };
    let tolerance = TOLERANCE.to_string();
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        group,
        "--method",
        method,
        "--reference",
        reference,
        "--tolerance",
        &tolerance,
        "--max-iterations",
        "100000",
    ];
    args.extend_from_slice(extra);
    let session = out.parent().unwrap();
    let o = verbss_mpi_with(np, &args, session, env);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

/// The pieces of a run on `np` ranks (`dir/moved_RANK.vtu`, or the split
/// set `dir/moved_PARTITION.msh`, partitions from 1) hold every cell
/// of `whole` once, with its tag and on the nodes of the same tags, and
/// their nodes the single-process coordinates `one` to 1e-10 of the largest
/// displacement `scale`; returns them.
fn pieces_like_one_process(
    dir: &Path,
    ext: &str,
    np: usize,
    whole: &Mesh,
    one: &Mesh,
    scale: f64,
) -> Vec<Mesh> {
    let index = node_index(whole);
    let dim = whole.dim;
    let pieces: Vec<Mesh> = (0..np)
        .map(|r| verbss::io::read(&dir.join(piece_name(ext, r))).unwrap())
        .collect();
    let cell_index: HashMap<u64, usize> = whole
        .cell_tags
        .iter()
        .enumerate()
        .map(|(c, &t)| (t, c))
        .collect();
    let node_tags = |mesh: &Mesh, c: usize| -> Vec<u64> {
        mesh.cells
            .cell(c)
            .iter()
            .map(|&v| mesh.node_tags[v])
            .collect()
    };
    let mut cells = Vec::new();
    let mut worst = 0.0f64;
    for piece in &pieces {
        cells.extend_from_slice(&piece.cell_tags);
        for (c, t) in piece.cell_tags.iter().enumerate() {
            assert_eq!(node_tags(piece, c), node_tags(whole, cell_index[t]));
        }
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
    assert_eq!(cells, all, "{ext}: {np} ranks");
    assert!(worst < 1e-10 * scale, "{ext}: {np} ranks: {worst:e}");
    pieces
}

/// The piece of rank `r`: `moved_R.vtu`, or `moved_{R+1}.msh` (partition
/// `R + 1` of a split set).
pub fn piece_name(ext: &str, r: usize) -> String {
    match ext {
        "msh" => format!("moved_{}.msh", r + 1),
        _ => format!("moved_{r}.{ext}"),
    }
}

/// Opens each MSH piece given, then merges them all: prints, as JSON, the
/// node count of each piece alone, and of the merged mesh every node entry
/// (tag and x y z, a node of several pieces once per piece) and, for its
/// elements of the top dimension and for those below, how many there are
/// and how many distinct tags they have, and per physical group (by name)
/// how many distinct element tags it has.
const GMSH_MERGE: &str = r#"
import json, sys
import gmsh
gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
alone = []
for piece in sys.argv[1:]:
    gmsh.open(piece)
    alone.append(len(gmsh.model.mesh.getNodes()[0]))
gmsh.open(sys.argv[1])
for piece in sys.argv[2:]:
    gmsh.merge(piece)
tags, xyz, _ = gmsh.model.mesh.getNodes()
nodes = [[int(t)] + [float(x) for x in xyz[3 * i:3 * i + 3]] for i, t in enumerate(tags)]
top = gmsh.model.getDimension()
def tags(dims):
    found = [int(t) for d in dims for block in gmsh.model.mesh.getElements(d)[1] for t in block]
    return [len(found), len(set(found))]
groups = {}
for d, p in gmsh.model.getPhysicalGroups():
    found = set()
    for e in set(gmsh.model.getEntitiesForPhysicalGroup(d, p)):
        for block in gmsh.model.mesh.getElements(d, e)[1]:
            found.update(int(t) for t in block)
    groups[gmsh.model.getPhysicalName(d, p)] = len(found)
summary = {"alone": alone, "nodes": nodes, "cells": tags([top]), "facets": tags(range(top)),
           "groups": groups}
print(json.dumps(summary))
gmsh.finalize()
"#;

/// Gmsh opens each of the MSH `pieces` (read by verbss as `read`) with
/// their node counts, and merges them into the whole mesh: every node of
/// `whole` (one node per tag) at the single-process coordinates `one` to
/// 1e-10 of `scale`, every cell once, no two facets with one tag, and the
/// pieces' physical groups with the facets of `whole`'s, the cells' with
/// every cell.
fn gmsh_merges(pieces: &[PathBuf], read: &[Mesh], whole: &Mesh, one: &Mesh, scale: f64) {
    let o = std::process::Command::new("python3")
        .args(["-c", GMSH_MERGE])
        .args(pieces)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let merged: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let alone: Vec<u64> = merged["alone"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_u64().unwrap())
        .collect();
    let counts: Vec<u64> = read.iter().map(|p| p.node_count() as u64).collect();
    assert_eq!(alone, counts);
    let index = node_index(whole);
    let dim = whole.dim;
    let mut tags = BTreeSet::new();
    let mut worst = 0.0f64;
    for node in merged["nodes"].as_array().unwrap() {
        let t = node[0].as_u64().unwrap();
        let g = index[&t];
        for d in 0..dim {
            let x = node[1 + d].as_f64().unwrap();
            worst = worst.max((x - one.coords[dim * g + d]).abs());
        }
        tags.insert(t);
    }
    assert_eq!(tags.len(), whole.node_count());
    assert!(worst < 1e-10 * scale, "Gmsh's merge: {worst:e}");
    let cells = whole.cell_count();
    assert_eq!(merged["cells"], serde_json::json!([cells, cells]));
    assert_eq!(merged["facets"][0], merged["facets"][1]);
    // The pieces' groups (SU2's markers too) with all their facets, and the
    // cells' own group with every cell.
    let groups = merged["groups"].as_object().unwrap();
    let names: BTreeSet<&str> = read
        .iter()
        .flat_map(|p| &p.groups)
        .map(|g| g.name.as_str())
        .collect();
    for name in &names {
        let facets = whole.group(name).unwrap().facets.len();
        assert_eq!(groups[*name], facets, "group {name}");
    }
    assert_eq!(groups.len(), names.len() + 1, "{groups:?}");
    assert!(groups.values().any(|n| *n == cells), "{groups:?}");
}

/// `verbss-mpi deform --pieces -o moved.msh` on `mesh` on 1, 2 and 3 ranks
/// (the environment variables `env` set on every rank): the MSH pieces,
/// binary exactly when `binary`, hold every cell of the file once, at the
/// single-process run's coordinates to 1e-10 of the largest displacement
/// `scale`; with python3 and gmsh, Gmsh opens each piece and merges them
/// into the whole moved mesh.
pub fn msh_pieces_like_one_process(
    mesh: &Path,
    group: &str,
    motion: &[&str],
    reference: Reference,
    scale: f64,
    binary: bool,
    env: &[(&str, &str)],
) {
    let whole = verbss::io::read(mesh).unwrap();
    let (one, _) = single(&whole, group, motion_of(motion), 2, reference);
    let gmsh = verbss_testkit::needs(
        "python3 with gmsh (pip install gmsh)",
        verbss_testkit::python(&["gmsh"]),
    );
    for np in 1..=3 {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("moved.msh");
        let mut args = vec!["--pieces", "-q", "--steps", "2"];
        args.extend_from_slice(motion);
        run(np, mesh, &out, group, "verbss", reference, &args, env);
        assert!(!out.exists(), "{}", out.display());
        let read = pieces_like_one_process(dir.path(), "msh", np, &whole, &one, scale);
        let paths: Vec<PathBuf> = (0..np)
            .map(|r| dir.path().join(piece_name("msh", r)))
            .collect();
        for path in &paths {
            let head = std::fs::read(path).unwrap();
            let format = format!("$MeshFormat\n4.1 {} 8\n", u8::from(binary));
            assert!(head.starts_with(format.as_bytes()), "{}", path.display());
        }
        if gmsh {
            gmsh_merges(&paths, &read, &whole, &one, scale);
        }
    }
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
/// rounding, the amplification to 1e-8; the header the whole mesh's node and cell counts; the solver's
/// true residual and the estimated error those of a converged solve.
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
        assert_eq!(got["substeps"], want.substeps, "{np} ranks, step {n}");
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
        // The coordinates agree to 1e-10 of the largest displacement.
        let amplification = got["amplification"].as_f64().unwrap();
        assert!(
            (amplification - want.amplification).abs() < 1e-8,
            "{np} ranks, step {n}: amplification {amplification} against {}",
            want.amplification
        );
        if n > 0 {
            // Escalating (no --omega): the accepted step's true residual
            // and estimated error.
            assert!(
                got["true_residual"].as_f64().is_some_and(|r| r >= 0.0),
                "{np} ranks, step {n}"
            );
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
    let near_wall = NearWall {
        method: "verbss",
        robust: Robust::off(),
        args: &[],
        slides: &[],
        steps: 2,
        stages: "sweeps",
    };
    deforms_like_one_process_with(mesh, group, motion, reference, scale, env, &near_wall).0
}

/// Near-wall treatments of both runs: the single process's `robust`, the
/// same as the distributed run's arguments `args`; and the number of steps.
pub struct NearWall<'a> {
    /// The method of both runs: `verbss` (with `robust`'s treatments) or
    /// `robust` (with its own, `robust` then being
    /// [`Robust::recommended`]).
    pub method: &'a str,
    /// The single-process treatments.
    pub robust: Robust,
    /// The same as `verbss-mpi deform` arguments.
    pub args: &'a [&'a str],
    /// The groups that slide in their planes (`--slide` among `args`).
    pub slides: &'a [&'a str],
    /// The steps of both runs.
    pub steps: usize,
    /// The stages rank 0's progress line names for every step: `sweeps`,
    /// or `sweeps → gmres` where an increment inverted a cell and was
    /// solved again to round-off before it was judged.
    pub stages: &'a str,
}

/// [`deforms_like_one_process`] with the near-wall treatments
/// `near_wall`; also the single-process run's number of rigid-layer nodes.
pub fn deforms_like_one_process_with(
    mesh: &Path,
    group: &str,
    motion: &[&str],
    reference: Reference,
    scale: f64,
    env: &[(&str, &str)],
    near_wall: &NearWall,
) -> (Vec<String>, usize) {
    let whole = verbss::io::read(mesh).unwrap();
    let (one, reports, layer) = single_with(
        &whole,
        (group, near_wall.slides),
        motion_of(motion),
        near_wall.steps,
        reference,
        near_wall.robust,
        near_wall.method.parse().unwrap(),
    );
    let index = node_index(&whole);
    let mut stdouts = Vec::new();
    for np in 1..=3 {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("moved.pvtu");
        let report = dir.path().join("report.json");
        let gathered = dir.path().join("all.vtu");
        let steps = near_wall.steps.to_string();
        let mut args = vec![
            "--report",
            report.to_str().unwrap(),
            "--gather",
            gathered.to_str().unwrap(),
            "--steps",
            &steps,
        ];
        args.extend_from_slice(motion);
        args.extend_from_slice(near_wall.args);
        let o = run(
            np,
            mesh,
            &out,
            group,
            near_wall.method,
            reference,
            &args,
            env,
        );
        pieces_like_one_process(dir.path(), "vtu", np, &whole, &one, scale);
        let pvtu = std::fs::read_to_string(&out).unwrap();
        assert_eq!(pvtu.matches("<Piece ").count(), np);
        reports_like_one_process(&report, &whole, &reports, np);
        gathered_like_one_process(&gathered, &whole, &one, &index, scale, np);
        let stderr = String::from_utf8_lossy(&o.stderr);
        let steps = near_wall.steps;
        for step in 1..=steps {
            let line = format!("step {step}/{steps}: {} (", near_wall.stages);
            assert_eq!(stderr.matches(&line).count(), 1, "{stderr}");
        }
        stdouts.push(String::from_utf8_lossy(&o.stdout).into_owned());
    }
    (stdouts, layer)
}
