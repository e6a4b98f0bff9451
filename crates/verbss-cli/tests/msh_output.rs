//! The MSH version and encoding of a `.msh` output: the input's unless
//! `--msh-version`, `--binary`, `--ascii` (on `deform`, `run`, `convert`)
//! or the case file's `[output]` say otherwise.

use std::path::{Path, PathBuf};

mod common;

use common::{stderr, verbss};

/// The unit square in MSH 2.2 ASCII, its left side the group `left`, the
/// cells the physical surface `fluid`.
const SQUARE_22: &str = "$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 \"left\"
2 2 \"fluid\"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
3
7 1 2 1 4 4 1
8 2 2 2 1 1 2 3
9 2 2 2 1 1 3 4
$EndElements
";

/// `SQUARE_22` written to `square.msh` in `dir`.
fn square(dir: &Path) -> PathBuf {
    let path = dir.join("square.msh");
    std::fs::write(&path, SQUARE_22).unwrap();
    path
}

/// The `$MeshFormat` line of the file at `path`: `version file-type 8`.
fn format_line(path: &Path) -> String {
    let bytes = std::fs::read(path).unwrap();
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(40)]).into_owned();
    text.lines().nth(1).unwrap().to_string()
}

/// `verbss deform` of the square, `left` moved by `-0.1,0`, to `out.msh`
/// with `flags`; the output's format line.
fn deform(dir: &Path, flags: &[&str]) -> String {
    let mesh = square(dir);
    let out = dir.join("out.msh");
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "left",
        "--translate",
        "-0.1,0",
        "--quiet",
    ];
    args.extend_from_slice(flags);
    let o = verbss(&args);
    assert!(o.status.success(), "{flags:?}: {}", stderr(&o));
    let back = verbss::io::read(&out).unwrap();
    assert_eq!(back.point(0), [-0.1, 0.0], "{flags:?}");
    assert_eq!(back.group_names(), ["left"], "{flags:?}");
    format_line(&out)
}

#[test]
fn deform_keeps_the_input_encoding_unless_told() {
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(deform(dir.path(), &[]), "2.2 0 8");
    let kept = std::fs::read_to_string(dir.path().join("out.msh")).unwrap();
    assert_eq!(
        kept,
        SQUARE_22
            .replace("1 0 0 0\n", "1 -0.1 0.0 0.0\n")
            .replace("4 0 1 0\n", "4 -0.1 1.0 0.0\n")
    );
    assert_eq!(deform(dir.path(), &["--binary"]), "2.2 1 8");
    assert_eq!(deform(dir.path(), &["--msh-version", "4.1"]), "4.1 0 8");
    assert_eq!(
        deform(dir.path(), &["--msh-version", "4.1", "--binary"]),
        "4.1 1 8"
    );
    let o = verbss(&[
        "deform",
        "square.msh",
        "-o",
        "out.msh",
        "--moving",
        "left",
        "--translate",
        "1,0",
        "--binary",
        "--ascii",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("'--binary' cannot be used with '--ascii'"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn convert_keeps_the_input_encoding_unless_told() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = square(dir.path());
    let convert = |input: &Path, output: &str, flags: &[&str]| {
        let out = dir.path().join(output);
        let mut args = vec!["convert", input.to_str().unwrap(), out.to_str().unwrap()];
        args.extend_from_slice(flags);
        let o = verbss(&args);
        assert!(o.status.success(), "{flags:?}: {}", stderr(&o));
        out
    };
    let binary = convert(&mesh, "binary.msh", &["--binary"]);
    assert_eq!(format_line(&binary), "2.2 1 8");
    let copy = convert(&binary, "copy.msh", &[]);
    assert_eq!(
        std::fs::read(&copy).unwrap(),
        std::fs::read(&binary).unwrap()
    );
    let ascii = convert(&binary, "ascii.msh", &["--ascii"]);
    assert_eq!(format_line(&ascii), "2.2 0 8");
    assert_eq!(
        verbss::io::read(&ascii).unwrap(),
        verbss::io::read(&mesh).unwrap()
    );
    let v41 = convert(&mesh, "v41.msh", &["--msh-version", "4.1"]);
    assert_eq!(format_line(&v41), "4.1 0 8");
    // Written anew, the cells keep their physical group.
    let text = std::fs::read_to_string(&v41).unwrap();
    assert!(text.contains("2 2 \"fluid\"\n"), "{text}");
    assert!(!text.contains("domain"), "{text}");
    // and their element tags: the facet 7 stays 7.
    assert!(text.contains("\n7 4 1\n"), "{text}");
    let su2 = convert(&mesh, "square.su2", &[]);
    assert_eq!(format_line(&convert(&su2, "from_su2.msh", &[])), "4.1 0 8");
}

/// `verbss run` of a case on the square with `output` as its `[output]`
/// table and `flags`; the final mesh's format line, or the error.
fn run(dir: &Path, output: &str, flags: &[&str]) -> Result<String, String> {
    square(dir);
    let case = dir.join("case.toml");
    std::fs::write(
        &case,
        format!(
            "mesh = \"square.msh\"\nsteps = 1\n\n[[motion]]\nkind = \"translation\"\n\
             groups = [\"left\"]\ndisplacement = [-0.1, 0]\n\n[output]\nseries = false\n{output}"
        ),
    )
    .unwrap();
    let out = dir.join("out");
    let mut args = vec![
        "run",
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ];
    args.extend_from_slice(flags);
    let o = verbss(&args);
    if !o.status.success() {
        assert_eq!(o.status.code(), Some(2));
        return Err(stderr(&o));
    }
    Ok(format_line(&out.join("square.msh")))
}

#[test]
fn run_takes_the_encoding_from_the_case_file_and_the_flags() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    assert_eq!(run(d, "", &[]).unwrap(), "2.2 0 8");
    assert_eq!(run(d, "msh_version = \"4.1\"\n", &[]).unwrap(), "4.1 0 8");
    assert_eq!(
        run(d, "msh_encoding = \"binary\"\n", &[]).unwrap(),
        "2.2 1 8"
    );
    assert_eq!(
        run(
            d,
            "msh_encoding = \"binary\"\n",
            &["--ascii", "--msh-version", "4.1"]
        )
        .unwrap(),
        "4.1 0 8"
    );
    let case = d.join("case.toml");
    assert_eq!(
        run(d, "msh_version = \"3\"\n", &[]).unwrap_err(),
        format!(
            "error: {}:11: unknown variant `3`, expected `2.2` or `4.1`\n",
            case.display()
        )
    );
}
