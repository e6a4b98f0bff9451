//! A Gmsh file split by Gmsh's partitioner, read by one process, is the
//! mesh of the unsplit file (issue 43, 17): the partition curves between
//! partitions, even with elements and their parent surface's physical tag
//! (scripts/gmsh_partitioned_airfoil.py writes both files), are no groups,
//! so `quality` and `deform` give what they give on the unsplit file.
//!
//! Needs python3 with `gmsh`; without it the test skips with a notice.

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

mod common;

use common::{stderr, verbss};
use verbss_testkit::{needs, python};

const SCRIPT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scripts/gmsh_partitioned_airfoil.py"
);

/// `verbss ARGS…`, which must succeed: its standard output.
fn ok(args: &[&str]) -> String {
    let o = verbss(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    String::from_utf8(o.stdout).unwrap()
}

/// Each node's position by its tag.
fn by_tag(path: &Path) -> HashMap<u64, Vec<f64>> {
    let mesh = verbss::io::read(path).unwrap();
    (0..mesh.node_count())
        .map(|i| (mesh.node_tags[i], mesh.point(i).to_vec()))
        .collect()
}

#[test]
fn a_file_split_by_gmsh_reads_and_deforms_as_the_unsplit_file() {
    if !needs("python3 with gmsh (pip install gmsh)", python(&["gmsh"])) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new("python3")
        .arg(SCRIPT)
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (whole, split) = (dir.path().join("whole.msh"), dir.path().join("split.msh"));
    let text = std::fs::read_to_string(&split).unwrap();
    assert!(text.contains("$PartitionedEntities"));
    let json = |p: &Path| -> serde_json::Value {
        serde_json::from_str(&ok(&["quality", p.to_str().unwrap(), "--json"])).unwrap()
    };
    let (mut a, mut b) = (json(&whole), json(&split));
    assert_eq!(
        a["groups"],
        serde_json::json!({"airfoil": 49, "farfield": 57})
    );
    // The mean is summed in each file's element order: equal to rounding.
    let (ma, mb) = (
        a["quality"]["mean"].take().as_f64().unwrap(),
        b["quality"]["mean"].take().as_f64().unwrap(),
    );
    assert!((ma - mb).abs() <= 1e-14, "{ma} {mb}");
    assert_eq!(a, b);
    let mut moved = Vec::new();
    for input in [&whole, &split] {
        let output = dir.path().join(format!(
            "moved_{}",
            input.file_name().unwrap().to_str().unwrap()
        ));
        ok(&[
            "deform",
            input.to_str().unwrap(),
            "-o",
            output.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--rotate",
            "5",
            "--center",
            "0.5,0",
            "--steps",
            "2",
            "--tolerance",
            "1e-12",
            "-q",
        ]);
        moved.push(by_tag(&output));
    }
    // Solved to 1e-12 of the motion, in each file's own node order: the
    // same positions to far below the motion (0.04 at the trailing edge).
    assert_eq!(moved[0].len(), moved[1].len());
    let worst = moved[0]
        .iter()
        .map(|(tag, p)| {
            let q = &moved[1][tag];
            (p[0] - q[0]).abs().max((p[1] - q[1]).abs())
        })
        .fold(0.0, f64::max);
    eprintln!("largest difference between the deformed files: {worst:e}");
    assert!(worst <= 1e-9, "{worst}");
}
