//! Periodic pairs ([`crate::mesh::Coupling::Periodic`]) kept consistent: each
//! node of the first side is paired with its image on the second by the
//! pair's transform. A pair whose two sides are held (the default for a
//! group no motion names) stays consistent; both moving, every step checks
//! that the transform still takes each node onto its partner; any other
//! plan (one side moving or sliding) is refused before the first step.

use std::collections::HashMap;

use super::coincident::bodies_of;
use super::roles::Plan;
use crate::error::{format_point, Error, Result};
use crate::geometry::norm;
use crate::mesh::{Coupling, Mesh, Transform};
use crate::near_wall::Bounds;
use crate::solve::NodeRole;

/// Partners are within this fraction of the mesh's size of each other's
/// image (exact in a mesh made periodic, round-off after a motion).
const TOLERANCE: f64 = 1e-6;

/// One periodic pair of sides, its nodes paired.
pub(super) struct Periodic {
    /// The names of the two sides.
    names: [String; 2],
    transform: Transform,
    /// Each node of the first side with its partner on the second, where
    /// both move (a pair of held nodes stays as it is).
    moving: Vec<(usize, usize)>,
    tolerance: f64,
}

fn at(mesh: &Mesh, i: usize) -> [f64; 3] {
    let p = mesh.point(i);
    std::array::from_fn(|d| p.get(d).copied().unwrap_or(0.0))
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    norm::<3>(&std::array::from_fn(|d| a[d] - b[d]))
}

fn described(t: &Transform) -> String {
    match t {
        Transform::Translation(s) => format!("translation by {}", format_point(s)),
        Transform::Rotation {
            axis,
            centre,
            angle,
        } => format!(
            "rotation of {:.6}° about {} through {}",
            angle.to_degrees(),
            format_point(axis),
            format_point(centre)
        ),
        Transform::Affine(m) => format!(
            "affine transform [{}]",
            m.chunks(4)
                .map(|r| format!("{} {} {} {}", r[0], r[1], r[2], r[3]))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    }
}

/// The periodic pairs of `mesh` under `plan`: each node of either side
/// paired (an error names a node without a partner), and the plan refused
/// where it moves the sides differently.
pub(super) fn pairs(mesh: &Mesh, plan: &Plan) -> Result<Vec<Periodic>> {
    let all: Vec<usize> = (0..mesh.node_count()).collect();
    let extent = Bounds::of(mesh.dim, &mesh.coords, &all).diagonal();
    let tolerance = TOLERANCE * extent;
    let mut found = Vec::new();
    for f in &mesh.origin.interfaces {
        let names = [f.sides[0].join("+"), f.sides[1].join("+")];
        let (transform, paired) = match &f.coupling {
            Coupling::Sliding => continue,
            Coupling::Periodic(t) => (
                t.clone(),
                by_transform(mesh, &f.sides, t, &names, tolerance)?,
            ),
            Coupling::Linked { transform, pairs } => {
                let t = transform
                    .clone()
                    .unwrap_or_else(|| mean_translation(mesh, pairs));
                given_pairs(mesh, pairs, &t, &names, tolerance)?;
                (t, pairs.clone())
            }
        };
        let moving = moving_pairs(mesh, plan, &names, &paired)?;
        found.push(Periodic {
            names,
            transform,
            moving,
            tolerance,
        });
    }
    Ok(found)
}

/// The nodes of the sides `sides` (group names; a patch of no faces in a
/// 2D case is no group) paired by `transform`: each node of the first with
/// the node of the second at its image, every node of both paired.
fn by_transform(
    mesh: &Mesh,
    sides: &[Vec<String>; 2],
    transform: &Transform,
    names: &[String; 2],
    tolerance: f64,
) -> Result<Vec<(usize, usize)>> {
    let side = |names: &[String]| -> Vec<usize> {
        let mut nodes: Vec<usize> = mesh
            .groups
            .iter()
            .filter(|g| names.contains(&g.name))
            .flat_map(|g| g.nodes())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    };
    let (first, second) = (side(&sides[0]), side(&sides[1]));
    let mut by_x: Vec<(f64, usize)> = second.iter().map(|&j| (at(mesh, j)[0], j)).collect();
    by_x.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut partnered = vec![false; by_x.len()];
    let mut paired = Vec::with_capacity(first.len());
    for &i in &first {
        let image = transform.apply(&at(mesh, i));
        let from = by_x.partition_point(|&(x, _)| x < image[0] - tolerance);
        let best = by_x[from..]
            .iter()
            .enumerate()
            .take_while(|(_, &(x, _))| x <= image[0] + tolerance)
            .map(|(k, &(_, j))| (from + k, distance(&at(mesh, j), &image)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match best {
            Some((k, d)) if d <= tolerance => {
                partnered[k] = true;
                paired.push((i, by_x[k].1));
            }
            _ => {
                return Err(Error::InvalidMesh(format!(
                    "the periodic patches {} and {} do not match: node {} of {} at {}, \
                     moved by their {} to {}, has no node of {} within {tolerance:.3e}",
                    names[0],
                    names[1],
                    mesh.node_tags[i],
                    names[0],
                    format_point(mesh.point(i)),
                    described(transform),
                    format_point(&image[..mesh.dim]),
                    names[1]
                )))
            }
        }
    }
    if let Some(k) = partnered.iter().position(|&p| !p) {
        let j = by_x[k].1;
        return Err(Error::InvalidMesh(format!(
            "the periodic patches {} and {} do not match: node {} of {} at {} is the \
             image of no node of {} by their {}",
            names[0],
            names[1],
            mesh.node_tags[j],
            names[1],
            format_point(mesh.point(j)),
            names[0],
            described(transform)
        )));
    }
    Ok(paired)
}

/// The mean translation from the first node of each pair to the second.
fn mean_translation(mesh: &Mesh, pairs: &[(usize, usize)]) -> Transform {
    let n = pairs.len().max(1) as f64;
    Transform::Translation(std::array::from_fn(|d| {
        pairs
            .iter()
            .map(|&(a, b)| at(mesh, b)[d] - at(mesh, a)[d])
            .sum::<f64>()
            / n
    }))
}

/// Fails unless `transform` takes the first node of each pair onto the
/// second, within `tolerance`.
fn given_pairs(
    mesh: &Mesh,
    pairs: &[(usize, usize)],
    transform: &Transform,
    names: &[String; 2],
    tolerance: f64,
) -> Result<()> {
    mismatch(mesh, names, transform, pairs, |i| at(mesh, i), tolerance).map_or(Ok(()), |m| {
        Err(Error::InvalidMesh(format!(
            "the periodic patches {} and {} do not match: {m}",
            names[0], names[1]
        )))
    })
}

/// The first pair whose second node is not within `tolerance` of the
/// image of its first (at `position`), described.
fn mismatch(
    mesh: &Mesh,
    names: &[String; 2],
    transform: &Transform,
    pairs: &[(usize, usize)],
    position: impl Fn(usize) -> [f64; 3],
    tolerance: f64,
) -> Option<String> {
    pairs.iter().find_map(|&(a, b)| {
        let (image, partner) = (transform.apply(&position(a)), position(b));
        let off = distance(&image, &partner);
        (off > tolerance).then(|| {
            format!(
                "node {} of {}, moved by their {} to {}, is {off:.3e} from its partner, \
                 node {} of {} at {} (more than {tolerance:.3e})",
                mesh.node_tags[a],
                names[0],
                described(transform),
                format_point(&image[..mesh.dim]),
                mesh.node_tags[b],
                names[1],
                format_point(&partner[..mesh.dim]),
            )
        })
    })
}

/// The pairs of `paired` whose nodes both move; an error where one moves
/// or slides and its partner does not do the same.
fn moving_pairs(
    mesh: &Mesh,
    plan: &Plan,
    names: &[String; 2],
    paired: &[(usize, usize)],
) -> Result<Vec<(usize, usize)>> {
    let wanted: std::collections::HashSet<usize> =
        paired.iter().flat_map(|&(a, b)| [a, b]).collect();
    let moving = bodies_of(plan, |i| wanted.contains(&i));
    let does = |i: usize| match (moving.contains_key(&i), plan.roles[i]) {
        (true, _) => "moves",
        (false, NodeRole::Fixed) => "is held",
        _ => "slides",
    };
    let mut both = Vec::new();
    for &(a, b) in paired {
        match (does(a), does(b)) {
            ("is held", "is held") => {}
            ("moves", "moves") => both.push((a, b)),
            (da, db) => {
                return Err(Error::InvalidSetting(format!(
                    "the periodic patches {} and {} would no longer match: node {} of {} {da} \
                     and its partner, node {} of {}, {db}; move both sides with one motion, or \
                     hold both (the default for a group no motion names)",
                    names[0], names[1], mesh.node_tags[a], names[0], mesh.node_tags[b], names[1]
                )))
            }
        }
    }
    Ok(both)
}

/// Fails unless at step `n`, with the moving nodes at `targets`, every
/// moving pair still matches by its transform.
pub(super) fn check(
    periodic: &[Periodic],
    mesh: &Mesh,
    targets: &[(usize, Vec<f64>)],
    n: usize,
) -> Result<()> {
    if periodic.iter().all(|p| p.moving.is_empty()) {
        return Ok(());
    }
    let wanted: std::collections::HashSet<usize> = periodic
        .iter()
        .flat_map(|p| p.moving.iter().flat_map(|&(a, b)| [a, b]))
        .collect();
    let target: HashMap<usize, [f64; 3]> = targets
        .iter()
        .filter(|(i, _)| wanted.contains(i))
        .map(|(i, x)| {
            (
                *i,
                std::array::from_fn(|d| x.get(d).copied().unwrap_or(0.0)),
            )
        })
        .collect();
    let position = |i: usize| target.get(&i).copied().unwrap_or_else(|| at(mesh, i));
    for p in periodic {
        if let Some(m) = mismatch(
            mesh,
            &p.names,
            &p.transform,
            &p.moving,
            position,
            p.tolerance,
        ) {
            return Err(Error::InvalidSetting(format!(
                "step {n}: the periodic patches {} and {} no longer match: {m}; move both \
                 sides with a motion their transform keeps (a translation for a translation), \
                 or hold both",
                p.names[0], p.names[1]
            )));
        }
    }
    Ok(())
}
