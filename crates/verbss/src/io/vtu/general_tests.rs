//! Polygons and polyhedra: VTK types 7 and 42 (with `faces` and
//! `faceoffsets`) written and read back, and their faults.

use std::path::Path;

use super::*;
use crate::mesh::{samples, CellKind, Cells, Group};

/// The mesh as `.vtu` bytes.
fn bytes(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    write_to(&mut out, mesh, &Fields::default()).unwrap();
    out
}

/// Two 2D cells (a pentagon and a triangle) and their boundary group.
fn pentagon_and_triangle() -> Mesh {
    let coords = vec![0., 0., 2., 0., 2.5, 1., 1., 2., -0.5, 1., 3., 2.];
    let mut cells = Cells::new();
    cells.push(CellKind::Polygon, &[0, 1, 2, 3, 4]);
    cells.push(CellKind::Triangle, &[2, 5, 3]);
    let mut facets = Cells::new();
    facets.push(CellKind::Line, &[0, 1]);
    let group = Group {
        name: "bottom".into(),
        tag: None,
        facets,
    };
    Mesh::new(2, coords, cells, vec![group]).unwrap()
}

#[test]
fn polygons_and_polyhedra_round_trip() {
    let flat = pentagon_and_triangle();
    let back = parse(&bytes(&flat), Path::new("p.vtu")).unwrap().mesh;
    assert_eq!(back, flat);
    // The 3D sample with every cell a polyhedron of its faces, and a group
    // of one pentagonal facet.
    let mut solid = samples::as_general(&samples::hex_wedge_pyramid_tet());
    let mut facets = Cells::new();
    facets.push(CellKind::Polygon, &[0, 1, 8, 2, 3]);
    solid.groups = vec![Group {
        name: "floor".into(),
        tag: None,
        facets,
    }];
    solid.validate().unwrap();
    let back = parse(&bytes(&solid), Path::new("s.vtu")).unwrap().mesh;
    assert_eq!(back.cells, solid.cells);
    assert_eq!(back.groups, solid.groups);
    assert_eq!(back.coords, solid.coords);
}

#[test]
fn a_polyhedron_without_its_faces_is_refused() {
    let solid = samples::as_general(&samples::hex_wedge_pyramid_tet());
    let text = String::from_utf8(bytes(&solid)).unwrap();
    let start = text
        .find(r#"<DataArray type="Int64" Name="faces""#)
        .unwrap();
    let end = text[start..].find("</Cells>").unwrap() + start;
    let cut = format!("{}{}", &text[..start], &text[end..]);
    let e = parse(cut.as_bytes(), Path::new("s.vtu"))
        .unwrap_err()
        .to_string();
    assert!(
        e.ends_with(
            "DataArray 'types': cell 0 is a polyhedron (42) but <Cells> has no 'faces' array"
        ),
        "{e}"
    );
}

/// SU2, Gmsh and fresh CGNS files have no polygon or polyhedron: writing
/// one is refused, naming the format and the element (or facet), and
/// nothing is written.
#[test]
fn formats_without_general_cells_refuse_them() {
    let dir = tempfile::tempdir().unwrap();
    let solid = samples::as_general(&samples::hex_wedge_pyramid_tet());
    let options = crate::io::WriteOptions::default();
    for (name, format) in [("s.su2", "SU2"), ("s.msh", "Gmsh MSH")] {
        let path = dir.path().join(name);
        let e = crate::io::write(&path, &solid, &options).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "{}: the {format} format cannot hold element 1, a polyhedron (write .vtu, or an \
                 OpenFOAM case; a mesh read from a .cgns file also writes back as .cgns)",
                path.display()
            )
        );
        assert!(!path.exists());
    }
    // A hexahedron mesh whose boundary group holds a pentagon.
    let mut mesh = samples::hex_wedge_pyramid_tet();
    let mut facets = Cells::new();
    facets.push(CellKind::Polygon, &[0, 1, 8, 2, 3]);
    mesh.groups.push(Group {
        name: "floor5".into(),
        tag: None,
        facets,
    });
    let path = dir.path().join("p.su2");
    let e = crate::io::write(&path, &mesh, &options)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("cannot hold facet 0 of group 'floor5', a polygon of 5 nodes"),
        "{e}"
    );
}
