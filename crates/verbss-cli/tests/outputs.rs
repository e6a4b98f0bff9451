//! Where outputs go: never over the input mesh unless `--overwrite`, never
//! over another input or output, through symbolic links to their targets,
//! never into FIFOs and devices, and at exactly the path the user gave.

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;

use common::{stderr, verbss, SQUARE};

/// A temporary folder holding the square as `square.su2`.
fn folder() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let square = dir.path().join("square.su2");
    std::fs::write(&square, SQUARE).unwrap();
    (dir, square)
}

/// `verbss deform MESH -o OUT` moving `rest` a little, with `extra` arguments.
fn deform(mesh: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "rest",
        "--translate",
        "0.01,0",
        "--quiet",
    ];
    args.extend(extra);
    verbss(&args)
}

#[test]
fn the_input_is_not_an_output_without_overwrite() {
    let (dir, square) = folder();
    // The same file under another name.
    let other = dir.path().join(".").join("square.su2");
    let o = deform(&square, &other, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("the output is the input mesh")
            && stderr(&o).contains("(give --overwrite to replace it)"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(&square).unwrap(), SQUARE);
    let o = verbss(&[
        "convert",
        square.to_str().unwrap(),
        square.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let o = deform(&square, &square, &["--overwrite"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_ne!(std::fs::read_to_string(&square).unwrap(), SQUARE);
}

#[test]
fn a_case_writing_over_its_own_mesh_is_refused() {
    let (dir, _) = folder();
    let case = dir.path().join("case.toml");
    std::fs::write(
        &case,
        "mesh = \"square.su2\"\nsteps = 1\n\n[[motion]]\nkind = \"translation\"\ngroups = [\"rest\"]\ndisplacement = [0.01, 0.0]\n\n[output]\ndir = \".\"\n",
    )
    .unwrap();
    let o = verbss(&["run", case.to_str().unwrap(), "--quiet"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("the output is the input mesh"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("square.su2")).unwrap(),
        SQUARE
    );
}

#[test]
fn the_output_path_is_the_one_given() {
    let (dir, square) = folder();
    let out = dir.path().join("out").join("UP.SU2");
    let o = deform(&square, &out, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let names: Vec<String> = std::fs::read_dir(dir.path().join("out"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(names, ["UP.SU2"]);
}

#[test]
fn a_report_through_a_symlink_keeps_the_link() {
    let (dir, square) = folder();
    let target = dir.path().join("target.json");
    std::fs::write(&target, "old").unwrap();
    let link = dir.path().join("report.json");
    std::os::unix::fs::symlink("target.json", &link).unwrap();
    let out = dir.path().join("moved.su2");
    let o = deform(&square, &out, &["--report", link.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(&target)
        .unwrap()
        .contains("\"steps\""));
}

/// `verbss deform MESH -o OUT` with `extra` as [`deform`], stopped after
/// 30 s (a FIFO opened for writing blocks until someone reads it).
fn deform_within_30_s(mesh: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend(["--moving", "rest", "--translate", "0.01,0", "--quiet"]);
    args.extend(extra);
    let mut child = Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args(&args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() > 30 {
            child.kill().unwrap();
            panic!("verbss {args:?} still ran after 30 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Asserts exit 2 and `message` on standard error, and that `mesh` still
/// holds the square.
fn refused(o: &Output, message: &str, mesh: &Path) {
    assert_eq!(o.status.code(), Some(2), "{}", stderr(o));
    assert_eq!(stderr(o), format!("error: {message}\n"));
    assert_eq!(std::fs::read_to_string(mesh).unwrap(), SQUARE);
}

/// Issue 43, 10: a FIFO or a device is refused as an output, as it is as
/// an input, before the first solve.
#[test]
fn a_fifo_or_a_device_is_refused_as_an_output() {
    let (dir, square) = folder();
    let fifo = dir.path().join("report.fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let out = dir.path().join("moved.su2");
    let fifo_out = dir.path().join("fifo.su2");
    let made = Command::new("mkfifo")
        .arg(&fifo_out)
        .status()
        .expect("mkfifo");
    assert!(made.success());
    let special = |flag: &str, path: &Path, what: &str| {
        format!(
            "{flag} {}: {what}, not a regular file (verbss writes its outputs to regular files \
             only)",
            path.display()
        )
    };
    for flag in ["--report", "--gif", "--html"] {
        let o = deform_within_30_s(&square, &out, &[flag, fifo.to_str().unwrap()]);
        refused(&o, &special(flag, &fifo, "a FIFO"), &square);
    }
    let o = deform_within_30_s(&square, &fifo_out, &[]);
    refused(&o, &special("-o", &fifo_out, "a FIFO"), &square);
    let null = Path::new("/dev/null");
    let o = deform_within_30_s(&square, &out, &["--report", "/dev/null"]);
    refused(&o, &special("--report", null, "a device"), &square);
    assert!(!out.exists());
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
}

/// Issue 43, 10: `--every`, `--report`, `--gif` and `--html` never replace
/// an input (the mesh, the positions file), nor one output another: each
/// is refused with exit 2 before the first solve, naming the option and
/// the file.
#[test]
fn no_side_output_replaces_an_input_or_another_output() {
    let (dir, square) = folder();
    let at = |name: &str| dir.path().join(name);
    // A mesh named like the series `deform x_0001.vtu -o x.su2 --every 1` writes.
    let series = at("x_0001.vtu");
    let o = verbss(&[
        "convert",
        square.to_str().unwrap(),
        series.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let vtu = std::fs::read(&series).unwrap();
    let o = deform(&series, &at("x.su2"), &["--every", "1"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let replaces = |flag: &str, path: &Path, what: &str, input: &Path| {
        format!(
            "{flag} {}: it would replace {what} {} (verbss never writes over an input file)",
            path.display(),
            input.display()
        )
    };
    assert_eq!(
        stderr(&o),
        format!(
            "error: {}\n",
            replaces("--every", &series, "the input mesh", &series)
        )
    );
    assert_eq!(std::fs::read(&series).unwrap(), vtu);
    assert!(!at("x.su2").exists());
    let out = at("moved.su2");
    for flag in ["--report", "--gif", "--html"] {
        let o = deform(&square, &out, &[flag, square.to_str().unwrap()]);
        refused(
            &o,
            &replaces(flag, &square, "the input mesh", &square),
            &square,
        );
    }
    // Through a link, and under another name of the same folder.
    let link = at("link.su2");
    std::os::unix::fs::symlink("square.su2", &link).unwrap();
    let o = deform(&square, &out, &["--report", link.to_str().unwrap()]);
    refused(
        &o,
        &replaces("--report", &link, "the input mesh", &square),
        &square,
    );
    let other = dir.path().join("new/../square.su2");
    let o = deform(&square, &out, &["--html", other.to_str().unwrap()]);
    refused(
        &o,
        &replaces("--html", &other, "the input mesh", &square),
        &square,
    );
    // The positions file.
    let positions = at("positions.dat");
    std::fs::write(&positions, "1 1.01 0\n").unwrap();
    let mut args = vec![
        "deform",
        square.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend([
        "--moving",
        "rest",
        "--positions",
        positions.to_str().unwrap(),
    ]);
    args.extend(["--report", positions.to_str().unwrap(), "-q"]);
    let o = verbss(&args);
    refused(
        &o,
        &replaces("--report", &positions, "the positions file", &positions),
        &square,
    );
    // One output over another.
    let vtu_out = at("out.vtu");
    let o = deform(&square, &vtu_out, &["--report", vtu_out.to_str().unwrap()]);
    refused(
        &o,
        &format!(
            "--report {}: also the output of -o ({}): each output needs its own file",
            vtu_out.display(),
            vtu_out.display()
        ),
        &square,
    );
    let o = deform(
        &square,
        &vtu_out,
        &["--every", "1", "--gif", at("out.pvd").to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--gif") && stderr(&o).contains("also the output of --every"));
    assert!(!vtu_out.exists() && !out.exists());
}

/// Issue 43, 10: a case file's outputs never replace the case file.
#[test]
fn a_case_writing_its_report_over_itself_is_refused() {
    let (dir, square) = folder();
    let case = dir.path().join("report.json");
    std::fs::write(
        &case,
        "mesh = \"square.su2\"\nsteps = 1\n\n[[motion]]\nkind = \"translation\"\ngroups = [\"rest\"]\ndisplacement = [0.01, 0.0]\n\n[output]\ndir = \"out/..\"\nfinal = false\n",
    )
    .unwrap();
    let before = std::fs::read(&case).unwrap();
    let o = verbss(&["run", case.to_str().unwrap(), "--quiet"]);
    let report = dir.path().join("out/../report.json");
    refused(
        &o,
        &format!(
            "output.report {}: it would replace the case file {} (verbss never writes over an \
             input file)",
            report.display(),
            case.display()
        ),
        &square,
    );
    assert_eq!(std::fs::read(&case).unwrap(), before);
}
