//! The paper's case files and the `verbss-paper` runner, end to end on the
//! smallest case.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;
use verbss::case::Case;
use verbss_testkit::{needs, program};

const NAMES: [&str; 10] = [
    "rectangle-298",
    "rectangle-1035",
    "rectangle-3055",
    "rectangle-8081",
    "rectangle-21376",
    "naca0012",
    "three-element",
    "sphere-cube",
    "two-fish",
    "bending-wing",
];

/// Meshes too large for the repository, generated on first use.
const GENERATED: [&str; 3] = ["rectangle-21376", "two-fish", "bending-wing"];

fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases")
}

#[test]
fn every_case_file_parses_and_its_committed_mesh_loads_with_its_groups() {
    for name in NAMES {
        let case = Case::read(&cases_dir().join(format!("{name}.toml"))).unwrap();
        assert_eq!(
            case.mesh.file_name().unwrap().to_string_lossy(),
            format!("{name}.msh"),
            "{name}"
        );
        if GENERATED.contains(&name) {
            continue;
        }
        let mesh = verbss::io::read(&case.mesh).unwrap();
        let attachments = case.attachments(&mesh).unwrap();
        assert!(!attachments.is_empty(), "{name}");
        let expected_dim = if ["sphere-cube", "two-fish", "bending-wing"].contains(&name) {
            3
        } else {
            2
        };
        assert_eq!(mesh.dim, expected_dim, "{name}");
    }
}

#[test]
fn committed_meshes_are_within_five_percent_of_the_papers_node_counts() {
    let paper = [
        ("rectangle-298", 298),
        ("rectangle-1035", 1035),
        ("rectangle-3055", 3055),
        ("rectangle-8081", 8081),
        ("naca0012", 4485),
        ("three-element", 11372),
        ("sphere-cube", 2058),
    ];
    for (name, nodes) in paper {
        let mesh = verbss::io::read(&cases_dir().join(format!("meshes/{name}.msh"))).unwrap();
        let off = (mesh.node_count() as f64 - nodes as f64).abs() / nodes as f64;
        assert!(off < 0.05, "{name}: {} nodes", mesh.node_count());
    }
}

#[test]
fn every_generated_mesh_has_its_script() {
    let scripts = [
        "rectangle.py",
        "naca0012.py",
        "three_element.py",
        "sphere_cube.py",
        "two_fish.py",
        "bending_wing.py",
    ];
    for s in scripts {
        assert!(cases_dir().join("meshes").join(s).is_file(), "{s}");
    }
}

fn run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verbss-paper"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn the_smallest_case_writes_every_methods_results_and_the_paper_tables() {
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().to_str().unwrap();
    let output = run(&["--case", "rectangle-298", "--out", dir]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("results.json")).unwrap())
            .unwrap();
    let case = &json["cases"][0];
    assert_eq!(case["name"], "rectangle-298");
    assert_eq!(case["nodes"], 304);
    let methods = case["methods"].as_array().unwrap();
    let names: Vec<&str> = methods
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["spring", "laplacian", "ball-vertex", "verbss"]);
    for m in methods {
        let limit = m["limit"].as_f64().unwrap();
        assert!(limit > 0.0 && limit <= 6.9, "{m}");
        assert!(m["iterations_per_step"].as_f64().unwrap() >= 1.0, "{m}");
        assert!(m["seconds_per_step"].as_f64().unwrap() >= 0.0, "{m}");
        assert_eq!(m["bins"][0]["amplitude"], 4.0, "{m}");
    }
    let counts = |k: usize| methods[k]["bins"][0]["counts"].clone();
    let bv = counts(2);
    assert_eq!(
        bv.as_array()
            .unwrap()
            .iter()
            .map(|c| c.as_u64().unwrap())
            .sum::<u64>(),
        540
    );
    assert_eq!(
        bv,
        counts(3),
        "ball-vertex and verbss histograms at 4.0 units"
    );
    let paper = std::fs::read_to_string(out.path().join("PAPER.md")).unwrap();
    for heading in ["## Table 1:", "## Table 2:", "## Largest motion"] {
        assert!(paper.contains(heading), "{heading}");
    }
    for p in case["pictures"].as_array().unwrap() {
        let file = out.path().join(p.as_str().unwrap());
        assert!(std::fs::read(&file).unwrap().starts_with(b"\x89PNG"), "{p}");
    }
}

#[test]
fn an_unknown_case_is_named_with_the_known_ones() {
    let output = run(&["--case", "wing", "--out", "unused"]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(
            "unknown case 'wing' (one of: rectangle-298, rectangle-1035, rectangle-3055, \
rectangle-8081, rectangle-21376, naca0012, three-element, sphere-cube, two-fish, bending-wing)"
        ),
        "{stderr}"
    );
}

#[test]
fn a_missing_mesh_whose_script_cannot_import_gmsh_says_what_to_install() {
    if !needs("python3", program("python3", &["--version"])) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        cases_dir().join("rectangle-298.toml"),
        dir.path().join("rectangle-298.toml"),
    )
    .unwrap();
    std::fs::create_dir(dir.path().join("meshes")).unwrap();
    std::fs::write(
        dir.path().join("meshes/rectangle.py"),
        "import sys\nsys.exit(\"ModuleNotFoundError: No module named 'gmsh'\")\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let output = run(&[
        "--case",
        "rectangle-298",
        "--cases-dir",
        dir.path().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    let mesh = dir.path().join("meshes/rectangle-298.msh");
    let script = dir.path().join("meshes/rectangle.py");
    let expected = format!(
        "cannot generate {}: {} failed (Gmsh's Python API is needed: pip install gmsh): \
ModuleNotFoundError: No module named 'gmsh'",
        mesh.display(),
        script.display()
    );
    assert!(stderr.contains(&expected), "{stderr}");
}
