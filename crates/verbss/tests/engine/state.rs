//! What the engine keeps between solves, what it reads, and the input it refuses.

use verbss::solve::{default_roles, Accel, Engine, Method, NodeRole, SolveParams, Solver};
use verbss::Mesh;

use crate::grid::{grid, Layout};
use crate::{params, wavy_boundary};

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
    assert_eq!(
        e.to_string(),
        "invalid setting: omega must be a number in (0, 2) (got 2)"
    );
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
