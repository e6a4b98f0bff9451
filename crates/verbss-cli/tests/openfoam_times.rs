//! `verbss deform CASE -o CASE`: the steps it writes go to the time
//! directories the case's `system/controlDict` names (startTime +
//! step·deltaT, as OpenFOAM writes times), which `checkMesh -time T`
//! reads; a failed run leaves the case as it was but for its failed state
//! `CASE/verbss.failed.vtu`, and the summary names what was written.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

mod common;

use common::foam::{block_case, foam, have_openfoam};
use common::{stderr, verbss};

/// Sets the `startTime` and `deltaT` of the case's controlDict.
fn set_times(case: &Path, start: &str, delta: &str) {
    let path = case.join("system/controlDict");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("startTime 0;") && text.contains("deltaT 1;"));
    let text = text
        .replace("startTime 0;", &format!("startTime {start};"))
        .replace("deltaT 1;", &format!("deltaT {delta};"));
    std::fs::write(path, text).unwrap();
}

/// Every file under `dir` with its bytes, by path relative to `dir`.
fn tree(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                todo.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                files.insert(path.strip_prefix(dir).unwrap().to_path_buf(), bytes);
            }
        }
    }
    files
}

/// The directories of `case` other than `constant` and `system`, sorted.
fn time_dirs(case: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(case)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != "constant" && n != "system")
        .collect();
    names.sort_by(|a, b| a.parse::<f64>().unwrap().total_cmp(&b.parse().unwrap()));
    names
}

/// `verbss deform CASE -o CASE` turning the wing of `case` by `degrees`
/// in `steps` steps, with `extra` options.
fn turn(case: &Path, degrees: &str, steps: &str, extra: &[&str]) -> std::process::Output {
    let c = case.to_str().unwrap();
    let mut args = vec![
        "deform", c, "-o", c, "--moving", "wing", "--rotate", degrees, "--center", "0,0",
        "--steps", steps,
    ];
    args.extend_from_slice(extra);
    verbss(&args)
}

#[test]
fn the_steps_go_to_the_time_directories_the_control_dict_names() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("square");
    block_case(&case, 4, 1);
    set_times(&case, "0", "5e-06");
    let o = turn(&case, "20", "4", &["--every", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(time_dirs(&case), ["1e-05", "2e-05"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains(&format!(
            "outputs in {} (time directories 1e-05, 2e-05)",
            case.display()
        )),
        "{out}"
    );
    for t in ["1e-05", "2e-05"] {
        let points = std::fs::read_to_string(case.join(t).join("polyMesh/points")).unwrap();
        assert!(
            points.contains(&format!("location    \"{t}/polyMesh\"")),
            "{points}"
        );
        let log = foam("checkMesh", &case, &["-time", t]);
        assert!(log.contains(&format!("Time = {t}\n")), "{log}");
        assert!(log.contains("Mesh OK."), "checkMesh -time {t}:\n{log}");
    }
    // The two steps are two different meshes.
    let read = |t: &str| std::fs::read(case.join(t).join("polyMesh/points")).unwrap();
    assert_ne!(read("1e-05")[200..], read("2e-05")[200..]);

    // --start-time and --dt replace the dictionary's; the last step always.
    let o = turn(
        &case,
        "10",
        "3",
        &["--start-time", "1", "--dt", "0.5", "--quiet"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(time_dirs(&case), ["1e-05", "2e-05", "2.5"]);
    assert!(foam("checkMesh", &case, &["-time", "2.5"]).contains("Mesh OK."));

    // A time step too fine for timePrecision 6 names two steps alike.
    let o = turn(&case, "10", "3", &["--start-time", "1", "--dt", "1e-7"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("steps 0 and 1 are both at time 1 at timePrecision 6"),
        "{}",
        stderr(&o)
    );
    // --start-time names time directories of the input case only.
    let vtu = dir.path().join("out.vtu");
    let o = verbss(&[
        "deform",
        case.to_str().unwrap(),
        "-o",
        vtu.to_str().unwrap(),
        "--moving",
        "wing",
        "--translate",
        "0.1,0",
        "--start-time",
        "1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--start-time names the time directories"));
}

#[test]
fn a_failed_run_leaves_the_case_as_it_was_but_for_its_failed_state() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("square");
    block_case(&case, 4, 1);
    let before = tree(&case);
    // The wing pushed through the farfield in one step.
    let c = case.to_str().unwrap();
    let push = |dx: &str, steps: &str| {
        verbss(&[
            "deform",
            c,
            "-o",
            c,
            "--moving",
            "wing",
            "--translate",
            &format!("{dx},0"),
            "--steps",
            steps,
            "--every",
            "1",
        ])
    };
    let o = push("1.4", "1");
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let mut after = tree(&case);
    let failed = after.remove(Path::new("verbss.failed.vtu"));
    assert!(failed.is_some(), "no failed state in {}", case.display());
    assert!(after == before, "the case changed: {:?}", after.keys());
    let err = stderr(&o);
    assert!(
        err.contains(&format!(
            "the last valid mesh (step 0) is in {} (the case is as it was: no step was accepted); \
             the failed state in {}",
            case.join("constant/polyMesh").display(),
            case.join("verbss.failed.vtu").display()
        )),
        "{err}"
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains(&format!(
            "outputs in {} (no time directory: no step was accepted)",
            case.display()
        )),
        "{out}"
    );

    // Failing later: the accepted steps only, each in its time directory.
    let o = push("1.4", "8");
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let accepted: usize = out.split(" steps in ").next().unwrap().parse().unwrap();
    assert!((1..8).contains(&accepted), "{out}");
    let expected: Vec<String> = (1..=accepted).map(|n| n.to_string()).collect();
    assert_eq!(time_dirs(&case), expected);
    assert!(stderr(&o).contains(&format!(
        "the last valid mesh (step {accepted}) is in {}",
        case.join(accepted.to_string()).display()
    )));
    let latest = foam("checkMesh", &case, &["-latestTime"]);
    assert!(latest.contains("Mesh OK."), "{latest}");
}
