//! The colours of the unknowns, the same on every rank.
//!
//! [`engine_colours`] reproduces the single-process engine's colouring
//! ([`verbss::solve`]): breadth-first layers from the moving boundary,
//! greedy colours in layer order. It needs the whole coupling graph, which
//! every rank of `verbss-mpi deform` has. With these colours the distributed
//! sweeps give the single-process iterates.

use verbss::geometry::point;
use verbss::solve::NodeRole;
use verbss::topology::{self, Csr};

/// The engine's colour of every node (`u32::MAX` for [`NodeRole::Fixed`]):
/// `seeds` are the prescribed nodes with a nonzero prescribed displacement
/// (fixed nodes with `u ≠ 0`, sliding nodes with `n·u ≠ 0`), or all
/// prescribed nodes when none moves; unknowns are coloured greedily in the
/// order (layer from the seeds, node).
pub fn engine_colours(graph: &Csr, roles: &[NodeRole], seeds: &[usize]) -> Vec<u32> {
    let n = roles.len();
    let fallback: Vec<usize>;
    let seeds = if seeds.is_empty() {
        fallback = (0..n).filter(|&i| roles[i] != NodeRole::Free).collect();
        &fallback
    } else {
        seeds
    };
    let layer = topology::bfs_layers(graph, seeds);
    let mut by_layer: Vec<usize> = (0..n).filter(|&i| roles[i] != NodeRole::Fixed).collect();
    by_layer.sort_by_key(|&i| (layer[i], i));
    topology::colour(graph, &by_layer).0
}

/// Whether node `i` is a seed of [`engine_colours`]: prescribed with a
/// nonzero prescribed displacement (`normals` unit, as the engine keeps them).
pub fn is_seed<const D: usize>(
    role: NodeRole,
    normals: &[[f64; 3]],
    displacement: &[f64],
    i: usize,
) -> bool {
    role.prescribed::<D>(normals, &point::<D>(displacement, i))
        .iter()
        .any(|&v| v != 0.0)
}
