//! The sweep against the machine's memory bandwidth, in one run: a
//! STREAM-like triad `a_i = b_i + s c_i` and VerBSS sweeps on the given
//! meshes, each with 1 and 2 threads.
//!
//! ```sh
//! cargo run --release -p verbss --example sweep_bandwidth -- \
//!     --moving sphere --translate 1,0,0 [--sweeps 5] [--repeat 20] [--triad-mb 256] MESH…
//! ```
//!
//! The triad moves 24 bytes per element (read `b`, `c`, write `a`; STREAM's
//! count, write-allocate traffic not included) over arrays of `--triad-mb`
//! MB each, far larger than the caches; its bandwidth is the best of 10
//! repetitions. A sweep must read the system's stored data once and read and
//! write each unknown's displacement once: `Engine::bytes_per_node` × unknown
//! nodes bytes (diagonal factors, coupling blocks, 32-bit neighbour indices,
//! offsets, right-hand side, the displacement read and written). Its seconds
//! are the best of `--repeat` solves of `--sweeps` sweeps each (the eq.-8
//! test never met: tolerance 0), springs formed beforehand: best-of timings
//! on both sides, so that a shared machine's interruptions count as little
//! as they can. Effective bandwidth = bytes
//! per sweep / seconds per sweep. The two thread counts' displacements are
//! compared bit by bit.
//!
//! The colour passes re-read the displacements: each pass reads its nodes'
//! neighbours from every other colour's block. `pass reads` is
//! `Engine::colour_pass_read_bytes`, the 64-byte lines of displacements the
//! passes of one sweep read, per node, each counted once per pass; `with
//! re-reads` is the one-thread bandwidth with those bytes in place of the
//! one read of the displacements, the traffic of a sweep whose
//! displacement lines do not stay cached from one colour pass to the next.
//!
//! Prints one Markdown table row per mesh and the triad's line.

use std::path::PathBuf;
use std::time::Instant;

use rayon::prelude::*;
use verbss::solve::{default_roles, Engine, NodeRole, SolveParams};

/// Best triad bandwidth in bytes per second with `threads` threads.
fn triad(threads: usize, len: usize) -> f64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool");
    let chunk = len.div_ceil(threads);
    let mut a = vec![0.0f64; len];
    let b = vec![1.0f64; len];
    let c = vec![2.0f64; len];
    let s = 3.0;
    let mut best = f64::INFINITY;
    pool.install(|| {
        for _ in 0..10 {
            let t = Instant::now();
            a.par_chunks_mut(chunk)
                .zip(b.par_chunks(chunk))
                .zip(c.par_chunks(chunk))
                .for_each(|((a, b), c)| {
                    for ((a, b), c) in a.iter_mut().zip(b).zip(c) {
                        *a = b + s * c;
                    }
                });
            best = best.min(t.elapsed().as_secs_f64());
        }
    });
    assert!(a.iter().all(|&v| v == 7.0));
    24.0 * len as f64 / best
}

/// What [`sweeps`] measured.
struct Sweeps {
    /// Best seconds per sweep.
    seconds: f64,
    /// `Engine::bytes_per_node`.
    bytes: f64,
    /// `Engine::colour_pass_read_bytes`.
    pass_reads: f64,
    /// The displacement after the last solve.
    last: Vec<f64>,
}

/// Best seconds per sweep with `threads` threads, the bytes per unknown node
/// and the displacement after one solve.
fn sweeps(
    mesh: &verbss::mesh::Mesh,
    roles: &[NodeRole],
    u0: &[f64],
    threads: usize,
    count: usize,
    repeat: usize,
) -> Sweeps {
    let mut engine = Engine::new(mesh, roles, &[]).expect("engine");
    let mut p = SolveParams::default();
    p.tolerance = 0.0;
    // The sweeps alone: never escalate to another solver.
    p.escalate = false;
    p.max_iterations = count;
    p.threads = threads;
    let mut best = f64::INFINITY;
    let mut last = Vec::new();
    let mut warm = u0.to_vec();
    engine.solve(&mesh.coords, &mut warm, &p).expect("solve");
    for _ in 0..repeat {
        let mut u = u0.to_vec();
        let info = engine.solve(&mesh.coords, &mut u, &p).expect("solve");
        assert!(!info.rebuilt);
        best = best.min(info.solve_seconds / info.iterations as f64);
        last = u;
    }
    Sweeps {
        seconds: best,
        bytes: engine.bytes_per_node(),
        pass_reads: engine.colour_pass_read_bytes(),
        last,
    }
}

fn main() {
    let mut meshes = Vec::new();
    let mut moving = String::new();
    let mut translate = [1.0, 0.0, 0.0];
    let mut count = 5;
    let mut repeat = 20;
    let mut triad_mb = 256.0;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--moving" => moving = value(),
            "--translate" => {
                let v: Vec<f64> = value().split(',').map(|x| x.parse().unwrap()).collect();
                translate = [v[0], v[1], *v.get(2).unwrap_or(&0.0)];
            }
            "--sweeps" => count = value().parse().unwrap(),
            "--repeat" => repeat = value().parse().unwrap(),
            "--triad-mb" => triad_mb = value().parse().unwrap(),
            _ => meshes.push(PathBuf::from(a)),
        }
    }
    let len = (triad_mb * 1e6 / 8.0) as usize;
    let t1 = triad(1, len);
    let t2 = triad(2, len);
    println!(
        "triad ({triad_mb} MB arrays): 1 thread {:.2} GB/s, 2 threads {:.2} GB/s, speed-up {:.2}",
        t1 / 1e9,
        t2 / 1e9,
        t2 / t1
    );
    println!(
        "| mesh | unknown nodes | bytes/node | MB per sweep | s/sweep 1 thread | GB/s | of triad | pass reads B/node | with re-reads: of triad | s/sweep 2 threads | GB/s | of triad | speed-up | of triad's | identical |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for path in &meshes {
        let mesh = verbss::io::read(path).expect("mesh");
        let d = mesh.dim;
        let roles = default_roles(&mesh);
        let mut u0 = vec![0.0; mesh.coords.len()];
        for i in mesh.group(&moving).expect("group").nodes() {
            u0[d * i..d * (i + 1)].copy_from_slice(&translate[..d]);
        }
        let unknown = roles.iter().filter(|r| **r == NodeRole::Free).count();
        let one = sweeps(&mesh, &roles, &u0, 1, count, repeat);
        let two = sweeps(&mesh, &roles, &u0, 2, count, repeat);
        let (s1, s2) = (one.seconds, two.seconds);
        let per_sweep = one.bytes * unknown as f64;
        let (b1, b2) = (per_sweep / s1, per_sweep / s2);
        let reread = (one.bytes - (8 * d) as f64 + one.pass_reads) * unknown as f64 / s1;
        println!(
            "| {} | {unknown} | {:.0} | {:.1} | {s1:.3e} | {:.2} | {:.0}% | {:.0} | {:.0}% | {s2:.3e} | {:.2} | {:.0}% | {:.2} | {:.0}% | {} |",
            path.file_name().unwrap().to_string_lossy(),
            one.bytes,
            per_sweep / 1e6,
            b1 / 1e9,
            100.0 * b1 / t1,
            one.pass_reads,
            100.0 * reread / t1,
            b2 / 1e9,
            100.0 * b2 / t2,
            s1 / s2,
            100.0 * (s1 / s2) / (t2 / t1),
            if one.last == two.last { "yes" } else { "NO" },
        );
    }
}
