//! OpenFOAM meshes: the `constant/polyMesh` of a case (ASCII).
//!
//! A polyMesh is five files: `points` (a list of `(x y z)`), `faces` (a list
//! of `k(p0 … pk-1)`, point labels from 0), `owner` and `neighbour` (the
//! cell on each side of each face; only the first `nInternalFaces` faces have
//! a neighbour, and a face's normal, by the right-hand rule, points from its
//! owner to its neighbour) and `boundary` (the patches: `name { type T;
//! nFaces N; startFace S; }`, each a run of the boundary faces):
//!
//! ```text
//! FoamFile { version 2.0; format ascii; class vectorField; object points; }
//! 8 ( (0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1) )
//! ```
//!
//! The reader takes the `FoamFile` header, `//` and `/* */` comments, lists
//! with or without their count, `N{item}` lists of one repeated item (where
//! the mesh bounds N), and `faceCompactList` faces. Binary (`format
//! binary;`) and compressed (`.gz`) files are refused with a message.
//!
//! Each cell is a tetrahedron, pyramid, prism or hexahedron when its faces
//! make one ([`cells`](self) recognises them), else a polyhedron of its
//! faces; its orientation is the faces' convention (a cell the case holds
//! inverted reads as inverted). Each patch becomes a group of its faces
//! (triangles, quadrilaterals and polygons). A case with patches of
//! type `empty` is a 2D case: it is read as the 2D mesh of its back plane
//! (see [`Plane`]), and its `empty` patches are not groups. A case with two
//! patches of type `wedge` is an axisymmetric one: read as the 2D mesh of
//! its (axial, radial) plane ([`Wedge`]), its `wedge` patches not groups,
//! the sides on its axis the group `axis`. Coupled patches (`cyclicAMI`,
//! `cyclicACMI`, `cyclic`, `mapped*`) are the mesh's interfaces
//! ([`crate::mesh::Interface`]).
//!
//! Writing ([`write()`]) needs a mesh read from a case, whose faces, owners,
//! neighbours and patches it keeps: only the points change. Into the case
//! it was read from it writes `CASE/TIME/polyMesh/points` (the time
//! directory an OpenFOAM solver reads a moved mesh from), leaving
//! `constant/polyMesh` as it was; into any other directory, a whole
//! `constant/polyMesh` (the moved points and a copy of the other four files).

mod cells;
mod file;
mod interfaces;
mod lex;
mod plane;
mod read;
mod times;
mod wedge;
mod write;

pub use times::{time_name, TimeFormat, Times};
pub use wedge::Wedge;
pub use write::{write, write_moved};

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells, FileOrigin, Group, Mesh};

/// The files of a polyMesh: the points, then the four that a moved mesh
/// keeps.
pub const FILES: [&str; 5] = ["points", "faces", "owner", "neighbour", "boundary"];

/// Where a mesh read from an OpenFOAM case came from, for writing its
/// points back.
#[derive(Debug, Clone, PartialEq)]
pub struct Origin {
    /// The `polyMesh` directory it was read from.
    pub dir: PathBuf,
    /// The number of points of the polyMesh.
    pub n_points: usize,
    /// For a 2D case, how its points follow the 2D nodes.
    pub plane: Option<Plane>,
}

/// How the points of a 2D case follow the nodes of its 2D mesh: point `p`
/// follows node `node_of_point[p]`, off the plane as `across` says.
#[derive(Debug, Clone, PartialEq)]
pub struct Plane {
    /// The 2D node of each point.
    pub node_of_point: Vec<usize>,
    /// Where each point is off the 2D plane.
    pub across: Across,
}

/// Where the points of a 2D case are off its plane.
#[derive(Debug, Clone, PartialEq)]
pub enum Across {
    /// An `empty` case: each point at its node's `(x, y)` and its own z.
    Z(Vec<f64>),
    /// A wedge case: its node's `(a, r)` on its wedge plane.
    Wedge(Box<Wedge>),
}

/// Whether `path` names an OpenFOAM case: an existing directory, or a path
/// without an extension (a case to be made).
pub fn is_case(path: &Path) -> bool {
    path.is_dir() || path.extension().is_none()
}

/// The `polyMesh` directory of `path`: `path/constant/polyMesh` for a case,
/// `path` itself when it holds a `faces` file or is named `polyMesh`.
pub fn polymesh_dir(path: &Path) -> PathBuf {
    let in_case = path.join("constant").join("polyMesh");
    if !in_case.is_dir() && (path.join("faces").is_file() || path.ends_with("polyMesh")) {
        path.to_path_buf()
    } else {
        in_case
    }
}

/// The case directory of a polyMesh directory: two levels up from
/// `CASE/constant/polyMesh`, else its parent.
pub fn case_dir(polymesh: &Path) -> PathBuf {
    let parent = polymesh.parent().unwrap_or(Path::new("."));
    match parent.file_name() {
        Some(n) if n == "constant" => parent.parent().unwrap_or(Path::new(".")).to_path_buf(),
        _ => parent.to_path_buf(),
    }
}

/// Whether `a` and `b` name the same polyMesh directory (both existing).
pub fn same_polymesh(a: &Path, b: &Path) -> bool {
    match (
        polymesh_dir(a).canonicalize(),
        polymesh_dir(b).canonicalize(),
    ) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// Reads the polyMesh of the case or polyMesh directory `path`.
///
/// Every list is checked against the others, with the file and line of a
/// failure: point labels below the number of points, cell labels below the
/// number of faces, one owner per face, patches on the boundary faces, and
/// each cell closed by its faces.
pub fn read(path: &Path) -> Result<Mesh> {
    let dir = polymesh_dir(path);
    if !dir.is_dir() {
        return Err(Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::NotFound,
                "not an OpenFOAM case (no constant/polyMesh directory) nor a polyMesh directory",
            ),
        });
    }
    let mut poly = read::read(&dir)?;
    let interfaces = interfaces::interfaces(&poly)?;
    let cells = cells::cells(&poly)?;
    let n_points = poly.points.len() / 3;
    let has_empty = poly
        .patches
        .iter()
        .any(|p| p.kind == "empty" && p.n_faces > 0);
    let flat = match wedge::wedge(&poly)? {
        Some((wedge, local)) => {
            // Read as a 2D case in the wedge's (axial, radial) coordinates.
            let points = std::mem::replace(&mut poly.points, local);
            let flat = plane::flatten(&poly, &cells, &wedge.on_axis);
            poly.points = points;
            let mut flat = flat?;
            flat.groups.extend(wedge::axis_group(
                &poly,
                &flat.cells,
                &flat.points,
                &wedge.on_axis,
            ));
            flat.plane.across = Across::Wedge(Box::new(wedge));
            Some(flat)
        }
        None if has_empty => Some(plane::flatten(&poly, &cells, &[])?),
        None => None,
    };
    let (dim, coords, node_tags, cells, groups, plane) = match flat {
        Some(flat) => {
            let tags = flat.points.iter().map(|&p| p as u64 + 1).collect();
            (
                2,
                flat.coords,
                tags,
                flat.cells,
                flat.groups,
                Some(flat.plane),
            )
        }
        None => {
            let groups = patches(&poly);
            let tags = (1..=n_points as u64).collect();
            (3, poly.points, tags, cells, groups, None)
        }
    };
    let mesh = Mesh {
        dim,
        node_tags,
        cell_tags: (1..=cells.len() as u64).collect(),
        coords,
        cells,
        groups,
        origin: FileOrigin {
            foam: Some(Box::new(Origin {
                dir: dir.clone(),
                n_points,
                plane,
            })),
            oriented: true,
            interfaces,
            ..FileOrigin::default()
        },
    };
    mesh.validate().map_err(|e| {
        crate::io::invalid_at(e, |message| Error::Parse {
            path: dir.join("owner"),
            line: 1,
            message,
        })
    })?;
    Ok(mesh)
}

/// Each patch as a group of its faces.
fn patches(poly: &read::PolyMesh) -> Vec<Group> {
    poly.patches
        .iter()
        .map(|p| {
            let mut facets = Cells::new();
            for f in p.start_face..p.start_face + p.n_faces {
                let face = poly.face(f);
                facets.push(CellKind::facet_kind(face.len()), face);
            }
            Group {
                name: p.name.clone(),
                tag: None,
                facets,
            }
        })
        .collect()
}

/// An OpenFOAM case's `constant/polyMesh`, ASCII or binary.
pub struct Foam;

impl super::MeshFormat for Foam {
    fn name(&self) -> &'static str {
        "OpenFOAM polyMesh"
    }

    fn read_zone(&self, path: &Path, zone: usize) -> Result<(Mesh, usize)> {
        super::format::one_zone(path, zone, || read(path))
    }

    fn write_moved(
        &self,
        path: &Path,
        mesh: &Mesh,
        coords: &[f64],
        options: &super::WriteOptions,
    ) -> Result<()> {
        write_moved(path, mesh, coords, options.foam_time.as_deref())
    }

    fn stores_general_cells(&self, _: &Mesh) -> bool {
        true
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod hostile_tests;
