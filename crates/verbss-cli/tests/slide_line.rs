//! A wall moving along the line where two symmetry planes meet, with the
//! default settings: the nodes on that line slide along it, the nodes on
//! one plane stay in it, a node on three groups stays where it is.

use std::collections::HashSet;
use std::path::Path;

mod common;

use common::{stderr, verbss};

#[test]
fn a_wall_moving_along_two_symmetry_planes_drags_their_common_line_with_it() {
    // Prisms, tetrahedra and pyramids (cases/meshes/symmetry_slice.py); the
    // body rests on both planes and moves 4 units along their common line,
    // the x axis, in 4 steps.
    let mesh = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/meshes/symmetry-slice.msh");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("moved.msh");
    let o = verbss(&[
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "body",
        "--translate",
        "4,0,0",
        "--steps",
        "4",
        "--slide",
        "symmetry_y,symmetry_z",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let input = verbss::io::read(&mesh).unwrap();
    let moved = verbss::io::read(&out).unwrap();
    let kinds: HashSet<_> = input.cells.kinds.iter().collect();
    assert_eq!(kinds.len(), 3, "prisms, tetrahedra and pyramids: {kinds:?}");

    let nodes =
        |name: &str| -> HashSet<usize> { input.group(name).unwrap().nodes().into_iter().collect() };
    let (on_y, on_z) = (nodes("symmetry_y"), nodes("symmetry_z"));
    let others: HashSet<usize> = ["body", "inlet", "outlet", "side", "top"]
        .iter()
        .flat_map(|g| nodes(g))
        .collect();
    let mut line: Vec<usize> = on_y
        .intersection(&on_z)
        .filter(|i| !others.contains(i))
        .copied()
        .collect();
    line.sort_by(|&a, &b| input.point(a)[0].total_cmp(&input.point(b)[0]));
    assert!(line.len() >= 10, "{} nodes on the line", line.len());
    for &i in &line {
        let q = moved.point(i);
        assert!(
            q[1].abs() <= 1e-12 && q[2].abs() <= 1e-12,
            "line node {i} left the line: {q:?}"
        );
    }
    // They slid along it, ahead of the body most, and kept their order.
    let ahead = line
        .iter()
        .map(|&i| moved.point(i)[0] - input.point(i)[0])
        .fold(0.0, f64::max);
    assert!(ahead > 0.5, "the line nodes moved at most {ahead}");
    for pair in line.windows(2) {
        assert!(
            moved.point(pair[0])[0] < moved.point(pair[1])[0],
            "line nodes crossed"
        );
    }
    // Nodes on one plane stay in it; each moved in it.
    for (plane, axis) in [(&on_y, 1), (&on_z, 2)] {
        for &i in plane.iter().filter(|i| !others.contains(i)) {
            assert!(
                moved.point(i)[axis].abs() <= 1e-12,
                "node {i} left its plane"
            );
        }
    }
    // Where the planes meet the inlet or the outlet: three groups, fixed.
    let body = nodes("body");
    let ends: Vec<usize> = on_y
        .intersection(&on_z)
        .filter(|j| others.contains(j) && !body.contains(j))
        .copied()
        .collect();
    assert_eq!(ends.len(), 2, "the line's two ends");
    for &j in &ends {
        assert_eq!(
            moved.point(j),
            input.point(j),
            "node {j} on three groups moved"
        );
    }
    let report = verbss(&["quality", out.to_str().unwrap(), "--json"]);
    let summary: serde_json::Value = serde_json::from_slice(&report.stdout).unwrap();
    assert_eq!(summary["inverted"], 0);
    assert!(summary["quality"]["min"].as_f64().unwrap() > 0.0);
}
