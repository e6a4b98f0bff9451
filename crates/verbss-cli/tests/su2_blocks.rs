//! SU2 sections verbss does not use (FFD boxes, periodic data) survive a
//! deformation written as SU2, byte for byte; another format says it drops them.

use std::path::{Path, PathBuf};

mod common;

use common::{stderr, verbss, SQUARE};

/// An FFD box as SU2 writes it after the markers.
const FFD: &str = "FFD_NBOX= 1
FFD_NLEVEL= 1
FFD_TAG= MAIN_BOX
FFD_LEVEL= 0
FFD_DEGREE_I= 1
FFD_DEGREE_J= 1
FFD_BLENDING= BEZIER
FFD_PARENTS= 0
FFD_CHILDREN= 0
FFD_CORNER_POINTS= 4
-0.1\t-0.1
1.1\t-0.1
1.1\t1.1
-0.1\t1.1
FFD_CONTROL_POINTS= 4
0\t0\t0\t-0.1\t-0.1\t-0.5
1\t0\t0\t1.1\t-0.1\t-0.5
0\t1\t0\t-0.1\t1.1\t-0.5
1\t1\t0\t1.1\t1.1\t-0.5
FFD_SURFACE_POINTS= 2
left\t0\t0.0833333\t0.0833333\t0.5
left\t3\t0.0833333\t0.9166667\t0.5
";

fn rae2822() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/mesh_RAE2822_turb_ffd.su2")
}

#[test]
fn a_deformed_su2_mesh_keeps_its_ffd_block_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("box.su2");
    std::fs::write(&mesh, format!("{SQUARE}{FFD}")).unwrap();
    let out = dir.path().join("moved.su2");
    let o = verbss(&[
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "-0.05,0",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.ends_with(&format!("3\t2\t3\n{FFD}")), "{text}");
    let moved = verbss::io::read(&out).unwrap();
    assert_eq!(moved.point(0), &[-0.05, 0.0]);

    let vtu = dir.path().join("moved.vtu");
    let note = format!(
        "note: {} leaves out the input's SU2 sections FFD_NBOX=, FFD_NLEVEL=, FFD_TAG=, … \
         (only an .su2 output keeps them)\n",
        vtu.display()
    );
    let o = verbss(&["convert", out.to_str().unwrap(), vtu.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), note);
    let o = verbss(&[
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        vtu.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "-0.05,0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).starts_with(&note), "{}", stderr(&o));
}

#[test]
fn the_rae2822_mesh_rotated_changes_only_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pitched.su2");
    let o = verbss(&[
        "deform",
        rae2822().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "AIRFOIL",
        "--rotate",
        "-0.5",
        "--center",
        "0.25,0",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let input = std::fs::read_to_string(rae2822()).unwrap();
    let output = std::fs::read_to_string(&out).unwrap();
    // Elements, markers and the periodic and FFD sections are the input's
    // lines; only the points differ.
    let lines = |t: &str| -> Vec<String> { t.lines().map(str::to_string).collect() };
    let (a, b) = (lines(&input), lines(&output));
    assert_eq!(a.len(), b.len());
    let points = a.iter().position(|l| l.starts_with("NPOIN=")).unwrap();
    let nodes = 13937;
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        if k <= points || k > points + nodes {
            assert_eq!(x, y, "line {}", k + 1);
        }
    }
    let before = verbss::io::read(&rae2822()).unwrap();
    let mut after = verbss::io::read(&out).unwrap();
    assert_ne!(after.coords, before.coords);
    after.coords.clone_from(&before.coords);
    assert_eq!(after, before);
}
