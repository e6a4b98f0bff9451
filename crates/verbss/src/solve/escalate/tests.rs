use std::path::Path;

use super::*;
use crate::solve::default_roles;
use crate::Mesh;

fn escalating() -> SolveParams {
    SolveParams::default()
}

#[test]
fn large_3d_meshes_escalate_to_the_sweep_gmres_before_the_multigrid() {
    let p = escalating();
    let large = GMRES_FIRST_NODES_3D;
    assert_eq!(
        chain(3, large, &p),
        [
            Stage::Sweeps,
            Stage::Gmres,
            Stage::Multigrid,
            Stage::Direct,
            Stage::SafeSweeps
        ]
    );
    assert_eq!(
        chain(3, large - 1, &p),
        [
            Stage::Sweeps,
            Stage::Multigrid,
            Stage::Direct,
            Stage::SafeSweeps
        ]
    );
    assert_eq!(
        chain(2, 10 * large, &p),
        [
            Stage::Sweeps,
            Stage::Multigrid,
            Stage::Direct,
            Stage::SafeSweeps
        ]
    );
    assert_eq!(
        exact_chain(3, large, Method::Verbss),
        [Stage::Gmres, Stage::Multigrid]
    );
    assert_eq!(
        exact_chain(3, DIRECT_NODES_3D + 1, Method::Verbss),
        [Stage::Multigrid, Stage::Direct]
    );
    let mut given = escalating();
    given.escalate = false;
    assert_eq!(chain(3, large, &given), [Stage::Sweeps]);
}

/// The tet brick of `assets/meshes/su2` on [0,2]×[0,1]×[0,1] with its `z_p`
/// face twisted by 10° about the long axis: the displacement with the
/// prescribed nodes set and the unknowns zero.
fn twisted_brick() -> (Mesh, Vec<f64>) {
    let path = format!(
        "{}/../../assets/meshes/su2/mesh_brick_tets_ffd.su2",
        env!("CARGO_MANIFEST_DIR")
    );
    let mesh = crate::io::read(Path::new(&path)).unwrap();
    let mut u = vec![0.0; mesh.coords.len()];
    let (s, c) = 10f64.to_radians().sin_cos();
    for i in mesh.group("z_p").unwrap().nodes() {
        let x = mesh.point(i);
        let (dy, dz) = (x[1] - 0.5, x[2] - 0.5);
        u[3 * i + 1] = 0.5 + c * dy - s * dz - x[1];
        u[3 * i + 2] = 0.5 + s * dy + c * dz - x[2];
    }
    (mesh, u)
}

/// The solution of the brick's system by the sparse direct solve.
fn direct(mesh: &Mesh, u0: &[f64]) -> Vec<f64> {
    let mut p = escalating();
    p.method = Method::BallVertex;
    p.solver = Solver::Direct;
    let mut exact = u0.to_vec();
    let mut engine = Engine::new(mesh, &default_roles(mesh), &[]).unwrap();
    engine.solve(&mesh.coords, &mut exact, &p).unwrap();
    exact
}

/// The largest difference between `a` and `b` over the largest `|b|`.
fn worst(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

#[test]
fn the_sweep_gmres_solves_a_stalled_step_within_the_error_bound() {
    let (mesh, u0) = twisted_brick();
    let exact = direct(&mesh, &u0);
    let mut p = escalating();
    // Too few sweeps to converge: the step goes on to the next stage.
    p.max_iterations = 10;
    let mut engine = Engine::new(&mesh, &default_roles(&mesh), &[]).unwrap();
    let mut u = u0.clone();
    let info = engine
        .solve_in_stages(
            &mesh.coords,
            &mut u,
            &p,
            &[Stage::Sweeps, Stage::Gmres],
            false,
        )
        .unwrap();
    assert_eq!(info.stages, [Stage::Sweeps, Stage::Gmres], "{info:?}");
    assert!(
        info.converged && info.error_ratio <= ERROR_FRACTION,
        "{info:?}"
    );
    assert_eq!(info.levels, 1, "no hierarchy");
    assert!(worst(&u, &exact) < 1e-4, "{}", worst(&u, &exact));
}

#[test]
fn the_sweep_gmres_solves_to_round_off() {
    let (mesh, u0) = twisted_brick();
    let exact = direct(&mesh, &u0);
    let mut engine = Engine::new(&mesh, &default_roles(&mesh), &[]).unwrap();
    let mut u = u0.clone();
    let info = engine
        .solve_in_stages(&mesh.coords, &mut u, &escalating(), &[Stage::Gmres], true)
        .unwrap();
    assert!(info.converged, "{info:?}");
    assert!(worst(&u, &exact) < 1e-9, "{}", worst(&u, &exact));
}
