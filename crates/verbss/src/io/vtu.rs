//! VTK XML unstructured grids (`.vtu`).
//!
//! # What verbss writes
//!
//! One `<Piece>` of an `UnstructuredGrid`, `version="1.0"`, little endian,
//! `header_type="UInt64"`, `compressor="vtkZLibDataCompressor"`, every array
//! `format="binary"` and zlib-compressed as VTK itself writes it: the values'
//! bytes in blocks of 32 KiB, each deflated on its own; base64 of the 8-byte
//! header words `[blocks, 32768, last block's size, compressed size of each
//! block]`, then base64 of the compressed blocks (the two encoded one after
//! the other). ParaView, VTK and meshio read this; a series frame takes
//! about a third of the uncompressed size.
//!
//! - `Points`: `Float64`, always 3 components (a 2D mesh gets `z = 0`), so
//!   coordinates survive a round trip bit for bit.
//! - `Cells`: `connectivity` and `offsets` as `Int64`, `types` as `UInt8` with
//!   the VTK numbers 1 vertex, 3 line, 5 triangle, 7 polygon, 9 quad,
//!   10 tetra, 12 hexahedron, 13 wedge, 14 pyramid, 42 polyhedron; with
//!   polyhedra, also VTK's `faces` (`Int64`: per polyhedron `nFaces`, then
//!   `nPoints, point …` per face, outward) and `faceoffsets` (`Int64`: the
//!   end of each cell's faces in `faces`, −1 for the other cells), which
//!   ParaView reads (and verbss reads back). The volume cells come first in mesh
//!   order, then the facets of group 0, group 1, … in group order. VTK
//!   numbers a wedge's two triangles the other way round from the mesh (and
//!   Gmsh): nodes `0 1 2 3 4 5` of a mesh wedge are written `0 2 1 3 5 4`, and
//!   read back the same way, as meshio does.
//! - Groups (VTU has none): the `Int32` cell-data array `group` is 0 on volume
//!   cells and `k + 1` on the facets of group `k`; `<FieldData>` holds one
//!   `Int32` array per group, named after the group, with the values
//!   `k + 1, facet dimension` and, if the group has a Gmsh physical tag, the
//!   tag as a third value. This is meshio's own `field_data` convention
//!   (`name → [id, dim]`), so meshio reads the names back in `field_data`
//!   (it cannot read `String` arrays, hence no `String` array).
//! - Numbering: the point-data array `node_tag` and the cell-data array
//!   `cell_tag` (`Int64`, 0 on facets) keep the mesh's node and cell tags.
//! - [`Fields`]: `Float64` point data and cell data; a cell field has one row
//!   per volume cell and is padded with NaN on the facet rows.
//!
//! # What verbss reads
//!
//! Its own files and those of ParaView/VTK and meshio: `ascii`, inline
//! `binary` (base64, `UInt32` or `UInt64` headers, each part encoded on its
//! own or all together, zlib-compressed or not) and `appended` data (`raw` or
//! `base64`), either byte order, any integer or float type. The dimension is 2
//! when every `z` is 0 and no cell is 3D, else 3; the cells of that dimension
//! become the volume cells, in file order. The lower-dimensional cells become
//! group facets: by the `group` array and the `<FieldData>` names above when
//! present; facets without a named group go to a group called `boundary`.
//! Every other point/cell data array is returned in [`Fields`] (cell data
//! restricted to the volume cells).
//!
//! # Why hand-written
//!
//! The format is small, and the parser must name the line or byte offset of
//! every fault and never allocate from a count that a header merely claims.
//! `vtkio` 0.7 is a release candidate whose errors carry no position and which
//! builds its own model that would have to be converted again; so `quick-xml`
//! tokenises the XML, `base64` and `flate2` decode the binary arrays, and this
//! module does the rest.

use std::path::Path;

use crate::error::Result;
use crate::mesh::Mesh;

mod assemble;
mod binary;

/// VTK XML unstructured grid (`.vtu`).
pub struct Vtu;

impl super::MeshFormat for Vtu {
    fn name(&self) -> &'static str {
        "VTK XML"
    }

    fn read_zone(&self, path: &Path, zone: usize) -> Result<(Mesh, usize)> {
        super::format::one_zone(path, zone, || read(path).map(|v| v.mesh))
    }

    fn write_moved(
        &self,
        path: &Path,
        mesh: &Mesh,
        coords: &[f64],
        _: &super::WriteOptions,
    ) -> Result<()> {
        write_moved(path, mesh, coords, &Fields::default())
    }

    fn stores_general_cells(&self, _: &Mesh) -> bool {
        true
    }
}

#[cfg(test)]
mod general_tests;
#[cfg(test)]
mod hostile_tests;
mod read;
#[cfg(test)]
mod tests;
mod write;
mod xml;

pub use read::parse;
pub use write::{write_moved_to, write_to};

/// Name of the cell-data array that maps cells to groups.
const GROUP_ARRAY: &str = "group";
/// Name of the cell-data array with the cell tags.
const CELL_TAG_ARRAY: &str = "cell_tag";
/// Name of the point-data array with the node tags.
const NODE_TAG_ARRAY: &str = "node_tag";
/// Name of the group that collects facets without a named group.
const UNNAMED_GROUP: &str = "boundary";

/// Point and cell data written beside the mesh.
///
/// Values are tuple-major: the `components` values of node (or cell) `i` are
/// `values[components*i .. components*(i+1)]`, as in VTK.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fields {
    /// Point data: name, components per node, values (`components × nodes`).
    pub point: Vec<(String, usize, Vec<f64>)>,
    /// Cell data: name, components per cell, values (`components × cells`),
    /// one row per volume cell.
    pub cell: Vec<(String, usize, Vec<f64>)>,
}

/// A `.vtu` file read back: the mesh and its fields.
#[derive(Debug, Clone, PartialEq)]
pub struct VtuData {
    /// The mesh.
    pub mesh: Mesh,
    /// Its point and cell data.
    pub fields: Fields,
}

/// Reads a `.vtu` file.
pub fn read(path: &Path) -> Result<VtuData> {
    parse(&crate::io::read_bytes(path)?, path)
}

/// Writes `mesh` and `fields` to `path` atomically (see [`crate::io::write_atomic`]).
pub fn write(path: &Path, mesh: &Mesh, fields: &Fields) -> Result<()> {
    write_moved(path, mesh, &mesh.coords, fields)
}

/// [`write()`] with the nodes at `coords` ([`write_moved_to`]).
pub fn write_moved(path: &Path, mesh: &Mesh, coords: &[f64], fields: &Fields) -> Result<()> {
    crate::io::write_atomic(path, |w| write_moved_to(w, mesh, coords, fields))
}
