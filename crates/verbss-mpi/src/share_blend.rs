//! The blended rigid motion (docs/method.md, "Blended rigid motion") where
//! no rank holds the whole mesh: [`Blend`] on each rank's part with its
//! ghosts, its sums, maxima and ghost values through [`Ranks`], so that
//! every rank finds one process's start on its nodes. One motion moves
//! every moving group, so there is one body: its moving nodes are fitted,
//! and they and the rigid-layer nodes that follow them are held.

use std::sync::Arc;

use verbss::deform::blend::{self, Blend};
use verbss::solve::NodeRole;
use verbss::topology;
use verbss::Mesh;
use verbss_mpi::coupled::Ghosts;
use verbss_mpi::ghosts::spread;
use verbss_mpi::halo::Halo;
use verbss_mpi::ranks::Ranks;
use verbss_mpi::Comm;

/// The blend of a rank's part, and how its share's nodes map into it.
pub struct PartBlend {
    blend: Blend,
    dim: usize,
    /// Part index of each of the share's nodes.
    local: Vec<usize>,
    /// The rank owning each part node.
    owner: Vec<i32>,
    halo: Halo,
    /// The part nodes the blend is given targets for: the moving nodes,
    /// then the layer nodes that follow them.
    targeted: Vec<usize>,
}

impl PartBlend {
    /// The blend of the share `mesh` with the ghost layer `ghosts`
    /// (collective): `roles` per share node with the rigid layer
    /// prescribed, `moving[i]` whether node `i` moves, `follows[i]` whether
    /// it is a layer node that moves with the body.
    pub fn new(
        comm: &Comm,
        mesh: &Mesh,
        ghosts: &Ghosts,
        roles: &[NodeRole],
        moving: &[bool],
        follows: &[bool],
    ) -> PartBlend {
        let dim = mesh.dim;
        let part = &ghosts.part;
        let m = part.node_count();
        let coords = ghosts.spread(comm, &mesh.coords, dim);
        // Per node: prescribed, then 1 moving, 2 following, 0 neither.
        let codes: Vec<f64> = (0..mesh.node_count())
            .flat_map(|i| {
                let fixed = f64::from(u8::from(roles[i] == NodeRole::Fixed));
                let held = if moving[i] {
                    1.0
                } else if follows[i] {
                    2.0
                } else {
                    0.0
                };
                [fixed, held]
            })
            .collect();
        let codes = ghosts.spread(comm, &codes, 2);
        let part_roles: Vec<NodeRole> = (0..m)
            .map(|i| {
                if codes[2 * i] == 1.0 {
                    NodeRole::Fixed
                } else {
                    NodeRole::Free
                }
            })
            .collect();
        let codes = &codes;
        let held_as = |code: f64| (0..m).filter(move |&i| codes[2 * i + 1] == code);
        let fitted: Vec<usize> = held_as(1.0).collect();
        let targeted: Vec<usize> = fitted.iter().copied().chain(held_as(2.0)).collect();
        let graph = Arc::new(topology::edge_graph(&part.cells, m));
        let ranks = Ranks::of(comm, part, &ghosts.halo);
        let body = ((0..fitted.len()).collect(), targeted.clone());
        let blend = Blend::new(
            dim,
            &coords,
            &part.node_tags,
            graph,
            &part_roles,
            &[],
            vec![body],
            &ranks,
        );
        PartBlend {
            blend,
            dim,
            local: ghosts.local.clone(),
            owner: part.owner.clone(),
            halo: ghosts.halo.clone(),
            targeted,
        }
    }

    /// The start of an increment (collective): the share's nodes at
    /// `reference` moved by the blend towards `targets`, the prescribed
    /// nodes' positions (`D` numbers per share node; the others' are not
    /// read).
    pub fn start(&mut self, comm: &Comm, reference: &[f64], targets: &[f64]) -> Vec<f64> {
        let dim = self.dim;
        let m = self.owner.len();
        let x = spread(comm, &self.halo, &self.local, m, reference, dim);
        let q = spread(comm, &self.halo, &self.local, m, targets, dim);
        let at: Vec<(usize, Vec<f64>)> = self
            .targeted
            .iter()
            .map(|&i| (i, q[dim * i..dim * (i + 1)].to_vec()))
            .collect();
        let ranks = Ranks::new(comm, &self.owner, &self.halo);
        let moved = self.blend.apply(&x, &at, &ranks);
        self.local
            .iter()
            .flat_map(|&p| &moved[dim * p..dim * (p + 1)])
            .copied()
            .collect()
    }
}

/// Whether `start` puts every prescribed node (`roles`) at its target in
/// `targets` to round-off, [`blend::ROUND_OFF`] of the mesh's size `size`,
/// on every rank (collective): the springs have nothing left to solve.
pub fn nothing_left(
    comm: &Comm,
    roles: &[NodeRole],
    start: &[f64],
    targets: &[f64],
    size: f64,
) -> bool {
    let dim = if roles.is_empty() {
        1
    } else {
        start.len() / roles.len()
    };
    let left = (0..roles.len())
        .filter(|&i| roles[i] == NodeRole::Fixed)
        .flat_map(|i| (dim * i..dim * (i + 1)).map(|k| (targets[k] - start[k]).abs()))
        .fold(0.0, f64::max);
    comm.max(left) <= blend::ROUND_OFF * size
}
