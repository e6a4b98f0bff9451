//! `verbss run CASE.toml [--out DIR]`: a case file's run, with its outputs.
//!
//! Writes to DIR: the `.vtu` series `NAME_NNNN.vtu` (every k-th step, the
//! input as step 0 and the last step always; point data `displacement`, cell
//! data `quality` and `inverted`) with `NAME.pvd` for ParaView, the final
//! mesh `NAME.EXT` in the input's format and `report.json`. When a step
//! inverts an element the run stops with exit code 3 (4 when no solver
//! converged): `NAME.EXT` holds the last valid mesh and `NAME.failed.vtu`
//! the failed state.
//!
//! The runner ([`execute`]) is shared: `verbss run`, `verbss deform` and
//! `verbss demo` prepare a [`Prepared`] job and run it here
//! ([`run_here`]); `verbss-mpi deform` runs the same job with its
//! distributed stepper.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context;
use clap::Args;
use verbss::case::Case;
use verbss::collective::Collective;
use verbss::deform::{Deformer, Snapshot};
use verbss::io::foam::Times;
use verbss::io::outputs::Input;
use verbss::io::{self, vtu, WriteOptions};
use verbss::mesh::Mesh;
use verbss::motion::Attachment;
use verbss::report::Report;
use verbss::settings::{Reference, Settings};
use verbss::solve::SpringSolver;
use verbss::Error;

use crate::case_times::TimeArgs;
use crate::msh::MshArgs;
use crate::overwrite::{check_outputs, mesh_inputs, note_lost_su2_blocks};
use crate::progress::Progress;
use crate::render::{PictureArgs, Recorder};

/// Arguments of `verbss run`.
#[derive(Args)]
pub struct RunArgs {
    /// The case file (TOML; see docs/case-file.md).
    case: PathBuf,
    /// Output folder [default: the case's `output.dir`, else out/CASE-NAME].
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress output.
    #[arg(long, short)]
    quiet: bool,
    /// Allow the final mesh to replace the input mesh.
    #[arg(long)]
    overwrite: bool,
    /// Write every K-th step of the .vtu series (step 0 and the last step
    /// always) [default: the case's `output.every`, else 1].
    #[arg(long, value_name = "K", value_parser = parse_every, allow_hyphen_values = true)]
    every: Option<usize>,
    #[command(flatten)]
    msh: MshArgs,
    #[command(flatten)]
    pictures: PictureArgs,
}

/// A whole number of steps ≥ 1.
pub fn parse_every(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(k) if k >= 1 => Ok(k),
        _ => Err(format!("expected a whole number of steps ≥ 1, got '{s}'")),
    }
}

/// Runs `verbss run`.
pub fn run(args: RunArgs) -> anyhow::Result<ExitCode> {
    let case = Case::read(&args.case)?;
    let mesh = crate::zone::read(&case.mesh, case.zone, "zone = K", args.quiet)?;
    let attachments = case.attachments(&mesh)?;
    let name = file_stem(&case.mesh);
    let dir = args
        .out
        .or_else(|| case.output.dir.clone())
        .unwrap_or_else(|| Path::new("out").join(file_stem(&args.case)));
    let extension = case
        .mesh
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_else(|| "vtu".into());
    let write_options = args.msh.apply(case.output.write_options(&mesh));
    let foam_times = match case.output.final_mesh {
        true => {
            TimeArgs::default().case_times(&case.mesh, &dir.join(&name), case.settings.steps)?
        }
        false => None,
    };
    let job = Job {
        name,
        source: case.mesh.display().to_string(),
        write_options,
        mesh: Arc::new(mesh),
        attachments,
        settings: case.settings.clone(),
        foam_times,
        every: args.every.unwrap_or(case.output.every),
        series: case.output.series,
        final_mesh: case.output.final_mesh,
        report: case.output.report.then(|| dir.join("report.json")),
        extension,
        dir,
        inputs: case_inputs(&case),
        overwrite: args.overwrite,
        from_case: true,
    };
    let recorder = Recorder::new(&args.pictures, &job.mesh, job.settings.steps, None);
    run_here(Prepared {
        job,
        quiet: args.quiet,
        recorder,
    })
}

/// The files a case file's run reads: the case file, the mesh and the
/// positions files.
fn case_inputs(case: &Case) -> Vec<Input> {
    let mut inputs = vec![Input {
        what: "the case file",
        path: case.path.clone(),
    }];
    inputs.extend(mesh_inputs(&case.mesh));
    inputs.extend(case.position_files().into_iter().map(|path| Input {
        what: "a positions file",
        path,
    }));
    inputs
}

/// A job ready to run: what to compute and write, whether to print
/// progress, and the pictures to keep.
pub struct Prepared {
    /// The job.
    pub job: Job,
    /// No progress output.
    pub quiet: bool,
    /// The states kept for `--html` and `--gif`.
    pub recorder: Recorder,
}

/// Runs a prepared job in this process and prints its summary.
pub fn run_here(mut prepared: Prepared) -> anyhow::Result<ExitCode> {
    let job = &prepared.job;
    check_outputs(job, &prepared.recorder, Vec::new())?;
    spill_source(job);
    let mut deformer = Deformer::shared(
        Arc::clone(&job.mesh),
        &job.attachments,
        job.deformer_settings(&prepared.recorder),
    )?;
    let summary = execute(
        job,
        &mut deformer,
        prepared.quiet,
        true,
        &mut prepared.recorder,
        &mut Files::new(true),
    )?;
    Ok(summary.print(job, true))
}

/// An MSH output is the input file's bytes with the moved coordinates:
/// they wait in an unnamed temporary file beside the output (else in the
/// temporary folder), not in memory, for the run (`gmsh::Source::spill`);
/// where neither can be written they stay in memory.
fn spill_source(job: &Job) {
    if let Some(source) = &job.mesh.origin.gmsh {
        if !job.dir.is_dir() || source.spill(&job.dir).is_err() {
            let _kept_in_memory = source.spill(&std::env::temp_dir());
        }
    }
}

/// The file name without its extension (`mesh` when there is none).
pub fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".into())
}

/// The folder of an output file (`.` for a bare file name).
pub fn output_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Everything a run needs: the mesh, its motions, the settings and the outputs.
pub struct Job {
    /// Base name of the output files.
    pub name: String,
    /// Where the mesh came from (for the report).
    pub source: String,
    /// The input mesh (shared with the deformer and the pictures).
    pub mesh: Arc<Mesh>,
    /// The motions.
    pub attachments: Vec<Attachment>,
    /// Steps, reference and solver settings.
    pub settings: Settings,
    /// The times of an OpenFOAM output that is the input case: its steps
    /// go to time directories `CASE/TIME/polyMesh`, the series too.
    pub foam_times: Option<Times>,
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
    /// How the final mesh is written (MSH version and encoding).
    pub write_options: WriteOptions,
    /// The output folder.
    pub dir: PathBuf,
    /// The files the run reads, which no output may replace.
    pub inputs: Vec<Input>,
    /// The final mesh may replace the input mesh (`--overwrite`).
    pub overwrite: bool,
    /// The outputs are named by a case file's `[output]`, not by options
    /// (as messages name them).
    pub from_case: bool,
}

impl Job {
    /// Where the final mesh goes: `DIR/NAME.EXT` (`DIR/NAME` for an
    /// OpenFOAM case, which has no extension).
    pub fn final_path(&self) -> PathBuf {
        if self.extension.is_empty() {
            return self.dir.join(&self.name);
        }
        self.dir.join(format!("{}.{}", self.name, self.extension))
    }

    /// How the mesh after `steps` steps is written: an OpenFOAM case that
    /// is the input gets the points in the time directory of that step.
    pub fn write_options_after(&self, steps: usize) -> WriteOptions {
        let mut options = self.write_options.clone();
        options.foam_time = self.foam_times.as_ref().map(|t| t.name(steps));
        options
    }

    /// The time directory of step `n` in the input OpenFOAM case, when
    /// the output is that case.
    pub fn time_dir(&self, n: usize) -> Option<PathBuf> {
        let times = self.foam_times.as_ref()?;
        Some(self.case_dir()?.join(times.name(n)))
    }

    /// The input OpenFOAM case, when the output is that case.
    pub fn case_dir(&self) -> Option<PathBuf> {
        self.foam_times.as_ref()?;
        let origin = self.mesh.origin.foam.as_deref()?;
        Some(io::foam::case_dir(&origin.dir))
    }

    /// The file of step `n` of the `.vtu` series: `NAME_NNNN.vtu`.
    pub fn series_file(&self, n: usize) -> String {
        format!("{}_{n:04}.vtu", self.name)
    }

    /// Where the failed state goes: `NAME.failed.vtu` beside the outputs;
    /// into the input OpenFOAM case, `CASE/verbss.failed.vtu`.
    pub fn failed_path(&self) -> PathBuf {
        match self.case_dir() {
            Some(case) => case.join("verbss.failed.vtu"),
            None => self.dir.join(format!("{}.failed.vtu", self.name)),
        }
    }

    /// The steps whose meshes a run that accepted `steps` steps wrote
    /// (besides the series' step 0): every `every`-th of the series, and
    /// the last.
    pub fn written_steps(&self, steps: usize) -> Vec<usize> {
        (1..=steps)
            .filter(|&n| n == steps || (self.series && n % self.every == 0))
            .collect()
    }

    /// The settings the deformer runs with: the job's, with the sweep
    /// history recorded when the pictures want it.
    pub fn deformer_settings(&self, recorder: &Recorder) -> Settings {
        let mut settings = self.settings.clone();
        settings.solve.record_history |= recorder.wants_history();
        settings
    }
}

/// What a run did.
pub struct Summary {
    /// Steps done (accepted).
    pub steps: usize,
    /// Wall seconds of all steps.
    pub seconds: f64,
    /// Seconds forming and solving the spring systems.
    pub solve_seconds: f64,
    /// The number of MPI ranks the steps were solved on (none: one process).
    pub ranks: Option<usize>,
    /// The smallest element quality over all accepted steps, and its step.
    pub min_quality: (f64, usize),
    /// Total solver sweeps.
    pub iterations: usize,
    /// A failed step was also tried in increments down to `1/2^substeps` of it.
    pub substeps: u32,
    /// The inversion or unconverged solve that stopped the run, with the
    /// paths written for it.
    pub failure: Option<(Error, PathBuf, PathBuf)>,
    /// No summary line: the run was quiet.
    pub quiet: bool,
}

impl Summary {
    /// Prints the summary line (unless the run is quiet) and the failure
    /// when `printer`, and gives the exit code: 0, 3 when a step inverted
    /// an element, 4 when no solver converged.
    pub fn print(&self, job: &Job, printer: bool) -> ExitCode {
        let code = match &self.failure {
            None => ExitCode::SUCCESS,
            Some((Error::NotConverged { .. }, ..)) => ExitCode::from(4),
            Some(_) => ExitCode::from(3),
        };
        if !printer {
            return code;
        }
        let per_step = self.seconds / self.steps.max(1) as f64;
        let ranks = match self.ranks {
            Some(n) => format!("; {:.2} s solving on {n} ranks", self.solve_seconds),
            None => String::new(),
        };
        if !self.quiet {
            println!(
                "{} in {:.2} s ({:.1} ms per step, {:.1} sweeps per step{ranks}); min quality {:.4} (step {}); outputs in {}",
                counted(self.steps, "step"),
                self.seconds,
                1e3 * per_step,
                self.iterations as f64 / self.steps.max(1) as f64,
                self.min_quality.0,
                self.min_quality.1,
                self.written(job)
            );
        }
        if let Some((e, last, failed)) = &self.failure {
            eprintln!("error: {e}");
            let k = self.substeps;
            if k > 0 {
                eprintln!(
                    "the step was also tried in increments down to 1/{} of it (--substeps {k})",
                    1u64 << k
                );
            }
            let last = match job.case_dir() {
                Some(_) if self.steps == 0 => format!(
                    "{} (the case is as it was: no step was accepted)",
                    last.display()
                ),
                _ => last.display().to_string(),
            };
            eprintln!(
                "the last valid mesh (step {}) is in {last}; the failed state in {}",
                self.steps,
                failed.display()
            );
        }
        code
    }

    /// The folders the run wrote its meshes to: the output folder, or the
    /// input OpenFOAM case and its time directories (the first, second and
    /// last of more than four).
    fn written(&self, job: &Job) -> String {
        let (Some(case), Some(times)) = (job.case_dir(), &job.foam_times) else {
            return job.dir.display().to_string();
        };
        let steps = job.written_steps(self.steps);
        let names: Vec<String> = steps.iter().map(|&n| times.name(n)).collect();
        let listed = match names.len() {
            0 => {
                return format!(
                    "{} (no time directory: no step was accepted)",
                    case.display()
                )
            }
            1..=4 => names.join(", "),
            n => format!(
                "{}, {}, …, {} ({n} of them)",
                names[0],
                names[1],
                names[n - 1]
            ),
        };
        let plural = if names.len() == 1 { "y" } else { "ies" };
        format!("{} (time director{plural} {listed})", case.display())
    }
}

/// Where a run's meshes go: the `.vtu` series, the final mesh and the
/// failed state. One process writes whole files ([`Files`]); the ranks of
/// `verbss-mpi` each write their piece of them.
pub trait Outputs {
    /// Writes step `s` of the series.
    fn step(&mut self, job: &Job, s: &Snapshot) -> anyhow::Result<()>;
    /// Writes the mesh at `coords`, the last valid one after `steps` steps;
    /// the path it names for the user.
    fn last(&mut self, job: &Job, coords: &[f64], steps: usize) -> anyhow::Result<PathBuf>;
    /// Writes the failed state `s`; the path it names for the user.
    fn failed(&mut self, job: &Job, s: &Snapshot) -> anyhow::Result<PathBuf>;
}

/// The outputs of a process holding the whole mesh: whole files in the
/// job's folder, written by the one `writer` (over MPI, rank 0 of ranks that
/// each hold the whole mesh).
pub struct Files {
    writer: bool,
    /// The series written so far: time and file name.
    series: Vec<(f64, String)>,
}

impl Files {
    /// The files, written only when `writer`.
    pub fn new(writer: bool) -> Files {
        Files {
            writer,
            series: Vec::new(),
        }
    }
}

impl Outputs for Files {
    /// `NAME_NNNN.vtu`, and `NAME.pvd` rewritten with it added (time `n·dt`);
    /// into the input OpenFOAM case, the step's time directory (none for
    /// step 0, the case's own `constant/polyMesh`, nor for the last).
    fn step(&mut self, job: &Job, s: &Snapshot) -> anyhow::Result<()> {
        if job.foam_times.is_some() {
            // The last step is the final mesh, written after the run.
            if s.report.step > 0 && s.report.step < job.settings.steps {
                self.last(job, &s.coords, s.report.step)?;
            }
            return Ok(());
        }
        let file = job.series_file(s.report.step);
        if self.writer {
            let path = job.dir.join(&file);
            vtu::write_moved(&path, &job.mesh, &s.coords, &fields(&job.mesh, s))?;
        }
        self.series
            .push((s.report.step as f64 * job.settings.dt, file));
        if self.writer {
            io::pvd::write(&job.dir.join(format!("{}.pvd", job.name)), &self.series)?;
        }
        Ok(())
    }

    /// The final mesh; into the input OpenFOAM case, the time directory of
    /// step `steps`, and nothing after no step (the case is as it was).
    fn last(&mut self, job: &Job, coords: &[f64], steps: usize) -> anyhow::Result<PathBuf> {
        let path = job.final_path();
        if let (0, Some(origin)) = (steps, job.mesh.origin.foam.as_deref()) {
            if job.foam_times.is_some() {
                return Ok(origin.dir.clone());
            }
        }
        if self.writer {
            io::write_moved(&path, &job.mesh, coords, &job.write_options_after(steps))?;
        }
        Ok(job.time_dir(steps).unwrap_or(path))
    }

    /// The failed state at [`Job::failed_path`].
    fn failed(&mut self, job: &Job, s: &Snapshot) -> anyhow::Result<PathBuf> {
        let path = job.failed_path();
        if self.writer {
            vtu::write_moved(&path, &job.mesh, &s.coords, &fields(&job.mesh, s))?;
        }
        Ok(path)
    }
}

/// Runs a job with `deformer` (made for it, with
/// [`Job::deformer_settings`]) on every process that shares its mesh:
/// steps `1..=N`, writing the outputs as it goes (every file atomically,
/// through `outputs`), and stops at the first rejected step; `recorder`
/// keeps the states for the `--html` report and the `--gif`. Only a
/// `writer` writes the report and keeps pictures (over MPI: rank 0); every
/// process writes through `outputs`, which decides what each writes.
pub fn execute<S: SpringSolver, C: Collective>(
    job: &Job,
    deformer: &mut Deformer<S, C>,
    quiet: bool,
    writer: bool,
    recorder: &mut Recorder,
    outputs: &mut dyn Outputs,
) -> anyhow::Result<Summary> {
    std::fs::create_dir_all(&job.dir)
        .with_context(|| format!("cannot create the output folder {}", job.dir.display()))?;
    if writer && job.final_mesh && !quiet {
        note_lost_su2_blocks(&job.mesh, &job.final_path());
    }
    let steps = job.settings.steps;
    let settings = deformer.settings();
    let mut report = Report::new(&job.source, deformer.size(), settings);
    let substeps = match settings.reference {
        Reference::Updated => settings.robust.substeps,
        _ => 0,
    };
    let initial = deformer.current();
    report.steps.push(initial.report.clone());
    if writer {
        // Outcome "running" until this run ends: an earlier run's report never
        // outlives a failure of this one.
        if let Some(path) = job.report.as_ref().filter(|p| p.is_file()) {
            report.write(path)?;
        }
        recorder.step(initial);
    }
    if job.series {
        outputs.step(job, initial)?;
    }
    let progress = Progress::new(steps, quiet);
    let start = Instant::now();
    let mut summary = Summary {
        steps: 0,
        seconds: 0.0,
        solve_seconds: 0.0,
        ranks: (deformer.processes().processes() > 1).then(|| deformer.processes().processes()),
        min_quality: (initial.report.min_quality, 0),
        iterations: 0,
        substeps,
        failure: None,
        quiet,
    };
    for n in 1..=steps {
        match deformer.step(n) {
            Ok(r) => {
                progress.step(&r);
                summary.steps = n;
                summary.iterations += r.iterations;
                summary.solve_seconds += r.form_seconds + r.solve_seconds;
                if r.min_quality < summary.min_quality.0 {
                    summary.min_quality = (r.min_quality, n);
                }
                report.steps.push(r);
                if writer {
                    recorder.step(deformer.current());
                }
                if job.series && (n % job.every == 0 || n == steps) {
                    outputs.step(job, deformer.current())?;
                }
            }
            Err(e @ (Error::Inverted { .. } | Error::NotConverged { .. })) => {
                progress.finish();
                let failed = deformer.failed().expect("a failed step keeps its state");
                report.steps.push(failed.report.clone());
                let failed_path = outputs.failed(job, failed)?;
                let last = outputs.last(job, &deformer.current().coords, n - 1)?;
                if writer {
                    report.outcome = e.to_string();
                    if let Some(path) = &job.report {
                        report.write(path)?;
                    }
                    recorder.finish(&report, deformer.current(), Some(failed));
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
    if job.final_mesh {
        outputs.last(job, &deformer.current().coords, steps)?;
    }
    if writer {
        report.outcome = "completed".into();
        if let Some(path) = &job.report {
            report.write(path)?;
        }
        recorder.finish(&report, deformer.current(), None);
    }
    Ok(summary)
}

/// Point data `displacement` (3 components, as ParaView's vectors), cell data
/// `quality` and `inverted` (0 or 1).
pub fn fields(mesh: &Mesh, s: &Snapshot) -> vtu::Fields {
    let dim = mesh.dim;
    let mut displacement = vec![0.0; 3 * mesh.node_count()];
    for i in 0..mesh.node_count() {
        for d in 0..dim {
            displacement[3 * i + d] = s.coords[dim * i + d] - mesh.coords[dim * i + d];
        }
    }
    let mut f = vtu::Fields::default();
    f.point.push(("displacement".into(), 3, displacement));
    f.cell.push(("quality".into(), 1, s.qualities(mesh)));
    f.cell.push((
        "inverted".into(),
        1,
        s.inverted.iter().map(|&b| f64::from(u8::from(b))).collect(),
    ));
    f
}

/// `n` things named: `1 step`, `2 steps`.
pub fn counted(n: usize, thing: &str) -> String {
    if n == 1 {
        format!("1 {thing}")
    } else {
        format!("{n} {thing}s")
    }
}
