//! Sums, maxima and ghost values over the processes that each hold a part
//! of a mesh: what a computation written once needs to give one process's
//! answer on any cut (docs/distributed.md). A process's local nodes are the
//! ones it owns and ghosts, copies of nodes another process owns; every
//! node is owned by exactly one process, so a sum over owned nodes,
//! summed over the processes, counts each node once.
//!
//! [`Whole`] is the single process holding the whole mesh: it owns every
//! node and has nothing to exchange.

use crate::error::{Error, Result};

/// The processes a mesh is cut between, seen from one of them (each
/// method but [`Collective::owns`] and [`Collective::processes`] is
/// collective: every process calls it, in the same order).
pub trait Collective {
    /// The number of processes.
    fn processes(&self) -> usize;
    /// Whether this process owns local node `node`.
    fn owns(&self, node: usize) -> bool;
    /// Each entry of `values` summed over the processes, in place.
    fn sum(&self, values: &mut [f64]);
    /// Each entry of `values` the largest over the processes, in place.
    fn max(&self, values: &mut [f64]);
    /// The ghosts' `width` values per local node set to their owners'.
    fn refresh(&self, values: &mut [f64], width: usize);
    /// Every process's `values` joined, in the order of the processes.
    fn gather(&self, values: &[f64]) -> Vec<f64>;

    /// Whether this process counts the local cell of nodes `cell` in the
    /// sums over cells: the one that owns its first node (each cell of
    /// the mesh is counted by exactly one process).
    fn counts(&self, cell: &[usize]) -> bool {
        self.owns(cell[0])
    }
}

/// `result` on every process where every process's is `Ok` (collective);
/// otherwise an error on every process: its own, or for a process whose
/// result was `Ok`, the lowest failing process's message
/// ([`Error::Reported`]). So that no process goes on to a collective call
/// the others have left.
pub fn agree<T>(on: &dyn Collective, result: Result<T>) -> Result<T> {
    if on.processes() == 1 {
        return result;
    }
    let text: Vec<f64> = match &result {
        Ok(_) => Vec::new(),
        Err(e) => e.to_string().bytes().map(f64::from).collect(),
    };
    let lengths = on.gather(&[text.len() as f64]);
    let Some(first) = lengths.iter().position(|&n| n > 0.0) else {
        return result;
    };
    let all = on.gather(&text);
    let Ok(_) = &result else {
        return result;
    };
    let start = lengths[..first].iter().sum::<f64>() as usize;
    let bytes: Vec<u8> = all[start..start + lengths[first] as usize]
        .iter()
        .map(|&b| b as u8)
        .collect();
    Err(Error::Reported(
        String::from_utf8_lossy(&bytes).into_owned(),
    ))
}

/// One process holding the whole mesh.
#[derive(Debug, Clone, Copy, Default)]
pub struct Whole;

impl Collective for Whole {
    fn processes(&self) -> usize {
        1
    }

    fn owns(&self, _: usize) -> bool {
        true
    }

    fn sum(&self, _: &mut [f64]) {}

    fn max(&self, _: &mut [f64]) {}

    fn refresh(&self, _: &mut [f64], _: usize) {}

    fn gather(&self, values: &[f64]) -> Vec<f64> {
        values.to_vec()
    }
}

/// The `sync` of a walk that only ever marks more nodes
/// (the near-wall treatments' walks): the ghosts' marks set to their
/// owners', saying whether the processes' owned marks grew since the last
/// call (at the first, whether there is any). On one process the walk is
/// whole after its first pass.
pub fn mark_sync(on: &dyn Collective) -> impl FnMut(&mut [bool]) -> bool + '_ {
    let mut last = 0.0;
    move |marks| {
        if on.processes() == 1 {
            return false;
        }
        let mut flat: Vec<f64> = marks.iter().map(|&x| f64::from(u8::from(x))).collect();
        on.refresh(&mut flat, 1);
        for (x, f) in marks.iter_mut().zip(&flat) {
            *x = *f == 1.0;
        }
        let mut total = [marks
            .iter()
            .enumerate()
            .filter(|&(i, &m)| m && on.owns(i))
            .count() as f64];
        on.sum(&mut total);
        std::mem::replace(&mut last, total[0]) != total[0]
    }
}

/// The sums over `0..n` of the `K` terms `term(i)` of this process, summed
/// over every process, the same to the last bit however the terms are
/// ordered or split between processes (collective): each term is cut to a
/// multiple of `2^-s` (towards zero), with `2^s` times the largest term of
/// its sum over all processes at most `2^60`, and the multiples are added
/// as integers, exactly. The cut is below `2^-60` of the largest term. A
/// sum with a term that is not finite is a plain sum.
pub fn exact_sums<const K: usize>(
    on: &dyn Collective,
    n: usize,
    term: impl Fn(usize) -> [f64; K],
) -> [f64; K] {
    let mut largest = [0.0f64; K];
    for i in 0..n {
        for (m, t) in largest.iter_mut().zip(term(i)) {
            *m = m.max(t.abs());
        }
    }
    on.max(&mut largest);
    if largest.iter().any(|m| !m.is_finite()) {
        let mut plain = [0.0; K];
        for i in 0..n {
            for (s, t) in plain.iter_mut().zip(term(i)) {
                *s += t;
            }
        }
        on.sum(&mut plain);
        return plain;
    }
    let up: [f64; K] = largest.map(|m| {
        if m > 0.0 {
            2f64.powi((60 - m.log2().ceil() as i32).clamp(-1000, 1000))
        } else {
            1.0
        }
    });
    let mut total = [0i128; K];
    for i in 0..n {
        for (k, t) in term(i).into_iter().enumerate() {
            total[k] += i128::from((t * up[k]) as i64);
        }
    }
    // Four 32-bit limbs each, the last signed: a limb summed over up to
    // 2^20 processes stays below 2^52, exact as a double.
    let mut limbs = vec![0.0; 4 * K];
    for (k, x) in total.iter().enumerate() {
        for j in 0..3 {
            limbs[4 * k + j] = ((x >> (32 * j)) & 0xffff_ffff) as f64;
        }
        limbs[4 * k + 3] = (x >> 96) as f64;
    }
    on.sum(&mut limbs);
    std::array::from_fn(|k| {
        let x: i128 = (0..4).map(|j| (limbs[4 * k + j] as i128) << (32 * j)).sum();
        x as f64 / up[k]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_sums_match_plain_sums_to_their_cut() {
        let terms: Vec<f64> = (0..1000)
            .map(|i| ((i as f64) * 0.37).sin() * 10f64.powi(i % 7 - 3))
            .collect();
        let plain: f64 = terms.iter().sum();
        let [exact, count] = exact_sums(&Whole, terms.len(), |i| [terms[i], 1.0]);
        assert!((exact - plain).abs() < 1e-12 * 1e3, "{exact} {plain}");
        assert_eq!(count, 1000.0);
        // Any order gives the same bits.
        let [reversed, _] = exact_sums(&Whole, terms.len(), |i| [terms[999 - i], 1.0]);
        assert_eq!(exact.to_bits(), reversed.to_bits());
        let [negative] = exact_sums(&Whole, 3, |i| [[-1.5, -2.25, 0.5][i]]);
        assert_eq!(negative, -3.25);
    }
}
