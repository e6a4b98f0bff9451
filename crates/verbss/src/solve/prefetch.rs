//! Cache hints for the sweep's reads.
//!
//! A sweep reads each node's neighbours' displacements from all over the
//! unknowns' array (nodes of one colour couple only to other colours, each
//! stored in its own block). Past the caches, these scattered reads wait on
//! memory one window of the processor's reorder buffer at a time; asking for
//! the displacement of a neighbour a few nodes ahead lets those waits
//! overlap. The coupling blocks, read in order, are asked for a little ahead
//! too. The hints change no value: results are bit-identical with and
//! without them.
// The solver's one `unsafe` (the other `unsafe` code of the library calls
// the CGNS C library, io/cgns/ffi): `_mm_prefetch` takes a raw pointer and is
// declared unsafe, but a prefetch never reads memory as far as the program
// can observe, cannot fault and is dropped by the processor for an invalid
// address. The addresses are formed with `wrapping_add` and never
// dereferenced; the last blocks' look-ahead points past the array's end.
#![allow(unsafe_code)]

/// How many couplings ahead of the one being added (in the sweep's order,
/// about three nodes) the neighbour's displacement is asked for: the fastest
/// of 20, 40, 64 and 100 (CHANGELOG.md, 2026-11-22).
const AHEAD: usize = 40;

/// Asks for the displacement (`D` numbers per position in `work`) of the
/// neighbour [`AHEAD`] couplings after coupling `e` of `neighbours`.
#[inline(always)]
pub(crate) fn ahead<const D: usize>(work: &[f64], neighbours: &[u32], e: usize) {
    if let Some(&j) = neighbours.get(e + AHEAD) {
        prefetch(work, D * j as usize);
    }
}

/// Asks for the coupling blocks 1.5 KB (192 numbers: 32 couplings in 3D, 64
/// in 2D) after the start of `block`, the one being added. The blocks are
/// read in order, but the processor's own look-ahead comes too late for the
/// sweep (CHANGELOG.md, 2026-11-22).
#[inline(always)]
pub(crate) fn block(block: &[f64]) {
    prefetch(block, 192);
}

/// Asks the processor to bring the cache line of `values[index]` in (no-op on
/// targets other than x86-64).
#[inline(always)]
fn prefetch(values: &[f64], index: usize) {
    #[cfg(all(target_arch = "x86_64", not(miri)))]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let at = values.as_ptr().wrapping_add(index);
        // SAFETY: a prefetch is a hint without architectural effect (see the
        // module note); the address is not dereferenced.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(at.cast::<i8>()) }
    }
    #[cfg(not(all(target_arch = "x86_64", not(miri))))]
    let _ = (values, index);
}
