//! The crate's only `unsafe` code: safe wrappers of the MPI and METIS calls
//! of `src/shim.c`, which `build.rs` compiles against the MPI and METIS it
//! found.
//!
//! Every wrapper passes buffers whose lengths it has checked against the
//! counts it hands to MPI or METIS, and waits for each non-blocking message
//! before its buffers can be touched again. Errors of MPI calls are fatal
//! (MPI's default error handler aborts the job; a status that still comes
//! back is a panic that names the call).

use std::ffi::c_int;
use std::marker::PhantomData;

mod ffi {
    use std::ffi::{c_int, c_void};

    extern "C" {
        pub fn verbss_mpi_init() -> c_int;
        pub fn verbss_mpi_finalize() -> c_int;
        pub fn verbss_mpi_state() -> c_int;
        pub fn verbss_mpi_world() -> c_int;
        pub fn verbss_mpi_valid(comm: c_int) -> c_int;
        pub fn verbss_mpi_rank(comm: c_int, rank: *mut c_int) -> c_int;
        pub fn verbss_mpi_size(comm: c_int, size: *mut c_int) -> c_int;
        pub fn verbss_mpi_barrier(comm: c_int) -> c_int;
        pub fn verbss_mpi_allreduce(
            comm: c_int,
            input: *const c_void,
            output: *mut c_void,
            count: c_int,
            kind: c_int,
            op: c_int,
        ) -> c_int;
        pub fn verbss_mpi_bcast(
            comm: c_int,
            data: *mut c_void,
            count: c_int,
            kind: c_int,
            root: c_int,
        ) -> c_int;
        pub fn verbss_mpi_alltoall_int(comm: c_int, send: *const c_int, recv: *mut c_int) -> c_int;
        pub fn verbss_mpi_alltoallv(
            comm: c_int,
            send: *const c_void,
            scounts: *const c_int,
            sdispls: *const c_int,
            recv: *mut c_void,
            rcounts: *const c_int,
            rdispls: *const c_int,
            kind: c_int,
        ) -> c_int;
        pub fn verbss_mpi_allgather_int(comm: c_int, value: c_int, all: *mut c_int) -> c_int;
        pub fn verbss_mpi_allgatherv(
            comm: c_int,
            send: *const c_void,
            count: c_int,
            recv: *mut c_void,
            counts: *const c_int,
            displs: *const c_int,
            kind: c_int,
        ) -> c_int;
        pub fn verbss_mpi_exchange(
            comm: c_int,
            n: c_int,
            ranks: *const c_int,
            send: *const *const f64,
            send_len: *const c_int,
            recv: *const *mut f64,
            recv_len: *const c_int,
        ) -> c_int;
        #[cfg(with_ptscotch)]
        pub fn verbss_scotch_part(
            comm: c_int,
            n: usize,
            offsets: *const u64,
            targets: *const u64,
            vertices: u64,
            parts: c_int,
            part: *mut i32,
        ) -> c_int;
        pub fn verbss_metis_idx_bits() -> c_int;
        pub fn verbss_metis_part_kway(
            n: usize,
            xadj: *const usize,
            adjncy: *const usize,
            nparts: usize,
            part: *mut i32,
        ) -> c_int;
    }
}

/// Panics with the name of the MPI call when its status is not `MPI_SUCCESS`.
fn check(status: c_int, call: &str) {
    assert!(status == 0, "{call} failed with MPI error code {status}");
}

/// MPI itself: [`Mpi::init`] initialises it, dropping the value finalises it.
pub struct Mpi {
    _not_send: PhantomData<*const ()>,
}

impl Mpi {
    /// Initialises MPI (`MPI_Init_thread`, `MPI_THREAD_SINGLE`); `None` when
    /// it was initialised before (by the flow solver: use [`Comm::world`]
    /// or [`Comm::from_fortran`] then), finalised or not.
    pub fn init() -> Option<Mpi> {
        // SAFETY: plain calls without arguments; the state check keeps
        // MPI_Init_thread from running twice.
        unsafe {
            if ffi::verbss_mpi_state() != 0 {
                return None;
            }
            check(ffi::verbss_mpi_init(), "MPI_Init_thread");
        }
        Some(Mpi {
            _not_send: PhantomData,
        })
    }

    /// `MPI_COMM_WORLD`.
    pub fn world(&self) -> Comm {
        Comm::world()
    }
}

impl Drop for Mpi {
    fn drop(&mut self) {
        // SAFETY: a call without arguments, once, by the value that initialised MPI.
        check(unsafe { ffi::verbss_mpi_finalize() }, "MPI_Finalize");
    }
}

/// An MPI communicator, held as its Fortran handle (`MPI_Fint`), which
/// every MPI binding can give (`MPI_Comm_c2f(comm)` in C, the integer
/// itself in Fortran, `comm.py2f()` in mpi4py), whatever the MPI
/// implementation's C handle type is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Comm {
    handle: c_int,
    _not_send: PhantomData<*const ()>,
}

/// Element types MPI can carry (`u8`, `i32`, `u32`, `u64`, `f64`).
pub trait Scalar: Copy + Default + sealed::Sealed {
    /// The code of the type in `src/shim.c`.
    #[doc(hidden)]
    const CODE: c_int;
}

mod sealed {
    pub trait Sealed {}
}

macro_rules! scalar {
    ($($t:ty = $code:expr),*) => {$(
        impl sealed::Sealed for $t {}
        impl Scalar for $t {
            const CODE: c_int = $code;
        }
    )*};
}

scalar!(u8 = 0, i32 = 1, u32 = 2, u64 = 3, f64 = 4);

/// `count` as MPI's `int`.
fn count(n: usize) -> c_int {
    c_int::try_from(n).expect("a message longer than MPI's int count")
}

/// The sum of `counts` (each ≥ 0, as MPI gives them).
fn total(counts: &[c_int]) -> usize {
    counts
        .iter()
        .map(|&c| usize::try_from(c).expect("a count ≥ 0"))
        .sum()
}

/// `all` cut into consecutive lists of `counts` values.
fn split<T: Copy>(all: &[T], counts: &[c_int]) -> Vec<Vec<T>> {
    let mut at = 0;
    counts
        .iter()
        .map(|&c| {
            let list = all[at..at + c as usize].to_vec();
            at += c as usize;
            list
        })
        .collect()
}

/// Exclusive prefix sums of `counts`.
fn displacements(counts: &[c_int]) -> Vec<c_int> {
    counts
        .iter()
        .scan(0, |acc, &c| {
            let d = *acc;
            *acc = c_int::checked_add(*acc, c).expect("messages longer than MPI's int count");
            Some(d)
        })
        .collect()
}

/// Panics unless MPI is initialised and not finalised.
fn assert_active() {
    // SAFETY: MPI_Initialized and MPI_Finalized may be called at any time.
    let active = unsafe { ffi::verbss_mpi_state() } == 1;
    assert!(
        active,
        "MPI is not initialised (verbss_mpi::Mpi::init or MPI_Init first) or already finalised"
    );
}

impl Comm {
    fn new(handle: c_int) -> Comm {
        Comm {
            handle,
            _not_send: PhantomData,
        }
    }

    /// `MPI_COMM_WORLD`. Panics when MPI is not initialised.
    pub fn world() -> Comm {
        assert_active();
        // SAFETY: MPI is initialised.
        Comm::new(unsafe { ffi::verbss_mpi_world() })
    }

    /// The communicator of a Fortran handle (`MPI_Fint`; from C,
    /// `MPI_Comm_c2f(comm)`); `None` for `MPI_COMM_NULL` or a handle MPI
    /// does not know. Panics when MPI is not initialised.
    pub fn from_fortran(handle: i32) -> Option<Comm> {
        assert_active();
        // SAFETY: MPI is initialised; MPI_Comm_f2c takes any integer.
        (unsafe { ffi::verbss_mpi_valid(handle) } != 0).then(|| Comm::new(handle))
    }

    /// The Fortran handle (`MPI_Fint`).
    pub fn fortran(&self) -> i32 {
        self.handle
    }

    /// This process's rank.
    pub fn rank(&self) -> i32 {
        let mut rank = 0;
        // SAFETY: one int written.
        check(
            unsafe { ffi::verbss_mpi_rank(self.handle, &mut rank) },
            "MPI_Comm_rank",
        );
        rank
    }

    /// The number of ranks.
    pub fn size(&self) -> i32 {
        let mut size = 0;
        // SAFETY: one int written.
        check(
            unsafe { ffi::verbss_mpi_size(self.handle, &mut size) },
            "MPI_Comm_size",
        );
        size
    }

    /// Waits for every rank (collective).
    pub fn barrier(&self) {
        // SAFETY: no buffers.
        check(
            unsafe { ffi::verbss_mpi_barrier(self.handle) },
            "MPI_Barrier",
        );
    }

    /// Each of `values` reduced over the ranks by `op` (0 sum, 1 max, 2 min).
    fn reduce<T: Scalar>(&self, values: &[T], op: c_int) -> Vec<T> {
        let mut out = vec![T::default(); values.len()];
        if values.is_empty() {
            return out;
        }
        // SAFETY: values.len() values of type T read and as many written.
        check(
            unsafe {
                ffi::verbss_mpi_allreduce(
                    self.handle,
                    values.as_ptr().cast(),
                    out.as_mut_ptr().cast(),
                    count(values.len()),
                    T::CODE,
                    op,
                )
            },
            "MPI_Allreduce",
        );
        out
    }

    /// The sum of `value` over the ranks (collective).
    pub fn sum<T: Scalar>(&self, value: T) -> T {
        self.reduce(&[value], 0)[0]
    }

    /// The sums over the ranks of each of `values`, of the same length on
    /// every rank (collective).
    pub fn sums<T: Scalar>(&self, values: &[T]) -> Vec<T> {
        self.reduce(values, 0)
    }

    /// The largest `value` of the ranks (collective).
    pub fn max<T: Scalar>(&self, value: T) -> T {
        self.reduce(&[value], 1)[0]
    }

    /// The largest over the ranks of each of `values`, of the same length
    /// on every rank (collective).
    pub fn maxs<T: Scalar>(&self, values: &[T]) -> Vec<T> {
        self.reduce(values, 1)
    }

    /// The smallest `value` of the ranks (collective).
    pub fn min<T: Scalar>(&self, value: T) -> T {
        self.reduce(&[value], 2)[0]
    }

    /// The smallest over the ranks of each of `values`, of the same length
    /// on every rank (collective).
    pub fn mins<T: Scalar>(&self, values: &[T]) -> Vec<T> {
        self.reduce(values, 2)
    }

    /// Rank `root`'s `data` into every rank's `data`, of the same length
    /// on every rank (collective).
    pub fn broadcast<T: Scalar>(&self, root: i32, data: &mut [T]) {
        // SAFETY: data.len() values of type T.
        check(
            unsafe {
                ffi::verbss_mpi_bcast(
                    self.handle,
                    data.as_mut_ptr().cast(),
                    count(data.len()),
                    T::CODE,
                    root,
                )
            },
            "MPI_Bcast",
        );
    }

    /// All-to-all of lists: `out[r]` goes to rank `r` (one list per rank);
    /// returns the list each rank sent here, in rank order (collective).
    pub fn all_to_all<T: Scalar>(&self, out: &[Vec<T>]) -> Vec<Vec<T>> {
        let size = self.size() as usize;
        assert_eq!(out.len(), size, "one list per rank");
        let send_counts: Vec<c_int> = out.iter().map(|v| count(v.len())).collect();
        let send: Vec<T> = out.iter().flatten().copied().collect();
        let mut recv_counts = vec![0; size];
        // SAFETY: `size` ints read and written.
        check(
            unsafe {
                ffi::verbss_mpi_alltoall_int(
                    self.handle,
                    send_counts.as_ptr(),
                    recv_counts.as_mut_ptr(),
                )
            },
            "MPI_Alltoall",
        );
        let sdispls = displacements(&send_counts);
        let rdispls = displacements(&recv_counts);
        let mut recv = vec![T::default(); total(&recv_counts)];
        // SAFETY: `send` is the concatenation of the counted lists; `recv`
        // is sized from its counts and displacements.
        check(
            unsafe {
                ffi::verbss_mpi_alltoallv(
                    self.handle,
                    send.as_ptr().cast(),
                    send_counts.as_ptr(),
                    sdispls.as_ptr(),
                    recv.as_mut_ptr().cast(),
                    recv_counts.as_ptr(),
                    rdispls.as_ptr(),
                    T::CODE,
                )
            },
            "MPI_Alltoallv",
        );
        split(&recv, &recv_counts)
    }

    /// Every rank's list, in rank order, on every rank (collective).
    pub fn all_gather<T: Scalar>(&self, mine: &[T]) -> Vec<Vec<T>> {
        let size = self.size() as usize;
        let mut counts = vec![0; size];
        // SAFETY: one int read, `size` written.
        check(
            unsafe {
                ffi::verbss_mpi_allgather_int(self.handle, count(mine.len()), counts.as_mut_ptr())
            },
            "MPI_Allgather",
        );
        if total(&counts) == 0 {
            // Two empty buffers share one dangling address, which MPI
            // refuses as a send buffer that is also the receive buffer.
            return vec![Vec::new(); size];
        }
        let displs = displacements(&counts);
        let mut all = vec![T::default(); total(&counts)];
        // SAFETY: `mine` is read whole; `all` is sized from the counts and
        // displacements.
        check(
            unsafe {
                ffi::verbss_mpi_allgatherv(
                    self.handle,
                    mine.as_ptr().cast(),
                    count(mine.len()),
                    all.as_mut_ptr().cast(),
                    counts.as_ptr(),
                    displs.as_ptr(),
                    T::CODE,
                )
            },
            "MPI_Allgatherv",
        );
        split(&all, &counts)
    }

    /// Neighbour to neighbour: `send[k]` goes to rank `ranks[k]` and what
    /// it sends comes into `recv[k]` (whose length both sides know); empty
    /// lists post nothing. Returns when every message is done.
    pub fn exchange(&self, ranks: &[i32], send: &[Vec<f64>], recv: &mut [Vec<f64>]) {
        let n = ranks.len();
        assert!(send.len() == n && recv.len() == n, "one list per neighbour");
        let send_len: Vec<c_int> = send.iter().map(|b| count(b.len())).collect();
        let recv_len: Vec<c_int> = recv.iter().map(|b| count(b.len())).collect();
        let send_ptr: Vec<*const f64> = send.iter().map(|b| b.as_ptr()).collect();
        let recv_ptr: Vec<*mut f64> = recv.iter_mut().map(|b| b.as_mut_ptr()).collect();
        // SAFETY: each pointer has the length beside it; the buffers stay
        // borrowed until every request is waited for, inside the call.
        check(
            unsafe {
                ffi::verbss_mpi_exchange(
                    self.handle,
                    count(n),
                    ranks.as_ptr(),
                    send_ptr.as_ptr(),
                    send_len.as_ptr(),
                    recv_ptr.as_ptr(),
                    recv_len.as_ptr(),
                )
            },
            "a neighbour exchange (MPI_Isend, MPI_Irecv, MPI_Waitall)",
        );
    }
}

/// Why PT-Scotch could not partition a distributed graph (the same on every rank).
#[cfg(with_ptscotch)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ScotchError {
    /// A number beyond PT-Scotch's index type.
    TooLarge,
    /// PT-Scotch failed (it said why on stderr).
    Failed,
    /// Out of memory.
    Memory,
}

#[cfg(with_ptscotch)]
impl Comm {
    /// PT-Scotch's cut of the distributed graph into `parts` parts
    /// (collective; `src/scotch.c`): this rank's `offsets.len() − 1`
    /// vertices are numbered after the lower ranks' ones, local vertex `i`
    /// has the neighbours `targets[offsets[i]..offsets[i + 1]]` (global
    /// numbers below `vertices`, the graph symmetric without self loops).
    /// Deterministic: the same graph on the same ranks gives the same parts.
    /// The part of each local vertex.
    pub(crate) fn scotch_part(
        &self,
        offsets: &[u64],
        targets: &[u64],
        vertices: u64,
        parts: usize,
    ) -> Result<Vec<i32>, ScotchError> {
        assert!(!offsets.is_empty(), "one offset per vertex, plus the end");
        let n = offsets.len() - 1;
        assert_eq!(
            offsets[n],
            targets.len() as u64,
            "the offsets end at the targets' end"
        );
        let parts = c_int::try_from(parts).map_err(|_| ScotchError::TooLarge)?;
        let mut part = vec![0i32; n];
        // SAFETY: `offsets` has n + 1 entries ending at `targets.len()`,
        // `part` n; scotch.c checks every number against SCOTCH_Num.
        let status = unsafe {
            ffi::verbss_scotch_part(
                self.handle,
                n,
                offsets.as_ptr(),
                targets.as_ptr(),
                vertices,
                parts,
                part.as_mut_ptr(),
            )
        };
        match status {
            0 => Ok(part),
            1 => Err(ScotchError::TooLarge),
            3 => Err(ScotchError::Memory),
            _ => Err(ScotchError::Failed),
        }
    }
}

/// Why METIS could not partition a graph.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MetisError {
    /// A number beyond METIS's index type (of this many bits).
    TooLarge(u32),
    /// METIS's status: `METIS_ERROR_INPUT`, `_MEMORY` or `METIS_ERROR`.
    Status(i32),
}

/// METIS k-way partition of the CSR graph (`offsets`, `targets`: symmetric,
/// no self loops, targets below `offsets.len() − 1`) into `parts ≥ 2` parts
/// with METIS's default options and the seed 1: the part of each row.
pub(crate) fn part_kway(
    offsets: &[usize],
    targets: &[usize],
    parts: usize,
) -> Result<Vec<i32>, MetisError> {
    assert!(!offsets.is_empty(), "one offset per row, plus the end");
    let n = offsets.len() - 1;
    assert_eq!(
        offsets[n],
        targets.len(),
        "the offsets end at the targets' end"
    );
    assert!(targets.iter().all(|&t| t < n), "a target beyond the rows");
    // SAFETY: no arguments.
    let bits = unsafe { ffi::verbss_metis_idx_bits() } as u32;
    let limit = if bits >= 64 {
        i64::MAX as usize
    } else {
        (1usize << (bits - 1)) - 1
    };
    if targets.len() > limit || parts > limit.min(i32::MAX as usize) {
        return Err(MetisError::TooLarge(bits));
    }
    let mut part = vec![0i32; n];
    // SAFETY: `offsets` has n + 1 entries, `targets` offsets[n], `part` n;
    // every number fits idx_t (checked above).
    let status = unsafe {
        ffi::verbss_metis_part_kway(
            n,
            offsets.as_ptr(),
            targets.as_ptr(),
            parts,
            part.as_mut_ptr(),
        )
    };
    match status {
        1 => Ok(part),
        s => Err(MetisError::Status(s)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every wrapper on one process (MPI's singleton start, no mpirun).
    #[test]
    fn the_wrappers_on_one_rank() {
        let mpi = Mpi::init().expect("MPI is not initialised yet");
        assert!(Mpi::init().is_none(), "MPI is initialised once");
        let world = mpi.world();
        assert_eq!((world.rank(), world.size()), (0, 1));
        assert_eq!(Comm::from_fortran(world.fortran()), Some(world));
        assert_eq!(world.sum(2.5f64), 2.5);
        assert_eq!(world.max(7u8), 7);
        assert_eq!(world.max(-3i32), -3);
        assert_eq!(world.sum(u64::MAX), u64::MAX);
        assert_eq!(world.max(9u32), 9);
        assert_eq!(world.min(-1.5f64), -1.5);
        assert_eq!(world.sums(&[1u64, 2, 3]), [1, 2, 3]);
        assert_eq!(world.sums::<u64>(&[]), Vec::<u64>::new());
        let mut data = [1, 2, 3i32];
        world.broadcast(0, &mut data);
        assert_eq!(data, [1, 2, 3]);
        assert_eq!(world.all_to_all(&[vec![4u64, 5]]), [vec![4u64, 5]]);
        assert_eq!(world.all_gather(&[1.5f64, -2.0]), [vec![1.5, -2.0]]);
        assert_eq!(world.all_gather::<u8>(&[]), [Vec::<u8>::new()]);
        let mut recv = [vec![0.0; 2], Vec::new()];
        world.exchange(&[0, 0], &[vec![3.0, 4.0], Vec::new()], &mut recv);
        assert_eq!(recv, [vec![3.0, 4.0], Vec::new()]);
        world.barrier();
    }

    /// A 4 × 4 grid of nodes cut in two by METIS: 8 nodes each.
    #[test]
    fn metis_halves_a_grid() {
        let at = |i: usize, j: usize| 4 * i + j;
        let mut offsets = vec![0];
        let mut targets = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                if i > 0 {
                    targets.push(at(i - 1, j));
                }
                if j > 0 {
                    targets.push(at(i, j - 1));
                }
                if j < 3 {
                    targets.push(at(i, j + 1));
                }
                if i < 3 {
                    targets.push(at(i + 1, j));
                }
                offsets.push(targets.len());
            }
        }
        let part = part_kway(&offsets, &targets, 2).unwrap();
        assert_eq!(part.iter().filter(|&&p| p == 0).count(), 8, "{part:?}");
        assert_eq!(part.iter().filter(|&&p| p == 1).count(), 8, "{part:?}");
        assert_eq!(
            part,
            part_kway(&offsets, &targets, 2).unwrap(),
            "the same seed"
        );
    }
}
