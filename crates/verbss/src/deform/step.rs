//! One step: the boundary at its targets, in adaptive sub-steps, each
//! solved and checked ([`super::attempt`], [`super::accept`]), the last
//! accepted configuration kept or the failed one reported.

use std::time::Instant;

use super::accept::{Check, Totals};
use super::attempt::Attempt;
use super::report::{summarize, Snapshot, StepReport};
use super::Deformer;
use crate::collective::Collective;
use crate::error::{Error, Result, Unconverged};
use crate::settings::{Predictor, Reference};
use crate::solve::{NodeRole, SolveInfo, SpringSolver, Stage};

impl<S: SpringSolver, C: Collective> Deformer<S, C> {
    /// Moves the boundary to its position at step `n` and the interior with
    /// it, from the last accepted configuration (collective). On success
    /// the new configuration is accepted and its report returned. When a
    /// cell is invalid — in the smallest increment [`crate::near_wall::Robust`]
    /// allows — the configuration is rejected (kept in
    /// [`Deformer::failed`], the current one stays) and [`Error::Inverted`]
    /// names the worst cell of any process.
    pub fn step(&mut self, n: usize) -> Result<StepReport> {
        let start = Instant::now();
        let targets = self.targets(n)?;
        super::periodic::check(&self.periodic, &self.mesh, &targets, n)?;
        // The step starts from the current coordinates, lent to it rather
        // than copied, and given back when it fails.
        let from = std::mem::take(&mut self.current.coords);
        let stepped = self.step_from(n, &targets, &from, start);
        if stepped.is_err() {
            self.current.coords = from;
        }
        stepped
    }

    /// [`Deformer::step`] from coordinates `from` to `targets`, in adaptive
    /// sub-steps: the new current snapshot, or the error.
    fn step_from(
        &mut self,
        n: usize,
        targets: &[(usize, Vec<f64>)],
        from: &[f64],
        start: Instant,
    ) -> Result<StepReport> {
        // With a total unknown the accepted mesh does not depend on the
        // increments taken to reach it: no sub-steps.
        let updated = self.settings.reference == Reference::Updated;
        let substeps = if updated {
            self.settings.robust.substeps.min(30)
        } else {
            0
        };
        let floor = 0.5f64.powi(substeps as i32);
        let mut reference_quality = if updated {
            self.current.report.min_quality
        } else {
            self.input_quality
        };
        // The last accepted sub-step's coordinates (`None`: `from`).
        let mut coords: Option<Vec<f64>> = None;
        let (mut done, mut h) = (0.0, 1.0);
        let mut report = StepReport {
            step: n,
            converged: true,
            ..StepReport::default()
        };
        let dim = self.mesh.dim;
        loop {
            let end = if done + h >= 1.0 { 1.0 } else { done + h };
            let at: Vec<(usize, Vec<f64>)> = targets
                .iter()
                .map(|(i, p)| {
                    let x0 = &from[dim * i..dim * (i + 1)];
                    let q = if end == 1.0 {
                        p.clone()
                    } else {
                        x0.iter().zip(p).map(|(a, b)| a + end * (b - a)).collect()
                    };
                    (*i, q)
                })
                .collect();
            let at_start = coords.as_deref().unwrap_or(from);
            let attempt = self.chosen(at_start, &at, end - done, reference_quality, &mut report)?;
            let Attempt {
                coords: trial,
                u,
                info,
                check,
                ..
            } = attempt;
            report.add(&info);
            report.amplification = self.amplification(from, &trial);
            if !info.converged || check.summary.invalid > 0 {
                if h * 0.5 >= floor {
                    h *= 0.5;
                    continue;
                }
                report.converged = info.converged;
                report.substeps += 1;
                let err = self.failure(n, &info, &check.summary);
                self.failed = Some(self.snapshot(trial, &check, report, start));
                return Err(err);
            }
            report.substeps += 1;
            let fraction = end - done;
            let solved = u.iter().map(|v| v / fraction).collect();
            let kept = std::mem::replace(&mut self.guess, solved);
            if self.settings.predictor == Predictor::Linear && self.guess_is_solution {
                self.earlier = Some(kept);
            }
            self.guess_is_solution = true;
            if updated {
                reference_quality = check.summary.min_quality;
            }
            done = end;
            if done >= 1.0 {
                self.current = self.snapshot(trial, &check, report, start);
                return Ok(self.current.report.clone());
            }
            coords = Some(trial);
            h = (2.0 * h).min(1.0 - done);
        }
    }

    /// The error of step `n` rejected with the solve `info` and the check
    /// `totals`: the worst invalid cell, or the solve that did not converge.
    fn failure(&self, n: usize, info: &SolveInfo, totals: &Totals) -> Error {
        match &totals.worst {
            Some(worst) if info.converged => Error::Inverted {
                step: n,
                count: totals.invalid,
                element: worst.element,
                centroid: worst.centroid.clone(),
                volume: worst.volume,
                failure: worst.failure,
            },
            _ => Error::NotConverged {
                step: n,
                what: Box::new(Unconverged {
                    stages: Stage::names(&info.stages),
                    true_residual: info.true_residual,
                    error_ratio: info.error_ratio,
                    node: self.worst_node_tag(info.worst_node),
                    diverged: info.diverged,
                }),
            },
        }
    }

    /// The input tag of the solve's worst node `node` ([`SolveInfo::worst_node`]:
    /// on one process's part, the process holding it names it, the others
    /// give `usize::MAX`), the same on every process (collective).
    fn worst_node_tag(&self, node: usize) -> u64 {
        let mut tag = [self.mesh.node_tags.get(node).map_or(-1.0, |&t| t as f64)];
        self.on.max(&mut tag);
        tag[0].max(0.0) as u64
    }

    /// The amplification of the move from `from` to `to` (collective): the
    /// largest displacement of a node the springs solve for (free or
    /// sliding) over the largest of a fixed one, 0 where none of those moved.
    fn amplification(&self, from: &[f64], to: &[f64]) -> f64 {
        let dim = self.mesh.dim;
        // [solved, prescribed]
        let mut largest = [0.0f64; 2];
        for (i, role) in self.roles.iter().enumerate() {
            let d = (0..dim).map(|k| to[dim * i + k] - from[dim * i + k]);
            let moved = d.map(|v| v * v).sum::<f64>().sqrt();
            let side = usize::from(*role == NodeRole::Fixed);
            largest[side] = largest[side].max(moved);
        }
        self.on.max(&mut largest);
        if largest[1] > 0.0 {
            largest[0] / largest[1]
        } else {
            0.0
        }
    }

    /// The configuration `coords` with its `check`, for the step of `report`.
    fn snapshot(
        &self,
        coords: Vec<f64>,
        check: &Check,
        mut report: StepReport,
        start: Instant,
    ) -> Snapshot {
        let summary = summarize(&check.summary);
        report.min_quality = summary.min_quality;
        report.mean_quality = summary.mean_quality;
        report.inverted = summary.inverted;
        report.bins = summary.bins;
        report.seconds = start.elapsed().as_secs_f64();
        let mut inverted = vec![false; check.quality.len()];
        for inv in &check.invalid {
            inverted[inv.cell] = true;
        }
        Snapshot {
            coords,
            inverted,
            report,
        }
    }
}
