//! The deformation engine against the contract of docs/method.md: row sums,
//! translations, zero motion, thread independence, and VerBSS against the
//! exact (direct) ball-vertex solution on generated and real meshes.
//!
//! The meshes are the structured grids of [`grid`] and the SU2 meshes of
//! `assets/meshes/su2` ([`real`]); the helpers below are shared by every file.

mod accel;
mod contract;
mod grid;
mod real;
mod sliding;
mod state;

use verbss::solve::{Accel, Engine, Method, NodeRole, SolveInfo, SolveParams, Solver};
use verbss::topology::boundary_nodes;
use verbss::Mesh;

fn params(method: Method, solver: Solver, tolerance: f64) -> SolveParams {
    let mut p = SolveParams::default();
    p.method = method;
    p.solver = solver;
    p.tolerance = tolerance;
    p.max_iterations = 200_000;
    p
}

/// Every method and global solver.
const METHODS: [(Method, Solver); 5] = [
    (Method::Verbss, Solver::Sor),
    (Method::BallVertex, Solver::Sor),
    (Method::BallVertex, Solver::Direct),
    (Method::Spring, Solver::Sor),
    (Method::Laplacian, Solver::Sor),
];

/// A smooth, non-affine displacement of every boundary node; zero elsewhere.
fn wavy_boundary(mesh: &Mesh) -> Vec<f64> {
    let d = mesh.dim;
    let boundary = boundary_nodes(mesh);
    let mut u = vec![0.0; mesh.coords.len()];
    for i in 0..mesh.node_count() {
        if boundary[i] {
            let x = mesh.point(i);
            for k in 0..d {
                u[d * i + k] = 0.05 * (3.0 * x[(k + 1) % d] + k as f64).sin() * x[k];
            }
        }
    }
    u
}

fn solve(
    mesh: &Mesh,
    roles: &[NodeRole],
    normals: &[[f64; 3]],
    u: &mut [f64],
    p: &SolveParams,
) -> SolveInfo {
    let mut engine = Engine::new(mesh, roles, normals).unwrap();
    engine.solve(&mesh.coords, u, p).unwrap()
}

/// The exact (direct) ball-vertex solution for the initial values `u0`.
fn direct_solution(mesh: &Mesh, roles: &[NodeRole], normals: &[[f64; 3]], u0: &[f64]) -> Vec<f64> {
    let mut exact = u0.to_vec();
    let p = params(Method::BallVertex, Solver::Direct, 0.0);
    solve(mesh, roles, normals, &mut exact, &p);
    exact
}

/// `p` solved with 1, 2 and 3 threads (a fresh engine each time, so that the
/// direct solver factors anew), sweep histories recorded.
fn thread_runs(
    mesh: &Mesh,
    roles: &[NodeRole],
    u0: &[f64],
    mut p: SolveParams,
) -> Vec<(Vec<f64>, SolveInfo)> {
    p.record_history = true;
    [1, 2, 3]
        .into_iter()
        .map(|threads| {
            p.threads = threads;
            let mut u = u0.to_vec();
            let info = solve(mesh, roles, &[], &mut u, &p);
            (u, info)
        })
        .collect()
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let size: f64 = b.iter().map(|y| y * y).sum();
    (diff / size).sqrt()
}

fn amg(tolerance: f64) -> SolveParams {
    let mut p = params(Method::Verbss, Solver::Sor, tolerance);
    p.accel = Accel::Amg;
    p.max_iterations = 500;
    p
}
