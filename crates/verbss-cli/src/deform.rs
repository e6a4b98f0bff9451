//! `verbss deform MESH -o OUT --moving GROUP … (--translate | --rotate | --positions)`:
//! one total motion of some groups, reached in `--steps` equal increments.
//!
//! OUT is written in the format of its extension with the input's numbering;
//! `--report FILE.json` writes the per-step report. An inverted element stops
//! the run with exit code 3, the last valid mesh in OUT and the failed state
//! beside it (`OUT-STEM.failed.vtu`). `--every K` also writes the `.vtu`
//! series of every K-th step beside OUT (`OUT-STEM_NNNN.vtu`, `OUT-STEM.pvd`).
//!
//! An OpenFOAM OUT that is the input case gets its steps as the flow solver
//! reads them: the last step, and with `--every K` every K-th, each in the
//! time directory of its time (`CASE/TIME/polyMesh/points`; see
//! [`crate::case_times`]); `constant/polyMesh` stays as it was, and a failed
//! run writes only the accepted steps and the failed state
//! `CASE/verbss.failed.vtu`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::bail;
use clap::{ArgGroup, Args};

use verbss::io::outputs::Input;
use verbss::io::{Format, WriteOptions};
use verbss::motion::{Attachment, Motion, Numbering, PositionSource};
use verbss::Mesh;

use crate::case_times::TimeArgs;
use crate::msh::MshArgs;
use crate::overwrite::mesh_inputs;
use crate::render::{PictureArgs, Recorder};
use crate::run::{file_stem, output_dir, parse_every, run_here, Job, Prepared};
use crate::settings::SettingArgs;
use crate::zone::{self, ZoneArg};

/// Arguments of `verbss deform`.
#[derive(Args)]
#[command(group(ArgGroup::new("motion").required(true).args(["translate", "rotate", "positions"])))]
pub struct DeformArgs {
    /// The input mesh (.msh, .su2, .vtu, .cgns, an OpenFOAM case directory).
    mesh: PathBuf,
    /// The output mesh; its extension chooses the format. An OpenFOAM case
    /// (no extension): the input case itself gets the moved points in
    /// `CASE/TIME/polyMesh/points` (TIME = startTime + step·deltaT, see
    /// --dt), another a whole `constant/polyMesh`.
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
    /// Number of equal increments.
    #[arg(long, default_value_t = 1, allow_hyphen_values = true)]
    steps: usize,
    #[command(flatten)]
    settings: SettingArgs,
    #[command(flatten)]
    times: TimeArgs,
    /// Also write the .vtu series of every K-th step (step 0 and the last
    /// step always) beside OUT: OUT-STEM_NNNN.vtu and OUT-STEM.pvd; into the
    /// input OpenFOAM case, every K-th step's time directory instead.
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

/// The job of `verbss deform`: reads the mesh, checks the output path,
/// and decides the motion and the settings ([`DeformArgs::prepare_on`]).
pub fn prepare(args: DeformArgs) -> anyhow::Result<Prepared> {
    let format = Format::from_path(&args.output)?;
    let mut mesh = zone::read(&args.mesh, args.zone.zone, "--zone K", args.quiet)?;
    let write_options = args.msh.options(&mesh);
    if format != Format::Msh {
        // Only an MSH output writes the coordinates back into the input
        // file's bytes; any other format frees them (the file's size).
        mesh.origin.gmsh = None;
    }
    args.prepare_on(Arc::new(mesh), &Numbering::default(), write_options)
}

impl DeformArgs {
    /// The job of these arguments on `mesh`: the input mesh, or one rank's
    /// part of it (its groups all named, its nodes numbered by `numbering`
    /// in a positions file), written with `write_options`: checks the
    /// groups and decides the motion and the settings.
    pub fn prepare_on(
        &self,
        mesh: Arc<Mesh>,
        numbering: &Numbering,
        write_options: WriteOptions,
    ) -> anyhow::Result<Prepared> {
        // A rank's pieces (`.pvtu`) are not a format of one mesh.
        let format = Format::from_path(&self.output).ok();
        let dim = mesh.dim;
        let slides = slides(&self.slide, dim)?;
        for g in self
            .moving
            .iter()
            .chain(slides.iter().flat_map(|a| &a.groups))
        {
            if let Err(e) = mesh.group(g) {
                return Err(zone::missing_group(e, &self.mesh, g));
            }
        }
        let motion = match self.field_motion(dim)? {
            Some(motion) => motion,
            None => match &self.positions {
                Some(path) => Motion::Positions(PositionSource::for_groups(
                    path,
                    &mesh,
                    &self.moving,
                    numbering,
                )?),
                None => unreachable!("clap requires one motion"),
            },
        };
        let mut settings = self.settings.settings(self.steps)?;
        // `-o .` names its directory by its path only.
        let output = match format {
            Some(Format::Foam) => std::path::absolute(&self.output)?.components().collect(),
            _ => self.output.clone(),
        };
        let foam_times = self.times.case_times(&self.mesh, &output, self.steps)?;
        if let Some(dt) = self.times.dt()?.or(foam_times.as_ref().map(|t| t.delta)) {
            settings.dt = dt;
        }
        let dir = output_dir(&output);
        let job = Job {
            name: file_stem(&output),
            source: self.mesh.display().to_string(),
            write_options,
            mesh,
            attachments: slides
                .into_iter()
                .chain([Attachment {
                    groups: self.moving.clone(),
                    motion,
                }])
                .collect(),
            settings,
            foam_times,
            every: self.every.unwrap_or(1),
            series: self.every.is_some(),
            final_mesh: true,
            report: self.report.clone(),
            // As given (`UP.SU2` stays `UP.SU2`).
            extension: output.extension().map_or_else(
                || format.map_or("", Format::extension).into(),
                |e| e.to_string_lossy().into_owned(),
            ),
            dir,
            inputs: self.inputs(),
            overwrite: self.overwrite,
            from_case: false,
        };
        let recorder = Recorder::new(&self.pictures, &job.mesh, job.settings.steps, None);
        Ok(Prepared {
            job,
            quiet: self.quiet,
            recorder,
        })
    }

    /// The files `verbss deform` reads: the mesh and the positions file.
    pub fn inputs(&self) -> Vec<Input> {
        let mut inputs = mesh_inputs(&self.mesh);
        inputs.extend(self.positions.iter().map(|path| Input {
            what: "the positions file",
            path: path.clone(),
        }));
        inputs
    }

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

    /// Whether the setting `name` was given.
    pub fn given(&self, name: &str) -> bool {
        self.settings.given(name)
    }

    /// Whether `--zone` was given.
    pub fn zone_given(&self) -> bool {
        self.zone.zone.is_some()
    }

    /// Whether `--html` or `--gif` was given.
    pub fn pictures_given(&self) -> bool {
        self.pictures.html.is_some() || self.pictures.gif.is_some()
    }

    /// Whether `--overwrite` was given.
    pub fn overwrite(&self) -> bool {
        self.overwrite
    }

    /// The encoding `--binary`/`--ascii` give MSH pieces (`None`: the input's).
    pub fn split_encoding(&self) -> anyhow::Result<Option<bool>> {
        self.msh.split_encoding()
    }
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
