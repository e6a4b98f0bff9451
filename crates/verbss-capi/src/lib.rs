//! # The C API of verbss
//!
//! A flow solver written in C, C++ or Fortran builds a deformer once from
//! arrays (node coordinates, cells, the ids of the nodes it moves), then once
//! per time step gives the displacement of those nodes and reads the new
//! coordinates of all nodes back. `include/verbss.h` declares it (generated
//! from this file by cbindgen); `examples/c/deform.c` uses it.
//!
//! ```c
//! VerbssSettings s;
//! verbss_settings_default(&s);
//! VerbssDeformer *d = NULL;
//! if (verbss_deformer_new(2, xy, n, kinds, ncells, nodes, nnodes,
//!                         moving, nmoving, &s, &d) != VERBSS_OK)
//!     fprintf(stderr, "%s\n", verbss_last_error());
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
//! - The moving nodes follow the displacements given at each step, measured
//!   from the input coordinates: at each step node `moving[k]` is put exactly
//!   at `X + u[D*k .. D*k+D]`. Every other node on the mesh's boundary (a
//!   facet of one cell only) stays fixed; all other nodes move with the
//!   springs. Each call of [`verbss_deformer_step`] is the next step.
//! - Every function returns a status ([`VERBSS_OK`] or an error code) and
//!   never lets a panic cross into C (a caught panic is
//!   [`VERBSS_ERROR_INTERNAL`]). The message of the last failed call is
//!   per thread: [`verbss_last_error`].
//! - A deformer may be used from any thread, but from one thread at a time;
//!   different deformers are independent. A step runs on the deformer's
//!   `threads` worker threads.

#![deny(unsafe_op_in_unsafe_fn)]

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::ffi::{c_char, c_int, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use verbss::deform::{Deformer, Preset, Reference, Settings, StepReport};
use verbss::motion::{Attachment, Motion, PositionSource};
use verbss::solve::{Accel, Solver};
use verbss::{CellKind, Cells, Error, Group, Mesh};

/// Success.
pub const VERBSS_OK: c_int = 0;
/// Bad input: a NULL pointer, an array of the wrong length, an invalid mesh,
/// setting or displacement. Nothing changed.
pub const VERBSS_ERROR_INPUT: c_int = 2;
/// The step inverted an element: it was rejected, the deformer keeps the last
/// accepted step (the same codes as the `verbss` command).
pub const VERBSS_ERROR_INVERTED: c_int = 3;
/// A bug in verbss, caught before it reached the caller.
pub const VERBSS_ERROR_INTERNAL: c_int = 4;

/// Cell kind: 3-node triangle (VTK type id 5).
pub const VERBSS_TRIANGLE: i32 = 5;
/// Cell kind: 4-node quadrilateral (VTK 9).
pub const VERBSS_QUAD: i32 = 9;
/// Cell kind: 4-node tetrahedron (VTK 10).
pub const VERBSS_TETRA: i32 = 10;
/// Cell kind: 8-node hexahedron (VTK 12).
pub const VERBSS_HEXAHEDRON: i32 = 12;
/// Cell kind: 6-node prism (wedge), VTK's node order (VTK 13).
pub const VERBSS_WEDGE: i32 = 13;
/// Cell kind: 5-node pyramid (VTK 14).
pub const VERBSS_PYRAMID: i32 = 14;

/// Method: edge and ball-vertex springs solved node by node (block SOR).
pub const VERBSS_METHOD_VERBSS: i32 = 0;
/// Method: the same springs as one global system (see `solver`).
pub const VERBSS_METHOD_BALL_VERTEX: i32 = 1;
/// Method: edge springs only, node by node.
pub const VERBSS_METHOD_SPRING: i32 = 2;
/// Method: component-wise Laplacian with `k = 1/L`.
pub const VERBSS_METHOD_LAPLACIAN: i32 = 3;
/// Method: VerBSS with the near-wall treatments (rigid layer, inverse
/// wall-distance stiffening, sub-steps; docs/robustness.md), the command's default.
pub const VERBSS_METHOD_ROBUST: i32 = 4;

/// Global solver of `VERBSS_METHOD_BALL_VERTEX`: scalar SOR.
pub const VERBSS_SOLVER_SOR: i32 = 0;
/// Global solver of `VERBSS_METHOD_BALL_VERTEX`: exact sparse LU.
pub const VERBSS_SOLVER_DIRECT: i32 = 1;

/// Plain VerBSS sweeps (the paper's method).
pub const VERBSS_ACCEL_NONE: i32 = 0;
/// GMRES around a multigrid V-cycle whose smoother is the VerBSS sweep
/// (`tolerance` then bounds the estimated RMS error; docs/acceleration.md).
pub const VERBSS_ACCEL_AMG: i32 = 1;
/// `VERBSS_ACCEL_AMG` on large meshes of mostly triangles/tetrahedra, plain sweeps otherwise.
pub const VERBSS_ACCEL_AUTO: i32 = 2;

/// Springs built on the current coordinates each step, solve for the increment.
pub const VERBSS_REFERENCE_UPDATED: i32 = 0;
/// Springs built once on the input coordinates, solve for the total displacement.
pub const VERBSS_REFERENCE_INITIAL: i32 = 1;

/// Settings of a deformer; `verbss_settings_default` fills the defaults.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerbssSettings {
    /// `VERBSS_METHOD_*` (default `VERBSS_METHOD_ROBUST`, as on the command line).
    pub method: i32,
    /// `VERBSS_SOLVER_*` (default `VERBSS_SOLVER_SOR`).
    pub solver: i32,
    /// `VERBSS_REFERENCE_*` (default `VERBSS_REFERENCE_UPDATED`).
    pub reference: i32,
    /// Over-relaxation factor ω of the sweeps (default 1.6).
    pub omega: f64,
    /// Stop when the mean absolute change of one sweep is below `tolerance`
    /// times the step's largest prescribed displacement (default 1e-6).
    pub tolerance: f64,
    /// Nonzero: `tolerance` is an absolute threshold (default 0).
    pub absolute_tolerance: i32,
    /// Most sweeps per step (default 2000).
    pub max_iterations: usize,
    /// Worker threads, 0 for one per core (default 0); results do not depend on it.
    pub threads: usize,
    /// `VERBSS_ACCEL_*`, for the methods verbss and spring (default `VERBSS_ACCEL_NONE`).
    pub accel: i32,
}

impl Default for VerbssSettings {
    /// The product's defaults ([`Settings::robust`]), as on the command line.
    fn default() -> Self {
        let d = Settings::robust(1).solve;
        VerbssSettings {
            method: VERBSS_METHOD_ROBUST,
            solver: VERBSS_SOLVER_SOR,
            reference: VERBSS_REFERENCE_UPDATED,
            omega: d.omega,
            tolerance: d.tolerance,
            absolute_tolerance: 0,
            max_iterations: d.max_iterations,
            threads: 0,
            accel: VERBSS_ACCEL_NONE,
        }
    }
}

/// What the last accepted step did.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VerbssInfo {
    /// The step number (0 before the first step).
    pub step: usize,
    /// Solver sweeps.
    pub iterations: usize,
    /// The mean absolute change of the last sweep.
    pub residual: f64,
    /// 1 when the stop test was met, 0 when `max_iterations` ran out.
    pub converged: i32,
    /// Wall seconds of the step.
    pub seconds: f64,
    /// The smallest element quality (1 ideal, 0 degenerate).
    pub min_quality: f64,
    /// The mean element quality.
    pub mean_quality: f64,
    /// The number of inverted elements (0 for an accepted step).
    pub inverted: usize,
}

/// A mesh in motion (opaque).
pub struct VerbssDeformer {
    deformer: Deformer,
    /// The moving nodes, in the caller's order.
    moving: Vec<usize>,
    /// The last accepted step's report.
    info: StepReport,
}

/// An error and the status it returns.
struct Failure {
    code: c_int,
    message: String,
}

impl From<Error> for Failure {
    fn from(e: Error) -> Failure {
        let code = match e {
            Error::Inverted { .. } => VERBSS_ERROR_INVERTED,
            _ => VERBSS_ERROR_INPUT,
        };
        Failure {
            code,
            message: e.to_string(),
        }
    }
}

fn input(message: String) -> Failure {
    Failure {
        code: VERBSS_ERROR_INPUT,
        message,
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', "")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

/// Runs `body`, turning its error or panic into a status and the thread's
/// last error message.
fn guard(body: impl FnOnce() -> Result<(), Failure>) -> c_int {
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => return VERBSS_OK,
        Ok(Err(failure)) => failure,
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Failure {
                code: VERBSS_ERROR_INTERNAL,
                message: format!("internal error: {what}"),
            }
        }
    };
    set_last_error(&failure.message);
    failure.code
}

/// The `len` elements at `ptr`, or an error naming `what` when `ptr` is NULL
/// (an empty array may be NULL).
///
/// # Safety
/// A non-NULL `ptr` must point to `len` readable elements.
unsafe fn slice<'a, T>(ptr: *const T, len: usize, what: &str) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(input(format!("`{what}` is NULL")));
    }
    // SAFETY: the caller guarantees `len` readable elements at `ptr`.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// The deformer behind a handle, or an error when it is NULL.
///
/// # Safety
/// A non-NULL `d` must come from `verbss_deformer_new` and not be freed.
unsafe fn handle<'a>(d: *const VerbssDeformer) -> Result<&'a VerbssDeformer, Failure> {
    // SAFETY: the caller guarantees a live handle or NULL.
    unsafe { d.as_ref() }.ok_or_else(|| input("the deformer is NULL".into()))
}

fn kind_of(code: i32, cell: usize) -> Result<CellKind, Failure> {
    match CellKind::from_vtk_id(code.into()).filter(|k| k.dim() >= 2) {
        Some(kind) => Ok(kind),
        None => Err(Error::InvalidMesh(format!(
            "cell {cell} has kind {code} (expected 5 triangle, 9 quad, 10 tetra, \
             12 hexahedron, 13 wedge or 14 pyramid)"
        ))
        .into()),
    }
}

/// A 0-based node id below `n`.
fn node_index(id: i64, n: usize, what: impl Fn() -> String) -> Result<usize, Failure> {
    usize::try_from(id).ok().filter(|&i| i < n).ok_or_else(|| {
        Error::InvalidMesh(format!(
            "{} is node {id}, not a node id of the mesh (0 to {})",
            what(),
            n as i64 - 1
        ))
        .into()
    })
}

/// The cells from VTK kinds and concatenated VTK-ordered nodes.
fn cells(kinds: &[i32], nodes: &[i64], n: usize) -> Result<Cells, Failure> {
    let mut cells = Cells::new();
    let mut next = 0;
    let mut local = Vec::with_capacity(8);
    for (c, &code) in kinds.iter().enumerate() {
        let kind = kind_of(code, c)?;
        let count = kind.node_count();
        let Some(stored) = nodes.get(next..next + count) else {
            return Err(too_few(kinds, nodes.len()));
        };
        local.clear();
        for k in 0..count {
            let id = stored[kind.vtk_local(k)];
            local.push(node_index(id, n, || format!("node {k} of cell {c}"))?);
        }
        cells.push(kind, &local);
        next += count;
    }
    if next != nodes.len() {
        return Err(Error::InvalidMesh(format!(
            "`cell_nodes` holds {} node ids but the {} cells use {next}",
            nodes.len(),
            kinds.len()
        ))
        .into());
    }
    Ok(cells)
}

fn too_few(kinds: &[i32], given: usize) -> Failure {
    let needed: usize = kinds
        .iter()
        .enumerate()
        .filter_map(|(c, &k)| kind_of(k, c).ok())
        .map(CellKind::node_count)
        .sum();
    Error::InvalidMesh(format!(
        "`cell_nodes` holds {given} node ids but the {} cells use {needed}",
        kinds.len()
    ))
    .into()
}

fn settings(s: &VerbssSettings) -> Result<Settings, Failure> {
    let bad = |what: &str, value: i32| {
        Failure::from(Error::InvalidSetting(format!(
            "{what} {value} is not one of VERBSS_{}_*",
            what.to_ascii_uppercase()
        )))
    };
    let preset = match s.method {
        VERBSS_METHOD_VERBSS => Preset::Verbss,
        VERBSS_METHOD_BALL_VERTEX => Preset::BallVertex,
        VERBSS_METHOD_SPRING => Preset::Spring,
        VERBSS_METHOD_LAPLACIAN => Preset::Laplacian,
        VERBSS_METHOD_ROBUST => Preset::Robust,
        m => return Err(bad("method", m)),
    };
    let mut settings = preset.settings(1);
    settings.reference = match s.reference {
        VERBSS_REFERENCE_UPDATED => Reference::Updated,
        VERBSS_REFERENCE_INITIAL => Reference::Fixed,
        r => return Err(bad("reference", r)),
    };
    let p = &mut settings.solve;
    p.solver = match s.solver {
        VERBSS_SOLVER_SOR => Solver::Sor,
        VERBSS_SOLVER_DIRECT => Solver::Direct,
        v => return Err(bad("solver", v)),
    };
    p.accel = match s.accel {
        VERBSS_ACCEL_NONE => Accel::None,
        VERBSS_ACCEL_AMG => Accel::Amg,
        VERBSS_ACCEL_AUTO => Accel::Auto,
        a => return Err(bad("accel", a)),
    };
    p.omega = s.omega;
    p.tolerance = s.tolerance;
    p.absolute_tolerance = s.absolute_tolerance != 0;
    p.max_iterations = s.max_iterations;
    p.threads = s.threads;
    settings.validate()?;
    Ok(settings)
}

fn info(r: &StepReport) -> VerbssInfo {
    VerbssInfo {
        step: r.step,
        iterations: r.iterations,
        residual: r.residual,
        converged: i32::from(r.converged),
        seconds: r.seconds,
        min_quality: r.min_quality,
        mean_quality: r.mean_quality,
        inverted: r.inverted,
    }
}

/// Fills `out` with the default settings.
///
/// # Safety
/// `out` must be NULL or point to a writable `VerbssSettings`.
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_default(out: *mut VerbssSettings) -> c_int {
    guard(|| {
        // SAFETY: the caller guarantees a writable struct or NULL.
        let out = unsafe { out.as_mut() }.ok_or_else(|| input("`out` is NULL".into()))?;
        *out = VerbssSettings::default();
        Ok(())
    })
}

/// Creates a deformer and stores it in `*out`.
///
/// - `points`: `n_points × dim` coordinates (`dim` 2 or 3);
/// - `cell_kinds`: `n_cells` VTK cell type ids (`VERBSS_TRIANGLE` …);
/// - `cell_nodes`: the cells' node ids concatenated, VTK's node order,
///   `n_cell_nodes` in all;
/// - `moving`: the `n_moving` distinct ids of the nodes whose displacement
///   each step gives;
/// - `settings`: NULL for the defaults.
///
/// Checks the mesh (no degenerate or inverted element, no two nodes at the
/// same position) and builds its topology, once.
///
/// # Safety
/// Each non-NULL array must hold the number of elements stated; `settings`
/// must be NULL or valid; `out` must point to a writable pointer.
#[no_mangle]
pub unsafe extern "C" fn verbss_deformer_new(
    dim: usize,
    points: *const f64,
    n_points: usize,
    cell_kinds: *const i32,
    n_cells: usize,
    cell_nodes: *const i64,
    n_cell_nodes: usize,
    moving: *const i64,
    n_moving: usize,
    settings: *const VerbssSettings,
    out: *mut *mut VerbssDeformer,
) -> c_int {
    guard(|| {
        // SAFETY: the caller guarantees a writable pointer or NULL.
        let out = unsafe { out.as_mut() }.ok_or_else(|| input("`out` is NULL".into()))?;
        *out = std::ptr::null_mut();
        if dim != 2 && dim != 3 {
            return Err(Error::InvalidMesh(format!("dimension {dim} (expected 2 or 3)")).into());
        }
        let len = n_points
            .checked_mul(dim)
            .ok_or_else(|| input(format!("{n_points} points of dimension {dim} overflow")))?;
        // SAFETY (all four): the caller guarantees the stated lengths.
        let coords = unsafe { slice(points, len, "points") }?;
        let kinds = unsafe { slice(cell_kinds, n_cells, "cell_kinds") }?;
        let nodes = unsafe { slice(cell_nodes, n_cell_nodes, "cell_nodes") }?;
        let ids = unsafe { slice(moving, n_moving, "moving") }?;
        // SAFETY: the caller guarantees a valid struct or NULL.
        let chosen = unsafe { settings.as_ref() }.copied().unwrap_or_default();
        let settings = self::settings(&chosen)?;
        let cells = cells(kinds, nodes, n_points)?;
        if ids.is_empty() {
            return Err(Error::InvalidSetting("no moving node was given".into()).into());
        }
        let mut seen = HashSet::new();
        let mut moved = Vec::with_capacity(ids.len());
        let mut facets = Cells::new();
        for (k, &id) in ids.iter().enumerate() {
            let i = node_index(id, n_points, || format!("moving node {k}"))?;
            if !seen.insert(i) {
                return Err(Error::InvalidSetting(format!(
                    "moving node {k} is node {id}, listed twice"
                ))
                .into());
            }
            moved.push(i);
            facets.push(CellKind::Vertex, &[i]);
        }
        let group = Group {
            name: "moving".into(),
            tag: None,
            facets,
        };
        let mesh = Mesh::new(dim, coords.to_vec(), cells, vec![group])?;
        let attachment = Attachment {
            groups: vec!["moving".into()],
            motion: Motion::Positions(PositionSource::Given(HashMap::new())),
        };
        let deformer = Deformer::new(&mesh, &[attachment], settings)?;
        let info = deformer.current().report.clone();
        *out = Box::into_raw(Box::new(VerbssDeformer {
            deformer,
            moving: moved,
            info,
        }));
        Ok(())
    })
}

/// Takes the next step: node `moving[k]` goes to its input position plus
/// `displacement[dim*k .. dim*k+dim]` (`len = n_moving × dim` numbers), the
/// other nodes follow. On `VERBSS_ERROR_INVERTED` the step is rejected and
/// the deformer keeps the last accepted step, so the same step can be
/// retried with a smaller displacement.
///
/// # Safety
/// `d` must be a live deformer; `displacement` must hold `len` numbers.
#[no_mangle]
pub unsafe extern "C" fn verbss_deformer_step(
    d: *mut VerbssDeformer,
    displacement: *const f64,
    len: usize,
) -> c_int {
    guard(|| {
        // SAFETY: the caller guarantees a live deformer or NULL.
        let d = unsafe { d.as_mut() }.ok_or_else(|| input("the deformer is NULL".into()))?;
        let dim = d.deformer.initial().dim;
        let expected = d.moving.len() * dim;
        if len != expected {
            return Err(input(format!(
                "the displacement has {len} numbers, expected {expected} ({} moving node(s) × {dim})",
                d.moving.len()
            )));
        }
        // SAFETY: the caller guarantees `len` numbers.
        let u = unsafe { slice(displacement, len, "displacement") }?;
        if let Some(k) = u.iter().position(|x| !x.is_finite()) {
            return Err(Error::InvalidSetting(format!(
                "the displacement of moving node {} is not finite",
                k / dim
            ))
            .into());
        }
        let mesh = d.deformer.initial();
        let positions = d
            .moving
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let x = mesh.point(i);
                let p = (0..dim).map(|c| x[c] + u[dim * k + c]).collect();
                (i, p)
            })
            .collect();
        d.deformer
            .set_motion(0, Motion::Positions(PositionSource::Given(positions)))?;
        d.info = d.deformer.advance()?;
        Ok(())
    })
}

/// Copies the current coordinates of all nodes (`len = n_points × dim`) to `out`.
///
/// # Safety
/// `d` must be a live deformer; `out` must have room for `len` numbers.
#[no_mangle]
pub unsafe extern "C" fn verbss_deformer_points(
    d: *const VerbssDeformer,
    out: *mut f64,
    len: usize,
) -> c_int {
    guard(|| {
        // SAFETY: the caller guarantees a live deformer or NULL.
        let d = unsafe { handle(d) }?;
        let coords = &d.deformer.current().coords;
        if len != coords.len() {
            return Err(input(format!(
                "`out` has room for {len} numbers, the mesh has {}",
                coords.len()
            )));
        }
        if out.is_null() {
            return Err(input("`out` is NULL".into()));
        }
        // SAFETY: the caller guarantees room for `len` numbers at `out`.
        unsafe { std::ptr::copy_nonoverlapping(coords.as_ptr(), out, len) };
        Ok(())
    })
}

/// Writes what the last accepted step did to `out`.
///
/// # Safety
/// `d` must be a live deformer; `out` must point to a writable `VerbssInfo`.
#[no_mangle]
pub unsafe extern "C" fn verbss_deformer_info(
    d: *const VerbssDeformer,
    out: *mut VerbssInfo,
) -> c_int {
    guard(|| {
        // SAFETY: the caller guarantees a live deformer or NULL.
        let d = unsafe { handle(d) }?;
        // SAFETY: the caller guarantees a writable struct or NULL.
        let out = unsafe { out.as_mut() }.ok_or_else(|| input("`out` is NULL".into()))?;
        *out = info(&d.info);
        Ok(())
    })
}

/// Frees a deformer (NULL is allowed and does nothing).
///
/// # Safety
/// `d` must be NULL or a deformer from `verbss_deformer_new` not yet freed.
#[no_mangle]
pub unsafe extern "C" fn verbss_deformer_free(d: *mut VerbssDeformer) -> c_int {
    guard(|| {
        if !d.is_null() {
            // SAFETY: `d` came from `Box::into_raw` and is freed once.
            drop(unsafe { Box::from_raw(d) });
        }
        Ok(())
    })
}

/// The message of the last call that failed on this thread ("" if none):
/// the text the `verbss` command prints after `error: `. The pointer stays
/// valid until the next failing call on this thread.
#[no_mangle]
pub extern "C" fn verbss_last_error() -> *const c_char {
    catch_unwind(|| LAST_ERROR.with(|e| e.borrow().as_ptr())).unwrap_or(c"".as_ptr())
}
