//! A one-cell-thick 2D case (patches of type `empty` on its front and
//! back) read as the 2D mesh of its back plane: the points on the plane of
//! smallest z are the 2D nodes, each point of the other plane follows the
//! node its extrusion edge joins it to, each prism, hexahedron or
//! polygonal prism becomes its triangle, quadrilateral or polygon (its back
//! face reversed: counter-clockwise when the cell is valid, clockwise when
//! the case holds it inverted, whose orientation comes from the faces'
//! convention, never from the shape), and each face of the other patches
//! becomes the line of its two back points.
//!
//! A wedge case is read the same way from the local coordinates of its
//! points ([`super::wedge`]): its axis points are on both planes, each its
//! own front point, so edges from them are not edges between the planes,
//! and a face of another patch at the axis is a triangle.

use super::read::PolyMesh;
use super::{Across, Plane};
use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells, Group};

/// The 2D mesh of a 2D case.
pub(super) struct Flat {
    /// `x y` of each 2D node.
    pub coords: Vec<f64>,
    /// The foam point label of each 2D node.
    pub points: Vec<usize>,
    /// Triangles, quadrilaterals and polygons, one per cell.
    pub cells: Cells,
    /// The patches that are not `empty`, as lines.
    pub groups: Vec<Group>,
    /// How the case's points follow the 2D nodes.
    pub plane: Plane,
}

/// Which plane a point lies on: `Some(true)` the back (smallest z),
/// `Some(false)` the front, `None` neither (farther than 1e-9 of the
/// planes' z scale from both).
fn sides(mesh: &PolyMesh) -> Vec<Option<bool>> {
    let z = |p: usize| mesh.points[3 * p + 2];
    let n = mesh.points.len() / 3;
    let (lo, hi) = (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(z(p)), hi.max(z(p)))
    });
    // Relative to the planes' own z (their distance, and their distance
    // from 0): an x or y however large never merges the two planes.
    let tol = 1e-9 * (hi - lo).max(lo.abs()).max(hi.abs());
    (0..n)
        .map(|p| {
            if (z(p) - lo).abs() <= tol {
                Some(true)
            } else if (z(p) - hi).abs() <= tol {
                Some(false)
            } else {
                None
            }
        })
        .collect()
}

/// 1e-9 of the largest extent of the points in x or y: how far an edge
/// between the planes may stray from z.
fn along_z(mesh: &PolyMesh) -> f64 {
    let n = mesh.points.len() / 3;
    let extent = (0..2)
        .map(|d| {
            let (a, b) = (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(mesh.points[3 * p + d]), b.max(mesh.points[3 * p + d]))
            });
            b - a
        })
        .fold(0.0, f64::max);
    1e-9 * extent
}

/// The 2D mesh of `mesh`, whose 3D cells are `cells`; the points
/// `on_axis` (of a wedge case; none when empty) are on both planes.
pub(super) fn flatten(mesh: &PolyMesh, cells: &Cells, on_axis: &[bool]) -> Result<Flat> {
    let axis = |p: usize| on_axis.get(p).copied().unwrap_or(false);
    let err = |file: &str, line: usize, message: String| Error::Parse {
        path: mesh.file(file),
        line,
        message,
    };
    let (side, tol) = (sides(mesh), along_z(mesh));
    let n_points = side.len();
    if let Some(p) = side.iter().position(Option::is_none) {
        return Err(err(
            "points",
            mesh.point_lines[p] as usize,
            format!(
                "point {p} lies on neither plane of the 2D case (its empty patches must lie \
                 on two planes of constant z: verbss reads 2D cases in the x-y plane)"
            ),
        ));
    }
    let back = |p: usize| side[p] == Some(true);
    // The back point each front point is extruded from.
    let mut below = vec![usize::MAX; n_points];
    let mut flat_cells = Cells::new();
    let mut line_of_cell = vec![1; cells.len()];
    for f in (0..mesh.owner.len()).rev() {
        line_of_cell[mesh.owner[f]] = mesh.owner_lines[f];
    }
    for (c, (kind, nodes)) in cells.iter().enumerate() {
        let line = line_of_cell[c];
        let refuse = |why: &str| {
            err(
                "owner",
                line as usize,
                format!("cell {c} ({}) {why}", kind.name()),
            )
        };
        if !matches!(
            kind,
            CellKind::Wedge | CellKind::Hexahedron | CellKind::Polyhedron
        ) {
            return Err(refuse(
                "in a 2D case (expected prisms, hexahedra and polygonal prisms one cell thick)",
            ));
        }
        let local = cells.local(c);
        let mut bad_edge: Option<(usize, usize)> = None;
        local.edges(|a, b| {
            let (a, b) = (nodes[a], nodes[b]);
            if axis(a) || axis(b) {
                return;
            }
            let (lower, upper) = match (back(a), back(b)) {
                (true, false) => (a, b),
                (false, true) => (b, a),
                _ => return,
            };
            let moved = (0..2)
                .any(|d| (mesh.points[3 * lower + d] - mesh.points[3 * upper + d]).abs() > tol);
            if moved || (below[upper] != usize::MAX && below[upper] != lower) {
                bad_edge.get_or_insert((lower, upper));
            }
            below[upper] = lower;
        });
        if let Some((lower, upper)) = bad_edge {
            let at = |p: usize| crate::error::format_point(&mesh.points[3 * p..3 * p + 3]);
            return Err(refuse(&format!(
                "has an edge between the planes that is not along z: point {lower} at {} to \
                 point {upper} at {}",
                at(lower),
                at(upper)
            )));
        }
        let mut corners: Vec<usize> = Vec::new();
        local.facets(|f| {
            // The largest: at the axis a side face may have all its
            // points on the back plane too.
            if f.len() > corners.len() && f.iter().all(|&l| back(nodes[l])) {
                corners.clear();
                corners.extend(f.iter().map(|&l| nodes[l]));
            }
        });
        if corners.is_empty() {
            return Err(refuse("has no face on the back plane"));
        }
        // The back face points out of the cell (towards −z): reversed, it
        // runs counter-clockwise seen from +z when the cell is valid.
        corners.reverse();
        flat_cells.push(CellKind::facet_kind(corners.len()), &corners);
    }
    // 2D nodes: the back points, in label order.
    let points: Vec<usize> = (0..n_points).filter(|&p| back(p)).collect();
    let mut node_of_point = vec![usize::MAX; n_points];
    for (i, &p) in points.iter().enumerate() {
        node_of_point[p] = i;
    }
    for p in 0..n_points {
        if !back(p) {
            if below[p] == usize::MAX {
                return Err(err(
                    "points",
                    mesh.point_lines[p] as usize,
                    format!("point {p} of the front plane is on no edge from the back plane"),
                ));
            }
            node_of_point[p] = node_of_point[below[p]];
        }
    }
    for k in &mut flat_cells.nodes {
        *k = node_of_point[*k];
    }
    let groups = lines(mesh, &side, &node_of_point, &axis)?;
    Ok(Flat {
        coords: points
            .iter()
            .flat_map(|&p| [mesh.points[3 * p], mesh.points[3 * p + 1]])
            .collect(),
        points,
        cells: flat_cells,
        groups,
        plane: Plane {
            node_of_point,
            across: Across::Z((0..n_points).map(|p| mesh.points[3 * p + 2]).collect()),
        },
    })
}

/// The patches that are not `empty` (nor `wedge`), each face as the line
/// of its two back points (a triangle at the axis: its axis point and its
/// back point); every face of an `empty` or `wedge` patch must lie in one
/// plane (but for its axis points).
fn lines(
    mesh: &PolyMesh,
    side: &[Option<bool>],
    node_of_point: &[usize],
    axis: &dyn Fn(usize) -> bool,
) -> Result<Vec<Group>> {
    let mut groups = Vec::new();
    for patch in &mesh.patches {
        let faces = patch.start_face..patch.start_face + patch.n_faces;
        let empty = matches!(patch.kind.as_str(), "empty" | "wedge");
        let mut facets = Cells::new();
        for f in faces {
            let face = mesh.face(f);
            let on_back: Vec<usize> = face
                .iter()
                .copied()
                .filter(|&p| side[p] == Some(true))
                .collect();
            let at_axis = face.iter().filter(|&&p| axis(p)).count();
            let ok = if empty {
                on_back.len() == at_axis || on_back.len() == face.len()
            } else {
                (face.len() == 4 || face.len() == 3 && at_axis == 1) && on_back.len() == 2
            };
            if !ok {
                return Err(Error::Parse {
                    path: mesh.file("boundary"),
                    line: patch.line,
                    message: format!(
                        "face {f} of patch '{}' ({}) {}",
                        patch.name,
                        patch.kind,
                        if empty {
                            "is not in the front or back plane of the 2D case"
                        } else {
                            "does not join two back points to two front points"
                        }
                    ),
                });
            }
            if !empty {
                facets.push(
                    CellKind::Line,
                    &[node_of_point[on_back[0]], node_of_point[on_back[1]]],
                );
            }
        }
        if !empty {
            groups.push(Group {
                name: patch.name.clone(),
                tag: None,
                facets,
            });
        }
    }
    Ok(groups)
}
