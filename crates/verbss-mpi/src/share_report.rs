//! The `--report` of a run on shares: the single-process `report.json`
//! ([`verbss::report::Report`]) with each step's quality reduced over the
//! ranks ([`step_quality`]), written by rank 0.
//!
//! The header's `nodes` and `cells` are the whole mesh's (the owned nodes
//! and the cells summed over the ranks). Per step, what the distributed
//! sweeps do not compute is left open: `true_residual` is NaN (`null` in
//! the JSON), `error_ratio` too unless an escalating solve accepted the
//! step (the sweeper's estimate, docs/distributed.md, "Escalation without
//! the whole mesh"), `stages` is `["sweeps"]`, `["sweeps", "gmres"]` or
//! `["sweeps", "gmres", "safe-sweeps"]` (none where the blend alone moved
//! the mesh) and `substeps` the increments the step took.

use std::path::PathBuf;
use std::process::ExitCode;

use verbss::deform::StepReport;
use verbss::report::Report;
use verbss::Mesh;
use verbss_cli::deform::ShareJob;
use verbss_mpi::part::Part;
use verbss_mpi::step_quality::step_quality;
use verbss_mpi::Comm;

/// The steps so far, and where rank 0 writes them.
pub struct StepLog {
    report: Report,
    path: Option<PathBuf>,
    root: bool,
}

impl StepLog {
    /// The report of `job` with step 0, the input `mesh` (collective: this
    /// rank's share, `part` its part with the ghost layer).
    pub fn new(world: &Comm, job: &ShareJob, mesh: &Mesh, part: &Part, orientation: &[i8]) -> Self {
        let mut report = Report::new(&job.source, mesh, &job.settings);
        let owned = part.owner.iter().filter(|&&o| o == part.rank).count();
        report.nodes = world.sum(owned as u64) as usize;
        let initial = step_quality(world, mesh, &mesh.coords, orientation);
        report.cells = initial.bins.iter().sum();
        report.steps.push(initial);
        StepLog {
            report,
            path: job.report.clone(),
            root: world.rank() == 0,
        }
    }

    /// Adds a step (the same on every rank).
    pub fn push(&mut self, step: StepReport) {
        self.report.steps.push(step);
    }

    /// The last step added.
    pub fn last(&self) -> &StepReport {
        self.report.steps.last().expect("step 0 is always there")
    }

    /// Ends the run at a failed step: rank 0 prints `message`, every rank
    /// writes its last valid state (`write`, collective), rank 0 writes the
    /// report with `message` as its outcome; exit code `code`.
    pub fn stop(
        &mut self,
        message: &str,
        code: u8,
        write: impl FnOnce() -> anyhow::Result<()>,
    ) -> anyhow::Result<ExitCode> {
        if self.root {
            eprintln!("error: {message}");
        }
        write()?;
        self.finish(message)?;
        Ok(ExitCode::from(code))
    }

    /// Rank 0 writes the report with `outcome`, when one was asked for.
    pub fn finish(&mut self, outcome: &str) -> anyhow::Result<()> {
        self.report.outcome = outcome.to_string();
        match &self.path {
            Some(path) if self.root => Ok(self.report.write(path)?),
            _ => Ok(()),
        }
    }
}
