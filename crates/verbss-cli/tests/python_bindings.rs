//! The Python bindings' tests (`python/tests`, pytest) against this build of
//! the `verbss` command: the bindings give the coordinates, quality summary
//! and error messages the command gives. It lives with the command's tests
//! because cargo builds the command for them (`CARGO_BIN_EXE_verbss`).
//!
//! Needs `python3` with the package installed (`pip install ./python`),
//! `pytest`, `meshio` and `matplotlib`; without them the test skips with a
//! notice (`verbss_testkit::needs`).

use std::process::Command;

use verbss_testkit::{needs, python};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

#[test]
fn python_tests_pass_against_this_command() {
    if !needs(
        "python3 with verbss (pip install ./python), pytest, meshio and matplotlib",
        python(&["verbss", "pytest", "meshio", "matplotlib"]),
    ) {
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
