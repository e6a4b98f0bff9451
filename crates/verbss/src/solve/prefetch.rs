//! A cache hint for the sweep's neighbour reads.
//!
//! A sweep reads each node's neighbours' displacements from all over the
//! unknowns' array (nodes of one colour couple only to other colours, each
//! stored in its own block). Past the caches, these scattered reads wait on
//! memory one window of the processor's reorder buffer at a time; asking for
//! the displacement of a neighbour a few nodes ahead lets those waits
//! overlap. The hint changes no value: results are bit-identical with and
//! without it.
// The one `unsafe` of the library: `_mm_prefetch` takes a raw pointer and is
// declared unsafe, but a prefetch never reads memory as far as the program
// can observe, cannot fault and is dropped by the processor for an invalid
// address; the pointer passed is moreover inside `values`.
#![allow(unsafe_code)]

/// How many couplings ahead of the one being added (in the sweep's order,
/// about three nodes) the neighbour's displacement is asked for: 40 was
/// fastest of 20, 40, 64 and 100 on 12,931–418,879 unknowns (BENCHMARKS.md).
const AHEAD: usize = 40;

/// Asks for the displacement (`D` numbers per position in `work`) of the
/// neighbour [`AHEAD`] couplings after coupling `e` of `neighbours`.
#[inline(always)]
pub(crate) fn neighbour<const D: usize>(work: &[f64], neighbours: &[u32], e: usize) {
    if let Some(&j) = neighbours.get(e + AHEAD) {
        prefetch(work, D * j as usize);
    }
}

/// Asks the processor to bring `values[index]` into the cache (no-op when
/// `index` is out of range, and on targets other than x86-64).
#[inline(always)]
fn prefetch(values: &[f64], index: usize) {
    #[cfg(all(target_arch = "x86_64", not(miri)))]
    if let Some(v) = values.get(index) {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: a prefetch is a hint without architectural effect; `v` is
        // a valid reference (see the module note).
        unsafe { _mm_prefetch::<_MM_HINT_T0>((v as *const f64).cast::<i8>()) }
    }
    #[cfg(not(all(target_arch = "x86_64", not(miri))))]
    let _ = (values, index);
}
