//! A single node (Gmsh physical point).

use crate::mesh::KindTable;

/// Reference table of the vertex.
pub static TABLE: KindTable = KindTable {
    name: "vertex",
    dim: 0,
    nodes: 1,
    edges: &[],
    facets: &[],
    corners: &[],
};
