//! From the scattered blocks of an SU2 file ([`crate::scatter`]) or a CGNS
//! file ([`crate::cgns_read`]) to
//! PT-Scotch's parts: each rank ends with its part's cells and their nodes,
//! the [`Share`] that [`crate::coupled::LocalSolver::new`] takes.
//!
//! 1. **Graph.** The node-coupling graph (nodes sharing a cell) is built on
//!    the directory ranks: every cell of a block sends each pair `(a, b)` of
//!    its nodes to the directory rank of `a` (`a mod P`). PT-Scotch numbers
//!    a distributed graph's vertices rank after rank, so node `g` is vertex
//!    `s_{g mod P} + ⌊g/P⌋`, with `s_q` the number of nodes of the
//!    directories below `q`.
//! 2. **Cut.** PT-Scotch cuts it into `P` parts (`SCOTCH_dgraphPart`, in a
//!    deterministic context with a fixed seed: the parts depend only on the
//!    file and the number of ranks).
//! 3. **Cells.** A cell goes to the part of its lowest-numbered node (one
//!    request to that node's directory rank), and is sent there.
//! 4. **Nodes.** Each rank asks the directory ranks for its cells' nodes:
//!    their coordinates and their markers. A node is on the boundary when it
//!    is on a facet of any marker, and on a group when on one of that
//!    marker's facets (as `verbss deform --moving MARKER`). Each rank checks
//!    its cells as the whole-file reader checks a mesh ([`validate_at`]):
//!    the line checks were the stream's, and two cells with the same nodes
//!    have the same lowest node, so they meet on one rank.
//! 5. **Facets.** Each rank asks the same directory ranks for the marker
//!    facets whose lowest node is one of its nodes and keeps those one of
//!    its cells is bounded by (all the facet's nodes in one cell): a
//!    boundary facet bounds one cell, which one rank holds, so every facet
//!    lands on one rank, in its marker's group ([`Mesh::groups`]), for the
//!    pieces it writes.

use std::collections::HashMap;

use verbss::io::gmsh::partitioned::Share;
use verbss::io::gmsh::PieceLabels;
use verbss::io::su2::validate_at;
use verbss::mesh::{CellKind, Cells, FileOrigin, Group};
use verbss::topology;
use verbss::{Error, Mesh, Result};

use crate::directory::ask;
use crate::ghosts::kind_code;
use crate::scatter::{decode_facets, CellsAt, Facet, Scattered};
use crate::share::agree;
use crate::sys::ScotchError;
use crate::Comm;

/// The number of nodes of `points` that directory rank `q` of `ranks` holds
/// (those `g ≡ q mod ranks`).
fn directory_count(points: u64, ranks: u64, q: u64) -> u64 {
    if points > q {
        (points - 1 - q) / ranks + 1
    } else {
        0
    }
}

/// This rank's part of the file (collective; see the module documentation):
/// its cells in increasing file order with their tags (`e + 1`), their
/// nodes in increasing order with their tags (`g + 1`), roles and groups.
/// [`Share::partitions`] is the number of ranks.
pub fn repartition(comm: &Comm, scattered: &Scattered) -> Result<Share> {
    let size = comm.size() as usize;
    let ranks = size as u64;
    let directory = |g: u64| (g % ranks) as usize;
    let points = scattered.points;
    let start: Vec<u64> = (0..ranks)
        .scan(0, |s, q| {
            let here = *s;
            *s += directory_count(points, ranks, q);
            Some(here)
        })
        .collect();
    let vertex = |g: u64| start[directory(g)] + g / ranks;
    // 1. The graph's edges, to the directory of their first node.
    let mut pairs: Vec<Vec<u64>> = vec![Vec::new(); size];
    for (_, _, nodes) in scattered.cells() {
        for &a in nodes {
            for &b in nodes.iter().filter(|&&b| b != a) {
                pairs[directory(a)].extend([a, b]);
            }
        }
    }
    let pairs = comm.all_to_all(&pairs);
    let mut edges: Vec<(u64, u64)> = pairs
        .iter()
        .flat_map(|list| list.chunks(2).map(|p| (p[0] / ranks, vertex(p[1]))))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let local = directory_count(points, ranks, comm.rank() as u64) as usize;
    let mut offsets = vec![0u64; local + 1];
    for &(i, _) in &edges {
        offsets[i as usize + 1] += 1;
    }
    for i in 0..local {
        offsets[i + 1] += offsets[i];
    }
    let targets: Vec<u64> = edges.iter().map(|e| e.1).collect();
    drop(edges);
    // 2. The cut.
    let part = comm
        .scotch_part(&offsets, &targets, points, size)
        .map_err(|e| {
            Error::InvalidSetting(match e {
                ScotchError::TooLarge => {
                    format!("the node graph ({points} nodes) is too large for PT-Scotch's indices")
                }
                ScotchError::Memory => "PT-Scotch could not partition: out of memory".into(),
                ScotchError::Failed => "PT-Scotch could not partition the node graph".into(),
            })
        })?;
    drop(targets);
    // 3. Each cell to the part of its lowest node.
    let lowest: Vec<u64> = scattered
        .cells()
        .map(|(_, _, nodes)| nodes.iter().copied().min().unwrap_or(0))
        .collect();
    let parts_of = ask(comm, &lowest, |g| {
        vec![u64::from(part[(g / ranks) as usize] as u32)]
    });
    let mut out: Vec<Vec<u64>> = vec![Vec::new(); size];
    for ((e, kind, nodes), to) in scattered.cells().zip(&parts_of) {
        let list = &mut out[to[0] as usize];
        list.extend([e, kind_code(kind)]);
        list.extend_from_slice(nodes);
    }
    let received = comm.all_to_all(&out);
    drop(out);
    let mut cells: Vec<(u64, CellKind, Vec<u64>)> = Vec::new();
    for list in &received {
        let mut at = 0;
        while at < list.len() {
            let kind = CellKind::ALL[list[at + 1] as usize];
            let n = kind.node_count();
            cells.push((list[at], kind, list[at + 2..at + 2 + n].to_vec()));
            at += 2 + n;
        }
    }
    drop(received);
    cells.sort_unstable_by_key(|c| c.0);
    // 4. The cells' nodes, their coordinates and markers.
    let mut global: Vec<u64> = cells.iter().flat_map(|c| c.2.iter().copied()).collect();
    global.sort_unstable();
    global.dedup();
    let dim = scattered.dim;
    let coords = ask(comm, &global, |g| {
        let i = (g / ranks) as usize;
        scattered.coords[dim * i..dim * (i + 1)]
            .iter()
            .map(|x| x.to_bits())
            .collect()
    });
    let markers = ask(comm, &global, |g| {
        let from = scattered.on_marker.partition_point(|p| p.0 < g);
        let to = scattered.on_marker.partition_point(|p| p.0 <= g);
        scattered.on_marker[from..to].iter().map(|p| p.1).collect()
    });
    let index: HashMap<u64, usize> = global.iter().enumerate().map(|(i, &g)| (g, i)).collect();
    let mut local_cells = Cells::new();
    for (_, kind, nodes) in &cells {
        let nodes: Vec<usize> = nodes.iter().map(|g| index[g]).collect();
        local_cells.push(*kind, &nodes);
    }
    let mut group_nodes: Vec<(String, Vec<usize>)> = scattered
        .markers
        .iter()
        .map(|name| (name.clone(), Vec::new()))
        .collect();
    for (i, on) in markers.iter().enumerate() {
        for &m in on {
            group_nodes[m as usize].1.push(i);
        }
    }
    // 5. The facets of the cells.
    let facets = ask(comm, &global, |g| {
        let from = scattered.facets.partition_point(|f| f.lowest < g);
        let to = scattered.facets.partition_point(|f| f.lowest <= g);
        let mut out = Vec::new();
        for facet in &scattered.facets[from..to] {
            facet.encode(&mut out);
        }
        out
    });
    let groups = bounding_facets(
        &decode_facets(&facets),
        &index,
        &local_cells,
        &scattered.markers,
    );
    let mesh = Mesh {
        dim,
        coords: coords
            .iter()
            .flatten()
            .map(|&b| f64::from_bits(b))
            .collect(),
        cells: local_cells,
        node_tags: global.iter().map(|g| g + 1).collect(),
        cell_tags: cells.iter().map(|c| c.0 + 1).collect(),
        groups,
        origin: FileOrigin::default(),
    };
    // A duplicated element lands on one rank (the part of its lowest node),
    // which finds it here as the whole-file reader would.
    let valid = match &scattered.cells_at {
        CellsAt::Line(line) => validate_at(&mesh, &scattered.path, *line),
        CellsAt::Zone(zone) => verbss::io::cgns::blocks::validate(&mesh, &scattered.path, zone),
    };
    agree(comm, valid, "found an invalid cell")?;
    Ok(Share {
        mesh,
        boundary: markers.iter().map(|on| !on.is_empty()).collect(),
        partitions: size,
        group_nodes,
        binary: false,
        labels: PieceLabels::default(),
    })
}

/// The groups of `markers` with the `facets` (by file node, `index` their
/// local nodes) that bound one of `cells`, in marker order, those with a
/// facet here only.
fn bounding_facets(
    facets: &[Facet],
    index: &HashMap<u64, usize>,
    cells: &Cells,
    markers: &[String],
) -> Vec<Group> {
    let node_cells = topology::node_cells(cells, index.len());
    let mut groups: Vec<Group> = markers
        .iter()
        .map(|name| Group {
            name: name.clone(),
            tag: None,
            facets: Cells::new(),
        })
        .collect();
    for facet in facets {
        let Some(nodes) = facet
            .nodes
            .iter()
            .map(|g| index.get(g).copied())
            .collect::<Option<Vec<usize>>>()
        else {
            continue;
        };
        let bounds = node_cells
            .entries(nodes[0])
            .any(|c| nodes.iter().all(|v| cells.cell(c).contains(v)));
        if bounds {
            let kind = CellKind::ALL[facet.kind as usize];
            groups[facet.marker as usize].facets.push(kind, &nodes);
        }
    }
    groups.retain(|g| !g.facets.is_empty());
    groups
}

#[cfg(test)]
mod tests {
    use super::directory_count;

    /// Directory rank `q` holds the nodes `g ≡ q (mod P)`: counted, they are
    /// every node once.
    #[test]
    fn directories_hold_every_node_once() {
        for (points, ranks) in [(10, 3), (2, 3), (0, 2), (9, 3), (1, 1)] {
            let counts: Vec<u64> = (0..ranks)
                .map(|q| directory_count(points, ranks, q))
                .collect();
            for q in 0..ranks {
                assert_eq!(
                    counts[q as usize],
                    (0..points).filter(|g| g % ranks == q).count() as u64
                );
            }
            assert_eq!(counts.iter().sum::<u64>(), points);
        }
    }
}
