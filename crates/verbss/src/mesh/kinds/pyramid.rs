//! The 5-node pyramid: base quad 0-1-2-3 counter-clockwise seen from the apex 4.
//!
//! ```text
//!          4
//!        /| |\
//!       / 3-|-2
//!      / /  |/
//!     0-----1
//! ```
//!
//! Its corners are the four base corners (each with its two base neighbours and
//! the apex); the apex has four edges and no single corner Jacobian.

use crate::mesh::KindTable;

/// Reference table of the pyramid.
pub static TABLE: KindTable = KindTable {
    name: "pyramid",
    dim: 3,
    nodes: 5,
    edges: &[
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [0, 4],
        [1, 4],
        [2, 4],
        [3, 4],
    ],
    facets: &[
        &[0, 3, 2, 1],
        &[0, 1, 4],
        &[1, 2, 4],
        &[2, 3, 4],
        &[3, 0, 4],
    ],
    corners: &[[0, 1, 3, 4], [1, 2, 0, 4], [2, 3, 1, 4], [3, 0, 2, 4]],
};
