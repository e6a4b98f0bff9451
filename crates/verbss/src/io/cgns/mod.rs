//! CGNS meshes (`.cgns`, HDF5 or ADF underneath), through the CGNS C
//! library: unstructured zones with element sections and boundary conditions.
//!
//! Reading takes zone 1 of base 1, as the library numbers them (zones in
//! the order of their names; [`Source::zones`] tells how many the base holds). The cells are the elements of the base's cell dimension, in
//! section order (TRI_3, QUAD_4 in 2D; TETRA_4, PYRA_5, PENTA_6, HEXA_8 in
//! 3D; MIXED of those), numbered as in the file; BAR_2, TRI_3 and QUAD_4
//! elements of one dimension less are boundary facets. CGNS numbers the nodes
//! of these kinds as verbss does. NGON_n/NFACE_n sections, other element
//! kinds and structured zones are refused, naming the zone and section.
//!
//! Groups: each boundary condition (`ZoneBC/BC_t`) becomes the group named by
//! its `FamilyName`, else by its own name (conditions of one family make one
//! group); a family that belongs to another family (a `FamilyName_t` under
//! its `Family_t`, as Gmsh writes one family per entity in the family of its
//! physical group) gives the name of the family at the top. A condition over
//! element numbers (`ElementRange`/`ElementList`, or `PointRange`/`PointList`
//! at `FaceCenter`/`EdgeCenter`/`CellCenter`) holds those facets; one over
//! vertices (`Vertex`) holds single nodes; one at `CellCenter` over cells of
//! the zone's own dimension is a region, not a boundary, and no group. A
//! section of facets that no condition holds or is named after becomes a
//! group of its own name.
//!
//! [`blocks::Blocks`] reads the same zone in blocks, with the same checks
//! and names, for a distributed read (`verbss-mpi`).
//!
//! Writing a mesh read from a CGNS file copies that file and replaces only
//! the values of `GridCoordinates/CoordinateX, Y (, Z)`, in their own
//! precision; any other mesh is written as a fresh file (see [`write()`]).

pub mod blocks;
#[cfg(with_cgns)]
mod check;
#[cfg(with_cgns)]
mod container;
#[cfg(with_cgns)]
mod ffi;
pub mod nodes;
#[cfg(with_cgns)]
mod read;
#[cfg(with_cgns)]
mod write;
#[cfg(with_cgns)]
mod zone;

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// Where a mesh read from a CGNS file came from, so that writing it as CGNS
/// copies that file and replaces the coordinates only.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// The file that was read.
    pub path: PathBuf,
    /// The name of the base read (base 1).
    pub base: String,
    /// The name of the zone read (zone 1 of the base).
    pub zone: String,
    /// The number of zones of the base (only the first is read).
    pub zones: usize,
}

/// `Ok` when verbss was built with the CGNS library, else why not and how
/// to rebuild.
pub fn available() -> std::result::Result<(), String> {
    let missing = env!("VERBSS_CGNS_MISSING");
    if missing.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "built without CGNS ({missing}): install the CGNS library (Debian: libcgns-dev), \
             then rebuild with the cargo feature `cgns` (on by default) after `cargo clean -p verbss`"
        ))
    }
}

/// An error about the CGNS file `path`.
fn error(path: &Path, message: impl Into<String>) -> Error {
    Error::Cgns {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// Reads zone 1 of base 1 of a CGNS file.
pub fn read(path: &Path) -> Result<Mesh> {
    #[cfg(with_cgns)]
    return read::read(path);
    #[cfg(not(with_cgns))]
    return Err(unavailable(path));
}

/// The error for a `.cgns` file given to a build without the library.
#[cfg(not(with_cgns))]
fn unavailable(path: &Path) -> Error {
    error(path, available().err().unwrap_or_default())
}

/// Writes `mesh` to the CGNS file `path`, atomically (a temporary file beside
/// it is renamed over it once complete).
///
/// A mesh read from a CGNS file ([`FileOrigin::cgns`](crate::mesh::FileOrigin::cgns)) is written as a copy
/// of that file with only its coordinate values replaced. Any other mesh is
/// written fresh: base `Base`, zone `Zone`, the cells in one section (MIXED
/// when of several kinds), and each group as a section of its facets with a
/// `FamilySpecified` boundary condition over that element range at
/// `FaceCenter` (3D) or `EdgeCenter` (2D), its name and family the group's;
/// a group of single nodes is a condition over a `PointList` of vertices.
pub fn write(path: &Path, mesh: &Mesh) -> Result<()> {
    write_moved(path, mesh, &mesh.coords)
}

/// [`write()`] with the nodes at `coords` (`dim` numbers per node) instead of
/// the mesh's own.
pub fn write_moved(path: &Path, mesh: &Mesh, coords: &[f64]) -> Result<()> {
    #[cfg(with_cgns)]
    return write::write(path, mesh, coords);
    #[cfg(not(with_cgns))]
    {
        let _ = (mesh, coords);
        Err(unavailable(path))
    }
}

/// CGNS, unstructured zones (with the CGNS library).
pub struct Cgns;

impl super::MeshFormat for Cgns {
    fn name(&self) -> &'static str {
        "CGNS"
    }

    fn read_zone(&self, path: &Path, zone: usize) -> Result<(Mesh, usize)> {
        super::format::one_zone(path, zone, || read(path))
    }

    fn write_moved(
        &self,
        path: &Path,
        mesh: &Mesh,
        coords: &[f64],
        _: &super::WriteOptions,
    ) -> Result<()> {
        write_moved(path, mesh, coords)
    }

    /// A file written from a CGNS input is that file with new coordinates,
    /// its `NGON_n`/`NFACE_n` sections kept; a new file holds the paper's
    /// kinds only.
    fn stores_general_cells(&self, mesh: &Mesh) -> bool {
        mesh.origin.cgns.is_some()
    }
}

#[cfg(test)]
mod tests;

#[cfg(all(test, with_cgns))]
mod hostile_tests;
