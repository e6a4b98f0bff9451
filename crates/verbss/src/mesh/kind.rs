//! Element kinds and their reference tables (node count, edges, facets, corners).
//!
//! Node numbering follows Gmsh, VTK and SU2, which agree for all linear kinds.
//! Every node list is kept exactly as the file stored it; orientation (which
//! way round a cell is numbered) is measured, never assumed: see
//! [`crate::quality`].

use super::kinds;

/// The kind of a cell: volume elements and the boundary facets of groups.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CellKind {
    /// A single node (Gmsh physical points).
    Vertex,
    /// 2-node segment: a 2D boundary facet.
    Line,
    /// 3-node triangle.
    Triangle,
    /// 4-node quadrilateral.
    Quad,
    /// 4-node tetrahedron.
    Tetra,
    /// 8-node hexahedron.
    Hexahedron,
    /// 6-node prism (wedge).
    Wedge,
    /// 5-node pyramid.
    Pyramid,
    /// A polygon of 3 or more nodes in cyclic order (counter-clockwise when
    /// positive): a 2D cell of any shape, or a 3D boundary facet of 5 or more
    /// nodes. Its edges and facets are its sides.
    Polygon,
    /// A polyhedron of any shape: its nodes, and its faces (polygons of
    /// local node indices, outward) in [`crate::mesh::Faces`].
    Polyhedron,
}

/// The reference table of one element kind.
#[derive(Debug)]
pub struct KindTable {
    /// The name meshio uses for the kind.
    pub name: &'static str,
    /// Topological dimension (0 to 3).
    pub dim: usize,
    /// Number of nodes.
    pub nodes: usize,
    /// Element edges as pairs of local node indices (never diagonals).
    pub edges: &'static [[usize; 2]],
    /// Facets (edges in 2D, faces in 3D) as local node lists, numbered so that
    /// for a positively oriented element their normal points outward.
    pub facets: &'static [&'static [usize]],
    /// Corners: local node `c[0]` followed by its `dim` neighbours, numbered so
    /// that the corner Jacobian `det(x[c1]-x[c0], …)` is positive for a
    /// positively oriented element.
    pub corners: &'static [[usize; 4]],
}

impl CellKind {
    /// All kinds, in declaration order.
    pub const ALL: [CellKind; 10] = [
        CellKind::Vertex,
        CellKind::Line,
        CellKind::Triangle,
        CellKind::Quad,
        CellKind::Tetra,
        CellKind::Hexahedron,
        CellKind::Wedge,
        CellKind::Pyramid,
        CellKind::Polygon,
        CellKind::Polyhedron,
    ];

    /// The kind's reference table.
    pub fn table(self) -> &'static KindTable {
        match self {
            CellKind::Vertex => &kinds::vertex::TABLE,
            CellKind::Line => &kinds::line::TABLE,
            CellKind::Triangle => &kinds::triangle::TABLE,
            CellKind::Quad => &kinds::quad::TABLE,
            CellKind::Tetra => &kinds::tetra::TABLE,
            CellKind::Hexahedron => &kinds::hexahedron::TABLE,
            CellKind::Wedge => &kinds::wedge::TABLE,
            CellKind::Pyramid => &kinds::pyramid::TABLE,
            CellKind::Polygon => &kinds::general::POLYGON,
            CellKind::Polyhedron => &kinds::general::POLYHEDRON,
        }
    }

    /// Whether the kind has no fixed node count (polygon, polyhedron): its
    /// table lists no edge, facet or corner, and its cells are read through
    /// [`crate::mesh::Local`].
    pub fn is_general(self) -> bool {
        matches!(self, CellKind::Polygon | CellKind::Polyhedron)
    }

    /// The name meshio uses (`"triangle"`, `"tetra"`, `"wedge"`, …).
    pub fn name(self) -> &'static str {
        self.table().name
    }

    /// Number of nodes of the kind (0 for a polygon or polyhedron, whose
    /// cells have any number).
    pub fn node_count(self) -> usize {
        self.table().nodes
    }

    /// Topological dimension of the kind.
    pub fn dim(self) -> usize {
        self.table().dim
    }

    /// The kind with a given meshio name.
    pub fn from_name(name: &str) -> Option<CellKind> {
        CellKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The VTK cell type id of the kind (1 vertex, 3 line, 5 triangle, 9 quad,
    /// 10 tetra, 12 hexahedron, 13 wedge, 14 pyramid, 7 polygon, 42
    /// polyhedron), which SU2 files and the C API use too for the fixed kinds.
    pub fn vtk_id(self) -> u8 {
        match self {
            CellKind::Vertex => 1,
            CellKind::Line => 3,
            CellKind::Triangle => 5,
            CellKind::Quad => 9,
            CellKind::Tetra => 10,
            CellKind::Hexahedron => 12,
            CellKind::Wedge => 13,
            CellKind::Pyramid => 14,
            CellKind::Polygon => 7,
            CellKind::Polyhedron => 42,
        }
    }

    /// The kind with VTK cell type id `id`, if verbss has it.
    pub fn from_vtk_id(id: i64) -> Option<CellKind> {
        CellKind::ALL
            .into_iter()
            .find(|k| i64::from(k.vtk_id()) == id)
    }

    /// Local node `i` of a cell numbered as VTK and SU2 number it is local
    /// node `vtk_local(i)` of the same cell numbered as verbss (and Gmsh) do,
    /// and back (the map is its own inverse). They differ only for the wedge,
    /// whose triangles VTK numbers the other way round (VTK's triangle 0-1-2
    /// faces away from 3-4-5, Gmsh's towards it).
    pub fn vtk_local(self, i: usize) -> usize {
        const WEDGE: [usize; 6] = [0, 2, 1, 3, 5, 4];
        if self == CellKind::Wedge {
            WEDGE[i]
        } else {
            i
        }
    }

    /// The kind of a facet with `n` nodes (2: line, 3: triangle, 4: quad,
    /// 5 or more: polygon).
    pub fn facet_kind(n: usize) -> CellKind {
        match n {
            1 => CellKind::Vertex,
            2 => CellKind::Line,
            3 => CellKind::Triangle,
            4 => CellKind::Quad,
            _ => CellKind::Polygon,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_consistent() {
        for kind in CellKind::ALL {
            let t = kind.table();
            assert_eq!(kind.dim(), t.dim);
            for e in t.edges {
                assert!(e[0] < t.nodes && e[1] < t.nodes && e[0] != e[1], "{kind:?}");
            }
            for f in t.facets {
                assert!(f.iter().all(|&n| n < t.nodes), "{kind:?}");
            }
            for c in t.corners {
                assert!(c[..=t.dim].iter().all(|&n| n < t.nodes), "{kind:?}");
            }
            assert_eq!(CellKind::from_name(t.name), Some(kind));
            assert_eq!(CellKind::from_vtk_id(kind.vtk_id().into()), Some(kind));
        }
    }

    #[test]
    fn every_edge_lies_on_a_facet_and_facets_close() {
        // Each facet edge of a 3D element is shared by exactly two facets.
        for kind in [
            CellKind::Tetra,
            CellKind::Hexahedron,
            CellKind::Wedge,
            CellKind::Pyramid,
        ] {
            let t = kind.table();
            for e in t.edges {
                let mut uses = 0;
                for f in t.facets {
                    for k in 0..f.len() {
                        let (a, b) = (f[k], f[(k + 1) % f.len()]);
                        if (a, b) == (e[0], e[1]) || (b, a) == (e[0], e[1]) {
                            uses += 1;
                        }
                    }
                }
                assert_eq!(uses, 2, "{kind:?} edge {e:?}");
            }
        }
    }

    #[test]
    fn facets_not_touching_a_node_match_design() {
        let count = |kind: CellKind, node: usize| {
            kind.table()
                .facets
                .iter()
                .filter(|f| !f.contains(&node))
                .count()
        };
        assert_eq!(count(CellKind::Triangle, 0), 1);
        assert_eq!(count(CellKind::Quad, 0), 2);
        assert_eq!(count(CellKind::Tetra, 0), 1);
        assert_eq!(count(CellKind::Hexahedron, 0), 3);
        assert_eq!(count(CellKind::Wedge, 0), 2);
        assert_eq!(count(CellKind::Pyramid, 4), 1);
        assert_eq!(count(CellKind::Pyramid, 0), 2);
    }
}
