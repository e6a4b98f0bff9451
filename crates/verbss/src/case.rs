//! The TOML case file: mesh, motions, method, steps and outputs of a run
//! (documented in `docs/case-file.md`).
//!
//! Paths in a case file are relative to the case file. Unknown keys are
//! errors; every error names the file, the line and the key with what was
//! expected.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::deform::{Predictor, Preset, Reference, Settings};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::motion::{Attachment, Motion, PositionSource};
use crate::robust::Layer;
use crate::solve::{Accel, SolveParams, Solver};

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
}

impl Default for Output {
    fn default() -> Self {
        Output {
            dir: None,
            every: 1,
            series: true,
            final_mesh: true,
            report: true,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    mesh: String,
    steps: usize,
    dt: Option<f64>,
    #[serde(default)]
    reference: Reference,
    #[serde(default)]
    solver: SolverTable,
    #[serde(default)]
    motion: Vec<toml::Spanned<MotionSpec>>,
    #[serde(default)]
    output: OutputTable,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct SolverTable {
    #[serde(default)]
    method: Preset,
    solver: Option<Solver>,
    accel: Option<Accel>,
    omega: Option<f64>,
    tolerance: Option<f64>,
    absolute_tolerance: Option<bool>,
    max_iterations: Option<usize>,
    threads: Option<usize>,
    rigid_layer: Option<LayerSpec>,
    substeps: Option<u32>,
    stiffening: Option<f64>,
    blend: Option<bool>,
    #[serde(default)]
    predictor: Predictor,
}

/// `rigid_layer = "off" | "auto" | THICKNESS`.
#[derive(Deserialize)]
#[serde(untagged)]
enum LayerSpec {
    Name(String),
    Thickness(f64),
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
}

impl Default for OutputTable {
    fn default() -> Self {
        OutputTable {
            dir: None,
            every: 1,
            series: true,
            final_mesh: true,
            report: true,
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
        if file.steps == 0 {
            return Err(at(top("steps"), "`steps` must be at least 1".into()));
        }
        let dt = file.dt.unwrap_or(1.0 / file.steps as f64);
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(at(top("dt"), format!("`dt` must be positive (got {dt})")));
        }
        let s = &file.solver;
        let preset = s.method.settings(file.steps);
        let mut solve = SolveParams {
            solver: s.solver.unwrap_or_default(),
            accel: s.accel.unwrap_or_default(),
            // A solver, accel or omega given explicitly means exactly that.
            escalate: s.solver.is_none() && s.accel.is_none() && s.omega.is_none(),
            ..preset.solve
        };
        if let Some(omega) = s.omega {
            if !(omega > 0.0 && omega < 2.0) {
                return Err(at(
                    top("omega"),
                    format!("`solver.omega` must lie in (0, 2) (got {omega})"),
                ));
            }
            solve.omega = omega;
        }
        if let Some(tol) = s.tolerance {
            if !(tol > 0.0 && tol.is_finite()) {
                return Err(at(
                    top("tolerance"),
                    format!("`solver.tolerance` must be positive (got {tol})"),
                ));
            }
            solve.tolerance = tol;
        }
        if let Some(b) = s.absolute_tolerance {
            solve.absolute_tolerance = b;
        }
        if let Some(k) = s.max_iterations {
            if k == 0 {
                return Err(at(
                    top("max_iterations"),
                    "`solver.max_iterations` must be at least 1".into(),
                ));
            }
            solve.max_iterations = k;
        }
        if let Some(t) = s.threads {
            if t == 0 {
                return Err(at(
                    top("threads"),
                    "`solver.threads` must be at least 1".into(),
                ));
            }
            solve.threads = t;
        }
        let mut robust = preset.robust;
        if let Some(spec) = &s.rigid_layer {
            robust.layer = match spec {
                LayerSpec::Name(n) if n == "off" => Layer::Off,
                LayerSpec::Name(n) if n == "auto" => Layer::Auto,
                LayerSpec::Thickness(t) if *t > 0.0 && t.is_finite() => Layer::Thickness(*t),
                LayerSpec::Name(n) => {
                    return Err(at(
                        top("rigid_layer"),
                        format!("`solver.rigid_layer` must be \"off\", \"auto\" or a positive thickness (got \"{n}\")"),
                    ))
                }
                LayerSpec::Thickness(t) => {
                    return Err(at(
                        top("rigid_layer"),
                        format!("`solver.rigid_layer` must be \"off\", \"auto\" or a positive thickness (got {t})"),
                    ))
                }
            };
        }
        if let Some(k) = s.substeps {
            if k > 30 {
                return Err(at(
                    top("substeps"),
                    format!("`solver.substeps` must be at most 30 (got {k})"),
                ));
            }
            robust.substeps = k;
        }
        if let Some(p) = s.stiffening {
            if !(p >= 0.0 && p.is_finite()) {
                return Err(at(
                    top("stiffening"),
                    format!("`solver.stiffening` must be zero or positive (got {p})"),
                ));
            }
            robust.stiffening = p;
        }
        robust.blend = s.blend.unwrap_or(robust.blend);
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
            settings: Settings {
                steps: file.steps,
                dt,
                reference: file.reference,
                solve,
                robust,
                predictor: file.solver.predictor,
            },
            output: Output {
                dir: file.output.dir.map(|d| base.join(d)),
                every: file.output.every,
                series: file.output.series,
                final_mesh: file.output.final_mesh,
                report: file.output.report,
            },
            motions,
        })
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
            let z = [0.0, 0.0, 1.0];
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
                    axis: axis.as_ref().map_or(Ok(z), |a| v("axis", a))?,
                    angle: angle_deg.to_radians(),
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
                    axis: axis.as_ref().map_or(Ok(z), |a| v("axis", a))?,
                    pitch: pitch_deg.to_radians(),
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
                        amplitude: amplitude.clone(),
                        wavelength: *wavelength,
                        speed: *speed,
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
                    span: *span,
                    tip: *tip,
                },
                MotionSpec::Positions { file, files, .. } => match (file, files) {
                    (Some(f), None) => {
                        Motion::Positions(PositionSource::for_groups(&base.join(f), mesh, spec.groups())?)
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

/// A vector of `dim` numbers (a 2D mesh also takes 3 numbers with z = 0), padded to 3.
fn vector(key: &str, x: &[f64], dim: usize) -> std::result::Result<[f64; 3], String> {
    match x.len() {
        n if n == dim => Ok([x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]),
        3 if dim == 2 && x[2] == 0.0 => Ok([x[0], x[1], 0.0]),
        n => Err(format!(
            "`{key}` has {n} numbers (expected {dim} for a {dim}D mesh)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robust::Robust;
    use crate::solve::Method;

    fn parse(text: &str) -> Result<Case> {
        Case::parse(text, Path::new("cases/c.toml"))
    }

    fn err(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    #[test]
    fn parses_a_full_case() {
        let c = parse(
            r#"
mesh = "../m/naca.su2"
steps = 160
reference = "fixed"
[solver]
method = "ball-vertex"
solver = "direct"
accel = "auto"
omega = 1.5
tolerance = 1e-5
absolute_tolerance = true
max_iterations = 300
threads = 2
[[motion]]
kind = "pitch-plunge"
groups = ["airfoil"]
center = [0.25, 0.0]
pitch_deg = 40
plunge = [0.0, 0.2]
[[motion]]
kind = "fixed"
groups = ["farfield"]
[output]
dir = "out/naca"
every = 4
final = false
"#,
        )
        .unwrap();
        assert_eq!(c.mesh, PathBuf::from("cases/../m/naca.su2"));
        assert_eq!(c.settings.steps, 160);
        assert_eq!(c.settings.dt, 1.0 / 160.0);
        assert_eq!(c.settings.reference, Reference::Fixed);
        let s = &c.settings.solve;
        assert_eq!(s.method, Method::BallVertex);
        assert_eq!(s.solver, Solver::Direct);
        assert_eq!(s.accel, Accel::Auto);
        assert_eq!(
            (s.omega, s.tolerance, s.max_iterations, s.threads),
            (1.5, 1e-5, 300, 2)
        );
        assert!(s.absolute_tolerance);
        assert_eq!(c.motions.len(), 2);
        assert_eq!(c.motions[0].0, 14);
        assert_eq!(c.output.dir, Some(PathBuf::from("cases/out/naca")));
        assert_eq!(c.output.every, 4);
        assert!(!c.output.final_mesh && c.output.series && c.output.report);
    }

    #[test]
    fn unknown_top_level_key() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 3\nstep = 4\n"),
            "cases/c.toml:3: unknown field `step`, expected one of `mesh`, `steps`, `dt`, `reference`, `solver`, `motion`, `output`"
        );
    }

    #[test]
    fn missing_mesh() {
        assert_eq!(err("steps = 3\n"), "cases/c.toml:1: missing field `mesh`");
    }

    #[test]
    fn wrong_type() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = \"ten\"\n"),
            "cases/c.toml:2: invalid type: string \"ten\", expected usize"
        );
    }

    #[test]
    fn unknown_method() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 3\n[solver]\nmethod = \"fem\"\n"),
            "cases/c.toml:4: unknown variant `fem`, expected one of `robust`, `verbss`, `ball-vertex`, `spring`, `laplacian`"
        );
    }

    #[test]
    fn near_wall_treatments_follow_the_method_unless_given() {
        let head = "mesh = \"m.su2\"\nsteps = 3\n";
        let robust = parse(head).unwrap().settings.robust;
        assert_eq!(robust, Robust::recommended());
        let paper = parse(&format!("{head}[solver]\nmethod = \"verbss\"\n"))
            .unwrap()
            .settings
            .robust;
        assert_eq!(paper, Robust::off());
        let mixed = parse(&format!(
            "{head}[solver]\nmethod = \"verbss\"\nrigid_layer = 0.2\nsubsteps = 3\nstiffening = 2.0\n"
        ))
        .unwrap()
        .settings
        .robust;
        assert_eq!(mixed.layer, Layer::Thickness(0.2));
        assert_eq!((mixed.substeps, mixed.stiffening), (3, 2.0));
        let off = parse(&format!("{head}[solver]\nrigid_layer = \"off\"\n"))
            .unwrap()
            .settings
            .robust;
        assert_eq!(off.layer, Layer::Off);
        assert_eq!(
            err(&format!("{head}[solver]\nrigid_layer = \"thick\"\n")),
            "cases/c.toml:4: `solver.rigid_layer` must be \"off\", \"auto\" or a positive thickness (got \"thick\")"
        );
        assert_eq!(
            err(&format!("{head}[solver]\nrigid_layer = -0.5\n")),
            "cases/c.toml:4: `solver.rigid_layer` must be \"off\", \"auto\" or a positive thickness (got -0.5)"
        );
        assert_eq!(
            err(&format!("{head}[solver]\nsubsteps = 40\n")),
            "cases/c.toml:4: `solver.substeps` must be at most 30 (got 40)"
        );
        assert_eq!(
            err(&format!("{head}[solver]\nstiffening = -1.0\n")),
            "cases/c.toml:4: `solver.stiffening` must be zero or positive (got -1)"
        );
    }

    #[test]
    fn unknown_motion_kind() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 3\n[[motion]]\nkind = \"spin\"\ngroups = [\"a\"]\n"),
            "cases/c.toml:4: unknown variant `spin`, expected one of `fixed`, `slide`, `translation`, `rotation`, `pitch-plunge`, `undulation`, `bending`, `positions`"
        );
    }

    #[test]
    fn unknown_motion_key() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 3\n[[motion]]\nkind = \"rotation\"\ngroups = [\"a\"]\ncenter = [0, 0]\nangle = 3\n"),
            "cases/c.toml:3: unknown field `angle`, expected one of `groups`, `center`, `axis`, `angle_deg`"
        );
    }

    #[test]
    fn missing_motion_key() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 3\n[[motion]]\nkind = \"translation\"\ngroups = [\"a\"]\n"),
            "cases/c.toml:3: missing field `displacement`"
        );
    }

    #[test]
    fn out_of_range_values() {
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 0\n"),
            "cases/c.toml:2: `steps` must be at least 1"
        );
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 2\n[solver]\nomega = 2.5\n"),
            "cases/c.toml:4: `solver.omega` must lie in (0, 2) (got 2.5)"
        );
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 2\n[output]\nevery = 0\n"),
            "cases/c.toml:4: `output.every` must be at least 1"
        );
        assert_eq!(
            err("mesh = \"m.su2\"\nsteps = 2\n[[motion]]\nkind = \"fixed\"\ngroups = []\n"),
            "cases/c.toml:3: `groups` must name at least one group"
        );
    }

    #[test]
    fn vectors_must_match_the_dimension() {
        assert_eq!(vector("center", &[1.0, 2.0], 2), Ok([1.0, 2.0, 0.0]));
        assert_eq!(vector("center", &[1.0, 2.0, 0.0], 2), Ok([1.0, 2.0, 0.0]));
        assert_eq!(
            vector("axis", &[1.0, 2.0], 3),
            Err("`axis` has 2 numbers (expected 3 for a 3D mesh)".to_string())
        );
    }
}
