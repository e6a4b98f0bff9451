//! The ranks sharing a mesh, seen from one rank's part with its ghosts:
//! the sums, maxima, ghost refreshes and gathers that make the engine
//! written once for every domain ([`verbss::collective::Collective`]) give
//! one process's answer on every rank.

use verbss::collective::Collective;

use crate::halo::Halo;
use crate::Comm;

/// This rank's view of the ranks: its communicator, which of its part's
/// nodes it owns and the part's ghost exchange lists.
pub struct Ranks<'c> {
    comm: &'c Comm,
    rank: i32,
    owner: Vec<i32>,
    halo: Halo,
}

impl<'c> Ranks<'c> {
    /// The ranks of `comm` seen from the part whose node `i` rank
    /// `owner[i]` owns, with the ghost exchange lists `halo`.
    pub fn new(comm: &'c Comm, owner: Vec<i32>, halo: Halo) -> Ranks<'c> {
        Ranks {
            comm,
            rank: comm.rank(),
            owner,
            halo,
        }
    }

    /// The communicator.
    pub fn comm(&self) -> &'c Comm {
        self.comm
    }
}

impl Collective for Ranks<'_> {
    fn processes(&self) -> usize {
        self.comm.size() as usize
    }

    fn owns(&self, node: usize) -> bool {
        self.owner[node] == self.rank
    }

    fn sum(&self, values: &mut [f64]) {
        let sums = self.comm.sums(values);
        values.copy_from_slice(&sums);
    }

    fn max(&self, values: &mut [f64]) {
        let largest = self.comm.maxs(values);
        values.copy_from_slice(&largest);
    }

    fn refresh(&self, values: &mut [f64], width: usize) {
        self.halo.exchange(self.comm, values, width);
    }

    fn gather(&self, values: &[f64]) -> Vec<f64> {
        self.comm.all_gather(values).concat()
    }
}
