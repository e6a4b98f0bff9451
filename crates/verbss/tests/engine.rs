//! The deformation engine against the contract of docs/method.md: row sums,
//! translations, zero motion, thread independence, and VerBSS against the
//! exact (direct) ball-vertex solution on generated and real meshes.

use std::path::Path;

use verbss::solve::{
    default_roles, Accel, Engine, Method, NodeRole, SolveInfo, SolveParams, Solver, Stage,
    AUTO_AMG_NODES_2D, AUTO_AMG_NODES_3D, ERROR_FRACTION,
};
use verbss::springs::{assemble, Connectivity, Springs};
use verbss::topology::boundary_nodes;
use verbss::{CellKind, Cells, Mesh};

/// The element layouts of the generated meshes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Layout {
    Tri,
    Quad,
    MixedTriQuad,
    Tet,
    Hex,
    Wedge,
    Pyramid,
    /// Hexahedra, prism columns and cubes of six pyramids around a centre node.
    MixedHexWedgePyramid,
}

const LAYOUTS: [Layout; 8] = [
    Layout::Tri,
    Layout::Quad,
    Layout::MixedTriQuad,
    Layout::Tet,
    Layout::Hex,
    Layout::Wedge,
    Layout::Pyramid,
    Layout::MixedHexWedgePyramid,
];

/// A deterministic number in [−0.5, 0.5) from a node's grid index.
fn jitter(seed: usize) -> f64 {
    let mut h = (seed as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    h ^= h >> 29;
    h = h.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h ^= h >> 32;
    (h % 1_000_000) as f64 / 1_000_000.0 - 0.5
}

/// A structured grid of `n` cells per side on the unit square or cube, cells
/// split according to `layout`, interior grid nodes moved by up to ±10 % of a
/// cell.
fn grid(layout: Layout, n: usize) -> Mesh {
    let dim = match layout {
        Layout::Tri | Layout::Quad | Layout::MixedTriQuad => 2,
        _ => 3,
    };
    let h = 1.0 / n as f64;
    let side = n + 1;
    let count = side.pow(dim as u32);
    let mut coords = Vec::with_capacity(dim * count);
    for id in 0..count {
        let ijk = [id % side, (id / side) % side, id / (side * side)];
        let interior = ijk[..dim].iter().all(|&v| v > 0 && v < n);
        for (axis, &v) in ijk[..dim].iter().enumerate() {
            let shift = if interior {
                0.2 * h * jitter(dim * id + axis)
            } else {
                0.0
            };
            coords.push(v as f64 * h + shift);
        }
    }
    let node = |i: usize, j: usize, k: usize| i + side * (j + side * k);
    let mut cells = Cells::new();
    for k in 0..if dim == 3 { n } else { 1 } {
        for j in 0..n {
            for i in 0..n {
                if dim == 2 {
                    let q = [
                        node(i, j, 0),
                        node(i + 1, j, 0),
                        node(i + 1, j + 1, 0),
                        node(i, j + 1, 0),
                    ];
                    let quad =
                        layout == Layout::Quad || (layout == Layout::MixedTriQuad && i < n / 2);
                    if quad {
                        cells.push(CellKind::Quad, &q);
                    } else {
                        cells.push(CellKind::Triangle, &[q[0], q[1], q[2]]);
                        cells.push(CellKind::Triangle, &[q[0], q[2], q[3]]);
                    }
                    continue;
                }
                let v = |b: usize| node(i + (b & 1), j + ((b >> 1) & 1), k + (b >> 2));
                // Hexahedron numbering: bottom 0 1 2 3, top 4 5 6 7.
                let hex = [v(0), v(1), v(3), v(2), v(4), v(5), v(7), v(6)];
                let kind = match layout {
                    Layout::MixedHexWedgePyramid => match (i + j) % 3 {
                        0 => Layout::Hex,
                        1 => Layout::Wedge,
                        _ => Layout::Pyramid,
                    },
                    other => other,
                };
                match kind {
                    Layout::Hex => cells.push(CellKind::Hexahedron, &hex),
                    Layout::Wedge => {
                        cells.push(
                            CellKind::Wedge,
                            &[hex[0], hex[1], hex[2], hex[4], hex[5], hex[6]],
                        );
                        cells.push(
                            CellKind::Wedge,
                            &[hex[0], hex[2], hex[3], hex[4], hex[6], hex[7]],
                        );
                    }
                    Layout::Tet => {
                        // Six tetrahedra along the diagonal v(0)–v(7), one per axis order.
                        for axes in [
                            [0, 1, 2],
                            [0, 2, 1],
                            [1, 0, 2],
                            [1, 2, 0],
                            [2, 0, 1],
                            [2, 1, 0],
                        ] {
                            let a = 1 << axes[0];
                            let b = a | (1 << axes[1]);
                            cells.push(CellKind::Tetra, &[v(0), v(a), v(b), v(7)]);
                        }
                    }
                    _ => {
                        let centre = coords.len() / 3;
                        for axis in 0..3 {
                            let mid = (0..8).map(|b| coords[3 * v(b) + axis]).sum::<f64>() / 8.0;
                            coords.push(mid);
                        }
                        for face in [
                            [0, 3, 2, 1],
                            [4, 5, 6, 7],
                            [0, 1, 5, 4],
                            [1, 2, 6, 5],
                            [2, 3, 7, 6],
                            [3, 0, 4, 7],
                        ] {
                            let f = face.map(|l| hex[l]);
                            cells.push(CellKind::Pyramid, &[f[0], f[1], f[2], f[3], centre]);
                        }
                    }
                }
            }
        }
    }
    Mesh::new(dim, coords, cells, vec![]).unwrap()
}

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

#[test]
fn coupling_rows_sum_to_the_diagonal() {
    for layout in LAYOUTS {
        let mesh = grid(layout, 3);
        let conn = Connectivity::new(&mesh);
        let boundary = boundary_nodes(&mesh);
        let order: Vec<usize> = (0..mesh.node_count()).filter(|&i| !boundary[i]).collect();
        let mut position = vec![u32::MAX; mesh.node_count()];
        for (p, &i) in order.iter().enumerate() {
            position[i] = p as u32;
        }
        let s = mesh.dim * (mesh.dim + 1) / 2;
        for springs in [Springs::Edge, Springs::BallVertex] {
            let b = assemble(&conn, &mesh.coords, &order, &position, springs).unwrap();
            for p in 0..order.len() {
                let mut sum = vec![0.0; s];
                let rows = [
                    (&b.blocks, b.offsets[p]..b.offsets[p + 1]),
                    (&b.fixed_blocks, b.fixed_offsets[p]..b.fixed_offsets[p + 1]),
                ];
                for (blocks, range) in rows {
                    for e in range {
                        for k in 0..s {
                            sum[k] += blocks[s * e + k];
                        }
                    }
                }
                let diag = &b.diag[s * p..s * (p + 1)];
                let scale = diag.iter().map(|v| v.abs()).fold(0.0, f64::max);
                for k in 0..s {
                    assert!(
                        (sum[k] - diag[k]).abs() <= 1e-13 * scale,
                        "{layout:?} {springs:?} row {p}: {sum:?} vs {diag:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_common_translation_moves_every_node() {
    for layout in LAYOUTS {
        let mesh = grid(layout, 3);
        let roles = default_roles(&mesh);
        let shift = [0.3, -0.2, 0.1];
        for (method, solver) in METHODS {
            let mut u = vec![0.0; mesh.coords.len()];
            for i in 0..mesh.node_count() {
                if roles[i] == NodeRole::Fixed {
                    u[mesh.dim * i..mesh.dim * (i + 1)].copy_from_slice(&shift[..mesh.dim]);
                }
            }
            let info = solve(&mesh, &roles, &[], &mut u, &params(method, solver, 1e-12));
            assert!(info.converged, "{layout:?} {method:?} {solver:?}");
            let err = (0..u.len())
                .map(|k| (u[k] - shift[k % mesh.dim]).abs())
                .fold(0.0, f64::max);
            let bound = if solver == Solver::Direct && method == Method::BallVertex {
                1e-14
            } else {
                1e-9
            };
            assert!(err < bound, "{layout:?} {method:?} {solver:?}: {err}");
        }
    }
}

#[test]
fn zero_motion_gives_zero_displacement() {
    for layout in [Layout::MixedTriQuad, Layout::MixedHexWedgePyramid] {
        let mesh = grid(layout, 3);
        let roles = default_roles(&mesh);
        for (method, solver) in METHODS {
            let mut u = vec![0.0; mesh.coords.len()];
            let info = solve(&mesh, &roles, &[], &mut u, &params(method, solver, 1e-6));
            assert!(
                info.converged && info.iterations == 1,
                "{method:?}: {info:?}"
            );
            assert!(
                u.iter().all(|&v| v == 0.0),
                "{layout:?} {method:?} {solver:?}"
            );
        }
    }
}

#[test]
fn a_mesh_without_unknowns_keeps_its_prescribed_values() {
    let mesh = grid(Layout::Hex, 1);
    let roles = default_roles(&mesh);
    assert!(roles.iter().all(|&r| r == NodeRole::Fixed));
    for (method, solver) in METHODS {
        let mut u: Vec<f64> = (0..mesh.coords.len()).map(|k| k as f64).collect();
        let before = u.clone();
        let info = solve(&mesh, &roles, &[], &mut u, &params(method, solver, 1e-6));
        assert!(
            info.converged && info.iterations == 0,
            "{method:?}: {info:?}"
        );
        assert_eq!(u, before);
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    for mesh in [grid(Layout::MixedTriQuad, 64), grid(Layout::Hex, 16)] {
        let roles = default_roles(&mesh);
        let u0 = wavy_boundary(&mesh);
        for (method, solver) in METHODS {
            let runs = thread_runs(&mesh, &roles, &u0, params(method, solver, 1e-5));
            for (u, info) in &runs[1..] {
                assert!(u == &runs[0].0, "{method:?}");
                assert_eq!(info.history, runs[0].1.history, "{method:?}");
            }
            let sweeps = if solver == Solver::Direct { 1 } else { 6 };
            assert!(runs[0].1.converged && runs[0].1.iterations >= sweeps);
        }
    }
}

#[test]
fn verbss_converges_to_the_direct_ball_vertex_solution() {
    for layout in LAYOUTS {
        let mesh = grid(layout, 4);
        let roles = default_roles(&mesh);
        let exact = direct_solution(&mesh, &roles, &[], &wavy_boundary(&mesh));
        for (method, solver) in [
            (Method::Verbss, Solver::Sor),
            (Method::BallVertex, Solver::Sor),
        ] {
            let mut u = wavy_boundary(&mesh);
            let info = solve(&mesh, &roles, &[], &mut u, &params(method, solver, 1e-13));
            assert!(info.converged, "{layout:?} {method:?}");
            let rel = rel_diff(&u, &exact);
            assert!(rel < 1e-8, "{layout:?} {method:?}: {rel}");
        }
    }
}

#[test]
fn the_multigrid_accelerated_solve_converges_to_the_direct_solution() {
    for layout in LAYOUTS {
        let n = match layout {
            Layout::Tri | Layout::Quad | Layout::MixedTriQuad => 40,
            _ => 10,
        };
        let mesh = grid(layout, n);
        let roles = default_roles(&mesh);
        let exact = direct_solution(&mesh, &roles, &[], &wavy_boundary(&mesh));
        let mut u = wavy_boundary(&mesh);
        let info = solve(&mesh, &roles, &[], &mut u, &amg(1e-13));
        assert!(info.converged && info.levels >= 2, "{layout:?}: {info:?}");
        let rel = rel_diff(&u, &exact);
        assert!(rel < 1e-8, "{layout:?}: {rel}");
    }
}

fn amg(tolerance: f64) -> SolveParams {
    let mut p = params(Method::Verbss, Solver::Sor, tolerance);
    p.accel = Accel::Amg;
    p.max_iterations = 500;
    p
}

#[test]
fn accelerated_results_do_not_depend_on_the_thread_count() {
    for mesh in [grid(Layout::MixedTriQuad, 64), grid(Layout::Tet, 12)] {
        let roles = default_roles(&mesh);
        let u0 = wavy_boundary(&mesh);
        let runs = thread_runs(&mesh, &roles, &u0, amg(1e-9));
        assert!(runs[0].1.converged && runs[0].1.levels >= 2 && runs[0].1.iterations >= 3);
        for (u, info) in &runs[1..] {
            assert!(u == &runs[0].0);
            assert_eq!(info.history, runs[0].1.history);
        }
    }
}

#[test]
fn the_hierarchy_is_kept_while_the_mesh_moves_and_the_answer_stays_exact() {
    let mesh = grid(Layout::Tet, 10);
    let roles = default_roles(&mesh);
    let mut engine = Engine::new(&mesh, &roles, &[]).unwrap();
    let mut direct = Engine::new(&mesh, &roles, &[]).unwrap();
    let exact_params = params(Method::BallVertex, Solver::Direct, 0.0);
    let mut coords = mesh.coords.clone();
    let mut total = vec![0.0; coords.len()];
    for step in 1..=4 {
        let increment: Vec<f64> = wavy_boundary(&mesh).iter().map(|v| v / 4.0).collect();
        let mut u = increment.clone();
        let info = engine.solve(&coords, &mut u, &amg(1e-12)).unwrap();
        assert_eq!(info.hierarchy_built, step == 1, "step {step}");
        assert!(info.rebuilt && info.converged);
        let mut exact = increment;
        direct.solve(&coords, &mut exact, &exact_params).unwrap();
        let rel = rel_diff(&u, &exact);
        assert!(rel < 1e-8, "step {step}: {rel}");
        for k in 0..coords.len() {
            coords[k] += u[k];
            total[k] += u[k];
        }
    }
    assert!(total.iter().any(|&v| v != 0.0));
}

#[test]
fn auto_accelerates_large_simplex_meshes_only() {
    assert!(47usize.pow(3) >= AUTO_AMG_NODES_3D && 59usize.pow(2) >= AUTO_AMG_NODES_2D);
    for (layout, accelerated) in [
        (Layout::Tet, true),
        (Layout::Hex, false),
        (Layout::Tri, true),
        (Layout::Quad, false),
    ] {
        let mesh = grid(
            layout,
            if layout == Layout::Tri || layout == Layout::Quad {
                60
            } else {
                48
            },
        );
        let roles = default_roles(&mesh);
        let mut u = wavy_boundary(&mesh);
        let mut p = params(Method::Verbss, Solver::Sor, 1e-2);
        p.accel = Accel::Auto;
        // What `auto` chooses, without the escalation that a loose
        // tolerance would trigger.
        p.escalate = false;
        let info = solve(&mesh, &roles, &[], &mut u, &p);
        assert!(info.converged);
        assert_eq!(info.levels >= 2, accelerated, "{layout:?}: {info:?}");
    }
    for small in [grid(Layout::Tet, 20), grid(Layout::Tri, 40)] {
        let mut u = wavy_boundary(&small);
        let mut p = params(Method::Verbss, Solver::Sor, 1e-6);
        p.accel = Accel::Auto;
        assert_eq!(
            solve(&small, &default_roles(&small), &[], &mut u, &p).levels,
            0
        );
    }
}

/// Roles with the interior of the `x = 0` side sliding in its plane (normal
/// given as (−2, 0, 0): the engine normalises it), the rest of the boundary
/// fixed; the sliding nodes' entries hold normal component 0.01.
fn sliding_side(mesh: &Mesh, u: &mut [f64]) -> (Vec<NodeRole>, Vec<usize>) {
    let d = mesh.dim;
    let mut roles = default_roles(mesh);
    let mut sliding = Vec::new();
    let inside = |v: f64| v > 1e-9 && v < 1.0 - 1e-9;
    for i in 0..mesh.node_count() {
        let x = mesh.point(i);
        if x[0] == 0.0 && x[1..].iter().all(|&v| inside(v)) {
            roles[i] = NodeRole::Slide(0);
            u[d * i..d * (i + 1)].fill(0.0);
            u[d * i] = 0.01;
            sliding.push(i);
        }
    }
    (roles, sliding)
}

#[test]
fn sliding_nodes_keep_their_normal_component() {
    let normals = [[-2.0, 0.0, 0.0]];
    for layout in [Layout::MixedTriQuad, Layout::Hex, Layout::Tet] {
        let mesh = grid(layout, 4);
        let d = mesh.dim;
        let mut u = wavy_boundary(&mesh);
        let (roles, sliding) = sliding_side(&mesh, &mut u);
        let exact = direct_solution(&mesh, &roles, &normals, &u);
        for &i in &sliding {
            assert!((exact[d * i] - 0.01).abs() < 1e-15, "{layout:?} node {i}");
            assert!(exact[d * i + 1..d * (i + 1)].iter().all(|&v| v != 0.0));
        }
        for (method, solver) in [
            (Method::Verbss, Solver::Sor),
            (Method::BallVertex, Solver::Sor),
        ] {
            let mut v = u.clone();
            let info = solve(
                &mesh,
                &roles,
                &normals,
                &mut v,
                &params(method, solver, 1e-13),
            );
            assert!(info.converged);
            let rel = rel_diff(&v, &exact);
            assert!(rel < 1e-8, "{layout:?} {method:?}: {rel}");
        }
        let mut v = u.clone();
        let info = solve(&mesh, &roles, &normals, &mut v, &amg(1e-13));
        assert!(info.converged, "{layout:?} amg: {info:?}");
        let rel = rel_diff(&v, &exact);
        assert!(rel < 1e-8, "{layout:?} amg: {rel}");
        // The same on a mesh large enough for several levels.
        let big = grid(layout, if d == 2 { 24 } else { 8 });
        let mut w = wavy_boundary(&big);
        let (big_roles, big_sliding) = sliding_side(&big, &mut w);
        let big_exact = direct_solution(&big, &big_roles, &normals, &w);
        let info = solve(&big, &big_roles, &normals, &mut w, &amg(1e-13));
        assert!(info.converged && info.levels >= 2, "{layout:?}: {info:?}");
        assert!(rel_diff(&w, &big_exact) < 1e-8);
        for &i in &big_sliding {
            assert_eq!(w[d * i], 0.01, "{layout:?} node {i}");
        }
        // A translation along the sliding plane moves every node by it.
        let shift = [0.0, 0.2, -0.1];
        for (method, solver) in METHODS {
            let mut t = vec![0.0; mesh.coords.len()];
            for i in 0..mesh.node_count() {
                if roles[i] == NodeRole::Fixed {
                    t[d * i..d * (i + 1)].copy_from_slice(&shift[..d]);
                }
            }
            let info = solve(
                &mesh,
                &roles,
                &normals,
                &mut t,
                &params(method, solver, 1e-12),
            );
            assert!(info.converged);
            let err = (0..t.len())
                .map(|k| (t[k] - shift[k % d]).abs())
                .fold(0.0, f64::max);
            let bound = if solver == Solver::Direct {
                1e-14
            } else {
                1e-9
            };
            assert!(err < bound, "{layout:?} {method:?} {solver:?}: {err}");
        }
    }
}

#[test]
fn springs_are_rebuilt_only_when_the_reference_or_method_changes() {
    let mesh = grid(Layout::Tri, 6);
    let roles = default_roles(&mesh);
    let mut engine = Engine::new(&mesh, &roles, &[]).unwrap();
    let p = params(Method::Verbss, Solver::Sor, 1e-8);
    let mut u = wavy_boundary(&mesh);
    assert!(engine.solve(&mesh.coords, &mut u, &p).unwrap().rebuilt);
    assert!(engine.bytes_per_node() > 0.0);
    let mut v = wavy_boundary(&mesh);
    let again = engine.solve(&mesh.coords, &mut v, &p).unwrap();
    assert!(!again.rebuilt);
    assert_eq!(u, v);
    let moved: Vec<f64> = mesh.coords.iter().zip(&u).map(|(x, d)| x + d).collect();
    assert!(engine.solve(&moved, &mut v, &p).unwrap().rebuilt);
    let laplace = params(Method::Laplacian, Solver::Sor, 1e-8);
    assert!(engine.solve(&moved, &mut v, &laplace).unwrap().rebuilt);
}

#[test]
fn colour_passes_read_whole_lines_once_per_pass() {
    let read = |mesh: &Mesh, method: Method| {
        let mut engine = Engine::new(mesh, &default_roles(mesh), &[]).unwrap();
        assert_eq!(engine.colour_pass_read_bytes(), 0.0);
        let mut u = wavy_boundary(mesh);
        engine
            .solve(&mesh.coords, &mut u, &params(method, Solver::Sor, 1e-8))
            .unwrap();
        engine.colour_pass_read_bytes()
    };
    for method in [Method::Verbss, Method::Laplacian] {
        // One unknown node: one colour pass reads its own line.
        assert_eq!(read(&grid(Layout::Tri, 2), method), 64.0);
        // Four unknown nodes (2 × 8 bytes each) share one line, which each
        // of the 2 to 4 colour passes reads once.
        let four = read(&grid(Layout::Tri, 3), method);
        assert!([32.0, 48.0, 64.0].contains(&four), "{method:?}: {four}");
        // In 3D every pass reads lines of the other colours: more than the
        // one read of 24 bytes per node, less than a line per coupling.
        let tets = read(&grid(Layout::Tet, 6), method);
        assert!(tets > 24.0 && tets < 64.0 * 30.0, "{method:?}: {tets}");
    }
}

#[test]
fn bad_input_is_reported() {
    let mesh = grid(Layout::Quad, 2);
    let roles = default_roles(&mesh);
    let msg = |r: Result<Engine, verbss::Error>| r.err().unwrap().to_string();
    assert_eq!(
        msg(Engine::new(&mesh, &roles[1..], &[])),
        "invalid setting: 8 node roles for 9 nodes"
    );
    let free = vec![NodeRole::Free; 9];
    assert_eq!(
        msg(Engine::new(&mesh, &free, &[])),
        "invalid setting: node 1 is not connected to any fixed node (its displacement would \
         be undetermined)"
    );
    let mut slide = roles.clone();
    slide[4] = NodeRole::Slide(1);
    assert_eq!(
        msg(Engine::new(&mesh, &slide, &[[1.0, 0.0, 0.0]])),
        "invalid setting: node 5 slides on normal 1 but 1 normals were given"
    );
    assert_eq!(
        msg(Engine::new(&mesh, &roles, &[[0.0, 0.0, 7.0]])),
        "invalid setting: sliding normal 0 is zero or not finite"
    );
    let mut engine = Engine::new(&mesh, &roles, &[]).unwrap();
    let mut u = vec![0.0; 18];
    let mut p = SolveParams::default();
    let e = engine.solve(&mesh.coords[2..], &mut u, &p).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: 16 coordinates for 9 nodes in 2D (expected 18)"
    );
    u[5] = f64::NAN;
    let e = engine.solve(&mesh.coords, &mut u, &p).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: displacements of node 3 are not finite"
    );
    u[5] = 0.0;
    p.omega = 2.0;
    let e = engine.solve(&mesh.coords, &mut u, &p).unwrap_err();
    assert_eq!(e.to_string(), "invalid setting: omega 2 is outside (0, 2)");
    p.omega = 1.5;
    let mut laplace = params(Method::Laplacian, Solver::Sor, 1e-6);
    laplace.accel = Accel::Amg;
    let e = engine.solve(&mesh.coords, &mut u, &laplace).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: accel amg solves the block systems of method verbss and spring \
         (not ball-vertex or laplacian)"
    );
    let mut flat = mesh.coords.clone();
    flat[8] = flat[2];
    flat[9] = flat[3];
    let e = engine.solve(&flat, &mut u, &p).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid mesh: nodes 5 and 2 coincide (an edge of zero length)"
    );
}

// ---- real meshes -------------------------------------------------------------

fn real(name: &str) -> Mesh {
    let path = format!(
        "{}/../../assets/meshes/su2/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    verbss::io::read(Path::new(&path)).unwrap()
}

/// Displacement rotating the nodes of `group` by `degrees` about `centre`
/// (in the x–y plane), zero elsewhere.
fn rotate_group(mesh: &Mesh, group: &str, degrees: f64, centre: [f64; 2]) -> Vec<f64> {
    let (s, c) = degrees.to_radians().sin_cos();
    let d = mesh.dim;
    let mut u = vec![0.0; mesh.coords.len()];
    for i in mesh.group(group).unwrap().nodes() {
        let x = mesh.point(i);
        let (dx, dy) = (x[0] - centre[0], x[1] - centre[1]);
        u[d * i] = centre[0] + c * dx - s * dy - x[0];
        u[d * i + 1] = centre[1] + s * dx + c * dy - x[1];
    }
    u
}

/// VerBSS at a tight tolerance against the direct solution, for each motion
/// (one engine per method, so the LU factors are computed once).
fn check_against_direct(mesh: &Mesh, motions: &[Vec<f64>]) {
    let roles = default_roles(mesh);
    let mut direct = Engine::new(mesh, &roles, &[]).unwrap();
    let mut verbss = Engine::new(mesh, &roles, &[]).unwrap();
    let mut accelerated = Engine::new(mesh, &roles, &[]).unwrap();
    for u0 in motions {
        let mut exact = u0.clone();
        direct
            .solve(
                &mesh.coords,
                &mut exact,
                &params(Method::BallVertex, Solver::Direct, 0.0),
            )
            .unwrap();
        let mut u = u0.clone();
        let info = verbss
            .solve(
                &mesh.coords,
                &mut u,
                &params(Method::Verbss, Solver::Sor, 1e-12),
            )
            .unwrap();
        assert!(info.converged, "{info:?}");
        let rel = rel_diff(&u, &exact);
        assert!(
            rel < 1e-8,
            "relative difference {rel} after {} sweeps",
            info.iterations
        );
        let mut v = u0.clone();
        let info = accelerated
            .solve(&mesh.coords, &mut v, &amg(1e-13))
            .unwrap();
        assert!(info.converged && info.levels >= 2, "{info:?}");
        let rel = rel_diff(&v, &exact);
        assert!(rel < 1e-8, "accelerated: relative difference {rel}");
    }
}

#[test]
fn naca0012_rotated_5_degrees() {
    let mesh = real("mesh_NACA0012_inv.su2");
    check_against_direct(&mesh, &[rotate_group(&mesh, "airfoil", 5.0, [0.25, 0.0])]);
}

#[test]
fn rae2822_hybrid_rotated_2_degrees() {
    let mesh = real("mesh_RAE2822_turb_ffd.su2");
    check_against_direct(&mesh, &[rotate_group(&mesh, "AIRFOIL", 2.0, [0.25, 0.0])]);
}

/// The `z_p` face of a brick on [0,2]×[0,1]×[0,1] lifted by 0.1, or twisted
/// by 10° about the box's long axis (y = z = 0.5).
fn brick_motions(mesh: &Mesh) -> [Vec<f64>; 2] {
    let mut lift = vec![0.0; mesh.coords.len()];
    let mut twist = vec![0.0; mesh.coords.len()];
    let (s, c) = 10f64.to_radians().sin_cos();
    for i in mesh.group("z_p").unwrap().nodes() {
        let x = mesh.point(i);
        lift[3 * i + 2] = 0.1;
        let (dy, dz) = (x[1] - 0.5, x[2] - 0.5);
        twist[3 * i + 1] = 0.5 + c * dy - s * dz - x[1];
        twist[3 * i + 2] = 0.5 + s * dy + c * dz - x[2];
    }
    [lift, twist]
}

#[test]
fn tet_brick_lifted_and_twisted() {
    let mesh = real("mesh_brick_tets_ffd.su2");
    check_against_direct(&mesh, &brick_motions(&mesh));
}

#[test]
fn hex_brick_lifted_and_twisted() {
    let mesh = real("mesh_brick_hex_ffd.su2");
    check_against_direct(&mesh, &brick_motions(&mesh));
}

#[test]
fn diverging_sweeps_are_reported() {
    // The ball-vertex system is not symmetric: SOR need not converge for every
    // ω in (0, 2). On this mesh ω = 1.95 diverges.
    let mesh = real("mesh_NACA0012_inv.su2");
    let u0 = rotate_group(&mesh, "airfoil", 5.0, [0.25, 0.0]);
    let mut u = u0.clone();
    let mut p = params(Method::Verbss, Solver::Sor, 1e-6);
    p.omega = 1.95;
    p.escalate = false;
    let mut engine = Engine::new(&mesh, &default_roles(&mesh), &[]).unwrap();
    let info = engine.solve(&mesh.coords, &mut u, &p).unwrap();
    assert!(info.diverged && !info.converged, "{info:?}");
    assert_eq!(info.stages, [Stage::Sweeps]);
    assert_eq!(u, u0, "a diverged solve leaves the initial guess");
}

#[test]
fn diverging_sweeps_escalate_to_the_exact_answer() {
    let mesh = real("mesh_NACA0012_inv.su2");
    let u0 = rotate_group(&mesh, "airfoil", 5.0, [0.25, 0.0]);
    let roles = default_roles(&mesh);
    let mut p = params(Method::Verbss, Solver::Sor, 1e-6);
    p.omega = 1.95;
    let mut engine = Engine::new(&mesh, &roles, &[]).unwrap();
    let mut u = u0.clone();
    let info = engine.solve(&mesh.coords, &mut u, &p).unwrap();
    assert!(info.converged, "{info:?}");
    assert_eq!(info.stages[0], Stage::Sweeps);
    assert!(info.stages.len() >= 2, "{info:?}");
    assert!(info.error_ratio <= ERROR_FRACTION, "{info:?}");
    let mut exact = u0.clone();
    let direct = params(Method::BallVertex, Solver::Direct, 1e-6);
    let mut reference = Engine::new(&mesh, &roles, &[]).unwrap();
    reference.solve(&mesh.coords, &mut exact, &direct).unwrap();
    let scale = u0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let worst = u
        .iter()
        .zip(&exact)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(worst < 1e-4 * scale, "{worst:e} against {scale:e}");
}

#[test]
fn the_laplacian_direct_solve_matches_its_converged_sweeps() {
    let normals = [[-2.0, 0.0, 0.0]];
    for layout in [Layout::MixedTriQuad, Layout::Hex, Layout::Tet] {
        let mesh = grid(layout, 4);
        let mut u = wavy_boundary(&mesh);
        let (roles, sliding) = sliding_side(&mesh, &mut u);
        let mut p = params(Method::Laplacian, Solver::Sor, 1e-14);
        p.escalate = false;
        let mut swept = u.clone();
        assert!(solve(&mesh, &roles, &normals, &mut swept, &p).converged);
        let mut exact = u.clone();
        let mut engine = Engine::new(&mesh, &roles, &normals).unwrap();
        let info = engine.solve_exact(&mesh.coords, &mut exact, &p).unwrap();
        assert_eq!(info.stages, [Stage::Direct], "{layout:?}");
        assert!(info.converged && info.error_ratio < 1e-10, "{info:?}");
        let rel = rel_diff(&exact, &swept);
        assert!(rel < 1e-9, "{layout:?}: {rel}");
        let d = mesh.dim;
        for &i in &sliding {
            assert!((exact[d * i] - 0.01).abs() < 1e-15, "{layout:?} node {i}");
        }
    }
}
