//! Round trips in all four encodings, Gmsh's own files, and every error message.

use std::path::Path;

use super::model::kind_of_type;
use super::{parse, write_to};
use crate::io::MshVersion;
use crate::mesh::{CellKind, Cells, Group, Mesh};

const ENCODINGS: [(MshVersion, bool); 4] = [
    (MshVersion::V22, false),
    (MshVersion::V22, true),
    (MshVersion::V41, false),
    (MshVersion::V41, true),
];

fn fixture_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/gmsh")
}

fn read_fixture(name: &str) -> Mesh {
    let path = fixture_dir().join(name);
    let bytes = std::fs::read(&path).unwrap();
    parse(&bytes, &path).unwrap()
}

fn written(mesh: &Mesh, version: MshVersion, binary: bool) -> Vec<u8> {
    let mut bytes = Vec::new();
    write_to(&mut bytes, mesh, version, binary).unwrap();
    bytes
}

/// The error message for `bytes` read as `t.msh`.
fn error(bytes: &[u8]) -> String {
    parse(bytes, Path::new("t.msh")).unwrap_err().to_string()
}

/// Asserts equality including the bit patterns of the coordinates.
fn assert_same(a: &Mesh, b: &Mesh) {
    assert_eq!(a, b);
    let bits = |m: &Mesh| m.coords.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(a), bits(b));
}

fn cells(list: &[(CellKind, &[usize])]) -> Cells {
    let mut c = Cells::new();
    for (k, n) in list {
        c.push(*k, n);
    }
    c
}

fn group(name: &str, tag: i32, facets: &[(CellKind, &[usize])]) -> Group {
    Group {
        name: name.into(),
        tag: Some(tag),
        facets: cells(facets),
    }
}

/// Two triangles and a quad, sparse unsorted tags, awkward coordinates.
fn hybrid_2d() -> Mesh {
    use CellKind::*;
    Mesh {
        dim: 2,
        coords: vec![
            0.0,
            -0.0,
            1.0 / 3.0,
            0.1,
            2.0,
            1e-300,
            0.0,
            1.0,
            1.0,
            1.0,
            2.0,
            1.0 + f64::EPSILON,
        ],
        node_tags: vec![7, 3, 100, 1, 5, 64],
        cells: cells(&[
            (Triangle, &[0, 1, 4]),
            (Quad, &[1, 2, 5, 4]),
            (Triangle, &[0, 4, 3]),
        ]),
        cell_tags: vec![10, 4, 11],
        groups: vec![
            group("wall", 3, &[(Line, &[0, 1]), (Line, &[1, 2])]),
            group("far field", 9, &[(Line, &[5, 4]), (Line, &[4, 3])]),
            group("corner", 1, &[(Vertex, &[2])]),
        ],
        su2_skipped: Vec::new(),
    }
}

/// A tetrahedron, a hexahedron, a prism and a pyramid sharing faces.
fn mixed_3d() -> Mesh {
    use CellKind::*;
    #[rustfmt::skip]
    let coords = vec![
        0.0, 0.0, 0.0,  1.0, 0.0, 0.0,  1.0, 1.0, 0.0,  0.0, 1.0, 0.0,
        0.0, 0.0, 1.0,  1.0, 0.0, 1.0,  1.0, 1.0, 1.0,  0.0, 1.0, 1.0,
        2.0, 0.0, 0.0,  2.0, 1.0, 0.0,  0.5, 0.5, 1.75, 0.1, 0.2, -1.0,
    ];
    Mesh {
        dim: 3,
        coords,
        node_tags: (1..=12).rev().map(|t| t * 2).collect(),
        cells: cells(&[
            (Hexahedron, &[0, 1, 2, 3, 4, 5, 6, 7]),
            (Wedge, &[1, 8, 5, 2, 9, 6]),
            (Pyramid, &[4, 5, 6, 7, 10]),
            (Tetra, &[0, 3, 1, 11]),
        ]),
        cell_tags: vec![1, 2, 3, 4],
        groups: vec![
            group(
                "bottom",
                2,
                &[(Quad, &[0, 3, 2, 1]), (Triangle, &[0, 1, 11])],
            ),
            group("side", 5, &[(Quad, &[1, 8, 9, 2]), (Triangle, &[1, 8, 5])]),
            group("edge", 1, &[(Line, &[8, 9])]),
        ],
        su2_skipped: Vec::new(),
    }
}

#[test]
fn round_trips_2d_hybrid_in_all_encodings() {
    let mesh = hybrid_2d();
    mesh.validate().unwrap();
    for (version, binary) in ENCODINGS {
        let back = parse(&written(&mesh, version, binary), Path::new("t.msh")).unwrap();
        assert_same(&mesh, &back);
    }
}

#[test]
fn round_trips_3d_mixed_in_all_encodings() {
    let mesh = mixed_3d();
    mesh.validate().unwrap();
    for (version, binary) in ENCODINGS {
        let back = parse(&written(&mesh, version, binary), Path::new("t.msh")).unwrap();
        assert_same(&mesh, &back);
    }
}

#[test]
fn round_trips_gmsh_files_in_all_encodings() {
    for name in ["box_v41_ascii.msh", "channel_hole_v41_binary.msh"] {
        let mesh = read_fixture(name);
        for (version, binary) in ENCODINGS {
            let back = parse(&written(&mesh, version, binary), Path::new("t.msh")).unwrap();
            assert_same(&mesh, &back);
        }
    }
}

#[test]
fn groups_without_tags_get_fresh_ones_and_facets_fresh_tags() {
    let mut mesh = hybrid_2d();
    mesh.groups[1].tag = None;
    mesh.groups[2].tag = Some(3);
    let text = String::from_utf8(written(&mesh, MshVersion::V41, false)).unwrap();
    // The volume cells get the next fresh tag, 5, named "domain".
    assert!(text.contains(
        "$PhysicalNames\n4\n1 3 \"wall\"\n1 4 \"far field\"\n0 3 \"corner\"\n2 5 \"domain\"\n"
    ));
    let back = parse(text.as_bytes(), Path::new("t.msh")).unwrap();
    let tags: Vec<_> = back.groups.iter().map(|g| g.tag).collect();
    assert_eq!(tags, [Some(3), Some(4), Some(3)]);
    // Facet element tags continue after the largest cell tag, 11.
    assert!(text.contains("1 1 1 2\n12 7 3\n13 3 100\n"));
}

#[test]
fn writer_rejects_what_msh_cannot_store() {
    let mut mesh = hybrid_2d();
    mesh.groups[0].name = "a\"b".into();
    let e = write_to(&mut Vec::new(), &mesh, MshVersion::V41, false).unwrap_err();
    assert_eq!(
        e.to_string(),
        "group name \"a\\\"b\" holds a quote or a line break, which MSH cannot store"
    );
    let mut mesh = hybrid_2d();
    mesh.groups[2].facets.push(CellKind::Line, &[0, 1]);
    let e = write_to(&mut Vec::new(), &mesh, MshVersion::V41, false).unwrap_err();
    assert_eq!(
        e.to_string(),
        "group 'corner' mixes facets of dimension 0 and 1; a Gmsh physical group has one dimension"
    );
    let mut mesh = hybrid_2d();
    mesh.node_tags[0] = 1 << 40;
    let e = write_to(&mut Vec::new(), &mesh, MshVersion::V22, true).unwrap_err();
    assert_eq!(
        e.to_string(),
        "node tag 1099511627776 does not fit the 32-bit integers of MSH 2.2 (write MSH 4.1)"
    );
    let back = parse(&written(&mesh, MshVersion::V41, true), Path::new("t.msh")).unwrap();
    assert_same(&mesh, &back);
}

/// Compares a fixture with the numbers Gmsh itself gave (counts.json).
#[test]
fn gmsh_fixtures_match_gmsh_counts() {
    let text = std::fs::read_to_string(fixture_dir().join("counts.json")).unwrap();
    let counts: serde_json::Value = serde_json::from_str(&text).unwrap();
    let files = counts.as_object().unwrap();
    assert_eq!(files.len(), 6);
    for (name, want) in files {
        let mesh = read_fixture(name);
        let dim = want["dim"].as_u64().unwrap() as usize;
        assert_eq!(mesh.dim, dim, "{name}");
        assert_eq!(
            mesh.node_count() as u64,
            want["nodes"].as_u64().unwrap(),
            "{name}"
        );
        assert_eq!(
            mesh.cell_count() as u64,
            want["cells"].as_u64().unwrap(),
            "{name}"
        );
        for (etype, n) in want["cells_per_type"].as_object().unwrap() {
            let kind = kind_of_type(etype.parse().unwrap()).unwrap();
            let have = mesh.cells.kinds.iter().filter(|&&k| k == kind).count();
            assert_eq!(have as u64, n.as_u64().unwrap(), "{name} type {etype}");
        }
        let lower: Vec<_> = want["groups"]
            .as_object()
            .unwrap()
            .iter()
            .filter(|(_, g)| (g["dim"].as_u64().unwrap() as usize) < dim)
            .collect();
        assert_eq!(mesh.groups.len(), lower.len(), "{name}");
        for (gname, g) in lower {
            let group = mesh.group(gname).unwrap();
            assert_eq!(
                group.tag,
                Some(g["tag"].as_i64().unwrap() as i32),
                "{name} {gname}"
            );
            assert_eq!(
                group.facets.len() as u64,
                g["elements"].as_u64().unwrap(),
                "{name} {gname}"
            );
            let gdim = g["dim"].as_u64().unwrap() as usize;
            assert!(
                group.facets.kinds.iter().all(|k| k.dim() == gdim),
                "{name} {gname}"
            );
        }
    }
}

#[test]
fn gmsh_encodings_agree() {
    // Gmsh's ASCII keeps 16 significant digits, its binary all 17.
    let close = |a: &Mesh, b: &Mesh| {
        assert_eq!(a.coords.len(), b.coords.len());
        for (x, y) in a.coords.iter().zip(&b.coords) {
            assert!((x - y).abs() <= 1e-15 * x.abs().max(1.0), "{x} {y}");
        }
    };
    let binary = read_fixture("channel_hole_v41_binary.msh");
    for name in [
        "channel_hole_v22_ascii.msh",
        "channel_hole_v22_binary.msh",
        "channel_hole_v41_ascii.msh",
    ] {
        let other = read_fixture(name);
        assert_eq!(other.node_tags, binary.node_tags, "{name}");
        assert_eq!(other.cells, binary.cells, "{name}");
        assert_eq!(other.groups, binary.groups, "{name}");
        close(&other, &binary);
    }
    let (v41, v22) = (
        read_fixture("box_v41_ascii.msh"),
        read_fixture("box_v22_ascii.msh"),
    );
    assert_eq!(v22.cells, v41.cells);
    assert_eq!(v22.groups, v41.groups);
    assert_eq!(v22.coords, v41.coords);
}

#[test]
fn box_boundary_group_is_the_union_of_the_others() {
    for name in ["box_v41_ascii.msh", "box_v22_ascii.msh"] {
        let mesh = read_fixture(name);
        let mut parts: Vec<&[usize]> = ["inlet", "outlet", "sides"]
            .iter()
            .flat_map(|g| mesh.group(g).unwrap().facets.iter().map(|(_, n)| n))
            .collect();
        let mut all: Vec<&[usize]> = mesh
            .group("boundary")
            .unwrap()
            .facets
            .iter()
            .map(|(_, n)| n)
            .collect();
        parts.sort();
        all.sort();
        assert_eq!(parts, all, "{name}");
    }
}

const V22: &str = "$MeshFormat
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

const V41: &str = "$MeshFormat
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

fn replaced(text: &str, from: &str, to: &str) -> Vec<u8> {
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
    let extra = "$Periodic\n1\n1 1 1\n$EndPeriodic\n$NodeData\n1\n\"u\"\n$EndNodeData\n";
    let bytes = replaced(V22, "$Nodes\n", &format!("{extra}$Nodes\n"));
    let plain = parse(V22.as_bytes(), Path::new("t.msh")).unwrap();
    assert_eq!(parse(&bytes, Path::new("t.msh")).unwrap(), plain);
    let mut binary = written(&plain, MshVersion::V41, true);
    binary.extend_from_slice(extra.as_bytes());
    assert_eq!(parse(&binary, Path::new("t.msh")).unwrap(), plain);
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
        "t.msh:29: element block on entity 4 of dimension 1, which $Entities does not list"
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
