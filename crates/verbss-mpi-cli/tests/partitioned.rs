//! The distributed read of a partitioned MSH 4.1 file written by Gmsh
//! (`assets/meshes/gmsh/*_part3_*.msh`, 3 partitions, made by
//! `scripts/make_partitioned_fixtures.py`) on 1, 2 and 3 ranks: each rank
//! reads only its partitions ([`verbss_mpi::share::read_rank_share`]), the
//! flow-solver entry ([`verbss_mpi::coupled::LocalSolver`]) adds the ghost
//! layer, and the solve of a translated group gives the single-process
//! exact solution.
//!
//! Each rank's node and cell counts — of what it read, and of its part with
//! ghosts — are asserted against counts made here on one process from the
//! whole file: the shares' cells are its partitions' (Gmsh's own numbers,
//! `partitions.json`), and the part holds every cell with a node the rank
//! owns (the lowest rank holding a node owns it) plus its own cells.
//!
//! The test re-runs this test binary under `mpirun` with the ignored
//! `worker` test, which writes each rank's counts and displacements to a
//! file. Without MPI (in this build or `mpirun`) the tests skip with a notice.

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

use verbss::io::gmsh::partitioned::{partition_count, read_share};
use verbss::settings::Reference;
use verbss::solve::{default_roles, Engine, Method, SolveParams, Solver};
use verbss::Mesh;
use verbss_mpi::share::partitions_of;

mod common;
mod like_one_process;

use like_one_process::{deforms_like_one_process, node_index, verbss_mpi_with};

/// `mpirun -np NP verbss-mpi ARGS…`.
fn verbss_mpi(np: usize, args: &[&str], session: &Path) -> std::process::Output {
    verbss_mpi_with(np, args, session, &[])
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes/gmsh")
        .join(name)
}

/// The prescribed displacement of the moving group: a translation.
fn translation(dim: usize) -> Vec<f64> {
    [0.02, 0.01, 0.005][..dim].to_vec()
}

/// Worker, one per rank (run by `mpirun` from the tests below): reads this
/// rank's share, solves, and writes `counts SHARE_NODES SHARE_CELLS
/// PART_NODES PART_CELLS` then `tag u…` lines in `$VERBSS_MPI_OUT.RANK`.
#[cfg(with_mpi)]
#[test]
#[ignore = "run under mpirun by the other tests"]
fn worker() {
    use verbss_mpi::coupled::LocalSolver;
    use verbss_mpi::share::{global_numbers, prescribe, read_rank_share, read_rank_split};

    let mpi = verbss_mpi::Mpi::init().unwrap();
    let world = mpi.world();
    let path = PathBuf::from(std::env::var("VERBSS_MPI_MESH").unwrap());
    let group = std::env::var("VERBSS_MPI_GROUP").unwrap();
    let out = std::env::var("VERBSS_MPI_OUT").unwrap();
    let share = match std::env::var_os("VERBSS_MPI_SPLIT") {
        Some(_) => read_rank_split(&world, &path).unwrap(),
        None => read_rank_share(&world, &path).unwrap(),
    };
    let dim = share.mesh.dim;
    let (roles, mut u) = prescribe(&share, &[group], |_| Ok(translation(dim))).unwrap();
    let global = global_numbers(&share);
    let mut solver = LocalSolver::new(&world, &share.mesh, &global, &roles, &[]).unwrap();
    let mut params = SolveParams::default();
    params.tolerance = 1e-13;
    params.max_iterations = 100_000;
    let info = solver.solve(&share.mesh.coords, &mut u, &params).unwrap();
    assert!(info.converged, "{info:?}");
    let part = solver.part();
    let mut text = format!(
        "counts {} {} {} {}\n",
        share.mesh.node_count(),
        share.mesh.cell_count(),
        part.node_count(),
        part.cells.len()
    );
    for (i, &tag) in share.mesh.node_tags.iter().enumerate() {
        text += &tag.to_string();
        for d in 0..dim {
            text += &format!(" {:e}", u[dim * i + d]);
        }
        text += "\n";
    }
    std::fs::write(format!("{out}.{}", world.rank()), text).unwrap();
}

/// What one rank wrote.
struct Rank {
    /// Nodes and cells read; nodes and cells of the part with its ghosts.
    counts: [usize; 4],
    /// Node tag → displacement.
    u: HashMap<u64, Vec<f64>>,
}

/// Runs the worker on `np` ranks, reading `name` or, when given, the split
/// set whose first file is `split`.
fn distributed(np: usize, name: &str, split: Option<&str>, group: &str) -> Vec<Rank> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("u");
    let mut mpirun = common::mpirun(np, dir.path());
    if split.is_some() {
        mpirun.env("VERBSS_MPI_SPLIT", "1");
    }
    let o = mpirun
        .env("VERBSS_MPI_MESH", fixture(split.unwrap_or(name)))
        .env("VERBSS_MPI_GROUP", group)
        .env("VERBSS_MPI_OUT", &out)
        .arg(std::env::current_exe().unwrap())
        .args(["worker", "--exact", "--ignored", "--test-threads", "1"])
        .output()
        .expect("run mpirun (Debian: openmpi-bin)");
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (0..np)
        .map(|r| {
            let text = std::fs::read_to_string(format!("{}.{r}", out.display())).unwrap();
            let mut lines = text.lines();
            let counts: Vec<usize> = lines.next().unwrap()[7..]
                .split(' ')
                .map(|x| x.parse().unwrap())
                .collect();
            let u = lines
                .map(|l| {
                    let mut parts = l.split(' ');
                    let tag = parts.next().unwrap().parse().unwrap();
                    (tag, parts.map(|x| x.parse().unwrap()).collect())
                })
                .collect();
            Rank {
                counts: counts.try_into().unwrap(),
                u,
            }
        })
        .collect()
}

/// The counts each of `np` ranks must have, from the whole mesh: the
/// nodes and cells of its partitions, and of its part with ghosts.
fn expected_counts(whole: &Mesh, name: &str, np: usize) -> Vec<[usize; 4]> {
    let path = fixture(name);
    let index = node_index(whole);
    let cell_index: HashMap<u64, usize> = whole
        .cell_tags
        .iter()
        .enumerate()
        .map(|(c, &t)| (t, c))
        .collect();
    let gmsh: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fixture("partitions.json")).unwrap())
            .unwrap();
    let partitions = partition_count(&path).unwrap();
    let shares: Vec<_> = (0..np)
        .map(|r| read_share(&path, partitions_of(partitions, np, r, &path).unwrap()).unwrap())
        .collect();
    let mut owner = vec![usize::MAX; whole.node_count()];
    for (r, s) in shares.iter().enumerate().rev() {
        for t in &s.mesh.node_tags {
            owner[index[t]] = r;
        }
    }
    (0..np)
        .map(|r| {
            let s = &shares[r];
            let gmsh_cells: u64 = partitions_of(partitions, np, r, &path)
                .unwrap()
                .map(|p| gmsh[name][p.to_string()]["cells"].as_u64().unwrap())
                .sum();
            assert_eq!(s.mesh.cell_count() as u64, gmsh_cells, "rank {r}");
            let mut cells: BTreeSet<usize> =
                s.mesh.cell_tags.iter().map(|t| cell_index[t]).collect();
            cells.extend(
                (0..whole.cell_count())
                    .filter(|&c| whole.cells.cell(c).iter().any(|&v| owner[v] == r)),
            );
            let nodes: BTreeSet<usize> = cells
                .iter()
                .flat_map(|&c| whole.cells.cell(c).to_vec())
                .collect();
            [
                s.mesh.node_count(),
                s.mesh.cell_count(),
                nodes.len(),
                cells.len(),
            ]
        })
        .collect()
}

/// The exact solution on one process (sparse LU), by node tag.
fn direct(whole: &Mesh, group: &str) -> HashMap<u64, Vec<f64>> {
    let dim = whole.dim;
    let roles = default_roles(whole);
    let mut u = vec![0.0; dim * whole.node_count()];
    for i in whole.group(group).unwrap().nodes() {
        u[dim * i..dim * (i + 1)].copy_from_slice(&translation(dim));
    }
    let mut engine = Engine::new(whole, &roles, &[]).unwrap();
    let mut params = SolveParams::default();
    params.method = Method::BallVertex;
    params.solver = Solver::Direct;
    engine.solve(&whole.coords, &mut u, &params).unwrap();
    (0..whole.node_count())
        .map(|i| (whole.node_tags[i], u[dim * i..dim * (i + 1)].to_vec()))
        .collect()
}

/// On 1, 2 and 3 ranks: the counts, and the displacements against the
/// single-process exact solution (relative to the translation's length)
/// and against 1 rank; the ranks read `name`, or the split set of the same
/// partitions whose first file is `split`.
fn reads_and_solves(name: &str, split: Option<&str>, group: &str) {
    let whole = verbss::io::read(&fixture(name)).unwrap();
    let exact = direct(&whole, group);
    let scale = translation(whole.dim)
        .iter()
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt();
    let mut one: HashMap<u64, Vec<f64>> = HashMap::new();
    for np in 1..=3 {
        let ranks = distributed(np, name, split, group);
        let want = expected_counts(&whole, name, np);
        for (r, rank) in ranks.iter().enumerate() {
            assert_eq!(rank.counts, want[r], "{name}: rank {r} of {np}");
            if np > 1 {
                assert!(
                    rank.counts[2] < whole.node_count(),
                    "{name}: rank {r} of {np}"
                );
            }
        }
        let mut u: HashMap<u64, Vec<f64>> = HashMap::new();
        for rank in &ranks {
            for (tag, v) in &rank.u {
                if let Some(w) = u.insert(*tag, v.clone()) {
                    assert_eq!(&w, v, "{name}: node {tag} on two ranks");
                }
            }
        }
        assert_eq!(
            u.len(),
            whole.node_count(),
            "{name}: every node on some rank"
        );
        for (tag, v) in &u {
            for (a, b) in v.iter().zip(&exact[tag]) {
                assert!(
                    (a - b).abs() < 1e-10 * scale,
                    "{name}, {np} ranks: node {tag}: {a} against {b}"
                );
            }
            if np == 1 {
                continue;
            }
            for (a, b) in v.iter().zip(&one[tag]) {
                assert!(
                    (a - b).abs() < 1e-12 * scale,
                    "{name}, {np} ranks against 1: node {tag}"
                );
            }
        }
        if np == 1 {
            one = u;
        }
    }
}

#[test]
fn gmsh_partitioned_channel_read_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    reads_and_solves("channel_hole_part3_v41_ascii.msh", None, "wall");
}

/// The same channel in the files of `gmsh -part 3 -part_split`, one a
/// partition: each rank reads only its partitions' files and holds what it
/// holds from the single file.
#[test]
fn gmsh_split_channel_read_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    let first = "channel_hole_split3_v41_ascii_1.msh";
    reads_and_solves("channel_hole_part3_v41_ascii.msh", Some(first), "wall");
}

/// The box cut in 6 in the files of `-part_split`, where nodes that
/// elements of one partition use lie on partition boundary entities that
/// do not list it: each rank reads its 2 to 6 files and holds what it holds
/// from the single file.
#[test]
fn gmsh_split_box_cut_in_six_read_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    let first = "box_split6_v41_ascii_1.msh";
    reads_and_solves("box_part6_v41_ascii.msh", Some(first), "inlet");
}

#[test]
fn gmsh_partitioned_box_read_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    reads_and_solves("box_part3_v41_binary.msh", None, "inlet");
}

#[test]
fn deform_a_partitioned_channel_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    let motion = ["--translate", "0.02,0.01"];
    deforms_like_one_process(
        &fixture("channel_hole_part3_v41_ascii.msh"),
        "wall",
        &motion,
        Reference::Updated,
        scale,
        &[],
    );
}

#[test]
fn deform_a_partitioned_box_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    // 3 degrees about the box's axis: the inlet's corners move by
    // 0.5·√2·sin 3° ≈ 0.037.
    let motion = [
        "--rotate",
        "3",
        "--center",
        "0.5,0.5,0.5",
        "--axis",
        "0,0,1",
    ];
    deforms_like_one_process(
        &fixture("box_part3_v41_binary.msh"),
        "inlet",
        &motion,
        Reference::Fixed,
        0.037,
        &[],
    );
}

/// The box cut in 6, where Gmsh puts nodes that elements of one partition
/// use on partition boundary entities that do not list it, and nodes of the
/// inlet's edges on entities whose parent is only the face beside it: each
/// rank reads those nodes in a second pass and the ranks join their groups,
/// so the translated inlet moves as on one process.
#[test]
fn deform_a_box_cut_in_six_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    deforms_like_one_process(
        &fixture("box_part6_v41_ascii.msh"),
        "inlet",
        &["--translate", "0.1,0,0"],
        Reference::Updated,
        0.1,
        &[],
    );
}

/// Refused with exit code 2 and one message: more ranks than partitions,
/// an input that is not partitioned, an error only rank 1 reads, the
/// near-wall treatments, an option that needs the whole mesh, `--gather`
/// to another format than `.vtu` or with a whole-mesh output, no steps, an
/// output folder that does not exist.
#[test]
fn deform_refuses_a_partitioned_input_it_cannot_run() {
    if !common::mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("moved.pvtu");
    let name = "channel_hole_part3_v41_ascii.msh";
    let refused = |np: usize, mesh: &Path, extra: &[&str], message: &str| {
        let mut args = vec![
            "deform",
            mesh.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "wall",
            "--translate",
            "0.02,0.01",
        ];
        args.extend_from_slice(extra);
        let o = verbss_mpi(np, &args, dir.path());
        assert_eq!(o.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(stderr.matches(message).count(), 1, "{stderr}");
    };
    let verbss = ["--method", "verbss"];
    refused(
        4,
        &fixture(name),
        &verbss,
        "has 3 partitions, fewer than the 4 ranks",
    );
    refused(
        2,
        &fixture(name),
        &["--method", "laplacian"],
        "which runs --method robust, verbss or spring",
    );
    let gather = ["--method", "verbss", "--gather", "all.msh"];
    refused(
        2,
        &fixture(name),
        &gather,
        "--gather all.msh: the gathered mesh is written as one .vtu file",
    );
    // An element tag above 2^53 (the last element's, rank 1's of 2) does
    // not travel exactly as a double.
    let text = std::fs::read_to_string(fixture(name)).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let end = lines.iter().position(|l| l == "$EndElements").unwrap();
    let last = lines[end - 1].split_once(' ').unwrap().1.to_string();
    lines[end - 1] = format!("9007199254740993 {last}");
    let header = lines.iter().position(|l| l == "$Elements").unwrap() + 1;
    let blocks = lines[header]
        .split(' ')
        .take(3)
        .collect::<Vec<_>>()
        .join(" ");
    lines[header] = format!("{blocks} 9007199254740993");
    let huge = dir.path().join("huge_tag.msh");
    std::fs::write(&huge, lines.join("\n") + "\n").unwrap();
    let gather = ["--method", "verbss", "--gather", "all.vtu"];
    refused(2, &huge, &gather, "above 2^53 cannot be gathered");
    // The whole-mesh path writes the whole mesh already.
    let plain = fixture("channel_hole_v41_ascii.msh");
    let whole_out = dir.path().join("moved.msh");
    let args = [
        "deform",
        plain.to_str().unwrap(),
        "-o",
        whole_out.to_str().unwrap(),
        "--moving",
        "wall",
        "--translate",
        "0.02,0.01",
        "--gather",
        "all.vtu",
    ];
    let o = verbss_mpi(2, &args, dir.path());
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    let message = "--gather all.vtu: only a .pvtu output";
    assert_eq!(stderr.matches(message).count(), 1, "{stderr}");
    // Pieces whose folder cannot be made (a file stands in its place):
    // every rank stops before the solve, rank 0 says why.
    let blocked = dir.path().join("blocked");
    std::fs::write(&blocked, "").unwrap();
    let nowhere = blocked.join("moved.pvtu");
    let mesh = fixture(name);
    let args = [
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        nowhere.to_str().unwrap(),
        "--moving",
        "wall",
        "--translate",
        "0.02,0.01",
        "--method",
        "verbss",
        "-q",
    ];
    let o = verbss_mpi(2, &args, dir.path());
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    let said = format!("error: {}: cannot make the folder: ", blocked.display());
    assert_eq!(stderr.matches(&said).count(), 1, "{stderr}");
    let steps = ["--method", "verbss", "--steps", "0"];
    refused(
        2,
        &fixture(name),
        &steps,
        "the number of steps must be at least 1",
    );
    let plain = fixture("channel_hole_v41_ascii.msh");
    let not_partitioned = "is none of them: give another output format";
    refused(2, &plain, &verbss, not_partitioned);
    let v22 = fixture("channel_hole_v22_ascii.msh");
    refused(2, &v22, &verbss, "MSH 2.2 has no partitioned entities");
    // A bad node tag in the last element block, on entity 6 of dimension 2
    // in partition 2 (quadrangles): rank 1 of 2 reads it, rank 0 steps over
    // it; both name its line, and rank 0, the lowest, is heard.
    let text = std::fs::read_to_string(fixture(name)).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let block = lines.iter().position(|l| l.trim() == "2 6 3 36").unwrap();
    lines[block + 1] = "1 2 x 4 5".into();
    let bad = dir.path().join("bad.msh");
    std::fs::write(&bad, lines.join("\n") + "\n").unwrap();
    let want = format!(
        "error: {}:{}: an element block: expected a number, found 'x'",
        bad.display(),
        block + 2
    );
    refused(2, &bad, &verbss, &want);
}

/// A step that inverts a cell (the hole pushed through the top wall) stops
/// with exit code 3, sweeps that do not converge with exit code 4: one
/// message each, the report ends with the failed step, the pieces hold
/// the last valid mesh, the input, and the failed state is written as
/// pieces too.
#[test]
fn deform_stops_at_an_inverted_cell_and_at_unconverged_sweeps() {
    if !common::mpi_ready() {
        return;
    }
    let name = "channel_hole_part3_v41_ascii.msh";
    let whole = verbss::io::read(&fixture(name)).unwrap();
    let mesh = fixture(name);
    let index = node_index(&whole);
    for (extra, code, message) in [
        (
            vec!["--translate", "0,0.45", "--max-iterations", "100000"],
            3,
            "error: step 1: element ",
        ),
        // A stop below round-off: 2 sweeps at ω = 1.6, 400 GMRES
        // iterations, then 2 safe sweeps at ω = 1, none reaching it.
        (
            vec![
                "--translate",
                "0.02,0.01",
                "--max-iterations",
                "2",
                "--tolerance",
                "1e-30",
            ],
            4,
            "error: step 1: the solve did not converge (stages tried: sweeps, gmres, safe-sweeps; \
             true residual ",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("moved.pvtu");
        let report = dir.path().join("report.json");
        let mut args = vec![
            "deform",
            mesh.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "wall",
            "--method",
            "verbss",
            "--report",
            report.to_str().unwrap(),
        ];
        args.extend_from_slice(&extra);
        let o = verbss_mpi(2, &args, dir.path());
        assert_eq!(o.status.code(), Some(code));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(stderr.matches(message).count(), 1, "{stderr}");
        // The report ends with the failed step, its message the outcome.
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
        let outcome = report["outcome"].as_str().unwrap();
        assert!(stderr.contains(&format!("error: {outcome}\n")), "{stderr}");
        let failed = &report["steps"][1];
        assert_eq!(report["steps"].as_array().unwrap().len(), 2);
        assert_eq!(failed["converged"], code == 3);
        let inverted = failed["inverted"].as_u64().unwrap();
        if code == 3 {
            let count = format!("({inverted} inverted element(s))");
            assert!(outcome.ends_with(&count), "{outcome}");
        }
        assert!(
            stderr.contains("\nthe last valid mesh (step 0) is in "),
            "{stderr}"
        );
        for r in 0..2 {
            let piece = verbss::io::read(&dir.path().join(format!("moved_{r}.vtu"))).unwrap();
            for (i, t) in piece.node_tags.iter().enumerate() {
                assert_eq!(piece.point(i), whole.point(index[t]), "node {t}");
            }
            let failed = dir.path().join(format!("moved.failed_{r}.vtu"));
            assert!(verbss::io::read(&failed).unwrap().cell_count() > 0);
        }
    }
}
