//! Assembly of the node-block spring system (docs/method.md, "Springs").
//!
//! Every unknown node `i` gets one equation `K_ii u_i = Σ_j B_ij u_j` with
//! symmetric `D×D` blocks:
//!
//! * **edge springs** (Batina): for every element edge `(i, j)`,
//!   `L = |X_j − X_i|`, `n = (X_j − X_i)/L`, `k = 1/L`; `k n nᵀ` is added to
//!   `K_ii` and to `B_ij`;
//! * **ball-vertex springs** (Bottasso): for every element `e` containing `i`
//!   and every facet `F` of `e` not containing `i`, `p` is the point of `F`
//!   nearest to `X_i` ([`nearest_on_segment`], [`nearest_on_triangle`],
//!   [`nearest_on_quad`]) with weights `w_f ∈ [0, 1]`, `Σ w_f = 1`;
//!   `h = |p − X_i|`, `n = (p − X_i)/h`, `k = 1/h`; `k n nᵀ` is added to `K_ii`
//!   and `w_f k n nᵀ` to `B_if`.
//!
//! Since every spring's weights sum to one, `Σ_j B_ij = K_ii` for every row:
//! a common translation of all nodes solves every equation exactly.
//!
//! Rows are numbered by *position* (the solver's order of the unknowns).
//! Couplings to other unknowns are stored with the neighbour's position;
//! couplings to prescribed nodes are kept apart, since they only enter the
//! right-hand side, once per solve.

use std::sync::Arc;

use crate::error::{Error, Result};
use rayon::prelude::*;

use crate::geometry::{
    add_outer, morton_keys, nearest_on_polygon, nearest_on_quad, nearest_on_segment,
    nearest_on_triangle, norm, packed_len, packed_mul, point, sub,
};
use crate::mesh::{Cells, CompactCells, Mesh};
use crate::topology::{self, Csr};

mod refill;

pub use self::refill::{assemble_reusing, reassemble};

/// Which springs a system is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Springs {
    /// Edge springs only (the spring analogy).
    Edge,
    /// Edge and ball-vertex springs.
    BallVertex,
}

/// The connectivity the assembly needs, derived once per mesh.
#[derive(Debug, Clone)]
pub struct Connectivity {
    /// Spatial dimension `D`.
    pub dim: usize,
    /// The mesh's volume cells (in the order of [`Connectivity::new`]).
    pub cells: CompactCells,
    /// Node → cells incidence.
    pub node_cells: Csr,
    /// Node-coupling graph: nodes sharing a cell.
    pub graph: Arc<Csr>,
    /// Edge graph: nodes joined by an element edge (the node-coupling graph
    /// itself on a mesh of simplices, and shared with the blended rigid
    /// motion when it has one).
    pub edge_graph: Arc<Csr>,
    /// The file's node numbers (for messages).
    pub node_tags: Vec<u64>,
    /// The file's cell numbers (for messages).
    pub cell_tags: CellTags,
    /// Per-node stiffness factors `φ` (empty: all 1): an edge spring is
    /// scaled by `(φ_i + φ_j)/2`, the ball-vertex springs of a cell by the
    /// mean `φ` of its nodes. Scaling keeps `Σ_j B_ij = K_ii`.
    pub stiffness: Vec<f64>,
    /// Each node's Z-order key ([`crate::geometry::morton_keys`] of the
    /// input coordinates): rows are assembled in this order, so the cells
    /// and coordinates they read stay in cache (empty: in the given order).
    pub locality: Vec<u64>,
}

impl Connectivity {
    /// Derives the incidence, coupling graph and edge graph of `mesh`.
    ///
    /// The cells are stored along a Z-order curve of their centroids
    /// ([`crate::geometry::morton_keys`]), so that the cells of nearby nodes
    /// lie close together in memory; each node's incident cells keep the
    /// file's order, so sums over them are the same as in the file's order.
    pub fn new(mesh: &Mesh) -> Connectivity {
        Connectivity::with_edge_graph(mesh, None)
    }

    /// [`Connectivity::new`] with the mesh's edge graph when the caller
    /// has it already ([`topology::edge_graph`]): shared, not built again.
    pub fn with_edge_graph(mesh: &Mesh, edge_graph: Option<Arc<Csr>>) -> Connectivity {
        let n = mesh.node_count();
        let mut node_cells = topology::node_cells(&mesh.cells, n);
        let (graph, edge_graph) = Connectivity::graphs(&mesh.cells, &node_cells, edge_graph);
        let by_curve = curve_order(mesh);
        let mut rank = vec![0; by_curve.len()];
        for (r, &c) in by_curve.iter().enumerate() {
            rank[c] = r;
        }
        let cells = CompactCells::ordered(&mesh.cells, by_curve.iter().copied());
        for c in &mut node_cells.targets {
            *c = rank[*c as usize] as u32;
        }
        Connectivity {
            dim: mesh.dim,
            node_cells,
            graph,
            edge_graph,
            cells,
            node_tags: mesh.node_tags.clone(),
            cell_tags: CellTags::ordered(&mesh.cell_tags, by_curve.iter().copied()),
            stiffness: Vec::new(),
            locality: morton_keys(mesh.dim, &mesh.coords),
        }
    }

    /// The node-coupling and edge graphs of `cells` from their incidence
    /// `node_cells`, the edge graph `edge_graph` when given: one graph
    /// shared by both on a mesh of simplices, where they are equal.
    pub fn graphs(
        cells: &Cells,
        node_cells: &Csr,
        edge_graph: Option<Arc<Csr>>,
    ) -> (Arc<Csr>, Arc<Csr>) {
        let edge_graph =
            edge_graph.unwrap_or_else(|| Arc::new(topology::edge_graph_from(cells, node_cells)));
        let graph = if topology::all_simplices(cells) {
            Arc::clone(&edge_graph)
        } else {
            Arc::new(topology::node_graph_from(cells, node_cells))
        };
        (graph, edge_graph)
    }
}

/// The file's number of each cell of a [`Connectivity`], in its order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CellTags {
    /// Cell `c` is the file's cell `first + file_index[c]`: the files that
    /// number their cells consecutively (4 bytes a cell, not 8).
    Consecutive {
        /// The number of the file's first cell.
        first: u64,
        /// Each cell's index in the file.
        file_index: Vec<u32>,
    },
    /// Any other numbering: each cell's number.
    Listed(Vec<u64>),
}

impl CellTags {
    /// The numbers `tags` (in the file's order) of the cells `order`.
    pub fn ordered(tags: &[u64], order: impl Iterator<Item = usize>) -> CellTags {
        let first = tags.first().copied().unwrap_or(0);
        let consecutive = u32::try_from(tags.len()).is_ok()
            && tags
                .iter()
                .zip(first..)
                .all(|(&tag, expected)| tag == expected);
        if consecutive {
            CellTags::Consecutive {
                first,
                file_index: order.map(|c| c as u32).collect(),
            }
        } else {
            CellTags::Listed(order.map(|c| tags[c]).collect())
        }
    }

    /// The file's number of cell `c`.
    pub fn tag(&self, c: usize) -> u64 {
        match self {
            CellTags::Consecutive { first, file_index } => first + u64::from(file_index[c]),
            CellTags::Listed(tags) => tags[c],
        }
    }
}

/// The cells of `mesh` sorted by the Z-order key of their centroids.
fn curve_order(mesh: &Mesh) -> Vec<usize> {
    let d = mesh.dim;
    let mut centroids = Vec::with_capacity(d * mesh.cell_count());
    for c in 0..mesh.cell_count() {
        let nodes = mesh.cells.cell(c);
        for k in 0..d {
            let sum: f64 = nodes.iter().map(|&v| mesh.coords[d * v + k]).sum();
            centroids.push(sum / nodes.len() as f64);
        }
    }
    let keys = morton_keys(d, &centroids);
    let mut order: Vec<usize> = (0..mesh.cell_count()).collect();
    order.sort_by_key(|&c| (keys[c], c));
    order
}

/// The node-block system of the unknown nodes, one row per position.
///
/// Blocks are symmetric and stored packed ([`crate::geometry::packed_index`]):
/// `D(D+1)/2` numbers each (3 in 2D, 6 in 3D).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NodeBlocks {
    /// `K_ii` of each row.
    pub diag: Vec<f64>,
    /// Row `r`'s couplings to unknowns are entries `offsets[r]..offsets[r + 1]`.
    pub offsets: Vec<usize>,
    /// The position of each coupled unknown node.
    pub neighbours: Vec<u32>,
    /// `B_ij` of each entry.
    pub blocks: Vec<f64>,
    /// Row `r`'s couplings to prescribed nodes are entries
    /// `fixed_offsets[r]..fixed_offsets[r + 1]`.
    pub fixed_offsets: Vec<usize>,
    /// The (mesh) index of each coupled prescribed node.
    pub fixed_nodes: Vec<usize>,
    /// `B_ij` of each prescribed coupling.
    pub fixed_blocks: Vec<f64>,
}

impl NodeBlocks {
    /// Row `r`'s pull from the prescribed nodes, `Σ_{j prescribed} B_rj u_j`.
    pub fn prescribed_pull<const D: usize>(&self, r: usize, displacement: &[f64]) -> [f64; D] {
        let s = packed_len(D);
        let mut c = [0.0; D];
        for e in self.fixed_offsets[r]..self.fixed_offsets[r + 1] {
            let v = packed_mul::<D>(
                &self.fixed_blocks[s * e..],
                &point(displacement, self.fixed_nodes[e]),
            );
            for k in 0..D {
                c[k] += v[k];
            }
        }
        c
    }
}

/// Assembles the rows of the nodes `order` (position → node) at coordinates
/// `coords`; `position[j]` is node `j`'s position, or `u32::MAX` for a
/// prescribed node. Blocks that are exactly zero are left out. The rows are
/// assembled in parallel on the calling rayon pool; the result does not
/// depend on the number of threads.
///
/// Fails with [`Error::InvalidMesh`] naming the node (by its file number) when
/// an edge has zero length or a node lies on a facet of its ball (a spring of
/// zero length: a collapsed cell).
pub fn assemble(
    conn: &Connectivity,
    coords: &[f64],
    order: &[usize],
    position: &[u32],
    springs: Springs,
) -> Result<NodeBlocks> {
    match conn.dim {
        2 => assemble_d::<2>(conn, coords, order, position, springs),
        3 => assemble_d::<3>(conn, coords, order, position, springs),
        d => Err(Error::InvalidMesh(format!(
            "dimension {d} (expected 2 or 3)"
        ))),
    }
}

/// Rows are assembled in parallel chunks of this many on the calling rayon
/// pool; each row's sums do not depend on the chunks.
const ROWS: usize = 2048;

fn assemble_d<const D: usize>(
    conn: &Connectivity,
    coords: &[f64],
    order: &[usize],
    position: &[u32],
    springs: Springs,
) -> Result<NodeBlocks> {
    let visit = visit_order(conn, order);
    let pieces = visit
        .par_chunks(ROWS)
        .map(|rows| assemble_rows::<D>(conn, coords, rows, position, springs))
        .collect::<Result<Vec<NodeBlocks>>>()?;
    let s = packed_len(D);
    let mut at = vec![(0, 0); order.len()];
    for (k, piece) in pieces.iter().enumerate() {
        for r in 0..piece.offsets.len() - 1 {
            at[position[visit[ROWS * k + r]] as usize] = (k, r);
        }
    }
    let mut out = NodeBlocks {
        diag: Vec::with_capacity(s * order.len()),
        offsets: Vec::with_capacity(order.len() + 1),
        neighbours: Vec::with_capacity(pieces.iter().map(|p| p.neighbours.len()).sum()),
        blocks: Vec::with_capacity(pieces.iter().map(|p| p.blocks.len()).sum()),
        fixed_offsets: Vec::with_capacity(order.len() + 1),
        fixed_nodes: Vec::with_capacity(pieces.iter().map(|p| p.fixed_nodes.len()).sum()),
        fixed_blocks: Vec::with_capacity(pieces.iter().map(|p| p.fixed_blocks.len()).sum()),
    };
    out.offsets.push(0);
    out.fixed_offsets.push(0);
    for &(k, r) in &at {
        let p = &pieces[k];
        let (a, b) = (p.offsets[r], p.offsets[r + 1]);
        let (fa, fb) = (p.fixed_offsets[r], p.fixed_offsets[r + 1]);
        out.diag.extend_from_slice(&p.diag[s * r..s * (r + 1)]);
        out.neighbours.extend_from_slice(&p.neighbours[a..b]);
        out.blocks.extend_from_slice(&p.blocks[s * a..s * b]);
        out.offsets.push(out.neighbours.len());
        out.fixed_nodes.extend_from_slice(&p.fixed_nodes[fa..fb]);
        out.fixed_blocks
            .extend_from_slice(&p.fixed_blocks[s * fa..s * fb]);
        out.fixed_offsets.push(out.fixed_nodes.len());
    }
    Ok(out)
}

/// The nodes `order` in the order their rows are assembled: along the
/// Z-order curve ([`Connectivity::locality`]), so that the cells and
/// coordinates that nearby rows read stay in cache.
fn visit_order(conn: &Connectivity, order: &[usize]) -> Vec<usize> {
    let mut visit: Vec<usize> = order.to_vec();
    if !conn.locality.is_empty() {
        visit.sort_by_key(|&i| (conn.locality[i], i));
    }
    visit
}

/// Assembles the rows of the nodes `rows` (see [`assemble`]).
fn assemble_rows<const D: usize>(
    conn: &Connectivity,
    coords: &[f64],
    rows: &[usize],
    position: &[u32],
    springs: Springs,
) -> Result<NodeBlocks> {
    let s = packed_len(D);
    let mut out = NodeBlocks {
        offsets: vec![0],
        fixed_offsets: vec![0],
        ..NodeBlocks::default()
    };
    out.diag.reserve(s * rows.len());
    let mut acc = vec![0.0; s * widest(conn, rows.iter().copied())];
    for &i in rows {
        let kii = row::<D>(conn, coords, i, springs, &mut acc)?;
        out.diag.extend_from_slice(&kii[..s]);
        for (block, j) in acc.chunks_exact(s).zip(conn.graph.entries(i)) {
            if block.iter().all(|&v| v == 0.0) {
                continue;
            }
            if position[j] == u32::MAX {
                out.fixed_nodes.push(j);
                out.fixed_blocks.extend_from_slice(block);
            } else {
                out.neighbours.push(position[j]);
                out.blocks.extend_from_slice(block);
            }
        }
        out.offsets.push(out.neighbours.len());
        out.fixed_offsets.push(out.fixed_nodes.len());
    }
    Ok(out)
}

/// The most nodes any of `nodes` is coupled to.
fn widest(conn: &Connectivity, nodes: impl Iterator<Item = usize>) -> usize {
    nodes.map(|i| conn.graph.row(i).len()).max().unwrap_or(0)
}

/// Sums node `i`'s springs at `coords`: returns `K_ii` (packed) and leaves
/// `B_ij` in `acc`, `D(D+1)/2` numbers per node `j` of `conn.graph.row(i)`
/// in that order, the rest of `acc` untouched. The edge springs are added
/// first, in the order of `conn.edge_graph.row(i)`, then the ball-vertex
/// springs by incident cell and facet: the sums do not depend on which rows
/// are assembled together.
fn row<const D: usize>(
    conn: &Connectivity,
    coords: &[f64],
    i: usize,
    springs: Springs,
    acc: &mut [f64],
) -> Result<[f64; 6]> {
    let s = packed_len(D);
    let phi = |j: usize| conn.stiffness.get(j).copied().unwrap_or(1.0);
    let row = conn.graph.row(i);
    let acc = &mut acc[..s * row.len()];
    acc.fill(0.0);
    let slot = |j: usize| {
        s * row
            .binary_search(&(j as u32))
            .expect("coupled nodes share a cell")
    };
    let mut kii = [0.0; 6];
    let xi = point::<D>(coords, i);
    for j in conn.edge_graph.entries(i) {
        let d = sub(&point::<D>(coords, j), &xi);
        let len = norm(&d);
        if !(len > 0.0 && len.is_finite()) {
            return Err(Error::InvalidMesh(format!(
                "nodes {} and {} coincide (an edge of zero length)",
                conn.node_tags[i], conn.node_tags[j]
            )));
        }
        let n = d.map(|v| v / len);
        let k = 0.5 * (phi(i) + phi(j)) / len;
        add_outer(&mut kii, k, &n);
        let at = slot(j);
        add_outer(&mut acc[at..at + s], k, &n);
    }
    if springs == Springs::Edge {
        return Ok(kii);
    }
    let mut wide = Vec::new();
    for c in conn.node_cells.entries(i) {
        let nodes = conn.cells.cell(c);
        let local = nodes.iter().position(|&v| v == i).expect("incidence");
        let scale = if conn.stiffness.is_empty() {
            1.0
        } else {
            nodes.iter().map(|&v| phi(v)).sum::<f64>() / nodes.len() as f64
        };
        let mut failed = None;
        conn.cells.local(c).facets(|facet| {
            if failed.is_some() || facet.contains(&local) {
                return;
            }
            let Some(p) = nearest::<D>(coords, &xi, &nodes, facet, &mut wide) else {
                failed = Some(Error::InvalidMesh(format!(
                    "cell {} has a degenerate quadrilateral face",
                    conn.cell_tags.tag(c)
                )));
                return;
            };
            let d = sub(&p, &xi);
            let h = norm(&d);
            if !(h > 0.0 && h.is_finite() && wide.iter().all(|v| v.is_finite())) {
                failed = Some(Error::InvalidMesh(format!(
                    "node {} lies on a facet of cell {} (a collapsed cell: \
                     zero ball-vertex spring length)",
                    conn.node_tags[i],
                    conn.cell_tags.tag(c)
                )));
                return;
            }
            let n = d.map(|v| v / h);
            add_outer(&mut kii, scale / h, &n);
            for (&f, &wf) in facet.iter().zip(&wide) {
                let at = slot(nodes[f]);
                add_outer(&mut acc[at..at + s], scale * wf / h, &n);
            }
        });
        if let Some(e) = failed {
            return Err(e);
        }
    }
    Ok(kii)
}

/// The nearest point of facet `facet` (local indices into `nodes`) to `x`,
/// its weights left in `w` (one per facet node); `None` for a degenerate
/// quadrilateral. A facet of five or more nodes (a polyhedron's polygonal
/// face) is measured on its triangles about its centre
/// ([`crate::geometry::nearest_on_polygon`]).
fn nearest<const D: usize>(
    coords: &[f64],
    x: &[f64; D],
    nodes: &[usize],
    facet: &[usize],
    w: &mut Vec<f64>,
) -> Option<[f64; D]> {
    let at = |k: usize| point::<D>(coords, nodes[facet[k]]);
    let widen = |v: &[f64; D]| std::array::from_fn::<f64, 3, _>(|k| if k < D { v[k] } else { 0.0 });
    w.clear();
    match facet.len() {
        2 => {
            let (p, t) = nearest_on_segment(x, &at(0), &at(1));
            w.extend_from_slice(&t);
            Some(p)
        }
        3 => {
            let (p, t) = nearest_on_triangle(x, &at(0), &at(1), &at(2));
            w.extend_from_slice(&t);
            Some(p)
        }
        4 => {
            let q = [0, 1, 2, 3].map(|k| widen(&at(k)));
            let (p, t) = nearest_on_quad(&widen(x), &q)?;
            w.extend_from_slice(&t);
            Some(std::array::from_fn(|k| p[k]))
        }
        m => {
            let v: Vec<[f64; D]> = (0..m).map(at).collect();
            Some(nearest_on_polygon(x, &v, w))
        }
    }
}

#[cfg(test)]
mod tests;
