//! The settings of a run, their names and presets (docs/case-file.md lists
//! every key): one vocabulary for the command line, case files, Python and
//! C, which map nothing themselves.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::motion::{Attachment, Motion};
use crate::names::{named, one_of};
use crate::robust::Robust;
use crate::solve::{Method, SolveParams};

/// Which configuration the springs are built on and what the unknown is
/// (the paper's options 1 and 2, and a third that returns exactly:
/// docs/method.md, "Time stepping").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Reference {
    /// Option 1: springs on the current coordinates, solve for the increment.
    #[default]
    Updated,
    /// Option 2: springs on the input mesh, solve for the total displacement
    /// (also spelled `initial`).
    #[serde(alias = "initial")]
    #[cfg_attr(feature = "clap", value(alias = "initial"))]
    Fixed,
    /// Springs on the input mesh moved by the blended rigid motion to the
    /// step's boundary position, solve for the rest of the total
    /// displacement from the input mesh: the mesh is a function of the
    /// boundary's position, so a periodic motion comes back to the input
    /// mesh (the robust method's default for a periodic motion, as
    /// Reference::for_motions chooses it).
    Anchored,
}

impl Reference {
    /// The reference of [`Preset::Robust`] for a run of `motions`: anchored
    /// when every moving motion is periodic (pitch–plunge, undulation) and
    /// the mesh must come back with the boundary, updated for the one-way
    /// motions (a rotation, translation, bending or given positions), whose
    /// springs on the current mesh carry a gap that closes further
    /// (docs/method.md, "Time stepping").
    pub fn for_motions<'a>(motions: impl IntoIterator<Item = &'a Motion>) -> Reference {
        let mut moving = motions.into_iter().filter(|m| m.moves()).peekable();
        let periodic =
            |m: &Motion| matches!(m, Motion::PitchPlunge { .. } | Motion::Undulation { .. });
        if moving.peek().is_some() && moving.all(periodic) {
            Reference::Anchored
        } else {
            Reference::Updated
        }
    }
}

named!(Reference, "reference", [
    Updated => "updated",
    Fixed => "fixed",
    Anchored => "anchored",
], ["initial" => Fixed]);

/// How a step's initial guess is made from the steps before it. The guess
/// only decides where the sweeps start, not the system they solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Predictor {
    /// The previous step's solution (docs/method.md, "Time stepping").
    #[default]
    Previous,
    /// Linear extrapolation `2 u₁ − u₂` from the previous solution `u₁` and
    /// the one before it `u₂` (per unit step: increments with the updated
    /// reference, total displacements — the input mesh's `u = 0` counting
    /// as the first — with the fixed one). For a smooth motion the guess is
    /// off by the change of the increment rather than by the increment's
    /// change, so fewer sweeps reach the same stop.
    Linear,
}

named!(Predictor, "predictor", [Previous => "previous", Linear => "linear"]);

/// The named starting points of [`Settings`]: what `method` means on the
/// command line, in case files, Python and C.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Preset {
    /// VerBSS with the near-wall treatments (rigid layer, stiffening,
    /// sub-steps, blended rigid motion) and the escalating solve: the
    /// product's default.
    #[default]
    Robust,
    /// The paper's method exactly: VerBSS, no near-wall treatment.
    Verbss,
    /// The same springs solved as one global system.
    BallVertex,
    /// Edge springs only (Batina).
    Spring,
    /// The component-wise Laplacian.
    Laplacian,
}

named!(Preset, "method", [
    Robust => "robust",
    Verbss => "verbss",
    BallVertex => "ball-vertex",
    Spring => "spring",
    Laplacian => "laplacian",
]);

impl Preset {
    /// The settings of `steps` steps with this preset and every other
    /// setting at its default.
    pub fn settings(self, steps: usize) -> Settings {
        let mut s = Settings::new(steps);
        s.solve.method = match self {
            Preset::Robust | Preset::Verbss => Method::Verbss,
            Preset::BallVertex => Method::BallVertex,
            Preset::Spring => Method::Spring,
            Preset::Laplacian => Method::Laplacian,
        };
        if self == Preset::Robust {
            s.robust = Robust::recommended();
            s.reference = Reference::Anchored;
        }
        s
    }
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct Settings {
    /// The number of steps `N` of the run (the motions' `n/N`).
    pub steps: usize,
    /// Time per step (`t = n · dt`, used by undulation).
    pub dt: f64,
    /// Updated, fixed or anchored reference.
    pub reference: Reference,
    /// The solver's settings for every step.
    pub solve: SolveParams,
    /// The near-wall treatments (off: the paper's method).
    pub robust: Robust,
    /// How each step's initial guess is made.
    pub predictor: Predictor,
}

impl Settings {
    /// The names [`Settings::set`] takes: the case file's `[solver]` keys
    /// and `reference`, Python's keywords, and `verbss deform`'s options
    /// with `_` for `-`.
    pub const NAMES: &'static [&'static str] = &[
        "method",
        "solver",
        "accel",
        "reference",
        "predictor",
        "tolerance",
        "absolute_tolerance",
        "max_iterations",
        "omega",
        "threads",
        "rigid_layer",
        "substeps",
        "stiffening",
        "blend",
    ];

    /// `steps` steps of `dt = 1/steps`, updated reference, default solver,
    /// no near-wall treatment: [`Settings::paper`]. The product's default
    /// is [`Settings::robust`].
    pub fn new(steps: usize) -> Settings {
        Settings {
            steps,
            dt: 1.0 / steps.max(1) as f64,
            reference: Reference::Updated,
            solve: SolveParams::default(),
            robust: Robust::off(),
            predictor: Predictor::Previous,
        }
    }

    /// The product's default: [`Preset::Robust`].
    pub fn robust(steps: usize) -> Settings {
        Preset::Robust.settings(steps)
    }

    /// The paper's method exactly: [`Preset::Verbss`].
    pub fn paper(steps: usize) -> Settings {
        Preset::Verbss.settings(steps)
    }

    /// The preset these settings are, if they are one with their defaults
    /// changed only in the solver's numbers (`robust` when the method is
    /// VerBSS with the recommended near-wall treatments).
    pub fn preset(&self) -> Preset {
        match self.solve.method {
            Method::Verbss if self.robust == Robust::recommended() => Preset::Robust,
            Method::Verbss => Preset::Verbss,
            Method::BallVertex => Preset::BallVertex,
            Method::Spring => Preset::Spring,
            Method::Laplacian => Preset::Laplacian,
        }
    }

    /// Checks every setting; the messages name the settings.
    pub fn validate(&self) -> Result<()> {
        if self.steps == 0 {
            return Err(Error::InvalidSetting(
                "the number of steps must be at least 1".into(),
            ));
        }
        if !(self.dt > 0.0 && self.dt.is_finite()) {
            return Err(Error::InvalidSetting(format!(
                "dt must be positive (got {})",
                self.dt
            )));
        }
        self.solve.validate()?;
        self.robust.validate()
    }

    /// The settings of `steps` steps from named values in any order, as
    /// `verbss deform` builds them from its options: the preset of `method`
    /// (robust when not named), then every other value [`Settings::set`]
    /// over it in the order given (a name given twice: the last wins),
    /// checked by [`Settings::validate`]. The one mapping of the bindings.
    pub fn named<N: AsRef<str>, V: AsRef<str>>(
        steps: usize,
        values: &[(N, V)],
    ) -> Result<Settings> {
        let is_method = |name: &N| name.as_ref() == "method";
        let preset = match values.iter().rev().find(|(n, _)| is_method(n)) {
            Some((_, v)) => v.as_ref().parse()?,
            None => Preset::Robust,
        };
        let mut settings = preset.settings(steps);
        for (name, value) in values.iter().filter(|(n, _)| !is_method(n)) {
            settings.set(name.as_ref(), value.as_ref())?;
        }
        settings.validate()?;
        Ok(settings)
    }

    /// Checks one named value on its own over the defaults: its name, its
    /// spelling and its range ([`Settings::named`] also checks how the
    /// values go together).
    pub fn check(name: &str, value: &str) -> Result<()> {
        Settings::named(1, &[(name, value)]).map(|_| ())
    }

    /// Sets the setting `name` ([`Settings::NAMES`]) from its value as
    /// `verbss deform` spells it: `method`, `solver`, `accel`, `reference`
    /// and `predictor` by their names (`method` sets the system and its
    /// near-wall treatments, so it comes first); `tolerance`, `omega` and
    /// `stiffening` numbers; `max_iterations`, `threads` and `substeps`
    /// whole numbers; `absolute_tolerance` and `blend` `on` or `off`;
    /// `rigid_layer` `off`, `auto` or a wall distance. A `solver`, `accel`
    /// or `omega` given means exactly that solver: no escalation.
    pub fn set(&mut self, name: &str, value: &str) -> Result<()> {
        let s = &mut self.solve;
        let r = &mut self.robust;
        match name {
            "method" => {
                let preset = value.parse::<Preset>()?.settings(self.steps);
                s.method = preset.solve.method;
                *r = preset.robust;
            }
            "solver" => (s.solver, s.escalate) = (value.parse()?, false),
            "accel" => (s.accel, s.escalate) = (value.parse()?, false),
            "omega" => (s.omega, s.escalate) = (number(name, value)?, false),
            "reference" => self.reference = value.parse()?,
            "predictor" => self.predictor = value.parse()?,
            "tolerance" => s.tolerance = number(name, value)?,
            "absolute_tolerance" => s.absolute_tolerance = switch(name, value)?,
            "max_iterations" => s.max_iterations = count(name, value)?,
            "threads" => s.threads = count(name, value)?,
            "rigid_layer" => r.layer = value.parse()?,
            "substeps" => r.substeps = count(name, value)?,
            "stiffening" => r.stiffening = number(name, value)?,
            "blend" => r.blend = switch(name, value)?,
            _ => {
                return Err(Error::InvalidSetting(format!(
                    "unknown setting '{name}' (expected {})",
                    one_of(Settings::NAMES)
                )))
            }
        }
        Ok(())
    }
}

impl Attachment {
    /// A sliding wall (a symmetry plane) as the bindings give it: each node
    /// of `group` slides in the plane through it of normal `normal` (`dim`
    /// numbers, not all zero), or in the plane of the group's facets when
    /// `None`, as with `verbss deform --slide` (a case file's `kind =
    /// "slide"` and its `normal`).
    pub fn slide(group: &str, normal: Option<&[f64]>, dim: usize) -> Result<Attachment> {
        let normal = match normal {
            None => None,
            // A 2D normal may be given with a zero z, as 2D vectors may.
            Some(n) if dim == 2 && n.len() == 3 && n[2] != 0.0 => {
                return Err(Error::InvalidSetting(format!(
                    "the slide normal of group '{group}' has z = {} on a 2D mesh: give NX,NY \
                     (or NX,NY,0)",
                    n[2]
                )))
            }
            Some(n) if n.len() != dim && !(dim == 2 && n.len() == 3) => {
                return Err(Error::InvalidSetting(format!(
                    "the slide normal of group '{group}' has {} numbers, expected {dim} \
                     (the mesh's dimension)",
                    n.len()
                )))
            }
            Some(n) if !n.iter().all(|x| x.is_finite()) || n.iter().all(|&x| x == 0.0) => {
                return Err(Error::InvalidSetting(format!(
                    "the slide normal of group '{group}' must be a finite non-zero vector \
                     (got {n:?})"
                )))
            }
            Some(n) => Some([n[0], n[1], n.get(2).copied().unwrap_or(0.0)]),
        };
        Ok(Attachment {
            groups: vec![group.to_string()],
            motion: Motion::Slide { normal },
        })
    }
}

/// A number (its range is [`Settings::validate`]'s to check).
fn number(name: &str, value: &str) -> Result<f64> {
    value
        .parse()
        .map_err(|_| Error::InvalidSetting(format!("{name} must be a number (got '{value}')")))
}

/// A whole number ≥ 0 that fits `T`.
fn count<T: TryFrom<u64>>(name: &str, value: &str) -> Result<T> {
    let bad = |what: String| Error::InvalidSetting(format!("{name} {what}"));
    match (value.parse::<u64>(), value.parse::<i128>()) {
        (Ok(k), _) => T::try_from(k).map_err(|_| bad(format!("is too large (got {value})"))),
        (Err(_), Ok(k)) if k < 0 => Err(bad(format!("must be zero or positive (got {value})"))),
        (Err(_), Ok(_)) => Err(bad(format!("is too large (got {value})"))),
        (Err(_), Err(_)) => Err(bad(format!("must be a whole number (got '{value}')"))),
    }
}

/// `on` or `off`.
fn switch(name: &str, value: &str) -> Result<bool> {
    match value {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(Error::InvalidSetting(format!(
            "{name} must be on or off (got '{value}')"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robust::Layer;
    use crate::solve::{Accel, Solver};

    #[test]
    fn named_values_give_what_the_command_line_builds_in_any_order() {
        assert_eq!(
            Settings::named::<&str, &str>(3, &[]).unwrap(),
            Settings::robust(3)
        );
        let given = [
            ("rigid_layer", "0.1"),
            ("method", "verbss"),
            ("omega", "1.5"),
            ("substeps", "3"),
            ("stiffening", "2"),
            ("blend", "on"),
            ("predictor", "linear"),
            ("reference", "initial"),
            ("absolute_tolerance", "on"),
            ("tolerance", "1e-8"),
            ("max_iterations", "50"),
            ("threads", "2"),
            ("accel", "amg"),
        ];
        let mut expected = Settings::paper(4);
        expected.reference = Reference::Fixed;
        expected.predictor = Predictor::Linear;
        let s = &mut expected.solve;
        (s.omega, s.tolerance, s.absolute_tolerance) = (1.5, 1e-8, true);
        (s.max_iterations, s.threads, s.accel, s.escalate) = (50, 2, Accel::Amg, false);
        let r = &mut expected.robust;
        (r.layer, r.substeps, r.stiffening, r.blend) = (Layer::Thickness(0.1), 3, 2.0, true);
        assert_eq!(Settings::named(4, &given).unwrap(), expected);
        // A solver given means exactly that solver, as on the command line.
        let direct =
            Settings::named(1, &[("method", "ball-vertex"), ("solver", "direct")]).unwrap();
        assert_eq!(
            (direct.solve.solver, direct.solve.escalate),
            (Solver::Direct, false)
        );
        assert!(
            Settings::named(1, &[("tolerance", "1e-3")])
                .unwrap()
                .solve
                .escalate
        );
    }

    #[test]
    fn wrong_names_and_values_are_named() {
        let cases = [
            (
                "omegga",
                "1.5",
                "unknown setting 'omegga' (expected method, solver, accel, \
              reference, predictor, tolerance, absolute_tolerance, max_iterations, omega, \
              threads, rigid_layer, substeps, stiffening or blend)",
            ),
            (
                "method",
                "fast",
                "unknown method 'fast' (expected robust, verbss, ball-vertex, \
              spring or laplacian)",
            ),
            ("omega", "fast", "omega must be a number (got 'fast')"),
            ("omega", "2.5", "omega 2.5 is outside (0, 2)"),
            ("threads", "-1", "threads must be zero or positive (got -1)"),
            (
                "threads",
                "1.5",
                "threads must be a whole number (got '1.5')",
            ),
            (
                "substeps",
                "99999999999",
                "substeps is too large (got 99999999999)",
            ),
            ("substeps", "40", "substeps must be at most 30 (got 40)"),
            (
                "max_iterations",
                "0",
                "max_iterations is 0 (expected at least 1 sweep)",
            ),
            ("blend", "yes", "blend must be on or off (got 'yes')"),
            (
                "rigid_layer",
                "-1",
                "the rigid layer must be off, auto or a positive wall \
              distance (got '-1')",
            ),
        ];
        for (name, value, message) in cases {
            let e = Settings::check(name, value).unwrap_err().to_string();
            assert_eq!(e, format!("invalid setting: {message}"), "{name} = {value}");
        }
        let e = Settings::named(1, &[("accel", "amg"), ("method", "ball-vertex")]).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("invalid setting: accel amg solves"),
            "{e}"
        );
    }

    #[test]
    fn a_slide_normal_has_the_mesh_dimension() {
        let own = Attachment::slide("sym", None, 3).unwrap();
        assert_eq!(own.motion, Motion::Slide { normal: None });
        let given = Attachment::slide("sym", Some(&[0.0, 2.0]), 2).unwrap();
        assert_eq!(given.groups, ["sym"]);
        assert_eq!(
            given.motion,
            Motion::Slide {
                normal: Some([0.0, 2.0, 0.0])
            }
        );
        let e = Attachment::slide("sym", Some(&[0.0, 0.0, 1.0]), 2).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid setting: the slide normal of group 'sym' has z = 1 on a 2D mesh: give \
             NX,NY (or NX,NY,0)"
        );
        let flat = Attachment::slide("sym", Some(&[0.0, 1.0, 0.0]), 2).unwrap();
        assert_eq!(
            flat.motion,
            Motion::Slide {
                normal: Some([0.0, 1.0, 0.0])
            }
        );
        let e = Attachment::slide("sym", Some(&[1.0, 0.0, 1.0, 0.0]), 3).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid setting: the slide normal of group 'sym' has 4 numbers, expected 3 \
             (the mesh's dimension)"
        );
        let e = Attachment::slide("sym", Some(&[0.0, 0.0]), 2).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid setting: the slide normal of group 'sym' must be a finite non-zero \
             vector (got [0.0, 0.0])"
        );
    }
}
