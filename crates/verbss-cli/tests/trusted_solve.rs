//! The default solve escalates until every node's error is trusted; a solve
//! that cannot be trusted stops with exit code 4, never as bad input.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;

use common::{stderr, verbss};

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

/// `verbss deform MESH -o DIR/OUT --quiet --report DIR/report.json ARGS…`
/// (`mesh` relative to the repository): its output and its report.
fn deform(dir: &Path, mesh: &str, out: &str, args: &[&str]) -> (Output, serde_json::Value) {
    let mesh = repo(mesh);
    let out = dir.join(out);
    let report = dir.join("report.json");
    let mut all = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ];
    all.extend_from_slice(args);
    let o = verbss(&all);
    let r = serde_json::from_str(&std::fs::read_to_string(report).unwrap()).unwrap();
    (o, r)
}

/// The structured C-grid (wake cells 1e-5 high, aspect ratio 1.4e5)
/// pitched 3° in 3 steps, with `extra` arguments.
fn pitch_cgrid(dir: &Path, extra: &[&str]) -> (Output, serde_json::Value) {
    let mut args = vec![
        "--moving", "airfoil", "--rotate", "3", "--center", "0.25,0", "--steps", "3",
    ];
    args.extend_from_slice(extra);
    deform(dir, "cases/meshes/cgrid-113x33.msh", "pitched.msh", &args)
}

#[test]
fn the_default_blends_a_rigid_pitch_and_solves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (o, r) = pitch_cgrid(dir.path(), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(r["settings"]["method"], "robust");
    assert_eq!(r["settings"]["blend"], true);
    for step in &r["steps"].as_array().unwrap()[1..] {
        assert_eq!(step["stages"].as_array().unwrap().len(), 0, "{step}");
        assert_eq!(step["iterations"], 0);
        assert_eq!(step["inverted"], 0);
    }
}

/// The springs' solve on its own: the default without the blend.
#[test]
fn the_default_escalates_where_the_sweeps_diverge_and_records_what_ran() {
    let dir = tempfile::tempdir().unwrap();
    let (o, r) = pitch_cgrid(dir.path(), &["--blend", "off"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = &r["settings"];
    assert_eq!(s["method"], "verbss");
    assert_eq!(s["blend"], false);
    assert_eq!(s["escalate"], true);
    assert_eq!(s["accel"], "auto");
    assert_eq!(s["predictor"], "previous");
    assert_eq!(s["rigid_layer"], "auto");
    assert_eq!(s["stiffening"], 1.0);
    assert_eq!(s["substeps"], 6);
    assert_eq!(s["omega"], 1.6);
    let steps = r["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 4);
    let first: Vec<&str> = steps[1]["stages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(first[0], "sweeps", "{first:?}");
    assert!(
        first.len() >= 2,
        "the ω = 1.6 sweeps diverge here: {first:?}"
    );
    for step in &steps[1..] {
        assert_eq!(step["converged"], true);
        let ratio = step["error_ratio"].as_f64().unwrap();
        assert!(ratio <= 0.01, "step {}: {ratio}", step["step"]);
        assert!(step["true_residual"].as_f64().unwrap().is_finite());
    }
}

#[test]
fn an_explicit_omega_means_that_solver_only_and_a_diverged_solve_is_exit_4() {
    let dir = tempfile::tempdir().unwrap();
    let (o, r) = pitch_cgrid(
        dir.path(),
        &["--omega", "1.6", "--substeps", "0", "--blend", "off"],
    );
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("error: step 1: the solve did not converge (stages tried: sweeps; "),
        "{e}"
    );
    assert!(!e.contains("invalid setting"), "{e}");
    assert_eq!(r["settings"]["escalate"], false);
    assert!(r["outcome"].as_str().unwrap().contains("did not converge"));
    // As for an inversion: the last valid mesh (the input) and the failed state.
    assert!(dir.path().join("pitched.msh").exists());
    assert!(dir.path().join("pitched.failed.vtu").exists());
}

const NACA: &str = "assets/meshes/su2/mesh_NACA0012_inv.su2";

/// `--method verbss` on the NACA0012 rotated 5°, with `extra`.
fn rotate_naca(dir: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "--moving", "airfoil", "--rotate", "5", "--center", "0.25,0", "--method", "verbss",
    ];
    args.extend_from_slice(extra);
    deform(dir, NACA, "rotated.su2", &args).0
}

#[test]
fn diverging_sweeps_say_omega_is_too_large() {
    let dir = tempfile::tempdir().unwrap();
    let o = rotate_naca(dir.path(), &["--omega", "1.95"]);
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("the sweeps diverged: omega too large for this mesh)"),
        "{e}"
    );
    // Without the explicit ω the default escalates and completes.
    let o = rotate_naca(dir.path(), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_step_is_rejected_for_an_inversion_only_after_its_exact_solve() {
    let dir = tempfile::tempdir().unwrap();
    let (o, r) = deform(
        dir.path(),
        NACA,
        "pushed.su2",
        &[
            "--moving",
            "airfoil",
            "--translate",
            "30,0",
            "--substeps",
            "0",
            "--blend",
            "off",
        ],
    );
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let failed = r["steps"].as_array().unwrap().last().unwrap();
    assert_eq!(failed["step"], 1);
    let stages = failed["stages"].as_array().unwrap();
    assert_eq!(stages.last().unwrap(), "direct", "{stages:?}");
}
