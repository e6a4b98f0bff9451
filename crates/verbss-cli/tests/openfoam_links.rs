//! Issue 43, 5 and 6: an OpenFOAM output never writes through a link into
//! the input case, and an existing time directory's polyMesh is replaced
//! only with `--overwrite`, and then whole.

use std::path::Path;

mod common;

use common::foam::{block_case, foam, have_openfoam};
use common::{stderr, verbss};

/// The five files of the polyMesh `dir`, with their bytes.
fn polymesh(dir: &Path) -> Vec<Vec<u8>> {
    ["points", "faces", "owner", "neighbour", "boundary"]
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect()
}

/// `verbss deform CASE -o OUT` turning the wing by 5° in 2 steps, with `extra`.
fn turn(case: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let (c, o) = (case.to_str().unwrap(), out.to_str().unwrap());
    let mut args = vec!["deform", c, "-o", o, "--moving", "wing", "--rotate", "5"];
    args.extend(["--center", "0,0", "--steps", "2", "--quiet"]);
    args.extend_from_slice(extra);
    verbss(&args)
}

fn is_link(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink())
}

#[test]
fn a_case_of_links_to_the_input_gets_files_of_its_own() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("square");
    block_case(&case, 4, 1);
    let constant = case.join("constant/polyMesh");
    let before = polymesh(&constant);
    // A variant case whose polyMesh files are links to the input's.
    let variant = dir.path().join("variant");
    let linked = variant.join("constant/polyMesh");
    std::fs::create_dir_all(&linked).unwrap();
    for f in ["points", "faces", "owner", "neighbour", "boundary"] {
        std::os::unix::fs::symlink(constant.join(f), linked.join(f)).unwrap();
    }
    std::os::unix::fs::symlink(case.join("system"), variant.join("system")).unwrap();
    let o = turn(&case, &variant, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        polymesh(&constant) == before,
        "the input's polyMesh changed"
    );
    for f in ["points", "faces", "owner", "neighbour", "boundary"] {
        assert!(!is_link(&linked.join(f)), "{f} is still a link");
    }
    let moved = polymesh(&linked);
    assert_ne!(moved[0], before[0]);
    assert!(moved[1..] == before[1..]);
    assert!(foam("checkMesh", &variant, &[]).contains("Mesh OK."));
}

#[test]
fn a_time_directory_is_replaced_only_with_overwrite_and_then_whole() {
    if !have_openfoam() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("square");
    block_case(&case, 4, 1);
    let constant = case.join("constant/polyMesh");
    let before = polymesh(&constant);
    let time = case.join("2/polyMesh");
    let held = format!(
        "error: -o {}: the time directory 2 already holds a polyMesh (give --overwrite to \
         replace it whole)\n",
        time.display()
    );

    // Item 5: `2/polyMesh/points` a link to constant's points.
    std::fs::create_dir_all(&time).unwrap();
    std::os::unix::fs::symlink("../../constant/polyMesh/points", time.join("points")).unwrap();
    let o = turn(&case, &case, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o), held);
    let o = turn(&case, &case, &["--overwrite"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        polymesh(&constant) == before,
        "the input's polyMesh changed"
    );
    assert!(!is_link(&time.join("points")));
    assert_ne!(std::fs::read(time.join("points")).unwrap(), before[0]);

    // Item 6: `2/polyMesh` holding another mesh (here, the input's files).
    for (f, bytes) in ["points", "faces", "owner", "neighbour", "boundary"]
        .iter()
        .zip(&before)
    {
        std::fs::write(time.join(f), bytes).unwrap();
    }
    let o = turn(&case, &case, &[]);
    assert_eq!(stderr(&o), held);
    assert!(polymesh(&time) == before, "2/polyMesh changed");
    let o = turn(&case, &case, &["--overwrite"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let mut left: Vec<String> = std::fs::read_dir(&time)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["points"], "stale files in 2/polyMesh");
    let log = foam("checkMesh", &case, &["-time", "2"]);
    assert!(log.contains("Mesh OK."), "{log}");

    // A time directory that is a link to `constant`: never written, even
    // with --overwrite.
    std::fs::remove_dir_all(case.join("2")).unwrap();
    std::os::unix::fs::symlink("constant", case.join("2")).unwrap();
    let o = turn(&case, &case, &["--overwrite"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "error: -o {}: it would replace the input mesh {} (verbss never writes over an \
             input file)\n",
            time.join("points").display(),
            constant.join("points").display()
        )
    );
    assert!(
        polymesh(&constant) == before,
        "the input's polyMesh changed"
    );
}
