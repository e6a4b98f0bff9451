//! `verbss-mpi deform IN.su2 -o OUT.pvtu` on 1, 2 and 3 ranks: rank 0
//! reads the file once in chunks and scatters it, PT-Scotch cuts it, every
//! rank holds and writes only its part (docs/distributed.md).
//!
//! Each run is held to the single-process stepper to 1e-10 of the largest
//! displacement; the ranks' lines say how many cells each holds (all of them
//! once in all, none all of them on 2 or 3 ranks) and in how many chunks
//! rank 0 read the file (several: the chunk is set small with
//! `VERBSS_MPI_CHUNK_LINES`). A bad file stops every rank with the
//! whole-file reader's message, once, and exit code 2.

use verbss::mesh::CellKind;
use verbss::settings::Reference;
use verbss::{io, Mesh};

mod common;
mod like_one_process;

use like_one_process::{
    asset, deforms_like_one_process, ptscotch_ready, rank_lines, verbss_mpi_with,
};

/// Checks the ranks' lines of the runs on 1, 2 and 3 ranks of `whole`:
/// every cell once, no rank with all of them on several ranks, and rank 0
/// reading in at least `chunks` chunks.
fn check_counts(stdouts: &[String], whole: &Mesh, chunks: usize) {
    let total = whole.cells.len();
    for (k, stdout) in stdouts.iter().enumerate() {
        let np = k + 1;
        let ranks = rank_lines(
            stdout,
            [
                ": PT-Scotch part ",
                " chunks of",
                " cells read;",
                " cells read by rank 0",
            ],
        );
        assert_eq!(ranks.len(), np, "{stdout}");
        let mut sum = 0;
        for (r, &[rank, read_in, held, of]) in ranks.iter().enumerate() {
            assert_eq!(rank, r);
            assert!(read_in >= chunks, "{np} ranks: {read_in} chunks");
            assert_eq!(of, total);
            assert!(np == 1 || held < total, "{np} ranks: rank {r} holds {held}");
            sum += held;
        }
        assert_eq!(sum, total, "{np} ranks");
    }
}

#[test]
fn a_2d_hybrid_su2_file_is_scattered_cut_and_deformed_on_one_to_three_ranks() {
    if !ptscotch_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let su2 = dir.path().join("channel.su2");
    let msh = io::read(&asset("gmsh/channel_hole_v41_ascii.msh")).unwrap();
    io::write(&su2, &msh, &io::WriteOptions::default()).unwrap();
    let whole = io::read(&su2).unwrap();
    for kind in [CellKind::Triangle, CellKind::Quad] {
        assert!(whole.cells.kinds.contains(&kind), "{kind:?}");
    }
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    let motion = ["--translate", "0.02,0.01"];
    let env = [("VERBSS_MPI_CHUNK_LINES", "50")];
    let stdouts = deforms_like_one_process(&su2, "wall", &motion, Reference::Updated, scale, &env);
    let lines = std::fs::read_to_string(&su2).unwrap().lines().count();
    check_counts(&stdouts, &whole, lines / 50);
    // The same cut again: it depends only on the file and the rank count.
    let out = dir.path().join("again.pvtu");
    let args = [
        "deform",
        su2.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "wall",
        "--translate",
        "0.02,0.01",
        "--method",
        "verbss",
    ];
    let again = verbss_mpi_with(3, &args, dir.path(), &env);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    let ghosts = |stdout: &str| -> Vec<String> {
        let mut lines: Vec<String> = stdout
            .lines()
            .filter(|l| l.starts_with("rank "))
            .map(String::from)
            .collect();
        lines.sort();
        lines
    };
    assert_eq!(
        ghosts(&String::from_utf8_lossy(&again.stdout)),
        ghosts(&stdouts[2])
    );
}

#[test]
fn the_tetrahedral_brick_is_scattered_cut_and_deformed_on_one_to_three_ranks() {
    if !ptscotch_ready() {
        return;
    }
    let su2 = asset("su2/mesh_brick_tets_ffd.su2");
    let whole = io::read(&su2).unwrap();
    let motion = ["--translate", "0,0,0.05"];
    let env = [("VERBSS_MPI_CHUNK_LINES", "5000")];
    let stdouts = deforms_like_one_process(&su2, "z_p", &motion, Reference::Fixed, 0.05, &env);
    let lines = std::fs::read_to_string(&su2).unwrap().lines().count();
    check_counts(&stdouts, &whole, lines / 5000);
}

/// A bad line, a file cut short and a duplicated element: every rank stops,
/// one message (the whole-file reader's, with the file and the line), exit
/// code 2.
#[test]
fn a_bad_su2_file_stops_every_rank_with_one_message() {
    if !ptscotch_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(asset("su2/mesh_NACA0012_inv.su2")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let npoin = lines.iter().position(|l| l.starts_with("NPOIN")).unwrap();
    let mut bad_line: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    bad_line[npoin + 100] = "0.5 x 100".into();
    // The first element twice (NELEM= one more): found after the cut, on
    // the rank that holds both.
    let mut duplicated: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    let nelem = lines.iter().position(|l| l.starts_with("NELEM")).unwrap();
    let count: usize = lines[nelem]["NELEM=".len()..].trim().parse().unwrap();
    duplicated[nelem] = format!("NELEM= {}", count + 1);
    duplicated.insert(nelem + 2, lines[nelem + 1].to_string());
    let files = [
        ("bad_line.su2", bad_line.join("\n") + "\n"),
        ("cut.su2", lines[..npoin + 100].join("\n") + "\n"),
        ("duplicated.su2", duplicated.join("\n") + "\n"),
    ];
    for (name, text) in files {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let expected = io::read(&path).unwrap_err().to_string();
        assert!(
            expected.starts_with(&format!("{}:", path.display())),
            "{expected}"
        );
        let out = dir.path().join("moved.pvtu");
        let args = [
            "deform",
            path.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--translate",
            "0.01,0",
            "--method",
            "verbss",
        ];
        let env = [("VERBSS_MPI_CHUNK_LINES", "1000")];
        let o = verbss_mpi_with(3, &args, dir.path(), &env);
        assert_eq!(o.status.code(), Some(2), "{name}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(stderr.matches("error: ").count(), 1, "{name}: {stderr}");
        // Rank 0's message, or the rank's that found the duplicated element.
        let said = stderr.matches(&format!("error: {expected}")).count()
            + stderr
                .matches(&format!(" found an invalid cell: {expected}"))
                .count();
        assert_eq!(said, 1, "{name}: {stderr}");
    }
    // What the partitioned MSH path refuses, this path refuses: a method
    // with no partitioned form.
    let mesh = asset("su2/mesh_NACA0012_inv.su2");
    let out = dir.path().join("moved.pvtu");
    let args = [
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "airfoil",
        "--translate",
        "0.01,0",
        "--method",
        "ball-vertex",
    ];
    let o = verbss_mpi_with(2, &args, dir.path(), &[]);
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    let refused = "which runs --method robust, verbss or spring";
    assert_eq!(stderr.matches(refused).count(), 1, "{stderr}");
}
