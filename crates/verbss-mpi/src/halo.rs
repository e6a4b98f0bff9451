//! Messages between ranks: the ghost layer's neighbour-to-neighbour exchange
//! and the few all-to-all steps of the setup.
//!
//! A rank *owns* some nodes and holds copies (*ghosts*) of the nodes of
//! other ranks that share a cell with its own. After the owner changes a
//! value, [`swap`] sends it to every rank that holds a ghost of it: one
//! message per neighbouring rank that has something to send, never a
//! global gather.

use crate::Comm;

/// Who holds copies of whose nodes: per neighbouring rank, the owned local
/// nodes it holds as ghosts (`send`) and the local ghosts it owns (`recv`),
/// both in increasing global number, so that the two sides list the same
/// nodes in the same order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Halo {
    /// The neighbouring ranks, increasing.
    pub ranks: Vec<i32>,
    /// Per neighbour: owned local nodes it holds as ghosts.
    pub send: Vec<Vec<u32>>,
    /// Per neighbour: local ghosts it owns.
    pub recv: Vec<Vec<u32>>,
}

impl Halo {
    /// Finds the lists from the owners of the local nodes: every rank tells
    /// each owner which of its nodes it holds as ghosts (one all-to-all of
    /// global numbers, once per mesh). `global` is increasing; `owner[i]` is
    /// the rank owning local node `i`.
    pub fn new(comm: &Comm, global: &[u64], owner: &[i32]) -> Halo {
        let size = comm.size() as usize;
        let rank = comm.rank();
        let mut wanted: Vec<Vec<u64>> = vec![Vec::new(); size];
        let mut recv_all: Vec<Vec<u32>> = vec![Vec::new(); size];
        for (i, (&g, &o)) in global.iter().zip(owner).enumerate() {
            if o != rank {
                wanted[o as usize].push(g);
                recv_all[o as usize].push(i as u32);
            }
        }
        let asked = comm.all_to_all(&wanted);
        let mut halo = Halo::default();
        for r in 0..size {
            if asked[r].is_empty() && recv_all[r].is_empty() {
                continue;
            }
            let send = asked[r]
                .iter()
                .map(|g| global.binary_search(g).expect("asked for an owned node") as u32)
                .collect();
            halo.ranks.push(r as i32);
            halo.send.push(send);
            halo.recv.push(std::mem::take(&mut recv_all[r]));
        }
        halo
    }

    /// Sends the `width` values of every listed owned node to its holders
    /// and overwrites the ghosts' values with their owners'.
    pub fn exchange(&self, comm: &Comm, data: &mut [f64], width: usize) {
        swap(comm, &self.ranks, &self.send, &self.recv, data, width);
    }
}

/// One exchange: for neighbour `k`, the `width` values of entries
/// `send[k]` of `data` go to rank `ranks[k]`, and what it sends comes into
/// entries `recv[k]`. Empty lists send nothing (both sides know them).
pub fn swap(
    comm: &Comm,
    ranks: &[i32],
    send: &[Vec<u32>],
    recv: &[Vec<u32>],
    data: &mut [f64],
    width: usize,
) {
    let out: Vec<Vec<f64>> = send
        .iter()
        .map(|list| {
            let mut buf = Vec::with_capacity(width * list.len());
            for &p in list {
                let p = p as usize;
                buf.extend_from_slice(&data[width * p..width * (p + 1)]);
            }
            buf
        })
        .collect();
    let mut incoming: Vec<Vec<f64>> = recv.iter().map(|l| vec![0.0; width * l.len()]).collect();
    comm.exchange(ranks, &out, &mut incoming);
    for (list, buf) in recv.iter().zip(&incoming) {
        for (m, &p) in list.iter().enumerate() {
            let p = p as usize;
            data[width * p..width * (p + 1)].copy_from_slice(&buf[width * m..width * (m + 1)]);
        }
    }
}
