//! The C API's contract, called from Rust as C would call it: status codes,
//! the per-thread message (the library's own text), rejected steps that leave
//! the deformer as it was, and the same points as the library for the same
//! motion.

use std::ffi::CStr;
use std::ptr;

use verbss::deform::{Deformer, Settings};
use verbss::motion::{Attachment, Motion};
use verbss::robust::Robust;
use verbss::{CellKind, Cells, Group, Mesh};
use verbss_capi::*;

/// The unit square as a 4 × 4 grid of triangles: 25 nodes, node `5 j + i`
/// at `(i/4, j/4)`, cells as VTK triangles.
fn square() -> (Vec<f64>, Vec<i32>, Vec<i64>) {
    let mut points = Vec::new();
    for j in 0..5 {
        for i in 0..5 {
            points.extend([i as f64 / 4.0, j as f64 / 4.0]);
        }
    }
    let mut nodes = Vec::new();
    for j in 0..4i64 {
        for i in 0..4i64 {
            let a = 5 * j + i;
            nodes.extend([a, a + 1, a + 6, a, a + 6, a + 5]);
        }
    }
    (points, vec![VERBSS_TRIANGLE; 32], nodes)
}

/// The centre node 12 moves; the boundary stays.
const MOVING: [i64; 1] = [12];

fn last_error() -> String {
    unsafe { CStr::from_ptr(verbss_last_error()) }
        .to_str()
        .unwrap()
        .to_string()
}

fn create(
    points: &[f64],
    kinds: &[i32],
    nodes: &[i64],
    moving: &[i64],
) -> (i32, *mut VerbssDeformer) {
    create_with(points, kinds, nodes, moving, None)
}

/// `create` with explicit settings (`None`: the defaults).
fn create_with(
    points: &[f64],
    kinds: &[i32],
    nodes: &[i64],
    moving: &[i64],
    settings: Option<&VerbssSettings>,
) -> (i32, *mut VerbssDeformer) {
    let mut d = ptr::null_mut();
    let status = unsafe {
        verbss_deformer_new(
            2,
            points.as_ptr(),
            points.len() / 2,
            kinds.as_ptr(),
            kinds.len(),
            nodes.as_ptr(),
            nodes.len(),
            moving.as_ptr(),
            moving.len(),
            settings.map_or(ptr::null(), |s| s as *const VerbssSettings),
            &mut d,
        )
    };
    (status, d)
}

fn info(d: *const VerbssDeformer) -> VerbssInfo {
    let mut info = VerbssInfo {
        step: 99,
        iterations: 0,
        residual: 0.0,
        converged: 0,
        seconds: 0.0,
        min_quality: 0.0,
        mean_quality: 0.0,
        inverted: 0,
    };
    assert_eq!(unsafe { verbss_deformer_info(d, &mut info) }, VERBSS_OK);
    info
}

fn points(d: *const VerbssDeformer) -> Vec<f64> {
    let mut out = vec![0.0; 50];
    assert_eq!(
        unsafe { verbss_deformer_points(d, out.as_mut_ptr(), 50) },
        VERBSS_OK
    );
    out
}

#[test]
fn steps_match_the_library_and_a_rejected_step_changes_nothing() {
    let (p, k, n) = square();
    let (status, d) = create(&p, &k, &n, &MOVING);
    assert_eq!(status, VERBSS_OK, "{}", last_error());
    assert_eq!(info(d).step, 0);
    // The centre node pushed past the right boundary inverts elements.
    let far = [0.8, 0.0];
    assert_eq!(
        unsafe { verbss_deformer_step(d, far.as_ptr(), 2) },
        VERBSS_ERROR_INVERTED
    );
    let message = last_error();
    assert!(message.starts_with("step 1: element "), "{message}");
    assert_eq!(info(d).step, 0);
    assert_eq!(points(d), p);
    // The same step with a smaller displacement is accepted, then a second,
    // as the library computes them with the defaults (the robust preset)
    // after the same rejected step.
    let mut library = library_deformer(&p, &n, Robust::recommended());
    library
        .set_motion(
            0,
            Motion::Positions(verbss::motion::PositionSource::Given(
                [(12, vec![0.5 + far[0], 0.5 + far[1]])]
                    .into_iter()
                    .collect(),
            )),
        )
        .unwrap();
    assert!(library.advance().is_err());
    for (step, u) in [[0.1, 0.05], [0.15, -0.05]].iter().enumerate() {
        assert_eq!(unsafe { verbss_deformer_step(d, u.as_ptr(), 2) }, VERBSS_OK);
        let i = info(d);
        assert_eq!((i.step, i.inverted, i.converged), (step + 1, 0, 1));
        assert!(i.min_quality > 0.0 && i.min_quality <= i.mean_quality);
        let target = [0.5 + u[0], 0.5 + u[1]];
        library
            .set_motion(
                0,
                Motion::Positions(verbss::motion::PositionSource::Given(
                    [(12, target.to_vec())].into_iter().collect(),
                )),
            )
            .unwrap();
        let r = library.advance().unwrap();
        assert_eq!((r.step, r.iterations), (i.step, i.iterations));
        assert_eq!(points(d), library.current().coords);
        assert_eq!(&points(d)[24..26], &target);
    }
    assert_eq!(unsafe { verbss_deformer_free(d) }, VERBSS_OK);
}

/// The library's deformer for the same mesh: a vertex group of node 12.
fn library_deformer(points: &[f64], nodes: &[i64], robust: Robust) -> Deformer {
    let mut cells = Cells::new();
    for t in nodes.chunks(3) {
        cells.push(
            CellKind::Triangle,
            &[t[0] as usize, t[1] as usize, t[2] as usize],
        );
    }
    let mut facets = Cells::new();
    facets.push(CellKind::Vertex, &[12]);
    let group = Group {
        name: "moving".into(),
        tag: None,
        facets,
    };
    let mesh = Mesh::new(2, points.to_vec(), cells, vec![group]).unwrap();
    let mut settings = Settings::new(1);
    let c = VerbssSettings::default();
    settings.solve.tolerance = c.tolerance;
    settings.solve.max_iterations = c.max_iterations;
    settings.solve.threads = c.threads;
    settings.robust = robust;
    let given = Motion::Positions(verbss::motion::PositionSource::Given(Default::default()));
    let attachment = Attachment {
        groups: vec!["moving".into()],
        motion: given,
    };
    Deformer::new(&mesh, &[attachment], settings).unwrap()
}

/// Cell kinds, cell nodes, moving nodes and the message they give.
type Case = (Vec<i32>, Vec<i64>, Vec<i64>, &'static str);

#[test]
fn bad_input_returns_status_2_and_says_what_is_wrong() {
    let (p, k, n) = square();
    let cases: Vec<Case> = vec![
        (
            vec![7; 32],
            n.clone(),
            MOVING.to_vec(),
            "invalid mesh: cell 0 has kind 7 (expected 5 triangle, 9 quad, 10 tetra, 12 hexahedron, 13 wedge or 14 pyramid)",
        ),
        (
            k.clone(),
            n[..95].to_vec(),
            MOVING.to_vec(),
            "invalid mesh: `cell_nodes` holds 95 node ids but the 32 cells use 96",
        ),
        (
            k.clone(),
            [n.clone(), vec![1]].concat(),
            MOVING.to_vec(),
            "invalid mesh: `cell_nodes` holds 97 node ids but the 32 cells use 96",
        ),
        (
            k.clone(),
            [vec![-1], n[1..].to_vec()].concat(),
            MOVING.to_vec(),
            "invalid mesh: node 0 of cell 0 is node -1, not a node id of the mesh (0 to 24)",
        ),
        (
            k.clone(),
            n.clone(),
            vec![12, 25],
            "invalid mesh: moving node 1 is node 25, not a node id of the mesh (0 to 24)",
        ),
        (
            k.clone(),
            n.clone(),
            vec![12, 3, 12],
            "invalid setting: moving node 2 is node 12, listed twice",
        ),
        (k.clone(), n.clone(), vec![], "invalid setting: no moving node was given"),
    ];
    for (kinds, nodes, moving, expected) in cases {
        let (status, d) = create(&p, &kinds, &nodes, &moving);
        assert_eq!(
            (status, last_error().as_str()),
            (VERBSS_ERROR_INPUT, expected)
        );
        assert!(d.is_null());
    }
    let mut d = ptr::null_mut();
    let status = unsafe {
        verbss_deformer_new(
            2,
            ptr::null(),
            25,
            k.as_ptr(),
            32,
            n.as_ptr(),
            96,
            MOVING.as_ptr(),
            1,
            ptr::null(),
            &mut d,
        )
    };
    assert_eq!(
        (status, last_error().as_str()),
        (VERBSS_ERROR_INPUT, "`points` is NULL")
    );
    let settings = VerbssSettings {
        method: 9,
        ..VerbssSettings::default()
    };
    let status = unsafe {
        verbss_deformer_new(
            2,
            p.as_ptr(),
            25,
            k.as_ptr(),
            32,
            n.as_ptr(),
            96,
            MOVING.as_ptr(),
            1,
            &settings,
            &mut d,
        )
    };
    assert_eq!(
        (status, last_error().as_str()),
        (
            VERBSS_ERROR_INPUT,
            "invalid setting: method 9 is not one of VERBSS_METHOD_*"
        )
    );

    let (_, d) = create(&p, &k, &n, &MOVING);
    let u = [0.1, 0.0, 0.0];
    assert_eq!(
        unsafe { verbss_deformer_step(d, u.as_ptr(), 3) },
        VERBSS_ERROR_INPUT
    );
    assert_eq!(
        last_error(),
        "the displacement has 3 numbers, expected 2 (1 moving node(s) × 2)"
    );
    let u = [f64::NAN, 0.0];
    assert_eq!(
        unsafe { verbss_deformer_step(d, u.as_ptr(), 2) },
        VERBSS_ERROR_INPUT
    );
    assert_eq!(
        last_error(),
        "invalid setting: the displacement of moving node 0 is not finite"
    );
    let mut out = [0.0; 4];
    assert_eq!(
        unsafe { verbss_deformer_points(d, out.as_mut_ptr(), 4) },
        VERBSS_ERROR_INPUT
    );
    assert_eq!(
        last_error(),
        "`out` has room for 4 numbers, the mesh has 50"
    );
    assert_eq!(info(d).step, 0);
    assert_eq!(
        unsafe { verbss_deformer_step(ptr::null_mut(), u.as_ptr(), 2) },
        VERBSS_ERROR_INPUT
    );
    assert_eq!(last_error(), "the deformer is NULL");
    assert_eq!(unsafe { verbss_deformer_free(d) }, VERBSS_OK);
    assert_eq!(unsafe { verbss_deformer_free(ptr::null_mut()) }, VERBSS_OK);
}

#[test]
fn the_message_is_per_thread() {
    let (p, k, n) = square();
    let (status, _) = create(&p, &k, &n, &[]);
    assert_eq!(status, VERBSS_ERROR_INPUT);
    let other = std::thread::spawn(last_error).join().unwrap();
    assert_eq!(other, "");
    assert_eq!(last_error(), "invalid setting: no moving node was given");
}

#[test]
fn the_accelerated_solve_is_selectable_and_gives_the_direct_solution() {
    let (p, k, n) = square();
    let create_with = |settings: &VerbssSettings| create_with(&p, &k, &n, &MOVING, Some(settings));
    let u = [0.1, 0.05];
    let mut direct = VerbssSettings {
        method: VERBSS_METHOD_BALL_VERTEX,
        solver: VERBSS_SOLVER_DIRECT,
        ..VerbssSettings::default()
    };
    let (status, exact) = create_with(&direct);
    assert_eq!(status, VERBSS_OK, "{}", last_error());
    assert_eq!(
        unsafe { verbss_deformer_step(exact, u.as_ptr(), 2) },
        VERBSS_OK
    );
    let amg = VerbssSettings {
        method: VERBSS_METHOD_VERBSS,
        accel: VERBSS_ACCEL_AMG,
        tolerance: 1e-12,
        ..VerbssSettings::default()
    };
    let (status, fast) = create_with(&amg);
    assert_eq!(status, VERBSS_OK, "{}", last_error());
    assert_eq!(
        unsafe { verbss_deformer_step(fast, u.as_ptr(), 2) },
        VERBSS_OK
    );
    let diff = points(exact)
        .iter()
        .zip(points(fast))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(diff < 1e-10, "largest difference {diff}");
    for d in [exact, fast] {
        assert_eq!(unsafe { verbss_deformer_free(d) }, VERBSS_OK);
    }
    direct.accel = 7;
    let (status, _) = create_with(&direct);
    assert_eq!(status, VERBSS_ERROR_INPUT);
    assert_eq!(
        last_error(),
        "invalid setting: accel 7 is not one of VERBSS_ACCEL_*"
    );
}

#[test]
fn the_robust_method_is_the_library_with_the_recommended_treatments() {
    let (p, k, n) = square();
    let settings = VerbssSettings {
        method: VERBSS_METHOD_ROBUST,
        ..VerbssSettings::default()
    };
    let (status, d) = create_with(&p, &k, &n, &MOVING, Some(&settings));
    assert_eq!(status, VERBSS_OK, "{}", last_error());
    let mut library = library_deformer(&p, &n, Robust::recommended());
    let u = [0.3, 0.0];
    assert_eq!(
        unsafe { verbss_deformer_step(d, u.as_ptr(), 2) },
        VERBSS_OK,
        "{}",
        last_error()
    );
    library
        .set_motion(
            0,
            Motion::Positions(verbss::motion::PositionSource::Given(
                [(12, vec![0.8, 0.5])].into_iter().collect(),
            )),
        )
        .unwrap();
    let r = library.advance().unwrap();
    assert_eq!(info(d).iterations, r.iterations);
    assert_eq!(points(d), library.current().coords);
    assert_eq!(unsafe { verbss_deformer_free(d) }, VERBSS_OK);
}

#[test]
fn the_kind_constants_are_the_vtk_ids() {
    for (code, kind) in [
        (VERBSS_TRIANGLE, CellKind::Triangle),
        (VERBSS_QUAD, CellKind::Quad),
        (VERBSS_TETRA, CellKind::Tetra),
        (VERBSS_HEXAHEDRON, CellKind::Hexahedron),
        (VERBSS_WEDGE, CellKind::Wedge),
        (VERBSS_PYRAMID, CellKind::Pyramid),
    ] {
        assert_eq!(code, i32::from(kind.vtk_id()), "{kind:?}");
    }
}
