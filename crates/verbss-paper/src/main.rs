//! `verbss-paper`: runs the VerBSS paper's cases with every method and
//! writes `results.json` and `PAPER.md`, the paper's tables with its numbers
//! beside ours, and before/after pictures.
//!
//! ```sh
//! cargo run --release -p verbss-paper -- [--case NAME]… [--out DIR]
//! ```

mod cases;
mod markdown;
mod measure;
mod meshgen;
mod paper;
mod pictures;
mod results;

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use anyhow::{bail, Context};
use clap::Parser;
use serde::Serialize;

use cases::{PaperCase, CASES};
use results::CaseResult;

/// Runs the VerBSS paper's cases and writes its tables beside ours.
#[derive(Parser)]
#[command(name = "verbss-paper", version)]
struct Args {
    /// Run only this case (repeatable): rectangle-298, rectangle-1035,
    /// rectangle-3055, rectangle-8081, rectangle-21376, naca0012,
    /// three-element, sphere-cube, two-fish, bending-wing [default: all].
    #[arg(long = "case")]
    cases: Vec<String>,
    /// Output folder: results.json, PAPER.md and the pictures.
    #[arg(long, default_value = "out/paper")]
    out: PathBuf,
    /// The folder of the case files and `meshes/`.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/../../cases"))]
    cases_dir: PathBuf,
}

/// The machine a run was made on.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Machine {
    /// `uname -a`.
    pub uname: String,
    /// `lscpu`'s model name, CPU count and threads per core.
    pub cpu: String,
    /// `lscpu`, whole.
    pub lscpu: String,
    /// The load average (1, 5, 15 minutes, `/proc/loadavg`) when the run started.
    pub load_at_start: String,
    /// The load average when it ended.
    pub load_at_end: String,
}

/// Everything a run found (`results.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Results {
    /// When the run started (UTC, `date -u`).
    pub date: String,
    /// The command that reproduces it.
    pub command: String,
    /// Where it ran.
    pub machine: Machine,
    /// Wall seconds of the whole run.
    pub seconds: f64,
    /// One record per case.
    pub cases: Vec<CaseResult>,
}

/// The output of `program args…`, trimmed, or `unknown`.
fn shell(program: &str, args: &[&str]) -> String {
    Command::new(program)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into())
}

fn machine() -> Machine {
    let lscpu = shell("lscpu", &[]);
    let field = |key: &str| {
        lscpu
            .lines()
            .find_map(|l| l.strip_prefix(key))
            .map(|v| v.trim_start_matches(':').trim().to_string())
            .unwrap_or_else(|| "?".into())
    };
    Machine {
        uname: shell("uname", &["-a"]),
        cpu: format!(
            "{}, {} CPU(s), {} thread(s) per core",
            field("Model name"),
            field("CPU(s)"),
            field("Thread(s) per core")
        ),
        lscpu,
        load_at_start: load_average(),
        load_at_end: String::new(),
    }
}

/// The first three fields of `/proc/loadavg`, or `unknown`.
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
}

fn main() -> anyhow::Result<()> {
    let args = Args::parse();
    let selected: Vec<&PaperCase> = if args.cases.is_empty() {
        CASES.iter().collect()
    } else {
        args.cases
            .iter()
            .map(|name| {
                PaperCase::find(name).with_context(|| {
                    let names: Vec<&str> = CASES.iter().map(|c| c.name).collect();
                    format!("unknown case '{name}' (one of: {})", names.join(", "))
                })
            })
            .collect::<anyhow::Result<_>>()?
    };
    if !args.cases_dir.is_dir() {
        bail!(
            "the cases folder {} does not exist (--cases-dir)",
            args.cases_dir.display()
        );
    }
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let start = Instant::now();
    let mut command = "cargo run --release -p verbss-paper --".to_string();
    for c in &args.cases {
        command.push_str(&format!(" --case {c}"));
    }
    command.push_str(&format!(" --out {}", args.out.display()));
    let mut results = Results {
        date: shell("date", &["-u", "+%Y-%m-%d %H:%M UTC"]),
        command,
        machine: machine(),
        seconds: 0.0,
        cases: Vec::new(),
    };
    for case in selected {
        results
            .cases
            .push(results::run_case(case, &args.cases_dir, &args.out)?);
        results.seconds = start.elapsed().as_secs_f64();
        results.machine.load_at_end = load_average();
        write(&args.out, &results)?;
    }
    eprintln!(
        "{} and PAPER.md written in {:.0} s",
        args.out.join("results.json").display(),
        results.seconds
    );
    Ok(())
}

/// Writes `results.json` and `PAPER.md` (after every case, so a long run
/// leaves its finished cases behind).
fn write(out: &std::path::Path, results: &Results) -> anyhow::Result<()> {
    let json = serde_json::to_string_pretty(results)?;
    std::fs::write(out.join("results.json"), json + "\n")?;
    std::fs::write(out.join("PAPER.md"), markdown::render(results))?;
    Ok(())
}
