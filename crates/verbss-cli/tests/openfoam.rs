//! OpenFOAM cases end to end: a case made by OpenFOAM's `blockMesh` is
//! deformed by `verbss deform`, and OpenFOAM's `checkMesh` accepts what it
//! wrote (a new time directory of the input case, or a whole new case).

use std::path::Path;
use std::process::Command;

mod common;

use common::foam::{
    assert_mesh_ok, block_case, foam, have_openfoam, write_system, write_system_as,
};
use common::{stderr, verbss};

#[test]
fn a_2d_case_gets_its_moved_points_in_a_new_time_directory() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("square");
    block_case(&case, 4, 1);
    let constant = case.join("constant/polyMesh");
    let before: Vec<Vec<u8>> = ["points", "faces", "owner", "neighbour", "boundary"]
        .iter()
        .map(|f| std::fs::read(constant.join(f)).unwrap())
        .collect();
    let c = case.to_str().unwrap();
    let o = verbss(&[
        "deform", c, "-o", c, "--moving", "wing", "--rotate", "20", "--center", "0,0", "--steps",
        "4", "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let after: Vec<Vec<u8>> = ["points", "faces", "owner", "neighbour", "boundary"]
        .iter()
        .map(|f| std::fs::read(constant.join(f)).unwrap())
        .collect();
    assert!(before == after, "constant/polyMesh changed");
    let moved = std::fs::read_to_string(case.join("4/polyMesh/points")).unwrap();
    assert_ne!(moved.as_bytes(), &before[0][..]);
    assert!(moved.contains("location    \"4/polyMesh\""), "{moved}");
    assert_mesh_ok(&case);
    let log = foam("checkMesh", &case, &["-latestTime"]);
    assert!(log.contains("Time = 4"), "{log}");
}

#[test]
fn a_3d_case_is_written_as_a_whole_new_case() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("box");
    block_case(&case, 3, 2);
    let new = dir.path().join("moved");
    let o = verbss(&[
        "deform",
        case.to_str().unwrap(),
        "-o",
        new.to_str().unwrap(),
        "--moving",
        "wing",
        "--translate",
        "0.1,0.05,0",
        "--slide",
        "front,back",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in ["faces", "owner", "neighbour", "boundary"] {
        assert_eq!(
            std::fs::read(case.join("constant/polyMesh").join(f)).unwrap(),
            std::fs::read(new.join("constant/polyMesh").join(f)).unwrap(),
            "{f}"
        );
    }
    assert!(!case.join("1").exists());
    write_system(&new);
    assert_mesh_ok(&new);
    let log = foam("checkMesh", &new, &[]);
    assert!(log.contains("hexahedra:     144"), "{log}");
}

#[test]
fn a_case_converts_and_is_not_overwritten_without_asking() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("square");
    block_case(&case, 2, 1);
    let vtu = dir.path().join("square.vtu");
    let c = case.to_str().unwrap();
    let o = verbss(&["convert", c, vtu.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mesh = verbss::io::read(&vtu).unwrap();
    assert_eq!((mesh.dim, mesh.cell_count()), (2, 32));
    assert_eq!(mesh.group_names(), ["wing", "farfield"]);
    let points = case.join("constant/polyMesh/points");
    let before = std::fs::read(&points).unwrap();
    let o = verbss(&["convert", c, c]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("give --overwrite"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&points).unwrap(), before);
    let o = verbss(&["convert", c, c, "--overwrite"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_mesh_ok(&case);
    let o = verbss(&[
        "deform",
        c,
        "-o",
        &format!("{c}/constant/polyMesh"),
        "--moving",
        "wing",
        "--translate",
        "0.1,0",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(case.join("1/polyMesh/points").is_file());
}

/// A case OpenFOAM itself wrote in binary (`foamFormatConvert` with
/// `writeFormat binary`) reads as the same mesh as its ASCII original, and
/// deforms into a time directory that `checkMesh` passes.
#[test]
fn a_binary_case_reads_as_its_ascii_original() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("box");
    block_case(&case, 3, 2);
    let ascii = verbss::io::read(&case).unwrap();
    write_system_as(&case, "binary");
    foam("foamFormatConvert", &case, &["-constant"]);
    let points = std::fs::read(case.join("constant/polyMesh/points")).unwrap();
    assert!(
        String::from_utf8_lossy(&points).contains("format      binary"),
        "not converted"
    );
    let binary = verbss::io::read(&case).unwrap();
    assert_eq!(binary, ascii);
    let o = verbss(&[
        "deform",
        case.to_str().unwrap(),
        "-o",
        case.to_str().unwrap(),
        "--moving",
        "wing",
        "--translate",
        "0.1,0.05,0",
        "--slide",
        "front,back",
        "--steps",
        "2",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(case.join("2/polyMesh/points").is_file());
    assert_mesh_ok(&case);
}

/// `verbss quality CASE`, killed after 30 s: its exit code and standard error.
fn quality_within_30_s(case: &Path) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_verbss"))
        .arg("quality")
        .arg(case)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() > 30 {
            child.kill().unwrap();
            panic!("verbss quality {} ran past 30 s", case.display());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let o = child.wait_with_output().unwrap();
    (o.status.code(), stderr(&o))
}

/// Issue 43, 7–9: a `points` that is a FIFO blocked `quality` forever; one
/// point at x = 1e300 was blamed on a patch (the planes' tolerance grew with
/// the largest extent); two patches of one name were merged into one group.
#[test]
fn a_fifo_a_far_point_and_a_repeated_patch_name_are_refused_with_their_place() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case");
    block_case(&case, 4, 1);
    let poly = case.join("constant/polyMesh");
    let copy = |name: &str| {
        let to = dir.path().join(name);
        std::fs::create_dir_all(to.join("constant/polyMesh")).unwrap();
        for f in ["points", "faces", "owner", "neighbour", "boundary"] {
            std::fs::copy(poly.join(f), to.join("constant/polyMesh").join(f)).unwrap();
        }
        to
    };
    let fifo = copy("fifo");
    let points = fifo.join("constant/polyMesh/points");
    std::fs::remove_file(&points).unwrap();
    let made = Command::new("mkfifo").arg(&points).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    assert_eq!(
        quality_within_30_s(&fifo),
        (
            Some(2),
            format!(
                "error: {}: a FIFO, not a regular file (verbss reads its inputs from regular files only)\n",
                points.display()
            )
        )
    );
    // Point 4 (line 25) of the back plane moved to x = 1e300, its front
    // point (29) left where it was: the cell joining them is named.
    let far = copy("far");
    let points = far.join("constant/polyMesh/points");
    let text = std::fs::read_to_string(&points).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[24], "(-0.5 -1.5 0)");
    let moved = text.replacen("\n(-0.5 -1.5 0)\n", "\n(1e300 -1.5 0)\n", 1);
    std::fs::write(&points, moved).unwrap();
    assert_eq!(
        quality_within_30_s(&far),
        (
            Some(2),
            format!(
                "error: {}:28: cell 3 (hexahedron) has an edge between the planes that is not \
                 along z: point 4 at (1.000000e300, -1.500000, 0.000000) to point 29 at \
                 (-0.500000, -1.500000, 0.200000)\n",
                far.join("constant/polyMesh/owner").display()
            )
        )
    );
    let twice = copy("twice");
    let boundary = twice.join("constant/polyMesh/boundary");
    let text = std::fs::read_to_string(&boundary).unwrap();
    let line = |name: &str| 1 + text.lines().position(|l| l.trim() == name).unwrap();
    let (wing, farfield) = (line("wing"), line("farfield"));
    std::fs::write(&boundary, text.replace("    farfield\n", "    wing\n")).unwrap();
    assert_eq!(
        quality_within_30_s(&twice),
        (
            Some(2),
            format!(
                "error: {}:{farfield}: patch 'wing' is given twice (first at line {wing}): each \
                 patch needs a name of its own\n",
                boundary.display()
            )
        )
    );
}
