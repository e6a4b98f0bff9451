//! The rigid layer and the wall-distance stiffening (docs/method.md, the
//! `robust` method) where no rank holds the whole mesh: what
//! [`verbss::robust::prepare`] computes on one process, computed on each
//! rank's part with its ghosts ([`Ghosts`]) and made global by ghost
//! exchanges and all-reduces.
//!
//! * **Bodies.** The moving nodes of one chain of motions form a body (the
//!   caller numbers them); a group whose nodes are all prescribed, none
//!   moving, with a bounding box strictly inside the mesh's, is a fixed
//!   wall: the group's node count, an all-prescribed flag and its box are
//!   all-reduced (sum, minimum, minimum and maximum), as the mesh's box.
//!   A body's size is the diagonal of its all-reduced box.
//! * **Wall distances.** Per body (and for the other fixed boundary) every
//!   rank all-gathers the seeds it owns — coordinates and global numbers —
//!   and finds for each node of its part, connected to a seed (with
//!   ghost exchanges until an all-reduce finds no new node), the nearest
//!   seed in straight line ([`nearest_connected`]). That
//!   answer is exact, ties going to the smaller global number as they go
//!   to the smaller node tag on one process, so it is one process's.
//! * **Thickness.** [`Layer::Auto`]'s boundary layer is the reach through
//!   cells of aspect ratio at least [`verbss::robust::ANISOTROPIC`]
//!   ([`reach`]), iterated with ghost exchanges the same way; its largest
//!   wall distance is a max all-reduce.
//! * **Per node.** The layer nodes and the stiffness factors follow from the
//!   distances by the single-process rules ([`layer_body`],
//!   [`stiffness_factor`]), on every node of the part, so that a node has
//!   the same answer on every rank holding it.

use verbss::collective::mark_sync;
use verbss::robust::spread::{nearest_connected, reach};
use verbss::robust::Seeds;
use verbss::robust::{
    fixed_limits, layer_body, stiffness_factor, thickness, Bounds, Layer, Robust,
};
use verbss::solve::NodeRole;
use verbss::topology;
use verbss::{Error, Mesh, Result};

use crate::ghosts::Ghosts;
use crate::ranks::Ranks;
use crate::Comm;

/// The rigid layer and the stiffness factors of a rank's nodes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NearWall {
    /// Per local node: `None` outside the rigid layer, `Some(Some(b))` a
    /// layer node that moves with moving body `b`, `Some(None)` one that
    /// stays (next to a fixed wall).
    pub layer: Vec<Option<Option<usize>>>,
    /// Per local node the spring stiffness factor (empty: no stiffening).
    pub stiffness: Vec<f64>,
    /// The layer's thickness around each body: the moving bodies, then the
    /// fixed walls.
    pub thickness: Vec<f64>,
    /// The number of layer nodes on all ranks.
    pub layer_nodes: u64,
}

/// The near-wall treatment `robust` of the local mesh `mesh` (collective;
/// see the module documentation): `ghosts` its ghost layer, `roles` its
/// nodes' roles before the layer, `body[i]` the moving body of a moving
/// node (numbered from 0 over all ranks), `groups` the mesh's
/// groups with their local nodes, the same names in the same order on
/// every rank.
pub fn near_wall(
    comm: &Comm,
    mesh: &Mesh,
    ghosts: &Ghosts,
    roles: &[NodeRole],
    body: &[Option<usize>],
    groups: &[(String, Vec<usize>)],
    robust: &Robust,
) -> Result<NearWall> {
    robust.validate()?;
    let p = robust.stiffening;
    if !robust.treats() {
        return Ok(NearWall::default());
    }
    let count = groups.len() as u64;
    if comm.min(count) != comm.max(count) {
        return Err(Error::InvalidSetting(
            "the ranks hold different lists of groups".into(),
        ));
    }
    let dim = mesh.dim;
    let part = &ghosts.part;
    let ranks = Ranks::of(comm, part, &ghosts.halo);
    let m = part.node_count();
    let coords = ghosts.spread(comm, &mesh.coords, dim);
    // Per part node: prescribed or not, and the moving body (−1: none).
    let codes: Vec<f64> = roles
        .iter()
        .zip(body)
        .flat_map(|(r, b)| {
            [
                f64::from(u8::from(*r == NodeRole::Fixed)),
                b.map_or(-1.0, |b| b as f64),
            ]
        })
        .collect();
    let codes = ghosts.spread(comm, &codes, 2);
    let fixed_at = |i: usize| codes[2 * i] == 1.0;
    let body_at = |i: usize| (codes[2 * i + 1] >= 0.0).then(|| codes[2 * i + 1] as usize);
    let bodies = comm.max(
        body.iter()
            .flatten()
            .map(|&b| b as u64 + 1)
            .max()
            .unwrap_or(0),
    ) as usize;
    let mut seeds: Vec<Vec<usize>> = vec![Vec::new(); bodies];
    for i in 0..m {
        if let Some(b) = body_at(i) {
            seeds[b].push(i);
        }
    }
    let all: Vec<usize> = (0..mesh.node_count()).collect();
    let outer = Bounds::of(dim, &mesh.coords, &all).reduced(&ranks);
    let mut in_wall = vec![false; m];
    for (_, nodes) in groups {
        let prescribed = nodes
            .iter()
            .all(|&i| roles[i] == NodeRole::Fixed && body[i].is_none());
        let held = comm.sum(nodes.len() as u64);
        let all_prescribed = comm.min(u64::from(prescribed)) == 1;
        let bounds = Bounds::of(dim, &mesh.coords, nodes).reduced(&ranks);
        if held == 0 || !all_prescribed || !bounds.inside(&outer) {
            continue;
        }
        let mut flag = vec![0.0; mesh.node_count()];
        for &i in nodes {
            flag[i] = 1.0;
        }
        let flag = ghosts.spread(comm, &flag, 1);
        let wall: Vec<usize> = (0..m).filter(|&i| flag[i] == 1.0).collect();
        for &i in &wall {
            in_wall[i] = true;
        }
        seeds.push(wall);
    }
    let graph = topology::edge_graph_from(&part.cells, &topology::node_cells(&part.cells, m));
    let nearest = |seeds: &[usize], limit: &dyn Fn(usize) -> f64| -> (Vec<f64>, Vec<u64>) {
        // Every rank's owned seeds go to every rank.
        let owned: Vec<usize> = seeds.iter().copied().filter(|&s| part.owns(s)).collect();
        let points: Vec<f64> = owned
            .iter()
            .flat_map(|&s| &coords[dim * s..dim * (s + 1)])
            .copied()
            .collect();
        let ids: Vec<u64> = owned.iter().map(|&s| part.global[s]).collect();
        let all = Seeds::new(
            dim,
            &comm.all_gather(&points).concat(),
            &comm.all_gather(&ids).concat(),
        );
        nearest_connected(&all, &graph, &coords, seeds, limit, mark_sync(&ranks))
    };
    let fields: Vec<(Vec<f64>, Vec<u64>)> = seeds
        .iter()
        .map(|s| nearest(s, &|_| f64::INFINITY))
        .collect();
    let other_fixed: Vec<usize> = (0..m)
        .filter(|&i| fixed_at(i) && body_at(i).is_none() && !in_wall[i])
        .collect();
    let thickness: Vec<f64> = seeds
        .iter()
        .zip(&fields)
        .map(|(seeds, field)| {
            let size = Bounds::of(dim, &coords, seeds).reduced(&ranks).diagonal();
            thickness(robust.layer, size, |cap| {
                let mut reached = vec![false; m];
                for &s in seeds {
                    reached[s] = true;
                }
                let layer = reach(
                    &part.cells,
                    &coords,
                    dim,
                    &field.0,
                    cap,
                    &mut reached,
                    mark_sync(&ranks),
                );
                comm.max(layer)
            })
        })
        .collect();
    let free = |i: usize| robust.layer != Layer::Off && !fixed_at(i);
    let limits = fixed_limits(m, &fields, &thickness, free);
    let to_fixed = nearest(&other_fixed, &|i| limits[i]).0;
    let stiffen = p > 0.0 && thickness.iter().any(|&t| t > 0.0);
    let mut at = vec![0.0; fields.len()];
    let mut factors = vec![1.0; m];
    let mut layer = vec![None; m];
    for i in 0..m {
        for (a, field) in at.iter_mut().zip(&fields) {
            *a = field.0[i];
        }
        if stiffen {
            factors[i] = stiffness_factor(&at, &thickness, p);
        }
        if free(i) {
            layer[i] = layer_body(&at, to_fixed[i], &thickness).map(|b| (b < bodies).then_some(b));
        }
    }
    let owned = (0..m)
        .filter(|&i| part.owns(i) && layer[i].is_some())
        .count();
    Ok(NearWall {
        layer: ghosts.local.iter().map(|&i| layer[i]).collect(),
        stiffness: if stiffen {
            ghosts.local.iter().map(|&i| factors[i]).collect()
        } else {
            Vec::new()
        },
        thickness,
        layer_nodes: comm.sum(owned as u64),
    })
}
