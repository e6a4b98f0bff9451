//! `NGON_n` and `NFACE_n` sections: polyhedra (3D) and polygons (2D) read
//! from their faces, moved and written back as read.

use std::path::{Path, PathBuf};

use super::*;
use crate::io::cgns::ffi::{self, CgSize, File, Mode};
use crate::io::write_moved;

/// Two unit boxes side by side (x from 0 to 2) as `NGON_n` faces 1–11 and
/// `NFACE_n` cells 12–13, the faces at x = 0 a `QUAD_4` section `left`
/// (element 14). The shared face (2) points out of the first box: the
/// second names it `shared` (−2 when right).
fn two_boxes(path: &Path, shared: CgSize) -> PathBuf {
    let Some(file) = File::open(path, Mode::Write).ok() else {
        panic!("cannot write {}", path.display());
    };
    let b = file.write_base("Base", 3, 3).unwrap();
    let z = file
        .write_zone(b, "Zone", ffi::UNSTRUCTURED, &[12, 2, 0])
        .unwrap();
    // Node (i, j, k) is 1 + i + 3 (j + 2 k), i in 0..3, j and k in 0..2.
    let id = |i: CgSize, j: CgSize, k: CgSize| 1 + i + 3 * (j + 2 * k);
    let (mut x, mut y, mut zs) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..3 {
                x.push(i as f64);
                y.push(j as f64);
                zs.push(k as f64);
            }
        }
    }
    for (name, v) in [
        ("CoordinateX", &x),
        ("CoordinateY", &y),
        ("CoordinateZ", &zs),
    ] {
        file.write_coordinate(b, z, name, v).unwrap();
    }
    // Faces: x = 0, 1, 2 (normal +x); then per box y = 0, y = 1, z = 0, z = 1,
    // outward from that box.
    let mut faces: Vec<Vec<CgSize>> = (0..3)
        .map(|i| vec![id(i, 0, 0), id(i, 1, 0), id(i, 1, 1), id(i, 0, 1)])
        .collect();
    for i in 0..2 {
        faces.push(vec![
            id(i, 0, 0),
            id(i + 1, 0, 0),
            id(i + 1, 0, 1),
            id(i, 0, 1),
        ]);
        faces.push(vec![
            id(i, 1, 0),
            id(i, 1, 1),
            id(i + 1, 1, 1),
            id(i + 1, 1, 0),
        ]);
        faces.push(vec![
            id(i, 0, 0),
            id(i, 1, 0),
            id(i + 1, 1, 0),
            id(i + 1, 0, 0),
        ]);
        faces.push(vec![
            id(i, 0, 1),
            id(i + 1, 0, 1),
            id(i + 1, 1, 1),
            id(i, 1, 1),
        ]);
    }
    let stream = |lists: &[Vec<CgSize>]| {
        let mut offsets = vec![0];
        for l in lists {
            offsets.push(offsets.last().unwrap() + l.len() as CgSize);
        }
        (lists.concat(), offsets)
    };
    let (nodes, offsets) = stream(&faces);
    file.write_section(b, z, "Faces", ffi::NGON_N, (1, 11), &nodes, &offsets)
        .unwrap();
    let cells = vec![vec![-1, 2, 4, 5, 6, 7], vec![shared, 3, 8, 9, 10, 11]];
    let (nodes, offsets) = stream(&cells);
    file.write_section(b, z, "Cells", ffi::NFACE_N, (12, 13), &nodes, &offsets)
        .unwrap();
    let left = [id(0, 0, 0), id(0, 0, 1), id(0, 1, 1), id(0, 1, 0)];
    file.write_section(b, z, "left", 7, (14, 14), &left, &[])
        .unwrap();
    file.close().unwrap();
    path.to_path_buf()
}

#[test]
fn polyhedra_are_read_from_their_faces_and_written_back_as_read() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let path = two_boxes(&dir.path().join("boxes.cgns"), -2);
    let mesh = read(&path).unwrap();
    assert_eq!(mesh.cells.kinds, [CellKind::Polyhedron; 2]);
    assert_eq!(mesh.cell_tags, [12, 13]);
    assert_eq!(mesh.cells.faces.of(1).unwrap().len(), 6);
    assert_eq!(mesh.group_names(), ["left"]);
    let summary = crate::quality::summary_json(&mesh);
    assert_eq!(summary["inverted"], 0, "{summary}");
    assert!(
        (summary["quality"]["min"].as_f64().unwrap() - 1.0).abs() < 1e-12,
        "{summary}"
    );
    // Moved (the middle plane sheared) and written back: the same file
    // but its coordinates.
    let mut coords = mesh.coords.clone();
    for i in 0..mesh.node_count() {
        if mesh.point(i)[0] == 1.0 {
            coords[3 * i + 1] += 0.25 * mesh.point(i)[2];
        }
    }
    let out = dir.path().join("moved.cgns");
    write_moved(&out, &mesh, &coords, &WriteOptions::default()).unwrap();
    let back = read(&out).unwrap();
    assert_eq!(back.cells, mesh.cells);
    assert_eq!(back.coords, coords);
    assert_eq!(back.cell_tags, mesh.cell_tags);
    // The second box naming its shared face +2: its faces no longer close
    // it outward, and the message names the cell.
    let bad = two_boxes(&dir.path().join("bad.cgns"), 2);
    let e = read(&bad).unwrap_err().to_string();
    assert!(
        e.contains("cell 1 (polyhedron) has two faces that run along one side the same way"),
        "{e}"
    );
}

#[test]
fn polygons_are_read_from_their_edges() {
    if !needs(LIBRARY, available()) {
        return;
    }
    // Two unit squares side by side: nodes 1 + i + 3 j, edges 1–7, cells 8–9.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("squares.cgns");
    let file = File::open(&path, Mode::Write).unwrap();
    let b = file.write_base("Base", 2, 2).unwrap();
    let z = file
        .write_zone(b, "Zone", ffi::UNSTRUCTURED, &[6, 2, 0])
        .unwrap();
    file.write_coordinate(b, z, "CoordinateX", &[0., 1., 2., 0., 1., 2.])
        .unwrap();
    file.write_coordinate(b, z, "CoordinateY", &[0., 0., 0., 1., 1., 1.])
        .unwrap();
    let edges: [CgSize; 14] = [1, 2, 2, 3, 4, 5, 5, 6, 1, 4, 2, 5, 3, 6];
    let offsets: Vec<CgSize> = (0..=7).map(|k| 2 * k).collect();
    file.write_section(b, z, "Edges", ffi::NGON_N, (1, 7), &edges, &offsets)
        .unwrap();
    let cells: [CgSize; 8] = [1, 6, -3, -5, 2, 7, -4, -6];
    file.write_section(b, z, "Cells", ffi::NFACE_N, (8, 9), &cells, &[0, 4, 8])
        .unwrap();
    file.close().unwrap();
    let mesh = read(&path).unwrap();
    assert_eq!(mesh.cells.kinds, [CellKind::Polygon; 2]);
    assert_eq!(mesh.cells.cell(0), [0, 1, 4, 3]);
    assert_eq!(mesh.cells.cell(1), [1, 2, 5, 4]);
    let summary = crate::quality::summary_json(&mesh);
    assert_eq!(summary["inverted"], 0, "{summary}");
    assert!(
        (summary["quality"]["min"].as_f64().unwrap() - 1.0).abs() < 1e-12,
        "{summary}"
    );
}

#[test]
fn a_face_that_does_not_fit_the_base_is_refused() {
    if !needs(LIBRARY, available()) {
        return;
    }
    // scripts/make_cgns_fixtures.c: a 2D square with an NGON_n "face" of 3 nodes.
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/bad/polyhedral.cgns"
    ));
    assert_eq!(
        read(path).unwrap_err().to_string(),
        format!(
            "{}: section 'Faces' of zone 'Zone' (zone 1 of base 'Base'): face 5 has 3 nodes \
             (expected 2 in a base of cell dimension 2)",
            path.display()
        )
    );
}
