//! The benchmark scripts still work: `bench/compare.py --smoke` (a tiny
//! sphere-in-a-cube mesh and the smallest of the paper's 2D rectangles, two
//! steps of every verbss variant on 1 and 2 threads, without OpenFOAM).
//! It runs the binaries this `cargo test` built (`--bin-dir`: the
//! `motion_bench` example of this crate and the `verbss` binary, which
//! `cargo test --workspace` builds for the CLI's tests), so it compiles
//! nothing itself. Needs python3 with gmsh (CI installs it); elsewhere,
//! without them or without the `verbss` binary, the test says so and checks
//! nothing.

use std::path::Path;
use std::process::Command;

fn python_has_gmsh() -> bool {
    Command::new("python3")
        .args(["-c", "import gmsh"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Says why the test checks nothing; under CI, where everything it needs is
/// installed and built, fails instead.
fn skip(why: &str) {
    assert!(
        std::env::var_os("CI").is_none(),
        "the benchmark smoke test cannot be skipped under CI: {why}"
    );
    eprintln!("skipped: {why}");
}

#[test]
fn compare_script_runs_in_smoke_mode() {
    if !python_has_gmsh() {
        return skip("python3 with gmsh is not installed");
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let exe = std::env::current_exe().expect("the test's own path");
    let bin_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("the test runs from <target>/<profile>/deps");
    if !bin_dir.join("verbss").is_file() {
        return skip(&format!(
            "no verbss binary in {} (cargo test --workspace builds it)",
            bin_dir.display()
        ));
    }
    let work = std::env::temp_dir().join(format!("verbss-bench-smoke-{}", std::process::id()));
    for extra in [&[][..], &["--series-2d"][..]] {
        let out = Command::new("python3")
            .arg(root.join("bench/compare.py"))
            .args(["--smoke", "--no-openfoam", "--work"])
            .arg(&work)
            .arg("--bin-dir")
            .arg(bin_dir)
            .args(extra)
            .current_dir(&root)
            .output()
            .expect("python3 runs");
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "compare.py --smoke {extra:?} failed:\n{stdout}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        for variant in [
            "| verbss updated none previous | 1 |",
            "| verbss updated none linear | 2 |",
            "| verbss updated amg linear | 1 |",
            "| verbss fixed none linear | 2 |",
        ] {
            assert!(stdout.contains(variant), "{variant} missing:\n{stdout}");
        }
    }
    std::fs::remove_dir_all(&work).ok();
}
