//! Property tests on random small valid meshes of every element kind, 2D
//! (triangles, quads, both) and 3D (hexahedra, prisms, tetrahedra, pyramids,
//! hexahedra with pyramids): structured grids of `[0, 1]^D` whose nodes are
//! jittered by up to 0.15 of the spacing (the generator is shared with the
//! fuzz targets: [`verbss::mesh::samples::jittered_grid`]).

use std::path::Path;

use proptest::prelude::*;
use verbss::deform::Deformer;
use verbss::io::{gmsh, su2, vtu, MshVersion};
use verbss::mesh::samples::jittered_grid;
use verbss::motion::{Attachment, Motion};
use verbss::quality;
use verbss::settings::Settings;
use verbss::solve::{default_roles, Engine, Method, NodeRole, SolveParams, Solver};
use verbss::Mesh;

/// A random valid mesh: dimension, kind, nodes a side and jitter.
fn meshes() -> impl Strategy<Value = Mesh> {
    (
        2usize..=3,
        0u8..5,
        0usize..3,
        prop::collection::vec(-1.0f64..1.0, 256),
    )
        .prop_map(|(dim, kind, size, jitter)| {
            let n = if dim == 2 { 3 + size } else { 3 + size % 2 };
            let mut k = jitter.into_iter().cycle();
            jittered_grid(dim, n, kind, || 0.15 * k.next().unwrap_or(0.0))
                .expect("the generated grid is valid")
        })
}

/// Solves with every boundary node prescribed to `prescribed(node)`, free
/// nodes starting from zero.
fn solve(mesh: &Mesh, params: &SolveParams, prescribed: impl Fn(usize) -> Vec<f64>) -> Vec<f64> {
    let roles = default_roles(mesh);
    let mut u = vec![0.0; mesh.coords.len()];
    for (i, role) in roles.iter().enumerate() {
        if *role == NodeRole::Fixed {
            u[mesh.dim * i..mesh.dim * (i + 1)].copy_from_slice(&prescribed(i));
        }
    }
    let mut engine = Engine::new(mesh, &roles, &[]).expect("engine");
    engine.solve(&mesh.coords, &mut u, params).expect("solve");
    u
}

fn params(method: Method, solver: Solver) -> SolveParams {
    let mut p = SolveParams::default();
    p.method = method;
    p.solver = solver;
    p.tolerance = 1e-12;
    p.max_iterations = 50_000;
    p
}

/// A smooth prescribed field: `0.02 (sin 3x, cos 2y, sin(x + z))`.
fn wave(mesh: &Mesh, i: usize) -> Vec<f64> {
    let p = mesh.point(i);
    let z = p.get(2).copied().unwrap_or(0.0);
    [
        0.02 * (3.0 * p[0]).sin(),
        0.02 * (2.0 * p[1]).cos(),
        0.02 * (p[0] + z).sin(),
    ][..mesh.dim]
        .to_vec()
}

/// `max_i |a_i − b_i|`.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The reference element of each kind, to find its corners independently of
/// the library's tables: node coordinates and edges.
fn reference(kind: verbss::CellKind) -> (Vec<[f64; 3]>, Vec<[usize; 2]>) {
    use verbss::CellKind::*;
    let cycle = |k: usize| (0..k).map(move |a| [a, (a + 1) % k]);
    match kind {
        Triangle => (
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            cycle(3).collect(),
        ),
        Quad => (
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            cycle(4).collect(),
        ),
        Tetra => (
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            vec![[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]],
        ),
        Hexahedron => {
            let base = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]];
            let mut pts = Vec::new();
            for z in [0.0, 1.0] {
                pts.extend(base.iter().map(|b| [b[0], b[1], z]));
            }
            let mut edges: Vec<[usize; 2]> = cycle(4).collect();
            edges.extend(cycle(4).map(|[a, b]| [a + 4, b + 4]));
            edges.extend((0..4).map(|a| [a, a + 4]));
            (pts, edges)
        }
        Wedge => {
            let tri = [[0., 0.], [1., 0.], [0., 1.]];
            let mut pts = Vec::new();
            for z in [0.0, 1.0] {
                pts.extend(tri.iter().map(|b| [b[0], b[1], z]));
            }
            let mut edges: Vec<[usize; 2]> = cycle(3).collect();
            edges.extend(cycle(3).map(|[a, b]| [a + 3, b + 3]));
            edges.extend((0..3).map(|a| [a, a + 3]));
            (pts, edges)
        }
        Pyramid => {
            let mut edges: Vec<[usize; 2]> = cycle(4).collect();
            edges.extend((0..4).map(|a| [a, 4]));
            (
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 1.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.5, 0.5, 1.0],
                ],
                edges,
            )
        }
        Vertex | Line | Polygon | Polyhedron => (Vec::new(), Vec::new()),
    }
}

/// `det(a, b)` in 2D, `a · (b × c)` in 3D, of the first `dim` components.
fn det(dim: usize, e: &[[f64; 3]]) -> f64 {
    let [a, b] = [e[0], e[1]];
    if dim == 2 {
        return a[0] * b[1] - a[1] * b[0];
    }
    let c = e[2];
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// The corners of a kind: each node with exactly `D` edge neighbours, the
/// neighbours ordered so that the reference element's corner determinant is
/// positive.
fn corners(kind: verbss::CellKind, dim: usize) -> Vec<(usize, Vec<usize>)> {
    let (pts, edges) = reference(kind);
    let mut out = Vec::new();
    for v in 0..pts.len() {
        let mut nb: Vec<usize> = edges
            .iter()
            .filter_map(|&[a, b]| (a == v).then_some(b).or((b == v).then_some(a)))
            .collect();
        if nb.len() != dim {
            continue;
        }
        let edge = |n: &[usize]| -> Vec<[f64; 3]> {
            n.iter()
                .map(|&w| std::array::from_fn(|d| pts[w][d] - pts[v][d]))
                .collect()
        };
        if det(dim, &edge(&nb)) < 0.0 {
            nb.swap(0, 1);
        }
        out.push((v, nb));
    }
    out
}

/// Per corner of cell `c` on `coords`: the determinant and the scaled
/// determinant (divided by the product of its edge lengths).
fn corner_dets(mesh: &Mesh, coords: &[f64], c: usize) -> Vec<(f64, f64)> {
    let dim = mesh.dim;
    let nodes = mesh.cells.cell(c);
    let at = |k: usize| -> [f64; 3] {
        std::array::from_fn(|d| {
            if d < dim {
                coords[dim * nodes[k] + d]
            } else {
                0.0
            }
        })
    };
    corners(mesh.cells.kinds[c], dim)
        .into_iter()
        .map(|(v, nb)| {
            let e: Vec<[f64; 3]> = nb
                .iter()
                .map(|&w| std::array::from_fn(|d| at(w)[d] - at(v)[d]))
                .collect();
            let j = det(dim, &e);
            let lengths: f64 = e
                .iter()
                .map(|x| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt())
                .product();
            (j, j / lengths)
        })
        .collect()
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 32,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    /// Every boundary node moved by `t` moves every node by `t` (VerBSS sweeps
    /// and the direct solve).
    #[test]
    fn common_translation_moves_every_node(mesh in meshes(), t in prop::array::uniform3(-0.5f64..0.5)) {
        let t = &t[..mesh.dim];
        for p in [params(Method::Verbss, Solver::Sor), params(Method::BallVertex, Solver::Direct)] {
            let u = solve(&mesh, &p, |_| t.to_vec());
            for (i, ui) in u.chunks(mesh.dim).enumerate() {
                prop_assert!(max_diff(ui, t) <= 1e-8, "{:?}: node {i} moved by {ui:?}, not {t:?}", p.method);
            }
        }
    }

    /// A zero motion over several steps leaves every node exactly where it was.
    #[test]
    fn zero_motion_changes_nothing(mesh in meshes(), steps in 1usize..4) {
        let attachment = Attachment {
            groups: vec!["left".into()],
            motion: Motion::Translation { displacement: [0.0; 3] },
        };
        let mut deformer = Deformer::new(&mesh, &[attachment], Settings::new(steps)).expect("deformer");
        for _ in 0..steps {
            deformer.advance().expect("step");
        }
        prop_assert_eq!(&deformer.current().coords, &mesh.coords);
    }

    /// One and two worker threads give bit-identical displacements.
    #[test]
    fn thread_count_does_not_change_the_result(mesh in meshes(), verbss in any::<bool>()) {
        let mut p = params(if verbss { Method::Verbss } else { Method::BallVertex }, Solver::Sor);
        p.tolerance = 1e-8;
        let one = solve(&mesh, &p, |i| wave(&mesh, i));
        p.threads = 2;
        let two = solve(&mesh, &p, |i| wave(&mesh, i));
        prop_assert_eq!(one, two);
    }

    /// The VerBSS sweeps converge to the direct solution of the same system.
    #[test]
    fn verbss_equals_the_direct_solve(mesh in meshes()) {
        let sweeps = solve(&mesh, &params(Method::Verbss, Solver::Sor), |i| wave(&mesh, i));
        let direct = solve(&mesh, &params(Method::BallVertex, Solver::Direct), |i| wave(&mesh, i));
        prop_assert!(max_diff(&sweeps, &direct) <= 1e-8, "differ by {}", max_diff(&sweeps, &direct));
    }

    /// The inversion check agrees with corner determinants computed here from
    /// the kinds' reference shapes: after one node is moved, a cell is
    /// inverted exactly when one of its corners has a non-positive
    /// determinant, and the reported volume is the worst corner's
    /// determinant / D!. Cells with a corner within 1e-9 of flat are left out
    /// (the library counts |σ| ≤ 1e-12 as flat).
    #[test]
    fn inversion_check_agrees_with_signed_volumes(
        mesh in meshes(),
        pick in any::<prop::sample::Index>(),
        d in prop::array::uniform3(-0.8f64..0.8),
    ) {
        for c in 0..mesh.cell_count() {
            prop_assert!(corner_dets(&mesh, &mesh.coords, c).iter().all(|&(j, _)| j > 0.0));
        }
        let node = pick.index(mesh.node_count());
        let mut coords = mesh.coords.clone();
        for k in 0..mesh.dim {
            coords[mesh.dim * node + k] += d[k];
        }
        let reference = quality::orientation(&mesh);
        prop_assert!(reference.iter().all(|&s| s == 1));
        let found = quality::inversions(&mesh, &coords, &reference);
        for c in 0..mesh.cell_count() {
            let dets = corner_dets(&mesh, &coords, c);
            if dets.iter().any(|&(_, s)| s.abs() < 1e-9) {
                continue;
            }
            let worst = dets.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1)).expect("corners");
            let reported = found.iter().find(|i| i.cell == c);
            prop_assert_eq!(reported.is_some(), worst.1 <= 0.0, "cell {}", c);
            if let Some(inv) = reported {
                let factorial = if mesh.dim == 2 { 2.0 } else { 6.0 };
                prop_assert!((inv.volume - worst.0 / factorial).abs() <= 1e-12);
            }
        }
    }

    /// Writing a mesh and reading it back gives the same mesh, in every
    /// format and encoding.
    #[test]
    fn reading_what_was_written_gives_the_same_mesh(mesh in meshes()) {
        let same = |read: &Mesh| {
            read.dim == mesh.dim
                && read.coords == mesh.coords
                && read.cells == mesh.cells
                && read.node_tags == mesh.node_tags
                && read.cell_tags == mesh.cell_tags
                && read.group_names() == mesh.group_names()
                && read.groups.iter().zip(&mesh.groups).all(|(a, b)| a.facets == b.facets)
        };
        let mut bytes = Vec::new();
        su2::write_to(&mut bytes, &mesh).expect("write su2");
        prop_assert!(same(&su2::parse(&bytes, Path::new("p.su2")).expect("read su2")), "su2");
        for version in [MshVersion::V22, MshVersion::V41] {
            for binary in [false, true] {
                let mut bytes = Vec::new();
                gmsh::write_to(&mut bytes, &mesh, version, binary).expect("write msh");
                let read = gmsh::parse(&bytes, Path::new("p.msh")).expect("read msh");
                prop_assert!(same(&read), "msh {:?} binary {}", version, binary);
            }
        }
        let mut bytes = Vec::new();
        vtu::write_to(&mut bytes, &mesh, &vtu::Fields::default()).expect("write vtu");
        prop_assert!(same(&vtu::parse(&bytes, Path::new("p.vtu")).expect("read vtu").mesh), "vtu");
    }
}

/// Found by the `deform` fuzz target: one undistorted hexahedron, the four
/// nodes of its `x = 1` face sliding in the plane `x = 1`, the others fixed,
/// solved by the direct ball-vertex solver. The sparse LU meets an exact
/// zero pivot, where faer's `factorize_simplicial_numeric_lu` panics; the
/// solver catches it and reports a singular system as an error.
#[test]
fn a_singular_direct_system_is_an_error_not_a_panic() {
    let mesh = jittered_grid(3, 2, 0, || 0.0).expect("one hexahedron");
    let mut settings = Settings::new(3);
    settings.solve.method = Method::BallVertex;
    settings.solve.solver = Solver::Direct;
    let attachment = Attachment {
        groups: vec!["walls".into()],
        motion: Motion::Slide {
            normal: Some([1.0, 0.0, 0.0]),
        },
    };
    let result = std::panic::catch_unwind(|| {
        Deformer::new(&mesh, &[attachment], settings).and_then(|mut d| d.advance().map(|_| ()))
    });
    let outcome = result.expect("the direct solver panicked");
    assert_eq!(
        outcome.unwrap_err().to_string(),
        "invalid mesh: the ball-vertex system is singular (an exact zero pivot in its LU factorisation)"
    );
}
