//! The TOML case file: mesh, motions, method, steps and outputs of a run
//! (documented in `docs/case-file.md`).
//!
//! Paths in a case file are relative to the case file. Unknown keys are
//! errors; every error names the file, the line and the key with what was
//! expected.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::io::{MshVersion, WriteOptions};
use crate::mesh::Mesh;
use crate::motion::{Attachment, Motion, Numbering, PositionSource};
use crate::settings::Settings;

/// The largest case file [`Case::read`] reads (1 MiB: it holds settings;
/// positions go in their own files).
pub const MAX_CASE_BYTES: u64 = 1 << 20;

/// A parsed case file.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The case file.
    pub path: PathBuf,
    /// The mesh file (resolved against the case file's folder).
    pub mesh: PathBuf,
    /// The zone of a multi-zone SU2 mesh file (`IZONE=`), if given.
    pub zone: Option<u32>,
    /// Steps, time step, reference and solver settings.
    pub settings: Settings,
    /// The output settings.
    pub output: Output,
    motions: Vec<(usize, MotionSpec)>,
}

/// What a run writes.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Output {
    /// The output folder (resolved against the case file's folder), if given.
    pub dir: Option<PathBuf>,
    /// Write every k-th step of the `.vtu` series (the last step always).
    pub every: usize,
    /// Write the `.vtu` series and its `.pvd`.
    pub series: bool,
    /// Write the final mesh in the input's format.
    pub final_mesh: bool,
    /// Write `report.json`.
    pub report: bool,
    /// MSH version of a `.msh` final mesh (`None`: the input's).
    pub msh_version: Option<MshVersion>,
    /// Binary (`Some(true)`) or ASCII `.msh` final mesh (`None`: as the input).
    pub msh_binary: Option<bool>,
}

impl Default for Output {
    fn default() -> Self {
        Output {
            dir: None,
            every: 1,
            series: true,
            final_mesh: true,
            report: true,
            msh_version: None,
            msh_binary: None,
        }
    }
}

impl Output {
    /// The options the final mesh `mesh` is written with: the input's MSH
    /// version and encoding ([`WriteOptions::for_mesh`]) unless this output
    /// names others.
    pub fn write_options(&self, mesh: &Mesh) -> WriteOptions {
        let mut options = WriteOptions::for_mesh(mesh);
        options.msh_version = self.msh_version.unwrap_or(options.msh_version);
        options.binary = self.msh_binary.unwrap_or(options.binary);
        options
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    mesh: String,
    zone: Option<u32>,
    steps: usize,
    dt: Option<f64>,
    /// Refused with a message: `reference` is a `[solver]` setting.
    reference: Option<toml::Value>,
    /// The `[solver]` table: the settings of [`crate::settings::TABLE`] and their values.
    #[serde(default)]
    solver: toml::Table,
    #[serde(default)]
    motion: Vec<toml::Spanned<MotionSpec>>,
    #[serde(default)]
    output: OutputTable,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OutputTable {
    dir: Option<String>,
    #[serde(default = "one")]
    every: usize,
    #[serde(default = "yes")]
    series: bool,
    #[serde(default = "yes", rename = "final")]
    final_mesh: bool,
    #[serde(default = "yes")]
    report: bool,
    msh_version: Option<MshVersion>,
    msh_encoding: Option<MshEncoding>,
}

/// `msh_encoding` of `[output]`.
#[derive(Deserialize)]
#[serde(rename_all = "lowercase")]
enum MshEncoding {
    Ascii,
    Binary,
}

impl Default for OutputTable {
    fn default() -> Self {
        OutputTable {
            dir: None,
            every: 1,
            series: true,
            final_mesh: true,
            report: true,
            msh_version: None,
            msh_encoding: None,
        }
    }
}

fn one() -> usize {
    1
}

fn yes() -> bool {
    true
}

/// One `[[motion]]` table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
enum MotionSpec {
    Fixed {
        groups: Vec<String>,
    },
    Slide {
        groups: Vec<String>,
        normal: Option<Vec<f64>>,
    },
    Translation {
        groups: Vec<String>,
        displacement: Vec<f64>,
    },
    Rotation {
        groups: Vec<String>,
        center: Vec<f64>,
        axis: Option<Vec<f64>>,
        angle_deg: f64,
    },
    PitchPlunge {
        groups: Vec<String>,
        center: Vec<f64>,
        axis: Option<Vec<f64>>,
        pitch_deg: f64,
        plunge: Vec<f64>,
        period: Option<usize>,
    },
    Undulation {
        groups: Vec<String>,
        head: Vec<f64>,
        axis: Vec<f64>,
        lateral: Option<Vec<f64>>,
        amplitude: Vec<f64>,
        wavelength: f64,
        speed: f64,
        #[serde(default)]
        ramp: usize,
    },
    Bending {
        groups: Vec<String>,
        root: Vec<f64>,
        span_axis: Vec<f64>,
        direction: Vec<f64>,
        span: f64,
        tip: f64,
    },
    Positions {
        groups: Vec<String>,
        file: Option<String>,
        files: Option<String>,
    },
}

impl MotionSpec {
    fn groups(&self) -> &[String] {
        match self {
            MotionSpec::Fixed { groups }
            | MotionSpec::Slide { groups, .. }
            | MotionSpec::Translation { groups, .. }
            | MotionSpec::Rotation { groups, .. }
            | MotionSpec::PitchPlunge { groups, .. }
            | MotionSpec::Undulation { groups, .. }
            | MotionSpec::Bending { groups, .. }
            | MotionSpec::Positions { groups, .. } => groups,
        }
    }
}

/// The message of a setting's error, without the `invalid setting: ` of
/// its display.
fn setting_message(e: Error) -> String {
    match e {
        Error::InvalidSetting(message) => message,
        other => other.to_string(),
    }
}

/// 1-based line of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

impl Case {
    /// Reads and checks a case file.
    pub fn read(path: &Path) -> Result<Case> {
        let (path_buf, io) = (path.to_path_buf(), |source| Error::Io {
            path: path.into(),
            source,
        });
        // Refused before its TOML tree (some hundred bytes a key) is built.
        let size = std::fs::metadata(path).map_err(io)?.len();
        if size > MAX_CASE_BYTES {
            let message = format!("the case file is {size} bytes (at most {MAX_CASE_BYTES})");
            return Err(Error::Parse {
                path: path_buf,
                line: 1,
                message,
            });
        }
        let text = std::fs::read_to_string(path).map_err(io)?;
        Case::parse(&text, path)
    }

    /// Parses a case file's text; `path` names it in errors and anchors its relative paths.
    pub fn parse(text: &str, path: &Path) -> Result<Case> {
        let at = |line: usize, message: String| Error::Parse {
            path: path.to_path_buf(),
            line,
            message,
        };
        let file: CaseFile = toml::from_str(text).map_err(|e| {
            let line = e.span().map_or(1, |s| line_of(text, s.start));
            at(line, e.message().trim_end().to_string())
        })?;
        let top = |key: &str| {
            text.lines()
                .position(|l| l.trim_start().starts_with(key))
                .map_or(1, |i| i + 1)
        };
        if file.zone == Some(0) {
            return Err(at(top("zone"), "`zone` must be at least 1".into()));
        }
        if file.steps == 0 {
            return Err(at(top("steps"), "`steps` must be at least 1".into()));
        }
        let dt = file.dt.unwrap_or(1.0 / file.steps as f64);
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(at(
                top("dt"),
                format!(
                    "`dt` must be positive (got {})",
                    crate::error::format_number(dt)
                ),
            ));
        }
        if file.reference.is_some() {
            return Err(at(
                top("reference"),
                "`reference` is a setting of the `[solver]` table: move it there".into(),
            ));
        }
        let mut named = Vec::new();
        for (key, value) in &file.solver {
            let line = top(key);
            let text = match value {
                toml::Value::String(s) => s.clone(),
                toml::Value::Integer(i) => i.to_string(),
                toml::Value::Float(x) => x.to_string(),
                toml::Value::Boolean(b) => (if *b { "on" } else { "off" }).into(),
                other => {
                    return Err(at(
                        line,
                        format!(
                            "`solver.{key}` must be a string, a number or true/false (got {other})"
                        ),
                    ))
                }
            };
            Settings::check(key, &text)
                .map_err(|e| at(line, format!("`solver.{key}`: {}", setting_message(e))))?;
            named.push((key.as_str(), text));
        }
        let mut settings = Settings::named(file.steps, &named)
            .map_err(|e| at(top("[solver]"), setting_message(e)))?;
        settings.dt = dt;
        if file.output.every == 0 {
            return Err(at(top("every"), "`output.every` must be at least 1".into()));
        }
        let base = path.parent().unwrap_or(Path::new("")).to_path_buf();
        let mut motions = Vec::new();
        for m in file.motion {
            let line = line_of(text, m.span().start);
            let spec = m.into_inner();
            if spec.groups().is_empty() {
                return Err(at(line, "`groups` must name at least one group".into()));
            }
            motions.push((line, spec));
        }
        Ok(Case {
            path: path.to_path_buf(),
            mesh: base.join(&file.mesh),
            zone: file.zone,
            settings,
            output: Output {
                dir: file.output.dir.map(|d| base.join(d)),
                every: file.output.every,
                series: file.output.series,
                final_mesh: file.output.final_mesh,
                report: file.output.report,
                msh_version: file.output.msh_version,
                msh_binary: file
                    .output
                    .msh_encoding
                    .map(|e| matches!(e, MshEncoding::Binary)),
            },
            motions,
        })
    }

    /// The positions files its motions read: each `file`, and each step's
    /// file of a `files` pattern.
    pub fn position_files(&self) -> Vec<PathBuf> {
        let base = self.path.parent().unwrap_or(Path::new(""));
        let mut files = Vec::new();
        for (_, spec) in &self.motions {
            match spec {
                MotionSpec::Positions { file: Some(f), .. } => files.push(base.join(f)),
                MotionSpec::Positions {
                    files: Some(pattern),
                    ..
                } => files.extend(
                    (1..=self.settings.steps)
                        .map(|n| crate::motion::step_path(&base.join(pattern), n)),
                ),
                _ => {}
            }
        }
        files
    }

    /// The motions for `mesh`: vectors checked against its dimension, groups
    /// checked to exist, position files read (node IDs are 0-based node
    /// indices in the mesh file's order: SU2's `GlobalID`).
    pub fn attachments(&self, mesh: &Mesh) -> Result<Vec<Attachment>> {
        let base = self.path.parent().unwrap_or(Path::new(""));
        let mut out = Vec::new();
        for (line, spec) in &self.motions {
            let at = |message: String| Error::Parse {
                path: self.path.clone(),
                line: *line,
                message,
            };
            for g in spec.groups() {
                mesh.group(g).map_err(|e| at(e.to_string()))?;
            }
            let dim = mesh.dim;
            let v = |key: &str, x: &[f64]| vector(key, x, dim).map_err(at);
            let turn = |x: &Option<Vec<f64>>| rotation_axis(x.as_deref(), dim).map_err(at);
            let motion = match spec {
                MotionSpec::Fixed { .. } => Motion::Fixed,
                MotionSpec::Slide { normal, .. } => Motion::Slide {
                    normal: normal.as_ref().map(|n| v("normal", n)).transpose()?,
                },
                MotionSpec::Translation { displacement, .. } => Motion::Translation {
                    displacement: v("displacement", displacement)?,
                },
                MotionSpec::Rotation {
                    center,
                    axis,
                    angle_deg,
                    ..
                } => Motion::Rotation {
                    center: v("center", center)?,
                    axis: turn(axis)?,
                    angle: number("angle_deg", *angle_deg, false).map_err(at)?.to_radians(),
                },
                MotionSpec::PitchPlunge {
                    center,
                    axis,
                    pitch_deg,
                    plunge,
                    period,
                    ..
                } => Motion::PitchPlunge {
                    center: v("center", center)?,
                    axis: turn(axis)?,
                    pitch: number("pitch_deg", *pitch_deg, false).map_err(at)?.to_radians(),
                    plunge: v("plunge", plunge)?,
                    period: *period,
                },
                MotionSpec::Undulation {
                    head,
                    axis,
                    lateral,
                    amplitude,
                    wavelength,
                    speed,
                    ramp,
                    ..
                } => {
                    let axis = v("axis", axis)?;
                    let lateral = match (lateral, dim) {
                        (Some(l), _) => v("lateral", l)?,
                        (None, 2) => [-axis[1], axis[0], 0.0],
                        (None, _) => {
                            return Err(at(
                                "`lateral` is required for an undulation in 3D".into(),
                            ))
                        }
                    };
                    Motion::Undulation {
                        head: v("head", head)?,
                        axis,
                        lateral,
                        amplitude: amplitude
                            .iter()
                            .map(|&a| number("amplitude", a, false).map_err(at))
                            .collect::<Result<_>>()?,
                        wavelength: number("wavelength", *wavelength, true).map_err(at)?,
                        speed: number("speed", *speed, false).map_err(at)?,
                        ramp: *ramp,
                    }
                }
                MotionSpec::Bending {
                    root,
                    span_axis,
                    direction,
                    span,
                    tip,
                    ..
                } => Motion::Bending {
                    root: v("root", root)?,
                    span_axis: v("span_axis", span_axis)?,
                    direction: v("direction", direction)?,
                    span: number("span", *span, true).map_err(at)?,
                    tip: number("tip", *tip, false).map_err(at)?,
                },
                MotionSpec::Positions { file, files, .. } => match (file, files) {
                    (Some(f), None) => {
                        Motion::Positions(PositionSource::for_groups(
                            &base.join(f),
                            mesh,
                            spec.groups(),
                            &Numbering::default(),
                        )?)
                    }
                    (None, Some(pattern)) => {
                        Motion::Positions(PositionSource::PerStep(base.join(pattern)))
                    }
                    _ => return Err(at(
                        "a positions motion needs exactly one of `file` (final positions) or `files` (a file pattern with {step})".into(),
                    )),
                },
            };
            motion.validate(dim).map_err(|e| at(e.to_string()))?;
            out.push(Attachment {
                groups: spec.groups().to_vec(),
                motion,
            });
        }
        Ok(out)
    }
}

/// The axis of a rotation (`None`: z). A 2D mesh turns in its x–y plane:
/// its axis is z, or −z for the opposite sense, and any other is refused
/// rather than ignored.
fn rotation_axis(axis: Option<&[f64]>, dim: usize) -> std::result::Result<[f64; 3], String> {
    match (axis, dim) {
        (None, _) => Ok([0.0, 0.0, 1.0]),
        (Some(a), 2) if a.len() == 3 && a[0] == 0.0 && a[1] == 0.0 && a[2] != 0.0 => {
            Ok([0.0, 0.0, a[2].signum()])
        }
        (Some(a), 2) => Err(format!(
            "`axis` {a:?} on a 2D mesh, which turns in its x–y plane (give [0, 0, 1], or \
             [0, 0, -1] for the opposite sense, or leave it out)"
        )),
        (Some(a), _) => vector("axis", a, dim),
    }
}

/// The number `x` of `key`, unless it is not finite or beyond ±1e100
/// ([`crate::motion::MAX_COORDINATE`]: beyond it positions overflow), or,
/// when `positive`, below 1e-100 (a length divided by it overflows).
fn number(key: &str, x: f64, positive: bool) -> std::result::Result<f64, String> {
    let bound = crate::motion::MAX_COORDINATE;
    let fits = match positive {
        true => (1.0 / bound..=bound).contains(&x),
        false => x.abs() <= bound,
    };
    if fits {
        return Ok(x);
    }
    Err(format!(
        "`{key}` = {}: expected {} (beyond it the positions overflow)",
        crate::error::format_number(x),
        match positive {
            true => "a positive number from 1e-100 to 1e100",
            false => "a finite number within ±1e100",
        }
    ))
}

/// A vector of `dim` numbers (a 2D mesh also takes 3 numbers with z = 0),
/// each finite and within ±1e100 ([`number`]), padded to 3.
fn vector(key: &str, x: &[f64], dim: usize) -> std::result::Result<[f64; 3], String> {
    for &v in x {
        number(key, v, false)?;
    }
    match x.len() {
        n if n == dim => Ok([x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]),
        3 if dim == 2 && x[2] == 0.0 => Ok([x[0], x[1], 0.0]),
        3 if dim == 2 => Err(format!(
            "`{key}` has a non-zero z on a 2D mesh, which lies in the x–y plane \
             (give 2 numbers, or 3 with z = 0)"
        )),
        n => Err(format!(
            "`{key}` has {n} numbers (expected {dim} for a {dim}D mesh)"
        )),
    }
}

#[cfg(test)]
mod tests;
