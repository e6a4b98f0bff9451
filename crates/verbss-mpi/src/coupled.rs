//! The entry point of a flow solver that already runs on MPI with its own
//! partition: each rank passes its local mesh, the global number of each of
//! its nodes and the communicator, and gets the displacements of its nodes
//! back. verbss does not re-partition.
//!
//! ```text
//! let mut solver = LocalSolver::new(&comm, &local_mesh, &global_ids, &roles, &normals)?;  // once
//! let info = solver.solve(&coords, &mut displacement, &params)?;                          // per step
//! ```
//!
//! `comm` is the flow solver's communicator as a [`Comm`]:
//! [`Comm::world`], or [`Comm::from_fortran`] of its Fortran handle (from
//! C, `MPI_Comm_c2f(comm)`).
//! MPI is initialised by the flow solver or by [`crate::Mpi::init`].
//!
//! The local meshes may be any split of the cells (each cell on one rank or
//! on several, as with halo cells); a node on several ranks has the same
//! global number, role and coordinates on each. Setup (collective, once):
//!
//! 1. every node gets one owner, the lowest rank holding it (a directory
//!    keyed by `global mod ranks`, two all-to-all exchanges);
//! 2. every rank sends each cell to the owners of its nodes, so that each
//!    owner has every cell around its nodes and one ghost layer ([`Part`]);
//! 3. the unknowns are coloured in parallel, Jones–Plassmann style: a node
//!    whose hashed global number beats those of all its uncoloured unknown
//!    neighbours takes the smallest colour none of its neighbours has,
//!    round after round with a ghost exchange in between. The colours depend
//!    only on the mesh and the global numbers, not on the number of ranks.
//!
//! Each solve then sweeps colour by colour like [`crate::sweeper`]. With
//! these colours (not the single-process engine's layer-ordered ones) the
//! sweeps converge to the same solution as one process, but the iterates
//! differ: compare converged results, not sweep counts. Results for
//! different numbers of ranks agree to rounding.

use verbss::mesh::CellKind;
use verbss::solve::{NodeRole, SolveInfo, SolveParams};
use verbss::topology;
use verbss::{Cells, Error, Mesh, Result};

use crate::halo::Halo;
use crate::part::Part;
use crate::sweeper::Sweeper;
use crate::Comm;

/// A flow-solver rank's deformer (see the module documentation).
pub struct LocalSolver<'c> {
    sweeper: Sweeper<'c>,
    /// Part index of each of the caller's local nodes.
    local: Vec<usize>,
    colours: Vec<u32>,
}

impl<'c> LocalSolver<'c> {
    /// Sets up rank `comm.rank()` (collective): `mesh` is its local mesh,
    /// `global[i]` the global number of local node `i` (distinct within the
    /// rank), `roles` per local node, `normals` the sliding planes' normals
    /// (as [`verbss::solve::Engine::new`]).
    pub fn new(
        comm: &'c Comm,
        mesh: &Mesh,
        global: &[u64],
        roles: &[NodeRole],
        normals: &[[f64; 3]],
    ) -> Result<LocalSolver<'c>> {
        let n = mesh.node_count();
        if global.len() != n || roles.len() != n {
            return Err(Error::InvalidSetting(format!(
                "{} global numbers and {} roles for {n} local nodes",
                global.len(),
                roles.len()
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
                for &v in nodes {
                    buf.push(global[v]);
                    buf.push(owner[v] as u64);
                }
            }
        }
        let received = comm.all_to_all(&out);
        // The part: own cells and received ones, each once (keyed by its sorted nodes).
        let mut cells: Vec<(Vec<u64>, CellKind, Vec<u64>)> = Vec::new();
        let mut node_owner: Vec<(u64, i32)> = global.iter().copied().zip(owner.clone()).collect();
        for c in 0..mesh.cells.len() {
            let g: Vec<u64> = mesh.cells.cell(c).iter().map(|&v| global[v]).collect();
            cells.push((sorted(&g), mesh.cells.kinds[c], g));
        }
        for buf in &received {
            let mut at = 0;
            while at < buf.len() {
                let kind = CellKind::ALL[buf[at] as usize];
                let count = buf[at + 1] as usize;
                let mut g = Vec::with_capacity(count);
                for k in 0..count {
                    g.push(buf[at + 2 + 2 * k]);
                    node_owner.push((buf[at + 2 + 2 * k], buf[at + 3 + 2 * k] as i32));
                }
                at += 2 + 2 * count;
                cells.push((sorted(&g), kind, g));
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
        for (_, kind, g) in &cells {
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
            cell_tags: (1..=cells.len() as u64).collect(),
            cell_global: (0..cells.len() as u64).collect(),
            cells: part_cells,
            global: part_global,
        };
        // Roles of the new nodes from their owners: Free −1, Fixed −2,
        // Slide(k) k, Line(k) −3 − k.
        let halo = Halo::new(comm, &part.global, &part.owner);
        let mut codes = vec![0.0; m];
        for (i, r) in roles.iter().enumerate() {
            codes[local[i]] = match r {
                NodeRole::Free => -1.0,
                NodeRole::Fixed => -2.0,
                NodeRole::Slide(k) => *k as f64,
                NodeRole::Line(k) => -3.0 - *k as f64,
            };
        }
        halo.exchange(comm, &mut codes, 1);
        let part_roles: Vec<NodeRole> = codes
            .iter()
            .map(|&c| match c {
                -1.0 => NodeRole::Free,
                -2.0 => NodeRole::Fixed,
                k if k < 0.0 => NodeRole::Line((-3.0 - k) as usize),
                k => NodeRole::Slide(k as usize),
            })
            .collect();
        let colours = jones_plassmann(comm, &part, &part_roles, &halo);
        let sweeper = Sweeper::new(comm, part, part_roles, normals)?;
        Ok(LocalSolver {
            sweeper,
            local,
            colours,
        })
    }

    /// One step (collective): `coords` are the local nodes' reference
    /// coordinates, `displacement` their prescribed values and initial
    /// guesses on entry and the solution on return (`D` numbers per local
    /// node each). Settings as [`verbss::solve::Engine::solve`], with the
    /// methods of [`Sweeper::solve`].
    pub fn solve(
        &mut self,
        coords: &[f64],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        let dim = self.sweeper.part().dim;
        let n = self.local.len();
        if coords.len() != dim * n || displacement.len() != dim * n {
            return Err(Error::InvalidSetting(format!(
                "{} coordinates and {} displacements for {n} local nodes in {dim}D",
                coords.len(),
                displacement.len()
            )));
        }
        let m = self.sweeper.part().node_count();
        let mut x = vec![0.0; dim * m];
        let mut u = vec![0.0; dim * m];
        for (i, &p) in self.local.iter().enumerate() {
            x[dim * p..dim * (p + 1)].copy_from_slice(&coords[dim * i..dim * (i + 1)]);
            u[dim * p..dim * (p + 1)].copy_from_slice(&displacement[dim * i..dim * (i + 1)]);
        }
        self.sweeper.exchange(&mut x, dim);
        let info = self.sweeper.solve(&x, &self.colours, &mut u, params)?;
        for (i, &p) in self.local.iter().enumerate() {
            displacement[dim * i..dim * (i + 1)].copy_from_slice(&u[dim * p..dim * (p + 1)]);
        }
        Ok(info)
    }

    /// This rank's part: its cells, its nodes and their ghosts.
    pub fn part(&self) -> &Part {
        self.sweeper.part()
    }

    /// The number of colours of the unknowns.
    pub fn colours(&self) -> u32 {
        self.colours
            .iter()
            .filter(|&&c| c != u32::MAX)
            .map(|&c| c + 1)
            .max()
            .unwrap_or(0)
    }
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

/// Parallel greedy colouring of the unknown nodes of `part` (see the
/// module documentation); `u32::MAX` for prescribed nodes.
fn jones_plassmann(comm: &Comm, part: &Part, roles: &[NodeRole], halo: &Halo) -> Vec<u32> {
    let n = part.node_count();
    let graph = topology::node_graph(&part.cells, n);
    let unknown = |i: usize| roles[i] != NodeRole::Fixed;
    let priority = |i: usize| (mix(part.global[i]), part.global[i]);
    let mut colour = vec![f64::NAN; n];
    let mut used: Vec<u32> = Vec::new();
    loop {
        let mut chosen = Vec::new();
        for i in (0..n).filter(|&i| part.owns(i) && unknown(i) && colour[i].is_nan()) {
            let wins = graph
                .entries(i)
                .all(|j| !unknown(j) || !colour[j].is_nan() || priority(j) < priority(i));
            if wins {
                used.clear();
                used.extend(
                    graph
                        .entries(i)
                        .filter(|&j| !colour[j].is_nan())
                        .map(|j| colour[j] as u32),
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
                chosen.push((i, c));
            }
        }
        for (i, c) in chosen {
            colour[i] = f64::from(c);
        }
        halo.exchange(comm, &mut colour, 1);
        let left = (0..n)
            .filter(|&i| part.owns(i) && unknown(i) && colour[i].is_nan())
            .count() as u64;
        if comm.sum(left) == 0 {
            break;
        }
    }
    colour
        .iter()
        .map(|&c| if c.is_nan() { u32::MAX } else { c as u32 })
        .collect()
}

/// A fixed 64-bit mix (SplitMix64's finaliser): priorities that look random
/// but are the same on every rank and every run.
fn mix(g: u64) -> u64 {
    let mut z = g.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
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
