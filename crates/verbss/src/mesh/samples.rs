//! Small meshes for tests, examples and fuzzing, each named for what it holds.
//!
//! ```
//! use verbss::mesh::samples;
//!
//! let square = samples::square_of_triangles(4);
//! assert_eq!((square.node_count(), square.cell_count()), (25, 32));
//! assert_eq!(square.group_names(), ["left", "right", "bottom", "top"]);
//! ```

use super::{CellKind, Cells, Group, Mesh};
use crate::{quality, topology};

/// The cells of `list`, in order.
fn cells(list: &[(CellKind, &[usize])]) -> Cells {
    let mut cells = Cells::new();
    for (kind, nodes) in list {
        cells.push(*kind, nodes);
    }
    cells
}

/// A group named `name` with physical tag `tag` and the facets of `list`.
fn group(name: &str, tag: Option<i32>, list: &[(CellKind, &[usize])]) -> Group {
    Group {
        name: name.into(),
        tag,
        facets: cells(list),
    }
}

/// One triangle, (0, 0), (1, 0), (0, 1); no groups.
pub fn one_triangle() -> Mesh {
    let cells = cells(&[(CellKind::Triangle, &[0, 1, 2])]);
    Mesh::new(2, vec![0., 0., 1., 0., 0., 1.], cells, vec![]).expect("a valid triangle")
}

/// The unit square as an `n × n` grid of triangles: node `j (n + 1) + i` at
/// `(i / n, j / n)`, each square cut along its diagonal from `(i, j)` to
/// `(i + 1, j + 1)`; groups `left`, `right`, `bottom` and `top` of lines.
pub fn square_of_triangles(n: usize) -> Mesh {
    unit_square(n, false)
}

/// The same grid of quadrilaterals `(i, j), (i + 1, j), (i + 1, j + 1),
/// (i, j + 1)`, with the same nodes and groups.
pub fn square_of_quads(n: usize) -> Mesh {
    unit_square(n, true)
}

/// [`square_of_triangles`], or [`square_of_quads`] when `quads`.
fn unit_square(n: usize, quads: bool) -> Mesh {
    let node = |i: usize, j: usize| j * (n + 1) + i;
    let mut coords = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            coords.extend([i as f64 / n as f64, j as f64 / n as f64]);
        }
    }
    let mut cells = Cells::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (
                node(i, j),
                node(i + 1, j),
                node(i + 1, j + 1),
                node(i, j + 1),
            );
            if quads {
                cells.push(CellKind::Quad, &[a, b, c, d]);
            } else {
                cells.push(CellKind::Triangle, &[a, b, c]);
                cells.push(CellKind::Triangle, &[a, c, d]);
            }
        }
    }
    let side = |name: &str, f: &dyn Fn(usize) -> [usize; 2]| {
        let mut facets = Cells::new();
        for k in 0..n {
            facets.push(CellKind::Line, &f(k));
        }
        Group {
            name: name.into(),
            tag: None,
            facets,
        }
    };
    let groups = vec![
        side("left", &|k| [node(0, k), node(0, k + 1)]),
        side("right", &|k| [node(n, k), node(n, k + 1)]),
        side("bottom", &|k| [node(k, 0), node(k + 1, 0)]),
        side("top", &|k| [node(k, n), node(k + 1, n)]),
    ];
    Mesh::new(2, coords, cells, groups).expect("a valid square")
}

/// Two triangles and a quad on `[0, 2] × [0, 1]` (nodes row by row from the
/// origin); groups `bottom` (tag 1) and `top` (tag 2) of lines.
pub fn two_triangles_and_a_quad() -> Mesh {
    let coords = vec![0., 0., 1., 0., 2., 0., 0., 1., 1., 1., 2., 1.];
    let volume = cells(&[
        (CellKind::Triangle, &[1, 2, 5]),
        (CellKind::Triangle, &[1, 5, 4]),
        (CellKind::Quad, &[0, 1, 4, 3]),
    ]);
    let groups = vec![
        group(
            "bottom",
            Some(1),
            &[(CellKind::Line, &[0, 1]), (CellKind::Line, &[1, 2])],
        ),
        group(
            "top",
            Some(2),
            &[(CellKind::Line, &[5, 4]), (CellKind::Line, &[4, 3])],
        ),
    ];
    Mesh::new(2, coords, volume, groups).expect("a valid 2D mesh")
}

/// A unit-cube hexahedron, a wedge beside it, a pyramid on the cube and a
/// tetrahedron on the wedge; groups `floor` (tag 1: a quad and a triangle)
/// and `roof` (tag 2: a triangle).
pub fn hex_wedge_pyramid_tet() -> Mesh {
    let coords = vec![
        0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 0., 0., 1., 1., 0., 1., 1., 1., 1., 0., 1.,
        1., 2., 0., 0., 2., 0., 1., 0.5, 0.5, 1.5, 1.5, 0.25, 1.5,
    ];
    let volume = cells(&[
        (CellKind::Hexahedron, &[0, 1, 2, 3, 4, 5, 6, 7]),
        (CellKind::Wedge, &[1, 8, 2, 5, 9, 6]),
        (CellKind::Pyramid, &[4, 5, 6, 7, 10]),
        (CellKind::Tetra, &[5, 9, 6, 11]),
    ]);
    let groups = vec![
        group(
            "floor",
            Some(1),
            &[
                (CellKind::Quad, &[0, 3, 2, 1]),
                (CellKind::Triangle, &[1, 2, 8]),
            ],
        ),
        group("roof", Some(2), &[(CellKind::Triangle, &[4, 5, 10])]),
    ];
    Mesh::new(3, coords, volume, groups).expect("a valid 3D mesh")
}

/// The corners of the diamond airfoil of [`fluid_around_an_airfoil`] and
/// [`solid_airfoil`], counter-clockwise from the leading edge.
const AIRFOIL: [[f64; 2]; 4] = [[0., 0.], [0.5, -0.1], [1., 0.], [0.5, 0.1]];

/// The fluid zone of a fluid–structure case: three rings of 4 nodes around a
/// diamond airfoil with chord `[0, 1]` (nodes `0..4` the airfoil, `4..8`
/// halfway out, `8..12` the far field, each ring counter-clockwise), 16
/// triangles between them; groups `airfoil` and `farfield` of lines.
pub fn fluid_around_an_airfoil() -> Mesh {
    let far = [[-1., 0.], [0.5, -1.], [2., 0.], [0.5, 1.]];
    let mut coords = Vec::new();
    for t in [0., 0.5, 1.] {
        for (a, f) in AIRFOIL.iter().zip(far) {
            coords.extend([a[0] + t * (f[0] - a[0]), a[1] + t * (f[1] - a[1])]);
        }
    }
    let ring = |r: usize, k: usize| 4 * r + k % 4;
    let mut volume = Cells::new();
    for r in 0..2 {
        for k in 0..4 {
            let (a, b) = (ring(r, k), ring(r, k + 1));
            let (c, d) = (ring(r + 1, k), ring(r + 1, k + 1));
            volume.push(CellKind::Triangle, &[a, c, d]);
            volume.push(CellKind::Triangle, &[a, d, b]);
        }
    }
    let lines = |r: usize| {
        let mut facets = Cells::new();
        for k in 0..4 {
            facets.push(CellKind::Line, &[ring(r, k), ring(r, k + 1)]);
        }
        facets
    };
    let groups = vec![
        Group {
            name: "airfoil".into(),
            tag: None,
            facets: lines(0),
        },
        Group {
            name: "farfield".into(),
            tag: None,
            facets: lines(2),
        },
    ];
    Mesh::new(2, coords, volume, groups).expect("a valid fluid zone")
}

/// The solid zone of the same case: the diamond airfoil of
/// [`fluid_around_an_airfoil`] as 4 triangles around its centre (node 4);
/// group `interface` of its 4 edges.
pub fn solid_airfoil() -> Mesh {
    let mut coords: Vec<f64> = AIRFOIL.iter().flatten().copied().collect();
    coords.extend([0.5, 0.]);
    let mut volume = Cells::new();
    let mut edges = Cells::new();
    for k in 0..4 {
        volume.push(CellKind::Triangle, &[4, k, (k + 1) % 4]);
        edges.push(CellKind::Line, &[k, (k + 1) % 4]);
    }
    let groups = vec![Group {
        name: "interface".into(),
        tag: None,
        facets: edges,
    }];
    Mesh::new(2, coords, volume, groups).expect("a valid solid zone")
}

/// `mesh` with every cell of a fixed kind written as the general kind of
/// its dimension: a 2D cell as the polygon of its nodes, a 3D cell as the
/// polyhedron of its facets (the same nodes, edges and faces).
pub fn as_general(mesh: &Mesh) -> Mesh {
    let mut cells = Cells::new();
    for (c, (kind, nodes)) in mesh.cells.iter().enumerate() {
        if kind.dim() == 2 {
            cells.push(CellKind::Polygon, nodes);
        } else {
            let faces: Vec<Vec<usize>> = kind
                .table()
                .facets
                .iter()
                .map(|f| f.iter().map(|&l| nodes[l]).collect())
                .collect();
            cells
                .push_polyhedron_on(nodes, faces.iter().map(Vec::as_slice))
                .expect("a facet's nodes are the cell's");
        }
        debug_assert_eq!(cells.cell(c), nodes);
    }
    let mut general = mesh.clone();
    general.cells = cells;
    general
}

/// A structured mesh of `[0, 1]^dim` with `n` nodes a side, cells of the kind
/// chosen by `kind` (2D: triangles, quads, both; 3D: hexahedra, prisms,
/// tetrahedra, pyramids, hexahedra and pyramids), every cell positively
/// oriented. Groups: `left` (boundary facets on `x = 0`) and `walls` (the
/// other boundary facets). Each coordinate is then moved by `jitter()` times
/// the spacing (which may tangle cells).
pub fn jittered_grid(
    dim: usize,
    n: usize,
    kind: u8,
    mut jitter: impl FnMut() -> f64,
) -> Option<Mesh> {
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
                CellKind::Vertex | CellKind::Line | CellKind::Polygon | CellKind::Polyhedron => &[],
            };
            let start = cells.offsets[c];
            for [a, b] in swaps {
                cells.nodes.swap(start + a, start + b);
            }
        }
    }
}
