//! SU2 native ASCII meshes (`.su2`).
//!
//! A file is a list of sections, each opened by a keyword line:
//!
//! ```text
//! NDIME= 2                      % spatial dimension, 2 or 3
//! NELEM= 2                      % volume elements: VTK type id, node indices, [index]
//! 5  0 1 2  0
//! 5  0 2 3  1
//! NPOIN= 4                      % points: x y [z] [index]
//! 0 0  0
//! 1 0  1
//! 1 1  2
//! 0 1  3
//! NMARK= 1                      % boundary markers
//! MARKER_TAG= wall
//! MARKER_ELEMS= 1               % marker facets: VTK type id, node indices
//! 3  0 1
//! ```
//!
//! Node indices are 0-based positions in the `NPOIN=` list. Element type ids
//! are VTK's: 1 vertex, 3 line, 5 triangle, 9 quadrilateral, 10 tetrahedron,
//! 12 hexahedron, 13 prism, 14 pyramid. SU2 numbers nodes as VTK does, which
//! differs from verbss (Gmsh) for the prism only: see [`CellKind::vtk_local`].
//!
//! The reader accepts what SU2 and other tools write: `%` comments, blank
//! lines, sections in any order after `NDIME=`, keywords in any case with or
//! without `_` and spaces (`MARKER_TAG=`, `MARKERTAG =`), trailing indices after
//! coordinates and node lists, `NPOIN= n n_domain`. Node tags are
//! `index + 1`, cell tags `element index + 1`.
//!
//! Sections it does not use (`FFD_NBOX=`, `NPERIODIC=` and any other unknown
//! keyword, with their data lines) are kept verbatim in [`Mesh::su2_skipped`],
//! each with the section it followed, and [`write_to`] puts them back in the
//! same place: reading a file and writing it back changes the layout of the
//! elements, points and markers, never the text of those sections.

mod read;
mod write;

pub use write::write_to;

use std::path::Path;

use crate::error::Result;
use crate::mesh::{CellKind, Mesh};

/// The kinds an SU2 file holds and the names used in messages; their SU2 type
/// ids are VTK's ([`CellKind::vtk_id`]).
const NAMES: [(CellKind, &str); 8] = [
    (CellKind::Vertex, "vertex"),
    (CellKind::Line, "line"),
    (CellKind::Triangle, "triangle"),
    (CellKind::Quad, "quadrilateral"),
    (CellKind::Tetra, "tetrahedron"),
    (CellKind::Hexahedron, "hexahedron"),
    (CellKind::Wedge, "prism"),
    (CellKind::Pyramid, "pyramid"),
];

/// Parses an SU2 file's bytes; `path` is only used in error messages.
///
/// Checks everything [`Mesh::validate`] checks, but reports it with the line:
/// every count against its data, every node index against `NPOIN=`, every
/// coordinate finite, every element type allowed where it stands.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh> {
    read::Parser::new(bytes, path).run()
}

/// A run of sections of an SU2 file that verbss does not use (`FFD_NBOX=`,
/// `NPERIODIC=`, …), kept so that writing the mesh back as SU2 keeps it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Skipped {
    /// The section it followed in the file; it is written back after that section.
    pub after: Anchor,
    /// The file's text from the end of the section before it (the comment
    /// lines just before its first keyword included) up to the next section
    /// verbss reads or the end of the file: verbatim, line ends included.
    pub text: String,
}

/// The section of an SU2 file that a [`Skipped`] block followed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Anchor {
    /// Nothing: the block came before `NDIME=`.
    Start,
    /// The `NDIME=` line.
    Dimension,
    /// The `NELEM=` section.
    Elements,
    /// The `NPOIN=` section.
    Points,
    /// The `NMARK=` line, before the first marker.
    MarkerCount,
    /// Marker `k` (0-based, in file order) with its elements.
    Marker(usize),
}

/// The SU2/VTK name of a kind, as used in messages.
fn kind_name(kind: CellKind) -> &'static str {
    NAMES
        .iter()
        .find(|t| t.0 == kind)
        .map(|t| t.1)
        .expect("every kind has an SU2 name")
}

#[cfg(test)]
mod hostile_tests;
#[cfg(test)]
mod tests;
