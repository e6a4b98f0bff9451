//! The multigrid-accelerated solve: exactness, thread independence, the kept
//! hierarchy and what `auto` chooses.

use verbss::solve::{default_roles, Accel, Engine, Method, Solver, Stage, AUTO_SWEEPS};

use crate::grid::{grid, Layout, LAYOUTS};
use crate::{amg, direct_solution, params, rel_diff, solve, thread_runs, wavy_boundary};

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

/// `auto` sweeps while they finish within AUTO_SWEEPS; on simplex meshes
/// a step they do not finish goes to the multigrid, which keeps its
/// hierarchy and solves the next step from the start.
#[test]
fn auto_hands_a_step_the_sweeps_do_not_finish_to_the_multigrid_on_simplex_meshes() {
    for (layout, n, simplex) in [
        (Layout::Tet, 24, true),
        (Layout::Hex, 24, false),
        (Layout::Tri, 60, true),
        (Layout::Quad, 60, false),
    ] {
        let mesh = grid(layout, n);
        let roles = default_roles(&mesh);
        let mut engine = Engine::new(&mesh, &roles, &[]).unwrap();
        let mut p = params(Method::Verbss, Solver::Sor, 1e-10);
        p.accel = Accel::Auto;
        // What `auto` chooses, without the escalation.
        p.escalate = false;
        let mut u = wavy_boundary(&mesh);
        let first = engine.solve(&mesh.coords, &mut u, &p).unwrap();
        assert!(first.converged, "{layout:?}: {first:?}");
        assert!(first.iterations > AUTO_SWEEPS, "{layout:?}: {first:?}");
        assert_eq!(first.hierarchy_built, simplex, "{layout:?}: {first:?}");
        let solver = if simplex {
            Stage::Multigrid
        } else {
            Stage::Sweeps
        };
        assert_eq!(first.stages, [solver], "{layout:?}");
        let mut again = wavy_boundary(&mesh);
        let second = engine.solve(&mesh.coords, &mut again, &p).unwrap();
        assert!(second.converged && !second.hierarchy_built, "{layout:?}");
        assert_eq!(second.stages, [solver], "{layout:?}");
        if simplex {
            assert!(
                second.iterations < AUTO_SWEEPS / 4,
                "{layout:?}: {second:?}"
            );
            assert!(rel_diff(&again, &u) < 1e-5, "{layout:?}");
        }
    }
    // A step the sweeps finish builds nothing.
    let small = grid(Layout::Tet, 4);
    let mut u = wavy_boundary(&small);
    let mut p = params(Method::Verbss, Solver::Sor, 1e-6);
    p.accel = Accel::Auto;
    let info = solve(&small, &default_roles(&small), &[], &mut u, &p);
    assert!(info.converged && info.iterations <= AUTO_SWEEPS && !info.hierarchy_built);
}
