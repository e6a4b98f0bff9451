//! Degenerate and hostile input to `verbss deform`: each case ends with a
//! message naming what is wrong and a non-zero exit, leaves no partial file
//! behind and never replaces a valid mesh by an invalid one. The meshes are
//! in `assets/meshes/bad/`: variants of a 3 × 3-node square of 8 triangles
//! with groups `left` (x = 0) and `rest`.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{stderr, verbss};

/// The valid square the bad meshes are variants of.
const SQUARE: &str = "NDIME= 2
NELEM= 8
5 0 1 4
5 0 4 3
5 1 2 5
5 1 5 4
5 3 4 7
5 3 7 6
5 4 5 8
5 4 8 7
NPOIN= 9
0 0
1 0
2 0
0 1
1 1
2 1
0 2
1 2
2 2
NMARK= 2
MARKER_TAG= left
MARKER_ELEMS= 2
3 0 3
3 3 6
MARKER_TAG= rest
MARKER_ELEMS= 6
3 0 1
3 1 2
3 2 5
3 5 8
3 8 7
3 7 6
";

fn bad(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes/bad")
        .join(name)
}

/// A temporary folder holding the valid square as `square.su2`.
fn folder() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temporary folder");
    let square = dir.path().join("square.su2");
    std::fs::write(&square, SQUARE).expect("write the square");
    (dir, square)
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `verbss deform MESH -o DIR/out.su2 --moving GROUP ARGS…`: checks exit
/// code 2, the exact message and that nothing was written; returns nothing.
fn rejected(mesh: &Path, moving: &str, args: &[&str], message: &str) {
    let (dir, _) = folder();
    let out = dir.path().join("out.su2");
    let mut all = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        moving,
        "-q",
    ];
    all.extend_from_slice(args);
    let o = verbss(&all);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o), format!("error: {message}\n"));
    assert_eq!(listing(dir.path()), ["square.su2"]);
}

#[test]
fn zero_area_element_is_refused() {
    rejected(
        &bad("zero_area.su2"),
        "left",
        &["--translate", "0.1,0"],
        "invalid mesh: element 9 is inverted or degenerate (tangled, or of zero area or volume) at (1.000000, 0.000000)",
    );
}

#[test]
fn already_inverted_input_is_refused() {
    rejected(
        &bad("inverted.su2"),
        "left",
        &["--translate", "0.1,0"],
        "invalid mesh: element 4 is inverted or degenerate (tangled, or of zero area or volume) at (1.833333, 0.833333)",
    );
}

#[test]
fn duplicate_nodes_are_refused() {
    rejected(
        &bad("duplicate_node.su2"),
        "left",
        &["--translate", "0.1,0"],
        "invalid mesh: nodes 1 and 10 are at the same position (0.000000, 0.000000): duplicate nodes",
    );
}

#[test]
fn a_node_used_by_no_element_is_refused() {
    rejected(
        &bad("unused_node.su2"),
        "left",
        &["--translate", "0.1,0"],
        "invalid setting: node 10 is not connected to any fixed node (its displacement would be undetermined)",
    );
}

#[test]
fn a_moving_group_without_nodes_is_refused() {
    rejected(
        &bad("empty_group.su2"),
        "empty",
        &["--translate", "0.1,0"],
        "invalid setting: group 'empty' has no nodes: nothing to move",
    );
}

#[test]
fn a_motion_given_as_nan_is_refused() {
    let (_dir, square) = folder();
    rejected(
        &square,
        "left",
        &["--translate", "NaN,0"],
        "--translate has a non-finite number (NaN)",
    );
    rejected(
        &square,
        "left",
        &["--rotate", "inf", "--center", "0,0"],
        "--rotate has a non-finite angle (inf)",
    );
}

#[test]
fn a_positions_file_naming_a_missing_node_is_refused() {
    let (dir, square) = folder();
    let positions = dir.path().join("positions.dat");
    std::fs::write(&positions, "0 0.1 0\n17 0 0\n").expect("write positions");
    rejected(
        &square,
        "left",
        &["--positions", positions.to_str().unwrap()],
        &format!(
            "{}:2: node id 17 out of range (the mesh has 9 nodes: ids 0 to 8)",
            positions.display()
        ),
    );
}

#[test]
fn a_positions_file_naming_a_node_off_the_moving_groups_is_refused() {
    // Node 4 is the square's centre: interior, on no group.
    let (dir, square) = folder();
    let positions = dir.path().join("positions.dat");
    std::fs::write(&positions, "0 0.1 0\n4 1 1\n").expect("write positions");
    rejected(
        &square,
        "left",
        &["--positions", positions.to_str().unwrap()],
        &format!(
            "{}:2: node id 4 is not on a moving group (left): its position would be ignored",
            positions.display()
        ),
    );
}

/// Issue 43, 12: a coordinate of 1e308 was blamed on the mesh (`nodes 287
/// and 5 coincide`); it is refused where it stands.
#[test]
fn a_positions_file_with_a_coordinate_beyond_1e100_is_refused_at_its_line() {
    let (dir, square) = folder();
    let positions = dir.path().join("positions.dat");
    std::fs::write(&positions, "0 0.1 0\n3 1e308 1\n").expect("write positions");
    rejected(
        &square,
        "left",
        &["--positions", positions.to_str().unwrap()],
        &format!(
            "{}:2: coordinate '1e308' of node 3 is beyond ±1e100 (a position that far from the \
             mesh would overflow the solve)",
            positions.display()
        ),
    );
}

/// Issue 43, 7: an input that is a FIFO blocked forever; it is refused
/// before it is opened, as a mesh and as a positions file.
#[test]
fn an_input_that_is_a_fifo_is_refused() {
    let (dir, square) = folder();
    let fifo = dir.path().join("positions.dat");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    let message = |p: &Path| {
        format!(
            "{}: a FIFO, not a regular file (verbss reads its inputs from regular files only)",
            p.display()
        )
    };
    rejected(
        &square,
        "left",
        &["--positions", fifo.to_str().unwrap()],
        &message(&fifo),
    );
    let cgns = verbss::io::cgns::available().is_ok();
    for name in ["m.su2", "m.msh", "m.vtu", "m.cgns"]
        .into_iter()
        .filter(|n| cgns || !n.ends_with(".cgns"))
    {
        let mesh = dir.path().join(name);
        let made = std::process::Command::new("mkfifo").arg(&mesh).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
        let o = verbss(&["quality", mesh.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        assert_eq!(stderr(&o), format!("error: {}\n", message(&mesh)), "{name}");
    }
}

#[test]
fn an_output_below_a_regular_file_is_refused() {
    // Root cannot bypass this one: a regular file is not a folder.
    let (dir, square) = folder();
    let out = square.join("out.su2");
    let o = verbss(&[
        "deform",
        square.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "0.1,0",
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "error: cannot create the output folder {}\n",
            square.display()
        )
    );
    assert_eq!(std::fs::read_to_string(&square).unwrap(), SQUARE);
    assert_eq!(listing(dir.path()), ["square.su2"]);
}

#[test]
fn an_output_folder_without_write_permission_is_refused() {
    use std::os::unix::fs::PermissionsExt;
    let (dir, square) = folder();
    let locked = dir.path().join("locked");
    std::fs::create_dir(&locked).unwrap();
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o555)).unwrap();
    let probe = locked.join("probe");
    if std::fs::write(&probe, "").is_ok() {
        std::fs::remove_file(&probe).unwrap();
        println!("skipped: this user (root?) can write into a read-only folder");
        return;
    }
    let out = locked.join("out.su2");
    let o = verbss(&[
        "deform",
        square.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "0.1,0",
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with(&format!("error: {}: Permission denied", out.display())),
        "{}",
        stderr(&o)
    );
    assert!(listing(&locked).is_empty());
}

#[test]
fn a_full_disk_leaves_the_previous_output_and_no_partial_file() {
    // `ulimit -f 1` caps files at 512 bytes; with SIGXFSZ ignored (an
    // ignored signal stays ignored across exec) a longer write fails with
    // EFBIG as on a full disk, instead of the kernel killing the process.
    let (dir, _) = folder();
    let out = dir.path().join("out.su2");
    std::fs::write(&out, SQUARE).unwrap();
    let naca =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/mesh_NACA0012_inv.su2");
    let script = format!(
        "trap '' XFSZ; ulimit -f 1; exec '{}' deform '{}' -o '{}' --moving airfoil --translate 0.01,0 -q",
        env!("CARGO_BIN_EXE_verbss"),
        naca.display(),
        out.display()
    );
    let o = Command::new("sh").args(["-c", &script]).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!("error: {}: File too large (os error 27)\n", out.display())
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), SQUARE);
    assert_eq!(listing(dir.path()), ["out.su2", "square.su2"]);
}

#[test]
fn an_inverting_motion_never_leaves_an_invalid_mesh_in_the_output() {
    let (dir, square) = folder();
    let out = dir.path().join("out.su2");
    std::fs::write(&out, SQUARE).unwrap();
    let o = verbss(&[
        "deform",
        square.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "1.5,0",
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with("error: step 1: element 6 inverted at"),
        "{}",
        stderr(&o)
    );
    let written = verbss::io::read(&out).unwrap();
    let input = verbss::io::read(&square).unwrap();
    assert_eq!(written, input);
    assert_eq!(
        listing(dir.path()),
        ["out.failed.vtu", "out.su2", "square.su2"]
    );
}

#[test]
fn a_duplicated_element_is_refused() {
    let (dir, _) = folder();
    let mesh = dir.path().join("twice.su2");
    std::fs::write(
        &mesh,
        SQUARE.replace("NELEM= 8\n5 0 1 4\n", "NELEM= 9\n5 0 1 4\n5 1 4 0\n"),
    )
    .expect("write the mesh");
    let message = format!(
        "{}:2: invalid mesh: elements 1 and 2 have the same nodes (a duplicated element)",
        mesh.display()
    );
    rejected(&mesh, "left", &["--translate", "0.1,0"], &message);
}

#[test]
fn a_failed_run_leaves_no_stale_completed_report() {
    let (dir, square) = folder();
    let report = dir.path().join("report.json");
    std::fs::write(&report, "{\"outcome\": \"completed\"}").expect("write a stale report");
    // A name too long for the file system: the run fails (exit 2) when it
    // writes the mesh, after the steps.
    let out = dir.path().join(format!("{}.su2", "o".repeat(300)));
    let o = verbss(&[
        "deform",
        square.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "0.1,0",
        "--report",
        report.to_str().unwrap(),
        "-q",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let text = std::fs::read_to_string(&report).expect("read the report");
    assert!(!text.contains("\"outcome\": \"completed\""), "{text}");
}

#[test]
fn a_rotation_center_too_far_to_compute_is_refused() {
    let (_dir, square) = folder();
    rejected(
        &square,
        "left",
        &["--rotate", "5", "--center", "1e308,1e308"],
        "invalid setting: the rotation center (1.000000e308, 1.000000e308) is beyond ±1e100 \
         (the displacements would overflow)",
    );
}
