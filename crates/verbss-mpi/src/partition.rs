//! METIS partitions of a mesh's nodes.
//!
//! The node-coupling graph (nodes sharing a cell, [`topology::node_graph`])
//! is cut into `parts` parts of nearly equal node counts with few cut edges
//! (METIS k-way, fixed seed: the same mesh gives the same partition). Each
//! part's rank then owns its nodes and needs one ghost layer: the other ends
//! of its cut edges.

use metis::{Graph, Idx};
use verbss::topology::{self, Csr};
use verbss::{Error, Mesh, Result};

/// The rank owning each node of `mesh` when cut into `parts` parts.
pub fn partition(mesh: &Mesh, parts: usize) -> Result<Vec<i32>> {
    partition_graph(&topology::node_graph(&mesh.cells, mesh.node_count()), parts)
}

/// The part of each row of `graph` (symmetric, no self loops) for `parts`
/// parts. Fails with [`Error::InvalidSetting`] when METIS does, or when the
/// graph is too large for its 32-bit indices.
pub fn partition_graph(graph: &Csr, parts: usize) -> Result<Vec<i32>> {
    let n = graph.rows();
    if parts <= 1 || n == 0 {
        return Ok(vec![0; n]);
    }
    let too_large = || {
        Error::InvalidSetting(format!(
            "the node graph ({n} nodes, {} couplings) is too large for METIS's 32-bit indices",
            graph.targets.len()
        ))
    };
    let xadj = graph
        .offsets
        .iter()
        .map(|&o| Idx::try_from(o).map_err(|_| too_large()))
        .collect::<Result<Vec<Idx>>>()?;
    let adjncy = graph
        .targets
        .iter()
        .map(|&t| Idx::try_from(t).map_err(|_| too_large()))
        .collect::<Result<Vec<Idx>>>()?;
    let nparts = Idx::try_from(parts).map_err(|_| too_large())?;
    let mut part = vec![0 as Idx; n];
    Graph::new(1, nparts, &xadj, &adjncy)
        .map_err(|e| Error::InvalidSetting(format!("METIS rejected the node graph: {e}")))?
        .set_option(metis::option::Seed(1))
        .part_kway(&mut part)
        .map_err(|e| Error::InvalidSetting(format!("METIS could not partition: {e}")))?;
    // METIS's index is 32 or 64 bits wide depending on its build.
    #[allow(clippy::unnecessary_cast)]
    Ok(part.into_iter().map(|p| p as i32).collect())
}
