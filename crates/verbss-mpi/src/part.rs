//! One rank's share of a mesh: the nodes it owns, one ghost layer, and every
//! cell around its own nodes.
//!
//! With the cells around an owned node `i` all present, its row of the
//! spring system (`K_ii u_i = Σ_j B_ij u_j`, [`verbss::springs`]) is
//! assembled locally exactly as on one process; the ghosts are the `j`
//! that share a cell with an owned node and belong to another rank. Local
//! nodes and cells keep the increasing order of their global numbers, so the
//! assembly adds the same terms in the same order as the single-process one.

use verbss::{Cells, Mesh};

/// A rank's part of a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// Spatial dimension `D`.
    pub dim: usize,
    /// This rank.
    pub rank: i32,
    /// Global number of each local node (0-based, increasing).
    pub global: Vec<u64>,
    /// Rank owning each local node.
    pub owner: Vec<i32>,
    /// Node coordinates, `D` per local node.
    pub coords: Vec<f64>,
    /// The file's number of each local node (for messages).
    pub node_tags: Vec<u64>,
    /// The local cells, by local node index, in increasing global order.
    pub cells: Cells,
    /// Global number of each local cell.
    pub cell_global: Vec<u64>,
    /// The file's number of each local cell (for messages).
    pub cell_tags: Vec<u64>,
}

impl Part {
    /// Rank `rank`'s part of the whole `mesh` when node `i` is owned by
    /// `owner[i]`: its nodes, every cell containing one of them, and the
    /// other nodes of those cells as ghosts.
    pub fn extract(mesh: &Mesh, owner: &[i32], rank: i32) -> Part {
        let n = mesh.node_count();
        let dim = mesh.dim;
        let mut local = vec![u32::MAX; n];
        let mut cell_global = Vec::new();
        for c in 0..mesh.cells.len() {
            let nodes = mesh.cells.cell(c);
            if nodes.iter().any(|&v| owner[v] == rank) {
                cell_global.push(c as u64);
                for &v in nodes {
                    local[v] = 0;
                }
            }
        }
        let mut global = Vec::new();
        for i in 0..n {
            if owner[i] == rank || local[i] == 0 {
                local[i] = global.len() as u32;
                global.push(i as u64);
            }
        }
        let mut cells = Cells::new();
        for &c in &cell_global {
            let c = c as usize;
            let nodes: Vec<usize> = mesh
                .cells
                .cell(c)
                .iter()
                .map(|&v| local[v] as usize)
                .collect();
            cells.push(mesh.cells.kinds[c], &nodes);
        }
        let mut coords = Vec::with_capacity(dim * global.len());
        for &g in &global {
            coords.extend_from_slice(mesh.point(g as usize));
        }
        Part {
            dim,
            rank,
            owner: global.iter().map(|&g| owner[g as usize]).collect(),
            node_tags: global.iter().map(|&g| mesh.node_tags[g as usize]).collect(),
            cell_tags: cell_global
                .iter()
                .map(|&c| mesh.cell_tags[c as usize])
                .collect(),
            coords,
            global,
            cells,
            cell_global,
        }
    }

    /// Number of local nodes (owned and ghosts).
    pub fn node_count(&self) -> usize {
        self.global.len()
    }

    /// Whether local node `i` is owned here.
    pub fn owns(&self, i: usize) -> bool {
        self.owner[i] == self.rank
    }

    /// The cells this rank writes: those whose first node it owns (each
    /// cell of the mesh belongs to exactly one rank this way).
    pub fn own_cells(&self) -> Vec<usize> {
        (0..self.cells.len())
            .filter(|&c| self.owns(self.cells.cell(c)[0]))
            .collect()
    }
}
