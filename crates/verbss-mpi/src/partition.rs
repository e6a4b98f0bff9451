//! METIS partitions of a mesh's nodes.
//!
//! The node-coupling graph (nodes sharing a cell, [`topology::node_graph`])
//! is cut into `parts` parts of nearly equal node counts with few cut edges
//! (METIS k-way, fixed seed: the same mesh gives the same partition). Each
//! part's rank then owns its nodes and needs one ghost layer: the other ends
//! of its cut edges.

use verbss::topology::{self, Csr};
use verbss::{Error, Mesh, Result};

use crate::sys::{part_kway, MetisError};

/// The rank owning each node of `mesh` when cut into `parts` parts.
pub fn partition(mesh: &Mesh, parts: usize) -> Result<Vec<i32>> {
    partition_graph(&topology::node_graph(&mesh.cells, mesh.node_count()), parts)
}

/// The part of each row of `graph` (symmetric, no self loops) for `parts`
/// parts. Fails with [`Error::InvalidSetting`] when METIS does, or when the
/// graph is too large for its indices.
pub fn partition_graph(graph: &Csr, parts: usize) -> Result<Vec<i32>> {
    let n = graph.rows();
    if parts <= 1 || n == 0 {
        return Ok(vec![0; n]);
    }
    let targets: Vec<usize> = graph.targets.iter().map(|&t| t as usize).collect();
    part_kway(&graph.offsets, &targets, parts).map_err(|e| {
        Error::InvalidSetting(match e {
            MetisError::TooLarge(bits) => format!(
                "the node graph ({n} nodes, {} couplings) or {parts} parts is too large \
                 for METIS's {bits}-bit indices",
                graph.targets.len()
            ),
            MetisError::Status(-2) => "METIS rejected the node graph: invalid input".into(),
            MetisError::Status(-3) => "METIS could not partition: out of memory".into(),
            MetisError::Status(s) => format!("METIS could not partition: error {s}"),
        })
    })
}
