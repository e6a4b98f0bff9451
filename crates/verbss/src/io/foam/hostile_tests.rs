//! OpenFOAM cases a hostile or careless user gives (issue 43, 8 and 9).

use super::tests::{two_squares, write_files};
use super::*;

/// The planes of a 2D case are told apart at 1e-9 of their own z scale:
/// x values of 2e9 (a tolerance of 2 when it followed the largest extent)
/// no longer merge planes 0.1 apart.
#[test]
fn a_wide_2d_case_keeps_its_two_planes() {
    let (_, mut files) = two_squares();
    let points = &mut files.iter_mut().find(|f| f.0 == "points").unwrap().1;
    *points = points.replace("(1 ", "(1e9 ").replace("(2 ", "(2e9 ");
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    let mesh = read(dir.path()).unwrap();
    assert_eq!((mesh.dim, mesh.node_count(), mesh.cell_count()), (2, 6, 2));
    assert_eq!(mesh.point(2), [2e9, 0.0]);
}

/// Two patches of one name were merged into one group.
#[test]
fn a_patch_name_given_twice_is_refused_at_its_line() {
    let (_, mut files) = two_squares();
    let boundary = &mut files.iter_mut().find(|f| f.0 == "boundary").unwrap().1;
    *boundary = boundary.replace("    sides\n", "    left\n");
    let lines: Vec<usize> = boundary
        .lines()
        .enumerate()
        .filter(|(_, l)| l.trim() == "left")
        .map(|(i, _)| i + 1)
        .collect();
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    assert_eq!(
        read(dir.path()).unwrap_err().to_string(),
        format!(
            "{}:{}: patch 'left' is given twice (first at line {}): each patch needs a name of \
             its own",
            dir.path().join("constant/polyMesh/boundary").display(),
            lines[1],
            lines[0]
        )
    );
}
