//! The times of an OpenFOAM case and the names of its time directories.
//!
//! Step `n` of a run is at time `t = startTime + n·deltaT` (the case's
//! `system/controlDict`, or the values the user gives), and its directory
//! is named as OpenFOAM names times: `t` written at `timePrecision`
//! significant digits (default 6) in `timeFormat` (default `general`, as
//! C's `%g`: `5e-06`, `0.001`, `2.5`; `fixed` as `%f`, `scientific` as
//! `%e`, both with `timePrecision` digits after the point).

use std::path::{Path, PathBuf};

use super::file::header;
use super::lex::Lexer;
use crate::error::{Error, Result};
use crate::io::shown;

/// How the times of a case are written (`timeFormat`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeFormat {
    /// `general`: fixed or scientific, whichever is shorter, without
    /// trailing zeros (C's `%g`).
    General,
    /// `fixed`: `timePrecision` digits after the point.
    Fixed,
    /// `scientific`: one digit, the point, `timePrecision` digits and the
    /// exponent.
    Scientific,
}

/// The times of a run's steps in a case.
#[derive(Debug, Clone, PartialEq)]
pub struct Times {
    /// The time of step 0 (`startTime`).
    pub start: f64,
    /// The time of one step (`deltaT`).
    pub delta: f64,
    /// `timeFormat`.
    pub format: TimeFormat,
    /// `timePrecision`: significant digits (`general`) or digits after the
    /// point (`fixed`, `scientific`).
    pub precision: usize,
}

/// The most digits a time is written with (an `f64` has 17).
const MAX_PRECISION: usize = 17;

impl Times {
    /// Reads `startTime`, `deltaT`, `timeFormat` and `timePrecision` from
    /// the `system/controlDict` of `case` (a case directory); a value
    /// given (`start`, `delta`) replaces the dictionary's, and the file is
    /// needed only for the values not given.
    pub fn of_case(case: &Path, start: Option<f64>, delta: Option<f64>) -> Result<Times> {
        let path = case.join("system").join("controlDict");
        let entries = if path.is_file() || start.is_none() || delta.is_none() {
            read_control(&path, start.is_none(), delta.is_none())?
        } else {
            Control::default()
        };
        let missing = |entry: &str| Error::Parse {
            path: path.clone(),
            line: 1,
            message: format!(
                "no {entry} entry (verbss names the time directories it writes \
                 startTime + step·deltaT; `verbss deform` takes --start-time and --dt \
                 instead)"
            ),
        };
        let times = Times {
            start: match start.or(entries.start) {
                Some(t) => t,
                None => return Err(missing("startTime")),
            },
            delta: match delta.or(entries.delta) {
                Some(d) => d,
                None => return Err(missing("deltaT")),
            },
            format: entries.format.unwrap_or(TimeFormat::General),
            precision: entries.precision.unwrap_or(6),
        };
        if !(times.delta > 0.0 && times.delta.is_finite()) {
            let given = delta.is_some();
            return Err(Error::InvalidSetting(format!(
                "{}: the time step must be a positive number (got {})",
                if given {
                    "--dt".to_string()
                } else {
                    format!("{} deltaT", path.display())
                },
                crate::error::format_number(times.delta)
            )));
        }
        Ok(times)
    }

    /// The time of step `n`.
    pub fn time(&self, n: usize) -> f64 {
        self.start + n as f64 * self.delta
    }

    /// The directory name of step `n`.
    pub fn name(&self, n: usize) -> String {
        time_name(self.time(n), self.format, self.precision)
    }

    /// Fails unless steps `0..=steps` all have names of their own (a time
    /// step too small for `timePrecision` gives two steps one name).
    pub fn check_distinct(&self, steps: usize) -> Result<()> {
        let mut last = self.name(0);
        for n in 1..=steps {
            let name = self.name(n);
            if name == last {
                return Err(Error::InvalidSetting(format!(
                    "steps {} and {n} are both at time {name} at timePrecision {} (deltaT {:e} \
                     from startTime {:e}): raise timePrecision in system/controlDict",
                    n - 1,
                    self.precision,
                    self.delta,
                    self.start
                )));
            }
            last = name;
        }
        Ok(())
    }
}

/// `t` as OpenFOAM names a time (the module's doc says how).
pub fn time_name(t: f64, format: TimeFormat, precision: usize) -> String {
    let p = precision.min(MAX_PRECISION);
    match format {
        TimeFormat::Fixed => format!("{t:.p$}"),
        TimeFormat::Scientific => {
            let text = format!("{t:.p$e}");
            let (mantissa, exponent) = split_exp(&text);
            format!("{mantissa}{}", c_exponent(exponent))
        }
        TimeFormat::General => {
            if t == 0.0 {
                return "0".into();
            }
            let p = p.max(1);
            // The exponent after rounding to p significant digits.
            let text = format!("{:.*e}", p - 1, t);
            let (mantissa, exponent) = split_exp(&text);
            if exponent < -4 || exponent >= p as i32 {
                format!("{}{}", trim_zeros(mantissa), c_exponent(exponent))
            } else {
                let decimals = (p as i32 - 1 - exponent) as usize;
                trim_zeros(&format!("{t:.decimals$}")).to_string()
            }
        }
    }
}

/// Rust's `1.5e-6` as its mantissa `1.5` and exponent `-6`.
fn split_exp(s: &str) -> (&str, i32) {
    let (mantissa, exponent) = s.split_once('e').unwrap_or((s, "0"));
    (mantissa, exponent.parse().unwrap_or(0))
}

/// An exponent as C writes it: a sign and at least two digits (`e-06`).
fn c_exponent(e: i32) -> String {
    format!("e{}{:02}", if e < 0 { '-' } else { '+' }, e.unsigned_abs())
}

/// A decimal number without the trailing zeros of its fraction (nor a
/// trailing point).
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// The entries of a controlDict that name times.
#[derive(Default)]
struct Control {
    start: Option<f64>,
    delta: Option<f64>,
    format: Option<TimeFormat>,
    precision: Option<usize>,
}

/// Reads the top-level `timeFormat` and `timePrecision` of the
/// controlDict at `path`, and its `startTime` and `deltaT` when `start` and
/// `delta`; other entries (and `#` directives, to the end of their line)
/// are skipped.
fn read_control(path: &Path, start: bool, delta: bool) -> Result<Control> {
    crate::io::regular_input(path)?;
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: PathBuf::from(path),
        source,
    })?;
    let mut lx = Lexer::new(&bytes, path);
    header(&mut lx)?;
    let mut control = Control::default();
    while let Some(key) = lx.next()? {
        if key.text.starts_with('#') {
            while lx.peek()?.is_some_and(|t| t.line == key.line) {
                lx.next()?;
            }
            continue;
        }
        match key.text {
            "startTime" if start => control.start = Some(lx.scalar("startTime")?),
            "deltaT" if delta => control.delta = Some(lx.scalar("deltaT")?),
            "timePrecision" => {
                let (p, line) = lx.label("timePrecision (a count of digits)")?;
                if p > MAX_PRECISION {
                    return Err(lx.err(
                        line,
                        format!(
                            "timePrecision {p} is more than the {MAX_PRECISION} digits of a number"
                        ),
                    ));
                }
                control.precision = Some(p);
            }
            "timeFormat" => {
                let t = lx.expect_any("the timeFormat")?;
                control.format = Some(match t.text {
                    "general" => TimeFormat::General,
                    "fixed" => TimeFormat::Fixed,
                    "scientific" => TimeFormat::Scientific,
                    other => {
                        return Err(lx.err(
                            t.line,
                            format!(
                                "timeFormat '{}' (expected general, fixed or scientific)",
                                shown(other)
                            ),
                        ))
                    }
                });
            }
            _ => {
                lx.skip_value(key.text, key.line)?;
                continue;
            }
        }
        lx.expect(";", &format!("after {}", key.text))?;
    }
    Ok(control)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_are_named_as_openfoam_names_them() {
        let g = |t| time_name(t, TimeFormat::General, 6);
        assert_eq!(g(5e-6), "5e-06");
        assert_eq!(g(0.001), "0.001");
        assert_eq!(g(0.0001), "0.0001");
        assert_eq!(g(1e-5), "1e-05");
        assert_eq!(g(0.0), "0");
        assert_eq!(g(4.0), "4");
        assert_eq!(g(2.5), "2.5");
        assert_eq!(g(100000.0), "100000");
        assert_eq!(g(1e6), "1e+06");
        assert_eq!(g(0.1 + 0.2), "0.3");
        assert_eq!(g(3.0 * 5e-6), "1.5e-05");
        assert_eq!(g(1.0000004), "1");
        assert_eq!(g(123456.7), "123457");
        assert_eq!(time_name(0.001, TimeFormat::Fixed, 6), "0.001000");
        assert_eq!(time_name(5e-6, TimeFormat::Scientific, 3), "5.000e-06");
        assert_eq!(time_name(1.5e-5, TimeFormat::General, 1), "2e-05");
    }

    #[test]
    fn a_control_dict_gives_the_times_and_a_too_short_precision_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("system")).unwrap();
        let control = dir.path().join("system/controlDict");
        std::fs::write(
            &control,
            "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n\
             #include \"$FOAM_CASE/system/extra\"\napplication pimpleFoam;\nstartTime 0;\n\
             functions { #include \"cuttingPlane\" probes { type probes; fields (p U); } }\n\
             deltaT 5e-06;\ntimeFormat general;\n",
        )
        .unwrap();
        let times = Times::of_case(dir.path(), None, None).unwrap();
        assert_eq!((times.start, times.delta, times.precision), (0.0, 5e-6, 6));
        assert_eq!(
            (1..=3).map(|n| times.name(n)).collect::<Vec<_>>(),
            ["5e-06", "1e-05", "1.5e-05"]
        );
        let given = Times::of_case(dir.path(), Some(1.0), Some(0.25)).unwrap();
        assert_eq!(given.name(2), "1.5");
        let long = Times::of_case(dir.path(), Some(1.0), Some(1e-7)).unwrap();
        let e = long.check_distinct(10).unwrap_err().to_string();
        assert!(e.contains("steps 0 and 1 are both at time 1"), "{e}");
        assert!(times.check_distinct(1000).is_ok());
        std::fs::write(&control, "startTime 0;\ndeltaT $dt;\n").unwrap();
        let e = Times::of_case(dir.path(), None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("controlDict:2: expected deltaT"), "{e}");
        assert!(Times::of_case(dir.path(), None, Some(0.5)).is_ok());
        std::fs::write(&control, "startTime 0;\ntimeFormat hex;\n").unwrap();
        let e = Times::of_case(dir.path(), None, Some(1.0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("timeFormat 'hex'"), "{e}");
        std::fs::remove_file(&control).unwrap();
        assert!(Times::of_case(dir.path(), None, Some(1.0)).is_err());
        assert_eq!(
            Times::of_case(dir.path(), Some(0.0), Some(1.0))
                .unwrap()
                .name(3),
            "3"
        );
    }
}
