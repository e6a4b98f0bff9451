//! The one table of settings ([`TABLE`]): per setting its name, its values
//! and their range, its default, its value under each preset that differs
//! and its help. Everything that names a setting reads it from here: the
//! command line's options (`--NAME`, `_` spelt `-`), the case file's
//! `[solver]` keys, Python's keywords, C's names, `report.json`'s
//! `settings` and the docs' table ([`markdown_table`]).

use super::{Predictor, Preset, Reference, Settings};
use crate::error::{format_number, Error, Result};
use crate::names::one_of;
use crate::near_wall::Layer;
use crate::solve::{Accel, Method, Solver};

/// One setting (see the module documentation).
pub struct Setting {
    /// Its name: the case file's key, Python's keyword, C's name, the
    /// report's key; the command line's option is `--NAME` with `-` for `_`.
    pub name: &'static str,
    /// The values it takes.
    pub values: Values,
    /// Its value when no preset says otherwise.
    pub default: &'static str,
    /// Its value under the presets that differ from the default.
    pub presets: &'static [(Preset, &'static str)],
    /// What it does (one sentence or two, for `--help` and the docs).
    pub help: &'static str,
    /// Puts a checked value into the settings.
    put: fn(&mut Settings, &Value) -> Result<()>,
    /// Takes the value out of the settings.
    take: fn(&Settings) -> Value,
}

/// The values a [`Setting`] takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Values {
    /// One of these names.
    Names(&'static [&'static str]),
    /// A finite number from `low` to `high`, the ends excluded where `open`.
    Number {
        /// The lowest value.
        low: f64,
        /// The highest value (`f64::INFINITY`: no bound).
        high: f64,
        /// Whether `low` itself is excluded.
        open_low: bool,
        /// Whether `high` itself is excluded.
        open_high: bool,
    },
    /// A whole number from `low` to `high`.
    Count {
        /// The lowest value.
        low: u64,
        /// The highest value.
        high: u64,
    },
    /// `on` or `off` (`true` or `false` in a case file).
    Switch,
    /// `off`, `auto` or a positive wall distance.
    Layer,
}

/// A setting's value, as a case file and `report.json` write it.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A name (`"robust"`, `"auto"`).
    Name(String),
    /// A number.
    Number(f64),
    /// A whole number.
    Count(u64),
    /// On or off.
    Switch(bool),
}

impl Value {
    /// The value as the command line spells it.
    pub fn text(&self) -> String {
        match self {
            Value::Name(s) => s.clone(),
            Value::Number(x) => x.to_string(),
            Value::Count(k) => k.to_string(),
            Value::Switch(b) => (if *b { "on" } else { "off" }).into(),
        }
    }

    /// The value as a JSON value (a TOML value alike).
    pub fn json(&self) -> serde_json::Value {
        match self {
            Value::Name(s) => s.clone().into(),
            Value::Number(x) => (*x).into(),
            Value::Count(k) => (*k).into(),
            Value::Switch(b) => (*b).into(),
        }
    }

    fn number(&self) -> f64 {
        match self {
            Value::Number(x) => *x,
            Value::Count(k) => *k as f64,
            _ => f64::NAN,
        }
    }

    fn count(&self) -> u64 {
        match self {
            Value::Count(k) => *k,
            _ => 0,
        }
    }

    fn switch(&self) -> bool {
        matches!(self, Value::Switch(true))
    }

    fn name(&self) -> &str {
        match self {
            Value::Name(s) => s,
            _ => "",
        }
    }
}

impl Values {
    /// How the values read in `--help` and the docs: `robust|verbss`, `NUMBER
    /// in (0, 2)`, `on|off`.
    pub fn describe(&self) -> String {
        match self {
            Values::Names(names) => names.join("|"),
            Values::Switch => "on|off".into(),
            Values::Layer => "off|auto|DISTANCE".into(),
            Values::Number { .. } | Values::Count { .. } => self.range(),
        }
    }

    /// The range of a number: `in (0, 2)`, `a finite number ≥ 0`, `a whole
    /// number from 0 to 30`.
    fn range(&self) -> String {
        match *self {
            Values::Number {
                low,
                high,
                open_low,
                open_high,
            } if high.is_finite() => format!(
                "a number in {}{}, {}{}",
                if open_low { "(" } else { "[" },
                format_number(low),
                format_number(high),
                if open_high { ")" } else { "]" }
            ),
            Values::Number { low, open_low, .. } => format!(
                "a finite number {} {}",
                if open_low { ">" } else { "≥" },
                format_number(low)
            ),
            Values::Count { low, high } if high == u64::MAX => format!("a whole number ≥ {low}"),
            Values::Count { low, high } => format!("a whole number from {low} to {high}"),
            _ => self.describe(),
        }
    }

    /// The value of `text`, checked against these values; the error names
    /// the setting `name` and what it takes.
    pub fn parse(&self, name: &str, text: &str) -> Result<Value> {
        let wrong = || {
            Error::InvalidSetting(format!(
                "{name} must be {} (got '{}')",
                self.expected(),
                crate::io::shown(text)
            ))
        };
        let value = match self {
            Values::Names(_) => Value::Name(text.to_string()),
            Values::Switch => match text {
                "on" => Value::Switch(true),
                "off" => Value::Switch(false),
                _ => return Err(wrong()),
            },
            Values::Layer => match text {
                "off" | "auto" => Value::Name(text.to_string()),
                _ => Value::Number(text.parse().map_err(|_| wrong())?),
            },
            Values::Number { .. } => Value::Number(text.parse().map_err(|_| wrong())?),
            Values::Count { .. } => match text.parse::<u64>() {
                Ok(k) => Value::Count(k),
                // A whole number out of range is said as out of range.
                Err(_) if text.parse::<i128>().is_ok() => {
                    return Err(Error::InvalidSetting(format!(
                        "{name} must be {} (got {text})",
                        self.range()
                    )))
                }
                Err(_) => return Err(wrong()),
            },
        };
        self.check(name, &value)?;
        Ok(value)
    }

    /// What a wrong spelling is told it should be.
    fn expected(&self) -> String {
        match self {
            Values::Names(names) => one_of(names),
            Values::Switch => "on or off".into(),
            Values::Layer => "off, auto or a positive wall distance".into(),
            Values::Number { .. } | Values::Count { .. } => self.range(),
        }
    }

    /// Checks that `value` is in the range of these values; the error names
    /// the setting `name`, the range and the value.
    pub fn check(&self, name: &str, value: &Value) -> Result<()> {
        let inside = match (*self, value) {
            (
                Values::Number {
                    low,
                    high,
                    open_low,
                    open_high,
                },
                Value::Number(x),
            ) => {
                x.is_finite()
                    && (*x > low || (!open_low && *x == low))
                    && (*x < high || (!open_high && *x == high))
            }
            (Values::Count { low, high }, Value::Count(k)) => (low..=high).contains(k),
            (Values::Layer, Value::Number(t)) => *t > 0.0 && t.is_finite(),
            _ => true,
        };
        if inside {
            return Ok(());
        }
        let got = match value {
            Value::Number(x) => format_number(*x),
            other => other.text(),
        };
        Err(Error::InvalidSetting(format!(
            "{name} must be {} (got {got})",
            self.expected()
        )))
    }
}

impl Setting {
    /// The setting called `name`; the error lists every name.
    pub fn named(name: &str) -> Result<&'static Setting> {
        TABLE.iter().find(|s| s.name == name).ok_or_else(|| {
            let names: Vec<&str> = TABLE.iter().map(|s| s.name).collect();
            Error::InvalidSetting(format!(
                "unknown setting '{}' (expected {})",
                crate::io::shown(name),
                one_of(&names)
            ))
        })
    }

    /// The option of the command line: `--rigid-layer` for `rigid_layer`.
    pub fn flag(&self) -> String {
        self.name.replace('_', "-")
    }

    /// Its value (text) under `preset` (`method`'s is the preset's name).
    pub fn value_in(&self, preset: Preset) -> &'static str {
        if self.name == "method" {
            return preset.name();
        }
        self.presets
            .iter()
            .find(|(p, _)| *p == preset)
            .map_or(self.default, |(_, v)| v)
    }

    /// Its default as `--help` says it: `6 for robust, 0 otherwise`.
    pub fn defaults(&self) -> String {
        let mut parts: Vec<String> = self
            .presets
            .iter()
            .map(|(p, v)| format!("{v} for {p}"))
            .collect();
        if parts.is_empty() {
            return self.default.to_string();
        }
        parts.push(format!("{} otherwise", self.default));
        parts.join(", ")
    }

    /// Sets it in `settings` from its text.
    pub fn set_text(&self, settings: &mut Settings, text: &str) -> Result<()> {
        let value = self.values.parse(self.name, text)?;
        (self.put)(settings, &value)
    }

    /// Its value in `settings`.
    pub fn get(&self, settings: &Settings) -> Value {
        (self.take)(settings)
    }

    /// Checks its value in `settings` against its range.
    pub fn check(&self, settings: &Settings) -> Result<()> {
        self.values.check(self.name, &self.get(settings))
    }
}

/// Checks the value `value` of the setting `name` against its range in
/// [`TABLE`] (for the settings' parts checked on their own).
pub(crate) fn check_value(name: &str, value: Value) -> Result<()> {
    Setting::named(name)?.values.check(name, &value)
}

fn name_of<T: std::fmt::Display>(t: T) -> Value {
    Value::Name(t.to_string())
}

/// Every setting (see the module documentation).
pub static TABLE: &[Setting] = &[
    Setting {
        name: "method",
        values: Values::Names(Preset::NAMES),
        default: "robust",
        presets: &[],
        help: "The spring system and its strategy, a preset of the settings below: robust is \
               VerBSS with the near-wall treatments (rigid layer, stiffening, sub-steps, blended \
               rigid motion); verbss is the paper's method exactly; ball-vertex the same springs \
               solved as one global system; spring edge springs only; laplacian the \
               component-wise Laplacian.",
        put: |s, v| {
            s.solve.method = match v.name().parse()? {
                Preset::Robust | Preset::Verbss => Method::Verbss,
                Preset::BallVertex => Method::BallVertex,
                Preset::Spring => Method::Spring,
                Preset::Laplacian => Method::Laplacian,
            };
            Ok(())
        },
        take: |s| name_of(s.preset()),
    },
    Setting {
        name: "reference",
        values: Values::Names(Reference::NAMES),
        default: "updated",
        presets: &[(Preset::Robust, "auto")],
        help: "What the springs are built on: the current mesh, solving for the increment \
               (updated); the input mesh, solving for the total displacement (fixed, also spelt \
               initial); the input mesh moved by the blended rigid motion (anchored: a periodic \
               motion returns to the input mesh); auto: anchored when every moving motion is \
               periodic, updated otherwise.",
        put: |s, v| {
            s.reference = v.name().parse()?;
            Ok(())
        },
        take: |s| name_of(s.reference),
    },
    Setting {
        name: "predictor",
        values: Values::Names(Predictor::NAMES),
        default: "previous",
        presets: &[],
        help: "Each step's initial guess: the previous step's solution, or extrapolated \
               linearly from the two previous steps (fewer sweeps for smooth motions).",
        put: |s, v| {
            s.predictor = v.name().parse()?;
            Ok(())
        },
        take: |s| name_of(s.predictor),
    },
    Setting {
        name: "rigid_layer",
        values: Values::Layer,
        default: "off",
        presets: &[(Preset::Robust, "auto")],
        help: "Nodes this close to a moving wall move with it: off, auto (the boundary layer, at \
               least 5% of the body's size) or a wall distance.",
        put: |s, v| {
            s.robust.layer = match v {
                Value::Number(t) => Layer::Thickness(*t),
                other => other.name().parse()?,
            };
            Ok(())
        },
        take: |s| match s.robust.layer {
            Layer::Off => Value::Name("off".into()),
            Layer::Auto => Value::Name("auto".into()),
            Layer::Thickness(t) => Value::Number(t),
        },
    },
    Setting {
        name: "stiffening",
        values: Values::Number {
            low: 0.0,
            high: f64::INFINITY,
            open_low: false,
            open_high: true,
        },
        default: "0",
        presets: &[(Preset::Robust, "1")],
        help: "Springs at wall distance d are scaled by (t/max(d,t))^P, t the rigid layer's \
               thickness; 0: off.",
        put: |s, v| {
            s.robust.stiffening = v.number();
            Ok(())
        },
        take: |s| Value::Number(s.robust.stiffening),
    },
    Setting {
        name: "substeps",
        values: Values::Count { low: 0, high: 30 },
        default: "0",
        presets: &[(Preset::Robust, "6")],
        help: "A step that inverts a cell is redone in smaller increments, down to 1/2^K of the \
               step; 0: off.",
        put: |s, v| {
            s.robust.substeps = v.count() as u32;
            Ok(())
        },
        take: |s| Value::Count(u64::from(s.robust.substeps)),
    },
    Setting {
        name: "blend",
        values: Values::Switch,
        default: "off",
        presets: &[(Preset::Robust, "on")],
        help: "Each body's fitted rigid motion carried into the mesh with smooth weights before \
               the springs solve what is left (docs/method.md, \"Blended rigid motion\").",
        put: |s, v| {
            s.robust.blend = v.switch();
            Ok(())
        },
        take: |s| Value::Switch(s.robust.blend),
    },
    Setting {
        name: "relocate",
        values: Values::Switch,
        default: "off",
        presets: &[(Preset::Robust, "on")],
        help: "After the springs, the free and sliding nodes of every cell below half its input \
               quality are moved to raise their cells' least quality ratio (docs/method.md, \
               \"Relocation of the worst cells' nodes\").",
        put: |s, v| {
            s.robust.relocate = v.switch();
            Ok(())
        },
        take: |s| Value::Switch(s.robust.relocate),
    },
    Setting {
        name: "solver",
        values: Values::Names(Solver::NAMES),
        default: "sor",
        presets: &[],
        help: "The global solver of method ball-vertex. Given, it is the only solver used \
               (escalate off unless given).",
        put: |s, v| {
            s.solve.solver = v.name().parse()?;
            Ok(())
        },
        take: |s| name_of(s.solve.solver),
    },
    Setting {
        name: "accel",
        values: Values::Names(Accel::NAMES),
        default: "none",
        presets: &[(Preset::Robust, "auto")],
        help: "Plain VerBSS sweeps (none), the multigrid-accelerated solve (amg), or sweeps that \
               hand a step they have not finished in 200 sweeps to the multigrid, which then \
               solves every later step (auto; meshes of mostly triangles or tetrahedra). Given, \
               it is the only solver used (escalate off unless given).",
        put: |s, v| {
            s.solve.accel = v.name().parse()?;
            Ok(())
        },
        take: |s| name_of(s.solve.accel),
    },
    Setting {
        name: "escalate",
        values: Values::Switch,
        default: "on",
        presets: &[],
        help: "Watch each solve and escalate when it stalls, grows or leaves a node's estimated \
               error above 1% of its cell height (sweeps, GMRES, multigrid, direct solve); off: \
               the configured solver alone, stopped by the eq.-8 test.",
        put: |s, v| {
            s.solve.escalate = v.switch();
            Ok(())
        },
        take: |s| Value::Switch(s.solve.escalate),
    },
    Setting {
        name: "omega",
        values: Values::Number {
            low: 0.0,
            high: 2.0,
            open_low: true,
            open_high: true,
        },
        default: "1.6",
        presets: &[],
        help: "The over-relaxation factor of the sweeps. Given, it is the only solver used \
               (escalate off unless given).",
        put: |s, v| {
            s.solve.omega = v.number();
            Ok(())
        },
        take: |s| Value::Number(s.solve.omega),
    },
    Setting {
        name: "tolerance",
        values: Values::Number {
            low: 0.0,
            high: f64::INFINITY,
            open_low: false,
            open_high: true,
        },
        default: "1e-6",
        presets: &[],
        help: "The eq.-8 stop, relative to the step's largest prescribed displacement.",
        put: |s, v| {
            s.solve.tolerance = v.number();
            Ok(())
        },
        take: |s| Value::Number(s.solve.tolerance),
    },
    Setting {
        name: "absolute_tolerance",
        values: Values::Switch,
        default: "off",
        presets: &[],
        help: "Take the tolerance as the paper's absolute eq.-8 threshold.",
        put: |s, v| {
            s.solve.absolute_tolerance = v.switch();
            Ok(())
        },
        take: |s| Value::Switch(s.solve.absolute_tolerance),
    },
    Setting {
        name: "max_iterations",
        values: Values::Count {
            low: 1,
            high: u64::MAX,
        },
        default: "2000",
        presets: &[],
        help: "The most sweeps of a solve.",
        put: |s, v| {
            s.solve.max_iterations = usize::try_from(v.count()).unwrap_or(usize::MAX);
            Ok(())
        },
        take: |s| Value::Count(s.solve.max_iterations as u64),
    },
    Setting {
        name: "threads",
        values: Values::Count { low: 0, high: 4096 },
        default: "0",
        presets: &[],
        help: "Worker threads, 0 for one per core (the results do not depend on it).",
        put: |s, v| {
            s.solve.threads = v.count() as usize;
            Ok(())
        },
        take: |s| Value::Count(s.solve.threads as u64),
    },
];

/// The docs' table of [`TABLE`] (Markdown): name, values, default (and the
/// presets' values), what it does.
pub fn markdown_table() -> String {
    let mut out =
        String::from("| setting | values | default | what it does |\n|---|---|---|---|\n");
    for s in TABLE {
        out.push_str(&format!(
            "| `{}` | {} | {} | {} |\n",
            s.name,
            s.values.describe().replace('|', "\\|"),
            s.defaults(),
            s.help
        ));
    }
    out
}
