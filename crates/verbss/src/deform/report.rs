//! What a step did ([`StepReport`], one line of `report.json`) and a
//! configuration with its check ([`Snapshot`]).

use serde::Serialize;

use super::accept::Totals;
use crate::mesh::Mesh;
use crate::quality;
use crate::solve::{SolveInfo, Stage};

/// What one step did (one line of `report.json`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct StepReport {
    /// The step `n` (0: the input mesh).
    pub step: usize,
    /// The increments the step was taken in (1 unless sub-steps were needed).
    pub substeps: usize,
    /// Solver sweeps (of all increments, the rejected ones too).
    pub iterations: usize,
    /// The final eq.-8 value (mean absolute change in the last sweep).
    pub residual: f64,
    /// Whether the solver's stop test was met.
    pub converged: bool,
    /// Wall seconds of the whole step (motion, solve, update, check).
    pub seconds: f64,
    /// Seconds forming the system (paper's Part I).
    pub form_seconds: f64,
    /// Seconds solving it (paper's Part II).
    pub solve_seconds: f64,
    /// Seconds assembling the springs (part of `form_seconds`).
    pub springs_seconds: f64,
    /// Seconds of the quality and inversion check of the new coordinates,
    /// and of the relocation of the worst cells' nodes before it.
    pub check_seconds: f64,
    /// Nodes moved by the relocation of the worst cells' nodes, over every
    /// solve of the step (docs/method.md, "Relocation of the worst cells' nodes").
    pub relocated: usize,
    /// The smallest element quality.
    pub min_quality: f64,
    /// The number of inverted elements.
    pub inverted: usize,
    /// Element counts in the paper's quality bins 0–0.02, 0.02–0.1, 0.1–0.4, 0.4–0.7, 0.7–1.
    pub bins: [usize; 5],
    /// The mean element quality.
    pub mean_quality: f64,
    /// The largest displacement of a node the step solved for over the
    /// largest of a node it prescribed, in this step (0 where the boundary
    /// did not move; docs/method.md, "Amplification").
    pub amplification: f64,
    /// The solvers the step used, in order of first use (`sweeps`,
    /// `multigrid`, `safe-sweeps`, `direct`).
    pub stages: Vec<Stage>,
    /// Root-mean-square true residual of the accepted solve.
    pub true_residual: f64,
    /// The worst node's estimated error relative to its local cell height
    /// in the accepted solve (docs/method.md, "Accepting a step").
    pub error_ratio: f64,
    /// The eq.-8 value of every sweep, when [`crate::solve::SolveParams::record_history`] is set.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub history: Vec<f64>,
}

impl StepReport {
    /// Adds one solve's account: sweeps, seconds, stages; the residuals and
    /// the error ratio are the last solve's.
    pub fn add(&mut self, info: &SolveInfo) {
        self.iterations += info.iterations;
        self.residual = info.residual;
        self.true_residual = info.true_residual;
        self.error_ratio = info.error_ratio;
        self.form_seconds += info.form_seconds;
        self.solve_seconds += info.solve_seconds;
        self.springs_seconds += info.springs_seconds;
        self.history.clone_from(&info.history);
        for stage in &info.stages {
            if !self.stages.contains(stage) {
                self.stages.push(*stage);
            }
        }
    }
}

/// A configuration of the mesh with its check. The quality of each cell is
/// not kept (8 bytes a cell for the whole run): [`Snapshot::qualities`]
/// measures it again, as the check did.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Node coordinates (D·N).
    pub coords: Vec<f64>,
    /// Whether each cell is inverted relative to the input mesh.
    pub inverted: Vec<bool>,
    /// The step's report.
    pub report: StepReport,
}

impl Snapshot {
    /// The quality of each cell of `mesh`, the input mesh this configuration
    /// moves, relative to its orientation ([`quality::qualities`]).
    pub fn qualities(&self, mesh: &Mesh) -> Vec<f64> {
        quality::qualities(mesh, &self.coords, &quality::orientation(mesh))
    }
}

/// A report with the quality of a configuration, `totals`.
pub(super) fn summarize(totals: &Totals) -> StepReport {
    StepReport {
        min_quality: totals.min_quality,
        mean_quality: totals.mean_quality,
        inverted: totals.invalid,
        bins: totals.bins,
        ..StepReport::default()
    }
}
