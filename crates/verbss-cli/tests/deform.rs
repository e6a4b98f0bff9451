//! `verbss deform` end to end on the real NACA0012 mesh.

use std::path::{Path, PathBuf};

mod common;

use common::{read_json, stderr, verbss};

fn naca() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/mesh_NACA0012_inv.su2")
}

fn bump() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/surface_bump.dat")
}

#[test]
fn positions_put_every_listed_node_where_the_file_says() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bump.msh");
    let report = dir.path().join("report.json");
    let o = verbss(&[
        "deform",
        naca().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "airfoil",
        "--positions",
        bump().to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let input = verbss::io::read(&naca()).unwrap();
    let moved = verbss::io::read(&out).unwrap();
    assert_eq!(moved.node_tags, input.node_tags);
    assert_eq!(moved.cells, input.cells);
    let table = verbss::io::positions::read(&bump(), 2).unwrap();
    for k in 0..table.len() {
        assert_eq!(
            moved.point(table.ids[k]),
            table.point(k),
            "node {}",
            table.ids[k]
        );
    }
    let r = read_json(&report);
    let last = r["steps"].as_array().unwrap().last().unwrap().clone();
    for key in [
        "step",
        "iterations",
        "residual",
        "seconds",
        "min_quality",
        "inverted",
        "bins",
        "amplification",
    ] {
        assert!(last.get(key).is_some(), "report step lacks {key}");
    }
    assert_eq!(last["inverted"], 0);
    // The bump moved the wall; the interior followed it.
    assert!(last["amplification"].as_f64().unwrap() > 0.0, "{last}");
}

#[test]
fn a_rotation_with_every_method_keeps_the_mesh_valid() {
    let dir = tempfile::tempdir().unwrap();
    for (method, solver) in [
        ("verbss", "sor"),
        ("ball-vertex", "sor"),
        ("ball-vertex", "direct"),
        ("spring", "sor"),
        ("laplacian", "sor"),
    ] {
        let out = dir.path().join(format!("{method}-{solver}.vtu"));
        let o = verbss(&[
            "deform",
            naca().to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--rotate",
            "-5",
            "--center",
            "0.25,0",
            "--steps",
            "2",
            "--method",
            method,
            "--solver",
            solver,
            "--quiet",
        ]);
        assert!(o.status.success(), "{method}/{solver}: {}", stderr(&o));
        let moved = verbss::io::read(&out).unwrap();
        // The trailing edge (1, 0) turned by −5° about the quarter chord.
        let input = verbss::io::read(&naca()).unwrap();
        let te = input
            .group("airfoil")
            .unwrap()
            .nodes()
            .into_iter()
            .max_by(|&a, &b| input.point(a)[0].total_cmp(&input.point(b)[0]))
            .unwrap();
        let (x, y) = (input.point(te)[0] - 0.25, input.point(te)[1]);
        let a = (-5f64).to_radians();
        let expect = [0.25 + a.cos() * x - a.sin() * y, a.sin() * x + a.cos() * y];
        let got = moved.point(te);
        assert!(
            (got[0] - expect[0]).abs() < 1e-12 && (got[1] - expect[1]).abs() < 1e-12,
            "{method}/{solver}: trailing edge at {got:?}, expected {expect:?}"
        );
    }
}

#[test]
fn the_accelerated_solve_gives_the_direct_solution() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = naca();
    let deform = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec![
            "deform",
            mesh.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--rotate",
            "8",
            "--center",
            "0.25,0",
            "--steps",
            "2",
            "--quiet",
        ];
        args.extend_from_slice(extra);
        (verbss(&args), out)
    };
    let moved = |name: &str, extra: &[&str]| {
        let (o, out) = deform(name, extra);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        verbss::io::read(&out).unwrap()
    };
    let exact = moved(
        "direct.su2",
        &["--method", "ball-vertex", "--solver", "direct"],
    );
    let largest_difference = |a: &verbss::mesh::Mesh, b: &verbss::mesh::Mesh| {
        a.coords
            .iter()
            .zip(&b.coords)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    let fast = moved(
        "amg.su2",
        &[
            "--method",
            "verbss",
            "--accel",
            "amg",
            "--tolerance",
            "1e-11",
        ],
    );
    let diff = largest_difference(&exact, &fast);
    assert!(diff < 1e-8, "largest difference {diff}");
    // The default (robust) method: the same springs, stiffened, around a rigid layer.
    let exact = moved(
        "direct-robust.su2",
        &[
            "--method",
            "ball-vertex",
            "--solver",
            "direct",
            "--rigid-layer",
            "auto",
            "--stiffening",
            "1",
        ],
    );
    let fast = moved(
        "amg-robust.su2",
        &["--accel", "amg", "--tolerance", "1e-11", "--blend", "off"],
    );
    let diff = largest_difference(&exact, &fast);
    assert!(diff < 1e-8, "largest difference {diff}");
    let plain = moved("plain.su2", &["--method", "verbss"]);
    assert!(largest_difference(&exact, &plain) > 1e-4);
    let (o, _) = deform("x.su2", &["--method", "laplacian", "--accel", "amg"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("accel amg solves the block systems of method verbss and spring"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn unknown_group_lists_the_groups_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.su2");
    let o = verbss(&[
        "deform",
        naca().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "wing",
        "--translate",
        "0,1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim(),
        "error: unknown group 'wing' (the mesh has: airfoil, farfield)"
    );
    assert!(!out.exists());
}

#[test]
fn a_motion_of_the_wrong_dimension_is_refused() {
    let o = verbss(&[
        "deform",
        naca().to_str().unwrap(),
        "-o",
        "x.su2",
        "--moving",
        "airfoil",
        "--translate",
        "0,1,0,0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim(),
        "error: --translate needs 2 numbers (or 3 with z = 0) for a 2D mesh, got 4"
    );
}

#[test]
fn pushing_the_airfoil_through_the_farfield_stops_with_exit_3() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("far.su2");
    let o = verbss(&[
        "deform",
        naca().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "airfoil",
        "--translate",
        "0,200",
        "--steps",
        "4",
        "--quiet",
    ]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let msg = stderr(&o);
    assert!(msg.contains("inverted"), "{msg}");
    assert!(dir.path().join("far.failed.vtu").exists());
    // The last valid mesh is in OUT and has no inverted element.
    let last = verbss::io::read(&out).unwrap();
    let reference = verbss::quality::orientation(&verbss::io::read(&naca()).unwrap());
    assert!(verbss::quality::inverted_cells(&last, &last.coords, &reference).is_empty());
}

#[test]
fn slide_groups_keep_their_plane_and_let_nodes_move_in_it() {
    let dir = tempfile::tempdir().unwrap();
    let brick = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes/su2/mesh_brick_tets_ffd.su2");
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec![
            "deform",
            brick.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "x_p",
            "--translate",
            "0,0,0.05",
            "--quiet",
        ];
        args.extend_from_slice(extra);
        let o = verbss(&args);
        (o, out)
    };
    let input = verbss::io::read(&brick).unwrap();
    let plane = input.group("y_m").unwrap().nodes();
    let (o, out) = run("slide.su2", &["--slide", "y_m"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    let mut largest: f64 = 0.0;
    for &i in &plane {
        let (p, q) = (input.point(i), moved.point(i));
        assert_eq!(q[1], p[1], "node {i} left the plane y = 0");
        largest = largest.max((q[2] - p[2]).abs());
    }
    assert!(largest > 0.01, "the plane's nodes moved at most {largest}");
    // Without --slide the plane is a fixed wall.
    let (o, out) = run("fixed.su2", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    let x_p = input.group("x_p").unwrap().nodes();
    for &i in plane.iter().filter(|i| !x_p.contains(i)) {
        assert_eq!(moved.point(i), input.point(i));
    }
    let (o, _) = run("x.su2", &["--slide", "wing"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("'wing'"), "{}", stderr(&o));
    // Normals given on the command line: y = 0 for y_m, y = 1 for y_p.
    let (o, out) = run("normal.su2", &["--slide", "y_m:0,1,0,y_p:0,-1,0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    let on_y_p = input.group("y_p").unwrap().nodes();
    for &i in plane.iter().chain(&on_y_p) {
        assert_eq!(
            moved.point(i)[1],
            input.point(i)[1],
            "node {i} left its plane"
        );
    }
    for (value, message) in [
        (
            "y_m:0,1",
            "error: invalid setting: the slide normal of group 'y_m' has 2 numbers, expected 3 \
             (the mesh's dimension)\n",
        ),
        (
            "y_m:up",
            "error: --slide y_m:up: 'up' is not a number (expected GROUP[:NX,NY[,NZ]])\n",
        ),
        (
            "y_m:0,0,0",
            "error: invalid setting: the slide normal of group 'y_m' must be a finite non-zero \
             vector (got 0, 0, 0)\n",
        ),
    ] {
        let (o, out) = run("bad.su2", &["--slide", value]);
        assert_eq!(o.status.code(), Some(2), "{value}");
        assert_eq!(stderr(&o), message);
        assert!(!out.exists());
    }
}

#[test]
fn every_writes_the_series_of_every_kth_step_beside_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("moved.su2");
    let o = verbss(&[
        "deform",
        naca().to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "airfoil",
        "--translate",
        "0,0.05",
        "--steps",
        "5",
        "--every",
        "2",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "moved.pvd",
            "moved.su2",
            "moved_0000.vtu",
            "moved_0002.vtu",
            "moved_0004.vtu",
            "moved_0005.vtu"
        ]
    );
    // The last frame is the output mesh.
    let last = verbss::io::vtu::read(&dir.path().join("moved_0005.vtu")).unwrap();
    let moved = verbss::io::read(&out).unwrap();
    assert_eq!(last.mesh.coords, moved.coords);
    for bad in ["0", "-1", "x"] {
        let o = verbss(&[
            "deform",
            naca().to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--translate",
            "0,0.05",
            "--every",
            bad,
        ]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        assert!(
            stderr(&o).contains(&format!(
                "expected a whole number of steps ≥ 1, got '{bad}'"
            )),
            "{}",
            stderr(&o)
        );
    }
}

#[test]
fn near_wall_options_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.su2");
    for (option, value, message) in [
        (
            "--rigid-layer",
            "-1",
            "error: invalid setting: rigid_layer must be off, auto or a positive wall distance \
             (got -1)",
        ),
        (
            "--stiffening",
            "nan",
            "error: invalid setting: stiffening must be a finite number ≥ 0 (got NaN)",
        ),
        (
            "--substeps",
            "31",
            "error: invalid setting: substeps must be a whole number from 0 to 30 (got 31)",
        ),
    ] {
        let o = verbss(&[
            "deform",
            naca().to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--rotate",
            "1",
            "--center",
            "0.25,0",
            option,
            value,
        ]);
        assert_eq!(o.status.code(), Some(2), "{option} {value}");
        assert!(stderr(&o).contains(message), "{}", stderr(&o));
    }
}
