//! SU2 native ASCII meshes.

use std::io::Write;
use std::path::Path;

use crate::error::Result;
use crate::mesh::Mesh;

/// Parses an SU2 file's bytes; `path` is only used in error messages.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh> {
    let _ = (bytes, path);
    unimplemented!("su2 reader")
}

/// Writes `mesh` in SU2 format.
pub fn write_to(w: &mut dyn Write, mesh: &Mesh) -> std::io::Result<()> {
    let _ = (w, mesh);
    unimplemented!("su2 writer")
}
