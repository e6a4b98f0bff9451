//! Re-assembly of a node-block system into the pattern it already has.
//!
//! Between two steps of a run the unknowns, their order and the mesh's
//! cells stay the same; only the coordinates move. The couplings that are
//! not exactly zero are then, as a rule, the same too (always on simplex
//! meshes, where every coupled pair shares an edge spring), and the new
//! blocks can be written over the old ones: the system's arrays are neither
//! allocated nor rebuilt. Each row is summed by the same code and in the
//! same order as [`assemble`]'s, so the numbers are the same.
//!
//! Rows are computed along the Z-order curve ([`super::visit_order`]), in
//! parallel chunks of [`ROWS`] a batch of [`BATCH`] chunks at a time, into
//! buffers kept from batch to batch; each batch is then copied to the rows'
//! positions (the solver's order, in which nodes of one colour lie far
//! apart: computed in that order, the rows would read the cells once per
//! colour instead of once).
//!
//! The first assembly of a run goes the same way, into the pattern of every
//! coupling of the node graph ([`full_pattern`]), which is the pattern
//! [`assemble`] finds when no block is exactly zero: the system is then
//! held once, never as chunks beside their copy. Where a block is exactly
//! zero it falls back to [`assemble`].

use rayon::prelude::*;

use super::{assemble, row, visit_order, widest, Connectivity, NodeBlocks, Springs, ROWS};
use crate::error::{Error, Result};
use crate::geometry::packed_len;

/// Chunks of [`ROWS`] rows computed in parallel before they are copied to
/// their positions.
const BATCH: usize = 8;

/// Re-assembles `blocks`, a system that [`assemble`] made for the same
/// `order`, `position` and `springs` (at other coordinates), at `coords`, in
/// place and in parallel on the calling rayon pool. Returns whether the
/// couplings fitted the pattern: `false` when a block that was exactly zero
/// is not any more, or the other way round (a ball-vertex spring's weight
/// that reached zero on a hybrid mesh), and then `blocks` holds no valid
/// system: assemble afresh.
///
/// Fails as [`assemble`] does.
pub fn reassemble(
    conn: &Connectivity,
    coords: &[f64],
    order: &[usize],
    position: &[u32],
    springs: Springs,
    blocks: &mut NodeBlocks,
) -> Result<bool> {
    match conn.dim {
        2 => reassemble_d::<2>(conn, coords, order, position, springs, blocks),
        3 => reassemble_d::<3>(conn, coords, order, position, springs, blocks),
        d => Err(Error::InvalidMesh(format!(
            "dimension {d} (expected 2 or 3)"
        ))),
    }
}

/// [`reassemble`] into `kept` (without one, into the pattern of every
/// coupling of the node graph) when the couplings fit its pattern,
/// [`assemble`] afresh otherwise.
pub fn assemble_reusing(
    conn: &Connectivity,
    coords: &[f64],
    order: &[usize],
    position: &[u32],
    springs: Springs,
    kept: Option<NodeBlocks>,
) -> Result<NodeBlocks> {
    let mut blocks = kept.unwrap_or_else(|| full_pattern(conn, order, position));
    if reassemble(conn, coords, order, position, springs, &mut blocks)? {
        return Ok(blocks);
    }
    drop(blocks);
    assemble(conn, coords, order, position, springs)
}

/// The system of `order` with a block for every coupling of the node graph
/// (`conn.graph`), in the graph's order: to unknowns by their `position`,
/// to prescribed nodes (`position` `u32::MAX`) by index; every number zero.
pub(super) fn full_pattern(conn: &Connectivity, order: &[usize], position: &[u32]) -> NodeBlocks {
    let s = packed_len(conn.dim);
    let mut out = NodeBlocks {
        diag: vec![0.0; s * order.len()],
        offsets: Vec::with_capacity(order.len() + 1),
        fixed_offsets: Vec::with_capacity(order.len() + 1),
        ..NodeBlocks::default()
    };
    out.offsets.push(0);
    out.fixed_offsets.push(0);
    for &i in order {
        for j in conn.graph.entries(i) {
            match position[j] {
                u32::MAX => out.fixed_nodes.push(j),
                p => out.neighbours.push(p),
            }
        }
        out.offsets.push(out.neighbours.len());
        out.fixed_offsets.push(out.fixed_nodes.len());
    }
    out.neighbours.shrink_to_fit();
    out.fixed_nodes.shrink_to_fit();
    out.blocks = vec![0.0; s * out.neighbours.len()];
    out.fixed_blocks = vec![0.0; s * out.fixed_nodes.len()];
    out
}

/// The couplings of a system: which blocks each row has.
struct Pattern<'a> {
    offsets: &'a [usize],
    neighbours: &'a [u32],
    fixed_offsets: &'a [usize],
    fixed_nodes: &'a [usize],
}

/// One chunk's rows, in the chunk's order: per row `K_ii` and the couplings
/// to unknowns in `values`, the couplings to prescribed nodes in `fixed`;
/// `acc` is the row's scratch.
#[derive(Default)]
struct Buffer {
    values: Vec<f64>,
    fixed: Vec<f64>,
    acc: Vec<f64>,
}

fn reassemble_d<const D: usize>(
    conn: &Connectivity,
    coords: &[f64],
    order: &[usize],
    position: &[u32],
    springs: Springs,
    system: &mut NodeBlocks,
) -> Result<bool> {
    let s = packed_len(D);
    let m = order.len();
    let NodeBlocks {
        diag,
        offsets,
        neighbours,
        blocks,
        fixed_offsets,
        fixed_nodes,
        fixed_blocks,
    } = system;
    let shaped = diag.len() == s * m
        && offsets.len() == m + 1
        && fixed_offsets.len() == m + 1
        && blocks.len() == s * neighbours.len()
        && fixed_blocks.len() == s * fixed_nodes.len();
    if !shaped {
        return Ok(false);
    }
    let pattern = Pattern {
        offsets,
        neighbours,
        fixed_offsets,
        fixed_nodes,
    };
    let visit = visit_order(conn, order);
    let mut buffers: Vec<Buffer> = (0..BATCH).map(|_| Buffer::default()).collect();
    for batch in visit.chunks(ROWS * BATCH) {
        let fits = batch
            .par_chunks(ROWS)
            .zip(buffers.par_iter_mut())
            .map(|(rows, buffer)| {
                fill::<D>(conn, coords, rows, position, springs, &pattern, buffer)
            })
            .try_reduce(|| true, |a, b| Ok(a && b))?;
        if !fits {
            return Ok(false);
        }
        for (rows, buffer) in batch.chunks(ROWS).zip(&buffers) {
            let (mut at, mut fixed_at) = (0, 0);
            for &i in rows {
                let p = position[i] as usize;
                let (a, b) = (pattern.offsets[p], pattern.offsets[p + 1]);
                let (fa, fb) = (pattern.fixed_offsets[p], pattern.fixed_offsets[p + 1]);
                diag[s * p..s * (p + 1)].copy_from_slice(&buffer.values[at..at + s]);
                at += s;
                blocks[s * a..s * b].copy_from_slice(&buffer.values[at..at + s * (b - a)]);
                at += s * (b - a);
                fixed_blocks[s * fa..s * fb]
                    .copy_from_slice(&buffer.fixed[fixed_at..fixed_at + s * (fb - fa)]);
                fixed_at += s * (fb - fa);
            }
        }
    }
    Ok(true)
}

/// Computes the rows of the nodes `rows` into `buffer`, checking each
/// against `pattern`; `false` when one does not fit it.
fn fill<const D: usize>(
    conn: &Connectivity,
    coords: &[f64],
    rows: &[usize],
    position: &[u32],
    springs: Springs,
    pattern: &Pattern,
    buffer: &mut Buffer,
) -> Result<bool> {
    let s = packed_len(D);
    let Buffer { values, fixed, acc } = buffer;
    values.clear();
    fixed.clear();
    acc.resize(s * widest(conn, rows.iter().copied()), 0.0);
    for &i in rows {
        let p = position[i] as usize;
        let kii = row::<D>(conn, coords, i, springs, acc)?;
        values.extend_from_slice(&kii[..s]);
        let (mut e, mut fe) = (pattern.offsets[p], pattern.fixed_offsets[p]);
        for (block, j) in acc.chunks_exact(s).zip(conn.graph.entries(i)) {
            if block.iter().all(|&v| v == 0.0) {
                continue;
            }
            if position[j] == u32::MAX {
                if fe == pattern.fixed_offsets[p + 1] || pattern.fixed_nodes[fe] != j {
                    return Ok(false);
                }
                fe += 1;
                fixed.extend_from_slice(block);
            } else {
                if e == pattern.offsets[p + 1] || pattern.neighbours[e] != position[j] {
                    return Ok(false);
                }
                e += 1;
                values.extend_from_slice(block);
            }
        }
        if e != pattern.offsets[p + 1] || fe != pattern.fixed_offsets[p + 1] {
            return Ok(false);
        }
    }
    Ok(true)
}
