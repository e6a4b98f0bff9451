//! The wall distances and the boundary layer's reach of the near-wall
//! treatments, on any set of nodes and cells: a whole mesh, or a rank's
//! part with its ghosts, where a `sync` closure between local passes makes
//! a walk global.
//!
//! * [`Seeds`] and [`nearest_seeds`]: every node's nearest seed in
//!   straight line, `min_s (|x_j − x_s|, id_s)` over the seeds of its
//!   connected part of the mesh (ties to the smaller seed number), found
//!   in a tree of the seeds' bounding boxes, up to a distance given per
//!   node. The answer is exact, so it depends neither on the order of the
//!   nodes nor on how the mesh is cut: a rank holding all seeds finds on
//!   its part what one process finds. [`connect`] marks the nodes
//!   connected to a seed, [`nearest_connected`] does both.
//! * [`reach`]: the nodes reached from the labelled ones through cells of
//!   aspect ratio at least [`super::ANISOTROPIC`], the boundary layer of
//!   the automatic rigid layer's thickness.

use crate::mesh::Cells;
use crate::topology::{self, Csr};

use super::{distance, ANISOTROPIC};

/// A leaf box's most seeds.
const LEAF: usize = 8;

/// Seed points, each with its number, in a tree of boxes: each box holds
/// the seeds `[lo, hi)` (in the tree's order) and is their bounding box;
/// a box of more than `LEAF` seeds is split in two halves at the median
/// of its longest side.
#[derive(Debug, Clone)]
pub struct Seeds {
    dim: usize,
    points: Vec<f64>,
    ids: Vec<u64>,
    boxes: Vec<SeedBox>,
}

/// A box of [`Seeds`]: its seeds, their bounds and its halves (none for a leaf).
#[derive(Debug, Clone)]
struct SeedBox {
    lo: usize,
    hi: usize,
    min: [f64; 3],
    max: [f64; 3],
    halves: Option<(usize, usize)>,
}

impl Seeds {
    /// The seeds at `points` (`dim` numbers each) numbered `ids`.
    pub fn new(dim: usize, points: &[f64], ids: &[u64]) -> Seeds {
        let mut order: Vec<usize> = (0..ids.len()).collect();
        let mut boxes = Vec::new();
        if !order.is_empty() {
            divide(dim, points, &mut order, 0, &mut boxes);
        }
        Seeds {
            dim,
            points: order
                .iter()
                .flat_map(|&k| &points[dim * k..dim * (k + 1)])
                .copied()
                .collect(),
            ids: order.iter().map(|&k| ids[k]).collect(),
            boxes,
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

    /// The squared distance from `x` to box `b`, summed as [`Seeds::squared`]
    /// sums: rounding is monotonic, so no seed in the box computes nearer.
    fn squared_to_box(&self, x: &[f64], b: &SeedBox) -> f64 {
        (0..self.dim)
            .map(|k| {
                let gap = (b.min[k] - x[k]).max(x[k] - b.max[k]).max(0.0);
                gap * gap
            })
            .sum()
    }

    /// Lowers `best` (squared distance, number, seed) to the smallest
    /// `(squared distance, number)` over the seeds of box `b`.
    fn search(&self, x: &[f64], b: usize, best: &mut (f64, u64, usize)) {
        let node = &self.boxes[b];
        let Some((first, second)) = node.halves else {
            for k in node.lo..node.hi {
                let d2 = self.squared(x, k);
                if (d2, self.ids[k]) < (best.0, best.1) {
                    *best = (d2, self.ids[k], k);
                }
            }
            return;
        };
        let mut halves = [first, second].map(|h| (self.squared_to_box(x, &self.boxes[h]), h));
        if halves[1].0 < halves[0].0 {
            halves.swap(0, 1);
        }
        // A seed at exactly the best distance may still win on its number.
        for (d2, h) in halves {
            if d2 <= best.0 {
                self.search(x, h, best);
            }
        }
    }
}

/// Pushes onto `boxes` the box of the seeds `order` (indices of `points`,
/// the slice starting at `lo` of the tree's order) and, below it, its
/// halves; returns its index.
fn divide(
    dim: usize,
    points: &[f64],
    order: &mut [usize],
    lo: usize,
    boxes: &mut Vec<SeedBox>,
) -> usize {
    let (mut min, mut max) = ([0.0; 3], [0.0; 3]);
    for k in 0..dim {
        let values = order.iter().map(|&i| points[dim * i + k]);
        min[k] = values.clone().fold(f64::INFINITY, f64::min);
        max[k] = values.fold(f64::NEG_INFINITY, f64::max);
    }
    let at = boxes.len();
    boxes.push(SeedBox {
        lo,
        hi: lo + order.len(),
        min,
        max,
        halves: None,
    });
    if order.len() > LEAF {
        let axis = (0..dim)
            .max_by(|&a, &b| (max[a] - min[a]).total_cmp(&(max[b] - min[b])))
            .unwrap_or(0);
        let mid = order.len() / 2;
        order.select_nth_unstable_by(mid, |&a, &b| {
            points[dim * a + axis].total_cmp(&points[dim * b + axis])
        });
        let (before, after) = order.split_at_mut(mid);
        let first = divide(dim, points, before, lo, boxes);
        let second = divide(dim, points, after, lo + mid, boxes);
        boxes[at].halves = Some((first, second));
    }
    at
}

/// For every node `j` with `limit[j] ≥ 0` (nodes at `coords`): the
/// distance to its nearest seed of `seeds` and that seed's number, where
/// that distance is at most `√limit[j]`; infinite and `u64::MAX` elsewhere.
/// A node starts its search from the seed of a neighbour in `graph`
/// already found, which bounds it.
pub fn nearest_seeds(
    seeds: &Seeds,
    graph: &Csr,
    coords: &[f64],
    limit: &[f64],
) -> (Vec<f64>, Vec<u64>) {
    let n = limit.len();
    let dim = seeds.dim;
    let mut dist = vec![f64::INFINITY; n];
    let mut seed = vec![u64::MAX; n];
    let mut found = vec![usize::MAX; n];
    if seeds.is_empty() {
        return (dist, seed);
    }
    for j in (0..n).filter(|&j| limit[j] >= 0.0) {
        let x = &coords[dim * j..dim * (j + 1)];
        let mut best = (limit[j], u64::MAX, usize::MAX);
        if let Some(k) = graph
            .entries(j)
            .map(|i| found[i])
            .find(|&k| k != usize::MAX)
        {
            let d2 = seeds.squared(x, k);
            if (d2, seeds.ids[k]) < (best.0, best.1) {
                best = (d2, seeds.ids[k], k);
            }
        }
        seeds.search(x, 0, &mut best);
        if best.2 != usize::MAX {
            dist[j] = best.0.sqrt();
            seed[j] = best.1;
            found[j] = best.2;
        }
    }
    (dist, seed)
}

/// [`nearest_seeds`] for the nodes connected along `graph` to the nodes
/// `marked` (the seeds' own, where the part holds them), each up to
/// `√limit(i)`; `sync` makes the connection global as [`connect`]'s.
pub fn nearest_connected(
    seeds: &Seeds,
    graph: &Csr,
    coords: &[f64],
    marked: &[usize],
    limit: impl Fn(usize) -> f64,
    sync: impl FnMut(&mut [bool]) -> bool,
) -> (Vec<f64>, Vec<u64>) {
    let mut reached = vec![false; graph.rows()];
    for &s in marked {
        reached[s] = true;
    }
    connect(graph, &mut reached, sync);
    let limit: Vec<f64> = (0..reached.len())
        .map(|i| if reached[i] { limit(i) } else { -1.0 })
        .collect();
    nearest_seeds(seeds, graph, coords, &limit)
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
    cells.local(c).edges(|a, b| {
        let l = distance(point(a), point(b));
        lo = lo.min(l);
        hi = hi.max(l);
    });
    hi / lo
}
