//! Sliding nodes: their normal component is kept by every solver.

use verbss::solve::{default_roles, Engine, Method, NodeRole, Solver, Stage};
use verbss::Mesh;

use crate::grid::{grid, Layout};
use crate::{amg, direct_solution, params, rel_diff, solve, wavy_boundary, METHODS};

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
