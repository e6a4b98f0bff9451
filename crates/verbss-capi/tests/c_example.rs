//! `examples/c/deform.c` compiles against `include/verbss.h` and the shared
//! library cargo built, runs on the repository's meshes, and ends with the
//! coordinates the library computes for the same positions with the same
//! (default, robust) settings, bit for bit.

use std::path::{Path, PathBuf};
use std::process::Command;

use verbss::deform::{Deformer, Reference, Settings};
use verbss::motion::{Attachment, Motion, PositionSource};
use verbss_capi::VerbssSettings;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The relative tolerance of the runs.
const TOLERANCE: f64 = 1e-5;

/// The folder holding the `libverbss_capi.so` built with this test: the
/// test's own `deps/` folder (cargo copies only plain builds' libraries up to
/// the profile folder).
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    assert!(
        dir.join("libverbss_capi.so").exists(),
        "no libverbss_capi.so in {}",
        dir.display()
    );
    dir
}

/// Compiles the example into `dir` and returns the program's path.
fn compile(dir: &Path) -> PathBuf {
    let lib = library_dir();
    let program = dir.join("deform");
    let out = Command::new("cc")
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
        .arg(format!("{ROOT}/examples/c/deform.c"))
        .arg(format!("-I{ROOT}/include"))
        .arg(format!("-L{}", lib.display()))
        .arg("-lverbss_capi")
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .arg("-o")
        .arg(&program)
        .output()
        .expect("cc runs");
    assert!(
        out.status.success(),
        "cc failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    program
}

/// What the library computes when MARKER's nodes are put at their input
/// positions plus `n/steps × shift` at step `n` (as the C example does), with
/// the C API's default settings and TOLERANCE.
fn library_result(mesh: &str, marker: &str, steps: usize, shift: &[f64]) -> Vec<f64> {
    let mesh = verbss_mesh(mesh);
    let c = VerbssSettings::default();
    let mut settings = Settings::robust(steps);
    settings.reference = Reference::Updated;
    settings.solve.omega = c.omega;
    settings.solve.tolerance = TOLERANCE;
    settings.solve.max_iterations = c.max_iterations;
    settings.solve.threads = c.threads;
    let marker_nodes = mesh.group(marker).unwrap().nodes();
    let at = |f: f64| {
        let table = marker_nodes
            .iter()
            .map(|&i| {
                let x = mesh.point(i);
                (i, (0..mesh.dim).map(|d| x[d] + f * shift[d]).collect())
            })
            .collect();
        Motion::Positions(PositionSource::Given(table))
    };
    let attachment = Attachment {
        groups: vec![marker.into()],
        motion: at(0.0),
    };
    let mut deformer = Deformer::new(&mesh, &[attachment], settings).unwrap();
    for n in 1..=steps {
        deformer.set_motion(0, at(n as f64 / steps as f64)).unwrap();
        deformer.step(n).unwrap();
    }
    deformer.current().coords.clone()
}

#[test]
fn c_example_matches_the_library_on_every_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let program = compile(dir.path());
    let cases: [(&str, &str, &[f64]); 4] = [
        ("mesh_NACA0012_inv.su2", "airfoil", &[0.05, 0.1]),
        ("mesh_RAE2822_turb_ffd.su2", "AIRFOIL", &[0.02, -0.03]),
        ("mesh_brick_tets_ffd.su2", "x_p", &[0.2, 0.0, 0.05]),
        ("mesh_brick_hex_ffd.su2", "x_p", &[0.2, 0.0, 0.05]),
    ];
    for (mesh, marker, shift) in cases {
        let steps = 2;
        let out_path = dir.path().join("points.txt");
        let out = Command::new(&program)
            .arg(format!("{ROOT}/assets/meshes/su2/{mesh}"))
            .arg(marker)
            .arg(steps.to_string())
            .arg(TOLERANCE.to_string())
            .arg(&out_path)
            .args(shift.iter().map(|x| x.to_string()))
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{mesh}: {stdout}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(stdout.lines().count(), steps, "{mesh}: {stdout}");
        assert!(stdout.starts_with("step 1: "), "{mesh}: {stdout}");
        let c_points: Vec<f64> = std::fs::read_to_string(&out_path)
            .unwrap()
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let expected = library_result(mesh, marker, steps, shift);
        assert_eq!(c_points.len(), expected.len(), "{mesh}");
        let differ = c_points
            .iter()
            .zip(&expected)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert_eq!(differ, 0, "{mesh}: coordinates that differ");
        assert_ne!(c_points, verbss_mesh(mesh).coords, "{mesh}: nothing moved");
    }
}

fn verbss_mesh(mesh: &str) -> verbss::Mesh {
    verbss::io::read(Path::new(&format!("{ROOT}/assets/meshes/su2/{mesh}"))).unwrap()
}

#[test]
fn c_example_reports_the_api_error_and_its_status() {
    let dir = tempfile::tempdir().unwrap();
    let program = compile(dir.path());
    // A translation that pushes the airfoil through the farfield inverts elements.
    let out = Command::new(&program)
        .arg(format!("{ROOT}/assets/meshes/su2/mesh_NACA0012_inv.su2"))
        .args(["airfoil", "1", "1e-5"])
        .arg(dir.path().join("points.txt"))
        .args(["1000", "0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let mesh = verbss_mesh("mesh_NACA0012_inv.su2");
    let table = mesh
        .group("airfoil")
        .unwrap()
        .nodes()
        .into_iter()
        .map(|i| (i, vec![mesh.point(i)[0] + 1000.0, mesh.point(i)[1]]))
        .collect();
    let attachment = Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::Positions(PositionSource::Given(table)),
    };
    let mut settings = Settings::robust(1);
    settings.solve.tolerance = VerbssSettings::default().tolerance;
    settings.solve.max_iterations = VerbssSettings::default().max_iterations;
    let message = Deformer::new(&mesh, &[attachment], settings)
        .unwrap()
        .step(1)
        .unwrap_err()
        .to_string();
    assert!(message.starts_with("step 1: element "), "{message}");
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!("verbss_deformer_step failed (status 3): {message}\n")
    );
}
