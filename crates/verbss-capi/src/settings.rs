//! The settings of a deformer: every setting of the library's table
//! (`verbss::settings::TABLE`, docs/case-file.md) by its name and its value
//! as the command line spells it, the sliding planes and the fixed nodes
//! that bound them.
//!
//! ```c
//! VerbssSettings *s = NULL;
//! verbss_settings_new(&s);                        /* robust, as `verbss deform` */
//! verbss_settings_set(s, "rigid_layer", "0.05");  /* --rigid-layer 0.05 */
//! verbss_settings_set_number(s, "tolerance", 1e-8);
//! verbss_settings_add_slide(s, sym, n_sym, NULL, 0);  /* --slide: its own plane */
//! ```

use std::ffi::{c_char, c_int};

use verbss::settings::Settings;
use verbss::Error;

use crate::error::{guard, input, slice, text};

/// The settings of a deformer (opaque): the named values in the order given,
/// the sliding planes and the fixed groups. `verbss_settings_new` makes one.
#[derive(Debug, Clone, PartialEq)]
pub struct VerbssSettings {
    /// `(name, value)` as given, checked one by one; the library combines
    /// them ([`Settings::named`]).
    pub(crate) values: Vec<(String, String)>,
    /// The sliding planes, in the order given.
    pub(crate) slides: Vec<Slide>,
    /// The fixed groups' node ids, in the order given.
    pub(crate) fixed: Vec<Vec<i64>>,
}

/// A plane in which some nodes slide.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Slide {
    /// The caller's node ids.
    pub(crate) nodes: Vec<i64>,
    /// The plane's normal (`dim` numbers), or `None` for the plane of the
    /// boundary facets among the nodes.
    pub(crate) normal: Option<Vec<f64>>,
}

impl Default for VerbssSettings {
    /// The defaults of every front end ([`Settings::robust`]).
    fn default() -> Self {
        VerbssSettings {
            values: Vec::new(),
            slides: Vec::new(),
            fixed: Vec::new(),
        }
    }
}

impl VerbssSettings {
    /// The library's settings: the named values over the method's preset,
    /// checked together.
    pub(crate) fn resolve(&self) -> Result<Settings, Error> {
        Settings::named(1, &self.values)
    }
}

/// The settings behind a handle, or an error when it is NULL.
///
/// # Safety
/// A non-NULL `s` must come from `verbss_settings_new` and not be freed.
unsafe fn handle<'a>(
    s: *mut VerbssSettings,
) -> Result<&'a mut VerbssSettings, crate::error::Failure> {
    // SAFETY: the caller guarantees a live handle or NULL.
    unsafe { s.as_mut() }.ok_or_else(|| input("the settings are NULL".into()))
}

/// Creates settings with the defaults of `verbss deform` (the robust method,
/// tolerance 1e-6, at most 2000 sweeps; one worker thread per core) and
/// stores them in `*out`. Free them with `verbss_settings_free`; a deformer
/// keeps its own copy.
///
/// # Safety
/// `out` must point to a writable pointer.
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_new(out: *mut *mut VerbssSettings) -> c_int {
    guard(|| {
        // SAFETY: the caller guarantees a writable pointer or NULL.
        let out = unsafe { out.as_mut() }.ok_or_else(|| input("`out` is NULL".into()))?;
        *out = Box::into_raw(Box::default());
        Ok(())
    })
}

/// Sets the setting `name` to `value`, both as the library's table of
/// settings spells them (docs/case-file.md: the case file's `[solver]` keys,
/// `verbss deform`'s options with `_` for `-`): `method` first sets every
/// other setting to its preset's value, whatever the order of the calls; a
/// `solver`, `accel` or `omega` given means exactly that solver (no
/// escalation unless `escalate` is set to `on`); `threads` is one per core
/// unless set.
///
/// A name or a value that is not one of the table's returns
/// `VERBSS_ERROR_INPUT` and changes nothing; `verbss_deformer_new` checks
/// how the values go together. Setting a name again replaces its value.
///
/// # Safety
/// `settings` must be live settings; `name` and `value` NUL-terminated strings.
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_set(
    settings: *mut VerbssSettings,
    name: *const c_char,
    value: *const c_char,
) -> c_int {
    guard(|| {
        // SAFETY (all three): the caller guarantees live pointers or NULL.
        let settings = unsafe { handle(settings) }?;
        let name = unsafe { text(name, "name") }?;
        let value = unsafe { text(value, "value") }?;
        Settings::check(name, value)?;
        settings.values.push((name.into(), value.into()));
        Ok(())
    })
}

/// `verbss_settings_set` with a number, for the settings whose values are
/// numbers (`tolerance`, `omega`, a `rigid_layer` wall distance, the whole
/// numbers `max_iterations`, `threads`, `substeps`, …: docs/case-file.md).
/// The number is written exactly (its shortest decimal form that reads
/// back as the same `double`).
///
/// # Safety
/// `settings` must be live settings; `name` a NUL-terminated string.
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_set_number(
    settings: *mut VerbssSettings,
    name: *const c_char,
    value: f64,
) -> c_int {
    guard(|| {
        // SAFETY (both): the caller guarantees live pointers or NULL.
        let settings = unsafe { handle(settings) }?;
        let name = unsafe { text(name, "name") }?;
        let value = value.to_string();
        Settings::check(name, &value)?;
        settings.values.push((name.into(), value));
        Ok(())
    })
}

/// Adds a sliding plane (a symmetry plane): the `n_nodes` nodes `nodes`
/// slide in the plane through each of them with the normal `normal` (`dim`
/// numbers, `n_normal` = `dim`), or, with `normal` NULL and `n_normal` 0, in
/// the plane of the mesh's boundary facets among them (`verbss deform
/// --slide`). A node that is also a moving node follows its displacement; a
/// node on two planes of different normals, or also in a fixed group
/// (`verbss_settings_add_fixed`), stays where it is.
///
/// # Safety
/// `settings` must be live settings; `nodes` must hold `n_nodes` ids and
/// `normal` `n_normal` numbers (or be NULL when `n_normal` is 0).
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_add_slide(
    settings: *mut VerbssSettings,
    nodes: *const i64,
    n_nodes: usize,
    normal: *const f64,
    n_normal: usize,
) -> c_int {
    guard(|| {
        // SAFETY (all three): the caller guarantees live pointers of the
        // stated lengths, or NULL.
        let settings = unsafe { handle(settings) }?;
        let nodes = unsafe { slice(nodes, n_nodes, "nodes") }?;
        let normal = unsafe { slice(normal, n_normal, "normal") }?;
        if nodes.is_empty() {
            return Err(Error::InvalidSetting(format!(
                "slide plane {} has no node",
                settings.slides.len()
            ))
            .into());
        }
        settings.slides.push(Slide {
            nodes: nodes.to_vec(),
            normal: (!normal.is_empty()).then(|| normal.to_vec()),
        });
        Ok(())
    })
}

/// Adds a fixed group: the `n_nodes` nodes `nodes` stay where they are. A
/// boundary node stays anyway; a fixed group also holds the nodes where a
/// sliding plane meets it, as the mesh file's other groups (walls,
/// farfield) do for `verbss deform --slide`.
///
/// # Safety
/// `settings` must be live settings; `nodes` must hold `n_nodes` ids.
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_add_fixed(
    settings: *mut VerbssSettings,
    nodes: *const i64,
    n_nodes: usize,
) -> c_int {
    guard(|| {
        // SAFETY (both): the caller guarantees live pointers of the stated
        // lengths, or NULL.
        let settings = unsafe { handle(settings) }?;
        let nodes = unsafe { slice(nodes, n_nodes, "nodes") }?;
        if nodes.is_empty() {
            return Err(Error::InvalidSetting(format!(
                "fixed group {} has no node",
                settings.fixed.len()
            ))
            .into());
        }
        settings.fixed.push(nodes.to_vec());
        Ok(())
    })
}

/// Frees settings (NULL is allowed and does nothing).
///
/// # Safety
/// `settings` must be NULL or settings from `verbss_settings_new` not yet
/// freed.
#[no_mangle]
pub unsafe extern "C" fn verbss_settings_free(settings: *mut VerbssSettings) -> c_int {
    guard(|| {
        if !settings.is_null() {
            // SAFETY: `settings` came from `Box::into_raw` and is freed once.
            drop(unsafe { Box::from_raw(settings) });
        }
        Ok(())
    })
}
