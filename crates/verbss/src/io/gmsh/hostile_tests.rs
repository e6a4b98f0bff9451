//! The reader against hostile files: bounded physical groups and names,
//! shared tag lists, a byte-order mark, duplicated elements.

use std::path::Path;

use super::*;
use crate::io::MAX_GROUPS;
use crate::mesh::CellKind;

/// An MSH 2.2 unit triangle (nodes 1-3, element 1) and `lines` line
/// elements on nodes 1 2, line `k` (0-based) with the physical tag `tag(k)`.
fn msh22(lines: usize, tag: impl Fn(usize) -> usize) -> String {
    let mut s = format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n\
         $Elements\n{}\n1 2 2 0 1 1 2 3\n",
        lines + 1
    );
    for k in 0..lines {
        s += &format!("{} 1 2 {} 1 1 2\n", k + 2, tag(k));
    }
    s + "$EndElements\n"
}

fn read(text: &str) -> Result<Mesh> {
    parse(text.as_bytes(), Path::new("t.msh"))
}

#[test]
fn physical_groups_are_bounded() {
    let m = read(&msh22(MAX_GROUPS, |k| k + 1)).unwrap();
    assert_eq!(m.groups.len(), MAX_GROUPS);
    assert_eq!(
        read(&msh22(MAX_GROUPS + 1, |k| k + 1))
            .unwrap_err()
            .to_string(),
        "t.msh:65549: more than 65536 physical groups of dimension 1 (the most verbss reads)"
    );
}

#[test]
fn alternating_physical_tags_share_their_groups() {
    // Tags 1 2 1 2 …: two groups, each line in one.
    let m = read(&msh22(6, |k| 1 + k % 2)).unwrap();
    let names: Vec<&str> = m.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["1", "2"]);
    assert!(m.groups.iter().all(|g| g.facets.len() == 3));
    assert!(m.groups[0]
        .facets
        .kinds
        .iter()
        .all(|&k| k == CellKind::Line));
}

#[test]
fn physical_names_are_bounded() {
    let n = 4 * MAX_GROUPS + 1;
    let mut s = format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n{n}\n");
    for k in 0..n {
        s += &format!("1 {k} \"n\"\n");
    }
    assert_eq!(
        read(&s).unwrap_err().to_string(),
        "t.msh:262150: more than 262144 physical names (65536 groups of each dimension are \
         the most verbss reads)"
    );
}

#[test]
fn a_byte_order_mark_is_skipped_and_a_duplicated_element_named() {
    let plain = msh22(1, |_| 5);
    assert_eq!(
        read(&format!("\u{feff}{plain}")).unwrap(),
        read(&plain).unwrap()
    );
    let twice = plain
        .replace("$Elements\n2\n", "$Elements\n3\n")
        .replace("$EndElements", "3 2 2 0 1 2 3 1\n$EndElements");
    assert_eq!(
        read(&twice).unwrap_err().to_string(),
        "t.msh:10: invalid mesh: elements 1 and 3 have the same nodes (a duplicated element)"
    );
}
