//! The Python bindings' tests (`python/tests`, pytest) against this build of
//! the `verbss` command: the bindings give the coordinates, quality summary
//! and error messages the command gives. It lives with the command's tests
//! because cargo builds the command for them (`CARGO_BIN_EXE_verbss`).
//!
//! Needs `python3` with the package installed (`pip install ./python`),
//! `pytest`, `meshio` and `matplotlib`. Without them the test prints
//! "skipped: …" and passes, unless the `CI` environment variable is set, in
//! which case it fails.

use std::process::Command;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// Whether python3 can import the bindings and the test tools; otherwise
/// fails under CI and says "skipped" elsewhere.
fn python_ready() -> bool {
    let probe = Command::new("python3")
        .args(["-c", "import verbss, pytest, meshio, matplotlib"])
        .output();
    let why = match probe {
        Ok(out) if out.status.success() => return true,
        Ok(out) => String::from_utf8_lossy(&out.stderr).trim().to_string(),
        Err(e) => format!("python3: {e}"),
    };
    if std::env::var_os("CI").is_some() {
        panic!("python3 with verbss (pip install ./python), pytest, meshio and matplotlib is required under CI: {why}");
    }
    println!(
        "skipped: python3 with verbss, pytest, meshio and matplotlib is not available ({why})"
    );
    false
}

#[test]
fn python_tests_pass_against_this_command() {
    if !python_ready() {
        return;
    }
    let out = Command::new("python3")
        .args([
            "-m",
            "pytest",
            "python/tests",
            "-q",
            "-p",
            "no:cacheprovider",
        ])
        .current_dir(ROOT)
        .env("VERBSS_CLI", env!("CARGO_BIN_EXE_verbss"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    println!("{stdout}");
    assert!(
        out.status.success(),
        "pytest failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!stdout.contains("skipped"), "{stdout}");
}
