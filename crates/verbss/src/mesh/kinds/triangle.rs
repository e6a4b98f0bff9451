//! The 3-node triangle (positive when counter-clockwise).
//!
//! ```text
//! 2
//! |`\
//! |  `\
//! 0----1
//! ```

use crate::mesh::KindTable;

/// Reference table of the triangle.
pub static TABLE: KindTable = KindTable {
    name: "triangle",
    dim: 2,
    nodes: 3,
    edges: &[[0, 1], [1, 2], [2, 0]],
    facets: &[&[0, 1], &[1, 2], &[2, 0]],
    corners: &[[0, 1, 2, 0], [1, 2, 0, 0], [2, 0, 1, 0]],
};
