//! The kinds without a fixed node count: the polygon (nodes in cyclic
//! order, its sides the edges and facets) and the polyhedron (its faces
//! listed per cell in [`crate::mesh::Faces`]). Their tables are empty:
//! edges, facets and corners come from each cell ([`crate::mesh::Local`]).
//!
//! ```text
//!     3-----2            a polyhedron: any closed set of polygonal faces,
//!    /       \           each face's nodes counter-clockwise seen from
//!   4         1          outside (its normal, by the right-hand rule,
//!    \       /           points out of the cell)
//!     5-----0
//! ```

use crate::mesh::KindTable;

/// Reference table of the polygon.
pub static POLYGON: KindTable = KindTable {
    name: "polygon",
    dim: 2,
    nodes: 0,
    edges: &[],
    facets: &[],
    corners: &[],
};

/// Reference table of the polyhedron.
pub static POLYHEDRON: KindTable = KindTable {
    name: "polyhedron",
    dim: 3,
    nodes: 0,
    edges: &[],
    facets: &[],
    corners: &[],
};
