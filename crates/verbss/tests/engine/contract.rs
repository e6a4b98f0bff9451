//! The engine's contract on generated grids: row sums, translations, zero
//! motion, thread independence, VerBSS against the direct solution.

use verbss::solve::{default_roles, Method, NodeRole, Solver};
use verbss::springs::{assemble, Connectivity, Springs};
use verbss::topology::boundary_nodes;

use crate::grid::{grid, Layout, LAYOUTS};
use crate::{direct_solution, params, rel_diff, solve, thread_runs, wavy_boundary, METHODS};

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
