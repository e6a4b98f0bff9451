//! Long-run check: 20 cycles of the demo's pitching–plunging NACA0012
//! airfoil (θ₀ = 40°, h₀ = 0.2 chord about the quarter chord, period 160
//! steps, 3,200 steps, updated reference, VerBSS with ε = 10⁻⁵ relative).
//!
//! ```sh
//! cargo run --release -p verbss --example long_run               # 20 cycles
//! cargo run --release -p verbss --example long_run -- --cycles 2 # shorter
//! cargo run --release -p verbss --example long_run -- --fixed    # option 2
//! cargo run --release -p verbss --example long_run -- --direct   # exact solves
//! cargo run --release -p verbss --example long_run -- --tolerance 1e-8
//! ```
//!
//! `--fixed` builds the springs once on the input mesh (paper option 2);
//! `--direct` solves each step's ball-vertex system exactly (sparse LU)
//! instead of sweeping to the tolerance.
//!
//! After each cycle the airfoil is back where it started, so the mesh should
//! be close to the input mesh. Printed per cycle: the largest and the RMS
//! distance of the nodes from their input positions, the smallest quality
//! at the end of the cycle (and the input mesh's), the smallest quality over
//! the cycle's steps, the sweeps, and the resident memory (`VmRSS` of
//! `/proc/self/status`, Linux) at the end of the cycle. Stops with a non-zero
//! exit at the first inverted step.

use std::process::ExitCode;
use std::time::Instant;

use verbss::deform::{Deformer, Reference, Settings};
use verbss::generate::{naca0012, AirfoilGrid};
use verbss::motion::{Attachment, Motion};
use verbss::quality;
use verbss::solve::{Method, Solver};

/// Steps per pitching–plunging cycle (the demo's run length).
const PERIOD: usize = 160;

/// Resident set size in KiB, from `/proc/self/status` (`None` off Linux).
fn rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
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

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .map(|k| args.get(k + 1).and_then(|v| v.parse::<f64>().ok()))
    };
    let cycles = match value("--cycles") {
        Some(Some(c)) if c >= 1.0 && c.fract() == 0.0 => c as usize,
        Some(_) => {
            eprintln!("--cycles needs a positive integer");
            return ExitCode::from(2);
        }
        None => 20,
    };
    let tolerance = match value("--tolerance") {
        Some(Some(t)) if t > 0.0 => t,
        Some(_) => {
            eprintln!("--tolerance needs a positive number");
            return ExitCode::from(2);
        }
        None => 1e-5,
    };
    let mesh = naca0012(&AirfoilGrid::default()).expect("the default airfoil grid is valid");
    let motion = Motion::PitchPlunge {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        pitch: 40f64.to_radians(),
        plunge: [0.0, 0.2, 0.0],
        period: Some(PERIOD),
    };
    let mut settings = Settings::new(cycles * PERIOD);
    settings.solve.tolerance = tolerance;
    if args.iter().any(|a| a == "--fixed") {
        settings.reference = Reference::Fixed;
    }
    if args.iter().any(|a| a == "--direct") {
        settings.solve.method = Method::BallVertex;
        settings.solve.solver = Solver::Direct;
    }
    let attachments = [Attachment {
        groups: vec!["airfoil".into()],
        motion,
    }];
    let mut deformer = match Deformer::new(&mesh, &attachments, settings) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let orientation = quality::orientation(&mesh);
    let q0 = quality::qualities(&mesh, &mesh.coords, &orientation)
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    println!(
        "{} nodes, {} cells, {cycles} cycles of {PERIOD} steps, {:?} reference, {:?}/{:?}, tolerance {tolerance:e}; input min quality {q0:.6}, RSS {} KiB",
        mesh.node_count(),
        mesh.cell_count(),
        deformer.settings().reference,
        deformer.settings().solve.method,
        deformer.settings().solve.solver,
        rss_kib().unwrap_or(0)
    );
    println!("cycle  max drift   rms drift   min q (end)  min q (cycle)  sweeps  seconds  RSS KiB");
    let start = Instant::now();
    for cycle in 1..=cycles {
        let (mut min_q, mut sweeps) = (f64::INFINITY, 0);
        let t = Instant::now();
        for _ in 0..PERIOD {
            match deformer.advance() {
                Ok(r) => {
                    min_q = min_q.min(r.min_quality);
                    sweeps += r.iterations;
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            }
        }
        let current = deformer.current();
        let (max, rms) = drift(mesh.dim, &current.coords, &mesh.coords);
        println!(
            "{cycle:5}  {max:.3e}  {rms:.3e}  {:11.6}  {min_q:13.6}  {sweeps:6}  {:7.1}  {}",
            current.report.min_quality,
            t.elapsed().as_secs_f64(),
            rss_kib().unwrap_or(0)
        );
    }
    println!(
        "{} steps, every one valid, {:.1} s",
        cycles * PERIOD,
        start.elapsed().as_secs_f64()
    );
    ExitCode::SUCCESS
}
