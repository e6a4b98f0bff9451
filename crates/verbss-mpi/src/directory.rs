//! The directory of global node numbers: node `g` has its directory rank
//! `g mod P`, which holds what the other ranks need to know of it (its
//! owner, its position in a file, its coordinates).

use crate::Comm;

/// Asks the directory rank of each of `nodes` for `answer(node)`
/// (collective): every rank answers the requests for its own nodes. The
/// answers in the order of `nodes`.
pub fn ask(comm: &Comm, nodes: &[u64], answer: impl Fn(u64) -> Vec<u64>) -> Vec<Vec<u64>> {
    let size = comm.size() as usize;
    let directory = |g: u64| (g % size as u64) as usize;
    let mut requests: Vec<Vec<u64>> = vec![Vec::new(); size];
    for &g in nodes {
        requests[directory(g)].push(g);
    }
    let asked = comm.all_to_all(&requests);
    // Each answer as its length, then its values.
    let replies: Vec<Vec<u64>> = asked
        .iter()
        .map(|list| {
            list.iter()
                .flat_map(|&g| {
                    let a = answer(g);
                    std::iter::once(a.len() as u64).chain(a)
                })
                .collect()
        })
        .collect();
    let replies = comm.all_to_all(&replies);
    let mut at = vec![0usize; size];
    nodes
        .iter()
        .map(|&g| {
            let d = directory(g);
            let n = replies[d][at[d]] as usize;
            let a = replies[d][at[d] + 1..at[d] + 1 + n].to_vec();
            at[d] += 1 + n;
            a
        })
        .collect()
}
