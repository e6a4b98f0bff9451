//! Running a `verbss deform` job over the ranks of `MPI_COMM_WORLD`: the
//! same steps, outputs and messages as `verbss`'s own runner, with the
//! steps of [`Stepper`] and the per-rank pieces added.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use verbss::deform::{Settings, Snapshot};
use verbss::io::{self, vtu, WriteOptions};
use verbss::mesh::Mesh;
use verbss::motion::Attachment;
use verbss::report::Report;
use verbss::Error;
use verbss_mpi::pieces::{write_piece, write_pvtu};
use verbss_mpi::stepper::Stepper;
use verbss_mpi::Comm;

use crate::overwrite::note_lost_su2_blocks;
use crate::progress::Progress;
use crate::render::Recorder;

/// Whether this process is rank 0 of `MPI_COMM_WORLD` (the one that prints).
pub fn is_root() -> bool {
    Comm::world().rank() == 0
}

/// The file name without its extension (`mesh` when there is none).
pub fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".into())
}

/// Everything a run needs: the mesh, its motions, the settings and the outputs.
pub struct Job {
    /// Base name of the output files.
    pub name: String,
    /// Where the mesh came from (for the report).
    pub source: String,
    /// The input mesh.
    pub mesh: Mesh,
    /// The motions.
    pub attachments: Vec<Attachment>,
    /// Steps, reference and solver settings.
    pub settings: Settings,
    /// Write every k-th step of the series.
    pub every: usize,
    /// Write the `.vtu` series and `.pvd`.
    pub series: bool,
    /// Write the final mesh.
    pub final_mesh: bool,
    /// Where to write `report.json`, if at all.
    pub report: Option<PathBuf>,
    /// Extension (format) of the final mesh.
    pub extension: String,
    /// The output folder.
    pub dir: PathBuf,
}

impl Job {
    /// Where the final mesh goes: `DIR/NAME.EXT`.
    pub fn final_path(&self) -> PathBuf {
        self.dir.join(format!("{}.{}", self.name, self.extension))
    }
}

/// What a run did.
pub struct Summary {
    /// Steps done (accepted).
    steps: usize,
    /// Wall seconds of all steps.
    seconds: f64,
    /// Seconds in the distributed solves (assembly and sweeps).
    solve_seconds: f64,
    /// The smallest element quality over all accepted steps, and its step.
    min_quality: (f64, usize),
    /// Total solver sweeps.
    iterations: usize,
    /// The inversion that stopped the run, with the paths written for it.
    failure: Option<(Error, PathBuf, PathBuf)>,
    /// Number of ranks.
    ranks: i32,
}

impl Summary {
    /// Prints the summary (or the failure) on rank 0 and gives the exit
    /// code: 0, or 3 when a step inverted an element.
    pub fn print(&self, job: &Job) -> ExitCode {
        let root = is_root();
        if root {
            let per_step = self.seconds / self.steps.max(1) as f64;
            println!(
                "{} steps in {:.2} s ({:.1} ms per step, {:.1} sweeps per step; {:.2} s solving on {} ranks); min quality {:.4} (step {}); outputs in {}",
                self.steps,
                self.seconds,
                1e3 * per_step,
                self.iterations as f64 / self.steps.max(1) as f64,
                self.solve_seconds,
                self.ranks,
                self.min_quality.0,
                self.min_quality.1,
                job.dir.display()
            );
        }
        match &self.failure {
            None => ExitCode::SUCCESS,
            Some((e, last, failed)) => {
                if root {
                    eprintln!("error: {e}");
                    eprintln!(
                        "the last valid mesh (step {}) is in {}; the failed state in {}",
                        self.steps,
                        last.display(),
                        failed.display()
                    );
                }
                ExitCode::from(3)
            }
        }
    }
}

/// Runs a job on every rank: steps `1..=N`; rank 0 writes the outputs of
/// `verbss` (the final mesh, the report, the series when asked, the
/// pictures), every rank its piece of the final state.
pub fn execute(job: &Job, quiet: bool, recorder: &mut Recorder) -> anyhow::Result<Summary> {
    let world = Comm::world();
    let root = world.rank() == 0;
    std::fs::create_dir_all(&job.dir)
        .with_context(|| format!("cannot create the output folder {}", job.dir.display()))?;
    if root && job.final_mesh && !quiet {
        note_lost_su2_blocks(&job.mesh, &job.final_path());
    }
    let mut settings = job.settings.clone();
    settings.solve.record_history |= recorder.wants_history();
    let mut stepper = Stepper::new(&world, &job.mesh, &job.attachments, settings)?;
    let steps = job.settings.steps;
    let mut report = Report::new(&job.source, &job.mesh, &job.settings);
    let mut series = Vec::new();
    let initial = stepper.current().clone();
    report.steps.push(initial.report.clone());
    if root {
        recorder.step(&initial);
        if job.series {
            write_step(job, &initial, &mut series)?;
        }
    }
    let progress = Progress::new(steps, quiet || !root);
    let start = Instant::now();
    let mut summary = Summary {
        steps: 0,
        seconds: 0.0,
        solve_seconds: 0.0,
        min_quality: (initial.report.min_quality, 0),
        iterations: 0,
        failure: None,
        ranks: world.size(),
    };
    for n in 1..=steps {
        match stepper.step(n) {
            Ok(r) => {
                progress.step(&r);
                summary.steps = n;
                summary.iterations += r.iterations;
                summary.solve_seconds += r.form_seconds + r.solve_seconds;
                if r.min_quality < summary.min_quality.0 {
                    summary.min_quality = (r.min_quality, n);
                }
                report.steps.push(r);
                if root {
                    recorder.step(stepper.current());
                    if job.series && (n % job.every == 0 || n == steps) {
                        write_step(job, stepper.current(), &mut series)?;
                    }
                }
            }
            Err(e @ Error::Inverted { .. }) => {
                progress.finish();
                let failed = stepper.failed().expect("a failed step keeps its state");
                report.steps.push(failed.report.clone());
                let failed_path = job.dir.join(format!("{}.failed.vtu", job.name));
                let last = job.final_path();
                if root {
                    let mut mesh = job.mesh.clone();
                    mesh.coords.clone_from(&failed.coords);
                    vtu::write(&failed_path, &mesh, &fields(&job.mesh, failed))?;
                    io::write(&last, &stepper.mesh(), &WriteOptions::default())?;
                    report.outcome = e.to_string();
                    if let Some(path) = &job.report {
                        report.write(path)?;
                    }
                    recorder.finish(&report, stepper.current(), Some(failed))?;
                }
                summary.seconds = start.elapsed().as_secs_f64();
                summary.failure = Some((e, last, failed_path));
                return Ok(summary);
            }
            Err(e) => return Err(e.into()),
        }
    }
    progress.finish();
    summary.seconds = start.elapsed().as_secs_f64();
    let current = stepper.current();
    write_piece(
        &job.dir,
        &job.name,
        stepper.part(),
        &job.mesh,
        &current.coords,
        &current.quality,
    )?;
    world.barrier();
    if root {
        write_pvtu(&job.dir, &job.name, world.size())?;
        if job.final_mesh {
            let path = job.final_path();
            io::write(&path, &stepper.mesh(), &WriteOptions::default())?;
        }
        report.outcome = "completed".into();
        if let Some(path) = &job.report {
            report.write(path)?;
        }
        recorder.finish(&report, stepper.current(), None)?;
    }
    Ok(summary)
}

/// Point data `displacement` (3 components), cell data `quality` and
/// `inverted` (0 or 1), as `verbss` writes them.
fn fields(mesh: &Mesh, s: &Snapshot) -> vtu::Fields {
    let dim = mesh.dim;
    let mut displacement = vec![0.0; 3 * mesh.node_count()];
    for i in 0..mesh.node_count() {
        for d in 0..dim {
            displacement[3 * i + d] = s.coords[dim * i + d] - mesh.coords[dim * i + d];
        }
    }
    let mut f = vtu::Fields::default();
    f.point.push(("displacement".into(), 3, displacement));
    f.cell.push(("quality".into(), 1, s.quality.clone()));
    f.cell.push((
        "inverted".into(),
        1,
        s.inverted.iter().map(|&b| f64::from(u8::from(b))).collect(),
    ));
    f
}

/// Writes step `s` as `NAME_NNNN.vtu` and rewrites `NAME.pvd` with it added.
fn write_step(job: &Job, s: &Snapshot, series: &mut Vec<(f64, String)>) -> anyhow::Result<()> {
    let file = format!("{}_{:04}.vtu", job.name, s.report.step);
    let mut mesh = job.mesh.clone();
    mesh.coords.clone_from(&s.coords);
    vtu::write(&job.dir.join(&file), &mesh, &fields(&job.mesh, s))?;
    series.push((s.report.step as f64 * job.settings.dt, file));
    io::pvd::write(&job.dir.join(format!("{}.pvd", job.name)), series)?;
    Ok(())
}
