//! The 4-node tetrahedron (positive when `(x1-x0)×(x2-x0)·(x3-x0) > 0`).
//!
//! ```text
//!        3
//!       /|\
//!      / | \
//!     /  |  \
//!    0---|---2
//!     `\ | ,/
//!       `1'
//! ```

use crate::mesh::KindTable;

/// Reference table of the tetrahedron.
pub static TABLE: KindTable = KindTable {
    name: "tetra",
    dim: 3,
    nodes: 4,
    edges: &[[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]],
    facets: &[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[0, 3, 2]],
    corners: &[[0, 1, 2, 3], [1, 2, 0, 3], [2, 0, 1, 3], [3, 0, 2, 1]],
};
