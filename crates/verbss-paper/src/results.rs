//! One case, every method: the runs, the limits, the histograms, the
//! threads comparison and the pictures, gathered as `results.json` records.

use std::path::Path;

use serde::Serialize;
use verbss::case::Case;
use verbss::deform::Snapshot;
use verbss::mesh::Mesh;
use verbss::settings::Settings;

use crate::cases::{LimitSearch, PaperCase};
use crate::measure::{self, Means, Run, METHODS};
use crate::paper::{self, Numbers};
use crate::pictures;

/// A method's histogram at one amplitude.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BinsResult {
    /// The amplitude (the case's unit).
    pub amplitude: f64,
    /// The counts in the paper's bins, or `None` when the method inverted an element before.
    pub counts: Option<[usize; 5]>,
}

/// One method on one case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodResult {
    /// `spring`, `laplacian`, `ball-vertex` or `verbss`.
    pub method: &'static str,
    /// The solver (`sor` for the sweeping methods' own sweeps).
    pub solver: &'static str,
    /// The largest amplitude reached without an inverted element (the last
    /// valid step of the limit search times the increment).
    pub limit: f64,
    /// Whether the limit search reached its cap without an inversion (the
    /// method may go further).
    pub limit_capped: bool,
    /// The limit search's step that inverted an element.
    pub limit_first_inverted_step: Option<usize>,
    /// Where: the centroid of that step's worst inverted element.
    pub limit_inverted_at: Option<Vec<f64>>,
    /// Whether all `N` steps of the case file's motion were valid.
    pub completed: bool,
    /// The case file's run's step that inverted an element (within its `N` steps).
    pub first_inverted_step: Option<usize>,
    /// Means over the valid steps of the case file's motion (at most `N`).
    #[serde(flatten)]
    pub means: Means,
    /// `ball-vertex` (scalar SOR) seconds per step divided by this method's,
    /// both from this run.
    pub speedup_over_ball_vertex_sor: f64,
    /// Histograms at the case's amplitudes.
    pub bins: Vec<BinsResult>,
}

/// VerBSS with 1 and 2 threads (Tables 8, 9).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThreadsRow {
    /// Worker threads.
    pub threads: usize,
    /// Solve seconds per step (the paper's measure in §5).
    pub solve_seconds_per_step: f64,
    /// Whole-step seconds per step.
    pub seconds_per_step: f64,
    /// Solve seconds with 1 thread divided by these.
    pub speedup: f64,
    /// Whether the final coordinates equal the 1-thread run's bit for bit.
    pub identical_to_one_thread: bool,
}

/// One case's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseResult {
    /// The case name.
    pub name: &'static str,
    /// The paper's section.
    pub section: &'static str,
    /// The motion, in words.
    pub motion: &'static str,
    /// The mesh file (relative to the repository).
    pub mesh: String,
    /// Node count.
    pub nodes: usize,
    /// Element count.
    pub cells: usize,
    /// Steps `N` of the case file.
    pub steps: usize,
    /// The limits' unit.
    pub unit: &'static str,
    /// The increment per step of the limit search.
    pub limit_increment: f64,
    /// The cap of the limit search (amplitude).
    pub limit_cap: f64,
    /// The solver settings of every run.
    pub settings: serde_json::Map<String, serde_json::Value>,
    /// Per method, in the order spring, laplacian, ball-vertex, verbss.
    pub methods: Vec<MethodResult>,
    /// VerBSS with 1 and 2 threads, for the cases of Tables 8 and 9.
    pub threads: Vec<ThreadsRow>,
    /// The pictures written (file names in the output folder).
    pub pictures: Vec<String>,
    /// The paper's numbers for this case.
    pub paper: Numbers,
    /// Wall seconds of all of this case's runs.
    pub seconds: f64,
}

/// Runs `case` (its case file under `root`) with every method; writes the
/// pictures to `out`.
pub fn run_case(case: &PaperCase, root: &Path, out: &Path) -> anyhow::Result<CaseResult> {
    let start = std::time::Instant::now();
    let file = Case::read(&case.file(root))?;
    crate::meshgen::ensure(&file.mesh, root, case.generator)?;
    let mesh = verbss::io::read(&file.mesh)?;
    let attachments = file.attachments(&mesh)?;
    let n = file.settings.steps;
    let (limit_cap, separate) = match &case.limit {
        LimitSearch::Continue { cap } => (*cap, None),
        LimitSearch::Rotation { cap, .. } => (*cap, case.rotation_attachments()),
    };
    eprintln!(
        "{}: {} nodes, {} cells, {n} steps",
        case.name,
        mesh.node_count(),
        mesh.cell_count()
    );
    let mut methods = Vec::new();
    let mut pictures = Vec::new();
    let mut verbss_run = None;
    for (name, method, solver) in METHODS {
        let mut settings = file.settings.clone();
        settings.solve.method = method;
        settings.solve.solver = solver;
        settings.solve.threads = 1;
        // The paper's solvers exactly, stopped by eq. 8 alone.
        settings.solve.escalate = false;
        let case_keep: Vec<usize> = case
            .bins
            .iter()
            .filter(|b| !b.in_limit_run)
            .map(|b| b.step)
            .chain([0, n])
            .collect();
        let last = if separate.is_some() { n } else { limit_cap };
        let label = format!("{} {name}", case.name);
        let run = measure::run(&mesh, &attachments, &settings, last, &case_keep, &label)?;
        let limit_run = match &separate {
            Some((rotation, cap)) => {
                let mut s = Settings::new(*cap);
                s.reference = settings.reference;
                s.solve = settings.solve.clone();
                let keep: Vec<usize> = case
                    .bins
                    .iter()
                    .filter(|b| b.in_limit_run)
                    .map(|b| b.step)
                    .collect();
                let label = format!("{} {name} limit", case.name);
                Some(measure::run(&mesh, rotation, &s, *cap, &keep, &label)?)
            }
            None => None,
        };
        let search = limit_run.as_ref().unwrap_or(&run);
        let valid = run.steps.len().min(n);
        let bins = case
            .bins
            .iter()
            .map(|b| BinsResult {
                amplitude: b.amplitude,
                counts: kept(if b.in_limit_run { search } else { &run }, b.step)
                    .map(|s| s.report.bins),
            })
            .collect();
        methods.push(MethodResult {
            method: name,
            solver: if method == verbss::solve::Method::BallVertex {
                solver.name()
            } else {
                "sweeps"
            },
            limit: amplitude(search.steps.len(), case.per_step),
            limit_capped: search.first_inverted.is_none(),
            limit_first_inverted_step: search.first_inverted,
            limit_inverted_at: search.inverted_at.clone(),
            completed: run.steps.len() >= n,
            first_inverted_step: run.first_inverted.filter(|&k| k <= n),
            means: Means::of(&run.steps[..valid]),
            speedup_over_ball_vertex_sor: 0.0,
            bins,
        });
        if case.pictures && (name == "spring" || name == "verbss") {
            if let Some(failed) = &search.failed {
                pictures.push(pictures::write(
                    case,
                    &mesh,
                    failed,
                    out,
                    &format!("{name}-inverted"),
                    &format!(
                        "{}: {name}, step {} (first inverted)",
                        case.name, failed.report.step
                    ),
                )?);
            }
        }
        if name == "verbss" {
            if let Some(limit) = limit_run.as_ref().filter(|_| case.pictures) {
                pictures.push(pictures::write(
                    case,
                    &mesh,
                    &limit.last,
                    out,
                    "verbss-limit",
                    &format!(
                        "{}: verbss at {}{}",
                        case.name,
                        amplitude(limit.steps.len(), case.per_step),
                        case.unit
                    ),
                )?);
            }
            verbss_run = Some(run);
        }
    }
    let bv = methods[2].means.seconds_per_step;
    for m in &mut methods {
        m.speedup_over_ball_vertex_sor = bv / m.means.seconds_per_step;
    }
    let verbss_run = verbss_run.expect("verbss is one of the methods");
    if let Some(before) = kept(&verbss_run, 0).filter(|_| case.pictures) {
        pictures.insert(
            0,
            pictures::write(
                case,
                &mesh,
                before,
                out,
                "before",
                &format!("{}: initial mesh", case.name),
            )?,
        );
    }
    if case.pictures {
        let after = kept(&verbss_run, n).unwrap_or(&verbss_run.last);
        pictures.insert(
            1,
            pictures::write(
                case,
                &mesh,
                after,
                out,
                "after",
                &format!("{}: verbss, step {}", case.name, after.report.step),
            )?,
        );
    }
    let threads = if case.threads {
        threads_rows(case, &mesh, &attachments, &file.settings, &verbss_run)?
    } else {
        Vec::new()
    };
    let mut header_settings = file.settings.clone();
    header_settings.solve.threads = 1;
    Ok(CaseResult {
        name: case.name,
        section: case.section,
        motion: case.motion,
        mesh: format!("cases/{}", relative(&file.mesh, root)),
        nodes: mesh.node_count(),
        cells: mesh.cell_count(),
        steps: n,
        unit: case.unit,
        limit_increment: case.per_step,
        limit_cap: amplitude(limit_cap, case.per_step),
        settings: header_settings.solver_table(),
        methods,
        threads,
        pictures,
        paper: paper::numbers(case.name),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The amplitude of step `n`, `n × per_step`, rounded to 9 decimals (0.825, not 0.8250000000000001).
fn amplitude(n: usize, per_step: f64) -> f64 {
    (n as f64 * per_step * 1e9).round() / 1e9
}

/// The kept state of step `step`, if the run reached it.
fn kept(run: &Run, step: usize) -> Option<&Snapshot> {
    run.kept.iter().find(|s| s.report.step == step)
}

/// `path` relative to `root` (as given when it is not under it).
fn relative(path: &Path, root: &Path) -> String {
    path.strip_prefix(root)
        .unwrap_or(path)
        .display()
        .to_string()
}

/// VerBSS on the case file's motion with 2 threads, against the 1-thread run.
fn threads_rows(
    case: &PaperCase,
    mesh: &Mesh,
    attachments: &[verbss::motion::Attachment],
    settings: &Settings,
    one: &Run,
) -> anyhow::Result<Vec<ThreadsRow>> {
    let n = settings.steps;
    let serial = Means::of(&one.steps[..one.steps.len().min(n)]);
    let mut rows = vec![ThreadsRow {
        threads: 1,
        solve_seconds_per_step: serial.solve_seconds_per_step,
        seconds_per_step: serial.seconds_per_step,
        speedup: 1.0,
        identical_to_one_thread: true,
    }];
    let mut s = settings.clone();
    s.solve.method = verbss::solve::Method::Verbss;
    s.solve.threads = 2;
    let label = format!("{} {} 2 threads", case.name, s.solve.method.name());
    let two = measure::run(mesh, attachments, &s, n, &[], &label)?;
    let means = Means::of(&two.steps);
    let reference = kept(one, n).unwrap_or(&one.last);
    rows.push(ThreadsRow {
        threads: 2,
        solve_seconds_per_step: means.solve_seconds_per_step,
        seconds_per_step: means.seconds_per_step,
        speedup: serial.solve_seconds_per_step / means.solve_seconds_per_step,
        identical_to_one_thread: two.last.coords == reference.coords,
    });
    Ok(rows)
}
