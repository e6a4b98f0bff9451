//! The settings of a run, declared once in [`TABLE`] (docs/case-file.md
//! shows it): the command line's options, the case file's `[solver]` keys,
//! Python's keywords, C's names and `report.json`'s `settings` all come from
//! that table, which maps each name to its field here.

use crate::error::{Error, Result};
use crate::motion::{Attachment, Motion};
use crate::names::named;
use crate::near_wall::Robust;
use crate::solve::SolveParams;

mod table;
#[cfg(test)]
mod tests;

pub(crate) use self::table::check_value;
pub use self::table::{markdown_table, Setting, Value, Values, TABLE};

/// Which configuration the springs are built on and what the unknown is
/// (the paper's options 1 and 2, and a third that returns exactly:
/// docs/method.md, "Time stepping").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reference {
    /// Chosen by the motions when the deformer is made
    /// ([`Reference::resolved`]): anchored when every moving motion is
    /// periodic, updated otherwise (the robust method's default).
    Auto,
    /// Option 1: springs on the current coordinates, solve for the increment.
    #[default]
    Updated,
    /// Option 2: springs on the input mesh, solve for the total displacement
    /// (also spelled `initial`).
    Fixed,
    /// Springs on the input mesh moved by the blended rigid motion to the
    /// step's boundary position, solve for the rest of the total
    /// displacement from the input mesh: the mesh is a function of the
    /// boundary's position, so a periodic motion comes back to the input
    /// mesh.
    Anchored,
}

impl Reference {
    /// What [`Reference::Auto`] is for a run of `motions`: anchored when
    /// every moving motion is periodic (pitch–plunge, undulation) and the
    /// mesh must come back with the boundary, updated for the one-way
    /// motions (a rotation, translation, bending or given positions), whose
    /// springs on the current mesh carry a gap that closes further
    /// (docs/method.md, "Time stepping"). Any other reference is itself.
    pub fn resolved<'a>(self, motions: impl IntoIterator<Item = &'a Motion>) -> Reference {
        if self != Reference::Auto {
            return self;
        }
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
    Auto => "auto",
    Updated => "updated",
    Fixed => "fixed",
    Anchored => "anchored",
], ["initial" => Fixed]);

/// How a step's initial guess is made from the steps before it. The guess
/// only decides where the sweeps start, not the system they solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
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
/// command line, in case files, Python and C. Each setting's value under
/// each preset is in [`TABLE`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
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
    /// The settings of `steps` steps with this preset: every setting of
    /// [`TABLE`] at this preset's value.
    pub fn settings(self, steps: usize) -> Settings {
        let mut s = Settings {
            steps,
            dt: 1.0 / steps.max(1) as f64,
            reference: Reference::Updated,
            solve: SolveParams::default(),
            robust: Robust::off(),
            predictor: Predictor::Previous,
        };
        for setting in TABLE {
            setting
                .set_text(&mut s, setting.value_in(self))
                .expect("the table's own values are valid");
        }
        s
    }
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Settings {
    /// The number of steps `N` of the run (the motions' `n/N`).
    pub steps: usize,
    /// Time per step (`t = n · dt`, used by undulation).
    pub dt: f64,
    /// The reference ([`Reference::Auto`] is chosen when the deformer is made).
    pub reference: Reference,
    /// The solver's settings for every step.
    pub solve: SolveParams,
    /// The near-wall treatments (off: the paper's method).
    pub robust: Robust,
    /// How each step's initial guess is made.
    pub predictor: Predictor,
}

/// The settings that, given, mean exactly that solver: the solve does not
/// escalate unless `escalate` is given too.
const EXACT_SOLVER: [&str; 3] = ["solver", "accel", "omega"];

impl Settings {
    /// `steps` steps with the paper's method and every other setting at its
    /// default ([`Preset::Verbss`]). The product's default is
    /// [`Settings::robust`].
    pub fn new(steps: usize) -> Settings {
        Preset::Verbss.settings(steps)
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
        use crate::solve::Method;
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
                crate::error::format_number(self.dt)
            )));
        }
        self.solve.validate()?;
        self.robust.validate()
    }

    /// The settings of `steps` steps from named values ([`TABLE`]) in any
    /// order: the preset of `method` (robust when not named), then every
    /// other value over it in the order given (a name given twice: the last
    /// wins), checked by [`Settings::validate`]. A `solver`, `accel` or
    /// `omega` given means exactly that solver: `escalate` off, unless
    /// `escalate` is given too. The one mapping of every front end.
    pub fn named<N: AsRef<str>, V: AsRef<str>>(
        steps: usize,
        values: &[(N, V)],
    ) -> Result<Settings> {
        let given = |name: &str| values.iter().any(|(n, _)| n.as_ref() == name);
        let preset = match values.iter().rev().find(|(n, _)| n.as_ref() == "method") {
            Some((_, v)) => v.as_ref().parse()?,
            None => Preset::Robust,
        };
        let mut settings = preset.settings(steps);
        if EXACT_SOLVER.iter().any(|name| given(name)) && !given("escalate") {
            settings.solve.escalate = false;
        }
        for (name, value) in values.iter().filter(|(n, _)| n.as_ref() != "method") {
            Setting::named(name.as_ref())?.set_text(&mut settings, value.as_ref())?;
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

    /// Every setting of [`TABLE`] with its value, in the table's order: what
    /// `report.json` writes as `settings` and a case file takes back as its
    /// `[solver]` table.
    pub fn values(&self) -> Vec<(&'static str, Value)> {
        TABLE.iter().map(|s| (s.name, s.get(self))).collect()
    }

    /// [`Settings::values`] as a JSON object: a case file's `[solver]` table.
    pub fn solver_table(&self) -> serde_json::Map<String, serde_json::Value> {
        self.values()
            .into_iter()
            .map(|(name, value)| (name.to_string(), value.json()))
            .collect()
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
                    crate::error::format_number(n[2])
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
                     (got {})",
                    crate::error::format_numbers(n)
                )))
            }
            // Scaled by its largest number: a normal of huge (or tiny)
            // finite numbers is still a direction.
            Some(n) => {
                let largest = n.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let v = [n[0], n[1], n.get(2).copied().unwrap_or(0.0)];
                Some(v.map(|x| x / largest))
            }
        };
        Ok(Attachment {
            groups: vec![group.to_string()],
            motion: Motion::Slide { normal },
        })
    }
}
