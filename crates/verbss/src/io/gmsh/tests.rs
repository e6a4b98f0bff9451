//! Round trips in all four encodings, Gmsh's own files, and every error message.
//!
//! Hand-written files are in [`hand_written`], the error messages in [`errors`].

mod errors;
mod hand_written;
mod partitioned;
mod source;

use std::path::Path;

use super::model::kind_of_type;
use super::{parse, write_to};
use crate::io::MshVersion;
use crate::mesh::{CellKind, Cells, FileOrigin, Group, Mesh};

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
        origin: FileOrigin::default(),
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
        origin: FileOrigin::default(),
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
