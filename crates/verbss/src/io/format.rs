//! The one interface every mesh format implements, and the choice of the
//! format from a path.
//!
//! | format | [`MeshFormat`] | module |
//! |---|---|---|
//! | Gmsh MSH 2.2/4.1, ASCII and binary | [`gmsh::Msh`] | [`gmsh`] |
//! | SU2, one zone or several | [`su2::Su2`] | [`su2`] |
//! | VTK XML unstructured grid | [`vtu::Vtu`] | [`vtu`] |
//! | CGNS, unstructured zones | [`cgns::Cgns`] | [`cgns`] |
//! | an OpenFOAM case's `constant/polyMesh` | [`foam::Foam`] | [`foam`] |
//!
//! A reader names the file, the line (or byte offset, or CGNS node) and what
//! was expected in every error; a writer writes atomically
//! ([`write_atomic`](super::write_atomic)). Adding a format: a module with a
//! unit type implementing [`MeshFormat`], a [`Format`] variant, its
//! extension in [`Format::from_path`] (ARCHITECTURE.md, "How to add a
//! format").

use std::path::Path;

use super::{cgns, foam, gmsh, su2, vtu, WriteOptions};
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// What a mesh format does: read a file's zones and write a moved mesh.
pub trait MeshFormat: Sync {
    /// The format's name in messages (`"Gmsh MSH"`).
    fn name(&self) -> &'static str;

    /// Reads zone `zone` (1-based) of `path` and gives the file's number of
    /// zones. Every format but SU2 has one zone: another `zone` is refused.
    fn read_zone(&self, path: &Path, zone: usize) -> Result<(Mesh, usize)>;

    /// Reads every zone of `path`, in order.
    fn read_zones(&self, path: &Path) -> Result<Vec<Mesh>> {
        self.read_zone(path, 1).map(|(mesh, _)| vec![mesh])
    }

    /// Writes `mesh` with its nodes at `coords` (`dim` numbers per node) to
    /// `path`.
    fn write_moved(
        &self,
        path: &Path,
        mesh: &Mesh,
        coords: &[f64],
        options: &WriteOptions,
    ) -> Result<()>;

    /// Whether the format stores `mesh`'s polygons and polyhedra (every
    /// format that has them; a CGNS file only when it is the one the mesh
    /// was read from).
    fn stores_general_cells(&self, mesh: &Mesh) -> bool;
}

/// Reads zone 1 of a one-zone format's file with `read`, refusing another
/// zone.
pub(crate) fn one_zone(
    path: &Path,
    zone: usize,
    read: impl FnOnce() -> Result<Mesh>,
) -> Result<(Mesh, usize)> {
    if zone != 1 {
        return Err(Error::InvalidSetting(format!(
            "{}: zone {zone} asked for, but verbss reads several zones from SU2 files only",
            path.display()
        )));
    }
    Ok((read()?, 1))
}

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Gmsh `.msh`.
    Msh,
    /// SU2 `.su2`.
    Su2,
    /// VTK XML unstructured grid `.vtu`.
    Vtu,
    /// CGNS `.cgns` (unstructured zones).
    Cgns,
    /// An OpenFOAM case directory (its `constant/polyMesh`).
    Foam,
}

impl Format {
    /// The format's file extension, without the dot (none for OpenFOAM).
    pub fn extension(self) -> &'static str {
        match self {
            Format::Msh => "msh",
            Format::Su2 => "su2",
            Format::Vtu => "vtu",
            Format::Cgns => "cgns",
            Format::Foam => "",
        }
    }

    /// The format's reader and writer.
    pub fn handler(self) -> &'static dyn MeshFormat {
        match self {
            Format::Msh => &gmsh::Msh,
            Format::Su2 => &su2::Su2,
            Format::Vtu => &vtu::Vtu,
            Format::Cgns => &cgns::Cgns,
            Format::Foam => &foam::Foam,
        }
    }

    /// The format named by a path's extension; a directory or a path
    /// without an extension is an OpenFOAM case ([`foam::is_case`]).
    pub fn from_path(path: &Path) -> Result<Format> {
        if foam::is_case(path) {
            return Ok(Format::Foam);
        }
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        [Format::Msh, Format::Su2, Format::Vtu, Format::Cgns]
            .into_iter()
            .find(|f| ext.as_deref() == Some(f.extension()))
            .ok_or_else(|| Error::UnknownFormat {
                path: path.to_path_buf(),
            })
    }
}

/// Reads a mesh, choosing the format by extension; of a multi-zone SU2
/// file, zone 1 ([`read_zone`] reads another).
pub fn read(path: &Path) -> Result<Mesh> {
    read_zone(path, 1).map(|(mesh, _)| mesh)
}

/// Reads zone `zone` (1-based, SU2's `IZONE=`) of a mesh file and gives its
/// number of zones ([`MeshFormat::read_zone`]). The other zones of an SU2
/// file are kept for an SU2 output ([`su2::parse_zone`]).
pub fn read_zone(path: &Path, zone: usize) -> Result<(Mesh, usize)> {
    Format::from_path(path)?.handler().read_zone(path, zone)
}

/// Reads every zone of a mesh file, in order: one mesh for every file but a
/// multi-zone SU2 file.
pub fn read_zones(path: &Path) -> Result<Vec<Mesh>> {
    Format::from_path(path)?.handler().read_zones(path)
}

/// Writes a mesh, choosing the format by extension (atomically, see
/// [`write_atomic`](super::write_atomic); a CGNS mesh read from a CGNS file
/// is a copy of that file with new coordinates, see [`cgns::write`]).
pub fn write(path: &Path, mesh: &Mesh, options: &WriteOptions) -> Result<()> {
    write_moved(path, mesh, &mesh.coords, options)
}

/// [`write()`] with the nodes at `coords` (`dim` numbers per node) instead of
/// the mesh's own: a moved mesh written without a copy of its cells.
pub fn write_moved(path: &Path, mesh: &Mesh, coords: &[f64], options: &WriteOptions) -> Result<()> {
    if coords.len() != mesh.coords.len() {
        return Err(Error::InvalidSetting(format!(
            "{} coordinates for the {} nodes of a {}D mesh",
            coords.len(),
            mesh.node_count(),
            mesh.dim
        )));
    }
    let format = Format::from_path(path)?.handler();
    if !format.stores_general_cells(mesh) {
        if let Some(what) = general_cell(mesh) {
            return Err(Error::Unrepresentable {
                path: path.to_path_buf(),
                format: format.name(),
                what,
            });
        }
    }
    format.write_moved(path, mesh, coords, options)
}

/// The first polygon or polyhedron of `mesh`, among its cells or its
/// groups' facets, named for a message (`element 17, a polyhedron`).
fn general_cell(mesh: &Mesh) -> Option<String> {
    if let Some(c) = mesh.cells.first_general() {
        return Some(format!(
            "element {}, a {}",
            mesh.cell_tags[c],
            mesh.cells.kinds[c].name()
        ));
    }
    mesh.groups.iter().find_map(|g| {
        g.facets.first_general().map(|f| {
            format!(
                "facet {f} of group '{}', a {} of {} nodes",
                g.name,
                g.facets.kinds[f].name(),
                g.facets.cell(f).len()
            )
        })
    })
}
