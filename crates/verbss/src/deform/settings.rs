//! The settings of a run, their names and presets (docs/case-file.md lists
//! every key): one vocabulary for the command line, case files, Python and
//! C, which map nothing themselves.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::motion::Motion;
use crate::names::named;
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
    /// mesh (the default of [`Preset::Robust`]; the command line and case
    /// files take [`Reference::for_motions`]).
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
    /// VerBSS with the near-wall treatments ([`Robust::recommended`]) and
    /// the escalating solve: the product's default.
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
#[derive(Debug, Clone, PartialEq)]
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
}
