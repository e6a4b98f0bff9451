//! The 4-node quadrilateral, nodes in cyclic order (positive when counter-clockwise).
//!
//! ```text
//! 3-----2
//! |     |
//! |     |
//! 0-----1
//! ```

use crate::mesh::KindTable;

/// Reference table of the quadrilateral.
pub static TABLE: KindTable = KindTable {
    name: "quad",
    dim: 2,
    nodes: 4,
    edges: &[[0, 1], [1, 2], [2, 3], [3, 0]],
    facets: &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]],
    corners: &[[0, 1, 3, 0], [1, 2, 0, 0], [2, 3, 1, 0], [3, 0, 2, 0]],
};
