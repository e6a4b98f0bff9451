//! The benchmark scripts still work: `bench/compare.py --smoke` (a tiny
//! sphere-in-a-cube mesh and the smallest of the paper's 2D rectangles, two
//! steps of every verbss variant, the command line's defaults included, on 1
//! and 2 threads, without OpenFOAM, and the defaults' table), and
//! `--report` merging two JSON files of one mesh into one row.
//! It runs the binaries this `cargo test` built (`--bin-dir`: the
//! `motion_bench` example of this crate and the `verbss` binary, which
//! `cargo test --workspace` builds for the CLI's tests), so it compiles
//! nothing itself. Needs python3 with gmsh and the `verbss` binary; without
//! them it skips with a notice (`verbss_testkit::needs`).

use std::ffi::OsStr;
use std::path::Path;
use std::process::Command;

use verbss_testkit::{needs, python};

/// Runs `bench/compare.py ARGS` from the repository `root`; its standard
/// output, after checking that it succeeded.
fn compare(root: &Path, args: &[&OsStr]) -> String {
    let out = Command::new("python3")
        .arg(root.join("bench/compare.py"))
        .args(args)
        .current_dir(root)
        .output()
        .expect("python3 runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "compare.py {args:?} failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

#[test]
fn compare_script_runs_in_smoke_mode() {
    if !needs("python3 with gmsh (pip install gmsh)", python(&["gmsh"])) {
        return;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let exe = std::env::current_exe().expect("the test's own path");
    let bin_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("the test runs from <target>/<profile>/deps");
    let binary = if bin_dir.join("verbss").is_file() {
        Ok(())
    } else {
        Err(format!("none in {}", bin_dir.display()))
    };
    if !needs(
        "the verbss binary (cargo test --workspace builds it)",
        binary,
    ) {
        return;
    }
    let work = std::env::temp_dir().join(format!("verbss-bench-smoke-{}", std::process::id()));
    let json = work.join("smoke.json");
    for extra in [&[][..], &["--series-2d"][..]] {
        let mut args: Vec<&OsStr> = ["--smoke", "--no-openfoam", "--work"]
            .iter()
            .map(OsStr::new)
            .collect();
        args.extend([work.as_os_str(), OsStr::new("--json"), json.as_os_str()]);
        args.extend([OsStr::new("--bin-dir"), bin_dir.as_os_str()]);
        args.extend(extra.iter().map(OsStr::new));
        let stdout = compare(&root, &args);
        for variant in [
            "| verbss defaults | 1 |",
            "| verbss defaults | 2 |",
            "| verbss updated none previous | 1 |",
            "| verbss updated none linear | 2 |",
            "| verbss updated amg linear | 1 |",
            "| verbss fixed none linear | 2 |",
        ] {
            assert!(stdout.contains(variant), "{variant} missing:\n{stdout}");
        }
        assert!(
            stdout.contains("| defaults s/step | moveDynamicMesh s/step | ratio"),
            "the defaults' table is missing:\n{stdout}"
        );
    }
    // --report merges the files by mesh: the same run given twice is one
    // mesh, its defaults' table one row (the last file's).
    let stdout = compare(
        &root,
        &[OsStr::new("--report"), json.as_os_str(), json.as_os_str()],
    );
    let table = stdout
        .split("| defaults s/step |")
        .nth(1)
        .expect("the defaults' table");
    let rows = table.lines().skip(2).take_while(|l| l.starts_with('|'));
    assert_eq!(rows.count(), 1, "one row for the one mesh:\n{stdout}");
    std::fs::remove_dir_all(&work).ok();
}
