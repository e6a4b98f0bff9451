//! Writing CGNS files: a copy of the file a mesh was read from with its
//! coordinates replaced, or a fresh file (see [`super::write`]).

use std::ffi::c_int;
use std::path::Path;

use super::ffi::{self, to_size, CgSize, File, Mode};
use super::zone::KINDS;
use super::{error, Source};
use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells, Mesh};

/// The coordinate arrays, in axis order.
const AXES: [&str; 3] = ["CoordinateX", "CoordinateY", "CoordinateZ"];

/// Writes `mesh` to a temporary file beside `path` and renames it over
/// `path` (its final target when a link) once complete.
pub fn write(path: &Path, mesh: &Mesh, coords: &[f64]) -> Result<()> {
    let target = crate::io::link_target(path);
    let tmp = crate::io::temp_path(&target);
    let written = match &mesh.origin.cgns {
        Some(source) => copy_with_coordinates(source, &tmp, mesh, coords),
        None => fresh(&tmp, mesh, coords),
    }
    .map_err(|m| error(path, m))
    .and_then(|()| {
        std::fs::rename(&tmp, &target).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    });
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// Copies the source file to `tmp` and overwrites the values of its
/// coordinate arrays with the mesh's, each in the array's own precision.
fn copy_with_coordinates(
    source: &Source,
    tmp: &Path,
    mesh: &Mesh,
    coords: &[f64],
) -> std::result::Result<(), String> {
    let from = source.path.display();
    std::fs::copy(&source.path, tmp).map_err(|e| format!("cannot copy {from}: {e}"))?;
    let file =
        File::open(tmp, Mode::Modify).map_err(|m| format!("cannot open a copy of {from}: {m}"))?;
    let (base, _, _) = file.base(1)?;
    let (zone, vertices, _) = file.zone(1, 1)?;
    if (base.as_str(), zone.as_str()) != (source.base.as_str(), source.zone.as_str()) {
        return Err(format!(
            "{from} changed since it was read: its zone 1 is now '{zone}' of base '{base}'"
        ));
    }
    let n = mesh.node_count();
    if usize::try_from(vertices) != Ok(n) {
        return Err(format!(
            "zone '{zone}' of {from} has {vertices} vertices and the mesh {n}: it is not the mesh read from it"
        ));
    }
    let present = file.coordinates(1, 1)?;
    for (axis, name) in AXES[..mesh.dim].iter().enumerate() {
        let kind = present
            .iter()
            .find(|(p, _)| p == name)
            .map(|p| p.1)
            .ok_or_else(|| format!("{from} no longer has {name}"))?;
        if kind != ffi::REAL_SINGLE && kind != ffi::REAL_DOUBLE {
            return Err(format!(
                "{name} of {from} has data type {kind}, not RealSingle or RealDouble"
            ));
        }
        let values: Vec<f64> = (0..n).map(|i| coords[i * mesh.dim + axis]).collect();
        file.overwrite_coordinate(1, 1, name, kind, &values)?;
    }
    file.close()
}

/// Writes `mesh` as a fresh file: base `Base`, zone `Zone`, the cells, then
/// each group as a section with its boundary condition and family.
fn fresh(tmp: &Path, mesh: &Mesh, coords: &[f64]) -> std::result::Result<(), String> {
    for g in &mesh.groups {
        if g.name.is_empty() || g.name.len() > 32 || g.name.contains('/') {
            return Err(format!(
                "the group name '{}' is no CGNS name (1 to 32 characters, no '/')",
                g.name
            ));
        }
        if g.facets.is_empty() {
            return Err(format!(
                "the group '{}' is empty: a CGNS boundary condition needs at least one point",
                g.name
            ));
        }
    }
    let file = File::open(tmp, Mode::Write)?;
    let dim = mesh.dim as c_int;
    let b = file.write_base("Base", dim, dim)?;
    let n = mesh.node_count();
    let size = [to_size(n)?, to_size(mesh.cell_count())?, 0];
    let z = file.write_zone(b, "Zone", ffi::UNSTRUCTURED, &size)?;
    for (axis, name) in AXES[..mesh.dim].iter().enumerate() {
        let values: Vec<f64> = (0..n).map(|i| coords[i * mesh.dim + axis]).collect();
        file.write_coordinate(b, z, name, &values)?;
    }
    let taken = |name: &str| mesh.groups.iter().any(|g| g.name == name);
    let cells_name = std::iter::once("Elements".to_string())
        .chain((1..).map(|k| format!("Elements_{k}")))
        .find(|name| !taken(name))
        .unwrap_or_default();
    let mut next: CgSize = 1;
    write_cells(&file, (b, z), &cells_name, &mesh.cells, &mut next)?;
    let location = if mesh.dim == 3 {
        ffi::FACE_CENTER
    } else {
        ffi::EDGE_CENTER
    };
    for g in &mesh.groups {
        file.write_family(b, &g.name)?;
        let vertices = g
            .facets
            .kinds
            .iter()
            .filter(|&&k| k == CellKind::Vertex)
            .count();
        if vertices == g.facets.len() {
            let points = g
                .facets
                .nodes
                .iter()
                .map(|&v| to_size(v + 1))
                .collect::<std::result::Result<Vec<_>, _>>()?;
            file.write_boco(
                ("Base", "Zone"),
                (b, z),
                (&g.name, &g.name),
                ffi::POINT_LIST,
                &points,
                ffi::VERTEX,
            )?;
        } else if vertices > 0 {
            return Err(format!(
                "the group '{}' mixes single nodes and facets: a CGNS boundary condition holds one or the other",
                g.name
            ));
        } else {
            let range = write_cells(&file, (b, z), &g.name, &g.facets, &mut next)?;
            file.write_boco(
                ("Base", "Zone"),
                (b, z),
                (&g.name, &g.name),
                ffi::POINT_RANGE,
                &range,
                location,
            )?;
        }
    }
    file.close()
}

/// Writes `cells` as the section `name` numbered from `next` (one element
/// type, else MIXED); returns its first and last element numbers and moves
/// `next` past them.
fn write_cells(
    file: &File,
    (b, z): (c_int, c_int),
    name: &str,
    cells: &Cells,
    next: &mut CgSize,
) -> std::result::Result<[CgSize; 2], String> {
    let code = |kind: CellKind| {
        KINDS
            .iter()
            .find(|k| k.1 == kind)
            .map(|k| CgSize::from(k.0 as i16))
            .ok_or_else(|| format!("CGNS has no linear element for {} cells", kind.name()))
    };
    if cells.is_empty() {
        return Err(format!("the section '{name}' would have no elements"));
    }
    let first = *next;
    let last = first + to_size(cells.len())? - 1;
    let one_kind = cells.kinds.windows(2).all(|w| w[0] == w[1]);
    let mut nodes = Vec::with_capacity(cells.nodes.len() + cells.len());
    let mut offsets = vec![0];
    for (kind, cell) in cells.iter() {
        if !one_kind {
            nodes.push(code(kind)?);
        }
        for &v in cell {
            nodes.push(to_size(v + 1)?);
        }
        offsets.push(to_size(nodes.len())?);
    }
    let kind = if one_kind {
        code(cells.kinds[0])? as c_int
    } else {
        ffi::MIXED
    };
    file.write_section(b, z, name, kind, (first, last), &nodes, &offsets)?;
    *next = last + 1;
    Ok([first, last])
}
