//! The 2-node segment, a boundary facet of 2D meshes.
//!
//! ```text
//! 0-----1
//! ```

use crate::mesh::KindTable;

/// Reference table of the segment.
pub static TABLE: KindTable = KindTable {
    name: "line",
    dim: 1,
    nodes: 2,
    edges: &[[0, 1]],
    facets: &[&[0], &[1]],
    corners: &[],
};
