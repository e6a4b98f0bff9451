//! The ghost layer of a rank's local mesh (the first two setup steps of
//! [`crate::coupled::LocalSolver`]): every node gets one owner, the lowest
//! rank holding it (a directory keyed by `global mod ranks`, two
//! all-to-all exchanges), and every rank sends each cell to the owners of
//! its nodes, so that each owner has every cell around its nodes and one
//! ghost layer ([`Part`]).

use verbss::mesh::CellKind;
use verbss::{Cells, Error, Group, Mesh, Result};

use crate::halo::Halo;
use crate::part::Part;
use crate::Comm;

/// A rank's part with its ghosts, and how its caller's nodes map into it.
pub struct Ghosts {
    /// The part: the local cells, those around the owned nodes, and their
    /// nodes (its coordinates are zero until the caller fills them).
    pub part: Part,
    /// Part index of each of the caller's local nodes.
    pub local: Vec<usize>,
    /// The ghost exchange lists of the part.
    pub halo: Halo,
}

impl Ghosts {
    /// The ghost layer of `mesh`, whose local node `i` has the global
    /// number `global[i]` (distinct within the rank; collective).
    pub fn new(comm: &Comm, mesh: &Mesh, global: &[u64]) -> Result<Ghosts> {
        let n = mesh.node_count();
        if global.len() != n {
            return Err(Error::InvalidSetting(format!(
                "{} global numbers for {n} local nodes",
                global.len()
            )));
        }
        let size = comm.size() as usize;
        let rank = comm.rank();
        let owner = owners(comm, global);
        // Cells go to the owners of their nodes: kind, node count, then per
        // node its global number and owner.
        let mut out: Vec<Vec<u64>> = vec![Vec::new(); size];
        for c in 0..mesh.cells.len() {
            let nodes = mesh.cells.cell(c);
            let mut targets: Vec<i32> = nodes.iter().map(|&v| owner[v]).collect();
            targets.sort_unstable();
            targets.dedup();
            for t in targets {
                let buf = &mut out[t as usize];
                buf.push(kind_code(mesh.cells.kinds[c]));
                buf.push(nodes.len() as u64);
                buf.push(mesh.cell_tags[c]);
                for &v in nodes {
                    buf.push(global[v]);
                    buf.push(owner[v] as u64);
                }
            }
        }
        let received = comm.all_to_all(&out);
        // The part: own cells and received ones, each once (keyed by its
        // sorted nodes), with its tag.
        let mut cells: Vec<(Vec<u64>, CellKind, Vec<u64>, u64)> = Vec::new();
        let mut node_owner: Vec<(u64, i32)> = global.iter().copied().zip(owner.clone()).collect();
        for c in 0..mesh.cells.len() {
            let g: Vec<u64> = mesh.cells.cell(c).iter().map(|&v| global[v]).collect();
            cells.push((sorted(&g), mesh.cells.kinds[c], g, mesh.cell_tags[c]));
        }
        for buf in &received {
            let mut at = 0;
            while at < buf.len() {
                let kind = CellKind::ALL[buf[at] as usize];
                let count = buf[at + 1] as usize;
                let tag = buf[at + 2];
                let mut g = Vec::with_capacity(count);
                for k in 0..count {
                    g.push(buf[at + 3 + 2 * k]);
                    node_owner.push((buf[at + 3 + 2 * k], buf[at + 4 + 2 * k] as i32));
                }
                at += 3 + 2 * count;
                cells.push((sorted(&g), kind, g, tag));
            }
        }
        cells.sort_by(|a, b| a.0.cmp(&b.0));
        cells.dedup_by(|a, b| a.0 == b.0);
        node_owner.sort_unstable();
        node_owner.dedup_by_key(|p| p.0);
        let part_global: Vec<u64> = node_owner.iter().map(|p| p.0).collect();
        let index = |g: u64| {
            part_global
                .binary_search(&g)
                .expect("a node of a part cell")
        };
        let mut part_cells = Cells::new();
        for (_, kind, g, _) in &cells {
            let nodes: Vec<usize> = g.iter().map(|&x| index(x)).collect();
            part_cells.push(*kind, &nodes);
        }
        let dim = mesh.dim;
        let local: Vec<usize> = global.iter().map(|&g| index(g)).collect();
        let m = part_global.len();
        let part = Part {
            dim,
            rank,
            owner: node_owner.iter().map(|p| p.1).collect(),
            coords: vec![0.0; dim * m],
            node_tags: part_global.iter().map(|&g| g + 1).collect(),
            cell_tags: cells.iter().map(|c| c.3).collect(),
            cell_global: (0..cells.len() as u64).collect(),
            cells: part_cells,
            global: part_global,
        };
        let halo = Halo::new(comm, &part.global, &part.owner);
        Ok(Ghosts { part, local, halo })
    }

    /// The groups of the part: the groups `names` (every rank the same, in
    /// the same order) with each facet of the caller's `mesh` that has a
    /// node this rank owns, from whichever rank holds it (collective). A
    /// facet goes to the owners of its nodes, as the cells do, so that an
    /// owner holds every facet around its nodes.
    pub fn groups(&self, comm: &Comm, mesh: &Mesh, names: &[String]) -> Result<Vec<Group>> {
        let size = comm.size() as usize;
        // Per facet: group, kind, node count, its nodes' global numbers.
        let mut out: Vec<Vec<u64>> = vec![Vec::new(); size];
        for group in &mesh.groups {
            let Some(k) = names.iter().position(|n| *n == group.name) else {
                continue;
            };
            for (kind, nodes) in group.facets.iter() {
                let mut targets: Vec<i32> = nodes
                    .iter()
                    .map(|&v| self.part.owner[self.local[v]])
                    .collect();
                targets.sort_unstable();
                targets.dedup();
                for t in targets {
                    let buf = &mut out[t as usize];
                    buf.extend([k as u64, kind_code(kind), nodes.len() as u64]);
                    buf.extend(nodes.iter().map(|&v| self.part.global[self.local[v]]));
                }
            }
        }
        let mut facets: Vec<(usize, Vec<u64>, CellKind, Vec<usize>)> = Vec::new();
        for buf in comm.all_to_all(&out) {
            let mut at = 0;
            while at < buf.len() {
                let (k, kind, count) =
                    (buf[at] as usize, buf[at + 1] as usize, buf[at + 2] as usize);
                let g = &buf[at + 3..at + 3 + count];
                at += 3 + count;
                let nodes = g
                    .iter()
                    .map(|x| self.part.global.binary_search(x))
                    .collect::<std::result::Result<Vec<usize>, _>>()
                    .map_err(|_| {
                        Error::InvalidMesh(format!(
                            "a facet of group '{}' has a node in no cell around its other \
                             nodes (the facets must lie on the cells' faces)",
                            names[k]
                        ))
                    })?;
                facets.push((k, sorted(g), CellKind::ALL[kind], nodes));
            }
        }
        facets.sort_by(|a, b| (a.0, &a.1).cmp(&(b.0, &b.1)));
        facets.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
        let mut groups: Vec<Group> = names
            .iter()
            .map(|name| Group {
                name: name.clone(),
                tag: None,
                facets: Cells::new(),
            })
            .collect();
        for (k, _, kind, nodes) in facets {
            groups[k].facets.push(kind, &nodes);
        }
        Ok(groups)
    }

    /// The caller's per-local-node values (`width` each) spread over the
    /// part, the ghosts' from their owners (collective).
    pub fn spread(&self, comm: &Comm, values: &[f64], width: usize) -> Vec<f64> {
        spread(
            comm,
            &self.halo,
            &self.local,
            self.part.node_count(),
            values,
            width,
        )
    }
}

/// The caller's per-local-node values (`width` each) spread over a part of
/// `nodes` nodes, caller's node `i` its node `local[i]`, the ghosts' from
/// their owners through `halo` (collective).
pub fn spread(
    comm: &Comm,
    halo: &Halo,
    local: &[usize],
    nodes: usize,
    values: &[f64],
    width: usize,
) -> Vec<f64> {
    let mut out = vec![0.0; width * nodes];
    for (i, &p) in local.iter().enumerate() {
        out[width * p..width * (p + 1)].copy_from_slice(&values[width * i..width * (i + 1)]);
    }
    halo.exchange(comm, &mut out, width);
    out
}

/// The owner of each local node: the lowest rank holding its global number.
fn owners(comm: &Comm, global: &[u64]) -> Vec<i32> {
    let size = comm.size() as u64;
    let mut ask: Vec<Vec<u64>> = vec![Vec::new(); size as usize];
    for &g in global {
        ask[(g % size) as usize].push(g);
    }
    let asked = comm.all_to_all(&ask);
    let mut holders: Vec<(u64, i32)> = asked
        .iter()
        .enumerate()
        .flat_map(|(r, list)| list.iter().map(move |&g| (g, r as i32)))
        .collect();
    holders.sort_unstable();
    holders.dedup_by_key(|p| p.0);
    let answers: Vec<Vec<u64>> = asked
        .iter()
        .map(|list| {
            list.iter()
                .map(|g| {
                    let k = holders.binary_search_by_key(g, |p| p.0).expect("asked");
                    holders[k].1 as u64
                })
                .collect()
        })
        .collect();
    let replies = comm.all_to_all(&answers);
    let mut next = vec![0usize; size as usize];
    global
        .iter()
        .map(|&g| {
            let d = (g % size) as usize;
            let o = replies[d][next[d]];
            next[d] += 1;
            o as i32
        })
        .collect()
}

/// The position of `kind` in [`CellKind::ALL`].
pub(crate) fn kind_code(kind: CellKind) -> u64 {
    CellKind::ALL
        .iter()
        .position(|&k| k == kind)
        .expect("every kind is listed") as u64
}

/// `g` sorted.
fn sorted(g: &[u64]) -> Vec<u64> {
    let mut s = g.to_vec();
    s.sort_unstable();
    s
}
