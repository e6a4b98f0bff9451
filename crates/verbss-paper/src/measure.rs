//! Running one method on one case: the case file's run (continued for the
//! limit search where the case says so), its per-step means and the
//! histograms.

use std::time::Instant;

use serde::Serialize;
use verbss::deform::{Deformer, Snapshot, StepReport};
use verbss::mesh::Mesh;
use verbss::motion::Attachment;
use verbss::settings::Settings;
use verbss::solve::{Method, Solver};
use verbss::Error;

/// The methods compared, in the tables' order: name, method, solver.
pub const METHODS: [(&str, Method, Solver); 4] = [
    ("spring", Method::Spring, Solver::Sor),
    ("laplacian", Method::Laplacian, Solver::Sor),
    ("ball-vertex", Method::BallVertex, Solver::Sor),
    ("verbss", Method::Verbss, Solver::Sor),
];

/// What stepping a mesh through a motion did.
pub struct Run {
    /// The accepted steps' reports, step 1 first.
    pub steps: Vec<StepReport>,
    /// The step that inverted an element, if one did.
    pub first_inverted: Option<usize>,
    /// The centroid of that step's worst inverted element.
    pub inverted_at: Option<Vec<f64>>,
    /// The states kept (the requested steps that were reached).
    pub kept: Vec<Snapshot>,
    /// The state of the step that inverted, if one did.
    pub failed: Option<Snapshot>,
    /// The last accepted state.
    pub last: Snapshot,
    /// Wall seconds of the whole run.
    pub seconds: f64,
}

/// Steps `mesh` through `attachments` from step 1 to `last` (past the
/// settings' `N` the motions continue linearly) and stops at the first
/// inverted element; keeps the states of the steps in `keep`. `label`
/// prefixes the progress lines on stderr.
pub fn run(
    mesh: &Mesh,
    attachments: &[Attachment],
    settings: &Settings,
    last: usize,
    keep: &[usize],
    label: &str,
) -> anyhow::Result<Run> {
    let start = Instant::now();
    let mut deformer = Deformer::new(mesh, attachments, settings.clone())?;
    let mut out = Run {
        steps: Vec::new(),
        first_inverted: None,
        inverted_at: None,
        kept: Vec::new(),
        failed: None,
        last: deformer.current().clone(),
        seconds: 0.0,
    };
    if keep.contains(&0) {
        out.kept.push(deformer.current().clone());
    }
    let mut shown = Instant::now();
    for n in 1..=last {
        match deformer.step(n) {
            Ok(report) => {
                out.steps.push(report);
                if keep.contains(&n) {
                    out.kept.push(deformer.current().clone());
                }
            }
            Err(Error::Inverted { centroid, .. }) => {
                out.first_inverted = Some(n);
                out.inverted_at = Some(centroid);
                out.failed = deformer.failed().cloned();
                break;
            }
            Err(e) => return Err(e.into()),
        }
        if shown.elapsed().as_secs_f64() > 10.0 {
            shown = Instant::now();
            eprintln!(
                "  {label}: step {n}/{last}, {:.1} s",
                start.elapsed().as_secs_f64()
            );
        }
    }
    out.seconds = start.elapsed().as_secs_f64();
    out.last = deformer.current().clone();
    let end = match out.first_inverted {
        Some(n) => format!("first inversion at step {n}"),
        None => "no inversion".to_string(),
    };
    eprintln!(
        "  {label}: {} steps, {end}, {:.1} s",
        out.steps.len(),
        out.seconds
    );
    Ok(out)
}

/// Means over steps (of a method's run of the prescribed motion).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Means {
    /// How many steps the means are over.
    pub steps: usize,
    /// Solver sweeps per step.
    pub iterations_per_step: f64,
    /// Wall seconds per step (motion, forming, solving, updating, checking).
    pub seconds_per_step: f64,
    /// Forming the system (paper's Part I).
    pub form_seconds_per_step: f64,
    /// Solving it (Part II).
    pub solve_seconds_per_step: f64,
    /// The rest of the step: boundary motion, coordinate update and the
    /// quality and inversion check (Part III).
    pub update_seconds_per_step: f64,
    /// The smallest element quality over these steps.
    pub min_quality: f64,
    /// Whether every step met the stop test (else some stopped at k_max).
    pub all_converged: bool,
}

impl Means {
    /// The means over `steps` (empty: all zero).
    pub fn of(steps: &[StepReport]) -> Means {
        let k = steps.len().max(1) as f64;
        let mean = |f: &dyn Fn(&StepReport) -> f64| steps.iter().map(f).sum::<f64>() / k;
        Means {
            steps: steps.len(),
            iterations_per_step: mean(&|r| r.iterations as f64),
            seconds_per_step: mean(&|r| r.seconds),
            form_seconds_per_step: mean(&|r| r.form_seconds),
            solve_seconds_per_step: mean(&|r| r.solve_seconds),
            update_seconds_per_step: mean(&|r| r.seconds - r.form_seconds - r.solve_seconds),
            min_quality: steps
                .iter()
                .map(|r| r.min_quality)
                .fold(f64::INFINITY, f64::min),
            all_converged: steps.iter().all(|r| r.converged),
        }
    }
}
