//! What one distributed sweep costs on a partition, counted without MPI.
//!
//! For `P` parts of a mesh (node owners), the engine's colours and the
//! unknown nodes, [`count`] finds per rank: owned unknowns, ghosts (nodes
//! of other ranks sharing a cell with an owned node), neighbouring ranks,
//! and per colour the owned unknowns swept, the messages sent (one per
//! neighbour that holds some of them as ghosts) and the values sent.
//!
//! [`Model::seconds`] turns the counts into the time of one sweep: the
//! colours are done one after the other and within a colour the slowest
//! rank sets the pace,
//!
//! ```text
//! T(P) = Σ_c max_r ( n_rc t + m_rc α + 8 D v_rc β ) + 2 α ⌈log₂ P⌉
//! ```
//!
//! with `n_rc` nodes swept, `m_rc` messages and `v_rc` values sent by rank
//! `r` in colour `c`, `t` the time per node update, `α` the latency of a
//! message, `β` the time per byte, and the eq.-8 all-reduce at the end.

use verbss::topology::Csr;

/// One rank's share of a sweep.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RankCost {
    /// Owned unknown nodes (updated by this rank).
    pub owned: usize,
    /// Ghost nodes (prescribed or unknown) of the ghost layer.
    pub ghosts: usize,
    /// Ranks it exchanges with.
    pub neighbours: usize,
    /// Messages it sends per sweep.
    pub messages: usize,
    /// Values (nodes) it sends per sweep.
    pub values: usize,
}

/// The counts of one sweep on one partition.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SweepCost {
    /// Per rank.
    pub ranks: Vec<RankCost>,
    /// Per colour and rank: (nodes swept, messages sent, values sent).
    pub colours: Vec<Vec<(usize, usize, usize)>>,
}

/// Counts one sweep for `parts` parts: `owner` per node, `colours` per node
/// (`u32::MAX` for prescribed nodes, which are never swept nor sent during
/// the sweeps), `graph` the node-coupling graph.
pub fn count(graph: &Csr, owner: &[i32], colours: &[u32], parts: usize) -> SweepCost {
    let n = graph.rows();
    let ncol = colours
        .iter()
        .filter(|&&c| c != u32::MAX)
        .map(|&c| c as usize + 1)
        .max()
        .unwrap_or(0);
    let mut ranks = vec![RankCost::default(); parts];
    let mut per_colour = vec![vec![(0usize, 0usize, 0usize); parts]; ncol];
    // Messages: distinct (colour, sender, receiver) with something to send.
    let mut links: Vec<(u32, i32, i32)> = Vec::new();
    let mut ghost_pairs: Vec<(i32, usize)> = Vec::new();
    let mut holders: Vec<i32> = Vec::new();
    for i in 0..n {
        let r = owner[i];
        holders.clear();
        holders.extend(graph.entries(i).map(|j| owner[j]).filter(|&s| s != r));
        holders.sort_unstable();
        holders.dedup();
        for &s in &holders {
            ghost_pairs.push((s, i));
        }
        if colours[i] == u32::MAX {
            continue;
        }
        let c = colours[i] as usize;
        ranks[r as usize].owned += 1;
        per_colour[c][r as usize].0 += 1;
        for &s in &holders {
            ranks[r as usize].values += 1;
            per_colour[c][r as usize].2 += 1;
            links.push((c as u32, r, s));
        }
    }
    for &(s, _) in &ghost_pairs {
        ranks[s as usize].ghosts += 1;
    }
    links.sort_unstable();
    links.dedup();
    let mut pairs: Vec<(i32, i32)> = Vec::new();
    for &(c, r, s) in &links {
        ranks[r as usize].messages += 1;
        per_colour[c as usize][r as usize].1 += 1;
        pairs.push((r.min(s), r.max(s)));
    }
    let mut all_pairs: Vec<(i32, i32)> = ghost_pairs
        .iter()
        .map(|&(s, i)| (s.min(owner[i]), s.max(owner[i])))
        .collect();
    all_pairs.sort_unstable();
    all_pairs.dedup();
    for &(a, b) in &all_pairs {
        ranks[a as usize].neighbours += 1;
        ranks[b as usize].neighbours += 1;
    }
    SweepCost {
        ranks,
        colours: per_colour,
    }
}

/// The machine of [`Model::seconds`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model {
    /// Seconds per node update `t` (measured on one rank).
    pub node: f64,
    /// Seconds of latency per message `α`.
    pub latency: f64,
    /// Seconds per byte `β`.
    pub per_byte: f64,
    /// Spatial dimension `D` (values of `8 D` bytes).
    pub dim: usize,
}

impl Model {
    /// The modelled seconds of one sweep (see the module documentation).
    pub fn seconds(&self, cost: &SweepCost) -> f64 {
        let parts = cost.ranks.len().max(1);
        let sweep: f64 = cost
            .colours
            .iter()
            .map(|ranks| {
                ranks
                    .iter()
                    .map(|&(nodes, messages, values)| {
                        nodes as f64 * self.node
                            + messages as f64 * self.latency
                            + (8 * self.dim * values) as f64 * self.per_byte
                    })
                    .fold(0.0, f64::max)
            })
            .sum();
        let reduce = if parts > 1 {
            2.0 * self.latency * (parts as f64).log2().ceil()
        } else {
            0.0
        };
        sweep + reduce
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path 0–1–2–3 cut in the middle, nodes 0 and 3 prescribed,
    /// colours 1: 0, 2: 1.
    #[test]
    fn a_cut_path_sends_one_value_each_way() {
        let graph = Csr::from_pairs(
            4,
            [(0, 1), (1, 0), (1, 2), (2, 1), (2, 3), (3, 2)].into_iter(),
        );
        let owner = [0, 0, 1, 1];
        let colours = [u32::MAX, 0, 1, u32::MAX];
        let cost = count(&graph, &owner, &colours, 2);
        assert_eq!(
            cost.ranks[0],
            RankCost {
                owned: 1,
                ghosts: 1,
                neighbours: 1,
                messages: 1,
                values: 1
            }
        );
        assert_eq!(cost.ranks[1].owned, 1);
        assert_eq!(
            cost.colours,
            vec![vec![(1, 1, 1), (0, 0, 0)], vec![(0, 0, 0), (1, 1, 1)]]
        );
        let model = Model {
            node: 1.0,
            latency: 10.0,
            per_byte: 0.5,
            dim: 2,
        };
        // Two colours of 1 + 10 + 16·0.5 each, and the all-reduce 2·10·1.
        assert_eq!(model.seconds(&cost), 2.0 * 19.0 + 20.0);
    }
}
