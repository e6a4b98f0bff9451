//! The 8-node hexahedron: bottom face 0-1-2-3 counter-clockwise seen from above,
//! top face 4-5-6-7 above it.
//!
//! ```text
//!     7--------6
//!    /|       /|
//!   4--------5 |
//!   | |      | |
//!   | 3------|-2
//!   |/       |/
//!   0--------1
//! ```

use crate::mesh::KindTable;

/// Reference table of the hexahedron.
pub static TABLE: KindTable = KindTable {
    name: "hexahedron",
    dim: 3,
    nodes: 8,
    edges: &[
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [4, 5],
        [5, 6],
        [6, 7],
        [7, 4],
        [0, 4],
        [1, 5],
        [2, 6],
        [3, 7],
    ],
    facets: &[
        &[0, 3, 2, 1],
        &[4, 5, 6, 7],
        &[0, 1, 5, 4],
        &[1, 2, 6, 5],
        &[2, 3, 7, 6],
        &[3, 0, 4, 7],
    ],
    corners: &[
        [0, 1, 3, 4],
        [1, 2, 0, 5],
        [2, 3, 1, 6],
        [3, 0, 2, 7],
        [4, 7, 5, 0],
        [5, 4, 6, 1],
        [6, 5, 7, 2],
        [7, 6, 4, 3],
    ],
};
