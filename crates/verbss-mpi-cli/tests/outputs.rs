//! Issue 43, 10: `verbss-mpi deform` checks every file its ranks write
//! (the per-rank pieces, the `.pvtu`, the report) against the input and
//! against each other before the first solve, as `verbss deform` does.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;

use common::mpi_ready;

/// `mpirun -np 2 verbss-mpi ARGS…`.
fn mpirun(args: &[&str]) -> Output {
    let session = tempfile::tempdir().unwrap();
    common::mpirun(2, session.path())
        .arg(env!("CARGO_BIN_EXE_verbss-mpi"))
        .args(args)
        .output()
        .expect("run mpirun (Debian: openmpi-bin)")
}

fn naca() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/mesh_NACA0012_inv.su2")
}

/// `deform MESH -o OUT` translating the airfoil a little, with `extra`.
fn deform(mesh: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend(["--moving", "airfoil", "--translate", "0,0.001", "-q"]);
    args.extend_from_slice(extra);
    mpirun(&args)
}

/// Asserts that the run exited with 2 and said `line` once (by rank 0).
fn said_once(o: &Output, line: &str) {
    let text = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{text}");
    assert_eq!(text.matches(line).count(), 1, "{text}");
}

#[test]
fn no_piece_replaces_the_input_or_another_output() {
    if !mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    // An input named like rank 1's piece of `-o x.su2`.
    let input = dir.path().join("x_1.vtu");
    let mesh = verbss::io::read(&naca()).unwrap();
    verbss::io::write(&input, &mesh, &verbss::io::WriteOptions::default()).unwrap();
    let before = std::fs::read(&input).unwrap();
    let o = deform(&input, &dir.path().join("x.su2"), &[]);
    assert_eq!(o.status.code(), Some(2));
    said_once(
        &o,
        &format!(
            "error: a rank's piece {}: it would replace the input mesh {} (verbss never writes \
             over an input file)\n",
            input.display(),
            input.display()
        ),
    );
    assert_eq!(std::fs::read(&input).unwrap(), before);
    assert!(!dir.path().join("x.su2").exists());

    // Without the whole mesh: the report over rank 0's piece of `-o y.pvtu`.
    let out = dir.path().join("y.pvtu");
    let piece = dir.path().join("y_0.vtu");
    let o = deform(&naca(), &out, &["--report", piece.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    said_once(
        &o,
        &format!(
            "error: --report {}: also the output of -o ({}): each output needs its own file\n",
            piece.display(),
            piece.display()
        ),
    );
    assert!(!out.exists() && !piece.exists());
}
