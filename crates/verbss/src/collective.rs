//! Sums, maxima and ghost values over the processes that each hold a part
//! of a mesh: what a computation written once needs to give one process's
//! answer on any cut (docs/distributed.md). A process's local nodes are the
//! ones it owns and ghosts, copies of nodes another process owns; every
//! node is owned by exactly one process, so a sum over owned nodes,
//! summed over the processes, counts each node once.
//!
//! [`Whole`] is the single process holding the whole mesh: it owns every
//! node and has nothing to exchange.

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
/// ([`crate::robust::spread::connect`]): the ghosts' marks set to their
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
