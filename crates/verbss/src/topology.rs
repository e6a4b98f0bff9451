//! Connectivity derived from the cells: node→cell incidence, unique edges,
//! boundary facets and nodes, the node-coupling graph, its colouring and
//! breadth-first layers.

use std::collections::HashMap;

use crate::mesh::{CellKind, Cells, Mesh};

/// A compressed adjacency list: the neighbours of `i` are
/// `targets[offsets[i]..offsets[i + 1]]`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Csr {
    /// Start of each row, plus the end.
    pub offsets: Vec<usize>,
    /// Concatenated rows.
    pub targets: Vec<usize>,
}

impl Csr {
    /// Row `i`.
    pub fn row(&self, i: usize) -> &[usize] {
        &self.targets[self.offsets[i]..self.offsets[i + 1]]
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Builds rows from `(row, target)` pairs; each row sorted and deduplicated.
    pub fn from_pairs(rows: usize, pairs: impl Iterator<Item = (usize, usize)> + Clone) -> Csr {
        let mut count = vec![0usize; rows + 1];
        for (r, _) in pairs.clone() {
            count[r + 1] += 1;
        }
        for r in 0..rows {
            count[r + 1] += count[r];
        }
        let mut fill = count.clone();
        let mut targets = vec![0; count[rows]];
        for (r, t) in pairs {
            targets[fill[r]] = t;
            fill[r] += 1;
        }
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        let mut out = Vec::with_capacity(targets.len());
        for r in 0..rows {
            let row = &mut targets[count[r]..count[r + 1]];
            row.sort_unstable();
            let mut last = usize::MAX;
            for &t in row.iter() {
                if t != last {
                    out.push(t);
                    last = t;
                }
            }
            offsets.push(out.len());
        }
        Csr {
            offsets,
            targets: out,
        }
    }
}

/// Node → cells incidence (`cells.len()` cells, `nodes` nodes).
pub fn node_cells(cells: &Cells, nodes: usize) -> Csr {
    Csr::from_pairs(
        nodes,
        (0..cells.len()).flat_map(move |c| cells.cell(c).iter().map(move |&n| (n, c))),
    )
}

/// The node-coupling graph: `j` is a neighbour of `i` when they share a cell (`i ≠ j`).
pub fn node_graph(cells: &Cells, nodes: usize) -> Csr {
    Csr::from_pairs(
        nodes,
        (0..cells.len()).flat_map(move |c| {
            let cell = cells.cell(c);
            cell.iter()
                .flat_map(move |&a| cell.iter().filter(move |&&b| b != a).map(move |&b| (a, b)))
        }),
    )
}

/// The graph of `edges` ([`edges`]) in both directions over `nodes` nodes.
pub fn edge_graph(nodes: usize, edges: &[[usize; 2]]) -> Csr {
    Csr::from_pairs(
        nodes,
        edges
            .iter()
            .flat_map(|&[a, b]| [(a, b), (b, a)].into_iter()),
    )
}

/// The unique element edges `(i, j)` with `i < j`, sorted (never face or cell diagonals).
pub fn edges(cells: &Cells) -> Vec<[usize; 2]> {
    let mut edges: Vec<[usize; 2]> = cells
        .iter()
        .flat_map(|(kind, nodes)| {
            kind.table().edges.iter().map(move |e| {
                let (a, b) = (nodes[e[0]], nodes[e[1]]);
                [a.min(b), a.max(b)]
            })
        })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Sorted node key of a facet (at most four nodes), padded with `usize::MAX`.
fn facet_key(nodes: &[usize]) -> [usize; 4] {
    let mut key = [usize::MAX; 4];
    key[..nodes.len()].copy_from_slice(nodes);
    key.sort_unstable();
    key
}

/// The boundary facets: facets that belong to exactly one cell, in the order
/// of their cells, numbered as in their cell (outward for a positive cell).
pub fn boundary_facets(cells: &Cells) -> Cells {
    let mut seen: HashMap<[usize; 4], (usize, u32)> = HashMap::new();
    let mut order = 0usize;
    for (kind, nodes) in cells.iter() {
        for f in kind.table().facets {
            let local: Vec<usize> = f.iter().map(|&k| nodes[k]).collect();
            let entry = seen.entry(facet_key(&local)).or_insert((order, 0));
            entry.1 += 1;
            order += 1;
        }
    }
    let mut single: Vec<usize> = seen.values().filter(|v| v.1 == 1).map(|v| v.0).collect();
    single.sort_unstable();
    let mut out = Cells::new();
    let mut next = single.iter().peekable();
    let mut order = 0usize;
    for (kind, nodes) in cells.iter() {
        for f in kind.table().facets {
            if next.peek() == Some(&&order) {
                let local: Vec<usize> = f.iter().map(|&k| nodes[k]).collect();
                out.push(CellKind::facet_kind(local.len()), &local);
                next.next();
            }
            order += 1;
        }
    }
    out
}

/// Boundary flag per node: on a boundary facet (found from topology) or in any named group.
pub fn boundary_nodes(mesh: &Mesh) -> Vec<bool> {
    let mut flag = vec![false; mesh.node_count()];
    for &n in &boundary_facets(&mesh.cells).nodes {
        flag[n] = true;
    }
    for g in &mesh.groups {
        for &n in &g.facets.nodes {
            flag[n] = true;
        }
    }
    flag
}

/// Greedy colouring of `graph` visiting nodes in `order` (only those listed):
/// two neighbours never share a colour. Returns the colour of each listed node
/// (`u32::MAX` for unlisted ones) and the number of colours.
pub fn colour(graph: &Csr, order: &[usize]) -> (Vec<u32>, u32) {
    let mut colour = vec![u32::MAX; graph.rows()];
    let mut used: Vec<u32> = Vec::new();
    let mut colours = 0;
    for &i in order {
        used.clear();
        used.extend(
            graph
                .row(i)
                .iter()
                .map(|&j| colour[j])
                .filter(|&c| c != u32::MAX),
        );
        used.sort_unstable();
        let mut c = 0;
        for &u in &used {
            if u == c {
                c += 1;
            } else if u > c {
                break;
            }
        }
        colour[i] = c;
        colours = colours.max(c + 1);
    }
    (colour, colours)
}

/// Breadth-first layer of every node from `seeds` (layer 0); unreachable nodes get `u32::MAX`.
pub fn bfs_layers(graph: &Csr, seeds: &[usize]) -> Vec<u32> {
    let mut layer = vec![u32::MAX; graph.rows()];
    let mut front: Vec<usize> = Vec::new();
    for &s in seeds {
        if layer[s] == u32::MAX {
            layer[s] = 0;
            front.push(s);
        }
    }
    let mut depth = 0;
    while !front.is_empty() {
        depth += 1;
        let mut next = Vec::new();
        for &i in &front {
            for &j in graph.row(i) {
                if layer[j] == u32::MAX {
                    layer[j] = depth;
                    next.push(j);
                }
            }
        }
        front = next;
    }
    layer
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    /// Two triangles forming the unit square plus a quad beside it.
    fn hybrid() -> Mesh {
        let mut cells = Cells::new();
        cells.push(CellKind::Triangle, &[0, 1, 2]);
        cells.push(CellKind::Triangle, &[0, 2, 3]);
        cells.push(CellKind::Quad, &[1, 4, 5, 2]);
        let coords = vec![0., 0., 1., 0., 1., 1., 0., 1., 2., 0., 2., 1.];
        Mesh::new(2, coords, cells, vec![]).unwrap()
    }

    #[test]
    fn edges_are_unique_and_exclude_diagonals() {
        let e = edges(&hybrid().cells);
        assert_eq!(
            e,
            vec![
                [0, 1],
                [0, 2],
                [0, 3],
                [1, 2],
                [1, 4],
                [2, 3],
                [2, 5],
                [4, 5]
            ]
        );
    }

    #[test]
    fn boundary_facets_from_topology() {
        let b = boundary_facets(&hybrid().cells);
        assert_eq!(b.len(), 6);
        let mut keys: Vec<_> = b.iter().map(|(_, n)| facet_key(n)).collect();
        keys.sort();
        assert!(!keys.contains(&facet_key(&[0, 2])));
        assert!(!keys.contains(&facet_key(&[1, 2])));
    }

    #[test]
    fn graph_colouring_and_layers() {
        let m = hybrid();
        let g = node_graph(&m.cells, m.node_count());
        assert_eq!(g.row(1), &[0, 2, 4, 5]);
        let order: Vec<usize> = (0..6).collect();
        let (col, n) = colour(&g, &order);
        for i in 0..6 {
            for &j in g.row(i) {
                assert_ne!(col[i], col[j]);
            }
        }
        assert!(n >= 3);
        assert_eq!(bfs_layers(&g, &[3]), vec![1, 2, 1, 0, 2, 2]);
    }
}
