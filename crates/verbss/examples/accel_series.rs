//! Plain VerBSS against the multigrid-accelerated solve (`--accel amg`) on
//! a series of meshes, side by side in one run, at the same true error.
//!
//! ```sh
//! python3 bench/sphere_cube.py /tmp/sc1.msh --h-sphere 1.0
//! cargo run --release -p verbss --example accel_series -- \
//!     --moving sphere --translate 1,0,0 /tmp/sc1.msh [more meshes…]
//! ```
//!
//! Per mesh, one step moves the group by the translation, every other
//! boundary node fixed:
//! 1. the reference: the direct ball-vertex solve up to `--direct-limit`
//!    unknown nodes, the accelerated solve to an RMS error estimate of
//!    1e-13 × the motion above;
//! 2. plain VerBSS at `--tolerance` (eq. 8, relative to the motion; default
//!    1e-6), its sweeps, seconds and true error `‖u − u_ref‖ / ‖u_ref‖`;
//! 3. the accelerated solve at tolerances 10×, 3×, 1×, 0.3×, … `--tolerance`
//!    until its true error is no larger than plain VerBSS's: that run's
//!    iterations, setup and solve seconds, and its cost in plain sweeps
//!    (seconds / seconds per plain sweep);
//! 4. the accelerated solve once more with the hierarchy reused (the next
//!    step of a fixed-reference run, or of an updated-reference run whose
//!    mesh changed little).
//!
//! `--threads N` sets the solver threads (default 1).

use std::path::PathBuf;
use std::time::Instant;

use verbss::mesh::Mesh;
use verbss::solve::{default_roles, Accel, Engine, Method, SolveInfo, SolveParams, Solver};

struct Options {
    meshes: Vec<PathBuf>,
    moving: String,
    translate: [f64; 3],
    tolerance: f64,
    threads: usize,
    direct_limit: usize,
}

fn options() -> Options {
    let mut o = Options {
        meshes: Vec::new(),
        moving: String::new(),
        translate: [1.0, 0.0, 0.0],
        tolerance: 1e-6,
        threads: 1,
        direct_limit: 60_000,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--moving" => o.moving = value(),
            "--translate" => {
                let v: Vec<f64> = value().split(',').map(|x| x.parse().unwrap()).collect();
                o.translate = [v[0], v[1], *v.get(2).unwrap_or(&0.0)];
            }
            "--tolerance" => o.tolerance = value().parse().unwrap(),
            "--threads" => o.threads = value().parse().unwrap(),
            "--direct-limit" => o.direct_limit = value().parse().unwrap(),
            _ => o.meshes.push(PathBuf::from(a)),
        }
    }
    assert!(!o.moving.is_empty(), "--moving GROUP is required");
    o
}

fn params(accel: Accel, tolerance: f64, threads: usize) -> SolveParams {
    let mut p = SolveParams::default();
    p.method = Method::Verbss;
    p.accel = accel;
    p.tolerance = tolerance;
    p.max_iterations = 1_000_000;
    p.threads = threads;
    p
}

fn rel_error(u: &[f64], reference: &[f64]) -> f64 {
    let diff: f64 = u.iter().zip(reference).map(|(a, b)| (a - b).powi(2)).sum();
    let size: f64 = reference.iter().map(|b| b * b).sum();
    (diff / size).sqrt()
}

fn run(
    engine: &mut Engine,
    mesh: &Mesh,
    u0: &[f64],
    p: &SolveParams,
) -> (Vec<f64>, SolveInfo, f64) {
    let mut u = u0.to_vec();
    let t = Instant::now();
    let info = engine.solve(&mesh.coords, &mut u, p).expect("solve");
    (u, info, t.elapsed().as_secs_f64())
}

fn main() {
    let o = options();
    println!(
        "| mesh | nodes | unknown nodes | plain sweeps | plain s | s/sweep | plain error | amg tol | amg iters | levels | setup s | amg solve s | amg total s | equiv. sweeps | speed-up | reused: iters | reused s | speed-up reused |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for path in &o.meshes {
        let mesh = verbss::io::read(path).expect("mesh");
        let d = mesh.dim;
        let roles = default_roles(&mesh);
        let mut u0 = vec![0.0; mesh.coords.len()];
        for i in mesh.group(&o.moving).expect("group").nodes() {
            u0[d * i..d * (i + 1)].copy_from_slice(&o.translate[..d]);
        }
        let unknown = roles
            .iter()
            .filter(|r| **r == verbss::solve::NodeRole::Free)
            .count();
        let reference = if unknown <= o.direct_limit {
            let mut p = params(Accel::None, 0.0, 1);
            p.method = Method::BallVertex;
            p.solver = Solver::Direct;
            run(
                &mut Engine::new(&mesh, &roles, &[]).unwrap(),
                &mesh,
                &u0,
                &p,
            )
            .0
        } else {
            let p = params(Accel::Amg, 1e-13, o.threads);
            run(
                &mut Engine::new(&mesh, &roles, &[]).unwrap(),
                &mesh,
                &u0,
                &p,
            )
            .0
        };
        let mut plain_engine = Engine::new(&mesh, &roles, &[]).unwrap();
        let (u, plain, plain_s) = run(
            &mut plain_engine,
            &mesh,
            &u0,
            &params(Accel::None, o.tolerance, o.threads),
        );
        let plain_error = rel_error(&u, &reference);
        let per_sweep = plain.solve_seconds / plain.iterations as f64;
        drop(plain_engine);
        let mut factor = 10.0;
        let (amg, amg_s, amg_tol, mut engine) = loop {
            let tol = o.tolerance * factor;
            let mut engine = Engine::new(&mesh, &roles, &[]).unwrap();
            let (u, info, s) = run(&mut engine, &mesh, &u0, &params(Accel::Amg, tol, o.threads));
            if rel_error(&u, &reference) <= plain_error || factor < 1e-6 {
                break (info, s, tol, engine);
            }
            factor /= if (factor.log10().fract()).abs() < 1e-9 {
                10.0 / 3.0
            } else {
                3.0
            };
        };
        let (_, reused, reused_s) = run(
            &mut engine,
            &mesh,
            &u0,
            &params(Accel::Amg, amg_tol, o.threads),
        );
        assert!(!reused.hierarchy_built);
        let setup = amg.hierarchy_seconds;
        println!(
            "| {} | {} | {} | {} | {:.3} | {:.2e} | {:.1e} | {:.1e} | {} | {} | {:.3} | {:.3} | {:.3} | {:.0} | {:.1} | {} | {:.3} | {:.1} |",
            path.file_name().unwrap().to_string_lossy(),
            mesh.node_count(),
            unknown,
            plain.iterations,
            plain_s,
            per_sweep,
            plain_error,
            amg_tol,
            amg.iterations,
            amg.levels,
            setup,
            amg.solve_seconds,
            amg_s,
            amg_s / per_sweep,
            plain_s / amg_s,
            reused.iterations,
            reused_s,
            plain_s / reused_s,
        );
    }
}
