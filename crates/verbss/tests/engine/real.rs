//! The real meshes of `assets/meshes/su2`: VerBSS and the accelerated solve
//! against the direct solution, and diverging sweeps.

use std::path::Path;

use verbss::solve::{default_roles, Engine, Method, Solver, Stage, ERROR_FRACTION};
use verbss::Mesh;

use crate::{amg, params, rel_diff};

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
