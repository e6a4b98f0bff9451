//! The two graph walks of the near-wall treatments, on any set of nodes
//! and cells: a whole mesh, or a rank's part with its ghosts, where a
//! `sync` closure between local passes makes the walk global.
//!
//! * [`Nearest`]: every node's nearest seed, spread along the mesh edges. In
//!   each round every node `j` next to a node whose label changed in the
//!   round before takes the seed `s` of such a neighbour when `|x_j − x_s|`
//!   is below its own distance (the smallest distance, then the smallest
//!   seed number, of them all), the labels of the round before being read;
//!   the rounds go on until no label changes. The result does not depend on
//!   the order of the nodes, so a rank's part with its ghosts, exchanging
//!   them after each round, finds what one process finds. (A heap ordered
//!   by distance, as a Dijkstra walk, would be cheaper but its result
//!   depends on the order of its steps: the straight-line distance to a
//!   seed is not a path length, and which seeds a node is offered depends
//!   on the labels its neighbours held on the way.)
//! * [`heap_distances`]: the same spread taken in order of distance from a
//!   heap, a node at a time. Several times cheaper on one process, but its
//!   result depends on the order of the steps, so it is what the blended
//!   rigid motion uses for its weights at every increment (docs/method.md,
//!   "Blended rigid motion"), and the rigid layer, which ranks must find
//!   alike, uses [`Nearest`].
//! * [`reach`]: the nodes reached from the labelled ones through cells of
//!   aspect ratio at least [`super::ANISOTROPIC`], the boundary layer of
//!   the automatic rigid layer's thickness.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::mesh::Cells;
use crate::topology::{self, Csr};

use super::{distance, ANISOTROPIC};

/// Per node the nearest seed found so far: the distance `dist` to it
/// (infinite where none reached), the seed's number `seed` and its point
/// `point` (`dim` numbers per node, carried so that a node can compare a
/// seed it does not hold).
#[derive(Debug, Clone, PartialEq)]
pub struct Nearest {
    /// The dimension.
    pub dim: usize,
    /// The distance to the nearest seed.
    pub dist: Vec<f64>,
    /// The nearest seed's number (`u64::MAX` where none reached).
    pub seed: Vec<u64>,
    /// The nearest seed's coordinates.
    pub point: Vec<f64>,
}

impl Nearest {
    /// `n` nodes that no seed reached yet.
    pub fn new(n: usize, dim: usize) -> Nearest {
        Nearest {
            dim,
            dist: vec![f64::INFINITY; n],
            seed: vec![u64::MAX; n],
            point: vec![0.0; dim * n],
        }
    }

    /// Makes node `i` the seed numbered `id`, at `point`.
    pub fn set_seed(&mut self, i: usize, id: u64, point: &[f64]) {
        self.dist[i] = 0.0;
        self.seed[i] = id;
        self.point[self.dim * i..self.dim * (i + 1)].copy_from_slice(point);
    }

    /// Spreads the labels along the edges of `graph` (nodes at `coords`)
    /// in synchronous rounds (see the module documentation) until no label
    /// changes: `exchange` runs after each round (a ghost exchange, saying
    /// that it may have changed labels, or nothing, saying `false`), `any`
    /// turns whether a label here changed in the round into whether one
    /// changed anywhere.
    pub fn spread(
        &mut self,
        graph: &Csr,
        coords: &[f64],
        mut exchange: impl FnMut(&mut Nearest) -> bool,
        mut any: impl FnMut(bool) -> bool,
    ) {
        let n = self.dist.len();
        let dim = self.dim;
        let mut active: Vec<usize> = (0..n).filter(|&i| self.dist[i].is_finite()).collect();
        let mut is_active = vec![false; n];
        let mut marked = vec![false; n];
        let mut targets = Vec::new();
        // Per update: the node, its new distance and seed; the seed's point.
        let mut updates: Vec<(usize, f64, u64)> = Vec::new();
        let mut points: Vec<f64> = Vec::new();
        let (mut prev_dist, mut prev_seed) = (self.dist.clone(), self.seed.clone());
        loop {
            for &i in &active {
                is_active[i] = true;
                for j in graph.entries(i) {
                    if !std::mem::replace(&mut marked[j], true) {
                        targets.push(j);
                    }
                }
            }
            for &j in &targets {
                marked[j] = false;
                let x = &coords[dim * j..dim * (j + 1)];
                let mut best = (self.dist[j], self.seed[j], usize::MAX);
                for i in graph.entries(j).filter(|&i| is_active[i]) {
                    let d = distance(x, &self.point[dim * i..dim * (i + 1)]);
                    if (d, self.seed[i]) < (best.0, best.1) {
                        best = (d, self.seed[i], i);
                    }
                }
                if best.2 != usize::MAX {
                    updates.push((j, best.0, best.1));
                    points.extend_from_slice(&self.point[dim * best.2..dim * (best.2 + 1)]);
                }
            }
            for &i in &active {
                is_active[i] = false;
            }
            targets.clear();
            active.clear();
            for (k, &(j, d, seed)) in updates.iter().enumerate() {
                self.dist[j] = d;
                self.seed[j] = seed;
                self.point[dim * j..dim * (j + 1)].copy_from_slice(&points[dim * k..dim * (k + 1)]);
                // An update is always a change: a nearer or lower seed.
                active.push(j);
            }
            updates.clear();
            points.clear();
            if exchange(self) {
                // The exchange may have changed ghosts: find every change.
                active.clear();
                for i in 0..n {
                    if self.dist[i] != prev_dist[i] || self.seed[i] != prev_seed[i] {
                        active.push(i);
                    }
                }
            }
            for &i in &active {
                prev_dist[i] = self.dist[i];
                prev_seed[i] = self.seed[i];
            }
            if !any(!active.is_empty()) {
                return;
            }
        }
    }
}

/// For every node of `coords` the distance to its nearest seed of `seeds`,
/// spread along the edges of `graph` in order of distance (a node takes the
/// nearest, in straight line, of its neighbours' seeds, until nothing
/// changes). Nodes no seed reaches keep an infinite distance.
pub(crate) fn heap_distances(graph: &Csr, dim: usize, coords: &[f64], seeds: &[usize]) -> Vec<f64> {
    let n = graph.rows();
    let mut dist = vec![f64::INFINITY; n];
    let mut seed = vec![usize::MAX; n];
    let mut heap = BinaryHeap::new();
    for &s in seeds {
        dist[s] = 0.0;
        seed[s] = s;
        heap.push(Reverse((0u64, s)));
    }
    // Non-negative f64s order like their bit patterns.
    while let Some(Reverse((bits, i))) = heap.pop() {
        if f64::from_bits(bits) > dist[i] {
            continue;
        }
        let s = seed[i];
        for j in graph.entries(i) {
            let d = distance(
                &coords[dim * j..dim * (j + 1)],
                &coords[dim * s..dim * (s + 1)],
            );
            if d < dist[j] {
                dist[j] = d;
                seed[j] = s;
                heap.push(Reverse((d.to_bits(), j)));
            }
        }
    }
    dist
}

/// Marks in `reached` every node reached from the marked ones through cells
/// of `cells` (nodes at `coords`) of aspect ratio at least [`ANISOTROPIC`],
/// taking only nodes with `dist ≤ cap`; repeats after each `sync` (which may
/// mark more nodes) while it returns `true`. Returns the largest `dist` of a
/// marked node.
pub fn reach(
    cells: &Cells,
    coords: &[f64],
    dim: usize,
    dist: &[f64],
    cap: f64,
    reached: &mut [bool],
    mut sync: impl FnMut(&mut [bool]) -> bool,
) -> f64 {
    let n = reached.len();
    let node_cells = topology::node_cells(cells, n);
    let stretched: Vec<bool> = (0..cells.len())
        .map(|c| aspect_ratio(cells, coords, dim, c) >= ANISOTROPIC)
        .collect();
    loop {
        let mut queue: Vec<usize> = (0..n).filter(|&i| reached[i]).collect();
        let mut seen_cell = vec![false; cells.len()];
        while let Some(i) = queue.pop() {
            for c in node_cells.entries(i) {
                if std::mem::replace(&mut seen_cell[c], true) || !stretched[c] {
                    continue;
                }
                for &j in cells.cell(c) {
                    if !reached[j] && dist[j] <= cap {
                        reached[j] = true;
                        queue.push(j);
                    }
                }
            }
        }
        if !sync(reached) {
            break;
        }
    }
    (0..n)
        .filter(|&i| reached[i])
        .map(|i| dist[i])
        .fold(0.0, f64::max)
}

/// Longest over shortest edge of cell `c`.
fn aspect_ratio(cells: &Cells, coords: &[f64], dim: usize, c: usize) -> f64 {
    let nodes = cells.cell(c);
    let point = |k: usize| &coords[dim * nodes[k]..dim * (nodes[k] + 1)];
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for &[a, b] in cells.kinds[c].table().edges {
        let l = distance(point(a), point(b));
        lo = lo.min(l);
        hi = hi.max(l);
    }
    hi / lo
}
