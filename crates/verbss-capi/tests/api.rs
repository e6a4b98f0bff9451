//! The C API's contract, called from Rust as C would call it: status codes,
//! the per-thread message (the library's own text), rejected steps that leave
//! the deformer as it was, and the same points as the library for the same
//! motion.

use std::ffi::{CStr, CString};
use std::ptr;

use verbss::deform::Deformer;
use verbss::motion::{Attachment, Motion};
use verbss::near_wall::Robust;
use verbss::settings::Settings;
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
    create_with(points, kinds, nodes, moving, ptr::null())
}

/// `create` with settings (NULL: the defaults).
fn create_with(
    points: &[f64],
    kinds: &[i32],
    nodes: &[i64],
    moving: &[i64],
    settings: *const VerbssSettings,
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
            settings,
            &mut d,
        )
    };
    (status, d)
}

/// `verbss_settings_set(s, name, value)`: its status and message.
fn set(s: *mut VerbssSettings, name: &str, value: &str) -> (i32, String) {
    let (name, value) = (CString::new(name).unwrap(), CString::new(value).unwrap());
    let status = unsafe { verbss_settings_set(s, name.as_ptr(), value.as_ptr()) };
    (status, last_error())
}

/// New settings with each `(name, value)` set.
fn settings(values: &[(&str, &str)]) -> *mut VerbssSettings {
    let mut s = ptr::null_mut();
    assert_eq!(unsafe { verbss_settings_new(&mut s) }, VERBSS_OK);
    for (name, value) in values {
        let (status, message) = set(s, name, value);
        assert_eq!(status, VERBSS_OK, "{message}");
    }
    s
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
    // The C defaults: the robust preset (anchored reference) or the paper's
    // method, one worker thread per core.
    let mut settings = if robust == Robust::recommended() {
        Settings::robust(1)
    } else {
        Settings::new(1)
    };
    settings.solve.threads = 0;
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
    let named = |x: &str| {
        format!(
            "invalid displacement: verbss_deformer_step displacement of moving node 0 (node {}) \
             is {x} (expected finite numbers within ±1e100)",
            MOVING[0]
        )
    };
    assert_eq!(last_error(), named("NaN"));
    // Issue 43, 11 and 15: a huge displacement is refused with its number,
    // printed short, before it makes a NaN position.
    let u = [1e308, 0.0];
    assert_eq!(
        unsafe { verbss_deformer_step(d, u.as_ptr(), 2) },
        VERBSS_ERROR_INPUT
    );
    assert_eq!(last_error(), named("1e308"));
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
    let create_with = |settings| create_with(&p, &k, &n, &MOVING, settings);
    let u = [0.1, 0.05];
    let direct = settings(&[("method", "ball-vertex"), ("solver", "direct")]);
    let (status, exact) = create_with(direct);
    assert_eq!(status, VERBSS_OK, "{}", last_error());
    assert_eq!(
        unsafe { verbss_deformer_step(exact, u.as_ptr(), 2) },
        VERBSS_OK
    );
    let amg = settings(&[
        ("method", "verbss"),
        ("accel", "amg"),
        ("tolerance", "1e-12"),
    ]);
    let (status, fast) = create_with(amg);
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
    // The multigrid solves the block systems only: the combination is
    // refused when the deformer is made.
    let (status, _) = set(direct, "accel", "amg");
    assert_eq!(status, VERBSS_OK);
    let (status, d) = create_with(direct);
    assert_eq!(status, VERBSS_ERROR_INPUT);
    assert!(d.is_null());
    assert_eq!(
        last_error(),
        "invalid setting: accel amg solves the block systems of method verbss and spring \
         (not ball-vertex or laplacian)"
    );
    for s in [direct, amg] {
        assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
    }
}

#[test]
fn the_robust_method_is_the_library_with_the_recommended_treatments() {
    let (p, k, n) = square();
    let settings = settings(&[("method", "robust")]);
    let (status, d) = create_with(&p, &k, &n, &MOVING, settings);
    assert_eq!(unsafe { verbss_settings_free(settings) }, VERBSS_OK);
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

/// Every setting of the library's table is a C name, taken with its
/// default and with each preset's value.
#[test]
fn every_setting_of_the_table_is_a_c_name() {
    for setting in verbss::settings::TABLE {
        let values =
            std::iter::once(setting.default).chain(setting.presets.iter().map(|(_, v)| *v));
        for value in values {
            let s = settings(&[]);
            assert_eq!(
                set(s, setting.name, value).0,
                VERBSS_OK,
                "{} = {value}",
                setting.name
            );
            assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
        }
    }
}

#[test]
fn settings_are_named_as_on_the_command_line_and_checked_when_set() {
    let (p, k, n) = square();
    // The paper's method, whose sweeps the tolerance below changes.
    let s = settings(&[("method", "verbss")]);
    let cases = [
        (
            "method",
            "fast",
            "unknown method 'fast' (expected robust, verbss, ball-vertex, spring or laplacian)",
        ),
        (
            "omegga",
            "1.5",
            "unknown setting 'omegga' (expected method, reference, predictor, rigid_layer, \
          stiffening, substeps, blend, relocate, solver, accel, escalate, omega, tolerance, \
          absolute_tolerance, max_iterations or threads)",
        ),
        ("omega", "2.5", "omega must be a number in (0, 2) (got 2.5)"),
        (
            "rigid_layer",
            "thick",
            "rigid_layer must be off, auto or a positive wall distance (got 'thick')",
        ),
        (
            "substeps",
            "40",
            "substeps must be a whole number from 0 to 30 (got 40)",
        ),
        ("blend", "yes", "blend must be on or off (got 'yes')"),
    ];
    for (name, value, message) in cases {
        let expected = format!("invalid setting: {message}");
        assert_eq!(set(s, name, value), (VERBSS_ERROR_INPUT, expected));
    }
    let name = CString::new("max_iterations").unwrap();
    let status = unsafe { verbss_settings_set_number(s, name.as_ptr(), 2.5) };
    assert_eq!(
        (status, last_error().as_str()),
        (
            VERBSS_ERROR_INPUT,
            "invalid setting: max_iterations must be a whole number ≥ 1 (got '2.5')"
        )
    );
    let value = CString::new("on").unwrap();
    let status = unsafe { verbss_settings_set(ptr::null_mut(), name.as_ptr(), value.as_ptr()) };
    assert_eq!(
        (status, last_error().as_str()),
        (VERBSS_ERROR_INPUT, "the settings are NULL")
    );
    let status = unsafe { verbss_settings_set(s, ptr::null(), value.as_ptr()) };
    assert_eq!(
        (status, last_error().as_str()),
        (VERBSS_ERROR_INPUT, "`name` is NULL")
    );
    let latin1 = CString::new(vec![0xe9u8]).unwrap();
    let status = unsafe { verbss_settings_set(s, name.as_ptr(), latin1.as_ptr()) };
    assert_eq!(
        (status, last_error().as_str()),
        (VERBSS_ERROR_INPUT, "`value` is not UTF-8 text")
    );
    // The refused values changed nothing.
    let u = [0.1, 0.05];
    let step = |settings| {
        let (status, d) = create_with(&p, &k, &n, &MOVING, settings);
        assert_eq!(status, VERBSS_OK, "{}", last_error());
        assert_eq!(unsafe { verbss_deformer_step(d, u.as_ptr(), 2) }, VERBSS_OK);
        let result = (info(d).iterations, points(d));
        assert_eq!(unsafe { verbss_deformer_free(d) }, VERBSS_OK);
        result
    };
    let paper = settings(&[("method", "verbss")]);
    assert_eq!(step(s), step(paper));
    // A number is written exactly: the same deformer as its text.
    let tight = settings(&[("method", "verbss"), ("tolerance", "1e-12")]);
    let name = CString::new("tolerance").unwrap();
    assert_eq!(
        unsafe { verbss_settings_set_number(s, name.as_ptr(), 1e-12) },
        VERBSS_OK
    );
    assert_eq!(step(s), step(tight));
    assert_ne!(step(s).0, step(paper).0);
    for s in [s, paper, tight] {
        assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
    }
    assert_eq!(unsafe { verbss_settings_free(ptr::null_mut()) }, VERBSS_OK);
}

/// `verbss_settings_add_slide(s, nodes, normal)`: its status and message.
fn add_slide(s: *mut VerbssSettings, nodes: &[i64], normal: &[f64]) -> (i32, String) {
    let normal_ptr = if normal.is_empty() {
        ptr::null()
    } else {
        normal.as_ptr()
    };
    let status = unsafe {
        verbss_settings_add_slide(s, nodes.as_ptr(), nodes.len(), normal_ptr, normal.len())
    };
    (status, last_error())
}

/// The square's points after the centre moves by (0.1, 0.05), with the
/// bottom edge (nodes 0 to 4, y = 0) sliding in the plane of `normal`
/// (empty: its own) and the nodes `fixed` a fixed group.
fn slide_bottom(normal: &[f64], fixed: &[i64]) -> Vec<f64> {
    let (p, k, n) = square();
    let s = settings(&[("method", "verbss")]);
    assert_eq!(add_slide(s, &[0, 1, 2, 3, 4], normal).0, VERBSS_OK);
    if !fixed.is_empty() {
        let status = unsafe { verbss_settings_add_fixed(s, fixed.as_ptr(), fixed.len()) };
        assert_eq!(status, VERBSS_OK);
    }
    let (status, d) = create_with(&p, &k, &n, &MOVING, s);
    assert_eq!(status, VERBSS_OK, "{}", last_error());
    assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
    let u = [0.1, 0.05];
    assert_eq!(unsafe { verbss_deformer_step(d, u.as_ptr(), 2) }, VERBSS_OK);
    let moved = points(d);
    assert_eq!(unsafe { verbss_deformer_free(d) }, VERBSS_OK);
    moved
}

#[test]
fn nodes_slide_in_their_own_plane_or_in_the_plane_of_a_normal() {
    let (p, _, _) = square();
    let own = slide_bottom(&[], &[]);
    // The bottom edge's own plane is y = 0: its nodes moved along x only.
    for i in 1..4 {
        assert_eq!(own[2 * i + 1], 0.0, "node {i}");
        assert_ne!(own[2 * i], p[2 * i], "node {i}");
    }
    assert_eq!(slide_bottom(&[0.0, 3.0], &[]), own);
    // A tilted plane: each node moved along (1, -1).
    let tilted = slide_bottom(&[1.0, 1.0], &[]);
    for i in 1..4 {
        let (dx, dy) = (tilted[2 * i] - p[2 * i], tilted[2 * i + 1] - p[2 * i + 1]);
        assert!(
            dx != 0.0 && (dx + dy).abs() < 1e-15,
            "node {i}: ({dx}, {dy})"
        );
    }
}

#[test]
fn bad_slide_planes_are_named() {
    let (p, k, n) = square();
    let cases: [(&[i64], &[f64], &str); 3] = [
        (
            &[0, 1, 25],
            &[],
            "invalid mesh: node 2 of slide plane 0 is node 25, not a node id of the mesh (0 to 24)",
        ),
        (
            &[0, 1, 2],
            &[0.0, 0.0, 1.0],
            "invalid setting: the slide normal of group 'slide plane 0' has z = 1 on a 2D \
             mesh: give NX,NY (or NX,NY,0)",
        ),
        (
            &[0, 1, 2, 7],
            &[],
            "invalid setting: group 'slide plane 0' is not made of parallel planes (its node \
             at (0.500000, 0.250000) is 2.500e-1 from the nearest plane of its facets, of \
             normal (0.000000, 1.000000), more than 5.590e-7): give the slide motion a `normal` \
             (`--slide GROUP:NX,NY[,NZ]`) or split the group into its planes",
        ),
    ];
    for (nodes, normal, message) in cases {
        let s = settings(&[]);
        assert_eq!(add_slide(s, nodes, normal).0, VERBSS_OK);
        let (status, d) = create_with(&p, &k, &n, &MOVING, s);
        assert_eq!(
            (status, last_error().as_str()),
            (VERBSS_ERROR_INPUT, message)
        );
        assert!(d.is_null());
        assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
    }
    let s = settings(&[]);
    assert_eq!(
        add_slide(s, &[], &[]),
        (
            VERBSS_ERROR_INPUT,
            "invalid setting: slide plane 0 has no node".into()
        )
    );
    assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
}

#[test]
fn a_fixed_group_holds_the_nodes_where_a_plane_meets_it() {
    let (p, k, n) = square();
    let free = slide_bottom(&[], &[]);
    let held = slide_bottom(&[], &[0, 1]);
    assert_ne!(free[2], p[2]);
    assert_eq!(&held[..4], &p[..4]);
    assert_ne!(held[4], p[4]);
    let s = settings(&[]);
    let ids = [30];
    let status = unsafe { verbss_settings_add_fixed(s, ids.as_ptr(), 1) };
    assert_eq!(status, VERBSS_OK);
    let (status, d) = create_with(&p, &k, &n, &MOVING, s);
    assert_eq!(
        (status, last_error().as_str()),
        (
            VERBSS_ERROR_INPUT,
            "invalid mesh: node 0 of fixed group 0 is node 30, not a node id of the mesh (0 to 24)"
        )
    );
    assert!(d.is_null());
    let status = unsafe { verbss_settings_add_fixed(s, ptr::null(), 0) };
    assert_eq!(
        (status, last_error().as_str()),
        (
            VERBSS_ERROR_INPUT,
            "invalid setting: fixed group 1 has no node"
        )
    );
    assert_eq!(unsafe { verbss_settings_free(s) }, VERBSS_OK);
}
