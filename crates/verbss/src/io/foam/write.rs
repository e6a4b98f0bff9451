//! Writing the moved points of a mesh read from an OpenFOAM case.

use std::path::Path;

use super::{case_dir, same_polymesh, Across, Origin, FILES};
use crate::error::{Error, Result};
use crate::io::outputs::resolved;
use crate::io::write_replacing;
use crate::mesh::Mesh;

/// Writes the points of `mesh` (read from an OpenFOAM case) to the case or
/// polyMesh directory `path`:
///
/// - `path` is the polyMesh the mesh was read from and `time` is given:
///   `CASE/TIME/polyMesh/points`, where CASE is the directory above
///   `constant` (or the polyMesh directory's parent);
/// - `path` is that polyMesh and no `time`: its `points` are replaced;
/// - any other `path`: `path/constant/polyMesh` (or `path` itself when it
///   is named `polyMesh`) gets the points and a copy of the other four files.
///
/// A 2D mesh's nodes carry their front and back points (see [`super::Plane`]).
pub fn write(path: &Path, mesh: &Mesh, time: Option<&str>) -> Result<()> {
    write_moved(path, mesh, &mesh.coords, time)
}

/// [`write()`] with the nodes at `coords` (`dim` numbers per node) instead of
/// the mesh's own.
pub fn write_moved(path: &Path, mesh: &Mesh, coords: &[f64], time: Option<&str>) -> Result<()> {
    let refuse = |message: String| Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, message),
    };
    let Some(origin) = mesh.origin.foam.as_deref() else {
        return Err(refuse(
            "an OpenFOAM case is written only from a mesh read from one (verbss writes its \
             moved points and keeps its faces; give a .msh, .su2 or .vtu output instead)"
                .into(),
        ));
    };
    let fits = match &origin.plane {
        None => mesh.dim == 3 && mesh.node_count() == origin.n_points,
        Some(plane) => mesh.dim == 2 && plane.node_of_point.iter().all(|&i| i < mesh.node_count()),
    };
    if !fits {
        return Err(refuse(format!(
            "the mesh's {} {}D nodes do not match the {} points of {}",
            mesh.node_count(),
            mesh.dim,
            origin.n_points,
            origin.dir.display()
        )));
    }
    let xyz = points(mesh, coords, origin).map_err(|(p, i, dr)| {
        refuse(format!(
            "point {p} of the wedge case's axis (node {}) was moved {dr:e} off the axis (its \
             points must stay on it: keep them fixed, or move them along it with --slide)",
            mesh.node_tags[i]
        ))
    })?;
    if same_polymesh(path, &origin.dir) {
        return match time {
            Some(t) => write_time(&case_dir(&origin.dir).join(t), origin, &xyz, t),
            None => write_points(&origin.dir, &xyz, "constant"),
        };
    }
    let target = if path.ends_with("polyMesh") {
        path.to_path_buf()
    } else {
        path.join("constant").join("polyMesh")
    };
    write_points(&target, &xyz, "constant")?;
    for name in &FILES[1..] {
        let from = origin.dir.join(name);
        let bytes = std::fs::read(&from).map_err(|source| Error::Io { path: from, source })?;
        write_replacing(&target.join(name), |w| w.write_all(&bytes))?;
    }
    Ok(())
}

/// `x y z` of every point of the case at `coords`: the coordinates, or
/// for a 2D case each point at its node's `x y` and its own `z`, for a
/// wedge case moved in its plane as its node moved ([`super::Wedge`]);
/// else the axis point that left the axis, its node and how far it went.
fn points(
    mesh: &Mesh,
    coords: &[f64],
    origin: &Origin,
) -> std::result::Result<Vec<f64>, (usize, usize, f64)> {
    let Some(plane) = &origin.plane else {
        return Ok(coords.to_vec());
    };
    let dim = mesh.dim;
    let node = |i: usize| [coords[dim * i], coords[dim * i + 1]];
    match &plane.across {
        Across::Z(z) => Ok(plane
            .node_of_point
            .iter()
            .zip(z)
            .flat_map(|(&i, &z)| [coords[dim * i], coords[dim * i + 1], z])
            .collect()),
        Across::Wedge(wedge) => {
            let mut xyz = Vec::with_capacity(3 * plane.node_of_point.len());
            for (p, &i) in plane.node_of_point.iter().enumerate() {
                let [a, r] = node(i);
                let (da, dr) = (a - mesh.coords[dim * i], r - mesh.coords[dim * i + 1]);
                match wedge.place(p, da, dr) {
                    Some(x) => xyz.extend(x),
                    None => return Err((p, i, dr)),
                }
            }
            Ok(xyz)
        }
    }
}

/// Writes the time directory `time_dir` (`CASE/TIME`) of the case of
/// `origin`: a new `polyMesh` holding `points` replaces the one there, if
/// any, whole (a link in its place is replaced, never followed), unless it
/// is the polyMesh the mesh was read from.
fn write_time(time_dir: &Path, origin: &Origin, xyz: &[f64], time: &str) -> Result<()> {
    let target = time_dir.join("polyMesh");
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| Error::Io { path, source }
    };
    if origin
        .dir
        .canonicalize()
        .is_ok_and(|d| d == resolved(&target, true))
    {
        return Err(Error::Io {
            path: target.clone(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "the time directory's polyMesh is the input polyMesh {} (through a link): \
                     verbss never writes into it",
                    origin.dir.display()
                ),
            ),
        });
    }
    let fresh = crate::io::temp_path(&target);
    if fresh.exists() {
        std::fs::remove_dir_all(&fresh).map_err(io(&fresh))?;
    }
    write_points(&fresh, xyz, time)?;
    match std::fs::symlink_metadata(&target) {
        Ok(m) if m.is_dir() => std::fs::remove_dir_all(&target).map_err(io(&target))?,
        Ok(_) => std::fs::remove_file(&target).map_err(io(&target))?,
        Err(_) => {}
    }
    std::fs::rename(&fresh, &target).map_err(io(&target))
}

/// Writes `dir/points` (creating `dir`), its header's location
/// `TIME/polyMesh`; a link at `dir/points` is replaced, never followed.
fn write_points(dir: &Path, xyz: &[f64], time: &str) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    write_replacing(&dir.join("points"), |w| {
        writeln!(
            w,
            "FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    \
             class       vectorField;\n    location    \"{time}/polyMesh\";\n    \
             object      points;\n}}\n\n{}\n(",
            xyz.len() / 3
        )?;
        for p in xyz.chunks(3) {
            writeln!(w, "({:?} {:?} {:?})", p[0], p[1], p[2])?;
        }
        writeln!(w, ")")
    })
}
