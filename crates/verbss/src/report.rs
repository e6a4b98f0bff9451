//! `report.json`: the settings of a run and one record per step.
//!
//! ```json
//! { "verbss": "0.1.0", "mesh": "naca.su2", "dim": 2, "nodes": 4500, "cells": 8700,
//!   "settings": { "method": "verbss", "reference": "updated", "steps": 160, … },
//!   "outcome": "completed",
//!   "steps": [ { "step": 1, "iterations": 41, "residual": 8.9e-6, "seconds": 0.004,
//!                "min_quality": 0.31, "inverted": 0, "bins": [0, 0, 12, 803, 7885], … } ] }
//! ```
//! Step 0 is the input mesh. `residual` is the paper's eq.-8 value of the last
//! sweep; `bins` counts elements in the paper's quality bins 0–0.02, 0.02–0.1,
//! 0.1–0.4, 0.4–0.7, 0.7–1.

use std::io::Write;
use std::path::Path;

use serde::Serialize;

use crate::deform::{Predictor, Reference, Settings, StepReport};
use crate::error::Result;
use crate::io::write_atomic;
use crate::mesh::Mesh;
use crate::robust::Layer;

/// The settings header of a report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Header {
    /// `robust` (VerBSS with the recommended near-wall treatments),
    /// `verbss`, `ball-vertex`, `spring` or `laplacian`.
    pub method: &'static str,
    /// The global solver of `ball-vertex`: `sor` or `direct`.
    pub solver: &'static str,
    /// `updated` (paper option 1) or `fixed` (option 2).
    pub reference: Reference,
    /// Steps of the run.
    pub steps: usize,
    /// Time per step.
    pub dt: f64,
    /// Over-relaxation factor ω.
    pub omega: f64,
    /// Stop tolerance ε.
    pub tolerance: f64,
    /// Whether ε is the paper's absolute eq.-8 threshold (else relative to the step's largest prescribed displacement).
    pub absolute_tolerance: bool,
    /// Maximum sweeps k_max.
    pub max_iterations: usize,
    /// Worker threads.
    pub threads: usize,
    /// Plain sweeps (`none`), the multigrid (`amg`) or chosen per mesh (`auto`).
    pub accel: &'static str,
    /// Whether a stalled, diverging or untrusted solve escalates to the
    /// multigrid and the direct solve (off when a solver, accel or ω was
    /// given explicitly).
    pub escalate: bool,
    /// Each step's initial guess: `previous` or `linear`.
    pub predictor: Predictor,
    /// The rigid layer: `off`, `auto` or its thickness.
    pub rigid_layer: String,
    /// The wall-distance stiffening exponent (0: off).
    pub stiffening: f64,
    /// Sub-steps: down to `1/2^substeps` of a step (0: off).
    pub substeps: u32,
    /// Whether the blended rigid motion moved the mesh before the springs.
    pub blend: bool,
}

impl Header {
    /// The header of a run with `settings`.
    pub fn new(settings: &Settings) -> Header {
        let s = &settings.solve;
        let robust = &settings.robust;
        let method = settings.preset().name();
        Header {
            method,
            solver: s.solver.name(),
            reference: settings.reference,
            steps: settings.steps,
            dt: settings.dt,
            omega: s.omega,
            tolerance: s.tolerance,
            absolute_tolerance: s.absolute_tolerance,
            max_iterations: s.max_iterations,
            threads: s.threads,
            accel: s.accel.name(),
            escalate: s.escalate,
            predictor: settings.predictor,
            rigid_layer: match robust.layer {
                Layer::Off => "off".into(),
                Layer::Auto => "auto".into(),
                Layer::Thickness(t) => t.to_string(),
            },
            stiffening: robust.stiffening,
            substeps: robust.substeps,
            blend: robust.blend,
        }
    }
}

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
    /// The settings.
    pub settings: Header,
    /// `completed`, or what stopped the run (the error message).
    pub outcome: String,
    /// One record per step, in order; the last one is the failed step when
    /// the run stopped on an inversion.
    pub steps: Vec<StepReport>,
}

impl Report {
    /// An empty report (outcome `running`) for `mesh`, read from `name`.
    pub fn new(name: &str, mesh: &Mesh, settings: &Settings) -> Report {
        Report {
            verbss: env!("CARGO_PKG_VERSION"),
            mesh: name.to_string(),
            dim: mesh.dim,
            nodes: mesh.node_count(),
            cells: mesh.cell_count(),
            settings: Header::new(settings),
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

    #[test]
    fn writes_the_step_keys_and_the_header() {
        let mesh = one_triangle();
        let mut report = Report::new("tri.su2", &mesh, &Settings::new(4));
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
        assert_eq!(v["settings"]["steps"], 4);
        assert_eq!(v["nodes"], 3);
        assert_eq!(v["outcome"], "completed");
    }
}
