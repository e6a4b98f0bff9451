//! The distances of the blend's angle weight (docs/method.md, "Blended
//! rigid motion"): each node's nearest seed in straight line (the nearest
//! of a body's held nodes, or of the other prescribed nodes) is found once,
//! exactly, on the input mesh ([`crate::near_wall::spread::nearest_seeds`],
//! ties to the smaller node number); every increment then starts each node
//! from its last seed, measured where both are now, and lets it take a
//! neighbour's seed while that is nearer, in rounds that each read the
//! last round's seeds. After a small move few nodes change, so that costs
//! about one pass over the edges, and the answer depends neither on the
//! order of the nodes nor on how the mesh is cut between processes: on the
//! same coordinates every process finds one process's distances on its
//! part (the rounds choose between equally near nodes by the coordinates'
//! last bits, so those must be the same: docs/distributed.md).

use rayon::prelude::*;

use crate::collective::{mark_sync, Collective};
use crate::near_wall::spread::nearest_connected;
use crate::near_wall::Seeds;
use crate::threads::Workers;
use crate::topology::Csr;

/// No seed is connected to the node.
const NONE: u32 = u32::MAX;
/// The node is in the set, away from its edge: at distance 0.
const INSIDE: u32 = u32::MAX - 1;

/// The nearest seed of every local node, as a slot of the seeds of all
/// processes.
pub(super) struct Nearest {
    dim: usize,
    /// Per local node its seed's slot ([`NONE`]: no seed is connected).
    slot: Vec<u32>,
    /// The seeds this process owns: local node and slot.
    owned: Vec<(usize, u32)>,
    /// The seeds of all processes.
    count: usize,
    /// Each slot's node number.
    numbers: Vec<u64>,
}

impl Nearest {
    /// The nearest node of the set `set` (local nodes, every process's
    /// together, `on`; collective) to each local node at `coords`,
    /// connected along `graph`, the nodes numbered `ids` (the same number
    /// for a node on every process). Only the set's nodes on its edge,
    /// with a neighbour outside it, are seeds: the others are at distance
    /// 0, and no node outside is nearer to them, so the seeds every
    /// process holds grow with the set's surface, not its volume.
    pub(super) fn new(
        on: &dyn Collective,
        graph: &Csr,
        dim: usize,
        coords: &[f64],
        ids: &[u64],
        set: &[usize],
    ) -> Nearest {
        let mut inside = vec![false; graph.rows()];
        for &i in set {
            inside[i] = true;
        }
        // The owned nodes hold every neighbour: they know their edge.
        let mine: Vec<usize> = set
            .iter()
            .copied()
            .filter(|&s| on.owns(s) && graph.entries(s).any(|j| !inside[j]))
            .collect();
        let points: Vec<f64> = mine
            .iter()
            .flat_map(|&s| &coords[dim * s..dim * (s + 1)])
            .copied()
            .collect();
        // Node numbers below 2^53 travel exactly as doubles.
        let numbers: Vec<f64> = mine.iter().map(|&s| ids[s] as f64).collect();
        let numbers: Vec<u64> = on.gather(&numbers).iter().map(|&x| x as u64).collect();
        let all = Seeds::new(dim, &on.gather(&points), &numbers);
        let infinite = |_| f64::INFINITY;
        let (_, nearest) = nearest_connected(&all, graph, coords, &mine, infinite, mark_sync(on));
        let mut by_number: Vec<(u64, u32)> = numbers
            .iter()
            .enumerate()
            .map(|(k, &x)| (x, k as u32))
            .collect();
        by_number.sort_unstable();
        let slot_of = |x: u64| {
            by_number
                .binary_search_by_key(&x, |p| p.0)
                .map_or(NONE, |k| by_number[k].1)
        };
        let edge: Vec<u32> = nearest.iter().map(|&x| slot_of(x)).collect();
        Nearest {
            dim,
            slot: (0..edge.len())
                .map(|i| match edge[i] {
                    k if inside[i] && k != NONE && numbers[k as usize] != ids[i] => INSIDE,
                    _ if inside[i] && edge[i] == NONE => INSIDE,
                    k => k,
                })
                .collect(),
            owned: mine.iter().map(|&s| (s, slot_of(ids[s]))).collect(),
            count: numbers.len(),
            numbers,
        }
    }

    /// Every local node's distance to its nearest seed at `coords`
    /// (collective; infinite where no seed is connected): each node starts
    /// from its last seed and takes its neighbours' (along `graph`) while
    /// one is nearer, ties to the smaller number, in rounds that read the
    /// last round's seeds, until no node changes. Each round's nodes are
    /// looked at on `workers`, each on its own: the same answer on any number.
    pub(super) fn distances(
        &mut self,
        on: &dyn Collective,
        graph: &Csr,
        coords: &[f64],
        workers: &Workers,
    ) -> Vec<f64> {
        let dim = self.dim;
        let mut at = vec![0.0; dim * self.count];
        for &(i, k) in &self.owned {
            let k = k as usize;
            at[dim * k..dim * (k + 1)].copy_from_slice(&coords[dim * i..dim * (i + 1)]);
        }
        on.sum(&mut at);
        let to = |i: usize, k: u32| -> (f64, u64) {
            match k {
                NONE => return (f64::INFINITY, u64::MAX),
                INSIDE => return (0.0, 0),
                _ => {}
            }
            let k = k as usize;
            let squared = coords[dim * i..dim * (i + 1)]
                .iter()
                .zip(&at[dim * k..dim * (k + 1)])
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>();
            (squared, self.numbers[k])
        };
        let n = self.slot.len();
        let mut best: Vec<(f64, u64)> = workers.install(|| {
            (0..n)
                .into_par_iter()
                .map(|i| to(i, self.slot[i]))
                .collect()
        });
        let mut active: Vec<usize> = (0..n).collect();
        let mut seen = vec![false; n];
        loop {
            let (slot, best_now) = (&self.slot, &best);
            let changed: Vec<(usize, u32, (f64, u64))> = workers.install(|| {
                active
                    .par_iter()
                    .filter_map(|&j| {
                        let mut found = (best_now[j], NONE);
                        for i in graph.entries(j).filter(|&i| slot[i] != INSIDE) {
                            let candidate = to(j, slot[i]);
                            if candidate < found.0 {
                                found = (candidate, slot[i]);
                            }
                        }
                        (found.1 != NONE).then_some((j, found.1, found.0))
                    })
                    .collect()
            });
            for &(j, k, d) in &changed {
                self.slot[j] = k;
                best[j] = d;
            }
            let mut moved: Vec<usize> = changed.iter().map(|c| c.0).collect();
            if on.processes() > 1 {
                let mut slots: Vec<f64> = self.slot.iter().map(|&k| f64::from(k)).collect();
                on.refresh(&mut slots, 1);
                for (i, &k) in slots.iter().enumerate() {
                    if k as u32 != self.slot[i] {
                        self.slot[i] = k as u32;
                        best[i] = to(i, self.slot[i]);
                        moved.push(i);
                    }
                }
            }
            let mut count = [moved.iter().filter(|&&i| on.owns(i)).count() as f64];
            on.sum(&mut count);
            if count[0] == 0.0 {
                break;
            }
            active.clear();
            for &i in &moved {
                for j in graph.entries(i) {
                    if !std::mem::replace(&mut seen[j], true) {
                        active.push(j);
                    }
                }
            }
            for &j in &active {
                seen[j] = false;
            }
        }
        workers.install(|| best.par_iter().map(|b| b.0.sqrt()).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collective::Whole;
    use crate::mesh::samples::square_of_triangles;
    use crate::topology::edge_graph;

    /// The distance from node `i` to the nearest of `seeds`, by brute force.
    fn brute(coords: &[f64], seeds: &[usize], i: usize) -> f64 {
        seeds
            .iter()
            .map(|&s| {
                ((coords[2 * i] - coords[2 * s]).powi(2)
                    + (coords[2 * i + 1] - coords[2 * s + 1]).powi(2))
                .sqrt()
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_nearest_seed_is_exact_on_the_input_and_followed_after_a_move() {
        let mesh = square_of_triangles(12);
        let graph = edge_graph(&mesh.cells, mesh.node_count());
        // The seeds: the bottom side and the node nearest the centre.
        let mut seeds: Vec<usize> = (0..mesh.node_count())
            .filter(|&i| mesh.point(i)[1] == 0.0)
            .collect();
        seeds.push(6 * 13 + 6);
        let mut moved = mesh.coords.clone();
        moved[2 * (6 * 13 + 6)] -= 0.3;
        // The distances on the input and after the move, on `threads` workers.
        let on = |threads: usize| {
            let workers = Workers::new(threads).unwrap();
            let mut nearest =
                Nearest::new(&Whole, &graph, 2, &mesh.coords, &mesh.node_tags, &seeds);
            let input = nearest.distances(&Whole, &graph, &mesh.coords, &workers);
            (input, nearest.distances(&Whole, &graph, &moved, &workers))
        };
        let (d, after) = on(1);
        for threads in [2, 3] {
            assert_eq!(on(threads), (d.clone(), after.clone()));
        }
        for (i, &di) in d.iter().enumerate() {
            assert_eq!(di, brute(&mesh.coords, &seeds, i), "node {i}");
        }
        // The centre seed swept to the left: the nodes it leaves find the
        // bottom side or its new place, each at a distance to a seed no
        // nearer than the nearest.
        for (i, &di) in after.iter().enumerate() {
            let exact = brute(&moved, &seeds, i);
            assert!(di >= exact && di <= exact + 0.3, "node {i}: {di} {exact}");
        }
        assert_eq!(after[6 * 13 + 6], 0.0);
        assert_eq!(after[6 * 13 + 2], brute(&moved, &seeds, 6 * 13 + 2));
    }
}
