//! The `verbss` binary end to end: `quality`, `convert`, exit codes and messages.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;

use common::{stderr, verbss};

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes")
        .join(name)
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn quality_json_has_the_documented_shape() {
    let o = verbss(&[
        "quality",
        asset("su2/mesh_NACA0012_inv.su2").to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(
        keys,
        [
            "dimension",
            "nodes",
            "elements",
            "kinds",
            "groups",
            "quality",
            "inverted",
            "checkmesh"
        ]
    );
    assert_eq!(v["dimension"], 2);
    assert_eq!(v["nodes"], 5233);
    assert_eq!(v["elements"], 10216);
    assert_eq!(v["kinds"], serde_json::json!({"triangle": 10216}));
    assert_eq!(
        v["groups"],
        serde_json::json!({"airfoil": 200, "farfield": 50})
    );
    assert_eq!(v["inverted"], 0);
    let bins = v["quality"]["bins"].as_array().unwrap();
    let edges: Vec<(f64, f64)> = bins
        .iter()
        .map(|b| (b["lo"].as_f64().unwrap(), b["hi"].as_f64().unwrap()))
        .collect();
    assert_eq!(
        edges,
        [(0.0, 0.02), (0.02, 0.1), (0.1, 0.4), (0.4, 0.7), (0.7, 1.0)]
    );
    let total: u64 = bins.iter().map(|b| b["count"].as_u64().unwrap()).sum();
    assert_eq!(total, 10216);
    let min = v["quality"]["min"].as_f64().unwrap();
    let mean = v["quality"]["mean"].as_f64().unwrap();
    assert!(0.0 < min && min <= mean && mean <= 1.0);
}

#[test]
fn a_reader_that_stops_early_ends_the_program_quietly() {
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args([
            "quality",
            asset("su2/mesh_RAE2822_turb_ffd.su2").to_str().unwrap(),
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run verbss");
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(141));
    assert_eq!(stderr(&o), "");
}

#[test]
fn quality_table_for_a_hybrid_mesh() {
    let o = verbss(&[
        "quality",
        asset("su2/mesh_RAE2822_turb_ffd.su2").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("triangle     18042"), "{out}");
    assert!(out.contains("quad         4800"), "{out}");
    assert!(out.contains("inverted   0"), "{out}");
}

/// Issue 43, 18: a group name longer than 12 characters pushed its count
/// out of the column.
#[test]
fn quality_table_aligns_long_group_names() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(asset("su2/mesh_NACA0012_inv.su2")).unwrap();
    let long = "airfoil_surface_of_the_wing";
    let mesh = dir.path().join("long.su2");
    std::fs::write(
        &mesh,
        text.replace("MARKER_TAG= airfoil", &format!("MARKER_TAG= {long}")),
    )
    .unwrap();
    let o = verbss(&["quality", mesh.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let rows: Vec<&str> = out
        .lines()
        .skip_while(|l| !l.starts_with("  elements"))
        .skip(1)
        .take_while(|l| !l.starts_with("  quality"))
        .filter(|l| l.starts_with("    "))
        .collect();
    assert_eq!(rows.len(), 3, "{out}");
    let column: Vec<usize> = rows.iter().map(|r| r.rfind(' ').unwrap()).collect();
    assert!(column.iter().all(|&c| c == column[0]), "{out}");
    assert!(out.contains(&format!("    {long} 200\n")), "{out}");
    assert!(
        out.contains(&format!(
            "    triangle{} 10216\n",
            " ".repeat(long.len() - 8)
        )),
        "{out}"
    );
}

#[test]
fn convert_round_trips_through_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let src = asset("su2/mesh_RAE2822_turb_ffd.su2");
    let reference = verbss(&["quality", src.to_str().unwrap(), "--json"]);
    let mut previous = src.clone();
    for (name, extra) in [
        ("a.msh", vec!["--msh-version", "2.2"]),
        ("b.msh", vec!["--msh-version", "4.1", "--binary"]),
        ("c.vtu", vec![]),
        ("d.msh", vec!["--msh-version", "2.2", "--binary"]),
        ("e.su2", vec![]),
    ] {
        let out = dir.path().join(name);
        let mut args = vec!["convert", previous.to_str().unwrap(), out.to_str().unwrap()];
        args.extend(extra);
        let o = verbss(&args);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let q = verbss(&["quality", out.to_str().unwrap(), "--json"]);
        assert_eq!(stdout(&q), stdout(&reference), "{name}");
        previous = out;
    }
    let mut a = verbss::io::read(&src).unwrap();
    let b = verbss::io::read(&previous).unwrap();
    // The FFD and periodic sections do not pass through the other formats.
    assert!(!a.origin.su2_skipped.is_empty() && b.origin.su2_skipped.is_empty());
    a.origin.su2_skipped.clear();
    assert_eq!(a, b);
}

#[test]
fn a_missing_file_is_exit_2_with_its_name() {
    let o = verbss(&["quality", "no/such/mesh.su2"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim(),
        "error: no/such/mesh.su2: No such file or directory (os error 2)"
    );
}

#[test]
fn an_unknown_extension_is_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("mesh.obj");
    let o = verbss(&[
        "convert",
        asset("su2/mesh_NACA0012_inv.su2").to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(
            "unknown mesh format (expected .msh, .su2, .vtu, .cgns or an OpenFOAM case directory)"
        ),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

#[test]
fn a_truncated_file_names_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(asset("su2/mesh_NACA0012_inv.su2")).unwrap();
    let cut: String = text.lines().take(100).map(|l| format!("{l}\n")).collect();
    let path = dir.path().join("cut.su2");
    std::fs::write(&path, cut).unwrap();
    let o = verbss(&["quality", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let msg = stderr(&o);
    assert!(
        msg.starts_with(&format!("error: {}:", path.display())),
        "{msg}"
    );
    assert_eq!(msg.lines().count(), 1, "{msg}");
}

/// `-q` prints nothing on success (no progress, no summary line); without
/// it the summary counts one step as `1 step`.
#[test]
fn quiet_prints_nothing_and_one_step_is_singular() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = asset("su2/mesh_NACA0012_inv.su2");
    let out = dir.path().join("pitched.su2");
    let args = [
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "airfoil",
        "--rotate",
        "1",
        "--center",
        "0.25,0",
        "--steps",
        "1",
    ];
    let o = verbss(&[&args[..], &["-q"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "");
    assert_eq!(stderr(&o), "");
    let o = verbss(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("1 step in "), "{}", stdout(&o));
}
