//! Command-line values and the messages that tell a user what to change:
//! negative numbers, a mesh without groups, 1-based positions, 2D vectors
//! with a z.

use std::path::{Path, PathBuf};

mod common;

use common::{stderr, verbss, SQUARE};

/// `SQUARE` written to `square.su2` in `dir`.
fn square(dir: &Path) -> PathBuf {
    let path = dir.join("square.su2");
    std::fs::write(&path, SQUARE).unwrap();
    path
}

/// `verbss deform SQUARE -o DIR/out.su2 --quiet` followed by `args`.
fn deform(dir: &Path, args: &[&str]) -> std::process::Output {
    let mesh = square(dir);
    let out = dir.join("out.su2");
    let mut all = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--quiet",
    ];
    all.extend_from_slice(args);
    verbss(&all)
}

fn coords(path: &Path) -> Vec<f64> {
    verbss::io::read(path).unwrap().coords
}

#[test]
fn negative_vectors_and_numbers_are_values() {
    let dir = tempfile::tempdir().unwrap();
    let o = deform(dir.path(), &["--moving", "left", "--translate", "-0.25,0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = coords(&dir.path().join("out.su2"));
    assert_eq!((moved[0], moved[6]), (-0.25, -0.25));
    let o = deform(
        dir.path(),
        &[
            "--moving",
            "left",
            "--rotate",
            "-5",
            "--center",
            "-0.5,-1e-1",
            "--tolerance",
            "1e-8",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // A negative count is a bad value, not an unknown argument.
    let o = deform(
        dir.path(),
        &["--moving", "left", "--translate", "-1,0", "--steps", "-2"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("invalid value '-2' for '--steps <STEPS>'"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_2d_mesh_takes_a_vector_with_z_zero_and_refuses_another_z() {
    let dir = tempfile::tempdir().unwrap();
    let o = deform(dir.path(), &["--moving", "left", "--translate", "0,0.1,0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = coords(&dir.path().join("out.su2"));
    assert_eq!(&moved[..2], &[0.0, 0.1]);
    let o = deform(
        dir.path(),
        &["--moving", "left", "--rotate", "3", "--center", "0,0,0"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = deform(dir.path(), &["--moving", "left", "--translate", "0,0.1,-2"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        "error: --translate has a non-zero z on a 2D mesh, which lies in the x–y plane \
         (give 2 numbers, or 3 with z = 0)\n"
    );
    let o = deform(dir.path(), &["--moving", "left", "--translate", "1"]);
    assert_eq!(
        stderr(&o),
        "error: --translate needs 2 numbers (or 3 with z = 0) for a 2D mesh, got 1\n"
    );
}

/// The unit square in MSH 2.2 as Gmsh writes it without physical groups:
/// every element's physical tag is 0.
const SQUARE_NO_PHYSICALS: &str = "$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
6
1 1 2 0 1 1 2
2 1 2 0 2 2 3
3 1 2 0 3 3 4
4 1 2 0 4 4 1
5 2 2 0 1 1 2 3
6 2 2 0 1 1 3 4
$EndElements
";

#[test]
fn a_mesh_without_groups_says_how_to_add_them_in_gmsh() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("square.msh");
    std::fs::write(&mesh, SQUARE_NO_PHYSICALS).unwrap();
    let out = dir.path().join("out.msh");
    let o = verbss(&[
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "wall",
        "--translate",
        "0.1,0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        "error: unknown group 'wall': the mesh has no boundary groups. A Gmsh mesh gets them \
         from physical groups: add `Physical Curve(\"wall\") = {1, 2};` to the .geo file, or \
         call `gmsh.model.addPhysicalGroup(1, [1, 2], name=\"wall\")` in Python, with the \
         tags of the curves on that boundary, and mesh again\n"
    );
    assert!(!out.exists());
}

/// `deform` with the `left` group moved to the positions in `positions`.
fn move_left_to(dir: &Path, positions: &Path) -> std::process::Output {
    deform(
        dir,
        &[
            "--moving",
            "left",
            "--positions",
            positions.to_str().unwrap(),
        ],
    )
}

#[test]
fn positions_with_1_based_ids_get_the_hint() {
    let dir = tempfile::tempdir().unwrap();
    let positions = dir.path().join("left.dat");
    // The left nodes are 0 and 3; numbered from 1 they become 1 and 4.
    std::fs::write(&positions, "1 -0.1 0\n4 -0.1 1\n").unwrap();
    let o = move_left_to(dir.path(), &positions);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        format!(
            "error: {}:2: node id 4 out of range (the mesh has 4 nodes: ids 0 to 3); the ids \
             look 1-based (no id 0, the largest equal to the node count): ids are 0-based \
             node indices in the mesh file's order, so subtract 1 from each\n",
            positions.display()
        )
    );
    std::fs::write(&positions, "0 -0.1 0\n3 -0.1 1\n").unwrap();
    let o = move_left_to(dir.path(), &positions);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Issue 43, 11: a case file's number that would make a non-finite
/// position (an infinite angle, a speed of 1e308, a wavelength of 1e-320)
/// is refused with exit 2, naming the file, the line of its motion, the
/// key and the value, printed short; no solve, no NaN.
#[test]
fn a_case_files_number_beyond_range_is_named_with_its_key() {
    let dir = tempfile::tempdir().unwrap();
    square(dir.path());
    let case = dir.path().join("case.toml");
    let motions = [
        (
            "kind = \"pitch-plunge\"\ncenter = [0.5, 0.5]\npitch_deg = inf\nplunge = [0, 0]",
            "`pitch_deg` = inf: expected a finite number within ±1e100",
        ),
        (
            "kind = \"undulation\"\nhead = [0, 0]\naxis = [1, 0]\namplitude = [0.01]\n\
             wavelength = 1.0\nspeed = 1e308",
            "`speed` = 1e308: expected a finite number within ±1e100",
        ),
        (
            "kind = \"undulation\"\nhead = [0, 0]\naxis = [1, 0]\namplitude = [0.01]\n\
             wavelength = 1e-320\nspeed = 1.0",
            "`wavelength` = 1e-320: expected a positive number from 1e-100 to 1e100",
        ),
        (
            "kind = \"translation\"\ndisplacement = [1e300, 0]",
            "`displacement` = 1e300: expected a finite number within ±1e100",
        ),
    ];
    for (motion, message) in motions {
        let text = format!(
            "mesh = \"square.su2\"\nsteps = 2\n\n[[motion]]\ngroups = [\"rest\"]\n{motion}\n\n\
             [output]\ndir = \"out\"\n"
        );
        std::fs::write(&case, text).unwrap();
        let o = verbss(&["run", case.to_str().unwrap(), "--quiet"]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert_eq!(
            stderr(&o),
            format!(
                "error: {}:4: {message} (beyond it the positions overflow)\n",
                case.display()
            )
        );
        assert!(!dir.path().join("out").exists());
    }
}

/// Issue 43, 15: `--slide GROUP:1e308,1e308` is the direction (1, 1), not
/// "a zero vector"; an infinite one is named.
#[test]
fn a_huge_slide_normal_is_a_direction() {
    let dir = tempfile::tempdir().unwrap();
    let o = deform(
        dir.path(),
        &[
            "--moving",
            "left",
            "--translate",
            "0,0.01",
            "--slide",
            "rest:1e308,1e308",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = deform(
        dir.path(),
        &[
            "--moving",
            "left",
            "--translate",
            "0,0.01",
            "--slide",
            "rest:inf,0",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "the slide normal of group 'rest' must be a finite non-zero vector (got inf, 0)"
        ),
        "{}",
        stderr(&o)
    );
}
