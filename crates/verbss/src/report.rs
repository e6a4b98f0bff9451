//! `report.json`: the settings of a run and one record per step.
//!
//! ```json
//! { "verbss": "0.1.0", "mesh": "naca.su2", "dim": 2, "nodes": 4500, "cells": 8700,
//!   "step_count": 160, "dt": 0.00625,
//!   "settings": { "method": "robust", "reference": "anchored", "rigid_layer": "auto", … },
//!   "outcome": "completed",
//!   "steps": [ { "step": 1, "iterations": 41, "residual": 8.9e-6, "seconds": 0.004,
//!                "min_quality": 0.31, "inverted": 0, "bins": [0, 0, 12, 803, 7885], … } ] }
//! ```
//! `settings` is a case file's `[solver]` table, every setting of
//! [`crate::settings::TABLE`] under its own name: pasted back it runs the
//! same steps. Step 0 is the input mesh. `residual` is the paper's eq.-8
//! value of the last sweep; `bins` counts elements in the paper's quality
//! bins 0–0.02, 0.02–0.1, 0.1–0.4, 0.4–0.7, 0.7–1.

use std::io::Write;
use std::path::Path;

use serde::Serialize;

use crate::deform::StepReport;
use crate::error::Result;
use crate::io::write_atomic;
use crate::settings::Settings;

/// A run's report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// The verbss version that wrote it.
    pub verbss: &'static str,
    /// The input mesh (as named by the user).
    pub mesh: String,
    /// Its dimension.
    pub dim: usize,
    /// Its node count.
    pub nodes: usize,
    /// Its element count.
    pub cells: usize,
    /// The number of steps of the run (a case file's `steps`).
    pub step_count: usize,
    /// The time per step (a case file's `dt`).
    pub dt: f64,
    /// The settings: a case file's `[solver]` table.
    pub settings: serde_json::Map<String, serde_json::Value>,
    /// `completed`, or what stopped the run (the error message).
    pub outcome: String,
    /// One record per step, in order; the last one is the failed step when
    /// the run stopped on an inversion.
    pub steps: Vec<StepReport>,
}

impl Report {
    /// An empty report (outcome `running`) of a run of `nodes` nodes and
    /// `cells` cells in `dim` dimensions read from `name`, with `settings`.
    pub fn new(
        name: &str,
        (dim, nodes, cells): (usize, usize, usize),
        settings: &Settings,
    ) -> Report {
        Report {
            verbss: env!("CARGO_PKG_VERSION"),
            mesh: name.to_string(),
            dim,
            nodes,
            cells,
            step_count: settings.steps,
            dt: settings.dt,
            settings: settings.solver_table(),
            outcome: "running".to_string(),
            steps: Vec::new(),
        }
    }

    /// Writes the report as pretty JSON, atomically.
    pub fn write(&self, path: &Path) -> Result<()> {
        write_atomic(path, |w: &mut dyn Write| {
            serde_json::to_writer_pretty(&mut *w, self)?;
            w.write_all(b"\n")
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::samples::one_triangle;
    use crate::near_wall::Layer;

    #[test]
    fn writes_the_step_keys_and_the_header() {
        let mesh = one_triangle();
        let size = (mesh.dim, mesh.node_count(), mesh.cell_count());
        let mut report = Report::new("tri.su2", size, &Settings::new(4));
        report.steps.push(StepReport {
            step: 1,
            iterations: 7,
            residual: 1e-7,
            min_quality: 0.8,
            bins: [0, 0, 0, 0, 1],
            ..StepReport::default()
        });
        report.outcome = "completed".into();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.json");
        report.write(&path).unwrap();
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let step = &v["steps"][0];
        for key in [
            "step",
            "iterations",
            "residual",
            "seconds",
            "min_quality",
            "inverted",
            "bins",
        ] {
            assert!(step.get(key).is_some(), "missing {key}");
        }
        assert_eq!(step["iterations"], 7);
        assert_eq!(step["bins"], serde_json::json!([0, 0, 0, 0, 1]));
        assert_eq!(v["settings"]["method"], "verbss");
        assert_eq!(v["settings"]["reference"], "updated");
        assert_eq!(v["step_count"], 4);
        assert_eq!(v["nodes"], 3);
        assert_eq!(v["outcome"], "completed");
    }

    /// Every setting is in the header, under the names of the case file.
    #[test]
    fn the_header_is_the_solver_table() {
        let mut settings = Settings::robust(10);
        settings.robust.layer = Layer::Thickness(0.02);
        let v = serde_json::Value::Object(settings.solver_table());
        let expected = serde_json::json!({
            "method": "verbss", "reference": "auto", "predictor": "previous",
            "rigid_layer": 0.02, "stiffening": 1.0, "substeps": 6, "blend": true,
            "relocate": true,
            "solver": "sor", "accel": "auto", "escalate": true, "omega": 1.6,
            "tolerance": 1e-6, "absolute_tolerance": false, "max_iterations": 2000,
            "threads": 0
        });
        assert_eq!(v, expected);
        let v = Settings::robust(10).solver_table();
        assert_eq!(v["method"], "robust");
        assert_eq!(v["rigid_layer"], "auto");
    }
}
