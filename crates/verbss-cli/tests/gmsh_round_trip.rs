//! Meshes written by Gmsh itself come back from `verbss deform` and
//! `verbss convert` changed only in their node coordinates: physical names,
//! entities, partitions, periodic links, node and element tags, MSH version
//! and encoding are kept (scripts/gmsh_round_trip.py writes the meshes and
//! compares the files).
//!
//! Needs python3 with `gmsh`; without it the tests skip with a notice
//! (`verbss_testkit::needs`).

use std::path::Path;
use std::process::Command;

mod common;

use common::{deform_to, stderr, verbss};
use verbss_testkit::{needs, python};

const SCRIPT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scripts/gmsh_round_trip.py"
);

/// The encodings Gmsh writes each mesh in (file name suffixes).
const ENCODINGS: [&str; 4] = ["4.1_ascii", "4.1_binary", "2.2_ascii", "2.2_binary"];

/// Runs the script with `args`; panics with its output when it fails.
fn script(args: &[&str]) -> String {
    let out = Command::new("python3")
        .arg(SCRIPT)
        .args(args)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{SCRIPT} {args:?} failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

/// Gmsh's meshes written into `dir`, or `false` (skip) without python3 and gmsh.
fn gmsh_meshes(dir: &Path) -> bool {
    if !needs("python3 with gmsh (pip install gmsh)", python(&["gmsh"])) {
        return false;
    }
    script(&["make", dir.to_str().unwrap()]);
    true
}

/// `path` as text.
fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn deform_changes_only_the_coordinates_of_gmsh_files() {
    let dir = tempfile::tempdir().unwrap();
    if !gmsh_meshes(dir.path()) {
        return;
    }
    let cases = [
        ("channel", "cylinder", "0.05,0"),
        ("partitioned", "body", "0.05,0,0"),
        ("periodic", "body", "0,-0.05,0"),
    ];
    for (name, group, translation) in cases {
        for encoding in ENCODINGS {
            let input = dir.path().join(format!("{name}_{encoding}.msh"));
            let output = dir.path().join(format!("{name}_{encoding}.out.msh"));
            let o = deform_to(
                &input,
                &output,
                &["--moving", group, "--translate", translation],
            );
            assert!(o.status.success(), "{name} {encoding}: {}", stderr(&o));
            let report: serde_json::Value =
                serde_json::from_str(&script(&["compare", s(&input), s(&output)])).unwrap();
            let moved = report["moved"].as_u64().unwrap();
            let nodes = report["nodes"].as_u64().unwrap();
            assert!(moved > 0 && moved < nodes, "{name} {encoding}: {report}");
        }
    }
}

#[test]
fn convert_to_the_same_msh_writes_the_file_back_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    if !gmsh_meshes(dir.path()) {
        return;
    }
    for name in ["channel", "partitioned", "periodic"] {
        for encoding in ENCODINGS {
            let input = dir.path().join(format!("{name}_{encoding}.msh"));
            let output = dir.path().join("copy.msh");
            let o = verbss(&["convert", s(&input), s(&output)]);
            assert!(o.status.success(), "{name} {encoding}: {}", stderr(&o));
            assert!(
                std::fs::read(&input).unwrap() == std::fs::read(&output).unwrap(),
                "{name} {encoding}: the copy differs"
            );
        }
    }
}

/// Gmsh's periodic box (its outlet the inlet moved by 2 along x): the links
/// of `$Periodic` are read in every encoding, held while the body moves
/// (above), and a motion of the outlet alone is refused.
#[test]
fn a_periodic_side_moved_without_its_master_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    if !gmsh_meshes(dir.path()) {
        return;
    }
    for encoding in ENCODINGS {
        let input = dir.path().join(format!("periodic_{encoding}.msh"));
        let output = dir.path().join("parted.msh");
        let o = deform_to(
            &input,
            &output,
            &["--moving", "body,outlet", "--translate", "0,-0.05,0"],
        );
        assert_eq!(o.status.code(), Some(2), "{encoding}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.starts_with("error: invalid setting: the periodic patches surface ")
                && e.contains(" would no longer match: node ")
                && e.contains(" is held and its partner, node ")
                && e.contains(", moves; move both sides with one motion, or hold both"),
            "{encoding}: {e}"
        );
        assert!(!output.exists());
    }
}
