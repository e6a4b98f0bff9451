//! `verbss-mpi deform --pieces -o OUT.msh` on 1, 2 and 3 ranks: every rank
//! writes its own cells as partition `RANK + 1` of a split set,
//! `OUT_{RANK+1}.msh` (the form of `gmsh -part_split`), from a
//! partitioned MSH 4.1 input (ASCII and binary) or an SU2 input
//! (docs/distributed.md).
//!
//! The pieces hold every cell of the input once, at the single-process
//! stepper's coordinates to 1e-10 of the largest displacement; Gmsh (python3
//! with gmsh, else that part skips) opens each and merges them into the whole
//! moved mesh. A piece one rank cannot write stops every rank with its
//! message, once, and exit code 2; an output that is neither `.msh` nor
//! `.pvtu` is refused; a step that inverts a cell leaves the input in the
//! pieces.

use std::path::Path;

use verbss::io;
use verbss::settings::Reference;

mod common;
mod like_one_process;

use like_one_process::{asset, msh_pieces_like_one_process, ptscotch_ready, verbss_mpi_with};

#[test]
fn msh_pieces_of_a_partitioned_ascii_channel() {
    if !common::mpi_ready() {
        return;
    }
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    msh_pieces_like_one_process(
        &asset("gmsh/channel_hole_part3_v41_ascii.msh"),
        "wall",
        &["--translate", "0.02,0.01"],
        Reference::Updated,
        scale,
        false,
        &[],
    );
}

#[test]
fn msh_pieces_of_a_partitioned_binary_box() {
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
    let box_mesh = asset("gmsh/box_part3_v41_binary.msh");
    msh_pieces_like_one_process(
        &box_mesh,
        "inlet",
        &motion,
        Reference::Fixed,
        0.037,
        true,
        &[],
    );
}

#[test]
fn msh_pieces_of_an_su2_channel() {
    if !ptscotch_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let su2 = dir.path().join("channel.su2");
    let msh = io::read(&asset("gmsh/channel_hole_v41_ascii.msh")).unwrap();
    io::write(&su2, &msh, &io::WriteOptions::default()).unwrap();
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    msh_pieces_like_one_process(
        &su2,
        "wall",
        &["--translate", "0.02,0.01"],
        Reference::Updated,
        scale,
        false,
        &[("VERBSS_MPI_CHUNK_LINES", "50")],
    );
}

/// A piece that only rank 1 cannot write (a link into a missing folder
/// stands in its place): every rank stops, rank 0 says which rank, which
/// file and why, once; exit code 2. A folder in its place is refused
/// before the first solve. `--pieces` with another output than `.msh` or `.pvtu` is
/// refused with exit code 2.
#[test]
fn a_piece_one_rank_cannot_write_stops_every_rank() {
    if !common::mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("gmsh/channel_hole_part3_v41_ascii.msh");
    let blocked = dir.path().join("moved_2.msh");
    std::fs::create_dir(&blocked).unwrap();
    let deform = |out: &Path| {
        let args = [
            "deform",
            mesh.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--pieces",
            "--moving",
            "wall",
            "--translate",
            "0.02,0.01",
            "--method",
            "verbss",
            "-q",
        ];
        let o = verbss_mpi_with(2, &args, dir.path(), &[]);
        assert_eq!(o.status.code(), Some(2));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    // A folder in the way is refused before the first solve.
    let stderr = deform(&dir.path().join("moved.msh"));
    let message = format!(
        "error: -o {}: a directory, not a regular file (verbss writes its outputs to regular \
         files only)",
        blocked.display()
    );
    assert_eq!(stderr.matches(&message).count(), 1, "{stderr}");
    // A link into a missing folder fails when rank 1 writes its piece.
    std::fs::remove_dir(&blocked).unwrap();
    std::os::unix::fs::symlink("missing/moved_2.msh", &blocked).unwrap();
    let stderr = deform(&dir.path().join("moved.msh"));
    let message = format!(
        "error: rank 1 could not write its piece: {}: ",
        blocked.display()
    );
    assert_eq!(stderr.matches(&message).count(), 1, "{stderr}");
    assert_eq!(stderr.matches("error: ").count(), 1, "{stderr}");
    let stderr = deform(&dir.path().join("moved.su2"));
    let message = "moved.su2: a partitioned input is written rank by rank: the output is a \
                   .pvtu file (one .vtu piece per rank beside it) or a .msh name";
    assert_eq!(stderr.matches(message).count(), 1, "{stderr}");
}

/// A step that inverts a cell (the hole pushed through the top wall) stops
/// with exit code 3, and the MSH pieces hold the last valid mesh, the
/// input, in the folder made for them, which the message names with the
/// failed state beside them.
#[test]
fn an_inverted_cell_leaves_the_input_in_the_pieces() {
    if !common::mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("gmsh/channel_hole_part3_v41_ascii.msh");
    let whole = io::read(&mesh).unwrap();
    let out = dir.path().join("new/moved.msh");
    let args = [
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--pieces",
        "--moving",
        "wall",
        "--translate",
        "0,0.45",
        "--method",
        "verbss",
        "--max-iterations",
        "100000",
        "-q",
    ];
    let o = verbss_mpi_with(2, &args, dir.path(), &[]);
    assert_eq!(o.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        stderr.matches("error: step 1: element ").count(),
        1,
        "{stderr}"
    );
    let new = dir.path().join("new");
    let said = format!(
        "the last valid mesh (step 0) is in {} to {}; the failed state in {}\n",
        new.join("moved_1.msh").display(),
        new.join("moved_2.msh").display(),
        new.join("moved.failed.pvtu").display()
    );
    assert!(stderr.contains(&said), "{stderr}");
    let mut cells = 0;
    for r in 0..2 {
        let piece = io::read(&new.join(format!("moved_{}.msh", r + 1))).unwrap();
        cells += piece.cell_count();
        for (i, t) in piece.node_tags.iter().enumerate() {
            let g = whole.node_tags.iter().position(|w| w == t).unwrap();
            assert_eq!(piece.point(i), whole.point(g), "node {t}");
        }
    }
    assert_eq!(cells, whole.cell_count());
}
