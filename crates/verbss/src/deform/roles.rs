//! Which node does what: a node of a moving group follows that group's
//! motions, even where it also lies on a fixed or sliding group (on several
//! moving groups: the first named); a node only on sliding groups of
//! parallel planes slides in its plane; a node only on sliding groups whose
//! planes meet in a line (in 3D: two planes, or more through one line)
//! slides along that line; every other boundary node (on planes that meet
//! in a point, or on a fixed group) is fixed; all other nodes are free.

use std::collections::HashMap;

use crate::collective::{agree, exact_sums, Collective};
use crate::error::{Error, Result};
use crate::geometry::{cross, dot, norm};
use crate::mesh::{CellKind, Mesh};
use crate::motion::{Attachment, Motion};
use crate::near_wall::Bounds;
use crate::solve::NodeRole;
use crate::topology;

/// Node roles, slide directions (plane normals and line directions), the
/// bodies and the moving nodes.
pub(super) struct Plan {
    pub(super) roles: Vec<NodeRole>,
    pub(super) normals: Vec<[f64; 3]>,
    /// The chains of motions (indices into the attachments) that move a
    /// node of some process, in the order of their groups' first mention:
    /// the bodies, the same on every process.
    pub(super) bodies: Vec<Vec<usize>>,
    /// The moving nodes and their bodies, group by group.
    pub(super) moving: Vec<(usize, usize)>,
}

/// What a group does, from all attachments naming it.
enum GroupRole {
    Moving(Vec<usize>),
    Fixed,
    Slide(usize),
}

/// The plan of `attachments` on the local mesh `mesh` (collective: every
/// process names the same groups, in the same order, and gets the same
/// normals and bodies; a ghost node takes its owner's role).
pub(super) fn plan_roles(
    mesh: &Mesh,
    attachments: &[Attachment],
    on: &dyn Collective,
) -> Result<Plan> {
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
            let mut facets = [mesh.groups[g].facets.len() as f64];
            on.sum(&mut facets);
            if att.motion.moves() && facets[0] == 0.0 {
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
                    let own = agree(on, group_normal(mesh, g, on));
                    normals.push(match normal {
                        Some(n) => given_normal(mesh, g, n, own)?,
                        None => own?,
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
    // The lines where two planes meet, numbered after the planes in the
    // order of their pair of planes on every process.
    let planes = normals.len();
    let line_of = |i: usize| -> Option<(usize, usize)> {
        match slide[i][..] {
            [a, b, ..] if mesh.dim == 3 && !blocked[i] => Some((a.min(b), a.max(b))),
            _ => None,
        }
    };
    let mut pairs = vec![0.0; planes * planes];
    for (a, b) in (0..n).filter_map(line_of) {
        pairs[a * planes + b] = 1.0;
    }
    on.max(&mut pairs);
    let mut lines: HashMap<(usize, usize), usize> = HashMap::new();
    for (k, _) in pairs.iter().enumerate().filter(|(_, &p)| p == 1.0) {
        let (a, b) = (k / planes, k % planes);
        lines.insert((a, b), normals.len());
        normals.push(unit3(&cross(&normals[a], &normals[b])));
    }
    for i in 0..n {
        if blocked[i] {
            continue;
        }
        node_role[i] = match (slide[i][..].len(), line_of(i)) {
            (0, _) => continue,
            (1, _) => NodeRole::Slide(slide[i][0]),
            (_, Some(pair)) => {
                let k = lines[&pair];
                // Every further plane must hold the line too.
                if slide[i][2..]
                    .iter()
                    .any(|&c| dot(&normals[c], &normals[k]).abs() > 1e-9)
                {
                    continue;
                }
                NodeRole::Line(k)
            }
            _ => continue,
        };
    }
    // The moving nodes, group by group, each with its group's chain.
    let mut chains: Vec<Vec<usize>> = Vec::new();
    let mut moving = Vec::new();
    let mut taken = vec![false; n];
    for &g in &order {
        if let Some(GroupRole::Moving(chain)) = roles.get(&g) {
            let b = chains.iter().position(|c| c == chain).unwrap_or_else(|| {
                chains.push(chain.clone());
                chains.len() - 1
            });
            for i in mesh.groups[g].nodes() {
                if !taken[i] {
                    taken[i] = true;
                    node_role[i] = NodeRole::Fixed;
                    moving.push((i, b));
                }
            }
        }
    }
    // The bodies: the chains that move a node of some process.
    let mut held = vec![0.0; chains.len()];
    for &(_, b) in &moving {
        held[b] = 1.0;
    }
    on.max(&mut held);
    let renumber: Vec<Option<usize>> = held
        .iter()
        .scan(0, |next, &h| {
            Some((h == 1.0).then(|| {
                *next += 1;
                *next - 1
            }))
        })
        .collect();
    for (_, b) in &mut moving {
        *b = renumber[*b].expect("a chain that moves a node is a body");
    }
    let bodies = chains
        .into_iter()
        .zip(&renumber)
        .filter(|(_, r)| r.is_some())
        .map(|(c, _)| c)
        .collect();
    refresh_roles(&mut node_role, on);
    Ok(Plan {
        roles: node_role,
        normals,
        bodies,
        moving,
    })
}

/// The ghosts' roles set to their owners' (collective).
fn refresh_roles(roles: &mut [NodeRole], on: &dyn Collective) {
    if on.processes() == 1 {
        return;
    }
    // Free −1, Fixed −2, Slide(k) k, Line(k) −3 − k.
    let mut codes: Vec<f64> = roles
        .iter()
        .map(|r| match r {
            NodeRole::Free => -1.0,
            NodeRole::Fixed => -2.0,
            NodeRole::Slide(k) => *k as f64,
            NodeRole::Line(k) => -3.0 - *k as f64,
        })
        .collect();
    on.refresh(&mut codes, 1);
    for (r, &c) in roles.iter_mut().zip(&codes) {
        *r = match c {
            -1.0 => NodeRole::Free,
            -2.0 => NodeRole::Fixed,
            k if k < 0.0 => NodeRole::Line((-3.0 - k) as usize),
            k => NodeRole::Slide(k as usize),
        };
    }
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
/// group's own plane `own` when it has one: a normal across that plane
/// would move the group's nodes off it.
fn given_normal(mesh: &Mesh, g: usize, n: &[f64; 3], own: Result<[f64; 3]>) -> Result<[f64; 3]> {
    let n = unit3(n);
    if let Ok(own) = own {
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
/// product, a quad's diagonals' cross product), each facet counted by one
/// process and the sum exact ([`exact_sums`]), so the same on any cut. Each
/// node then slides in the plane of that normal through it (docs/method.md,
/// "Unknowns"). Errors, naming a facet that is not parallel to the others
/// or a node off the facets' planes, when the group's facets are not all
/// parallel (this process's facets and owned nodes: the caller agrees).
fn group_normal(mesh: &Mesh, g: usize, on: &dyn Collective) -> Result<[f64; 3]> {
    let group = &mesh.groups[g];
    let dim = mesh.dim;
    let p = |i: usize| -> [f64; 3] {
        let x = mesh.point(i);
        [x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]
    };
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    // Every local facet with an area (not a lone vertex), and those this
    // process counts.
    let shaped: Vec<(usize, [f64; 3])> = group
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
    let facet_normals: Vec<(usize, [f64; 3])> = shaped
        .iter()
        .copied()
        .filter(|&(f, _)| on.counts(group.facets.cell(f)))
        .collect();
    // The first facet of the lowest process that has one sets the sign.
    let mut first = vec![0.0; 4];
    if let Some((_, n)) = facet_normals.first() {
        first = vec![1.0, n[0], n[1], n[2]];
    }
    let firsts = on.gather(&first);
    let reference = firsts
        .chunks_exact(4)
        .find(|r| r[0] == 1.0)
        .map_or([0.0; 3], |r| [r[1], r[2], r[3]]);
    let sum = exact_sums(on, facet_normals.len(), |k| {
        let n = facet_normals[k].1;
        let sign = if dot(&n, &reference) < 0.0 { -1.0 } else { 1.0 };
        [sign * n[0], sign * n[1], sign * n[2]]
    });
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
    let bent = shaped
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
    // of the facets' planes: its offset `n·x` is one of theirs. An owned
    // node has every facet of the group around it on this process.
    let offset = |i: usize| dot(&p(i), &nrm);
    let mut planes: Vec<f64> = shaped
        .iter()
        .flat_map(|&(f, _)| group.facets.cell(f).iter().map(|&i| offset(i)))
        .collect();
    planes.sort_by(f64::total_cmp);
    let nodes = group.nodes();
    let extent = Bounds::of(dim, &mesh.coords, &nodes).reduced(on).diagonal();
    let tolerance = PLANE_TOLERANCE * extent.max(f64::MIN_POSITIVE);
    let off_plane = nodes.iter().filter(|&&i| on.owns(i)).find(|&&i| {
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
