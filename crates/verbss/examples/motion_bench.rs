//! The motion benchmark of `bench/compare.py`: one group translated in equal
//! steps (updated reference, as `verbss deform`), timed per step, with the
//! accuracy each step bought.
//!
//! ```sh
//! cargo run --release -p verbss --example motion_bench -- MESH \
//!     --moving sphere --translate 16,0,0 --steps 16 [--threads 1] [--error-steps 1,16] \
//!     [--defaults | [--accel none|amg] [--fixed-reference] [--predictor previous|linear] \
//!     [--tolerance 1e-6] [--reference amg|direct]] [--output FINAL.vtu]
//! ```
//!
//! The paper's method (the library's [`Settings::new`]), or with
//! `--defaults` exactly what `verbss deform MESH --moving GROUP --translate
//! … --steps N` runs with nothing else given: [`Settings::robust`] (VerBSS,
//! the near-wall treatments, the blended rigid motion, the escalating
//! solve) with the reference its motion implies (`auto`). Every part of the step, the mesh
//! check included, runs on `--threads` threads.
//!
//! Prints one JSON object: per step the whole step's wall seconds (motion,
//! springs, solve, quality check) and the CPU seconds of the process over
//! it (all threads; a loaded machine shows as wall > CPU with one thread),
//! the seconds forming the system (springs, factors, multigrid setup), the
//! solve's seconds and sweeps (GMRES iterations with `--accel amg`); the
//! seconds assembling the springs (part of forming) and checking the new
//! mesh's quality and inversions; `shares`, each phase's part of the steps'
//! wall seconds summed over steps 2 on (all steps in a run of one): springs,
//! the rest of forming, solve, check and the rest of the step (motion,
//! blended rigid motion, update); `peak_rss_bytes`, the peak resident
//! memory (`VmHWM`) read right after the timed steps, before the output and
//! the error measures (it includes the copies of the coordinates of the
//! `--error-steps` kept for them: 2 × 3 doubles a node per step listed);
//! the sweep's bytes per unknown node; the final minimum quality and
//! inverted count; and for each step `n` of `--error-steps`:
//!
//! * without `--defaults`, `true_error`: the error of step `n`'s increment
//!   against the paper's spring system solved tightly, `‖Δu − Δu_ref‖ /
//!   ‖Δu_ref‖`, where `Δu_ref` solves the same step (same reference
//!   coordinates, same prescribed increments) to an estimated RMS error of
//!   1e-13 × the motion with the accelerated solve (`amg`), or exactly with
//!   the sparse LU of the ball-vertex system (`direct`, small meshes only);
//! * with `--defaults`, `true_error`: the mesh after step `n`, `x`, against
//!   the same default settings run again with the springs' tolerance 1e-12,
//!   `x_tight`: `‖x − x_tight‖ / ‖x_tight − x_input‖` (the ratio of the RMS
//!   node distances); and, for information, `paper_distance`: the measure
//!   above (the step's increment against the paper's springs solved
//!   tightly), which is not the system the defaults solve — the blend moves
//!   the mesh first and the springs solve only the remainder.
//!
//! The error measures run after the timed steps.

use std::path::PathBuf;
use std::sync::Arc;

use verbss::deform::Deformer;
use verbss::mesh::Mesh;
use verbss::motion::{Attachment, Motion};
use verbss::near_wall::Robust;
use verbss::settings::{Predictor, Reference, Settings};
use verbss::solve::{Accel, Engine, Method, NodeRole, SolveParams, Solver};

/// The springs' tolerance of the tight run that `--defaults`' true error
/// compares with.
const TIGHT_TOLERANCE: f64 = 1e-12;

struct Options {
    mesh: PathBuf,
    moving: String,
    translate: [f64; 3],
    steps: usize,
    threads: usize,
    accel: Accel,
    tolerance: f64,
    error_steps: Vec<usize>,
    direct: bool,
    defaults: bool,
    reference: Reference,
    predictor: Predictor,
    output: Option<PathBuf>,
}

fn options() -> Options {
    let mut o = Options {
        mesh: PathBuf::new(),
        moving: String::new(),
        translate: [16.0, 0.0, 0.0],
        steps: 16,
        threads: 1,
        accel: Accel::None,
        tolerance: 1e-6,
        error_steps: Vec::new(),
        direct: false,
        defaults: false,
        reference: Reference::Updated,
        predictor: Predictor::Previous,
        output: None,
    };
    let mut tuned = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--moving" => o.moving = value(),
            "--translate" => {
                let v: Vec<f64> = value().split(',').map(|x| x.parse().unwrap()).collect();
                o.translate = [v[0], v[1], *v.get(2).unwrap_or(&0.0)];
            }
            "--steps" => o.steps = value().parse().unwrap(),
            "--threads" => o.threads = value().parse().unwrap(),
            "--accel" => {
                o.accel = match value().as_str() {
                    "none" => Accel::None,
                    "amg" => Accel::Amg,
                    other => panic!("--accel {other}: expected none or amg"),
                }
            }
            "--tolerance" => o.tolerance = value().parse().unwrap(),
            "--error-steps" => {
                o.error_steps = value()
                    .split(',')
                    .filter(|s| !s.is_empty())
                    .map(|s| s.parse().unwrap())
                    .collect()
            }
            "--reference" => o.direct = value() == "direct",
            "--defaults" => o.defaults = true,
            "--fixed-reference" => o.reference = Reference::Fixed,
            "--predictor" => {
                o.predictor = match value().as_str() {
                    "previous" => Predictor::Previous,
                    "linear" => Predictor::Linear,
                    other => panic!("--predictor {other}: expected previous or linear"),
                }
            }
            "--output" => o.output = Some(PathBuf::from(value())),
            _ => o.mesh = PathBuf::from(a.clone()),
        }
        if matches!(
            a.as_str(),
            "--accel" | "--tolerance" | "--reference" | "--fixed-reference" | "--predictor"
        ) {
            tuned.push(a);
        }
    }
    assert!(!o.moving.is_empty(), "--moving GROUP is required");
    assert!(
        !o.defaults || tuned.is_empty(),
        "--defaults runs the command line's defaults: {} change them",
        tuned.join(", ")
    );
    o
}

/// The settings of the run: the paper's method as the options say, or
/// with `--defaults` those of `verbss deform` given nothing but the motion.
fn settings(o: &Options) -> Settings {
    let mut settings = if o.defaults {
        Settings::robust(o.steps)
    } else {
        let mut s = Settings::new(o.steps);
        s.solve.tolerance = o.tolerance;
        s.solve.accel = o.accel;
        s.reference = o.reference;
        s.predictor = o.predictor;
        s
    };
    settings.solve.threads = o.threads;
    settings
}

/// The coordinates of one step of `--error-steps`: before and after it.
struct Saved {
    step: usize,
    before: Vec<f64>,
    after: Vec<f64>,
}

/// The error of each saved step's increment against the paper's spring
/// system on the same reference with the same prescribed increments,
/// solved tightly: `‖Δu − Δu_ref‖ / ‖Δu_ref‖`.
fn paper_distance(
    o: &Options,
    reference: Reference,
    mesh: &Mesh,
    roles: &[NodeRole],
    saved: &[Saved],
) -> Vec<String> {
    let dim = mesh.dim;
    let mut engine = Engine::new(mesh, roles, &[]).expect("engine");
    let mut errors = Vec::new();
    for s in saved {
        let origin = if reference == Reference::Updated {
            &s.before
        } else {
            &mesh.coords
        };
        let increment: Vec<f64> = s.after.iter().zip(origin).map(|(a, b)| a - b).collect();
        let mut reference = vec![0.0; increment.len()];
        for (i, role) in roles.iter().enumerate() {
            if *role != NodeRole::Free {
                reference[dim * i..dim * (i + 1)]
                    .copy_from_slice(&increment[dim * i..dim * (i + 1)]);
            }
        }
        let mut p = SolveParams::default();
        p.max_iterations = 100_000;
        p.threads = o.threads;
        if o.direct {
            p.method = Method::BallVertex;
            p.solver = Solver::Direct;
        } else {
            p.accel = Accel::Amg;
            p.tolerance = 1e-13;
        }
        engine.solve(origin, &mut reference, &p).expect("reference");
        errors.push(format!(
            "[{}, {:.3e}]",
            s.step,
            relative(&increment, &reference)
        ));
    }
    errors
}

/// `‖a − b‖ / ‖b‖`.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let size: f64 = b.iter().map(|y| y * y).sum();
    (diff / size).sqrt()
}

/// The true error of a `--defaults` run: each saved step's mesh `x` against
/// the same settings run with the springs' tolerance [`TIGHT_TOLERANCE`],
/// `‖x − x_tight‖ / ‖x_tight − x_input‖`; or why the tight run stopped.
fn tight_error(
    mesh: &Arc<Mesh>,
    attachments: &[Attachment],
    mut settings: Settings,
    saved: &[Saved],
) -> Result<Vec<String>, String> {
    settings.solve.tolerance = TIGHT_TOLERANCE;
    let mut tight =
        Deformer::shared(mesh.clone(), attachments, settings).map_err(|e| e.to_string())?;
    let mut errors = Vec::new();
    for s in saved {
        while tight.current_step() < s.step {
            tight
                .step(tight.current_step() + 1)
                .map_err(|e| format!("tight run, step {}: {e}", tight.current_step() + 1))?;
        }
        let x_tight = &tight.current().coords;
        let moved: Vec<f64> = x_tight
            .iter()
            .zip(&mesh.coords)
            .map(|(t, x)| t - x)
            .collect();
        let off: Vec<f64> = s
            .after
            .iter()
            .zip(&mesh.coords)
            .map(|(a, x)| a - x)
            .collect();
        errors.push(format!("[{}, {:.3e}]", s.step, relative(&off, &moved)));
    }
    Ok(errors)
}

/// The peak resident set size of this process in bytes (`VmHWM`).
fn peak_rss() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// CPU seconds used by this process so far, all threads (user + system,
/// `/proc/self/stat`, in clock ticks of 1/100 s).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit_once(')')
        .map_or(vec![], |(_, rest)| rest.split_whitespace().collect());
    let ticks = |k: usize| fields.get(k).and_then(|v| v.parse::<f64>().ok());
    ticks(11)
        .zip(ticks(12))
        .map_or(0.0, |(u, s)| (u + s) / 100.0)
}

/// Each phase's part of the wall seconds of steps 2 on (all steps when
/// there is one), as a JSON object.
fn shares(steps: &[verbss::deform::StepReport]) -> String {
    let later = if steps.len() > 1 { &steps[1..] } else { steps };
    let sum = |f: &dyn Fn(&verbss::deform::StepReport) -> f64| later.iter().map(f).sum::<f64>();
    let total = sum(&|r| r.seconds).max(f64::MIN_POSITIVE);
    let springs = sum(&|r| r.springs_seconds);
    let form = sum(&|r| r.form_seconds);
    let solve = sum(&|r| r.solve_seconds);
    let check = sum(&|r| r.check_seconds);
    format!(
        "{{\"springs\": {:.3}, \"form_other\": {:.3}, \"solve\": {:.3}, \"check\": {:.3}, \
         \"rest\": {:.3}}}",
        springs / total,
        (form - springs) / total,
        solve / total,
        check / total,
        (total - form - solve - check) / total,
    )
}

fn main() {
    let o = options();
    rayon::ThreadPoolBuilder::new()
        .num_threads(o.threads)
        .build_global()
        .expect("thread pool");
    let mesh = Arc::new(verbss::io::read(&o.mesh).expect("mesh"));
    let motion = Motion::Translation {
        displacement: o.translate,
    };
    let settings = settings(&o);
    let attachments = [Attachment {
        groups: vec![o.moving.clone()],
        motion,
    }];
    let mut deformer =
        Deformer::shared(mesh.clone(), &attachments, settings.clone()).expect("deformer");
    let mut steps = Vec::new();
    let mut cpu_steps = Vec::new();
    let mut saved = Vec::new();
    let mut failure = None;
    for n in 1..=o.steps {
        let before = o
            .error_steps
            .contains(&n)
            .then(|| deformer.current().coords.clone());
        let cpu = cpu_seconds();
        match deformer.step(n) {
            Ok(r) => {
                steps.push(r);
                cpu_steps.push(cpu_seconds() - cpu);
            }
            Err(e) => {
                failure = Some(e.to_string());
                break;
            }
        }
        if let Some(before) = before {
            let after = deformer.current().coords.clone();
            saved.push(Saved {
                step: n,
                before,
                after,
            });
        }
    }
    let peak = peak_rss();
    if let Some(path) = &o.output {
        verbss::io::write(path, &deformer.mesh(), &verbss::io::WriteOptions::default())
            .expect("final mesh");
    }
    let roles = deformer.roles().to_vec();
    let reference = deformer.settings().reference;
    drop(deformer);
    let distance = paper_distance(&o, reference, &mesh, &roles, &saved);
    let (true_error, paper) = if o.defaults {
        let tight = tight_error(&mesh, &attachments, settings.clone(), &saved);
        let tight = tight.map_or_else(|e| format!("{e:?}"), |e| format!("[{}]", e.join(", ")));
        (
            tight,
            format!(", \"paper_distance\": [{}]", distance.join(", ")),
        )
    } else {
        (format!("[{}]", distance.join(", ")), String::new())
    };
    let mut plain = Engine::new(&mesh, &roles, &[]).expect("engine");
    let mut u = vec![0.0; mesh.coords.len()];
    let mut once = SolveParams::default();
    once.max_iterations = 1;
    plain.solve(&mesh.coords, &mut u, &once).expect("one sweep");
    let unknown = roles.iter().filter(|r| **r == NodeRole::Free).count();
    let list = |f: &dyn Fn(&verbss::deform::StepReport) -> String| {
        steps.iter().map(f).collect::<Vec<_>>().join(", ")
    };
    let last = steps.last();
    println!(
        "{{\"mesh\": {:?}, \"nodes\": {}, \"cells\": {}, \"unknown_nodes\": {unknown}, \
         \"threads\": {}, \"accel\": {:?}, \"defaults\": {}, \"robust\": {}, \"reference\": {:?}, \
         \"predictor\": {:?}, \"tolerance\": {:e}, \"steps_done\": {}, \
         \"failure\": {}, \"seconds\": [{}], \"cpu_seconds\": [{}], \"solve_seconds\": [{}], \"form_seconds\": [{}], \
         \"springs_seconds\": [{}], \"check_seconds\": [{}], \"shares\": {}, \"iterations\": [{}], \
         \"peak_rss_bytes\": {peak}, \"bytes_per_node\": {:.1}, \"min_quality\": {}, \
         \"inverted\": {}, \"true_error\": {true_error}{paper}}}",
        o.mesh.display().to_string(),
        mesh.node_count(),
        mesh.cell_count(),
        o.threads,
        format!("{:?}", settings.solve.accel).to_lowercase(),
        o.defaults,
        settings.robust == Robust::recommended(),
        format!("{:?}", settings.reference).to_lowercase(),
        format!("{:?}", settings.predictor).to_lowercase(),
        settings.solve.tolerance,
        steps.len(),
        failure.map_or("null".into(), |f| format!("{f:?}")),
        list(&|r| format!("{:.6}", r.seconds)),
        cpu_steps
            .iter()
            .map(|c| format!("{c:.2}"))
            .collect::<Vec<_>>()
            .join(", "),
        list(&|r| format!("{:.6}", r.solve_seconds)),
        list(&|r| format!("{:.6}", r.form_seconds)),
        list(&|r| format!("{:.6}", r.springs_seconds)),
        list(&|r| format!("{:.6}", r.check_seconds)),
        shares(&steps),
        list(&|r| r.iterations.to_string()),
        plain.bytes_per_node(),
        last.map_or(0.0, |r| r.min_quality),
        last.map_or(0, |r| r.inverted),
    );
}
