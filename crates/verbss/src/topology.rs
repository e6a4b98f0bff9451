//! Connectivity derived from the cells: node→cell incidence, unique edges,
//! boundary facets and nodes, the node-coupling graph, its colouring and
//! breadth-first layers.

use crate::mesh::{CellKind, Cells, Mesh};

/// A compressed adjacency list: the neighbours of `i` are
/// `targets[offsets[i]..offsets[i + 1]]`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Csr {
    /// Start of each row, plus the end.
    pub offsets: Vec<usize>,
    /// Concatenated rows (32-bit: the node and cell numbers of one mesh,
    /// as the solver's neighbour lists are).
    pub targets: Vec<u32>,
}

impl Csr {
    /// Row `i`.
    pub fn row(&self, i: usize) -> &[u32] {
        &self.targets[self.offsets[i]..self.offsets[i + 1]]
    }

    /// Row `i`'s entries as indices.
    pub fn entries(&self, i: usize) -> impl ExactSizeIterator<Item = usize> + Clone + '_ {
        self.row(i).iter().map(|&t| t as usize)
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Builds rows from `(row, target)` pairs; each row sorted and
    /// deduplicated in place (the pairs are held once, never copied).
    pub fn from_pairs(rows: usize, pairs: impl Iterator<Item = (usize, usize)> + Clone) -> Csr {
        let mut start = vec![0usize; rows + 1];
        for (r, _) in pairs.clone() {
            start[r + 1] += 1;
        }
        for r in 0..rows {
            start[r + 1] += start[r];
        }
        let mut fill = start[..rows].to_vec();
        let mut targets = vec![0; start[rows]];
        for (r, t) in pairs {
            targets[fill[r]] = t as u32;
            fill[r] += 1;
        }
        drop(fill);
        let mut end = 0;
        for r in 0..rows {
            let (from, to) = (start[r], start[r + 1]);
            targets[from..to].sort_unstable();
            start[r] = end;
            for k in from..to {
                if k == from || targets[k] != targets[k - 1] {
                    targets[end] = targets[k];
                    end += 1;
                }
            }
        }
        start[rows] = end;
        targets.truncate(end);
        targets.shrink_to_fit();
        Csr {
            offsets: start,
            targets,
        }
    }

    /// Builds the square graph whose row `i` is what `fill(i, buffer)`
    /// pushes (targets below `rows`, any order, repeats allowed), each row
    /// deduplicated and sorted. Twice over the rows, the first to count, so
    /// that the rows are stored once at their exact size; the repeats are
    /// dropped by marking each target with the row that last saw it, so only
    /// the distinct targets are sorted.
    pub fn from_rows(rows: usize, fill: impl Fn(usize, &mut Vec<usize>)) -> Csr {
        let mut buffer = Vec::new();
        let distinct = |i: usize, buffer: &mut Vec<usize>, seen_in: &mut [usize]| {
            buffer.clear();
            fill(i, buffer);
            buffer.retain(|&j| std::mem::replace(&mut seen_in[j], i) != i);
        };
        let mut seen_in = vec![usize::MAX; rows];
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        for i in 0..rows {
            distinct(i, &mut buffer, &mut seen_in);
            offsets.push(offsets[i] + buffer.len());
        }
        seen_in.fill(usize::MAX);
        let mut targets = Vec::with_capacity(offsets[rows]);
        for i in 0..rows {
            distinct(i, &mut buffer, &mut seen_in);
            buffer.sort_unstable();
            targets.extend(buffer.iter().map(|&t| t as u32));
        }
        Csr { offsets, targets }
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
    node_graph_from(cells, &node_cells(cells, nodes))
}

/// [`node_graph`] from the node → cells incidence `node_cells` ([`node_cells`]).
pub fn node_graph_from(cells: &Cells, node_cells: &Csr) -> Csr {
    Csr::from_rows(node_cells.rows(), |i, row| {
        for c in node_cells.entries(i) {
            row.extend(cells.cell(c).iter().filter(|&&j| j != i));
        }
    })
}

/// The element-edge graph of `cells` on `nodes` nodes ([`edge_graph_from`]).
pub fn edge_graph(cells: &Cells, nodes: usize) -> Csr {
    edge_graph_from(cells, &node_cells(cells, nodes))
}

/// Whether every two nodes of every cell are joined by an edge of it
/// (triangles and tetrahedra): then the edge graph is the node graph.
pub fn all_simplices(cells: &Cells) -> bool {
    cells.kinds.iter().all(|kind| {
        let n = kind.node_count();
        !kind.is_general() && kind.table().edges.len() == n * (n - 1) / 2
    })
}

/// The element-edge graph: `j` is a neighbour of `i` when an edge of a cell
/// joins them (never face or cell diagonals), from the node → cells
/// incidence `node_cells` ([`node_cells`]).
pub fn edge_graph_from(cells: &Cells, node_cells: &Csr) -> Csr {
    Csr::from_rows(node_cells.rows(), |i, row| {
        for c in node_cells.entries(i) {
            let nodes = cells.cell(c);
            cells.local(c).edges(|a, b| {
                let (a, b) = (nodes[a], nodes[b]);
                if a == i {
                    row.push(b);
                } else if b == i {
                    row.push(a);
                }
            });
        }
    })
}

/// The edges `(i, j)`, `i < j`, of an edge graph ([`edge_graph_from`]),
/// sorted.
pub fn upper_edges(graph: &Csr) -> impl Iterator<Item = [usize; 2]> + '_ {
    (0..graph.rows()).flat_map(move |i| {
        graph
            .entries(i)
            .filter(move |&j| j > i)
            .map(move |j| [i, j])
    })
}

/// The unique element edges `(i, j)` with `i < j`, sorted (never face or cell diagonals).
pub fn edges(cells: &Cells, nodes: usize) -> Vec<[usize; 2]> {
    let graph = edge_graph(cells, nodes);
    let mut edges = Vec::with_capacity(graph.targets.len() / 2);
    edges.extend(upper_edges(&graph));
    edges
}

/// A facet's key: its nodes sorted, the first four in place (padded with
/// `usize::MAX`), all of them on the heap only for a facet of more than
/// four (a polygonal face). Two facets with the same nodes are one.
type FacetKey = ([usize; 4], Vec<usize>);

/// The key of the facet of `cell` whose local nodes are `facet`.
fn facet_key_in(cell: &[usize], facet: &[usize]) -> FacetKey {
    let mut key = [usize::MAX; 4];
    if facet.len() > 4 {
        let mut all: Vec<usize> = facet.iter().map(|&local| cell[local]).collect();
        all.sort_unstable();
        key.copy_from_slice(&all[..4]);
        return (key, all);
    }
    for (k, &local) in key.iter_mut().zip(facet) {
        *k = cell[local];
    }
    key.sort_unstable();
    (key, Vec::new())
}

/// The boundary facets: facets that belong to exactly one cell, in the order
/// of their cells, numbered as in their cell (outward for a positive cell).
/// Each facet is counted at its lowest node, among the facets of the cells
/// around that node (through the node → cells incidence, without a table
/// of every facet of the mesh).
pub fn boundary_facets(cells: &Cells) -> Cells {
    let nodes = cells.nodes.iter().max().map_or(0, |&m| m + 1);
    let around = node_cells(cells, nodes);
    let mut single: Vec<(usize, usize)> = Vec::new();
    let mut here: Vec<(FacetKey, usize, usize)> = Vec::new();
    for v in 0..nodes {
        here.clear();
        for c in around.entries(v) {
            let cell = cells.cell(c);
            let mut k = 0;
            cells.local(c).facets(|f| {
                if f.iter().map(|&l| cell[l]).min() == Some(v) {
                    here.push((facet_key_in(cell, f), c, k));
                }
                k += 1;
            });
        }
        here.sort_unstable();
        for run in here.chunk_by(|a, b| a.0 == b.0) {
            if let [(_, c, k)] = run {
                single.push((*c, *k));
            }
        }
    }
    single.sort_unstable();
    let mut out = Cells::new();
    let mut local = Vec::with_capacity(4);
    for (c, k) in single {
        let cell = cells.cell(c);
        let mut at = 0;
        cells.local(c).facets(|f| {
            if at == k {
                local.clear();
                local.extend(f.iter().map(|&l| cell[l]));
            }
            at += 1;
        });
        out.push(CellKind::facet_kind(local.len()), &local);
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
                .entries(i)
                .map(|j| colour[j])
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
            for j in graph.entries(i) {
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

    fn facet_key(nodes: &[usize]) -> FacetKey {
        facet_key_in(nodes, &(0..nodes.len()).collect::<Vec<_>>())
    }

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
        let m = hybrid();
        let e = edges(&m.cells, m.node_count());
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

    /// The graphs built row by row equal those built from every pair of
    /// every cell, on a hex, wedge, pyramid and tet.
    #[test]
    fn graphs_by_rows_match_the_graphs_of_all_pairs() {
        let m = crate::mesh::samples::hex_wedge_pyramid_tet();
        let n = m.node_count();
        let pairs: Vec<(usize, usize)> = m
            .cells
            .iter()
            .flat_map(|(_, nodes)| {
                nodes.iter().flat_map(move |&a| {
                    nodes.iter().filter(move |&&b| b != a).map(move |&b| (a, b))
                })
            })
            .collect();
        let all_pairs = Csr::from_pairs(n, pairs.iter().copied());
        assert_eq!(node_graph(&m.cells, n), all_pairs);
        let pairs: Vec<(usize, usize)> = m
            .cells
            .iter()
            .flat_map(|(kind, nodes)| {
                kind.table()
                    .edges
                    .iter()
                    .flat_map(move |e| [(nodes[e[0]], nodes[e[1]]), (nodes[e[1]], nodes[e[0]])])
            })
            .collect();
        let edge_pairs = Csr::from_pairs(n, pairs.iter().copied());
        let by_rows = edge_graph_from(&m.cells, &node_cells(&m.cells, n));
        assert_eq!(by_rows, edge_pairs);
        let upper: Vec<[usize; 2]> = upper_edges(&edge_pairs).collect();
        assert_eq!(edges(&m.cells, n), upper);
        assert!(
            by_rows.targets.len() < all_pairs.targets.len(),
            "diagonals excluded"
        );
    }

    /// On triangles and tetrahedra every two nodes of a cell are joined by
    /// an edge, so the edge graph is the node graph (and the springs keep
    /// one of them); on any other kind it is not.
    #[test]
    fn the_edge_graph_is_the_node_graph_exactly_on_simplices() {
        use crate::mesh::samples::jittered_grid;
        for (dim, kind, simplices) in [(2, 0, true), (3, 2, true), (2, 1, false), (3, 0, false)] {
            let m = jittered_grid(dim, 4, kind, || 0.0).expect("grid");
            let n = m.node_count();
            assert_eq!(all_simplices(&m.cells), simplices, "{dim}D kind {kind}");
            let same = node_graph(&m.cells, n) == edge_graph(&m.cells, n);
            assert_eq!(same, simplices, "{dim}D kind {kind}");
            let conn = crate::springs::Connectivity::new(&m);
            assert_eq!(
                std::sync::Arc::ptr_eq(&conn.graph, &conn.edge_graph),
                simplices
            );
            assert_eq!(*conn.graph, node_graph(&m.cells, n));
            assert_eq!(*conn.edge_graph, edge_graph(&m.cells, n));
        }
        assert!(!all_simplices(
            &crate::mesh::samples::hex_wedge_pyramid_tet().cells
        ));
    }

    /// The facets found through the incidence are those that one cell
    /// alone has, counted over every facet of every cell, in cell order.
    #[test]
    fn boundary_facets_are_the_facets_counted_once() {
        for m in [
            crate::mesh::samples::hex_wedge_pyramid_tet(),
            crate::mesh::samples::fluid_around_an_airfoil(),
        ] {
            let mut count = std::collections::BTreeMap::new();
            for (kind, nodes) in m.cells.iter() {
                for f in kind.table().facets {
                    *count.entry(facet_key_in(nodes, f)).or_insert(0) += 1;
                }
            }
            let once: Vec<FacetKey> = m
                .cells
                .iter()
                .flat_map(|(kind, nodes)| {
                    kind.table()
                        .facets
                        .iter()
                        .map(move |f| facet_key_in(nodes, f))
                })
                .filter(|k| count[k] == 1)
                .collect();
            let found: Vec<FacetKey> = boundary_facets(&m.cells)
                .iter()
                .map(|(_, n)| facet_key(n))
                .collect();
            assert_eq!(found, once);
            assert!(!found.is_empty() && found.len() < count.len());
        }
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
            for j in g.entries(i) {
                assert_ne!(col[i], col[j]);
            }
        }
        assert!(n >= 3);
        assert_eq!(bfs_layers(&g, &[3]), vec![1, 2, 1, 0, 2, 2]);
    }
}
