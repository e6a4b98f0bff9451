//! Gmsh MSH 2.2 and 4.1, ASCII and binary.

use std::io::Write;
use std::path::Path;

use super::MshVersion;
use crate::error::Result;
use crate::mesh::Mesh;

/// Parses a Gmsh file's bytes; `path` is only used in error messages.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh> {
    let _ = (bytes, path);
    unimplemented!("gmsh reader")
}

/// Writes `mesh` as MSH `version`, ASCII or binary.
pub fn write_to(
    w: &mut dyn Write,
    mesh: &Mesh,
    version: MshVersion,
    binary: bool,
) -> std::io::Result<()> {
    let _ = (w, mesh, version, binary);
    unimplemented!("gmsh writer")
}
