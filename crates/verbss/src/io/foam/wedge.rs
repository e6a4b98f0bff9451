//! An axisymmetric case: two patches of type `wedge`, one cell thick
//! about an axis, read as the 2D mesh of its (axial, radial) plane.
//!
//! The two wedge patches are planes through the axis, at an angle θ (a few
//! degrees). With `n_b`, `n_f` their unit normals (from their faces' area
//! vectors), the axis runs along `d = n_b × n_f / |n_b × n_f|` (its largest
//! component positive) through the point `o` of both planes nearest the
//! origin; each plane's radial direction `u` is the unit vector of the
//! plane perpendicular to `d`, towards its faces. The back plane is the one
//! from which `d × u_back` turns towards the front one. A point `p` is at
//! axial `a = (p − o)·d` and radial `r = |p − o − a d|`, on the back plane,
//! the front one, or the axis (`r = 0`, both planes' point). The 2D node of
//! a back point is `(a, r)`, and the 2D mesh is read from the back plane as
//! a 2D `empty` case is ([`super::plane`]), each front point following the
//! back point its edge around the axis joins, each axis point its own.
//!
//! Written back, a point whose node moved by `(Δa, Δr)` moves by
//! `Δa d + Δr u` with the `u` of its plane: it stays in its plane, and both
//! planes stay as planar as the case made them (an unmoved point keeps its
//! coordinates). When the case has points on the axis, they place it: `d`
//! runs from the first to the last of them along it, through their mean.
//! An axis point must stay on the axis (`Δr = 0`): the sides of the 2D cells on it make the group `axis`
//! (named after the case's `empty` patch of no faces when it has one, as
//! blockMesh leaves a collapsed axis), which `--slide axis` moves along it.

use super::read::PolyMesh;
use crate::error::{format_point, Error, Result};
use crate::geometry::{cross, dot, norm, point, sub};
use crate::mesh::{CellKind, Cells, Group};

/// How the points of a wedge case lie about its axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Wedge {
    /// The point of the axis nearest the origin.
    pub origin: [f64; 3],
    /// The unit direction of the axis.
    pub axis: [f64; 3],
    /// The radial unit direction of the back plane and of the front one.
    pub radial: [[f64; 3]; 2],
    /// Which plane each point is on: 0 the back (or the axis), 1 the front.
    pub side: Vec<u8>,
    /// Each point on the axis.
    pub on_axis: Vec<bool>,
    /// The points as read, `x y z` each.
    pub points: Vec<f64>,
    /// How near the axis a moved axis point may be (1e-9 of the mesh's
    /// extent): it is put on the axis.
    pub axis_tolerance: f64,
}

impl Wedge {
    /// Where point `p` goes when its node moved by `(da, dr)`: by `da`
    /// along the axis and `dr` along its plane's radial direction; `None`
    /// for an axis point moved off the axis.
    pub fn place(&self, p: usize, da: f64, dr: f64) -> Option<[f64; 3]> {
        let dr = match self.on_axis[p] {
            true if dr.abs() > self.axis_tolerance => return None,
            true => 0.0,
            false => dr,
        };
        let u = &self.radial[self.side[p] as usize];
        let x = point::<3>(&self.points, p);
        Some(std::array::from_fn(|k| {
            x[k] + da * self.axis[k] + dr * u[k]
        }))
    }
}

/// Where `x` is from the axis through `o` along `d`: its distance along it
/// and its offset from it.
fn from_axis(x: &[f64; 3], o: &[f64; 3], d: &[f64; 3]) -> (f64, [f64; 3]) {
    let q = sub(x, o);
    let a = dot(&q, d);
    (a, std::array::from_fn(|k| q[k] - a * d[k]))
}

/// A patch's plane: its unit normal, its area-weighted centre and its area.
fn plane(mesh: &PolyMesh, start: usize, n_faces: usize) -> ([f64; 3], [f64; 3], f64) {
    let (mut area, mut centre, mut total) = ([0.0; 3], [0.0; 3], 0.0);
    for f in start..start + n_faces {
        let face = mesh.face(f);
        let at = |i: usize| point::<3>(&mesh.points, face[i % face.len()]);
        let mut n = [0.0; 3];
        let mut mean = [0.0; 3];
        for i in 0..face.len() {
            let c = cross(&at(i), &at(i + 1));
            (0..3).for_each(|k| {
                n[k] += 0.5 * c[k];
                mean[k] += at(i)[k] / face.len() as f64;
            });
        }
        let w = norm(&n);
        (0..3).for_each(|k| {
            area[k] += n[k];
            centre[k] += w * mean[k];
        });
        total += w;
    }
    let a = norm(&area);
    (
        area.map(|x| x / a),
        centre.map(|x| x / total.max(f64::MIN_POSITIVE)),
        a,
    )
}

/// The wedge of `mesh` when it has `wedge` patches (`None` when it has
/// none): exactly two, not parallel, every point on one of them or on
/// their axis. Also the local coordinates `a r s` of each point (`s` 0 on
/// the back plane and the axis, 1 on the front), as [`super::plane`]
/// reads a 2D case.
pub(super) fn wedge(mesh: &PolyMesh) -> Result<Option<(Wedge, Vec<f64>)>> {
    let patches: Vec<_> = mesh
        .patches
        .iter()
        .filter(|p| p.kind == "wedge" && p.n_faces > 0)
        .collect();
    if patches.is_empty() {
        return Ok(None);
    }
    let refuse = |line: usize, message: String| Error::Parse {
        path: mesh.file("boundary"),
        line,
        message,
    };
    if patches.len() != 2 {
        return Err(refuse(
            patches[0].line,
            format!(
                "{} patch{} of type wedge (expected two, the planes of an axisymmetric case \
                 one cell thick)",
                patches.len(),
                if patches.len() == 1 { "" } else { "es" }
            ),
        ));
    }
    let [(n0, c0, a0), (n1, c1, a1)] =
        [patches[0], patches[1]].map(|p| plane(mesh, p.start_face, p.n_faces));
    let along = cross(&n0, &n1);
    let sin = norm(&along);
    if sin.is_nan() || sin <= 1e-6 || a0 == 0.0 || a1 == 0.0 {
        return Err(refuse(
            patches[1].line,
            format!(
                "wedge patches '{}' and '{}' are parallel or of no area (expected two planes \
                 through an axis)",
                patches[0].name, patches[1].name
            ),
        ));
    }
    let mut d = along.map(|x| x / norm(&along));
    let big = (0..3).fold(0, |b, k| if d[k].abs() > d[b].abs() { k } else { b });
    if d[big] < 0.0 {
        d = d.map(|x| -x);
    }
    // o: on both planes, d·o = 0 (Cramer's rule; the determinant is
    // (n0 × n1)·d = |n0 × n1| > 0).
    let rhs = [dot(&n0, &c0), dot(&n1, &c1), 0.0];
    let rows = [n0, n1, d];
    let det = dot(&cross(&rows[0], &rows[1]), &rows[2]);
    let col = |j: usize| -> f64 {
        let mut m = rows;
        (0..3).for_each(|i| m[i][j] = rhs[i]);
        dot(&cross(&m[0], &m[1]), &m[2]) / det
    };
    let mut origin = [col(0), col(1), col(2)];
    let n_points = mesh.points.len() / 3;
    let extent = (0..3)
        .map(|k| {
            let (lo, hi) = (0..n_points).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (
                    lo.min(mesh.points[3 * p + k]),
                    hi.max(mesh.points[3 * p + k]),
                )
            });
            hi - lo
        })
        .fold(0.0, f64::max);
    // blockMesh's wedge vertices are given to a few digits: planes and
    // axis hold to 1e-6 of the mesh's extent, not to rounding.
    let (tol, off) = (1e-6 * extent, 1e-5 * extent);
    // The points on the axis place it better than the planes' fit: `o`
    // becomes the mean of their points nearest the origin along it.
    let at = |p: usize| point::<3>(&mesh.points, p);
    let axis_points: Vec<usize> = (0..n_points)
        .filter(|&p| norm(&from_axis(&at(p), &origin, &d).1) <= tol)
        .collect();
    let along = |p: &&usize| from_axis(&at(**p), &origin, &d).0;
    if let (Some(&first), Some(&last)) = (
        axis_points
            .iter()
            .min_by(|p, q| along(p).total_cmp(&along(q))),
        axis_points
            .iter()
            .max_by(|p, q| along(p).total_cmp(&along(q))),
    ) {
        let run = sub(
            &point::<3>(&mesh.points, last),
            &point::<3>(&mesh.points, first),
        );
        if norm(&run) > off {
            d = run.map(|x| x / norm(&run));
        }
    }
    if !axis_points.is_empty() {
        let mut mean = [0.0; 3];
        for &p in &axis_points {
            let x = point::<3>(&mesh.points, p);
            let along = dot(&x, &d);
            (0..3).for_each(|k| mean[k] += (x[k] - along * d[k]) / axis_points.len() as f64);
        }
        origin = mean;
    }
    let radial = |n: &[f64; 3], c: &[f64; 3]| {
        let u = cross(n, &d);
        let u = u.map(|x| x / norm(&u));
        let s = if dot(&sub(c, &origin), &u) < 0.0 {
            -1.0
        } else {
            1.0
        };
        u.map(|x| s * x)
    };
    let (u0, u1) = (radial(&n0, &c0), radial(&n1, &c1));
    // The back plane turns towards the front one by d × u_back.
    let (back, front, names) = if dot(&cross(&d, &u0), &u1) > 0.0 {
        ((n0, u0), (n1, u1), (&patches[0].name, &patches[1].name))
    } else {
        ((n1, u1), (n0, u0), (&patches[1].name, &patches[0].name))
    };
    let mut side = vec![0u8; n_points];
    let mut on_axis = vec![false; n_points];
    let mut local = Vec::with_capacity(3 * n_points);
    // The point farthest off both planes and the axis, when one is: a
    // point far off tilts the planes' fit, and the others with it.
    let mut worst: Option<(usize, f64)> = None;
    for p in 0..n_points {
        let (a, rq) = from_axis(&at(p), &origin, &d);
        let r = norm(&rq);
        if r <= tol {
            on_axis[p] = true;
            local.extend([a, 0.0, 0.0]);
            continue;
        }
        let (to_back, to_front) = (dot(&rq, &back.0).abs(), dot(&rq, &front.0).abs());
        let s = u8::from(to_front < to_back);
        let inward = dot(&rq, if s == 0 { &back.1 } else { &front.1 }) > 0.0;
        let plane_off = if inward { to_back.min(to_front) } else { r };
        if plane_off > off && worst.is_none_or(|(_, w)| plane_off.min(r) > w) {
            worst = Some((p, plane_off.min(r)));
        }
        side[p] = s;
        local.extend([a, r, f64::from(s)]);
    }
    if let Some((p, _)) = worst {
        return Err(Error::Parse {
            path: mesh.file("points"),
            line: mesh.point_lines[p] as usize,
            message: format!(
                "point {p} at {} lies on neither wedge plane ('{}' and '{}', planes through \
                 the axis at {} along {}) nor on the axis (expected a one-cell-thick \
                 axisymmetric case)",
                format_point(&mesh.points[3 * p..3 * p + 3]),
                names.0,
                names.1,
                format_point(&origin),
                format_point(&d)
            ),
        });
    }
    let wedge = Wedge {
        origin,
        axis: d,
        radial: [back.1, front.1],
        side,
        on_axis,
        points: mesh.points.clone(),
        axis_tolerance: 1e-9 * extent,
    };
    Ok(Some((wedge, local)))
}

/// The group of the sides of the 2D `cells` on the axis (both nodes on it;
/// `points` the foam point of each node), named after `mesh`'s `empty`
/// patch of no faces, else `axis`; `None` when a patch already has that
/// name or no side is on the axis.
pub(super) fn axis_group(
    mesh: &PolyMesh,
    cells: &Cells,
    points: &[usize],
    on_axis: &[bool],
) -> Option<Group> {
    let name = mesh
        .patches
        .iter()
        .find(|p| p.kind == "empty" && p.n_faces == 0)
        .map_or("axis", |p| p.name.as_str());
    let taken = mesh
        .patches
        .iter()
        .any(|p| p.name == name && !(p.kind == "empty" && p.n_faces == 0));
    let mut facets = Cells::new();
    for (_, nodes) in cells.iter() {
        for (k, &a) in nodes.iter().enumerate() {
            let b = nodes[(k + 1) % nodes.len()];
            if on_axis[points[a]] && on_axis[points[b]] {
                facets.push(CellKind::Line, &[a, b]);
            }
        }
    }
    (!taken && !facets.is_empty()).then(|| Group {
        name: name.to_string(),
        tag: None,
        facets,
    })
}
