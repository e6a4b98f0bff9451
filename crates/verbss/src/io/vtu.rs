//! VTK XML unstructured grids (`.vtu`) and ParaView collections (`.pvd`).

use std::io::Write;
use std::path::Path;

use crate::error::Result;
use crate::mesh::Mesh;

/// Point and cell data written beside the mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fields {
    /// Point data: name, components per node, values (`components × nodes`).
    pub point: Vec<(String, usize, Vec<f64>)>,
    /// Cell data: name, components per cell, values (`components × cells`).
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

/// Parses a `.vtu` file's bytes; `path` is only used in error messages.
pub fn parse(bytes: &[u8], path: &Path) -> Result<VtuData> {
    let _ = (bytes, path);
    unimplemented!("vtu reader")
}

/// Writes `mesh` and `fields` as a `.vtu` file.
pub fn write_to(w: &mut dyn Write, mesh: &Mesh, fields: &Fields) -> std::io::Result<()> {
    let _ = (w, mesh, fields);
    unimplemented!("vtu writer")
}
