//! The MSH pieces of `verbss-mpi deform --pieces` (a split set, one file a
//! partition) read back as a partitioned input on 1, 2 and 3 ranks
//! ([`verbss_mpi::share::read_rank_split`]): each rank reads only its
//! partitions' files and holds their nodes at the written coordinates,
//! bit for bit, with the roles of the input mesh (the boundary nodes and
//! the moving group's), and with the ghost layer only its part of the
//! mesh, from a partitioned MSH input and from an SU2 input. `--split`
//! with a badly named or incomplete set is refused.
//!
//! The test re-runs this test binary under `mpirun` with the ignored
//! `worker` test. Without MPI the tests skip with a notice.

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

use verbss::solve::{default_roles, NodeRole};
use verbss::Mesh;
use verbss_mpi::share::partitions_of;

mod common;
mod like_one_process;

use like_one_process::{asset, node_index, ptscotch_ready, verbss_mpi_with};

/// Worker, one per rank: reads this rank's share of the split set
/// `$VERBSS_MPI_MESH`, builds its part with ghosts, and writes `counts
/// SHARE_NODES SHARE_CELLS PART_NODES PART_CELLS` then per node `tag fixed
/// moving x y [z]` in `$VERBSS_MPI_OUT.RANK`.
#[cfg(with_mpi)]
#[test]
#[ignore = "run under mpirun by the other tests"]
fn worker() {
    use verbss_mpi::coupled::LocalSolver;
    use verbss_mpi::share::{global_numbers, prescribe, read_rank_split};

    let mpi = verbss_mpi::Mpi::init().unwrap();
    let world = mpi.world();
    let path = PathBuf::from(std::env::var("VERBSS_MPI_MESH").unwrap());
    let group = std::env::var("VERBSS_MPI_GROUP").unwrap();
    let out = std::env::var("VERBSS_MPI_OUT").unwrap();
    let share = read_rank_split(&world, &path).unwrap();
    let dim = share.mesh.dim;
    let (roles, _) =
        prescribe(&share, std::slice::from_ref(&group), |_| Ok(vec![0.0; dim])).unwrap();
    let global = global_numbers(&share);
    let solver = LocalSolver::new(&world, &share.mesh, &global, &roles, &[]).unwrap();
    let part = solver.part();
    let mut text = format!(
        "counts {} {} {} {}\n",
        share.mesh.node_count(),
        share.mesh.cell_count(),
        part.node_count(),
        part.cells.len()
    );
    let moving = &share
        .group_nodes
        .iter()
        .find(|(g, _)| *g == group)
        .unwrap()
        .1;
    for (i, &tag) in share.mesh.node_tags.iter().enumerate() {
        let fixed = u8::from(roles[i] == NodeRole::Fixed);
        text += &format!("{tag} {fixed} {}", u8::from(moving.contains(&i)));
        for x in share.mesh.point(i) {
            text += &format!(" {x:?}");
        }
        text += "\n";
    }
    std::fs::write(format!("{out}.{}", world.rank()), text).unwrap();
}

/// What one rank wrote: its counts, and per node tag whether it is fixed,
/// whether it moves, and its coordinates.
struct Rank {
    counts: [usize; 4],
    nodes: HashMap<u64, (bool, bool, Vec<f64>)>,
}

/// Runs the worker on `np` ranks on the split set whose first file is `first`.
fn read_back(np: usize, first: &Path, group: &str) -> Vec<Rank> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("u");
    let o = common::mpirun(np, dir.path())
        .env("VERBSS_MPI_MESH", first)
        .env("VERBSS_MPI_GROUP", group)
        .env("VERBSS_MPI_OUT", &out)
        .arg(std::env::current_exe().unwrap())
        .args(["worker", "--exact", "--ignored", "--test-threads", "1"])
        .output()
        .expect("run mpirun (Debian: openmpi-bin)");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (0..np)
        .map(|r| {
            let text = std::fs::read_to_string(format!("{}.{r}", out.display())).unwrap();
            let mut lines = text.lines();
            let counts: Vec<usize> = lines.next().unwrap()[7..]
                .split(' ')
                .map(|x| x.parse().unwrap())
                .collect();
            let nodes = lines
                .map(|l| {
                    let f: Vec<&str> = l.split(' ').collect();
                    let xyz = f[3..].iter().map(|x| x.parse().unwrap()).collect();
                    (f[0].parse().unwrap(), (f[1] == "1", f[2] == "1", xyz))
                })
                .collect();
            Rank {
                counts: counts.try_into().unwrap(),
                nodes,
            }
        })
        .collect()
}

/// `verbss-mpi deform MESH -o DIR/moved.msh --pieces` on 3 ranks, moving
/// `group` by `motion` in 2 steps; returns the set's first file.
fn write_pieces(mesh: &Path, dir: &Path, group: &str, motion: &[&str]) -> PathBuf {
    let out = dir.join("moved.msh");
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--pieces",
        "--moving",
        group,
        "--method",
        "verbss",
        "--steps",
        "2",
        "-q",
    ];
    args.extend_from_slice(motion);
    let o = verbss_mpi_with(3, &args, dir, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!out.exists());
    dir.join("moved_1.msh")
}

/// The pieces written from `mesh` on 3 ranks, read back on 1, 2 and 3
/// ranks: each rank's counts (its partitions' files, and its part with
/// ghosts by the owner rule), every node at the coordinates of the files
/// exactly, fixed and moving as in the input mesh.
fn pieces_read_back(mesh: &Path, group: &str, motion: &[&str], binary: bool) {
    let whole = verbss::io::read(mesh).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let first = write_pieces(mesh, dir.path(), group, motion);
    let pieces: Vec<Mesh> = (1..=3)
        .map(|k| {
            let path = dir.path().join(format!("moved_{k}.msh"));
            let head = std::fs::read(&path).unwrap();
            let format = format!("$MeshFormat\n4.1 {} 8\n", u8::from(binary));
            assert!(head.starts_with(format.as_bytes()), "{}", path.display());
            let text = String::from_utf8_lossy(&head);
            assert!(
                text.contains("$PartitionedEntities\n"),
                "{}",
                path.display()
            );
            verbss::io::read(&path).unwrap()
        })
        .collect();
    let mut written: HashMap<u64, Vec<f64>> = HashMap::new();
    for p in &pieces {
        for (i, &t) in p.node_tags.iter().enumerate() {
            written.insert(t, p.point(i).to_vec());
        }
    }
    let index = node_index(&whole);
    let roles = default_roles(&whole);
    let moving: BTreeSet<usize> = whole.group(group).unwrap().nodes().into_iter().collect();
    for np in 1..=3 {
        let ranks = read_back(np, &first, group);
        let want = expected_counts(&whole, &pieces, np);
        let mut seen = BTreeSet::new();
        for (r, rank) in ranks.iter().enumerate() {
            assert_eq!(rank.counts, want[r], "rank {r} of {np}");
            if np > 1 {
                assert!(rank.counts[2] < whole.node_count(), "rank {r} of {np}");
            }
            for (tag, (fixed, moves, xyz)) in &rank.nodes {
                let g = index[tag];
                assert_eq!(xyz, &written[tag], "node {tag}, {np} ranks");
                let in_group = moving.contains(&g);
                assert_eq!(*moves, in_group, "node {tag}, {np} ranks");
                assert_eq!(
                    *fixed,
                    in_group || roles[g] == NodeRole::Fixed,
                    "node {tag}"
                );
                seen.insert(*tag);
            }
        }
        assert_eq!(
            seen.len(),
            whole.node_count(),
            "{np} ranks: every node read"
        );
    }
}

/// Per rank of `np` reading the 3 `pieces`: the nodes and cells of its
/// partitions' files, and of its part with ghosts (its cells and every cell
/// of `whole` with a node it owns, the lowest rank holding a node owning
/// it).
fn expected_counts(whole: &Mesh, pieces: &[Mesh], np: usize) -> Vec<[usize; 4]> {
    let index = node_index(whole);
    let cell_index: HashMap<u64, usize> = whole
        .cell_tags
        .iter()
        .enumerate()
        .map(|(c, &t)| (t, c))
        .collect();
    let path = Path::new("moved_1.msh");
    let shares: Vec<(BTreeSet<usize>, BTreeSet<usize>)> = (0..np)
        .map(|r| {
            let (mut nodes, mut cells) = (BTreeSet::new(), BTreeSet::new());
            for k in partitions_of(3, np, r, path).unwrap() {
                nodes.extend(pieces[k - 1].node_tags.iter().map(|t| index[t]));
                cells.extend(pieces[k - 1].cell_tags.iter().map(|t| cell_index[t]));
            }
            (nodes, cells)
        })
        .collect();
    let mut owner = vec![usize::MAX; whole.node_count()];
    for (r, (nodes, _)) in shares.iter().enumerate().rev() {
        for &i in nodes {
            owner[i] = r;
        }
    }
    (0..np)
        .map(|r| {
            let (nodes, own) = &shares[r];
            let mut cells = own.clone();
            cells.extend(
                (0..whole.cell_count())
                    .filter(|&c| whole.cells.cell(c).iter().any(|&v| owner[v] == r)),
            );
            let part: BTreeSet<usize> = cells
                .iter()
                .flat_map(|&c| whole.cells.cell(c).to_vec())
                .collect();
            [nodes.len(), own.len(), part.len(), cells.len()]
        })
        .collect()
}

#[test]
fn msh_pieces_of_an_ascii_channel_read_back_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/channel_hole_part3_v41_ascii.msh");
    pieces_read_back(&mesh, "wall", &["--translate", "0.02,0.01"], false);
}

#[test]
fn msh_pieces_of_a_binary_box_read_back_on_one_to_three_ranks() {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/box_part3_v41_binary.msh");
    pieces_read_back(&mesh, "inlet", &["--translate", "0.05,0,0"], true);
}

/// The pieces of an SU2 and of a CGNS input (the channel written as
/// each), cut by PT-Scotch: their groups' facets reach the ranks whose
/// cells they bound, so the set read back moves the group and holds the
/// boundary as the input does.
#[test]
fn msh_pieces_of_an_su2_and_a_cgns_channel_read_back_on_one_to_three_ranks() {
    if !ptscotch_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let msh = verbss::io::read(&asset("gmsh/channel_hole_v41_ascii.msh")).unwrap();
    for name in ["channel.su2", "channel.cgns"] {
        let input = dir.path().join(name);
        verbss::io::write(&input, &msh, &verbss::io::WriteOptions::default()).unwrap();
        pieces_read_back(&input, "wall", &["--translate", "0.02,0.01"], false);
    }
}

/// Gmsh's split set of the channel copied into `dir` as `set_1.msh` …
/// `set_3.msh`; the name of `set_K.msh`.
fn channel_set(dir: &Path) -> impl Fn(usize) -> PathBuf + '_ {
    let set = move |k: usize| dir.join(format!("set_{k}.msh"));
    for k in 1..=3 {
        let gmsh = asset(&format!("gmsh/channel_hole_split3_v41_ascii_{k}.msh"));
        std::fs::copy(gmsh, set(k)).unwrap();
    }
    set
}

/// `--split` names a set by its first file `NAME_1.msh`; a set missing a
/// file, or one with a file too many, is refused, naming the file, with
/// exit code 2, as is `--split` without `--pieces` or a `.pvtu` output.
#[test]
fn split_sets_badly_named_or_incomplete_are_refused() {
    if !common::mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let set = channel_set(dir.path());
    let out = dir.path().join("out.msh");
    let refused = |input: &Path, extra: &[&str], message: &str| {
        let mut args = vec!["deform", input.to_str().unwrap(), "-o"];
        args.extend_from_slice(&[out.to_str().unwrap(), "--split", "--moving", "wall"]);
        args.extend_from_slice(&["--translate", "0.01,0", "--method", "verbss", "-q"]);
        args.extend_from_slice(extra);
        let o = verbss_mpi_with(2, &args, dir.path(), &[]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert_eq!(stderr.matches(message).count(), 1, "{stderr}");
    };
    refused(
        &set(2),
        &["--pieces"],
        "a split set is named by its first file, NAME_1.msh",
    );
    refused(&set(1), &[], "--split");
    std::fs::copy(set(3), set(4)).unwrap();
    refused(&set(1), &["--pieces"], "set_4.msh exists, but");
    std::fs::remove_file(set(4)).unwrap();
    std::fs::remove_file(set(2)).unwrap();
    refused(&set(1), &["--pieces"], "set_2.msh: missing");
}

/// MSH pieces never replace the split set they were read from unless
/// `--overwrite` says so; they, the report and the gathered mesh go into
/// folders made for them, the pieces binary with
/// `--binary` from an ASCII set; `--msh-version 2.2` is refused (a split
/// set is MSH 4.1).
#[test]
fn msh_pieces_keep_their_input_and_are_written_as_asked() {
    if !common::mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let set = channel_set(dir.path());
    let original: Vec<Vec<u8>> = (1..=3).map(|k| std::fs::read(set(k)).unwrap()).collect();
    let first = set(1);
    let deform = |out: &Path, extra: &[&str]| {
        let mut args = vec!["deform", first.to_str().unwrap(), "--split", "--pieces"];
        args.extend_from_slice(&["-o", out.to_str().unwrap(), "--moving", "wall"]);
        args.extend_from_slice(&["--translate", "0.01,0", "--method", "verbss", "-q"]);
        args.extend_from_slice(extra);
        let o = verbss_mpi_with(3, &args, dir.path(), &[]);
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    let (code, stderr) = deform(&dir.path().join("set.msh"), &[]);
    assert_eq!(code, Some(2), "{stderr}");
    let refusal = "the output is the input mesh ";
    assert_eq!(stderr.matches(refusal).count(), 1, "{stderr}");
    assert!(
        stderr.contains("(give --overwrite to replace it)"),
        "{stderr}"
    );
    for k in 1..=3 {
        assert_eq!(
            std::fs::read(set(k)).unwrap(),
            original[k - 1],
            "set_{k}.msh"
        );
    }
    let report = dir.path().join("r/report.json");
    let gathered = dir.path().join("g/all.vtu");
    let extra = [
        "--binary",
        "--report",
        report.to_str().unwrap(),
        "--gather",
        gathered.to_str().unwrap(),
    ];
    let (code, stderr) = deform(&dir.path().join("new/moved.msh"), &extra);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(report.is_file() && gathered.is_file());
    for k in 1..=3 {
        let piece = std::fs::read(dir.path().join(format!("new/moved_{k}.msh"))).unwrap();
        assert!(piece.starts_with(b"$MeshFormat\n4.1 1 8\n"), "piece {k}");
    }
    let (code, stderr) = deform(&dir.path().join("v22.msh"), &["--msh-version", "2.2"]);
    assert_eq!(code, Some(2), "{stderr}");
    let refusal = "--msh-version 2.2: MSH pieces are written as a split set of MSH 4.1 files";
    assert_eq!(stderr.matches(refusal).count(), 1, "{stderr}");
    let (code, stderr) = deform(&dir.path().join("set.msh"), &["--overwrite"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert_ne!(std::fs::read(set(1)).unwrap(), original[0]);
}
