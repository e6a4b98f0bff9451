//! How far the default, the paper's method, the Laplacian and the exact
//! solve carry a motion before the first inverted element, and what a step
//! costs (docs/robustness.md).
//!
//! ```sh
//! cargo run --release -p verbss --example robustness -- cases/robust/*.toml
//! cargo run --release -p verbss --example robustness -- --variants default,verbss CASE.toml
//! ```
//!
//! Each case file is run once per variant — `default` (the command line's
//! defaults: `--method robust`, the reference its motions' kind implies,
//! the escalating solve), `anchored` (the default with the anchored
//! reference, the default of periodic motions), `verbss` (the paper's
//! method), `laplacian`, `exact` (the default's near-wall treatment and
//! reference, every step solved by the sparse direct solve), `springs` (the
//! near-wall treatment without the blended rigid motion), `no-layer` (the
//! default without the rigid layer), and the single treatments `layer`,
//! `stiffening`, `substeps` — with the case's steps, motions and (but for
//! `default`, `no-layer`, `anchored` and `exact`) reference, until the
//! first inverted element, an unconverged step or the last step.
//! Printed per case and variant: the steps completed and the amplitude
//! reached (for a rotation, in degrees), where the run stopped, the rigid
//! layer's nodes, sweeps and seconds per step, the cost of a step relative
//! to `verbss` over the steps both completed, the steps that escalated
//! beyond the sweeps, and the minimum quality.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use verbss::case::Case;
use verbss::deform::Deformer;
use verbss::error::Error;
use verbss::motion::Motion;
use verbss::near_wall::{Layer, Robust};
use verbss::settings::Reference;
use verbss::solve::{Method, SolveParams, Solver, Stage};

const VARIANTS: [&str; 10] = [
    "default",
    "no-layer",
    "anchored",
    "springs",
    "verbss",
    "laplacian",
    "exact",
    "layer",
    "stiffening",
    "substeps",
];

/// The near-wall treatment and the solver settings of `variant`.
fn variant(name: &str) -> (Robust, SolveParams) {
    let mut r = Robust::off();
    let mut s = SolveParams::default();
    match name {
        "default" | "anchored" => r = Robust::recommended(),
        "springs" => {
            r = Robust::recommended();
            r.blend = false;
        }
        "no-layer" => {
            r = Robust::recommended();
            r.layer = Layer::Off;
        }
        "laplacian" => s.method = Method::Laplacian,
        "exact" => {
            r = Robust::recommended();
            (s.method, s.solver) = (Method::BallVertex, Solver::Direct);
        }
        "layer" => r.layer = Layer::Auto,
        "stiffening" => r.stiffening = 1.0,
        "substeps" => r.substeps = 6,
        _ => {}
    }
    (r, s)
}

/// What one run of a case gave.
struct Outcome {
    steps: usize,
    completed: usize,
    failure: Option<String>,
    layer_nodes: usize,
    sweeps: Vec<usize>,
    seconds: Vec<f64>,
    min_quality: f64,
    /// Steps that used more than the configured sweeps.
    escalated: usize,
}

fn run(case: &Case, variant_name: &str) -> Result<Outcome, Error> {
    let mesh = verbss::io::read(&case.mesh)?;
    let attachments = case.attachments(&mesh)?;
    let mut settings = case.settings.clone();
    let threads = settings.solve.threads;
    (settings.robust, settings.solve) = variant(variant_name);
    settings.reference = match variant_name {
        "default" | "no-layer" | "exact" => Reference::Auto,
        "anchored" => Reference::Anchored,
        _ => settings.reference,
    };
    settings.solve.threads = threads;
    let mut d = Deformer::new(&mesh, &attachments, settings)?;
    let mut out = Outcome {
        steps: case.settings.steps,
        completed: 0,
        failure: None,
        layer_nodes: d.rigid_layer().0,
        sweeps: Vec::new(),
        seconds: Vec::new(),
        min_quality: d.current().report.min_quality,
        escalated: 0,
    };
    for n in 1..=case.settings.steps {
        let start = Instant::now();
        match d.step(n) {
            Ok(r) => {
                out.seconds.push(start.elapsed().as_secs_f64());
                out.sweeps.push(r.iterations);
                out.completed = n;
                out.min_quality = out.min_quality.min(r.min_quality);
                out.escalated += usize::from(r.stages.iter().any(|s| *s != Stage::Sweeps));
            }
            Err(e @ (Error::Inverted { .. } | Error::NotConverged { .. })) => {
                out.failure = Some(e.to_string());
                break;
            }
            Err(e) => return Err(e),
        }
    }
    Ok(out)
}

/// The amplitude of the case's first moving motion reached after `fraction`
/// of its steps: degrees for a rotation, otherwise the fraction itself.
fn amplitude(case: &Case, fraction: f64) -> String {
    let Ok(mesh) = verbss::io::read(&case.mesh) else {
        return format!("{fraction:.3}");
    };
    let first = case
        .attachments(&mesh)
        .ok()
        .and_then(|a| a.into_iter().find(|a| a.motion.moves()));
    match first.map(|a| a.motion) {
        Some(Motion::Rotation { angle, .. }) => {
            format!("{:.2}°", fraction * angle.to_degrees().abs())
        }
        _ => format!("{:.0}% of the motion", 100.0 * fraction),
    }
}

fn mean<T: Copy + Into<f64>>(v: &[T]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.iter().map(|&x| x.into()).sum::<f64>() / v.len() as f64
}

fn main() -> ExitCode {
    let mut variants: Vec<String> = VARIANTS.iter().map(|s| s.to_string()).collect();
    let mut cases: Vec<PathBuf> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--variants" {
            let Some(list) = args.next() else {
                eprintln!("--variants needs a comma-separated list of {VARIANTS:?}");
                return ExitCode::from(2);
            };
            variants = list.split(',').map(str::to_string).collect();
            if let Some(v) = variants.iter().find(|v| !VARIANTS.contains(&v.as_str())) {
                eprintln!("unknown variant '{v}': expected one of {VARIANTS:?}");
                return ExitCode::from(2);
            }
        } else {
            cases.push(PathBuf::from(a));
        }
    }
    if cases.is_empty() {
        eprintln!("usage: robustness [--variants default,verbss,...] CASE.toml...");
        return ExitCode::from(2);
    }
    println!(
        "| case | variant | steps done | amplitude | layer nodes | sweeps/step | s/step | cost vs verbss | escalated steps | min quality | stopped by |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for path in &cases {
        let case = match Case::read(path) {
            Ok(c) => c,
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::from(2);
            }
        };
        let name = path.file_stem().unwrap_or_default().to_string_lossy();
        let mut outcomes = Vec::new();
        for v in &variants {
            match run(&case, v) {
                Ok(o) => outcomes.push(o),
                Err(e) => {
                    eprintln!("{}: {v}: {e}", path.display());
                    return ExitCode::from(1);
                }
            }
        }
        let paper_seconds = variants
            .iter()
            .position(|v| v == "verbss")
            .map(|k| outcomes[k].seconds.clone());
        for (v, o) in variants.iter().zip(&outcomes) {
            let cost = match &paper_seconds {
                Some(p) if !p.is_empty() && !o.seconds.is_empty() => {
                    let k = p.len().min(o.seconds.len());
                    format!("{:.2}×", mean(&o.seconds[..k]) / mean(&p[..k]))
                }
                _ => "–".into(),
            };
            let fraction = o.completed as f64 / o.steps as f64;
            println!(
                "| {name} | {v} | {}/{} | {} | {} | {:.0} | {:.3} | {cost} | {} | {:.4} | {} |",
                o.completed,
                o.steps,
                amplitude(&case, fraction),
                o.layer_nodes,
                mean(&o.sweeps.iter().map(|&s| s as f64).collect::<Vec<_>>()),
                mean(&o.seconds),
                o.escalated,
                o.min_quality,
                o.failure.as_deref().unwrap_or("none"),
            );
        }
    }
    ExitCode::SUCCESS
}
