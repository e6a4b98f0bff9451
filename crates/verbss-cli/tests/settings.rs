//! The settings have one vocabulary: every setting of the library's table
//! is an option of `verbss deform` with the table's help, and a run's
//! `report.json` `settings`, pasted as a case file's `[solver]` table,
//! runs the same steps to the same bytes.

use std::path::{Path, PathBuf};

mod common;

use common::{read_json, stderr, verbss};

fn naca() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/mesh_NACA0012_inv.su2")
}

#[test]
fn every_setting_is_an_option_with_the_tables_help() {
    let o = verbss(&["deform", "--help"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let help = String::from_utf8_lossy(&o.stdout);
    for setting in verbss::settings::TABLE {
        let flag = format!("--{}", setting.flag());
        assert!(help.contains(&flag), "{flag} missing from --help:\n{help}");
        let first_words: String = setting
            .help
            .split_whitespace()
            .take(4)
            .collect::<Vec<_>>()
            .join(" ");
        let flat: String = help.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(
            flat.contains(&first_words),
            "{flag}: '{first_words}' not in --help"
        );
        assert!(
            flat.contains(&format!("[default: {}]", setting.defaults())),
            "{flag}: its defaults are not in --help"
        );
    }
}

/// A TOML value of a report's JSON setting.
fn toml_value(v: &serde_json::Value) -> String {
    match v {
        serde_json::Value::String(s) => format!("{s:?}"),
        serde_json::Value::Number(n) if n.is_f64() => {
            // TOML floats need a point or an exponent.
            let text = format!("{:?}", n.as_f64().unwrap());
            text
        }
        other => other.to_string(),
    }
}

#[test]
fn a_reports_settings_pasted_as_a_case_file_run_the_same_steps() {
    let dir = tempfile::tempdir().unwrap();
    let direct = dir.path().join("direct.su2");
    let report = dir.path().join("direct.json");
    let o = verbss(&[
        "deform",
        naca().to_str().unwrap(),
        "-o",
        direct.to_str().unwrap(),
        "--moving",
        "airfoil",
        "--rotate",
        "6",
        "--center",
        "0.25,0",
        "--steps",
        "3",
        "--omega",
        "1.55",
        "--tolerance",
        "3e-7",
        "--substeps",
        "2",
        "--rigid-layer",
        "0.03",
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = read_json(&report);
    let settings = r["settings"].as_object().unwrap();
    assert_eq!(settings.len(), verbss::settings::TABLE.len());
    assert_eq!(settings["omega"], 1.55);
    assert_eq!(settings["escalate"], false);
    assert_eq!(settings["reference"], "updated");
    let mut case = format!(
        "mesh = {:?}\nsteps = {}\ndt = {:?}\n\n[solver]\n",
        naca().to_str().unwrap(),
        r["step_count"],
        r["dt"].as_f64().unwrap()
    );
    for (name, value) in settings {
        case += &format!("{name} = {}\n", toml_value(value));
    }
    case += "\n[[motion]]\nkind = \"rotation\"\ngroups = [\"airfoil\"]\ncenter = [0.25, 0.0]\n\
             angle_deg = 6.0\n\n[output]\nseries = false\nreport = true\n";
    let path = dir.path().join("pasted.toml");
    std::fs::write(&path, &case).unwrap();
    let out = dir.path().join("pasted");
    let o = verbss(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{case}\n{}", stderr(&o));
    let pasted = std::fs::read(out.join("mesh_NACA0012_inv.su2")).unwrap();
    assert!(
        pasted == std::fs::read(&direct).unwrap(),
        "the meshes differ"
    );
    let again: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(again["settings"], r["settings"]);
    let sweeps = |r: &serde_json::Value| -> Vec<u64> {
        r["steps"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["iterations"].as_u64().unwrap())
            .collect()
    };
    assert_eq!(sweeps(&again), sweeps(&r));
}
