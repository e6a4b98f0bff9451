//! The wall distances and the boundary layer's reach of the near-wall
//! treatments, on any set of nodes and cells: a whole mesh, or a rank's
//! part with its ghosts, where a `sync` closure between local passes makes
//! a walk global.
//!
//! * [`Seeds`] and [`nearest_seeds`]: every node's nearest seed in
//!   straight line, `min_s (|x_j − x_s|, id_s)` over the seeds of its
//!   connected part of the mesh (ties to the smaller seed number), found
//!   in a k-d tree of the seeds. The answer is exact, so it depends neither
//!   on the order of the nodes nor on how the mesh is cut: a rank holding
//!   all seeds finds on its part what one process finds. [`connect`] marks
//!   the nodes connected to a seed.
//! * [`heap_distances`]: the distance spread along the edges from a heap,
//!   in order of distance, a node taking the nearest of its neighbours'
//!   seeds. Cheaper still, but its answer depends on the order of its
//!   steps (the straight-line distance to a seed is not a path length), so
//!   it is what the blended rigid motion uses for its weights at every
//!   increment (docs/method.md, "Blended rigid motion"), while the rigid
//!   layer and the stiffening, which ranks must find alike, use
//!   [`nearest_seeds`].
//! * [`reach`]: the nodes reached from the labelled ones through cells of
//!   aspect ratio at least [`super::ANISOTROPIC`], the boundary layer of
//!   the automatic rigid layer's thickness.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::mesh::Cells;
use crate::topology::{self, Csr};

use super::{distance, ANISOTROPIC};

/// A k-d tree leaf's most points.
const LEAF: usize = 8;

/// Seed points in a k-d tree, each with its number: the points of
/// `[lo, hi)` split at the middle `m = (lo + hi) / 2` along axis
/// `depth mod dim`, those before `m` not above `split[m]`, those from `m`
/// on not below, down to leaves of at most [`LEAF`] points.
#[derive(Debug, Clone)]
pub struct Seeds {
    dim: usize,
    points: Vec<f64>,
    ids: Vec<u64>,
    split: Vec<f64>,
}

impl Seeds {
    /// The seeds at `points` (`dim` numbers each) numbered `ids`.
    pub fn new(dim: usize, points: &[f64], ids: &[u64]) -> Seeds {
        let mut order: Vec<usize> = (0..ids.len()).collect();
        let mut split = vec![0.0; ids.len()];
        arrange(dim, points, &mut order, 0, 0, &mut split);
        Seeds {
            dim,
            points: order
                .iter()
                .flat_map(|&k| &points[dim * k..dim * (k + 1)])
                .copied()
                .collect(),
            ids: order.iter().map(|&k| ids[k]).collect(),
            split,
        }
    }

    /// The number of seeds.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether there is no seed.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The squared distance from `x` to seed `k` (the terms summed in
    /// order, as every distance here, so that equal pairs give equal bits).
    fn squared(&self, x: &[f64], k: usize) -> f64 {
        let p = &self.points[self.dim * k..self.dim * (k + 1)];
        x.iter().zip(p).map(|(a, b)| (a - b) * (a - b)).sum()
    }

    /// Lowers `best` (squared distance, number, seed) to the smallest
    /// `(squared distance, number)` over the seeds of `[lo, hi)`.
    fn search(&self, x: &[f64], lo: usize, hi: usize, depth: usize, best: &mut (f64, u64, usize)) {
        if hi - lo <= LEAF {
            for k in lo..hi {
                let d2 = self.squared(x, k);
                if (d2, self.ids[k]) < (best.0, best.1) {
                    *best = (d2, self.ids[k], k);
                }
            }
            return;
        }
        let mid = (lo + hi) / 2;
        let dx = x[depth % self.dim] - self.split[mid];
        let (near, far) = if dx < 0.0 {
            ((lo, mid), (mid, hi))
        } else {
            ((mid, hi), (lo, mid))
        };
        self.search(x, near.0, near.1, depth + 1, best);
        // A seed beyond the plane is at least |dx| away; at exactly that
        // distance it may still win on its number.
        if dx * dx <= best.0 {
            self.search(x, far.0, far.1, depth + 1, best);
        }
    }
}

/// Orders `order` (indices of `points`, the slice starting at `lo` of the
/// whole) as [`Seeds`] keeps its points, recording the splits.
fn arrange(
    dim: usize,
    points: &[f64],
    order: &mut [usize],
    depth: usize,
    lo: usize,
    split: &mut [f64],
) {
    if order.len() <= LEAF {
        return;
    }
    let axis = depth % dim;
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        points[dim * a + axis].total_cmp(&points[dim * b + axis])
    });
    split[lo + mid] = points[dim * order[mid] + axis];
    let (before, after) = order.split_at_mut(mid);
    arrange(dim, points, before, depth + 1, lo, split);
    arrange(dim, points, after, depth + 1, lo + mid, split);
}

/// For every node marked in `reached` (nodes at `coords`): the distance to
/// its nearest seed of `seeds` and that seed's number; infinite and
/// `u64::MAX` elsewhere. A node starts its search from the seed of a
/// neighbour in `graph` already found, which bounds it.
pub fn nearest_seeds(
    seeds: &Seeds,
    graph: &Csr,
    coords: &[f64],
    reached: &[bool],
) -> (Vec<f64>, Vec<u64>) {
    let n = reached.len();
    let dim = seeds.dim;
    let mut dist = vec![f64::INFINITY; n];
    let mut seed = vec![u64::MAX; n];
    let mut found = vec![usize::MAX; n];
    if seeds.is_empty() {
        return (dist, seed);
    }
    for j in (0..n).filter(|&j| reached[j]) {
        let x = &coords[dim * j..dim * (j + 1)];
        let mut best = (f64::INFINITY, u64::MAX, usize::MAX);
        if let Some(k) = graph
            .entries(j)
            .map(|i| found[i])
            .find(|&k| k != usize::MAX)
        {
            best = (seeds.squared(x, k), seeds.ids[k], k);
        }
        seeds.search(x, 0, seeds.len(), 0, &mut best);
        dist[j] = best.0.sqrt();
        seed[j] = best.1;
        found[j] = best.2;
    }
    (dist, seed)
}

/// Marks in `reached` every node connected along the edges of `graph` to a
/// marked one; repeats after each `sync` (which may mark more nodes) while
/// it returns `true`.
pub fn connect(graph: &Csr, reached: &mut [bool], mut sync: impl FnMut(&mut [bool]) -> bool) {
    loop {
        let mut queue: Vec<usize> = (0..reached.len()).filter(|&i| reached[i]).collect();
        while let Some(i) = queue.pop() {
            for j in graph.entries(i) {
                if !std::mem::replace(&mut reached[j], true) {
                    queue.push(j);
                }
            }
        }
        if !sync(reached) {
            return;
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
