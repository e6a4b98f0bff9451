//! Reading the input mesh, saying on standard error what of the file verbss
//! leaves out.

use std::path::Path;

use verbss::mesh::Mesh;

/// Reads the mesh at `path` for a command without `--zone` (the format
/// chosen by extension; of a file of several zones, zone 1), noting what of
/// the file is left out.
pub fn read_mesh(path: &Path) -> anyhow::Result<Mesh> {
    crate::zone::read(path, None, "`verbss convert FILE OUT.vtu --zone K`", false)
}

/// For a CGNS file of several zones, notes that only the first was read.
pub fn note_left_out(path: &Path, mesh: &Mesh) {
    if let Some(source) = mesh.origin.cgns.as_ref().filter(|s| s.zones > 1) {
        eprintln!(
            "note: {} has {} zones in base '{}'; verbss reads zone 1 ('{}') only",
            path.display(),
            source.zones,
            source.base,
            source.zone
        );
    }
}
