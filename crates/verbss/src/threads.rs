//! The worker threads of a run (the setting `threads`, 0: one per core):
//! one pool, shared by the springs' solve ([`crate::solve::Engine`]) and the
//! deformer's own parallel work (the blended rigid motion, the check of every
//! cell), so that `threads = 1` keeps a whole step on one core.
//!
//! Everything computed on it gives the same bits for any number of workers:
//! each node's (or cell's) result depends on nothing another worker writes,
//! and sums are taken in fixed chunks added in order ([`chunked_sums`]).
//! Over MPI ranks only pure computation runs on the workers; every
//! collective call stays on the calling thread.

use std::sync::Arc;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::solve::SUM_CHUNK;

/// A pool of worker threads, shared by cloning.
#[derive(Clone)]
pub struct Workers {
    /// The count asked for (0: one per core).
    threads: usize,
    pool: Arc<rayon::ThreadPool>,
}

impl std::fmt::Debug for Workers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Workers")
            .field("threads", &self.threads)
            .field("workers", &self.pool.current_num_threads())
            .finish()
    }
}

impl Workers {
    /// `threads` workers (0: one per core).
    pub fn new(threads: usize) -> Result<Workers> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| Error::InvalidSetting(format!("cannot start {threads} threads: {e}")))?;
        Ok(Workers {
            threads,
            pool: Arc::new(pool),
        })
    }

    /// The count asked for (0: one per core).
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// The pool.
    pub fn pool(&self) -> &rayon::ThreadPool {
        &self.pool
    }

    /// Runs `f` on the workers: its parallel iterators use them.
    pub fn install<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        self.pool.install(f)
    }
}

/// The `K` sums over `i` in `0..n` of `term(i)`, in parallel on the current
/// pool: each fixed chunk of `SUM_CHUNK` (1024) indices summed in order, then the
/// chunks' sums in order, so the bits do not depend on the number of threads.
pub fn chunked_sums<const K: usize>(n: usize, term: impl Fn(usize) -> [f64; K] + Sync) -> [f64; K] {
    let add = |mut a: [f64; K], b: [f64; K]| {
        for (x, y) in a.iter_mut().zip(b) {
            *x += y;
        }
        a
    };
    let chunks: Vec<[f64; K]> = (0..n.div_ceil(SUM_CHUNK))
        .into_par_iter()
        .map(|c| (c * SUM_CHUNK..n.min((c + 1) * SUM_CHUNK)).fold([0.0; K], |s, i| add(s, term(i))))
        .collect();
    chunks.into_iter().fold([0.0; K], add)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunked_sums_are_the_same_on_any_number_of_workers() {
        let n = 10 * SUM_CHUNK + 17;
        let term = |i: usize| {
            let x = (i as f64 * 0.37).sin() * 10f64.powi(i as i32 % 9 - 4);
            [x, x * x, 1.0]
        };
        let on = |threads| {
            Workers::new(threads)
                .unwrap()
                .install(|| chunked_sums(n, term))
        };
        let one = on(1);
        for threads in [2, 3] {
            assert_eq!(on(threads).map(f64::to_bits), one.map(f64::to_bits));
        }
        // The serial sum in the same chunks, and the count exactly.
        let serial = (0..n.div_ceil(SUM_CHUNK))
            .map(|c| {
                (c * SUM_CHUNK..n.min((c + 1) * SUM_CHUNK))
                    .map(|i| term(i)[1])
                    .sum::<f64>()
            })
            .sum::<f64>();
        assert_eq!(one[1].to_bits(), serial.to_bits());
        assert_eq!(one[2], n as f64);
    }
}
