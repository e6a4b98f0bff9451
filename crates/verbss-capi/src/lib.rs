//! # The C API of verbss
//!
//! A flow solver written in C, C++ or Fortran builds a deformer once from
//! arrays (node coordinates, cells, the ids of the nodes it moves) and
//! settings, then once per time step gives the displacement of those nodes
//! and reads the new coordinates of all nodes back. `include/verbss.h`
//! declares it (generated from these files by cbindgen);
//! `examples/c/deform.c` uses it.
//!
//! ```c
//! VerbssSettings *s = NULL;
//! verbss_settings_new(&s);                        /* robust, as `verbss deform` */
//! verbss_settings_set(s, "predictor", "linear");  /* --predictor linear */
//! VerbssDeformer *d = NULL;
//! if (verbss_deformer_new(2, xy, n, kinds, ncells, nodes, nnodes,
//!                         moving, nmoving, s, &d) != VERBSS_OK)
//!     fprintf(stderr, "%s\n", verbss_last_error());
//! verbss_settings_free(s);
//! verbss_deformer_step(d, displacement, 2 * nmoving);  /* every time step */
//! verbss_deformer_points(d, xy_new, 2 * n);
//! verbss_deformer_free(d);
//! ```
//!
//! # Conventions
//!
//! - Arrays are flat and row-major: node `i` has coordinates
//!   `points[D*i .. D*i+D]`; node ids are 0-based `int64_t`.
//! - Cells are given as in SU2 and VTK files: a kind per cell (the VTK cell
//!   type ids `VERBSS_TRIANGLE` … `VERBSS_PYRAMID`) and the cells' nodes
//!   concatenated in VTK's node order.
//! - Settings are named as on the command line ([`verbss_settings_set`]):
//!   the library's one vocabulary ([`verbss::settings::Settings::named`]).
//! - The moving nodes follow the displacements given at each step, measured
//!   from the input coordinates: at each step node `moving[k]` is put exactly
//!   at `X + u[D*k .. D*k+D]`. The nodes of a sliding plane
//!   ([`verbss_settings_add_slide`]) move within it; every other node on the
//!   mesh's boundary (a facet of one cell only) stays fixed; all other nodes
//!   move with the springs. Each call of [`verbss_deformer_step`] is the
//!   next step.
//! - Every function returns a status ([`VERBSS_OK`] or an error code) and
//!   never lets a panic cross into C (a caught panic is
//!   [`VERBSS_ERROR_INTERNAL`]). The message of the last failed call is
//!   per thread: [`verbss_last_error`].
//! - A deformer may be used from any thread, but from one thread at a time;
//!   different deformers are independent. A step runs on the deformer's
//!   `threads` worker threads.

#![deny(unsafe_op_in_unsafe_fn)]

mod deformer;
mod error;
mod mesh;
mod settings;

pub use deformer::*;
pub use error::*;
pub use mesh::*;
pub use settings::*;
