//! The 6-node prism (wedge): triangle 0-1-2 counter-clockwise seen from the
//! top triangle 3-4-5, which lies above it.
//!
//! ```text
//!        5
//!      / | \
//!     3-----4
//!     |  2  |
//!     | / \ |
//!     0-----1
//! ```

use crate::mesh::KindTable;

/// Reference table of the prism.
pub static TABLE: KindTable = KindTable {
    name: "wedge",
    dim: 3,
    nodes: 6,
    edges: &[
        [0, 1],
        [1, 2],
        [2, 0],
        [3, 4],
        [4, 5],
        [5, 3],
        [0, 3],
        [1, 4],
        [2, 5],
    ],
    facets: &[
        &[0, 2, 1],
        &[3, 4, 5],
        &[0, 1, 4, 3],
        &[1, 2, 5, 4],
        &[2, 0, 3, 5],
    ],
    corners: &[
        [0, 1, 2, 3],
        [1, 2, 0, 4],
        [2, 0, 1, 5],
        [3, 5, 4, 0],
        [4, 3, 5, 1],
        [5, 4, 3, 2],
    ],
};
