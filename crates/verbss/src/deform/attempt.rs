//! One solve of a (sub-)step and the choice of where it starts.
//!
//! A (sub-)step starts from the reference configuration moved by the
//! blended rigid motion when the blend is on (docs/method.md, "Blended rigid
//! motion"), and the springs solve what is left. A body that translates
//! on a 2D mesh has its translation's weight coupled across the motion
//! ahead of and behind it ([`Weighting::Directional`]): the cells there
//! are compressed along the motion rather than sheared. Where that solve
//! is weak ([`accept::weak`]: next to a fixed wall along the motion the
//! directional weight can shear the cells between body and wall in a
//! thinner band) the (sub-)step is solved again with the isotropic weight
//! and the better of the two is kept ([`accept::better`]). The blend's weights are
//! harmonic: next to a sharp convex corner of a body their gradient is
//! singular, and on a mesh that is coarse there the blended start can crush
//! the cells ahead of the corner that the springs alone keep valid. The
//! near-wall treatment must never lose to the springs alone, so where the
//! blended solve is weak ([`accept::weak`]) the step is solved again from
//! the reference itself and the better of the two is kept
//! ([`accept::better`]).

use std::time::Instant;

use super::accept::{self, Check};
use super::{blend, Deformer, Reference, StepReport};
use crate::collective::Collective;
use crate::error::Result;
use crate::near_wall::blend::Weighting;
use crate::solve::{clear_prescribed, SolveInfo, SpringSolver, Stage};

impl<S: SpringSolver, C: Collective> Deformer<S, C> {
    /// The solve of the (sub-)step from `coords` to `targets`, `fraction` of
    /// a step, that the guard judges (see the module documentation);
    /// `reference_quality` is the minimum quality of the reference
    /// configuration. Every solve made is added to `report`'s account but
    /// the one returned, which the caller adds.
    pub(super) fn chosen(
        &mut self,
        coords: &[f64],
        targets: &[(usize, Vec<f64>)],
        fraction: f64,
        reference_quality: f64,
        report: &mut StepReport,
    ) -> Result<Attempt> {
        let (start, translated) = self.blended(coords, targets, Weighting::Directional);
        let mut blended = self.judged(&start, targets, fraction, report)?;
        if translated && accept::weak(&blended.check, reference_quality) {
            let (start, _) = self.blended(coords, targets, Weighting::Isotropic);
            let isotropic = self.judged(&start, targets, fraction, report)?;
            blended = better_of(isotropic, blended, report);
        }
        if self.blend.is_none() || !accept::weak(&blended.check, reference_quality) {
            return Ok(blended);
        }
        let plain_start = reference_of(self.settings.reference, coords, &self.mesh.coords).to_vec();
        let plain = self.judged(&plain_start, targets, fraction, report)?;
        Ok(better_of(plain, blended, report))
    }

    /// [`Deformer::attempt`] from `start`, and when it converged but left an
    /// invalid cell, solved again to round-off: a rejected step is never the
    /// solver's fault, so the step solved exactly is what the guard judges.
    /// Where no round-off solve converges, the accepted solve (error below
    /// the bound) stays the one judged.
    fn judged(
        &mut self,
        start: &[f64],
        targets: &[(usize, Vec<f64>)],
        fraction: f64,
        report: &mut StepReport,
    ) -> Result<Attempt> {
        let attempt = self.attempt(start, targets, fraction, false)?;
        report.check_seconds += attempt.check_seconds;
        report.relocated += attempt.relocated;
        let exact_wanted = self.settings.solve.escalate
            && attempt.info.converged
            && attempt.check.summary.invalid > 0
            && !attempt.info.stages.contains(&Stage::Direct);
        if !exact_wanted {
            return Ok(attempt);
        }
        let exact = self.attempt(start, targets, fraction, true)?;
        report.check_seconds += exact.check_seconds;
        report.relocated += exact.relocated;
        if exact.info.converged {
            report.add(&attempt.info);
            Ok(exact)
        } else {
            report.add(&exact.info);
            Ok(attempt)
        }
    }

    /// Where a (sub-)step from `coords` towards `targets` starts: the
    /// reference configuration (`coords`, or the input mesh with the fixed
    /// and anchored references) moved by the blended rigid motion when it is on
    /// (docs/method.md, "Blended rigid motion"), its translation weighted as
    /// `weighting` says; and whether a body translated.
    fn blended(
        &mut self,
        coords: &[f64],
        targets: &[(usize, Vec<f64>)],
        weighting: Weighting,
    ) -> (Vec<f64>, bool) {
        let reference = reference_of(self.settings.reference, coords, &self.mesh.coords);
        let Some(blend) = &mut self.blend else {
            return (reference.to_vec(), false);
        };
        let mut moved = blend.apply(reference, targets, &self.on, weighting, &self.workers);
        blend::keep_in_planes(
            self.mesh.dim,
            &self.roles,
            &self.normals,
            reference,
            &mut moved.coords,
        );
        (moved.coords, moved.translated)
    }

    /// Whether `start` ([`Deformer::blended`]) already puts every
    /// prescribed node of every process at its target, to round-off (10⁻¹²
    /// of the mesh's size): the springs have nothing to solve (a rigid body
    /// under the blend, or a boundary back at the input mesh with a total
    /// unknown, whose solution is then exactly `u = 0`).
    fn nothing_left(&self, start: &[f64], targets: &[(usize, Vec<f64>)]) -> bool {
        let dim = self.mesh.dim;
        let mut left = [targets
            .iter()
            .flat_map(|(node, p)| (0..dim).map(move |d| (p[d] - start[dim * node + d]).abs()))
            .fold(0.0, f64::max)];
        self.on.max(&mut left);
        (self.blend.is_some() || self.settings.reference != Reference::Updated)
            && left[0] <= self.round_off
    }

    /// One solve from `start` ([`Deformer::blended`]) with the prescribed
    /// nodes at `targets`, an increment of `fraction` of a step; to
    /// round-off when `exact` ([`SpringSolver::solve_exact`]). The springs are
    /// built on `start` (on the input mesh with the fixed reference) and
    /// solve for the move from `start`; where `start` already puts every
    /// prescribed node at its target (a rigid body under the blend) that
    /// move is zero and nothing is solved. The ghosts take their owners'
    /// positions before the check.
    fn attempt(
        &mut self,
        start: &[f64],
        targets: &[(usize, Vec<f64>)],
        fraction: f64,
        exact: bool,
    ) -> Result<Attempt> {
        let dim = self.mesh.dim;
        let springs_at = if self.settings.reference == Reference::Fixed {
            &self.mesh.coords
        } else {
            start
        };
        let mut u: Vec<f64> = match &self.earlier {
            Some(earlier) => self
                .guess
                .iter()
                .zip(earlier)
                .map(|(a, b)| (2.0 * a - b) * fraction)
                .collect(),
            None => self.guess.iter().map(|v| v * fraction).collect(),
        };
        clear_prescribed(dim, &self.roles, &self.normals, &mut u);
        for (node, p) in targets {
            for d in 0..dim {
                u[dim * node + d] = p[d] - start[dim * node + d];
            }
        }
        let info = if self.nothing_left(start, targets) {
            u.fill(0.0);
            SolveInfo {
                converged: true,
                ..SolveInfo::default()
            }
        } else if exact {
            self.solver
                .solve_exact(springs_at, &mut u, &self.settings.solve)?
        } else {
            self.solver
                .solve(springs_at, &mut u, &self.settings.solve)?
        };
        let mut next: Vec<f64> = start.iter().zip(&u).map(|(x, d)| x + d).collect();
        for (node, p) in targets {
            next[dim * node..dim * (node + 1)].copy_from_slice(p);
        }
        self.on.refresh(&mut next, dim);
        let checking = Instant::now();
        let relocated = self.relocation.as_ref().map_or(0, |relocation| {
            relocation.apply(
                &self.mesh,
                &mut next,
                &self.orientation,
                &self.roles,
                &self.normals,
                &self.mesh.node_tags,
                &self.on,
                &self.workers,
            )
        });
        let check = accept::check(
            &self.mesh,
            &next,
            &self.orientation,
            &self.on,
            &self.workers,
        );
        Ok(Attempt {
            coords: next,
            u,
            info,
            check,
            check_seconds: checking.elapsed().as_secs_f64(),
            relocated,
        })
    }
}

/// What one solve of a (sub-)step gave.
pub(super) struct Attempt {
    /// The new coordinates.
    pub(super) coords: Vec<f64>,
    /// The solved displacement (increment, or total for the fixed reference).
    pub(super) u: Vec<f64>,
    /// The solver's account.
    pub(super) info: SolveInfo,
    /// The check of the new coordinates.
    pub(super) check: Check,
    /// Seconds of the relocation and the check.
    pub(super) check_seconds: f64,
    /// Nodes the relocation moved ([`super::relocate`]).
    pub(super) relocated: usize,
}

/// The better of the solves `a` and `b` ([`accept::better`]; `b` where
/// neither is), the other's solve added to `report`'s account.
fn better_of(a: Attempt, b: Attempt, report: &mut StepReport) -> Attempt {
    let (kept, dropped) = if accept::better((&a.info, &a.check), (&b.info, &b.check)) {
        (a, b)
    } else {
        (b, a)
    };
    report.add(&dropped.info);
    kept
}

/// The reference configuration of a (sub-)step from `coords`: `coords`, or
/// the input mesh `input` with the fixed and anchored references.
pub(super) fn reference_of<'a>(
    reference: Reference,
    coords: &'a [f64],
    input: &'a [f64],
) -> &'a [f64] {
    if reference == Reference::Updated {
        coords
    } else {
        input
    }
}
