//! Small structured meshes of every element kind, for the fuzz targets and
//! the property tests (`crates/verbss/tests/properties.rs` includes this file).

use verbss::mesh::{CellKind, Cells, Group, Mesh};
use verbss::{quality, topology};

/// A structured mesh of `[0, 1]^dim` with `n` nodes a side, cells of the kind
/// chosen by `kind` (2D: triangles, quads, both; 3D: hexahedra, prisms,
/// tetrahedra, pyramids, hexahedra and pyramids), every cell positively
/// oriented. Groups: `left` (boundary facets on `x = 0`) and `walls` (the
/// other boundary facets). Each coordinate is then moved by `jitter()` times
/// the spacing (which may tangle cells).
pub fn grid(dim: usize, n: usize, kind: u8, mut jitter: impl FnMut() -> f64) -> Option<Mesh> {
    let h = 1.0 / (n - 1) as f64;
    let sides = if dim == 2 { [n, n, 1] } else { [n, n, n] };
    let id = |i: usize, j: usize, k: usize| i + n * (j + n * k);
    let mut coords = Vec::new();
    for k in 0..sides[2] {
        for j in 0..n {
            for i in 0..n {
                coords.extend_from_slice(&[i as f64 * h, j as f64 * h, k as f64 * h][..dim]);
            }
        }
    }
    let mut cells = Cells::new();
    let mut extra = Vec::new();
    let cubes = if dim == 2 {
        [n - 1, n - 1, 1]
    } else {
        [n - 1; 3]
    };
    for k in 0..cubes[2] {
        for j in 0..cubes[1] {
            for i in 0..cubes[0] {
                let c = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                let alternate = (i + j + k) % 2 == 0;
                if dim == 2 {
                    match (kind % 3, alternate) {
                        (1, _) | (2, true) => cells.push(CellKind::Quad, &c[..4]),
                        _ => {
                            cells.push(CellKind::Triangle, &[c[0], c[1], c[2]]);
                            cells.push(CellKind::Triangle, &[c[0], c[2], c[3]]);
                        }
                    }
                    continue;
                }
                match (kind % 5, alternate) {
                    (0, _) | (4, true) => cells.push(CellKind::Hexahedron, &c),
                    (1, _) => {
                        cells.push(CellKind::Wedge, &[c[0], c[1], c[2], c[4], c[5], c[6]]);
                        cells.push(CellKind::Wedge, &[c[0], c[2], c[3], c[4], c[6], c[7]]);
                    }
                    (2, _) => {
                        // Kuhn's six tetrahedra along the diagonal 0–6.
                        for [a, b] in [[1, 2], [2, 3], [3, 7], [7, 4], [4, 5], [5, 1]] {
                            cells.push(CellKind::Tetra, &[c[0], c[a], c[b], c[6]]);
                        }
                    }
                    _ => {
                        let centre = coords.len() / 3 + extra.len() / 3;
                        extra.extend_from_slice(&[
                            (i as f64 + 0.5) * h,
                            (j as f64 + 0.5) * h,
                            (k as f64 + 0.5) * h,
                        ]);
                        for f in [
                            [0, 1, 2, 3],
                            [4, 5, 6, 7],
                            [0, 1, 5, 4],
                            [1, 2, 6, 5],
                            [2, 3, 7, 6],
                            [3, 0, 4, 7],
                        ] {
                            cells.push(
                                CellKind::Pyramid,
                                &[c[f[0]], c[f[1]], c[f[2]], c[f[3]], centre],
                            );
                        }
                    }
                }
            }
        }
    }
    coords.extend_from_slice(&extra);
    orient_positive(dim, &coords, &mut cells);
    let facets = topology::boundary_facets(&cells);
    let (mut left, mut walls) = (Cells::new(), Cells::new());
    for (kind, nodes) in facets.iter() {
        if nodes.iter().all(|&v| coords[dim * v] == 0.0) {
            left.push(kind, nodes);
        } else {
            walls.push(kind, nodes);
        }
    }
    for x in coords.iter_mut() {
        *x += h * jitter();
    }
    let group = |name: &str, facets| Group {
        name: name.into(),
        tag: None,
        facets,
    };
    Mesh::new(
        dim,
        coords,
        cells,
        vec![group("left", left), group("walls", walls)],
    )
    .ok()
}

/// Reverses the cells whose orientation is negative, so that every cell of
/// the undistorted grid is positively oriented.
fn orient_positive(dim: usize, coords: &[f64], cells: &mut Cells) {
    for c in 0..cells.len() {
        let kind = cells.kinds[c];
        let nodes = cells.cell(c).to_vec();
        let sign = match dim {
            2 => quality::cell_orientation::<2>(kind, &nodes, coords),
            _ => quality::cell_orientation::<3>(kind, &nodes, coords),
        };
        if sign < 0 {
            let swaps: &[[usize; 2]] = match kind {
                CellKind::Triangle | CellKind::Tetra => &[[1, 2]],
                CellKind::Quad | CellKind::Pyramid => &[[1, 3]],
                CellKind::Hexahedron => &[[1, 3], [5, 7]],
                CellKind::Wedge => &[[1, 2], [4, 5]],
                CellKind::Vertex | CellKind::Line => &[],
            };
            let start = cells.offsets[c];
            for [a, b] in swaps {
                cells.nodes.swap(start + a, start + b);
            }
        }
    }
}
