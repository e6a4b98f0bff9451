//! Nodes at exactly the same position. Two sides of one of the mesh's
//! interfaces ([`crate::mesh::Interface`]) may have them: each moves with
//! its own side. Two sides of a baffle (a wall of no thickness, each side
//! on the facets of a group: OpenFOAM's blockMesh blades, createBaffles'
//! wall pairs) may too, when both move together: held both, or both moving
//! with one body. Any other pair is a duplicate node, a crack in the mesh,
//! and refused.

use std::collections::HashMap;

use super::roles::Plan;
use crate::error::{format_point, Error, Result};
use crate::mesh::Mesh;
use crate::solve::NodeRole;

/// The sets of two or more nodes at exactly the same position, each in
/// node order, in the order of their first node.
fn coincident_sets(mesh: &Mesh) -> Vec<Vec<usize>> {
    let mut seen: HashMap<[u64; 3], usize> = HashMap::with_capacity(mesh.node_count());
    let mut sets: Vec<Vec<usize>> = Vec::new();
    let mut set_of: HashMap<usize, usize> = HashMap::new();
    for i in 0..mesh.node_count() {
        // `+ 0.0` makes −0 and +0 the same key; a 2D point leaves z at 0.
        let mut key = [0u64; 3];
        for (k, x) in key.iter_mut().zip(mesh.point(i)) {
            *k = (x + 0.0).to_bits();
        }
        if let Some(&first) = seen.get(&key) {
            let s = *set_of.entry(first).or_insert_with(|| {
                sets.push(vec![first]);
                sets.len() - 1
            });
            sets[s].push(i);
        } else {
            seen.insert(key, i);
        }
    }
    sets
}

/// The coincident pairs of `mesh` that are two sides of a baffle, to be
/// checked against the plan ([`check_baffles`]); an error naming the first
/// pair that is neither an interface's nor a baffle's.
pub(super) fn baffles(mesh: &Mesh) -> Result<Vec<(usize, usize)>> {
    let sets = coincident_sets(mesh);
    if sets.is_empty() {
        return Ok(Vec::new());
    }
    // The groups of each coincident node.
    let mut groups: HashMap<usize, Vec<usize>> =
        sets.iter().flatten().map(|&i| (i, Vec::new())).collect();
    for (g, group) in mesh.groups.iter().enumerate() {
        for i in group.nodes() {
            if let Some(of) = groups.get_mut(&i) {
                of.push(g);
            }
        }
    }
    let named = |g: usize, names: &[String]| names.contains(&mesh.groups[g].name);
    let on_side = |i: usize, names: &[String]| groups[&i].iter().any(|&g| named(g, names));
    let interface = |a: usize, b: usize| {
        mesh.origin.interfaces.iter().any(|f| {
            let [s, t] = &f.sides;
            (on_side(a, s) && on_side(b, t)) || (on_side(a, t) && on_side(b, s))
        })
    };
    let mut pairs = Vec::new();
    for set in &sets {
        for (k, &a) in set.iter().enumerate() {
            for &b in &set[k + 1..] {
                if interface(a, b) {
                    continue;
                }
                if groups[&a].is_empty() || groups[&b].is_empty() {
                    return Err(Error::InvalidMesh(format!(
                        "nodes {} and {} are at the same position {}: duplicate nodes",
                        mesh.node_tags[a],
                        mesh.node_tags[b],
                        format_point(mesh.point(a))
                    )));
                }
                pairs.push((a, b));
            }
        }
    }
    Ok(pairs)
}

/// What a node does in the plan: held, moving with a body, or sliding.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Does {
    Held,
    Moves(usize),
    Slides,
}

impl Does {
    fn of(plan: &Plan, moving: &HashMap<usize, usize>, i: usize) -> Does {
        match (moving.get(&i), plan.roles[i]) {
            (Some(&b), _) => Does::Moves(b),
            (None, NodeRole::Fixed) => Does::Held,
            _ => Does::Slides,
        }
    }
}

/// The moving node → body map of `plan`, for the nodes `wanted`.
pub(super) fn bodies_of(plan: &Plan, wanted: impl Fn(usize) -> bool) -> HashMap<usize, usize> {
    plan.moving
        .iter()
        .filter(|&&(i, _)| wanted(i))
        .copied()
        .collect()
}

/// Fails unless both sides of every baffle pair move together under
/// `plan`, naming the pair and its groups.
pub(super) fn check_baffles(mesh: &Mesh, plan: &Plan, pairs: &[(usize, usize)]) -> Result<()> {
    if pairs.is_empty() {
        return Ok(());
    }
    let wanted: std::collections::HashSet<usize> =
        pairs.iter().flat_map(|&(a, b)| [a, b]).collect();
    let moving = bodies_of(plan, |i| wanted.contains(&i));
    let names = |i: usize| -> String {
        let of: Vec<&str> = mesh
            .groups
            .iter()
            .filter(|g| g.facets.nodes.contains(&i))
            .map(|g| g.name.as_str())
            .collect();
        of.join(", ")
    };
    for &(a, b) in pairs {
        let (da, db) = (Does::of(plan, &moving, a), Does::of(plan, &moving, b));
        if da == db && da != Does::Slides {
            continue;
        }
        let said = |d: Does| match d {
            Does::Held => "is held",
            Does::Moves(_) => "moves",
            Does::Slides => "slides",
        };
        let both = match (da, db) {
            (Does::Slides, Does::Slides) => "they would slide apart".to_string(),
            (Does::Moves(_), Does::Moves(_)) => "they move with different motions".to_string(),
            _ => format!(
                "node {} {} and node {} {}",
                mesh.node_tags[a],
                said(da),
                mesh.node_tags[b],
                said(db)
            ),
        };
        return Err(Error::InvalidSetting(format!(
            "nodes {} and {} at {} are the two sides of a baffle (on groups {} and {}), \
             which must move together: {both}; move both sides with one motion or hold both",
            mesh.node_tags[a],
            mesh.node_tags[b],
            format_point(mesh.point(a)),
            names(a),
            names(b)
        )));
    }
    Ok(())
}
