//! Long-run check (docs/reliability.md, "Long runs"): many cycles of a
//! periodic motion with the default settings (`--method robust`, whose
//! reference is `anchored`), or with the ones given.
//!
//! ```sh
//! cargo run --release -p verbss --example long_run -- --case demo   # 20 cycles
//! cargo run --release -p verbss --example long_run -- --case rans
//! cargo run --release -p verbss --example long_run -- --case fish
//! cargo run --release -p verbss --example long_run -- --case demo --cycles 2
//! cargo run --release -p verbss --example long_run -- --case demo --reference updated
//! cargo run --release -p verbss --example long_run -- --case demo --method verbss --tolerance 1e-5
//! cargo run --release -p verbss --example long_run -- --case fish --direct
//! ```
//!
//! The cases (`--case all`, the default, runs the three in turn; one case a
//! process gives its own memory figures):
//!
//! * `demo`: the demo's NACA0012 O-grid (4,500 nodes) pitching (θ₀ = 40°)
//!   and plunging (h₀ = 0.2 chord) about the quarter chord, 160 steps a cycle;
//! * `rans`: the RANS O-grid `cases/meshes/ogrid.msh` (Gmsh, 32,736 nodes,
//!   first cell 10⁻⁵ chord) pitching ±15° about the quarter chord, 80 steps
//!   a cycle;
//! * `fish`: `cases/two-fish.toml` (the two undulating fish, 3D; make the
//!   mesh with `python3 cases/meshes/two_fish.py cases/meshes/two-fish.msh`),
//!   60 steps a cycle after the case's 10-step ramp.
//!
//! `--reference`, `--predictor` and `--method` replace the default's; `--direct` solves each
//! step exactly (sparse LU), `--tolerance` sets the eq.-8 stop.
//!
//! A cycle ends where it started, so the mesh should be the one it started
//! from: the input mesh, or for the fish the mesh at the end of the ramp.
//! Printed per cycle, relative to the diagonal of the input mesh's bounding
//! box: the largest and the RMS distance of the nodes from that mesh, and
//! the largest distance from the end of the cycle before (the drift per
//! cycle); then the smallest quality at the end of the cycle and over its steps, the
//! sweeps, and the resident memory now and at its peak (`VmRSS`, `VmHWM` of
//! `/proc/self/status`, Linux). Stops with a non-zero exit at the first
//! inverted step.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use verbss::case::Case;
use verbss::deform::Deformer;
use verbss::generate::{naca0012, AirfoilGrid};
use verbss::mesh::Mesh;
use verbss::motion::{Attachment, Motion};
use verbss::quality;
use verbss::settings::{Predictor, Preset, Reference};
use verbss::solve::{Method, Solver};

/// One periodic run: a mesh, its motions, the steps of a cycle and the
/// steps before the first (a ramp).
struct Periodic {
    name: &'static str,
    mesh: Mesh,
    attachments: Vec<Attachment>,
    period: usize,
    lead: usize,
    dt: Option<f64>,
}

/// A value of `/proc/self/status` in KiB (`None` off Linux).
fn status_kib(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Largest and RMS distance between the nodes of two coordinate sets.
fn drift(dim: usize, a: &[f64], b: &[f64]) -> (f64, f64) {
    let (mut max, mut sum) = (0.0f64, 0.0);
    for (p, q) in a.chunks(dim).zip(b.chunks(dim)) {
        let d2: f64 = p.iter().zip(q).map(|(x, y)| (x - y) * (x - y)).sum();
        max = max.max(d2.sqrt());
        sum += d2;
    }
    (max, (sum / (a.len() / dim) as f64).sqrt())
}

/// An airfoil pitching by `pitch` degrees and plunging by `plunge` chords
/// about its quarter chord (its leading edge at `lead_x`), `period` steps a cycle.
fn pitch_plunge(lead_x: f64, pitch: f64, plunge: f64, period: usize) -> Vec<Attachment> {
    vec![Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::PitchPlunge {
            center: [lead_x + 0.25, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            pitch: pitch.to_radians(),
            plunge: [0.0, plunge, 0.0],
            period: Some(period),
        },
    }]
}

fn case(name: &str) -> Result<Periodic, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    match name {
        "demo" => Ok(Periodic {
            name: "demo",
            mesh: naca0012(&AirfoilGrid::default()).map_err(|e| e.to_string())?,
            attachments: pitch_plunge(0.0, 40.0, 0.2, 160),
            period: 160,
            lead: 0,
            dt: None,
        }),
        "rans" => Ok(Periodic {
            name: "rans",
            mesh: verbss::io::read(&root.join("cases/meshes/ogrid.msh"))
                .map_err(|e| e.to_string())?,
            attachments: pitch_plunge(0.0, 15.0, 0.0, 80),
            period: 80,
            lead: 0,
            dt: None,
        }),
        "fish" => {
            let case = Case::read(&root.join("cases/two-fish.toml")).map_err(|e| e.to_string())?;
            let mesh = verbss::io::read(&case.mesh).map_err(|e| e.to_string())?;
            Ok(Periodic {
                name: "fish",
                attachments: case.attachments(&mesh).map_err(|e| e.to_string())?,
                mesh,
                period: 60,
                lead: 10,
                dt: Some(case.settings.dt),
            })
        }
        _ => Err(format!("unknown case '{name}': demo, rans, fish or all")),
    }
}

/// Options of the run beyond the case.
struct Options {
    cycles: usize,
    method: Preset,
    reference: Option<Reference>,
    tolerance: Option<f64>,
    predictor: Option<Predictor>,
    direct: bool,
}

fn run(p: &Periodic, o: &Options) -> Result<(), String> {
    let steps = p.lead + o.cycles * p.period;
    let mut settings = o.method.settings(steps);
    if let Some(dt) = p.dt {
        settings.dt = dt;
    }
    settings.reference = o.reference.unwrap_or(settings.reference);
    if let Some(t) = o.tolerance {
        settings.solve.tolerance = t;
    }
    settings.predictor = o.predictor.unwrap_or(settings.predictor);
    if o.direct {
        settings.solve.method = Method::BallVertex;
        settings.solve.solver = Solver::Direct;
    }
    let mesh = &p.mesh;
    let size = mesh.diagonal();
    let mut d = Deformer::new(mesh, &p.attachments, settings).map_err(|e| e.to_string())?;
    let orientation = quality::orientation(mesh);
    let q0 = quality::qualities(mesh, &mesh.coords, &orientation)
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    for _ in 0..p.lead {
        d.advance().map_err(|e| e.to_string())?;
    }
    let origin = d.current().coords.clone();
    let mut previous = origin.clone();
    println!(
        "{}: {} nodes, {} cells, size {size:.4}, {} cycles of {} steps after {}, {} reference, {:?}/{:?}, tolerance {:e}; input min quality {q0:.6}, RSS {} KiB",
        p.name,
        mesh.node_count(),
        mesh.cell_count(),
        o.cycles,
        p.period,
        p.lead,
        d.settings().reference,
        d.settings().solve.method,
        d.settings().solve.solver,
        d.settings().solve.tolerance,
        status_kib("VmRSS:").unwrap_or(0)
    );
    println!("cycle  max drift/size  rms drift/size  max change/size  min q (end)  min q (cycle)  sweeps  seconds  RSS KiB  peak KiB");
    let start = Instant::now();
    for cycle in 1..=o.cycles {
        let (mut min_q, mut sweeps) = (f64::INFINITY, 0);
        let t = Instant::now();
        for _ in 0..p.period {
            let r = d.advance().map_err(|e| e.to_string())?;
            min_q = min_q.min(r.min_quality);
            sweeps += r.iterations;
        }
        let current = d.current();
        let (max, rms) = drift(mesh.dim, &current.coords, &origin);
        let (change, _) = drift(mesh.dim, &current.coords, &previous);
        previous.clone_from(&current.coords);
        println!(
            "{cycle:5}  {:14.3e}  {:14.3e}  {:15.3e}  {:11.6}  {min_q:13.6}  {sweeps:6}  {:7.1}  {:7}  {:8}",
            max / size,
            rms / size,
            change / size,
            current.report.min_quality,
            t.elapsed().as_secs_f64(),
            status_kib("VmRSS:").unwrap_or(0),
            status_kib("VmHWM:").unwrap_or(0)
        );
    }
    println!(
        "{}: {} steps, every one valid, {:.1} s",
        p.name,
        steps,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .map(|k| args.get(k + 1).cloned().unwrap_or_default())
    };
    let cycles = match value("--cycles").map(|c| c.parse::<usize>()) {
        Some(Ok(c)) if c >= 1 => c,
        Some(_) => {
            eprintln!("--cycles needs a positive integer");
            return ExitCode::from(2);
        }
        None => 20,
    };
    let tolerance = match value("--tolerance").map(|t| t.parse::<f64>()) {
        Some(Ok(t)) if t > 0.0 => Some(t),
        Some(_) => {
            eprintln!("--tolerance needs a positive number");
            return ExitCode::from(2);
        }
        None => None,
    };
    let method = match value("--method").map(|m| m.parse::<Preset>()) {
        Some(Ok(m)) => m,
        Some(Err(e)) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
        None => Preset::default(),
    };
    let reference = match value("--reference").map(|r| r.parse::<Reference>()) {
        Some(Ok(r)) => Some(r),
        Some(Err(e)) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
        None => None,
    };
    let predictor = match value("--predictor").map(|r| r.parse::<Predictor>()) {
        Some(Ok(r)) => Some(r),
        Some(Err(e)) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
        None => None,
    };
    let options = Options {
        predictor,
        cycles,
        method,
        reference,
        tolerance,
        direct: args.iter().any(|a| a == "--direct"),
    };
    let case_name = value("--case");
    let names = match case_name.as_deref() {
        None | Some("all") => vec!["demo", "rans", "fish"],
        Some(name) => vec![name],
    };
    for name in names {
        if let Err(e) = case(name).and_then(|p| run(&p, &options)) {
            eprintln!("{name}: error: {e}");
            return ExitCode::FAILURE;
        }
    }
    ExitCode::SUCCESS
}
