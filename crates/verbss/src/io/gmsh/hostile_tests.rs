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

#[test]
fn extreme_tags_are_written_so_that_they_read_back() {
    // Found by the `gmsh` fuzz target: a cell tagged u64::MAX numbered the
    // group facets on from 0 (it wrapped), which no reader accepts.
    let mut mesh = read(&msh22(1, |_| i32::MAX as usize)).unwrap();
    mesh.cell_tags = vec![u64::MAX];
    for version in [MshVersion::V22, MshVersion::V41] {
        let mut out = Vec::new();
        let written = write_to(&mut out, &mesh, version, false);
        if version == MshVersion::V22 {
            // MSH 2.2 stores 32-bit tags.
            assert!(written.unwrap_err().to_string().contains("does not fit"));
            continue;
        }
        written.unwrap();
        let back = parse(&out, Path::new("t.msh")).unwrap();
        assert_eq!(back.cell_tags, [u64::MAX]);
        // The group keeps its physical tag i32::MAX; the cells' own group
        // ("domain") gets a fresh one below it.
        assert_eq!(back.groups[0].tag, Some(i32::MAX));
    }
    // Cell tags 1 and u64::MAX leave no room for a facet's tag.
    let mut two = read(&msh22(1, |_| 3)).unwrap();
    two.coords.extend([1.0, 1.0]);
    two.node_tags.push(4);
    two.cells.push(CellKind::Triangle, &[1, 3, 2]);
    two.cell_tags = vec![1, u64::MAX];
    let mut out = Vec::new();
    assert_eq!(
        write_to(&mut out, &two, MshVersion::V41, true)
            .unwrap_err()
            .to_string(),
        "element tags 1 to 18446744073709551615 leave no room for the tags of the 1 group facets"
    );
}
