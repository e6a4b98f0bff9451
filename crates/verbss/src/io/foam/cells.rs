//! Cells from faces: each cell's faces, oriented outward (a face's normal
//! points out of its owner and into its neighbour), are recognised as one
//! of the four kinds of the VerBSS paper and numbered as that kind's table
//! wants (see [`crate::mesh::kinds`]); any other cell (a snappyHexMesh
//! refinement transition, a cell cut by a baffle) is a polyhedron of its
//! outward faces:
//!
//! | faces | kind |
//! |---|---|
//! | 4 triangles | tetrahedron |
//! | 1 quadrilateral, 4 triangles | pyramid |
//! | 2 triangles, 3 quadrilaterals | prism |
//! | 6 quadrilaterals | hexahedron |
//!
//! The base face, outward, is the kind's first facet (`0-3-2-1` for the
//! hexahedron and pyramid, `0-2-1` for the prism and tetrahedron), so the
//! cell is positively oriented when its faces point outward; each base
//! node's one edge leaving the base gives the node above it. The result's
//! facets must be the cell's faces exactly, else the cell is a polyhedron.
//! Either way the orientation is the faces' convention, never the cell's
//! shape: a cell the case holds tangled reads as inverted.

use super::read::PolyMesh;
use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells};

/// The cells of `mesh`, in label order.
pub(super) fn cells(mesh: &PolyMesh) -> Result<Cells> {
    let n_faces = mesh.n_faces();
    let n_cells = mesh
        .owner
        .iter()
        .chain(&mesh.neighbour)
        .max()
        .map_or(0, |&c| c + 1);
    // Faces of each cell, as (face, outward) in CSR form.
    let mut start = vec![0usize; n_cells + 1];
    for &c in mesh.owner.iter().chain(&mesh.neighbour) {
        start[c + 1] += 1;
    }
    for c in 0..n_cells {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut cell_faces = vec![(0usize, true); start[n_cells]];
    for f in 0..n_faces {
        cell_faces[fill[mesh.owner[f]]] = (f, true);
        fill[mesh.owner[f]] += 1;
        if let Some(&n) = mesh.neighbour.get(f) {
            cell_faces[fill[n]] = (f, false);
            fill[n] += 1;
        }
    }
    let mut cells = Cells::new();
    for c in 0..n_cells {
        let faces = &cell_faces[start[c]..start[c + 1]];
        let oriented: Vec<Vec<usize>> = faces
            .iter()
            .map(|&(f, outward)| {
                let mut p = mesh.face(f).to_vec();
                if !outward {
                    p.reverse();
                }
                p
            })
            .collect();
        if oriented.is_empty() {
            return Err(refuse(
                mesh,
                c,
                faces,
                "has no faces (cell labels must run from 0 without gaps)",
            ));
        }
        match shape(&oriented) {
            Some((kind, nodes)) => cells.push(kind, &nodes),
            None => cells.push_polyhedron(oriented.iter().map(Vec::as_slice)),
        }
    }
    Ok(cells)
}

/// The error for cell `c`, at the `owner` line of its first face.
fn refuse(mesh: &PolyMesh, c: usize, faces: &[(usize, bool)], why: &str) -> Error {
    let line = faces
        .iter()
        .find(|f| f.1)
        .map_or(1, |f| mesh.owner_lines[f.0] as usize);
    let labels: Vec<String> = faces.iter().take(8).map(|f| f.0.to_string()).collect();
    Error::Parse {
        path: mesh.file("owner"),
        line,
        message: format!(
            "cell {c} (faces {}{}) {why}",
            labels.join(" "),
            if faces.len() > 8 { " …" } else { "" }
        ),
    }
}

/// The kind and nodes of a cell from its outward faces, if it is one of the
/// four kinds.
fn shape(faces: &[Vec<usize>]) -> Option<(CellKind, Vec<usize>)> {
    let tris = faces.iter().filter(|f| f.len() == 3).count();
    let quads = faces.iter().filter(|f| f.len() == 4).count();
    let kind = match (faces.len(), tris, quads) {
        (4, 4, 0) => CellKind::Tetra,
        (5, 4, 1) => CellKind::Pyramid,
        (5, 2, 3) => CellKind::Wedge,
        (6, 0, 6) => CellKind::Hexahedron,
        _ => return None,
    };
    // The base: the kind's first facet, outward.
    let base_face = match kind {
        CellKind::Pyramid => faces.iter().find(|f| f.len() == 4),
        _ => faces
            .iter()
            .find(|f| f.len() == 3 || kind == CellKind::Hexahedron),
    }
    .expect("the kind has such a face");
    let first = kind.table().facets[0];
    let mut nodes = vec![usize::MAX; kind.node_count()];
    for (k, &local) in first.iter().enumerate() {
        nodes[local] = base_face[k];
    }
    let edges: Vec<[usize; 2]> = faces
        .iter()
        .flat_map(|f| (0..f.len()).map(move |i| [f[i], f[(i + 1) % f.len()]]))
        .collect();
    let base = first.len();
    match kind {
        CellKind::Tetra | CellKind::Pyramid => {
            let apex = edges.iter().flatten().find(|p| !base_face.contains(p))?;
            nodes[base] = *apex;
        }
        _ => {
            for i in 0..base {
                let b = nodes[i];
                let mut up = edges.iter().filter_map(|e| match e {
                    [x, y] if *x == b && !base_face.contains(y) => Some(*y),
                    [y, x] if *x == b && !base_face.contains(y) => Some(*y),
                    _ => None,
                });
                let above = up.next()?;
                if up.any(|y| y != above) {
                    return None;
                }
                nodes[i + base] = above;
            }
        }
    }
    same_faces(kind, &nodes, faces).then_some((kind, nodes))
}

/// Whether the facets of `kind` on `nodes` are `faces` (as sets of points).
fn same_faces(kind: CellKind, nodes: &[usize], faces: &[Vec<usize>]) -> bool {
    let sorted = |f: Vec<usize>| {
        let mut f = f;
        f.sort_unstable();
        f
    };
    let mut want: Vec<Vec<usize>> = kind
        .table()
        .facets
        .iter()
        .map(|f| sorted(f.iter().map(|&l| nodes[l]).collect()))
        .collect();
    let mut have: Vec<Vec<usize>> = faces.iter().map(|f| sorted(f.clone())).collect();
    want.sort_unstable();
    have.sort_unstable();
    let distinct = {
        let mut n = nodes.to_vec();
        n.sort_unstable();
        n.dedup();
        n.len() == nodes.len()
    };
    distinct && want == have
}
