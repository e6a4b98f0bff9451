//! `verbss deform MESH -o OUT --moving GROUP … (--translate | --rotate | --positions)`:
//! one total motion of some groups, reached in `--steps` equal increments.
//!
//! OUT is written in the format of its extension with the input's numbering;
//! `--report FILE.json` writes the per-step report. An inverted element stops
//! the run with exit code 3, the last valid mesh in OUT and the failed state
//! beside it (`OUT-STEM.failed.vtu`). `--every K` also writes the `.vtu`
//! series of every K-th step beside OUT (`OUT-STEM_NNNN.vtu`, `OUT-STEM.pvd`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::bail;
use clap::{ArgGroup, Args};
use verbss::deform::{Predictor, Preset, Reference, Settings};
use verbss::io::Format;
use verbss::motion::{Attachment, Motion, PositionSource};
use verbss::robust::Layer;
use verbss::solve::{Accel, Solver};

use crate::msh::MshArgs;
use crate::overwrite::refuse_input_as_output;
use crate::render::{PictureArgs, Recorder};
use crate::run::{file_stem, output_dir, parse_every, run_here, Job, Prepared};
use crate::zone::{self, ZoneArg};

/// Arguments of `verbss deform`.
#[derive(Args)]
#[command(group(ArgGroup::new("motion").required(true).args(["translate", "rotate", "positions"])))]
pub struct DeformArgs {
    /// The input mesh (.msh, .su2, .vtu, .cgns, an OpenFOAM case directory).
    mesh: PathBuf,
    /// The output mesh; its extension chooses the format. An OpenFOAM case
    /// (no extension): the input case itself gets the moved points in
    /// `CASE/STEPS/polyMesh/points`, another a whole `constant/polyMesh`.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    zone: ZoneArg,
    /// The moving groups, comma separated; every other boundary node is fixed.
    #[arg(long, value_delimiter = ',', required = true)]
    moving: Vec<String>,
    /// Total translation DX,DY[,DZ].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, num_args = 1)]
    translate: Option<Vec<f64>>,
    /// Total rotation in degrees (counter-clockwise about the axis), with --center.
    #[arg(long, allow_hyphen_values = true, requires = "center")]
    rotate: Option<f64>,
    /// Centre of the rotation CX,CY[,CZ].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    center: Option<Vec<f64>>,
    /// Rotation axis AX,AY,AZ (3D; default z).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    axis: Option<Vec<f64>>,
    /// New node positions (SU2 surface file `GlobalID x y [z]`, or CSV), reached at the last step.
    #[arg(long)]
    positions: Option<PathBuf>,
    /// Groups whose nodes slide in their own plane (symmetry planes; a group
    /// of parallel planes, each node in its own), comma separated; GROUP:NX,NY[,NZ]
    /// gives the plane's normal instead. Repeatable.
    #[arg(long, value_name = "GROUP[:NX,NY[,NZ]]", allow_hyphen_values = true)]
    slide: Vec<String>,
    /// Nodes this close to a moving wall move with it: off, auto (the boundary
    /// layer, at least 5% of the body's size) or a wall distance [default:
    /// auto for robust, off otherwise].
    #[arg(long, value_parser = parse_layer, allow_hyphen_values = true)]
    rigid_layer: Option<Layer>,
    /// A step that inverts an element is redone in smaller increments, down
    /// to 1/2^K of the step; 0: off [default: 6 for robust, 0 otherwise].
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=30), allow_hyphen_values = true)]
    substeps: Option<u32>,
    /// Springs at wall distance d scaled by (t/max(d,t))^P, t the rigid
    /// layer's thickness; 0: off [default: 1 for robust, 0 otherwise].
    #[arg(long, value_parser = parse_exponent, allow_hyphen_values = true)]
    stiffening: Option<f64>,
    /// Each body's fitted rigid motion carried into the mesh with smooth
    /// weights before the springs solve what is left (docs/method.md,
    /// "Blended rigid motion") [default: on for robust, off otherwise].
    #[arg(long, value_parser = parse_switch)]
    blend: Option<bool>,
    /// The spring system and its solution strategy: robust is VerBSS with
    /// the near-wall treatments (rigid layer auto, stiffening 1, substeps 6,
    /// blend on);
    /// verbss is the paper's method exactly.
    #[arg(long, value_enum, default_value = "robust")]
    method: Preset,
    /// The global solver of `--method ball-vertex` [default: sor]. Given
    /// explicitly (as --accel and --omega), it is the only solver used: no
    /// escalation when it stalls or diverges.
    #[arg(long, value_enum)]
    solver: Option<Solver>,
    /// Plain VerBSS sweeps (none), the multigrid-accelerated solve (amg), or
    /// amg on large meshes of mostly triangles/tetrahedra (auto) [default:
    /// none, escalating to the multigrid and the direct solve when needed].
    #[arg(long, value_enum)]
    accel: Option<Accel>,
    /// Number of equal increments.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    steps: usize,
    /// Springs on the current mesh each step, solving for the increment
    /// (updated); on the input mesh (fixed, also spelled initial); on the
    /// input mesh moved by the blended rigid motion, solving for the total
    /// displacement (anchored: a periodic motion returns to the input mesh)
    /// [default: updated; anchored with --method robust and a periodic motion].
    #[arg(long, value_enum)]
    reference: Option<Reference>,
    /// Each step's initial guess: the previous step's solution, or extrapolated
    /// linearly from the two previous steps (fewer sweeps for smooth motions).
    #[arg(long, value_enum, default_value = "previous")]
    predictor: Predictor,
    /// Eq.-8 stop, relative to the step's largest prescribed displacement
    /// [default: 1e-6].
    #[arg(long, allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// Use --tolerance as the paper's absolute eq.-8 threshold.
    #[arg(long)]
    absolute_tolerance: bool,
    /// Maximum sweeps per step [default: 2000].
    #[arg(long, allow_hyphen_values = true)]
    max_iterations: Option<usize>,
    /// Over-relaxation factor ω [default: 1.6].
    #[arg(long, allow_hyphen_values = true)]
    omega: Option<f64>,
    /// Worker threads (results do not depend on it).
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    threads: usize,
    /// Also write the .vtu series of every K-th step (step 0 and the last
    /// step always) beside OUT: OUT-STEM_NNNN.vtu and OUT-STEM.pvd.
    #[arg(long, value_name = "K", value_parser = parse_every, allow_hyphen_values = true)]
    every: Option<usize>,
    /// Write the per-step report (JSON) here.
    #[arg(long)]
    report: Option<PathBuf>,
    /// No progress output.
    #[arg(long, short)]
    quiet: bool,
    /// Allow the output to be the input mesh.
    #[arg(long)]
    overwrite: bool,
    #[command(flatten)]
    msh: MshArgs,
    #[command(flatten)]
    pictures: PictureArgs,
}

/// `off`, `auto` or a positive wall distance.
fn parse_layer(s: &str) -> Result<Layer, String> {
    s.parse()
        .map_err(|_| format!("expected off, auto or a positive wall distance, got '{s}'"))
}

/// A finite exponent ≥ 0.
fn parse_exponent(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(p) if p >= 0.0 && p.is_finite() => Ok(p),
        _ => Err(format!("expected a number ≥ 0, got '{s}'")),
    }
}

/// `on` or `off`.
fn parse_switch(s: &str) -> Result<bool, String> {
    match s {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(format!("expected on or off, got '{s}'")),
    }
}

/// A point of `dim` numbers as 3 (z = 0); a 2D mesh also takes 3 numbers
/// with z = 0, as a case file does.
fn point3(name: &str, v: &[f64], dim: usize) -> anyhow::Result<[f64; 3]> {
    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
        bail!("--{name} has a non-finite number ({x})");
    }
    match v.len() {
        n if n == dim => Ok([v[0], v[1], v.get(2).copied().unwrap_or(0.0)]),
        3 if dim == 2 && v[2] == 0.0 => Ok([v[0], v[1], 0.0]),
        3 if dim == 2 => bail!(
            "--{name} has a non-zero z on a 2D mesh, which lies in the x–y plane \
             (give 2 numbers, or 3 with z = 0)"
        ),
        n => bail!(
            "--{name} needs {} for a {dim}D mesh, got {n}",
            if dim == 2 {
                "2 numbers (or 3 with z = 0)"
            } else {
                "3 numbers"
            }
        ),
    }
}

/// Runs `verbss deform`.
pub fn run(args: DeformArgs) -> anyhow::Result<ExitCode> {
    run_here(prepare(args)?)
}

/// The job of `verbss deform`: reads the mesh, checks the groups and the
/// output path, and decides the motion and the settings.
pub fn prepare(args: DeformArgs) -> anyhow::Result<Prepared> {
    let format = Format::from_path(&args.output)?;
    refuse_input_as_output(&args.mesh, &args.output, args.overwrite, true)?;
    let mut mesh = zone::read(&args.mesh, args.zone.zone, "--zone K", args.quiet)?;
    let write_options = args.msh.options(&mesh);
    if format != Format::Msh {
        // Only an MSH output writes the coordinates back into the input
        // file's bytes; any other format frees them (the file's size).
        mesh.origin.gmsh = None;
    }
    let dim = mesh.dim;
    let slides = slides(&args.slide, dim)?;
    for g in args
        .moving
        .iter()
        .chain(slides.iter().flat_map(|a| &a.groups))
    {
        if let Err(e) = mesh.group(g) {
            return Err(zone::missing_group(e, &args.mesh, g));
        }
    }
    let motion = match args.field_motion(dim)? {
        Some(motion) => motion,
        None => match &args.positions {
            Some(path) => Motion::Positions(PositionSource::for_groups(path, &mesh, &args.moving)?),
            None => unreachable!("clap requires one motion"),
        },
    };
    let settings = args.settings(&motion);
    // `-o .` names its directory by its path only.
    let output = match format {
        Format::Foam => std::path::absolute(&args.output)?.components().collect(),
        _ => args.output.clone(),
    };
    let dir = output_dir(&output);
    let job = Job {
        name: file_stem(&output),
        source: args.mesh.display().to_string(),
        write_options,
        mesh: Arc::new(mesh),
        attachments: slides
            .into_iter()
            .chain([Attachment {
                groups: args.moving.clone(),
                motion,
            }])
            .collect(),
        settings,
        every: args.every.unwrap_or(1),
        series: args.every.is_some(),
        final_mesh: true,
        report: args.report.clone(),
        // As given (`UP.SU2` stays `UP.SU2`).
        extension: output.extension().map_or_else(
            || format.extension().into(),
            |e| e.to_string_lossy().into_owned(),
        ),
        dir,
    };
    let recorder = Recorder::new(&args.pictures, &job.mesh, job.settings.steps, None);
    Ok(Prepared {
        job,
        quiet: args.quiet,
        recorder,
    })
}

impl DeformArgs {
    /// The input mesh.
    pub fn mesh(&self) -> &Path {
        &self.mesh
    }

    /// The output.
    pub fn output(&self) -> &Path {
        &self.output
    }

    /// `--translate` or `--rotate` for a `dim`-dimensional mesh; `None`
    /// for `--positions`.
    fn field_motion(&self, dim: usize) -> anyhow::Result<Option<Motion>> {
        if let Some(t) = &self.translate {
            return Ok(Some(Motion::Translation {
                displacement: point3("translate", t, dim)?,
            }));
        }
        let Some(degrees) = self.rotate else {
            return Ok(None);
        };
        if !degrees.is_finite() {
            bail!("--rotate has a non-finite angle ({degrees})");
        }
        let center = point3("center", self.center.as_deref().unwrap_or_default(), dim)?;
        let axis = match (&self.axis, dim) {
            (Some(a), 3) => point3("axis", a, 3)?,
            (Some(_), _) => bail!("--axis applies to 3D meshes only"),
            (None, _) => [0.0, 0.0, 1.0],
        };
        Ok(Some(Motion::Rotation {
            center,
            axis,
            angle: degrees.to_radians(),
        }))
    }

    /// The settings of `--method` and the options that change them.
    fn settings(&self, motion: &Motion) -> Settings {
        let mut settings = self.method.settings(self.steps);
        settings.reference = self.reference.unwrap_or(match self.method {
            Preset::Robust => Reference::for_motions([motion]),
            _ => settings.reference,
        });
        settings.predictor = self.predictor;
        let robust = &mut settings.robust;
        robust.layer = self.rigid_layer.unwrap_or(robust.layer);
        robust.substeps = self.substeps.unwrap_or(robust.substeps);
        robust.stiffening = self.stiffening.unwrap_or(robust.stiffening);
        robust.blend = self.blend.unwrap_or(robust.blend);
        let s = &mut settings.solve;
        s.solver = self.solver.unwrap_or(s.solver);
        s.accel = self.accel.unwrap_or(s.accel);
        s.escalate = self.solver.is_none() && self.accel.is_none() && self.omega.is_none();
        s.tolerance = self.tolerance.unwrap_or(s.tolerance);
        s.absolute_tolerance = self.absolute_tolerance;
        s.max_iterations = self.max_iterations.unwrap_or(s.max_iterations);
        s.omega = self.omega.unwrap_or(s.omega);
        s.threads = self.threads;
        settings
    }

    /// The job of a run whose ranks each read their own partitions of a
    /// partitioned MSH 4.1 input of dimension `dim` (`verbss-mpi deform`,
    /// docs/distributed.md): refuses, with the reason, what needs the whole
    /// mesh or is not written rank by rank.
    pub fn share_job(&self, dim: usize) -> anyhow::Result<ShareJob> {
        if !matches!(
            self.method,
            Preset::Robust | Preset::Verbss | Preset::Spring
        ) {
            bail!(
                "{}: a partitioned input is read rank by rank, which runs --method robust, \
                 verbss or spring",
                self.mesh.display()
            );
        }
        let whole_mesh = [
            (self.positions.is_some(), "--positions"),
            (!self.slide.is_empty(), "--slide"),
            (self.solver.is_some(), "--solver"),
            (self.accel.is_some(), "--accel"),
            (self.predictor != Predictor::Previous, "--predictor"),
            (self.zone.zone.is_some(), "--zone"),
            (self.every.is_some(), "--every"),
            (self.pictures.html.is_some(), "--html"),
            (self.pictures.gif.is_some(), "--gif"),
        ];
        if let Some((_, option)) = whole_mesh.iter().find(|(given, _)| *given) {
            bail!(
                "{}: a partitioned input is read rank by rank, where {option} is not \
                 available (it needs the whole mesh)",
                self.mesh.display()
            );
        }
        if self
            .output
            .extension()
            .is_none_or(|e| e != "pvtu" && e != "msh")
        {
            bail!(
                "{}: a partitioned input is written rank by rank: the output is a .pvtu file \
                 (one .vtu piece per rank beside it) or a .msh name (one MSH 4.1 piece per \
                 rank beside it)",
                self.output.display()
            );
        }
        let Some(motion) = self.field_motion(dim)? else {
            bail!("--positions is not available on a partitioned input");
        };
        let binary = match self.output.extension() {
            Some(e) if e == "msh" => self.msh.split_encoding()?,
            _ => None,
        };
        Ok(ShareJob {
            output: self.output.clone(),
            moving: self.moving.clone(),
            settings: self.settings(&motion),
            motion,
            report: self.report.clone(),
            source: self.mesh.display().to_string(),
            quiet: self.quiet,
            overwrite: self.overwrite,
            binary,
        })
    }
}

/// A `verbss-mpi deform` job on a partitioned input ([`DeformArgs::share_job`]).
pub struct ShareJob {
    /// The output: a `.pvtu` file, or a `.msh` name for MSH 4.1 pieces.
    pub output: PathBuf,
    /// The moving groups.
    pub moving: Vec<String>,
    /// Their motion: a translation or a rotation.
    pub motion: Motion,
    /// The settings (method verbss or spring; of the near-wall treatments
    /// the rigid layer, the stiffening and the sub-steps).
    pub settings: Settings,
    /// Where rank 0 writes the per-step report (JSON), if anywhere.
    pub report: Option<PathBuf>,
    /// The input mesh as named by the user (the report's `mesh`).
    pub source: String,
    /// No progress output.
    pub quiet: bool,
    /// Whether the pieces may replace files of the input (`--overwrite`).
    pub overwrite: bool,
    /// MSH pieces binary (`true`) or ASCII, `None` for as the input
    /// (`--binary`, `--ascii`).
    pub binary: Option<bool>,
}

/// The `--slide` values as slide motions: `GROUP` slides in its own plane
/// (or planes), `GROUP:NX,NY[,NZ]` in the plane of that normal. In a value
/// `A,B:0,1,C` the numbers after `B:` (up to 3) are B's normal.
fn slides(values: &[String], dim: usize) -> anyhow::Result<Vec<Attachment>> {
    let mut specs: Vec<(&str, Option<Vec<f64>>)> = Vec::new();
    for value in values {
        for token in value.split(',') {
            let number = token.trim().parse::<f64>();
            match (token.split_once(':'), specs.last_mut(), number) {
                (Some((group, first)), ..) => {
                    let Ok(x) = first.trim().parse::<f64>() else {
                        bail!(
                            "--slide {value}: '{first}' is not a number (expected \
                             GROUP[:NX,NY[,NZ]])"
                        );
                    };
                    specs.push((group, Some(vec![x])));
                }
                (None, Some((_, Some(normal))), Ok(x)) if normal.len() < 3 => normal.push(x),
                _ => specs.push((token, None)),
            }
        }
    }
    let mut attachments = Vec::with_capacity(specs.len());
    for (group, normal) in specs {
        if group.is_empty() {
            bail!("--slide has an empty group name (expected GROUP[:NX,NY[,NZ]])");
        }
        attachments.push(Attachment::slide(group, normal.as_deref(), dim)?);
    }
    Ok(attachments)
}
