//! The native part of the `verbss` Python package (`verbss._verbss`): the
//! [`Mesh`] and [`Deformer`] classes, `read`, `quality_json` and the
//! `VerbssError` exception, over numpy arrays. `python/verbss/__init__.py`
//! re-exports them and adds the meshio conversions.
//!
//! Every library error becomes a `VerbssError` whose message is the error's
//! own text, the one the `verbss` command prints after `error: `.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::str::FromStr;
use verbss::deform::{Preset, Settings, StepReport};
use verbss::io::WriteOptions;
use verbss::motion::{Attachment, Motion, PositionSource};
use verbss::{CellKind, Cells, Error, Group};

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
/// number of columns (1 for a 1-D array).
fn node_ids(value: &Bound<'_, PyAny>, n: usize, what: &str) -> PyResult<(Vec<usize>, usize)> {
    let array = asarray(value, "int64")?;
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
                .filter(|k| k.dim() >= 2)
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
                            .filter(|k| k.dim() < dim && k.node_count() == columns)
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

/// Reads a mesh file (.msh Gmsh 2.2/4.1, .su2, .vtu), chosen by extension.
///
/// Raises VerbssError naming the file, the line and what was expected.
#[pyfunction]
fn read(py: Python<'_>, path: PathBuf) -> PyResult<Mesh> {
    let inner = py.detach(|| verbss::io::read(&path)).map_err(raise)?;
    Ok(Mesh { inner })
}

/// The `verbss quality --json` summary of a mesh, as JSON text.
#[pyfunction]
fn quality_json(py: Python<'_>, mesh: &Mesh) -> String {
    let m = &mesh.inner;
    py.detach(|| verbss::quality::summary_json(m).to_string())
}

/// The library's deformer and its moving groups, fixed by the first step.
struct Moving {
    deformer: verbss::deform::Deformer,
    /// The moving groups, in the order of the first step (attachment `k`
    /// moves group `names[k]`).
    names: Vec<String>,
}

/// A mesh in motion, stepped by a flow solver (see `Deformer.step`).
///
/// Deformer(mesh, method="robust", omega=None, tolerance=None,
///          max_iterations=None, threads=0, reference="updated", solver=None,
///          accel=None)
///
/// - method: "robust" (the default, as on the command line: verbss with the
///   near-wall treatments and the blended rigid motion of
///   docs/robustness.md), "verbss" (the paper's method: edge + ball-vertex
///   springs, node by node), "ball-vertex"
///   (the same system solved globally by `solver`, "sor" or "direct"),
///   "spring" (edge springs only) or "laplacian".
/// - omega: the over-relaxation factor of the sweeps (1.6 when None).
///   omega, solver and accel all None: a step whose sweeps stall or diverge,
///   or leave a node's estimated error above 1% of its cell height,
///   escalates to the multigrid and the direct solve (docs/method.md); any
///   of them given: exactly that solver.
/// - tolerance: the sweeps stop when the mean absolute change of one sweep is
///   below tolerance × the step's largest prescribed displacement (1e-6
///   when None).
/// - max_iterations: the most sweeps per step (2000 when None).
/// Invalid settings raise VerbssError here, not at the first step.
/// - threads: worker threads, 0 for one per core; results do not depend on it.
/// - reference: "updated" (springs on the current mesh each step) or
///   "fixed" (also spelled "initial": springs on the input mesh, solving for
///   the total displacement).
/// - accel: "none" (plain VerBSS sweeps), "amg" (GMRES around a multigrid
///   V-cycle whose smoother is the VerBSS sweep; tolerance then bounds the
///   estimated RMS error) or "auto" (amg on large meshes of mostly
///   triangles/tetrahedra), for the methods verbss and spring.
/// - keyword only, as `verbss deform`'s options of the same names (None: what
///   `method` implies): slide (groups whose nodes slide in their own plane),
///   rigid_layer ("off", "auto" or a wall distance), stiffening (exponent
///   ≥ 0), substeps (halvings of a step, at most 30), blend (True/False: the
///   blended rigid motion), predictor ("previous" or "linear").
#[pyclass(module = "verbss")]
struct Deformer {
    mesh: verbss::Mesh,
    settings: Settings,
    /// Groups whose nodes slide in their own plane.
    slide: Vec<String>,
    moving: Option<Moving>,
}

impl Deformer {
    /// Builds the library's deformer for the groups of the first step.
    fn start(&mut self, py: Python<'_>, names: &[String]) -> PyResult<()> {
        // The moving groups first: attachment k is the k-th name.
        let mut attachments: Vec<Attachment> = names
            .iter()
            .map(|name| Attachment {
                groups: vec![name.clone()],
                motion: Motion::Positions(PositionSource::Given(HashMap::new())),
            })
            .collect();
        if !self.slide.is_empty() {
            attachments.push(Attachment {
                groups: self.slide.clone(),
                motion: Motion::Slide { normal: None },
            });
        }
        let (mesh, settings) = (&self.mesh, &self.settings);
        let deformer = py
            .detach(|| verbss::deform::Deformer::new(mesh, &attachments, settings.clone()))
            .map_err(raise)?;
        self.moving = Some(Moving {
            deformer,
            names: names.to_vec(),
        });
        Ok(())
    }
}

/// The (N, D) displacement of a group from `value`: an (N, D) or (D,) array,
/// or a callable given the group's input coordinates and the step number.
fn displacement(
    value: &Bound<'_, PyAny>,
    name: &str,
    x0: &Bound<'_, PyArray2<f64>>,
    step: usize,
) -> PyResult<Vec<f64>> {
    let value = if value.is_callable() {
        value.call1((x0, step))?
    } else {
        value.clone()
    };
    let array = asarray(&value, "float64")?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    let (n, dim) = (x0.shape()[0], x0.shape()[1]);
    let u: Vec<f64> = if shape == [n, dim] {
        let a: PyReadonlyArray2<f64> = array.extract()?;
        a.as_array().iter().copied().collect()
    } else if shape == [dim] {
        let a: PyReadonlyArray1<f64> = array.extract()?;
        let row = a.as_array().to_vec();
        row.iter().copied().cycle().take(n * dim).collect()
    } else {
        return Err(invalid_setting(format!(
            "the displacement of group '{name}' has shape {}, expected ({n}, {dim}) or ({dim},)",
            shape_text(&shape)
        )));
    };
    if let Some(k) = u.iter().position(|x| !x.is_finite()) {
        return Err(invalid_setting(format!(
            "the displacement of group '{name}' is not finite at row {}",
            k / dim
        )));
    }
    Ok(u)
}

fn report_dict<'py>(py: Python<'py>, r: &StepReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("step", r.step)?;
    d.set_item("iterations", r.iterations)?;
    d.set_item("residual", r.residual)?;
    d.set_item("converged", r.converged)?;
    d.set_item("seconds", r.seconds)?;
    d.set_item("form_seconds", r.form_seconds)?;
    d.set_item("solve_seconds", r.solve_seconds)?;
    d.set_item("min_quality", r.min_quality)?;
    d.set_item("mean_quality", r.mean_quality)?;
    d.set_item("inverted", r.inverted)?;
    d.set_item("bins", PyList::new(py, r.bins)?)?;
    Ok(d)
}

#[pymethods]
impl Deformer {
    #[new]
    #[pyo3(signature = (
        mesh,
        method = "robust",
        omega = None,
        tolerance = None,
        max_iterations = None,
        threads = 0,
        reference = "updated",
        solver = None,
        accel = None,
        *,
        slide = None,
        rigid_layer = None,
        stiffening = None,
        substeps = None,
        blend = None,
        predictor = None,
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        mesh: &Mesh,
        method: &str,
        omega: Option<f64>,
        tolerance: Option<f64>,
        max_iterations: Option<i64>,
        threads: i64,
        reference: &str,
        solver: Option<&str>,
        accel: Option<&str>,
        slide: Option<Vec<String>>,
        rigid_layer: Option<&Bound<'_, PyAny>>,
        stiffening: Option<f64>,
        substeps: Option<i64>,
        blend: Option<bool>,
        predictor: Option<&str>,
    ) -> PyResult<Deformer> {
        let count = |name: &str, v: i64| {
            usize::try_from(v)
                .map_err(|_| invalid_setting(format!("{name} must be zero or positive (got {v})")))
        };
        let mut settings = Preset::from_str(method).map_err(raise)?.settings(1);
        settings.reference = reference.parse().map_err(raise)?;
        let s = &mut settings.solve;
        // A solver, accel or omega given means exactly that solver.
        s.escalate = solver.is_none() && accel.is_none() && omega.is_none();
        if let Some(solver) = solver {
            s.solver = solver.parse().map_err(raise)?;
        }
        if let Some(accel) = accel {
            s.accel = accel.parse().map_err(raise)?;
        }
        s.omega = omega.unwrap_or(s.omega);
        s.tolerance = tolerance.unwrap_or(s.tolerance);
        if let Some(k) = max_iterations {
            s.max_iterations = count("max_iterations", k)?;
        }
        s.threads = count("threads", threads)?;
        if let Some(p) = predictor {
            settings.predictor = p.parse().map_err(raise)?;
        }
        let robust = &mut settings.robust;
        if let Some(layer) = rigid_layer {
            let text = match layer.extract::<f64>() {
                Ok(t) => t.to_string(),
                Err(_) => layer.extract::<String>()?,
            };
            robust.layer = text.parse().map_err(raise)?;
        }
        robust.stiffening = stiffening.unwrap_or(robust.stiffening);
        if let Some(k) = substeps {
            robust.substeps = u32::try_from(count("substeps", k)?).unwrap_or(u32::MAX);
        }
        robust.blend = blend.unwrap_or(robust.blend);
        settings.validate().map_err(raise)?;
        Ok(Deformer {
            mesh: mesh.inner.clone(),
            settings,
            slide: slide.unwrap_or_default(),
            moving: None,
        })
    }

    /// Takes the next time step and returns the new node coordinates, an
    /// (N, D) float64 array.
    ///
    /// `displacements` maps each moving group's name to its displacement from
    /// the input mesh at this step: an (n, D) array (rows in the order of
    /// `mesh.groups[name]`), a (D,) array (the same for every node), or a
    /// callable `f(points, step)` given the group's input coordinates (an
    /// (n, D) array, same order) and the step number (1 for the first step),
    /// returning either. Each node of a group goes exactly to its input
    /// position plus its displacement; a node in several moving groups
    /// follows the first one named. Every other boundary node stays where it
    /// is, the interior nodes follow by the springs. The first step fixes
    /// which groups move: every later step names the same groups.
    ///
    /// The solve runs with the GIL released (`probe`, a [`GilProbe`], shows
    /// it). Raises VerbssError when a group
    /// is unknown, a displacement has the wrong shape or is not finite, or the
    /// step inverted an element: the step is then rejected and the deformer
    /// keeps the last accepted step (so the same step can be retried).
    #[pyo3(signature = (displacements, *, probe = None))]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        displacements: &Bound<'py, PyAny>,
        probe: Option<&Bound<'py, GilProbe>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let given = pairs(displacements)?;
        let names: Vec<String> = given.iter().map(|(n, _)| n.clone()).collect();
        match &self.moving {
            None if names.is_empty() => {
                return Err(invalid_setting(
                    "the first step names no group to move".into(),
                ))
            }
            Some(m) => {
                let (mut asked, mut moved) = (names.clone(), m.names.clone());
                asked.sort();
                moved.sort();
                if asked != moved {
                    return Err(invalid_setting(format!(
                        "the step moves {} but the deformer moves {} (the groups of its first step)",
                        names.join(", "),
                        moved.join(", ")
                    )));
                }
            }
            None => {}
        }
        let step = self
            .moving
            .as_ref()
            .map_or(1, |m| m.deformer.current_step() + 1);
        let mesh = &self.mesh;
        let dim = mesh.dim;
        let mut positions = Vec::with_capacity(given.len());
        for (name, value) in &given {
            let nodes = mesh.group(name).map_err(raise)?.nodes();
            let coords: Vec<f64> = nodes.iter().flat_map(|&i| mesh.point(i).to_vec()).collect();
            let u = displacement(value, name, &points_array(py, &coords, dim), step)?;
            let targets: HashMap<usize, Vec<f64>> = nodes
                .iter()
                .zip(u.chunks(dim))
                .map(|(&i, d)| (i, mesh.point(i).iter().zip(d).map(|(x, d)| x + d).collect()))
                .collect();
            positions.push(targets);
        }
        if self.moving.is_none() {
            self.start(py, &names)?;
        }
        let moving = self.moving.as_mut().expect("started above");
        for (k, name) in moving.names.iter().enumerate() {
            let at = names.iter().position(|n| n == name).expect("same names");
            let targets = std::mem::take(&mut positions[at]);
            moving
                .deformer
                .set_motion(k, Motion::Positions(PositionSource::Given(targets)))
                .map_err(raise)?;
        }
        let deformer = &mut moving.deformer;
        let probe = probe.map(|p| p.get().state.clone());
        py.detach(|| {
            if let Some(state) = probe {
                GilProbe::signal_and_wait(&state)?;
            }
            deformer.advance()
        })
        .map_err(raise)?;
        Ok(points_array(py, &deformer.current().coords, dim))
    }

    /// The current node coordinates, an (N, D) float64 array (a copy).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let coords = match &self.moving {
            Some(m) => &m.deformer.current().coords,
            None => &self.mesh.coords,
        };
        points_array(py, coords, self.mesh.dim)
    }

    /// The input mesh with the current coordinates.
    #[getter]
    fn mesh(&self) -> Mesh {
        let inner = match &self.moving {
            Some(m) => m.deformer.mesh(),
            None => self.mesh.clone(),
        };
        Mesh { inner }
    }

    /// What the last accepted step did, or None before the first step: a dict
    /// with step, iterations, residual, converged, seconds (form_seconds and
    /// solve_seconds of it), min_quality, mean_quality, inverted and bins
    /// (element counts in the quality bins 0–0.02, 0.02–0.1, 0.1–0.4, 0.4–0.7,
    /// 0.7–1).
    #[getter]
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        self.moving
            .as_ref()
            .map(|m| report_dict(py, &m.deformer.current().report))
            .transpose()
    }

    fn __repr__(&self) -> String {
        let step = self
            .moving
            .as_ref()
            .map_or(0, |m| m.deformer.current_step());
        format!(
            "<verbss.Deformer {}D, {} nodes, step {step}>",
            self.mesh.dim,
            self.mesh.node_count()
        )
    }
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

/// verbss: Vertex-Ball Spring Smoothing mesh motion, native part.
#[pymodule]
fn _verbss(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("VerbssError", m.py().get_type::<VerbssError>())?;
    m.add_class::<Mesh>()?;
    m.add_class::<Deformer>()?;
    m.add_class::<GilProbe>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(quality_json, m)?)?;
    Ok(())
}
