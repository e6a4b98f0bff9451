//! Small files written by hand, in both versions: what they hold, and what is skipped.

use std::path::Path;

use super::{cells, group, written};
use crate::io::gmsh::parse;
use crate::io::MshVersion;
use crate::mesh::{CellKind, Coupling, Interface, Transform};

pub(super) const V22: &str = "$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
1 1 \"wall\"
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
1 1 2 1 1 1 2
2 2 2 0 1 1 2 3
3 2 2 0 1 1 3 4
$EndElements
";

pub(super) const V41: &str = "$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 7 \"wall\"
2 8 \"fluid\"
$EndPhysicalNames
$Entities
0 1 1 0
3 0 0 0 1 0 0 1 7 0
1 0 0 0 1 1 0 1 8 0
$EndEntities
$Nodes
2 4 2 40
2 1 0 2
40
20
0 0 0
1 0 0
2 1 0 2
2
30
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 3 1 1
1 40 20
2 1 2 2
2 40 20 2
3 40 2 30
$EndElements
";

pub(super) fn replaced(text: &str, from: &str, to: &str) -> Vec<u8> {
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1).into_bytes()
}

#[test]
fn reads_hand_written_files() {
    let m = parse(V22.as_bytes(), Path::new("t.msh")).unwrap();
    assert_eq!(m.dim, 2);
    assert_eq!(m.coords, [0., 0., 1., 0., 1., 1., 0., 1.]);
    assert_eq!(
        m.cells,
        cells(&[
            (CellKind::Triangle, &[0, 1, 2]),
            (CellKind::Triangle, &[0, 2, 3])
        ])
    );
    assert_eq!(m.cell_tags, [2, 3]);
    assert_eq!(m.groups, [group("wall", 1, &[(CellKind::Line, &[0, 1])])]);

    let m = parse(V41.as_bytes(), Path::new("t.msh")).unwrap();
    assert_eq!(m.node_tags, [40, 20, 2, 30]);
    assert_eq!(m.coords, [0., 0., 1., 0., 1., 1., 0., 1.]);
    assert_eq!(
        m.cells,
        cells(&[
            (CellKind::Triangle, &[0, 1, 2]),
            (CellKind::Triangle, &[0, 2, 3])
        ])
    );
    assert_eq!(m.groups, [group("wall", 7, &[(CellKind::Line, &[0, 1])])]);
}

#[test]
fn unnamed_and_multiple_physical_tags() {
    // Entity 3 in two physical groups, the second without a name.
    let bytes = replaced(V41, "3 0 0 0 1 0 0 1 7 0", "3 0 0 0 1 0 0 2 7 12 0");
    let m = parse(&bytes, Path::new("t.msh")).unwrap();
    let line = [(CellKind::Line, &[0usize, 1][..])];
    assert_eq!(m.groups, [group("wall", 7, &line), group("12", 12, &line)]);
    // Without $Entities there are no physical tags, hence no groups.
    let start = V41.find("$Entities").unwrap();
    let end = V41.find("$Nodes").unwrap();
    let bytes = format!("{}{}", &V41[..start], &V41[end..]);
    assert!(parse(bytes.as_bytes(), Path::new("t.msh"))
        .unwrap()
        .groups
        .is_empty());
}

#[test]
fn skips_unknown_sections() {
    let extra = "$Comments\n1\n1 1 1\n$EndComments\n$NodeData\n1\n\"u\"\n$EndNodeData\n";
    let bytes = replaced(V22, "$Nodes\n", &format!("{extra}$Nodes\n"));
    let plain = parse(V22.as_bytes(), Path::new("t.msh")).unwrap();
    assert_eq!(parse(&bytes, Path::new("t.msh")).unwrap(), plain);
    let mut binary = written(&plain, MshVersion::V41, true);
    binary.extend_from_slice(extra.as_bytes());
    assert_eq!(parse(&binary, Path::new("t.msh")).unwrap(), plain);
}

#[test]
fn periodic_links_are_the_mesh_interfaces() {
    // The square's right side (nodes 2, 3) the image of its left (1, 4).
    let link =
        "$Periodic\n1\n1 2 1\nAffine 1 0 0 1 0 1 0 0 0 0 1 0 0 0 0 1\n2\n2 1\n3 4\n$EndPeriodic\n";
    let m = parse((V22.to_string() + link).as_bytes(), Path::new("t.msh")).unwrap();
    let shift = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    assert_eq!(
        m.origin.interfaces,
        [Interface {
            sides: [vec!["curve 1".into()], vec!["curve 2".into()]],
            coupling: Coupling::Linked {
                transform: Some(Transform::Affine(shift)),
                pairs: vec![(0, 1), (3, 2)],
            },
        }]
    );
    let bare = link.replace("Affine 1 0 0 1 0 1 0 0 0 0 1 0 0 0 0 1\n", "");
    let m = parse((V22.to_string() + &bare).as_bytes(), Path::new("t.msh")).unwrap();
    assert!(matches!(
        &m.origin.interfaces[0].coupling,
        Coupling::Linked {
            transform: None,
            ..
        }
    ));
    let e = parse(
        (V22.to_string() + &link.replace("3 4", "3 9")).as_bytes(),
        Path::new("t.msh"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("the periodic link of entity 2 names node 9, which $Nodes does not have"),
        "{e}"
    );
}

#[test]
fn msh2_copies_of_a_cell_are_one_cell() {
    // MSH 2.2 repeats an element in two physical volumes under a new tag.
    let bytes = replaced(
        V22,
        "3\n1 1 2 1 1 1 2\n2 2 2 0 1 1 2 3\n",
        "4\n1 1 2 1 1 1 2\n2 2 2 5 1 1 2 3\n5 2 2 6 1 1 2 3\n",
    );
    let m = parse(&bytes, Path::new("t.msh")).unwrap();
    assert_eq!(m.cell_tags, [2, 3]);
}
