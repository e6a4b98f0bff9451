//! End-to-end tests of `verbss run` and `verbss demo`: outputs, exit codes,
//! messages, and the files read back by meshio.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::verbss;
use verbss_testkit::{needs, python};

const SU2: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/su2");

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Checks files with meshio through scripts/check_external_readers.py
/// (skipped with a notice without python3 and meshio, `verbss_testkit::needs`).
fn check_with_meshio(files: &[PathBuf]) {
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scripts/check_external_readers.py"
    );
    if !needs(
        "python3 with meshio (pip install meshio)",
        python(&["meshio"]),
    ) {
        return;
    }
    let out = Command::new("python3")
        .arg(script)
        .args(files)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
}

fn write_case(dir: &Path, body: &str) -> PathBuf {
    let path = dir.join("case.toml");
    std::fs::write(&path, body).unwrap();
    path
}

#[test]
fn a_surface_file_case_writes_series_final_mesh_and_report() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        format!("{SU2}/mesh_NACA0012_inv.su2"),
        dir.path().join("naca.su2"),
    )
    .unwrap();
    std::fs::copy(
        format!("{SU2}/surface_bump.dat"),
        dir.path().join("bump.dat"),
    )
    .unwrap();
    let case = write_case(
        dir.path(),
        r#"
mesh = "naca.su2"
steps = 4
[[motion]]
kind = "positions"
groups = ["airfoil"]
file = "bump.dat"
[output]
every = 3
"#,
    );
    let out_dir = dir.path().join("out");
    let out = verbss(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    // Plain progress lines when not on a terminal.
    assert!(text(&out.stderr).contains("step 4/4: "));
    assert!(text(&out.stdout).starts_with("4 steps in "));
    let mut names: Vec<String> = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "naca.pvd",
            "naca.su2",
            "naca_0000.vtu",
            "naca_0003.vtu",
            "naca_0004.vtu",
            "report.json"
        ]
    );
    // `--every` overrides the case's `output.every`.
    let again = dir.path().join("again");
    let out = verbss(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
        "--every",
        "2",
        "-q",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let pvd = std::fs::read_to_string(again.join("naca.pvd")).unwrap();
    let frames: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| &s[..s.find('"').unwrap()])
        .collect();
    assert_eq!(frames, ["naca_0000.vtu", "naca_0002.vtu", "naca_0004.vtu"]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("report.json")).unwrap())
            .unwrap();
    assert_eq!(report["outcome"], "completed");
    assert_eq!(report["steps"].as_array().unwrap().len(), 5);
    for key in [
        "step",
        "iterations",
        "residual",
        "seconds",
        "min_quality",
        "inverted",
        "bins",
    ] {
        assert!(report["steps"][4].get(key).is_some(), "missing {key}");
    }
    let bins: u64 = report["steps"][4]["bins"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_u64().unwrap())
        .sum();
    assert_eq!(bins, 10216);
    // The final mesh puts every airfoil node where the file says.
    let mesh = verbss::io::read(&out_dir.join("naca.su2")).unwrap();
    let table = verbss::io::positions::read(&dir.path().join("bump.dat"), 2).unwrap();
    for k in 0..table.len() {
        assert_eq!(mesh.point(table.ids[k]), table.point(k));
    }
    check_with_meshio(&[
        out_dir.join("naca_0000.vtu"),
        out_dir.join("naca_0004.vtu"),
        out_dir.join("naca.su2"),
    ]);
}

#[test]
fn an_inverting_case_stops_with_exit_code_3() {
    let dir = tempfile::tempdir().unwrap();
    let case = write_case(
        dir.path(),
        &format!(
            r#"
mesh = "{SU2}/mesh_NACA0012_inv.su2"
steps = 2
# Push the airfoil through the farfield: it must invert elements.
[[motion]]
kind = "translation"
groups = ["airfoil"]
displacement = [40.0, 0.0]
"#
        ),
    );
    let out_dir = dir.path().join("out");
    let out = verbss(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "-q",
    ]);
    assert_eq!(out.status.code(), Some(3));
    let err = text(&out.stderr);
    let first = err.lines().next().unwrap();
    assert!(first.starts_with("error: step 1: element "), "{err}");
    assert!(first.contains(" inverted at ("), "{err}");
    assert!(first.contains("), signed volume -"), "{err}");
    assert!(
        err.contains(&format!(
            "the last valid mesh (step 0) is in {}; the failed state in {}",
            out_dir.join("mesh_NACA0012_inv.su2").display(),
            out_dir.join("mesh_NACA0012_inv.failed.vtu").display()
        )),
        "{err}"
    );
    // The last valid mesh is the input, unchanged.
    let last = verbss::io::read(&out_dir.join("mesh_NACA0012_inv.su2")).unwrap();
    let input = verbss::io::read(Path::new(&format!("{SU2}/mesh_NACA0012_inv.su2"))).unwrap();
    assert_eq!(last.coords, input.coords);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("report.json")).unwrap())
            .unwrap();
    assert!(report["steps"][1]["inverted"].as_u64().unwrap() > 0);
    assert!(report["outcome"]
        .as_str()
        .unwrap()
        .starts_with("step 1: element "));
    // No temporary file is left behind.
    for e in std::fs::read_dir(&out_dir).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".tmp"), "{name}");
    }
    check_with_meshio(&[out_dir.join("mesh_NACA0012_inv.failed.vtu")]);
}

#[test]
fn case_file_errors_name_the_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let case = write_case(dir.path(), "mesh = \"m.su2\"\nsteps = 3\nomega = 1.5\n");
    let out = verbss(&["run", case.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        text(&out.stderr),
        format!(
            "error: {}:3: unknown field `omega`, expected one of `mesh`, `zone`, `steps`, `dt`, `reference`, `solver`, `motion`, `output`\n",
            case.display()
        )
    );
    let case = write_case(
        dir.path(),
        &format!(
            "mesh = \"{SU2}/mesh_NACA0012_inv.su2\"\nsteps = 3\n[[motion]]\nkind = \"fixed\"\ngroups = [\"wing\"]\n"
        ),
    );
    let out = verbss(&["run", case.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        text(&out.stderr),
        format!(
            "error: {}:3: unknown group 'wing' (the mesh has: airfoil, farfield)\n",
            case.display()
        )
    );
}

#[test]
fn demo_runs_160_valid_steps() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("demo");
    let out = verbss(&["demo", "--out", out_dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("160 steps in "), "{stdout}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("report.json")).unwrap())
            .unwrap();
    assert_eq!(report["outcome"], "completed");
    assert_eq!(report["nodes"], 4500);
    let steps = report["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 161);
    assert!(steps
        .iter()
        .all(|s| s["inverted"] == 0 && s["min_quality"].as_f64().unwrap() > 0.05));
    // Every 10th step: 0, 10, …, 160.
    let pvd = std::fs::read_to_string(out_dir.join("naca0012.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 17);
    let frame = std::fs::read_to_string(out_dir.join("naca0012_0040.vtu")).unwrap();
    assert!(frame.contains(r#"compressor="vtkZLibDataCompressor""#));
    let bytes: u64 = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().metadata().unwrap().len())
        .sum();
    assert!(bytes <= 20_000_000, "the demo wrote {bytes} bytes");
    check_with_meshio(&[
        out_dir.join("naca0012_0040.vtu"),
        out_dir.join("naca0012.su2"),
    ]);
}
