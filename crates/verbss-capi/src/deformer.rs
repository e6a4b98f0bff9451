//! The deformer: built once from the caller's arrays and settings, stepped
//! once per time step with the moving nodes' displacements.

use std::collections::HashMap;
use std::ffi::c_int;

use verbss::deform::{Deformer, StepReport};
use verbss::motion::{check_displacement, Attachment, Motion, PositionSource};
use verbss::topology::boundary_facets;
use verbss::{Error, Mesh};

use crate::error::{guard, input, slice, Failure};
use crate::mesh::{add_facets_within, cells, node_group};
use crate::settings::VerbssSettings;

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

/// The deformer behind a handle, or an error when it is NULL.
///
/// # Safety
/// A non-NULL `d` must come from `verbss_deformer_new` and not be freed.
unsafe fn handle<'a>(d: *const VerbssDeformer) -> Result<&'a VerbssDeformer, Failure> {
    // SAFETY: the caller guarantees a live handle or NULL.
    unsafe { d.as_ref() }.ok_or_else(|| input("the deformer is NULL".into()))
}

/// The mesh with its groups (`moving`, `slide plane k`, `fixed group k`) and
/// their attachments (the moving nodes' positions first).
fn mesh_and_motions(
    dim: usize,
    coords: &[f64],
    cells: verbss::Cells,
    ids: &[i64],
    settings: &VerbssSettings,
) -> Result<(Mesh, Vec<Attachment>, Vec<usize>), Failure> {
    let n = coords.len() / dim;
    if ids.is_empty() {
        return Err(Error::InvalidSetting("no moving node was given".into()).into());
    }
    let (group, moving) = node_group("moving", ids, n, |k| format!("moving node {k}"))?;
    let mut groups = vec![group];
    let mut attachments = vec![Attachment {
        groups: vec!["moving".into()],
        motion: Motion::Positions(PositionSource::Given(HashMap::new())),
    }];
    let boundary = settings
        .slides
        .iter()
        .any(|s| s.normal.is_none())
        .then(|| boundary_facets(&cells));
    for (p, slide) in settings.slides.iter().enumerate() {
        let name = format!("slide plane {p}");
        let (mut group, _) = node_group(&name, &slide.nodes, n, |k| {
            format!("node {k} of slide plane {p}")
        })?;
        if let (None, Some(facets)) = (&slide.normal, &boundary) {
            add_facets_within(&mut group, facets, n);
        }
        groups.push(group);
        attachments.push(Attachment::slide(&name, slide.normal.as_deref(), dim)?);
    }
    for (f, ids) in settings.fixed.iter().enumerate() {
        let name = format!("fixed group {f}");
        let (group, _) = node_group(&name, ids, n, |k| format!("node {k} of fixed group {f}"))?;
        groups.push(group);
        attachments.push(Attachment {
            groups: vec![name],
            motion: Motion::Fixed,
        });
    }
    let mesh = Mesh::new(dim, coords.to_vec(), cells, groups)?;
    Ok((mesh, attachments, moving))
}

/// Creates a deformer and stores it in `*out`.
///
/// - `points`: `n_points × dim` coordinates (`dim` 2 or 3);
/// - `cell_kinds`: `n_cells` VTK cell type ids (`VERBSS_TRIANGLE` …);
/// - `cell_nodes`: the cells' node ids concatenated, VTK's node order,
///   `n_cell_nodes` in all;
/// - `moving`: the `n_moving` distinct ids of the nodes whose displacement
///   each step gives;
/// - `settings`: from `verbss_settings_new`, or NULL for the defaults.
///
/// Checks the settings together, the sliding planes, the fixed groups and
/// the mesh (no degenerate or inverted element, no two nodes at the same
/// position but the two sides of a baffle moving together) and builds its
/// topology, once.
///
/// # Safety
/// Each non-NULL array must hold the number of elements stated; `settings`
/// must be NULL or live settings; `out` must point to a writable pointer.
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
        let default = VerbssSettings::default();
        // SAFETY: the caller guarantees live settings or NULL.
        let chosen = unsafe { settings.as_ref() }.unwrap_or(&default);
        let settings = chosen.resolve()?;
        let cells = cells(kinds, nodes, n_points)?;
        let (mesh, attachments, moving) = mesh_and_motions(dim, coords, cells, ids, chosen)?;
        let deformer = Deformer::new(&mesh, &attachments, settings)?;
        let info = deformer.current().report.clone();
        *out = Box::into_raw(Box::new(VerbssDeformer {
            deformer,
            moving,
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
        check_displacement(u, dim, |k| {
            format!(
                "verbss_deformer_step displacement of moving node {k} (node {})",
                d.moving[k]
            )
        })?;
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
