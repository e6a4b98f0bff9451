//! One solve of an increment of `verbss-mpi deform` without the whole
//! mesh ([`crate::share_run`]): the springs solved from a start, solved
//! again to round-off where a converged solve inverts a cell, and the moved
//! mesh checked over the ranks, as `verbss deform`'s attempt
//! (`verbss::deform`).

use std::time::Instant;

use verbss::deform::StepReport;
use verbss::solve::{NodeRole, SolveInfo, SolveParams};
use verbss_mpi::coupled::LocalSolver;
use verbss_mpi::step_quality::step_quality;
use verbss_mpi::Comm;

/// Where one solve of an increment is: the springs' coordinates, the
/// configuration its displacement starts from, where the prescribed nodes
/// (`roles`) end (`goal`, set exactly), and whether the start already puts
/// every prescribed node there (nothing to solve).
pub struct Solve<'a> {
    pub springs: &'a [f64],
    pub base: &'a [f64],
    pub goal: &'a [f64],
    pub roles: &'a [NodeRole],
    pub nothing: bool,
}

/// One solve of an increment and its collective check.
pub struct Attempt {
    /// The moved mesh.
    pub moved: Vec<f64>,
    /// Its quality, reduced over the ranks.
    pub report: StepReport,
    /// The solves made, the one judged last.
    pub solves: Vec<SolveInfo>,
    /// Seconds of the checks.
    pub check_seconds: f64,
    /// Whether the springs were solved (not when nothing was left).
    pub swept: bool,
}

impl Attempt {
    /// Whether it converged without inverting a cell.
    fn valid(&self) -> bool {
        self.solves.last().is_some_and(|s| s.converged) && self.report.inverted == 0
    }

    /// Whether it is valid and `other` is not, or has a lower minimum
    /// quality (the guard's choice between the blended and the plain
    /// start, as one process's).
    pub fn better_than(&self, other: &Attempt) -> bool {
        self.valid() && (!other.valid() || self.report.min_quality > other.report.min_quality)
    }
}

/// One solve (collective): the springs at `to.springs`, the displacement
/// `u` from `to.base` (prescribed values and the initial guess), the moved
/// mesh `base + u`, its prescribed nodes at `to.goal`, checked over the
/// ranks. A converged solve that inverts a
/// cell is solved again to round-off ([`LocalSolver::solve_exact`]) and
/// judged on that where it converges: an inversion is never the solver's
/// fault (as on one process).
pub fn attempt(
    world: &Comm,
    solver: &mut LocalSolver,
    mesh: &verbss::Mesh,
    orientation: &[i8],
    settings: &SolveParams,
    to: Solve,
    mut u: Vec<f64>,
) -> anyhow::Result<Attempt> {
    let mut check_seconds = 0.0;
    let dim = mesh.dim;
    let mut judge = |u: &[f64]| {
        let mut moved: Vec<f64> = to.base.iter().zip(u).map(|(x, du)| x + du).collect();
        for i in (0..to.roles.len()).filter(|&i| to.roles[i] == NodeRole::Fixed) {
            moved[dim * i..dim * (i + 1)].copy_from_slice(&to.goal[dim * i..dim * (i + 1)]);
        }
        let check = Instant::now();
        let r = step_quality(world, mesh, &moved, orientation);
        check_seconds += check.elapsed().as_secs_f64();
        (moved, r)
    };
    let mut info = if to.nothing {
        u.fill(0.0);
        let mut none = SolveInfo::default();
        none.converged = true;
        none
    } else {
        solver.solve(to.springs, &mut u, settings)?
    };
    let (mut moved, mut report) = judge(&u);
    let mut solves = Vec::new();
    if settings.escalate && info.converged && report.inverted > 0 && !to.nothing {
        let exact = solver.solve_exact(to.springs, &mut u, settings)?;
        if exact.converged {
            (moved, report) = judge(&u);
            solves.push(std::mem::replace(&mut info, exact));
        } else {
            solves.push(exact);
        }
    }
    solves.push(info);
    Ok(Attempt {
        moved,
        report,
        solves,
        check_seconds,
        swept: !to.nothing,
    })
}
