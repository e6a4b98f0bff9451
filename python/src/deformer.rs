//! The `Deformer` class: a mesh in motion, stepped by a flow solver.

use std::collections::HashMap;

use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use verbss::deform::StepReport;
use verbss::motion::{check_displacement, Attachment, Motion, PositionSource};
use verbss::settings::Settings;

use crate::{asarray, invalid_setting, pairs, points_array, raise, shape_text, GilProbe, Mesh};

/// The library's deformer and its moving groups, fixed by the first step.
struct Moving {
    deformer: verbss::deform::Deformer,
    /// The moving groups, in the order of the first step (attachment `k`
    /// moves group `names[k]`).
    names: Vec<String>,
}

/// A mesh in motion, stepped by a flow solver (see `Deformer.step`).
///
/// Deformer(mesh, method="robust", *, slide=None, **settings)
///
/// Every keyword but `slide` is a setting of the library's one table
/// (`verbss.settings_table()`, docs/case-file.md): the same name as a case
/// file's `[solver]` key and `verbss deform`'s option (`-` for `_`), the
/// same values — a string, a number, or True/False for on/off; None or left
/// out: what `method` implies. `method` is "robust" (the default: VerBSS
/// with the near-wall treatments), "verbss" (the paper's method),
/// "ball-vertex", "spring" or "laplacian". `threads` defaults to one per
/// core; the results do not depend on it.
///
/// `slide`: group names, each sliding in its own plane, or a mapping of a
/// group name to its plane's normal (D numbers, or None for its own plane).
///
/// Invalid settings, unknown slide groups and slide normals of the wrong
/// length raise VerbssError here, not at the first step.
#[pyclass(module = "verbss")]
pub(crate) struct Deformer {
    mesh: verbss::Mesh,
    settings: Settings,
    /// The sliding walls.
    slide: Vec<Attachment>,
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
        attachments.extend(self.slide.iter().cloned());
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

/// A setting's value as the table spells it: True/False as on/off, a
/// number in its shortest exact form, a string as it is.
fn setting_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(b) = value.extract::<bool>() {
        return Ok((if b { "on" } else { "off" }).into());
    }
    if let Ok(k) = value.extract::<i64>() {
        return Ok(k.to_string());
    }
    if let Ok(x) = value.extract::<f64>() {
        return Ok(x.to_string());
    }
    value.extract::<String>()
}

/// The (N, D) displacement of a group from `value`: an (N, D) or (D,) array,
/// or a callable given the group's input coordinates and the step number.
fn displacement(
    value: &Bound<'_, PyAny>,
    (name, nodes): (&str, &[usize]),
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
        return Err(raise(verbss::Error::InvalidDisplacement(format!(
            "the displacement of group '{name}' has shape {}, expected ({n}, {dim}) or ({dim},)",
            shape_text(&shape)
        ))));
    };
    check_displacement(&u, dim, |row| {
        format!(
            "Python Deformer.step displacement of node {} (row {row} of group '{name}')",
            nodes[row]
        )
    })
    .map_err(raise)?;
    Ok(u)
}

/// The sliding walls: group names, each sliding in its own plane, or a
/// mapping of a group name to its plane's normal (D numbers) or None.
fn slides(value: &Bound<'_, PyAny>, mesh: &verbss::Mesh) -> PyResult<Vec<Attachment>> {
    let given: Vec<(String, Option<Vec<f64>>)> = if value.hasattr("items")? {
        pairs(value)?
            .into_iter()
            .map(|(name, normal)| {
                let normal = (!normal.is_none())
                    .then(|| vector(&normal, &name, mesh.dim))
                    .transpose()?;
                Ok((name, normal))
            })
            .collect::<PyResult<_>>()?
    } else if value.is_instance_of::<PyString>() {
        return Err(invalid_setting(format!(
            "slide must be a list of group names or a mapping of a group name to its \
             plane's normal (got the string '{value}')"
        )));
    } else {
        let names: Vec<String> = value.extract()?;
        names.into_iter().map(|name| (name, None)).collect()
    };
    given
        .iter()
        .map(|(name, normal)| {
            mesh.group(name).map_err(raise)?;
            Attachment::slide(name, normal.as_deref(), mesh.dim).map_err(raise)
        })
        .collect()
}

/// The numbers of a 1-D array: the slide normal of group `name`.
fn vector(value: &Bound<'_, PyAny>, name: &str, dim: usize) -> PyResult<Vec<f64>> {
    let array = asarray(value, "float64")?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    if shape.len() != 1 {
        return Err(invalid_setting(format!(
            "the slide normal of group '{name}' has shape {}, expected ({dim},)",
            shape_text(&shape)
        )));
    }
    let a: PyReadonlyArray1<f64> = array.extract()?;
    Ok(a.as_array().to_vec())
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
    #[pyo3(signature = (mesh, method = "robust", *, slide = None, **settings))]
    fn new(
        mesh: &Mesh,
        method: &str,
        slide: Option<&Bound<'_, PyAny>>,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Deformer> {
        let mut named = vec![("method".to_string(), method.to_string())];
        for (name, value) in settings.iter().flat_map(|d| d.iter()) {
            let name: String = name.extract()?;
            if value.is_none() {
                continue;
            }
            named.push((name, setting_text(&value)?));
        }
        let settings = Settings::named(1, &named).map_err(raise)?;
        let slide = slide
            .map(|s| slides(s, &mesh.inner))
            .transpose()?
            .unwrap_or_default();
        Ok(Deformer {
            mesh: mesh.inner.clone(),
            settings,
            slide,
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
        // A misspelt group is unknown, whatever the first step moved.
        for name in &names {
            self.mesh.group(name).map_err(raise)?;
        }
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
            let x0 = points_array(py, &coords, dim);
            let u = displacement(value, (name, &nodes), &x0, step)?;
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
