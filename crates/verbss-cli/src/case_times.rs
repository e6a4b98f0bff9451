//! `--dt` and `--start-time`: the times of the steps `deform` writes.
//!
//! An OpenFOAM output that is the input case gets each written step `n` in
//! the time directory of `t = startTime + n·deltaT`, named as OpenFOAM
//! names times ([`Times`]): from the case's `system/controlDict`, each
//! value replaced by the option given. `--dt` also sets the time per step
//! of a `.pvd` series.

use std::path::Path;

use anyhow::bail;
use clap::Args;
use verbss::error::format_number;
use verbss::io::foam::{self, Times};
use verbss::io::Format;

/// The time options of `verbss deform`.
#[derive(Args, Clone, Default)]
pub struct TimeArgs {
    /// Time per step: of the time directories written into the input
    /// OpenFOAM case (CASE/TIME/polyMesh), and of a .pvd series
    /// [default: the case's deltaT in system/controlDict; else 1/steps].
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    dt: Option<f64>,
    /// Time of step 0 of the time directories written into the input
    /// OpenFOAM case [default: the case's startTime in system/controlDict].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    start_time: Option<f64>,
}

impl TimeArgs {
    /// `--dt`, checked positive.
    pub fn dt(&self) -> anyhow::Result<Option<f64>> {
        match self.dt {
            Some(dt) if !(dt > 0.0 && dt.is_finite()) => {
                bail!(
                    "--dt must be a positive number of time per step (got {})",
                    format_number(dt)
                )
            }
            dt => Ok(dt),
        }
    }

    /// The times of the time directories of `output` when it is the
    /// OpenFOAM case `input` (all `steps` of them named apart); `None` for
    /// any other output, which `--start-time` does not apply to.
    pub fn case_times(
        &self,
        input: &Path,
        output: &Path,
        steps: usize,
    ) -> anyhow::Result<Option<Times>> {
        let dt = self.dt()?;
        if let Some(t) = self.start_time.filter(|t| !t.is_finite()) {
            bail!(
                "--start-time must be a finite time (got {})",
                format_number(t)
            );
        }
        let Some(case) = in_case(input, output) else {
            if self.start_time.is_some() {
                bail!(
                    "--start-time names the time directories of an OpenFOAM output that is \
                     the input case ({} is not)",
                    output.display()
                );
            }
            return Ok(None);
        };
        let times = Times::of_case(&case, self.start_time, dt)?;
        times.check_distinct(steps)?;
        Ok(Some(times))
    }
}

/// The case directory of `output` when it is the OpenFOAM case (or its
/// polyMesh) that `input` is.
pub fn in_case(input: &Path, output: &Path) -> Option<std::path::PathBuf> {
    let foam = |p: &Path| matches!(Format::from_path(p), Ok(Format::Foam));
    (foam(input) && foam(output) && foam::same_polymesh(input, output))
        .then(|| foam::case_dir(&foam::polymesh_dir(output)))
}
