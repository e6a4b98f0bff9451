//! What the command-line tests share: running the binary, its messages and
//! a small mesh.

// Each test binary compiles this module and uses a part of it.
#![allow(dead_code)]

pub mod foam;

use std::process::{Command, Output};

/// Runs the `verbss` binary with `args`.
pub fn verbss(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args(args)
        .output()
        .expect("run verbss")
}

/// What a run printed on standard error.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `verbss deform INPUT -o OUT ARGS… --quiet`.
pub fn deform_to(input: &std::path::Path, out: &std::path::Path, args: &[&str]) -> Output {
    let mut all = vec![
        "deform",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    all.extend_from_slice(args);
    all.push("--quiet");
    verbss(&all)
}

/// The JSON file at `path` (a run's `report.json`).
pub fn read_json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The unit square in SU2, groups `left` (x = 0) and `rest`.
pub const SQUARE: &str = "NDIME= 2
NELEM= 2
5 0 1 2
5 0 2 3
NPOIN= 4
0 0
1 0
1 1
0 1
NMARK= 2
MARKER_TAG= left
MARKER_ELEMS= 1
3 3 0
MARKER_TAG= rest
MARKER_ELEMS= 3
3 0 1
3 1 2
3 2 3
";
