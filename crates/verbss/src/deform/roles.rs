//! Which node does what: a node of a moving group follows that group's
//! motions, even where it also lies on a fixed or sliding group (on several
//! moving groups: the first named); a node only on sliding groups of
//! parallel planes slides in its plane; a node only on sliding groups whose
//! planes meet in a line (in 3D: two planes, or more through one line)
//! slides along that line; every other boundary node (on planes that meet
//! in a point, or on a fixed group) is fixed; all other nodes are free.

use std::collections::HashMap;

use crate::error::{Error, Result};
use crate::geometry::{cross, dot, norm};
use crate::mesh::{CellKind, Mesh};
use crate::motion::{Attachment, Motion};
use crate::solve::NodeRole;
use crate::topology;

/// The first two nodes (in node order of the second) at exactly the same
/// position, if any.
pub(super) fn duplicate_nodes(mesh: &Mesh) -> Option<(usize, usize)> {
    let mut seen: HashMap<[u64; 3], usize> = HashMap::with_capacity(mesh.node_count());
    (0..mesh.node_count()).find_map(|i| {
        // `+ 0.0` makes −0 and +0 the same key; a 2D point leaves z at 0.
        let mut key = [0u64; 3];
        for (k, x) in key.iter_mut().zip(mesh.point(i)) {
            *k = (x + 0.0).to_bits();
        }
        seen.insert(key, i).map(|first| (first, i))
    })
}

/// Node roles, slide directions (plane normals and line directions) and the
/// motions of moving nodes.
pub(super) struct Plan {
    pub(super) roles: Vec<NodeRole>,
    pub(super) normals: Vec<[f64; 3]>,
    pub(super) moving: Vec<(usize, Vec<usize>)>,
}

/// What a group does, from all attachments naming it.
enum GroupRole {
    Moving(Vec<usize>),
    Fixed,
    Slide(usize),
}

pub(super) fn plan_roles(mesh: &Mesh, attachments: &[Attachment]) -> Result<Plan> {
    // Per group (in order of first mention): its role.
    let mut order: Vec<usize> = Vec::new();
    let mut roles: HashMap<usize, GroupRole> = HashMap::new();
    let mut normals: Vec<[f64; 3]> = Vec::new();
    for (a, att) in attachments.iter().enumerate() {
        for name in &att.groups {
            mesh.group(name)?;
            let g = mesh
                .groups
                .iter()
                .position(|g| &g.name == name)
                .unwrap_or(0);
            if att.motion.moves() && mesh.groups[g].facets.is_empty() {
                return Err(Error::InvalidSetting(format!(
                    "group '{name}' has no nodes: nothing to move"
                )));
            }
            if !roles.contains_key(&g) {
                order.push(g);
            }
            let entry = roles.remove(&g);
            let next = match (&att.motion, entry) {
                (m, Some(GroupRole::Moving(mut chain))) if m.moves() => {
                    chain.push(a);
                    GroupRole::Moving(chain)
                }
                (m, _) if m.moves() => GroupRole::Moving(vec![a]),
                (_, Some(GroupRole::Moving(chain))) => GroupRole::Moving(chain),
                (Motion::Slide { normal }, None) => {
                    normals.push(match normal {
                        Some(n) => given_normal(mesh, g, n)?,
                        None => group_normal(mesh, g)?,
                    });
                    GroupRole::Slide(normals.len() - 1)
                }
                (Motion::Slide { .. }, Some(GroupRole::Slide(k))) => GroupRole::Slide(k),
                _ => GroupRole::Fixed,
            };
            roles.insert(g, next);
        }
    }
    let n = mesh.node_count();
    let boundary = topology::boundary_nodes(mesh);
    let mut node_role: Vec<NodeRole> = boundary
        .iter()
        .map(|&b| if b { NodeRole::Fixed } else { NodeRole::Free })
        .collect();
    // Sliding: nodes whose every group slides; the distinct planes' normals
    // of each.
    let mut slide: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut blocked = vec![false; n];
    for (g, group) in mesh.groups.iter().enumerate() {
        for i in group.nodes() {
            match roles.get(&g) {
                Some(GroupRole::Slide(k)) => {
                    if !slide[i]
                        .iter()
                        .any(|&j| parallel(&normals[j], &normals[*k]))
                    {
                        slide[i].push(*k);
                    }
                }
                _ => blocked[i] = true,
            }
        }
    }
    let mut lines: HashMap<(usize, usize), usize> = HashMap::new();
    for i in 0..n {
        if blocked[i] {
            continue;
        }
        node_role[i] = match slide[i][..] {
            [] => continue,
            [k] => NodeRole::Slide(k),
            [a, b, ..] if mesh.dim == 3 => {
                let line = unit3(&cross(&normals[a], &normals[b]));
                // Every further plane must hold the line too.
                if slide[i][2..]
                    .iter()
                    .any(|&c| dot(&normals[c], &line).abs() > 1e-9)
                {
                    continue;
                }
                let k = *lines.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    normals.push(line);
                    normals.len() - 1
                });
                NodeRole::Line(k)
            }
            _ => continue,
        };
    }
    let mut moving = Vec::new();
    let mut taken = vec![false; n];
    for &g in &order {
        if let Some(GroupRole::Moving(chain)) = roles.get(&g) {
            for i in mesh.groups[g].nodes() {
                if !taken[i] {
                    taken[i] = true;
                    node_role[i] = NodeRole::Fixed;
                    moving.push((i, chain.clone()));
                }
            }
        }
    }
    Ok(Plan {
        roles: node_role,
        normals,
        moving,
    })
}

fn unit3(v: &[f64; 3]) -> [f64; 3] {
    let l = norm(v);
    [v[0] / l, v[1] / l, v[2] / l]
}

fn parallel(a: &[f64; 3], b: &[f64; 3]) -> bool {
    norm(&cross(a, b)) < 1e-9
}

/// Facets within this angle (radians) of a group's plane, and nodes within
/// this fraction of its extent of one of its planes, lie in it: exact planes
/// and the round-off of meshes exported from CAD (10⁻⁷ of the size).
const PLANE_TOLERANCE: f64 = 1e-6;

/// An angle in degrees, readable however small.
fn degrees(radians: f64) -> String {
    let d = radians.to_degrees();
    if d >= 0.01 {
        format!("{d:.2}°")
    } else {
        format!("{d:.1e}°")
    }
}

/// The unit normal `n` given for group `g`'s slide, checked against the
/// group's own plane when it has one: a normal across that plane would
/// move the group's nodes off it.
fn given_normal(mesh: &Mesh, g: usize, n: &[f64; 3]) -> Result<[f64; 3]> {
    let n = unit3(n);
    if let Ok(own) = group_normal(mesh, g) {
        let angle = norm(&cross(&own, &n)).atan2(dot(&own, &n).abs());
        if angle > 0.5f64.to_radians() {
            return Err(Error::InvalidSetting(format!(
                "the slide normal {} given for group '{}' is at {} from the group's own plane \
                 (normal {}): its nodes would leave that plane; give its normal or none",
                crate::error::format_point(&n[..mesh.dim]),
                mesh.groups[g].name,
                degrees(angle),
                crate::error::format_point(&own[..mesh.dim])
            )));
        }
    }
    Ok(n)
}

/// The unit normal of a group of parallel planes (one plane, or several, as
/// a channel's two walls in one group): the sum of its facets' normals, each
/// turned to agree with the first (a line's normal in 2D, a triangle's cross
/// product, a quad's diagonals' cross product). Each node then slides in the
/// plane of that normal through it (docs/method.md, "Unknowns").
/// Errors, naming a facet that is not parallel to the others, when the
/// group's facets are not all parallel.
fn group_normal(mesh: &Mesh, g: usize) -> Result<[f64; 3]> {
    let group = &mesh.groups[g];
    let dim = mesh.dim;
    let p = |i: usize| -> [f64; 3] {
        let x = mesh.point(i);
        [x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]
    };
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let facet_normals: Vec<(usize, [f64; 3])> = group
        .facets
        .iter()
        .enumerate()
        .filter_map(|(f, (kind, nodes))| {
            let n = match (kind, dim) {
                (CellKind::Line, 2) => {
                    let d = sub(p(nodes[1]), p(nodes[0]));
                    [-d[1], d[0], 0.0]
                }
                (CellKind::Triangle, 3) => cross(
                    &sub(p(nodes[1]), p(nodes[0])),
                    &sub(p(nodes[2]), p(nodes[0])),
                ),
                (CellKind::Quad, 3) => cross(
                    &sub(p(nodes[2]), p(nodes[0])),
                    &sub(p(nodes[3]), p(nodes[1])),
                ),
                (CellKind::Polygon, 3) => (0..nodes.len()).fold([0.0; 3], |n, k| {
                    let t = cross(&p(nodes[k]), &p(nodes[(k + 1) % nodes.len()]));
                    [n[0] + t[0], n[1] + t[1], n[2] + t[2]]
                }),
                _ => return None,
            };
            Some((f, n))
        })
        .collect();
    let mut sum = [0.0; 3];
    for (_, n) in &facet_normals {
        let sign = if sum.iter().zip(n).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        for d in 0..3 {
            sum[d] += sign * n[d];
        }
    }
    let advice = "give the slide motion a `normal` (`--slide GROUP:NX,NY[,NZ]`) or \
                  split the group into its planes";
    if norm(&sum) == 0.0 {
        return Err(Error::InvalidSetting(format!(
            "group '{}' has no facet with an area to take a plane from: {advice}",
            group.name
        )));
    }
    let nrm = unit3(&sum);
    // |n_f × n| ≤ tolerance |n_f|: the facet lies in a plane parallel to the others.
    let bent = facet_normals
        .iter()
        .find(|(_, n)| norm(&cross(n, &nrm)) > PLANE_TOLERANCE * norm(n));
    if let Some((f, n)) = bent {
        let angle = norm(&cross(n, &nrm)).atan2(dot(n, &nrm).abs());
        let corners = group.facets.cell(*f);
        let centre: Vec<f64> = (0..dim)
            .map(|d| corners.iter().map(|&i| mesh.point(i)[d]).sum::<f64>() / corners.len() as f64)
            .collect();
        return Err(Error::InvalidSetting(format!(
            "group '{}' is not made of parallel planes (its facet centred at {} is at {} \
             from the plane of normal {}, more than {}): {advice}",
            group.name,
            crate::error::format_point(&centre),
            degrees(angle),
            crate::error::format_point(&nrm[..dim]),
            degrees(PLANE_TOLERANCE)
        )));
    }
    // A node of the group on none of its facets (a lone vertex) lies in one
    // of the facets' planes: its offset `n·x` is one of theirs.
    let offset = |i: usize| dot(&p(i), &nrm);
    let mut planes: Vec<f64> = facet_normals
        .iter()
        .flat_map(|&(f, _)| group.facets.cell(f).iter().map(|&i| offset(i)))
        .collect();
    planes.sort_by(f64::total_cmp);
    let nodes = group.nodes();
    let extent = nodes
        .iter()
        .map(|&i| norm(&sub(p(i), p(nodes[0]))))
        .fold(0.0, f64::max);
    let tolerance = PLANE_TOLERANCE * extent.max(f64::MIN_POSITIVE);
    let off_plane = nodes.iter().find(|&&i| {
        let o = offset(i);
        let k = planes.partition_point(|&q| q < o);
        let near = |j: usize| planes.get(j).is_some_and(|q| (q - o).abs() <= tolerance);
        !(near(k) || (k > 0 && near(k - 1)))
    });
    if let Some(&i) = off_plane {
        let o = offset(i);
        let distance = planes
            .iter()
            .map(|q| (q - o).abs())
            .fold(f64::INFINITY, f64::min);
        return Err(Error::InvalidSetting(format!(
            "group '{}' is not made of parallel planes (its node at {} is {distance:.3e} from \
             the nearest plane of its facets, of normal {}, more than {tolerance:.3e}): {advice}",
            group.name,
            crate::error::format_point(mesh.point(i)),
            crate::error::format_point(&nrm[..dim])
        )));
    }
    Ok(nrm)
}
