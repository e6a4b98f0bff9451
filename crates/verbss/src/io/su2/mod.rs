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
//! A multi-zone file (the usual fluid–structure file) announces its zones
//! with `NZONE= n` before anything else and gives each after an `IZONE= k`
//! line, `k` from 1 to `n` in order, with its own `NDIME=`, `NELEM=`,
//! `NPOIN=` and `NMARK=`:
//!
//! ```text
//! NZONE= 2
//! IZONE= 1
//! NDIME= 2
//! …                             % the fluid zone's sections
//! IZONE= 2
//! NDIME= 2
//! …                             % the solid zone's sections
//! ```
//!
//! [`parse_zone`] reads one zone and keeps the others verbatim; [`parse_zones`]
//! reads them all.
//!
//! [`stream`] reads a single-zone file once in chunks of lines, handing
//! each chunk's points, elements and marker facets over without ever
//! holding the whole mesh (the distributed read of `docs/distributed.md`);
//! it parses every line as the whole-file reader does, with its messages.
//!
//! Sections it does not use (`FFD_NBOX=`, `NPERIODIC=` and any other unknown
//! keyword, with their data lines) are kept verbatim in [`FileOrigin::su2_skipped`](crate::mesh::FileOrigin::su2_skipped),
//! each with the section it followed, and [`write_to`] puts them back in the
//! same place: reading a file and writing it back changes the layout of the
//! elements, points and markers, never the text of those sections.

mod read;
mod write;

pub use read::{stream, validate_at, Chunk, Outline};
pub use write::{write_moved_to, write_to, write_zones_to};

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
///
/// A multi-zone file gives its zone 1, as [`parse_zone`] does.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh> {
    parse_zone(bytes, path, 1).map(|(mesh, _)| mesh)
}

/// Parses zone `zone` (1-based, as `IZONE=` numbers it) of an SU2 file, and
/// gives the file's number of zones (1 for a file without `NZONE=`).
///
/// Every zone is checked as [`parse`] checks a file. The other zones are
/// kept verbatim in [`FileOrigin::su2_skipped`](crate::mesh::FileOrigin::su2_skipped) (anchored [`Anchor::ZonesBefore`]
/// and [`Anchor::ZonesAfter`]), so that writing the mesh as SU2 gives the
/// whole file back with only this zone rewritten.
pub fn parse_zone(bytes: &[u8], path: &Path, zone: usize) -> Result<(Mesh, usize)> {
    read::parse_zone(bytes, path, zone)
}

/// Parses every zone of an SU2 file, in order (one mesh for a file without
/// `NZONE=`); none keeps the others' text.
pub fn parse_zones(bytes: &[u8], path: &Path) -> Result<Vec<Mesh>> {
    read::parse_zones(bytes, path)
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
    /// The start of a multi-zone file up to the `IZONE=` line of the zone
    /// read: `NZONE=` and the zones before it. Written first.
    ZonesBefore,
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
    /// The zones after the one read in a multi-zone file, from the end of
    /// its last section. Written last.
    ZonesAfter,
}

/// The SU2/VTK name of a kind, as used in messages.
fn kind_name(kind: CellKind) -> &'static str {
    NAMES
        .iter()
        .find(|t| t.0 == kind)
        .map(|t| t.1)
        .expect("every kind has an SU2 name")
}

/// SU2, one zone or several.
pub struct Su2;

impl super::MeshFormat for Su2 {
    fn name(&self) -> &'static str {
        "SU2"
    }

    fn read_zone(&self, path: &Path, zone: usize) -> Result<(Mesh, usize)> {
        parse_zone(&super::read_bytes(path)?, path, zone)
    }

    fn read_zones(&self, path: &Path) -> Result<Vec<Mesh>> {
        parse_zones(&super::read_bytes(path)?, path)
    }

    fn write_moved(
        &self,
        path: &Path,
        mesh: &Mesh,
        coords: &[f64],
        _: &super::WriteOptions,
    ) -> Result<()> {
        super::write_atomic(path, |w| write_moved_to(w, mesh, coords))
    }

    fn stores_general_cells(&self, _: &Mesh) -> bool {
        false
    }
}

#[cfg(test)]
mod hostile_tests;
#[cfg(test)]
mod stream_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod zone_tests;
