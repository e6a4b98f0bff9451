//! The kernels of one step, timed by criterion on the repository's meshes:
//! spring assembly (edge + ball-vertex blocks of every unknown node), one
//! VerBSS sweep (1 and 2 threads, springs and factors already formed) and the
//! quality of every element.
//!
//! ```sh
//! cargo bench -p verbss --bench kernels            # measure
//! cargo test -p verbss --benches                   # run each once (a check)
//! ```
//!
//! Meshes: the tetrahedral brick (11,703 nodes, 59,156 tetrahedra; its `x_m`
//! face moves by 0.1 along x, every other face fixed) and the NACA0012
//! triangles (5,233 nodes; the airfoil moves by 0.05 along y). The big 3D
//! series is bench/compare.py's (sweeps per step, seconds per sweep, the
//! triad: examples/sweep_bandwidth.rs).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use verbss::mesh::Mesh;
use verbss::solve::{default_roles, Engine, NodeRole, SolveParams};
use verbss::springs::{assemble, Connectivity, Springs};

/// A repository mesh, its default roles and a displacement moving `group` by `by`.
fn case(file: &str, group: &str, by: [f64; 3]) -> (Mesh, Vec<NodeRole>, Vec<f64>) {
    let path = format!(
        "{}/../../assets/meshes/su2/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    let mesh = verbss::io::read(std::path::Path::new(&path)).expect("mesh");
    let roles = default_roles(&mesh);
    let d = mesh.dim;
    let mut u = vec![0.0; mesh.coords.len()];
    for i in mesh.group(group).expect("group").nodes() {
        u[d * i..d * (i + 1)].copy_from_slice(&by[..d]);
    }
    (mesh, roles, u)
}

fn cases() -> Vec<(&'static str, Mesh, Vec<NodeRole>, Vec<f64>)> {
    let (m3, r3, u3) = case("mesh_brick_tets_ffd.su2", "x_m", [0.1, 0.0, 0.0]);
    let (m2, r2, u2) = case("mesh_NACA0012_inv.su2", "airfoil", [0.0, 0.05, 0.0]);
    vec![("brick_tets", m3, r3, u3), ("naca0012", m2, r2, u2)]
}

fn springs(c: &mut Criterion) {
    for (name, mesh, roles, _) in cases() {
        let conn = Connectivity::new(&mesh);
        let order: Vec<usize> = (0..roles.len())
            .filter(|&i| roles[i] == NodeRole::Free)
            .collect();
        let mut position = vec![u32::MAX; roles.len()];
        for (p, &i) in order.iter().enumerate() {
            position[i] = p as u32;
        }
        c.bench_function(&format!("assemble/{name}"), |b| {
            b.iter(|| {
                assemble(
                    &conn,
                    black_box(&mesh.coords),
                    &order,
                    &position,
                    Springs::BallVertex,
                )
                .expect("assemble")
            })
        });
    }
}

fn sweep(c: &mut Criterion) {
    for (name, mesh, roles, u0) in cases() {
        for threads in [1, 2] {
            let mut engine = Engine::new(&mesh, &roles, &[]).expect("engine");
            let mut p = SolveParams::default();
            p.tolerance = 0.0;
            p.max_iterations = 1;
            p.threads = threads;
            let mut u = u0.clone();
            engine.solve(&mesh.coords, &mut u, &p).expect("build");
            c.bench_function(&format!("sweep/{name}/{threads}t"), |b| {
                b.iter(|| {
                    let info = engine.solve(&mesh.coords, &mut u, &p).expect("sweep");
                    assert!(!info.rebuilt);
                    black_box(info.residual)
                })
            });
        }
    }
}

fn quality(c: &mut Criterion) {
    for (name, mesh, _, _) in cases() {
        let orientation = verbss::quality::orientation(&mesh);
        c.bench_function(&format!("quality/{name}"), |b| {
            b.iter(|| verbss::quality::qualities(&mesh, black_box(&mesh.coords), &orientation))
        });
    }
}

criterion_group! {
    name = kernels;
    config = Criterion::default().sample_size(20);
    targets = springs, sweep, quality
}
criterion_main!(kernels);
