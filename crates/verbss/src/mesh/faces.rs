//! The faces of polyhedral cells, and the local topology (edges, facets)
//! of a cell of any kind.
//!
//! A polyhedron's faces are stored once, as lists of *local* node indices
//! (positions in the cell's own node list), each face counter-clockwise
//! seen from outside: its normal by the right-hand rule points out of the
//! cell. Local indices survive any renumbering of the nodes, so a part or a
//! reordered copy of the cells carries its polyhedra without touching them.

use super::{CellKind, KindTable};

/// The faces of the polyhedra of a list of cells: polyhedron `cells[k]`
/// has faces `first[k]..first[k + 1]`, face `f` the local nodes
/// `local[offsets[f]..offsets[f + 1]]`. Empty when there is no polyhedron.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Faces {
    cells: Vec<usize>,
    first: Vec<usize>,
    offsets: Vec<usize>,
    local: Vec<usize>,
}

impl Default for Faces {
    fn default() -> Faces {
        Faces {
            cells: Vec::new(),
            first: vec![0],
            offsets: vec![0],
            local: Vec::new(),
        }
    }
}

impl Faces {
    /// Whether there is no polyhedron.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// Appends the faces of cell `cell` (above every cell listed so far),
    /// each a list of local node indices.
    pub fn push<'a>(&mut self, cell: usize, faces: impl IntoIterator<Item = &'a [usize]>) {
        debug_assert!(self.cells.last().is_none_or(|&c| c < cell));
        self.cells.push(cell);
        for face in faces {
            self.local.extend_from_slice(face);
            self.offsets.push(self.local.len());
        }
        self.first.push(self.offsets.len() - 1);
    }

    /// The faces of cell `cell`, if it is a polyhedron listed here.
    pub fn of(&self, cell: usize) -> Option<FaceList<'_>> {
        let k = self.cells.binary_search(&cell).ok()?;
        let (a, b) = (self.first[k], self.first[k + 1]);
        Some(FaceList {
            offsets: &self.offsets[a..=b],
            local: &self.local,
        })
    }

    /// The polyhedra listed, in increasing order, with their faces.
    pub fn iter(&self) -> impl Iterator<Item = (usize, FaceList<'_>)> + '_ {
        self.cells.iter().map(|&c| (c, self.of(c).expect("listed")))
    }
}

/// The faces of one polyhedron, each a list of local node indices.
#[derive(Debug, Clone, Copy)]
pub struct FaceList<'a> {
    offsets: &'a [usize],
    local: &'a [usize],
}

impl<'a> FaceList<'a> {
    /// Number of faces.
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether there is no face.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Face `f`.
    pub fn face(&self, f: usize) -> &'a [usize] {
        &self.local[self.offsets[f]..self.offsets[f + 1]]
    }

    /// The faces in order.
    pub fn iter(&self) -> impl Iterator<Item = &'a [usize]> + 'a {
        let this = *self;
        (0..this.len()).map(move |f| this.face(f))
    }
}

/// The local topology of one cell: its edges and facets as local node
/// indices, from the kind's table or, for the general kinds, from the cell.
#[derive(Debug, Clone, Copy)]
pub enum Local<'a> {
    /// A kind with a fixed table.
    Table(&'static KindTable),
    /// A polygon of this many nodes: side `k` joins nodes `k` and `k + 1`.
    Polygon(usize),
    /// A polyhedron's faces.
    Polyhedron(FaceList<'a>),
}

impl<'a> Local<'a> {
    /// The topology of a cell of `kind` with `nodes` nodes and, for a
    /// polyhedron, faces `faces`.
    ///
    /// # Panics
    /// For a polyhedron without faces.
    pub fn of(kind: CellKind, nodes: usize, faces: Option<FaceList<'a>>) -> Local<'a> {
        match kind {
            CellKind::Polygon => Local::Polygon(nodes),
            CellKind::Polyhedron => Local::Polyhedron(faces.expect("a polyhedron has faces")),
            _ => Local::Table(kind.table()),
        }
    }

    /// Calls `f(a, b)` once for every edge of the cell (never a face or
    /// cell diagonal). A polyhedron's edge is the side `a → b` of the face
    /// that runs along it with `a < b` (its other face runs `b → a`).
    pub fn edges(&self, mut f: impl FnMut(usize, usize)) {
        match self {
            Local::Table(t) => t.edges.iter().for_each(|e| f(e[0], e[1])),
            Local::Polygon(n) => (0..*n).for_each(|k| f(k, (k + 1) % n)),
            Local::Polyhedron(faces) => {
                for face in faces.iter() {
                    for k in 0..face.len() {
                        let (a, b) = (face[k], face[(k + 1) % face.len()]);
                        if a < b {
                            f(a, b);
                        }
                    }
                }
            }
        }
    }

    /// Calls `f(facet)` for every facet (an edge in 2D, a face in 3D), as
    /// local node indices, outward for a positively oriented cell.
    pub fn facets(&self, mut f: impl FnMut(&[usize])) {
        match self {
            Local::Table(t) => t.facets.iter().for_each(|facet| f(facet)),
            Local::Polygon(n) => (0..*n).for_each(|k| f(&[k, (k + 1) % n])),
            Local::Polyhedron(faces) => faces.iter().for_each(f),
        }
    }
}
