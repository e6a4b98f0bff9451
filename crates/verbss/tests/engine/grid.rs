//! The generated meshes: structured grids of every element layout.

use verbss::{CellKind, Cells, Mesh};

/// The element layouts of the generated meshes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Layout {
    Tri,
    Quad,
    MixedTriQuad,
    Tet,
    Hex,
    Wedge,
    Pyramid,
    /// Hexahedra, prism columns and cubes of six pyramids around a centre node.
    MixedHexWedgePyramid,
}

pub const LAYOUTS: [Layout; 8] = [
    Layout::Tri,
    Layout::Quad,
    Layout::MixedTriQuad,
    Layout::Tet,
    Layout::Hex,
    Layout::Wedge,
    Layout::Pyramid,
    Layout::MixedHexWedgePyramid,
];

/// A deterministic number in [−0.5, 0.5) from a node's grid index.
fn jitter(seed: usize) -> f64 {
    let mut h = (seed as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    h ^= h >> 29;
    h = h.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h ^= h >> 32;
    (h % 1_000_000) as f64 / 1_000_000.0 - 0.5
}

/// A structured grid of `n` cells per side on the unit square or cube, cells
/// split according to `layout`, interior grid nodes moved by up to ±10 % of a
/// cell.
pub fn grid(layout: Layout, n: usize) -> Mesh {
    let dim = match layout {
        Layout::Tri | Layout::Quad | Layout::MixedTriQuad => 2,
        _ => 3,
    };
    let h = 1.0 / n as f64;
    let side = n + 1;
    let count = side.pow(dim as u32);
    let mut coords = Vec::with_capacity(dim * count);
    for id in 0..count {
        let ijk = [id % side, (id / side) % side, id / (side * side)];
        let interior = ijk[..dim].iter().all(|&v| v > 0 && v < n);
        for (axis, &v) in ijk[..dim].iter().enumerate() {
            let shift = if interior {
                0.2 * h * jitter(dim * id + axis)
            } else {
                0.0
            };
            coords.push(v as f64 * h + shift);
        }
    }
    let node = |i: usize, j: usize, k: usize| i + side * (j + side * k);
    let mut cells = Cells::new();
    for k in 0..if dim == 3 { n } else { 1 } {
        for j in 0..n {
            for i in 0..n {
                if dim == 2 {
                    let q = [
                        node(i, j, 0),
                        node(i + 1, j, 0),
                        node(i + 1, j + 1, 0),
                        node(i, j + 1, 0),
                    ];
                    let quad =
                        layout == Layout::Quad || (layout == Layout::MixedTriQuad && i < n / 2);
                    if quad {
                        cells.push(CellKind::Quad, &q);
                    } else {
                        cells.push(CellKind::Triangle, &[q[0], q[1], q[2]]);
                        cells.push(CellKind::Triangle, &[q[0], q[2], q[3]]);
                    }
                    continue;
                }
                let v = |b: usize| node(i + (b & 1), j + ((b >> 1) & 1), k + (b >> 2));
                // Hexahedron numbering: bottom 0 1 2 3, top 4 5 6 7.
                let hex = [v(0), v(1), v(3), v(2), v(4), v(5), v(7), v(6)];
                let kind = match layout {
                    Layout::MixedHexWedgePyramid => match (i + j) % 3 {
                        0 => Layout::Hex,
                        1 => Layout::Wedge,
                        _ => Layout::Pyramid,
                    },
                    other => other,
                };
                match kind {
                    Layout::Hex => cells.push(CellKind::Hexahedron, &hex),
                    Layout::Wedge => {
                        cells.push(
                            CellKind::Wedge,
                            &[hex[0], hex[1], hex[2], hex[4], hex[5], hex[6]],
                        );
                        cells.push(
                            CellKind::Wedge,
                            &[hex[0], hex[2], hex[3], hex[4], hex[6], hex[7]],
                        );
                    }
                    Layout::Tet => {
                        // Six tetrahedra along the diagonal v(0)–v(7), one per axis order.
                        for axes in [
                            [0, 1, 2],
                            [0, 2, 1],
                            [1, 0, 2],
                            [1, 2, 0],
                            [2, 0, 1],
                            [2, 1, 0],
                        ] {
                            let a = 1 << axes[0];
                            let b = a | (1 << axes[1]);
                            cells.push(CellKind::Tetra, &[v(0), v(a), v(b), v(7)]);
                        }
                    }
                    _ => {
                        let centre = coords.len() / 3;
                        for axis in 0..3 {
                            let mid = (0..8).map(|b| coords[3 * v(b) + axis]).sum::<f64>() / 8.0;
                            coords.push(mid);
                        }
                        for face in [
                            [0, 3, 2, 1],
                            [4, 5, 6, 7],
                            [0, 1, 5, 4],
                            [1, 2, 6, 5],
                            [2, 3, 7, 6],
                            [3, 0, 4, 7],
                        ] {
                            let f = face.map(|l| hex[l]);
                            cells.push(CellKind::Pyramid, &[f[0], f[1], f[2], f[3], centre]);
                        }
                    }
                }
            }
        }
    }
    Mesh::new(dim, coords, cells, vec![]).unwrap()
}
