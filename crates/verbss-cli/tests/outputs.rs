//! Where outputs go: never over the input mesh unless `--overwrite`, through
//! symbolic links to their targets, into FIFOs and devices without replacing
//! them, and at exactly the path the user gave.

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

#[test]
fn a_report_into_a_fifo_keeps_the_fifo() {
    let (dir, square) = folder();
    let fifo = dir.path().join("report.fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    let out = dir.path().join("moved.su2");
    let o = deform(&square, &out, &["--report", fifo.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(reader.join().unwrap().contains("\"steps\""));
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
}
