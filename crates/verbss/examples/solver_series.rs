//! Sweeps and seconds per step of `verbss` against `ball-vertex` with scalar
//! SOR and with the direct solver, on a series of 2D meshes (a square with a
//! rectangular body, as the paper's §4.1, ≈300 to ≈21,000 nodes) and 3D meshes
//! (a cube with a cubic body, tetrahedra), measured side by side in one run.
//!
//! ```sh
//! cargo run --release -p verbss --example solver_series            # full series
//! cargo run --release -p verbss --example solver_series -- --quick # smoke run
//! ```
//!
//! Each mesh: the body moves by 1 unit (2D: along y; 3D: along x) in one
//! step, every other boundary node is fixed; tolerance 1e-6 relative to the
//! motion, ω = 1.6 for both sweeping methods. The "error" column is the
//! relative distance ‖u − u_direct‖/‖u_direct‖ to the exact solution.

use std::time::Instant;

use verbss::mesh::{CellKind, Cells, Mesh};
use verbss::solve::{default_roles, Engine, Method, SolveParams, Solver};
use verbss::topology;

/// A structured mesh of `[-h, h]^D` with `n` cells a side and the body
/// `|x| < b` removed; 2D cells split into triangles, 3D cells into 6 tetrahedra.
fn box_with_body(dim: usize, n: usize, h: f64, b: f64) -> (Mesh, Vec<bool>) {
    let step = 2.0 * h / n as f64;
    let x = |i: usize| -h + step * i as f64;
    let nn = n + 1;
    let id = |i: usize, j: usize, k: usize| i + nn * (j + nn * k);
    let inside = |c: &[usize]| c.iter().all(|&i| (x(i) + 0.5 * step).abs() < b);
    let mut cells = Cells::new();
    let kmax = if dim == 2 { 1 } else { n };
    for k in 0..kmax {
        for j in 0..n {
            for i in 0..n {
                let centre: Vec<usize> = if dim == 2 { vec![i, j] } else { vec![i, j, k] };
                if inside(&centre) {
                    continue;
                }
                if dim == 2 {
                    let q = [
                        id(i, j, 0),
                        id(i + 1, j, 0),
                        id(i + 1, j + 1, 0),
                        id(i, j + 1, 0),
                    ];
                    if (i + j) % 2 == 0 {
                        cells.push(CellKind::Triangle, &[q[0], q[1], q[2]]);
                        cells.push(CellKind::Triangle, &[q[0], q[2], q[3]]);
                    } else {
                        cells.push(CellKind::Triangle, &[q[0], q[1], q[3]]);
                        cells.push(CellKind::Triangle, &[q[1], q[2], q[3]]);
                    }
                } else {
                    let v = |a: usize, b: usize, c: usize| id(i + a, j + b, k + c);
                    let (p0, p1, p2, p3) = (v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0));
                    let (p4, p5, p6, p7) = (v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1));
                    for t in [
                        [p0, p1, p2, p6],
                        [p0, p2, p3, p6],
                        [p0, p3, p7, p6],
                        [p0, p7, p4, p6],
                        [p0, p4, p5, p6],
                        [p0, p5, p1, p6],
                    ] {
                        cells.push(CellKind::Tetra, &t);
                    }
                }
            }
        }
    }
    // Keep only the nodes the cells use.
    let total = nn.pow(dim as u32);
    let mut new_index = vec![usize::MAX; total];
    let mut coords = Vec::new();
    for old in cells.nodes.iter_mut() {
        if new_index[*old] == usize::MAX {
            new_index[*old] = coords.len() / dim;
            let (i, j, k) = (*old % nn, (*old / nn) % nn, *old / (nn * nn));
            coords.extend_from_slice(&[x(i), x(j), x(k)][..dim]);
        }
        *old = new_index[*old];
    }
    let mesh = Mesh::new(dim, coords, cells, vec![]).expect("valid structured mesh");
    // Body nodes: boundary nodes strictly inside the outer box.
    let mut body = vec![false; mesh.node_count()];
    for &nd in &topology::boundary_facets(&mesh.cells).nodes {
        body[nd] = mesh.point(nd).iter().all(|c| c.abs() < h - 0.5 * step);
    }
    (mesh, body)
}

/// One step from scratch (a fresh engine: forming + solving), as option 1 does every step.
/// Returns the solution, the sweeps, the seconds and the solver's bytes per unknown node.
fn solve(mesh: &Mesh, prescribed: &[f64], params: &SolveParams) -> (Vec<f64>, usize, f64, f64) {
    let roles = default_roles(mesh);
    let mut engine = Engine::new(mesh, &roles, &[]).expect("engine");
    let mut u = prescribed.to_vec();
    let t = Instant::now();
    let info = engine.solve(&mesh.coords, &mut u, params).expect("solve");
    let seconds = t.elapsed().as_secs_f64();
    (u, info.iterations, seconds, engine.bytes_per_node())
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let n: f64 = b.iter().map(|y| y * y).sum();
    (d / n).sqrt()
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let series: Vec<(usize, usize)> = if quick {
        vec![(2, 16), (3, 8)]
    } else {
        vec![
            (2, 16),
            (2, 32),
            (2, 56),
            (2, 92),
            (2, 150),
            (3, 22),
            (3, 32),
            (3, 46),
        ]
    };
    println!("| D | nodes | cells | verbss sweeps | verbss s | SOR sweeps | SOR s | direct s | SOR/verbss | verbss error | verbss bytes/node |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (dim, n) in series {
        let (mesh, body) = box_with_body(dim, n, 10.0, if dim == 2 { 2.0 } else { 2.5 });
        let mut prescribed = vec![0.0; mesh.coords.len()];
        for (i, _) in body.iter().enumerate().filter(|(_, b)| **b) {
            prescribed[dim * i + if dim == 2 { 1 } else { 0 }] = 1.0;
        }
        let mut params = SolveParams::default();
        params.tolerance = 1e-6;
        params.max_iterations = 20_000;
        params.method = Method::BallVertex;
        params.solver = Solver::Direct;
        let (exact, _, direct_s, _) = solve(&mesh, &prescribed, &params);
        params.solver = Solver::Sor;
        let (_, sor_it, sor_s, _) = solve(&mesh, &prescribed, &params);
        params.method = Method::Verbss;
        let (u, vb_it, vb_s, bytes) = solve(&mesh, &prescribed, &params);
        println!(
            "| {dim} | {} | {} | {vb_it} | {vb_s:.4} | {sor_it} | {sor_s:.4} | {direct_s:.4} | {:.1} | {:.1e} | {bytes:.0} |",
            mesh.node_count(),
            mesh.cell_count(),
            sor_s / vb_s,
            rel(&u, &exact)
        );
    }
}
