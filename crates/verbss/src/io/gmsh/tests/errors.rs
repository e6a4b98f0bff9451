//! Every error message, with the line or byte it names.

use super::hand_written::{replaced, V22, V41};
use super::{error, hybrid_2d, mixed_3d, written};
use crate::io::MshVersion;

#[test]
fn error_missing_mesh_format() {
    assert_eq!(
        error(b""),
        "t.msh:1: the file is empty (expected $MeshFormat)"
    );
    assert_eq!(
        error(b"\n$Nodes\n"),
        "t.msh:2: expected $MeshFormat at the start of a Gmsh file, found '$Nodes'"
    );
}

#[test]
fn error_unsupported_version_and_format() {
    assert_eq!(
        error(&replaced(V22, "2.2 0 8", "4 0 8")),
        "t.msh:2: unsupported MSH version 4 (verbss reads 2.2 and 4.1)"
    );
    assert_eq!(
        error(&replaced(V22, "2.2 0 8", "2.2 2 8")),
        "t.msh:2: expected file type 0 (ASCII) or 1 (binary), found 2"
    );
    assert_eq!(
        error(&replaced(V22, "2.2 0 8", "2.2 0 4")),
        "t.msh:2: data size 4 is not supported (expected 8)"
    );
    let big_endian = b"$MeshFormat\n4.1 1 8\n\x00\x00\x00\x01\n$EndMeshFormat\n";
    assert_eq!(
        error(big_endian),
        "t.msh: byte 20: the binary file is big-endian; verbss reads little-endian files"
    );
    assert_eq!(
        error(b"$MeshFormat\n4.1 1 8\n\x05\x00\x00\x00\n$EndMeshFormat\n"),
        "t.msh: byte 20: expected the integer 1 after the format line, found 5"
    );
}

#[test]
fn error_truncated() {
    let cut = &V22[..V22.find("3 2 2 0 1 1 3").unwrap() + 9];
    assert_eq!(
        error(cut.as_bytes()),
        "t.msh:19: unexpected end of file: expected a node tag"
    );
    let cut = &V41[..V41.find("$EndElements").unwrap()];
    assert_eq!(
        error(cut.as_bytes()),
        "t.msh:34: unexpected end of file: expected $EndElements"
    );
    let bytes = written(&mixed_3d(), MshVersion::V41, true);
    // The first element block (one hexahedron: 9 size_t) cut after 30 bytes.
    let block = find(&bytes, b"$Elements\n") + 10 + 32;
    assert_eq!(
        error(&bytes[..block + 20 + 30]),
        format!("t.msh: byte {}: unexpected end of file: an element block needs 72 bytes, only 30 remain", block + 20)
    );
    assert_eq!(
        error(&bytes[..20]),
        "t.msh: byte 20: unexpected end of file: the byte-order check needs 4 bytes, only 0 remain"
    );
}

fn find(bytes: &[u8], what: &[u8]) -> usize {
    bytes.windows(what.len()).position(|w| w == what).unwrap()
}

#[test]
fn error_counts_disagree() {
    assert_eq!(
        error(&replaced(V22, "$Nodes\n4\n", "$Nodes\n5\n")),
        "t.msh:14: $Nodes declares 5 nodes but ends after 4"
    );
    assert_eq!(
        error(&replaced(V22, "$Nodes\n4\n", "$Nodes\n3\n")),
        "t.msh:13: expected $EndNodes after 3 nodes, found '4': the section holds more than it declares"
    );
    assert_eq!(
        error(&replaced(
            V22,
            "$Elements\n3\n",
            "$Elements\n1000000000000\n"
        )),
        "t.msh:20: $Elements declares 1000000000000 elements but ends after 3"
    );
    assert_eq!(
        error(&replaced(V41, "2 4 2 40\n", "2 5 2 40\n")),
        "t.msh:25: $Nodes declares 5 nodes but its blocks hold 4"
    );
    assert_eq!(
        error(&replaced(V41, "2 1 0 2\n2\n", "2 1 0 3\n2\n")),
        "t.msh:26: node block 2 declares 3 nodes but holds coordinates for 1"
    );
    assert_eq!(
        error(&replaced(V41, "2 3 1 3\n", "2 4 1 3\n")),
        "t.msh:33: $Elements declares 4 elements but its blocks hold 3"
    );
    assert_eq!(
        error(&replaced(V22, "1\n1 1 \"wall\"", "2\n1 1 \"wall\"")),
        "t.msh:7: $PhysicalNames declares 2 names but ends after 1"
    );
    // Binary: a block claiming 2^60 elements allocates nothing and fails.
    let mut bytes = written(&mixed_3d(), MshVersion::V41, true);
    let block = find(&bytes, b"$Elements\n") + 10 + 32;
    bytes[block + 12..block + 20].copy_from_slice(&(1u64 << 60).to_le_bytes());
    assert_eq!(
        error(&bytes),
        format!(
            "t.msh: byte {}: unexpected end of file: an element block needs 1152921504606846976 records of 72 bytes, only {} bytes remain",
            block + 20,
            bytes.len() - block - 20
        )
    );
    let mut bytes = written(&hybrid_2d(), MshVersion::V22, true);
    let header = find(&bytes, b"$Elements\n") + 12;
    bytes[header + 4..header + 8].copy_from_slice(&9i32.to_le_bytes());
    assert_eq!(
        error(&bytes),
        format!(
            "t.msh: byte {}: element header announces 9 elements but 8 of the 8 declared remain",
            header + 4
        )
    );
}

#[test]
fn error_unknown_node_tag() {
    assert_eq!(
        error(&replaced(V22, "3 2 2 0 1 1 3 4", "3 2 2 0 1 1 3 99")),
        "t.msh:19: element 3 refers to node 99, which $Nodes does not define"
    );
    assert_eq!(
        error(&replaced(V41, "3 40 2 30", "3 40 2 31")),
        "t.msh:33: element 3 refers to node 31, which $Nodes does not define"
    );
    let mut bytes = written(&mixed_3d(), MshVersion::V41, true);
    let first = find(&bytes, b"$Elements\n") + 10 + 32 + 20;
    bytes[first + 16..first + 24].copy_from_slice(&77u64.to_le_bytes());
    assert_eq!(
        error(&bytes),
        format!(
            "t.msh: byte {}: element 1 refers to node 77, which $Nodes does not define",
            first + 16
        )
    );
}

#[test]
fn error_bad_node_tags() {
    assert_eq!(
        error(&replaced(V22, "3 1 1 0\n", "2 1 1 0\n")),
        "t.msh:8: node tag 2 is given to two nodes"
    );
    assert_eq!(
        error(&replaced(V22, "3 1 1 0\n", "0 1 1 0\n")),
        "t.msh:12: node tag 0 is not allowed (tags start at 1)"
    );
    assert_eq!(
        error(&replaced(V22, "2 2 2 0 1 1 2 3", "3 2 2 0 1 1 2 3")),
        "t.msh:21: element tag 3 is used by two elements"
    );
}

#[test]
fn error_non_finite_coordinates() {
    assert_eq!(
        error(&replaced(V22, "3 1 1 0\n", "3 1 nan 0\n")),
        "t.msh:12: node 3 has a non-finite coordinate (NaN)"
    );
    assert_eq!(
        error(&replaced(V41, "1 1 0\n0 1 0", "1 1 0\n0 -inf 0")),
        "t.msh:25: node 30 has a non-finite coordinate (-inf)"
    );
    let mut bytes = written(&hybrid_2d(), MshVersion::V41, true);
    let coords = find(&bytes, b"$Nodes\n") + 7 + 32 + 20 + 6 * 8;
    bytes[coords + 32..coords + 40].copy_from_slice(&f64::INFINITY.to_le_bytes());
    assert_eq!(
        error(&bytes),
        format!(
            "t.msh: byte {}: node 3 has a non-finite coordinate (inf)",
            coords + 24
        )
    );
    assert_eq!(
        error(&replaced(V22, "3 1 1 0\n", "3 1 1e999x 0\n")),
        "t.msh:12: expected a coordinate, found '1e999x'"
    );
}

#[test]
fn error_unsupported_element_type() {
    assert_eq!(
        error(&replaced(V22, "3 2 2 0 1 1 3 4", "3 9 2 0 1 1 3 4 5 6 7")),
        "t.msh:19: element type 9 is not supported (verbss reads the linear types 15 point, 1 line, \
         2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron, 6 prism, 7 pyramid)"
    );
    let mut bytes = written(&mixed_3d(), MshVersion::V41, true);
    let block = find(&bytes, b"$Elements\n") + 10 + 32;
    bytes[block + 8..block + 12].copy_from_slice(&12i32.to_le_bytes());
    assert_eq!(
        error(&bytes),
        format!(
            "t.msh: byte {block}: element type 12 is not supported (verbss reads the linear types 15 point, \
             1 line, 2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron, 6 prism, 7 pyramid)"
        )
    );
}

#[test]
fn error_binary_junk() {
    let mut bytes = written(&mixed_3d(), MshVersion::V41, true);
    let at = find(&bytes, b"$Elements\n");
    bytes[at..at + 4].copy_from_slice(b"\x07\x00\xff$");
    assert_eq!(
        error(&bytes),
        format!("t.msh: byte {at}: expected a section header such as $Nodes, found '\\x07\\x00\\xff$ments'")
    );
    let mut bytes = written(&mixed_3d(), MshVersion::V22, true);
    let at = find(&bytes, b"$EndNodes");
    bytes[at + 4] = b'X';
    assert_eq!(
        error(&bytes),
        format!("t.msh: byte {at}: expected $EndNodes after 12 nodes, found '$EndXodes': the section holds more than it declares")
    );
}

#[test]
fn error_structure() {
    assert_eq!(
        error(&replaced(
            V22,
            "$Elements\n3\n1 1 2 1 1 1 2\n2 2 2 0 1 1 2 3\n3 2 2 0 1 1 3 4\n",
            "$Elements\n1\n1 1 2 1 1 1 2\n"
        )),
        "t.msh:19: the file has no 2D or 3D elements (highest element dimension: 1)"
    );
    assert_eq!(
        error(&replaced(V22, "3 1 1 0\n", "3 1 1 0.5\n")),
        "t.msh:12: node 3 has z = 0.5, but a mesh without 3D elements must lie in the plane z = 0 \
         (a surface mesh in 3D space is not a planar 2D mesh)"
    );
    let nodes_at = V22.find("$Nodes").unwrap();
    let elements_at = V22.find("$Elements").unwrap();
    let swapped = format!(
        "{}{}{}",
        &V22[..nodes_at],
        &V22[elements_at..],
        &V22[nodes_at..elements_at]
    );
    assert_eq!(
        error(swapped.as_bytes()),
        "t.msh:8: $Elements comes before $Nodes"
    );
    assert_eq!(
        error(&V22.as_bytes()[..V22.find("$Elements").unwrap()]),
        "t.msh:15: unexpected end of file: no $Elements section"
    );
    assert_eq!(
        error(&replaced(
            V22,
            "$EndNodes\n",
            "$EndNodes\n$Comments\nno end\n"
        )),
        "t.msh:15: unexpected end of file: no $EndComments closes it"
    );
    assert_eq!(
        error(&replaced(V41, "1 3 1 1\n", "1 4 1 1\n")),
        "t.msh:29: element block on entity 4 of dimension 1, which neither \
         $Entities nor $PartitionedEntities lists"
    );
    assert_eq!(
        error(&replaced(V41, "1 3 1 1\n", "2 3 1 1\n")),
        "t.msh:29: an element block on an entity of dimension 2 holds line elements (dimension 1)"
    );
    assert_eq!(
        error(&replaced(V22, "1 1 \"wall\"", "1 1 wall")),
        "t.msh:6: expected a physical name in double quotes, found 'wall'"
    );
}
