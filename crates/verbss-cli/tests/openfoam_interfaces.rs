//! OpenFOAM cases with interfaces: the coincident points of an AMI or ACMI
//! interface (and of blockMesh's baffles) move each with its own side, and
//! a cyclic pair stays matched or the run is refused (docs/openfoam.md,
//! "Interfaces"). Every moved mesh passes checkMesh.

use std::path::Path;

mod common;

use common::foam::{
    check_mesh_failures, copy_tutorial, count_after, foam, have_tutorial, have_utilities,
    ring_case, write_system,
};
use common::{deform_to, stderr, verbss};
use verbss::Mesh;

/// The largest distance of a node of group `g` from where `to` takes it.
fn off(input: &Mesh, moved: &Mesh, g: &str, to: impl Fn(&[f64]) -> [f64; 2]) -> f64 {
    input
        .group(g)
        .unwrap()
        .nodes()
        .into_iter()
        .map(|i| {
            let (p, q) = (to(input.point(i)), moved.point(i));
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(0.0, f64::max)
}

#[test]
fn mixer_vessel_ami_2d_turns_its_rotor_with_its_side_of_the_interface() {
    let name = "incompressible/pimpleFoam/laminar/mixerVesselAMI2D";
    if !have_tutorial(name) || !have_utilities(&["blockMesh", "topoSet", "checkMesh"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("mixer");
    copy_tutorial(name, &case);
    // Its makeMesh: m4, blockMesh, topoSet.
    let dict = std::process::Command::new("m4")
        .arg(case.join("system/blockMeshDict.m4"))
        .output()
        .expect("run m4");
    assert!(dict.status.success());
    std::fs::write(case.join("system/blockMeshDict"), dict.stdout).unwrap();
    foam("blockMesh", &case, &[]);
    foam("topoSet", &case, &[]);
    let input = verbss::io::read(&case).unwrap();
    assert_eq!((input.dim, input.cell_count()), (2, 3072));
    // Before, refused: `nodes 350 and 651 are at the same position
    // (0.000000, -0.020000): duplicate nodes` (the two sides of the AMI).
    let out = dir.path().join("turned");
    // About the origin of its dynamicMeshDict's rotatingMotion, in one step.
    let o = deform_to(
        &case,
        &out,
        &[
            "--moving",
            "rotor,AMI1",
            "--rotate",
            "90",
            "--center",
            "0,0",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    let quarter = |p: &[f64]| [-p[1], p[0]];
    let same = |p: &[f64]| [p[0], p[1]];
    for (g, to) in [
        ("rotor", &quarter as &dyn Fn(&[f64]) -> [f64; 2]),
        ("AMI1", &quarter),
        ("AMI2", &same),
        ("stator", &same),
    ] {
        assert!(off(&input, &moved, g, to) < 1e-12, "{g}");
    }
    write_system(&out);
    assert_eq!(check_mesh_failures(&out, &[]), Vec::<String>::new());
}

#[test]
fn oscillating_inlet_acmi_2d_slides_its_inlet_channel_along_the_interface() {
    let name = "incompressible/pimpleFoam/RAS/oscillatingInletACMI2D";
    let tools = ["blockMesh", "topoSet", "createBaffles", "checkMesh"];
    if !have_tutorial(name) || !have_utilities(&tools) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("acmi");
    copy_tutorial(name, &case);
    // Its Allrun.pre: blockMesh, topoSet, createBaffles.
    foam("blockMesh", &case, &[]);
    foam("topoSet", &case, &["-constant"]);
    foam("createBaffles", &case, &["-overwrite"]);
    let log = foam("checkMesh", &case, &[]);
    assert_eq!(count_after(&log, "polyhedra:"), Some(136), "{log}");
    let input = verbss::io::read(&case).unwrap();
    assert_eq!((input.dim, input.cell_count()), (2, 10880));
    let o = verbss(&["quality", case.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["inverted"], 0, "{v}");
    // Its dynamicMeshDict moves the cell zone of the inlet channel (x < 1)
    // as a solid body along y: the channel's patches go up 0.1, its side
    // of the interface with them, given as positions; the outlet's walls
    // (in the same patch) stay.
    let groups = ["inlet", "walls", "ACMI1_couple", "ACMI1_blockage"];
    let mut nodes: Vec<usize> = groups
        .iter()
        .flat_map(|g| input.group(g).unwrap().nodes())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    let channel: Vec<usize> = input.group("ACMI1_couple").unwrap().nodes();
    let up = |i: usize| input.point(i)[0] < 1.0 - 1e-9 || channel.contains(&i);
    let mut table = String::from("id,x,y\n");
    for &i in &nodes {
        let p = input.point(i);
        let dy = if up(i) { 0.1 } else { 0.0 };
        table += &format!("{i},{},{}\n", p[0], p[1] + dy);
    }
    let positions = dir.path().join("up.csv");
    std::fs::write(&positions, table).unwrap();
    let out = dir.path().join("slid");
    let o = deform_to(
        &case,
        &out,
        &[
            "--moving",
            &groups.join(","),
            "--positions",
            positions.to_str().unwrap(),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    let raised = |p: &[f64]| [p[0], p[1] + 0.1];
    let same = |p: &[f64]| [p[0], p[1]];
    assert!(off(&input, &moved, "ACMI1_couple", raised) < 1e-12);
    assert!(off(&input, &moved, "ACMI2_couple", same) == 0.0);
    assert!(off(&input, &moved, "outlet", same) == 0.0);
    write_system(&out);
    assert_eq!(check_mesh_failures(&out, &[]), Vec::<String>::new());
}

/// A square body (patch `wing`, side 1) in a 2D box of side 3, 8 blocks of
/// `n × n` cells, one cell thick: its left and right sides (`lo`, `hi`) a
/// cyclic pair, its bottom and top `walls`.
fn periodic_box(case: &Path, n: usize) {
    ring_case(
        case,
        n,
        1,
        ["walls", "hi", "walls", "lo"],
        &[
            ("lo", "cyclic; neighbourPatch hi"),
            ("hi", "cyclic; neighbourPatch lo"),
            ("walls", "wall"),
        ],
    );
}

#[test]
fn a_cyclic_pair_is_held_by_default_and_a_motion_that_parts_it_is_refused() {
    if !have_utilities(&["blockMesh", "checkMesh"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("periodic");
    periodic_box(&case, 6);
    let input = verbss::io::read(&case).unwrap();
    let out = dir.path().join("moved");
    let o = deform_to(
        &case,
        &out,
        &["--moving", "wing", "--translate", "0.2,0.1", "--steps", "2"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    let same = |p: &[f64]| [p[0], p[1]];
    assert!(off(&input, &moved, "lo", same) == 0.0 && off(&input, &moved, "hi", same) == 0.0);
    write_system(&out);
    assert_eq!(check_mesh_failures(&out, &[]), Vec::<String>::new());
    // One side moved with the body: refused before the first step.
    let o = deform_to(
        &case,
        &dir.path().join("parted"),
        &["--moving", "wing,lo", "--translate", "0.2,0"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.starts_with("error: invalid setting: the periodic patches lo and hi would no longer match: node ")
            && e.contains(" of lo moves and its partner, node ")
            && e.ends_with(" of hi, is held; move both sides with one motion, or hold both (the default for a group no motion names)\n"),
        "{e}"
    );
    // The walls (whose ends are on both sides) turned: the ends part at
    // the first step.
    let o = deform_to(
        &case,
        &dir.path().join("turned"),
        &["--moving", "walls", "--rotate", "2", "--center", "0,0"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.starts_with(
            "error: invalid setting: step 1: the periodic patches lo and hi no longer match: node "
        ) && e.contains("moved by their translation by (3.000000, 0.000000, 0.000000) to "),
        "{e}"
    );
}
