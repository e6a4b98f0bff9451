//! The native part of the `verbss` Python package (`verbss._verbss`): the
//! [`Mesh`] and [`Deformer`] classes, `read`, `quality_json` and the
//! `VerbssError` exception, over numpy arrays. `python/verbss/__init__.py`
//! re-exports them and adds the meshio conversions.
//!
//! Every library error becomes a `VerbssError` whose message is the error's
//! own text, the one the `verbss` command prints after `error: `.

use std::path::PathBuf;
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use verbss::io::WriteOptions;
use verbss::{CellKind, Cells, Error, Group};

mod deformer;

use deformer::Deformer;

create_exception!(
    verbss,
    VerbssError,
    PyValueError,
    "A verbss error: a file that cannot be read, an invalid mesh or setting, an unknown group, or a step that inverted an element. The message is the one the `verbss` command prints."
);

/// The Python exception for a library error.
fn raise(e: Error) -> PyErr {
    VerbssError::new_err(e.to_string())
}

/// An "invalid mesh: …" error.
fn invalid_mesh(message: String) -> PyErr {
    raise(Error::InvalidMesh(message))
}

/// An "invalid setting: …" error.
fn invalid_setting(message: String) -> PyErr {
    raise(Error::InvalidSetting(message))
}

/// `numpy.asarray(value, dtype=dtype)`.
fn asarray<'py>(value: &Bound<'py, PyAny>, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    let numpy = value.py().import("numpy")?;
    let kwargs = PyDict::new(value.py());
    kwargs.set_item("dtype", dtype)?;
    numpy.getattr("asarray")?.call((value,), Some(&kwargs))
}

/// The shape of an array as Python prints it.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// Node ids from a 1-D or 2-D integer array: the ids (row-major) and the
/// number of columns (1 for a 1-D array). Floating-point ids are taken only
/// when every one is a whole number (a cast would cut 0.9 to 0); any other
/// kind of array (bool, text, objects) is refused.
fn node_ids(value: &Bound<'_, PyAny>, n: usize, what: &str) -> PyResult<(Vec<usize>, usize)> {
    let raw = value
        .py()
        .import("numpy")?
        .getattr("asarray")?
        .call1((value,))?;
    let dtype = raw.getattr("dtype")?;
    match dtype.getattr("kind")?.extract::<String>()?.as_str() {
        "i" | "u" => {}
        "f" => {
            let flat = asarray(&raw, "float64")?.call_method0("ravel")?;
            let values: PyReadonlyArray1<f64> = flat.extract()?;
            let values = values.as_array();
            if let Some((k, v)) = values.iter().enumerate().find(|(_, v)| v.fract() != 0.0) {
                return Err(invalid_mesh(format!(
                    "{what} holds {v} at flat index {k}: node ids must be whole numbers"
                )));
            }
        }
        _ => {
            return Err(invalid_mesh(format!(
                "{what} is an array of {} (expected integer node ids)",
                dtype.str()?
            )))
        }
    }
    let array = asarray(&raw, "int64")?;
    let ndim: usize = array.getattr("ndim")?.extract()?;
    let (ids, columns) = match ndim {
        1 => {
            let a: PyReadonlyArray1<i64> = array.extract()?;
            (a.as_array().to_vec(), 1)
        }
        2 => {
            let a: PyReadonlyArray2<i64> = array.extract()?;
            let columns = a.shape()[1];
            (a.as_array().iter().copied().collect(), columns)
        }
        _ => {
            return Err(invalid_mesh(format!(
                "{what} is a {ndim}-dimensional array (expected 1 or 2 dimensions)"
            )))
        }
    };
    let ids = ids
        .into_iter()
        .map(|id| {
            usize::try_from(id).ok().filter(|&i| i < n).ok_or_else(|| {
                invalid_mesh(format!(
                    "{what} uses node {id}, not a node id of the mesh (0 to {})",
                    n as i64 - 1
                ))
            })
        })
        .collect::<PyResult<Vec<usize>>>()?;
    Ok((ids, columns))
}

/// `(kind name, array)` pairs from a mapping or a sequence of pairs.
fn pairs<'py>(value: &Bound<'py, PyAny>) -> PyResult<Vec<(String, Bound<'py, PyAny>)>> {
    let items = if value.hasattr("items")? {
        value.call_method0("items")?
    } else {
        value.clone()
    };
    items
        .try_iter()?
        .map(|item| item?.extract::<(String, Bound<'py, PyAny>)>())
        .collect()
}

/// Appends the rows of `ids` (`columns` per row) as cells of `kind`.
fn push_rows(cells: &mut Cells, kind: CellKind, ids: &[usize], columns: usize) {
    for row in ids.chunks(columns) {
        cells.push(kind, row);
    }
}

/// An `(N, D)` float64 array of `coords` (`dim` per row).
fn points_array<'py>(py: Python<'py>, coords: &[f64], dim: usize) -> Bound<'py, PyArray2<f64>> {
    let array = Array2::from_shape_vec((coords.len() / dim, dim), coords.to_vec())
        .expect("coordinates are whole points");
    PyArray2::from_owned_array(py, array)
}

/// An `(M, k)` int64 array of cells' nodes, all of `k` nodes.
fn rows_array<'py>(py: Python<'py>, rows: Vec<&[usize]>, k: usize) -> Bound<'py, PyArray2<i64>> {
    let flat: Vec<i64> = rows
        .iter()
        .flat_map(|r| r.iter().map(|&i| i as i64))
        .collect();
    let array = Array2::from_shape_vec((rows.len(), k), flat).expect("rows of k nodes");
    PyArray2::from_owned_array(py, array)
}

/// `{kind name: (M, k) array}` of `cells`, kinds in order of first appearance.
fn cells_dict<'py>(py: Python<'py>, cells: &Cells) -> PyResult<Bound<'py, PyDict>> {
    let mut kinds: Vec<CellKind> = Vec::new();
    for &k in &cells.kinds {
        if !kinds.contains(&k) {
            kinds.push(k);
        }
    }
    if let Some(kind) = kinds.iter().find(|k| k.is_general()) {
        return Err(invalid_mesh(format!(
            "the mesh has {} cells, which have no (M, k) array here: the Python bindings \
             take triangles, quads, tetrahedra, hexahedra, prisms and pyramids (read and move \
             such a mesh with the verbss command)",
            kind.name()
        )));
    }
    let dict = PyDict::new(py);
    for kind in kinds {
        let rows: Vec<&[usize]> = cells
            .iter()
            .filter(|(k, _)| *k == kind)
            .map(|(_, nodes)| nodes)
            .collect();
        dict.set_item(kind.name(), rows_array(py, rows, kind.node_count()))?;
    }
    Ok(dict)
}

/// An unstructured 2D or 3D hybrid mesh: node coordinates, volume cells and
/// named boundary groups.
///
/// Mesh(points, cells, groups=None)
///
/// - points: (N, D) floats, D = 2 or 3.
/// - cells: a mapping from a meshio cell kind name ("triangle", "quad",
///   "tetra", "hexahedron", "wedge", "pyramid") to an (M, k) array of
///   0-based node ids, or a sequence of (kind, array) pairs; nodes in Gmsh's
///   order (the same as VTK's except for the wedge, whose two triangles VTK
///   numbers the other way round).
/// - groups: a mapping from a group name to its node ids (a 1-D array), or to
///   its boundary facets (an (M, k) array: k = 2 lines, 3 triangles, 4
///   quads; or a mapping kind → array for mixed facets).
///
/// Raises VerbssError when the arrays do not make a valid mesh.
#[pyclass(module = "verbss", frozen)]
#[derive(Clone)]
struct Mesh {
    inner: verbss::Mesh,
}

#[pymethods]
impl Mesh {
    #[new]
    #[pyo3(signature = (points, cells, groups = None))]
    fn new(
        points: &Bound<'_, PyAny>,
        cells: &Bound<'_, PyAny>,
        groups: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Mesh> {
        let points = asarray(points, "float64")?;
        let ndim: usize = points.getattr("ndim")?.extract()?;
        if ndim != 2 {
            return Err(invalid_mesh(format!(
                "points is a {ndim}-dimensional array (expected an (N, D) array)"
            )));
        }
        let points: PyReadonlyArray2<f64> = points.extract()?;
        let (n, dim) = (points.shape()[0], points.shape()[1]);
        let coords: Vec<f64> = points.as_array().iter().copied().collect();
        let mut volume = Cells::new();
        for (name, array) in pairs(cells)? {
            let kind = CellKind::from_name(&name)
                .filter(|k| k.dim() >= 2 && !k.is_general())
                .ok_or_else(|| {
                    invalid_mesh(format!(
                        "unknown cell kind '{name}' (expected triangle, quad, tetra, \
                         hexahedron, wedge or pyramid)"
                    ))
                })?;
            let what = format!("cells '{name}'");
            let (ids, columns) = node_ids(&array, n, &what)?;
            if columns != kind.node_count() {
                return Err(invalid_mesh(format!(
                    "{what} must be an (M, {}) array",
                    kind.node_count()
                )));
            }
            push_rows(&mut volume, kind, &ids, columns);
        }
        let mut list = Vec::new();
        if let Some(groups) = groups {
            for (name, value) in pairs(groups)? {
                let mut facets = Cells::new();
                let nested = value.hasattr("items")?;
                let parts = if nested {
                    pairs(&value)?
                } else {
                    vec![(String::new(), value)]
                };
                for (kind_name, array) in parts {
                    let what = format!("group '{name}'");
                    let (ids, columns) = node_ids(&array, n, &what)?;
                    let kind = if nested {
                        CellKind::from_name(&kind_name)
                            .filter(|k| {
                                k.dim() < dim && !k.is_general() && k.node_count() == columns
                            })
                            .ok_or_else(|| {
                                invalid_mesh(format!(
                                    "{what} has facets '{kind_name}' with {columns} nodes, \
                                     not boundary facets of a {dim}D mesh"
                                ))
                            })?
                    } else {
                        CellKind::facet_kind(columns)
                    };
                    if columns > 4 {
                        return Err(invalid_mesh(format!(
                            "{what} has {columns} nodes per facet (expected node ids, \
                             or facets of 2 to 4 nodes)"
                        )));
                    }
                    push_rows(&mut facets, kind, &ids, columns);
                }
                list.push(Group {
                    name,
                    tag: None,
                    facets,
                });
            }
        }
        let inner = verbss::Mesh::new(dim, coords, volume, list).map_err(raise)?;
        Ok(Mesh { inner })
    }

    /// The node coordinates, an (N, D) float64 array (a copy).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, &self.inner.coords, self.inner.dim)
    }

    /// The volume cells: {kind name: (M, k) int64 array of node ids}, kinds
    /// in order of first appearance (copies).
    #[getter]
    fn cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        cells_dict(py, &self.inner.cells)
    }

    /// The groups: {name: sorted int64 array of its distinct node ids}.
    #[getter]
    fn groups<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for g in &self.inner.groups {
            let ids: Vec<i64> = g.nodes().into_iter().map(|i| i as i64).collect();
            dict.set_item(&g.name, PyArray1::from_vec(py, ids))?;
        }
        Ok(dict)
    }

    /// The boundary facets of group `name`: {kind name: (M, k) int64 array}
    /// ("vertex" for groups given as node ids).
    fn group_facets<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyDict>> {
        let group = self.inner.group(name).map_err(raise)?;
        cells_dict(py, &group.facets)
    }

    /// The spatial dimension, 2 or 3.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim
    }

    /// Writes the mesh to `path`, in the format of its extension (.msh Gmsh
    /// 4.1, .su2, .vtu), with the mesh's numbering.
    fn write(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let mesh = &self.inner;
        py.detach(|| verbss::io::write(&path, mesh, &WriteOptions::default()))
            .map_err(raise)
    }

    fn __repr__(&self) -> String {
        let m = &self.inner;
        format!(
            "<verbss.Mesh {}D: {} nodes, {} cells, groups {:?}>",
            m.dim,
            m.node_count(),
            m.cell_count(),
            m.group_names()
        )
    }
}

/// Reads a mesh file (.msh Gmsh 2.2/4.1, .su2, .vtu), chosen by extension;
/// of a multi-zone SU2 file, zone `zone` (its IZONE= K, 1 by default).
///
/// Raises VerbssError naming the file, the line and what was expected.
#[pyfunction]
#[pyo3(signature = (path, zone = 1))]
fn read(py: Python<'_>, path: PathBuf, zone: usize) -> PyResult<Mesh> {
    let (inner, _) = py
        .detach(|| verbss::io::read_zone(&path, zone))
        .map_err(raise)?;
    Ok(Mesh { inner })
}

/// The `verbss quality --json` summary of a mesh, as JSON text.
#[pyfunction]
fn quality_json(py: Python<'_>, mesh: &Mesh) -> String {
    let m = &mesh.inner;
    py.detach(|| verbss::quality::summary_json(m).to_string())
}

/// A handshake across a step's GIL release: `step(…, probe=p)` signals `p`
/// once the GIL is released and waits there (at most 30 s) for `p.answer()`
/// before it solves, so a caller that answers ran while the step held no GIL.
#[pyclass(module = "verbss", frozen)]
struct GilProbe {
    /// 0 before the signal, 1 signalled, 2 answered.
    state: Arc<(Mutex<u8>, Condvar)>,
}

impl GilProbe {
    /// The step's side: signals, then waits for the answer.
    fn signal_and_wait(state: &(Mutex<u8>, Condvar)) -> Result<(), Error> {
        let (lock, turn) = state;
        let mut at = lock.lock().unwrap_or_else(|e| e.into_inner());
        *at = 1;
        turn.notify_all();
        let (at, _) = turn
            .wait_timeout_while(at, Duration::from_secs(30), |s| *s < 2)
            .unwrap_or_else(|e| e.into_inner());
        if *at < 2 {
            return Err(Error::InvalidSetting(
                "GIL probe: no answer within 30 s while the step held no GIL".into(),
            ));
        }
        Ok(())
    }
}

#[pymethods]
impl GilProbe {
    #[new]
    fn new() -> Self {
        GilProbe {
            state: Arc::new((Mutex::new(0), Condvar::new())),
        }
    }

    /// Waits (GIL released, at most `timeout` seconds) for a step's signal;
    /// whether it came.
    fn wait(&self, py: Python<'_>, timeout: f64) -> bool {
        let state = self.state.clone();
        let timeout = Duration::try_from_secs_f64(timeout).unwrap_or(if timeout > 0.0 {
            Duration::from_secs(u32::MAX.into())
        } else {
            Duration::ZERO
        });
        py.detach(move || {
            let (lock, turn) = &*state;
            let at = lock.lock().unwrap_or_else(|e| e.into_inner());
            let (at, _) = turn
                .wait_timeout_while(at, timeout, |s| *s == 0)
                .unwrap_or_else(|e| e.into_inner());
            *at >= 1
        })
    }

    /// Lets the signalled step go on to its solve.
    fn answer(&self) {
        let (lock, turn) = &*self.state;
        *lock.lock().unwrap_or_else(|e| e.into_inner()) = 2;
        turn.notify_all();
    }
}

/// The library's table of settings, the keywords of `Deformer`: one dict
/// per setting with its `name`, `values`, `default`, `presets` (the
/// presets whose value differs, and that value) and `help`.
#[pyfunction]
fn settings_table(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let rows = PyList::empty(py);
    for setting in verbss::settings::TABLE {
        let row = PyDict::new(py);
        row.set_item("name", setting.name)?;
        row.set_item("values", setting.values.describe())?;
        row.set_item("default", setting.default)?;
        let presets = PyDict::new(py);
        for (preset, value) in setting.presets {
            presets.set_item(preset.name(), *value)?;
        }
        row.set_item("presets", presets)?;
        row.set_item("help", setting.help)?;
        rows.append(row)?;
    }
    Ok(rows)
}

/// verbss: Vertex-Ball Spring Smoothing mesh motion, native part.
#[pymodule]
fn _verbss(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("VerbssError", m.py().get_type::<VerbssError>())?;
    m.add_class::<Mesh>()?;
    m.add_class::<Deformer>()?;
    m.add_class::<GilProbe>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(quality_json, m)?)?;
    m.add_function(wrap_pyfunction!(settings_table, m)?)?;
    Ok(())
}
