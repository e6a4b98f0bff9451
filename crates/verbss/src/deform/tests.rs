//! Tests of the stepper and of the node roles.

use std::collections::HashMap;
use std::path::Path;

use super::*;
use crate::mesh::samples::square_of_triangles as square;
use crate::motion::PositionSource;
use crate::near_wall::Robust;
use crate::settings::Predictor;

const NACA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/meshes/su2/mesh_NACA0012_inv.su2"
);
const BUMP: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/meshes/su2/surface_bump.dat"
);

fn attach(groups: &[&str], motion: Motion) -> Attachment {
    Attachment {
        groups: groups.iter().map(|g| g.to_string()).collect(),
        motion,
    }
}

#[test]
fn naca0012_rotated_40_degrees_in_40_steps_stays_valid() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let rotation = Motion::Rotation {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        angle: 40f64.to_radians(),
    };
    let mut d = Deformer::new(&mesh, &[attach(&["airfoil"], rotation)], Settings::new(40)).unwrap();
    for n in 1..=40 {
        let r = d.step(n).unwrap();
        assert_eq!(r.inverted, 0);
        assert!(r.min_quality > 0.0);
    }
    // The airfoil turned rigidly by 40° about (0.25, 0); the farfield stayed.
    let (s, c) = 40f64.to_radians().sin_cos();
    let x = &d.current().coords;
    for i in mesh.group("airfoil").unwrap().nodes() {
        let p = mesh.point(i);
        let (dx, dy) = (p[0] - 0.25, p[1]);
        assert!((x[2 * i] - (0.25 + c * dx - s * dy)).abs() < 1e-12);
        assert!((x[2 * i + 1] - (s * dx + c * dy)).abs() < 1e-12);
    }
    for i in mesh.group("farfield").unwrap().nodes() {
        assert_eq!(&x[2 * i..2 * i + 2], mesh.point(i));
    }
}

/// A motion whose numbers make a non-finite (or overflowing) position —
/// an infinite pitch, an angle that is not a number — is refused naming the node and
/// the step, before any solve: no NaN reaches a message or a file.
#[test]
fn a_motion_beyond_finite_positions_is_refused_before_the_solve() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let pitch = Motion::PitchPlunge {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        pitch: f64::INFINITY,
        plunge: [0.0; 3],
        period: None,
    };
    let turn = Motion::Rotation {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        angle: f64::NAN,
    };
    for motion in [pitch, turn] {
        let mut d =
            Deformer::new(&mesh, &[attach(&["airfoil"], motion)], Settings::new(10)).unwrap();
        let e = d.step(1).unwrap_err().to_string();
        assert!(
            e.starts_with("invalid setting: step 1: the motion moves node "),
            "{e}"
        );
        assert!(
            e.ends_with(
                "not a finite position within ±1e100 (check the motion's numbers: angles, speeds, \
             wavelengths, displacements)"
            ),
            "{e}"
        );
        assert_eq!(d.current_step(), 0);
    }
}

#[test]
fn surface_file_puts_every_node_where_the_file_says() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let table = crate::io::positions::read(Path::new(BUMP), 2).unwrap();
    let map = (0..table.len())
        .map(|k| (table.ids[k], table.point(k).to_vec()))
        .collect();
    let motion = Motion::Positions(PositionSource::Final(map));
    let mut d = Deformer::new(&mesh, &[attach(&["airfoil"], motion)], Settings::new(2)).unwrap();
    d.step(1).unwrap();
    d.step(2).unwrap();
    assert_eq!(table.len(), 200);
    for k in 0..table.len() {
        let i = table.ids[k];
        assert_eq!(&d.current().coords[2 * i..2 * i + 2], table.point(k));
    }
}

#[test]
fn translation_is_reproduced_by_both_references() {
    let mesh = square(6);
    let shift = Motion::Translation {
        displacement: [0.0, 0.0, 0.0],
    };
    for reference in [Reference::Updated, Reference::Fixed, Reference::Anchored] {
        let mut settings = Settings::new(3);
        settings.reference = reference;
        settings.solve.tolerance = 1e-12;
        let all = ["left", "right", "bottom", "top"];
        let mut d = Deformer::new(&mesh, &[attach(&all, shift.clone())], settings).unwrap();
        for n in 1..=3 {
            let r = d.step(n).unwrap();
            assert_eq!((r.step, r.amplification), (n, 0.0));
        }
        assert!(d.displacement().iter().all(|u| u.abs() < 1e-12));
    }
    let moved = Motion::Translation {
        displacement: [0.3, 0.0, 0.0],
    };
    for reference in [Reference::Updated, Reference::Fixed, Reference::Anchored] {
        let mut settings = Settings::new(3);
        settings.reference = reference;
        settings.solve.tolerance = 1e-12;
        let all = ["left", "right", "bottom", "top"];
        let mut d = Deformer::new(&mesh, &[attach(&all, moved.clone())], settings).unwrap();
        // Every node moves as the boundary: an amplification of 1.
        for _ in 0..3 {
            let r = d.advance().unwrap();
            assert!((r.amplification - 1.0).abs() < 1e-9, "{}", r.amplification);
        }
        let u = d.displacement();
        for i in 0..mesh.node_count() {
            assert!(
                (u[2 * i] - 0.3).abs() < 1e-9,
                "{reference:?} node {i}: {}",
                u[2 * i]
            );
            assert!(u[2 * i + 1].abs() < 1e-9);
        }
    }
}

/// A pitch–plunge cycle brings the boundary back to the input mesh: with a
/// total unknown every prescribed displacement is then round-off and the
/// last step solves nothing, so the free nodes are exactly where they
/// started (the anchored reference without the blend, which is the fixed
/// one, and with it); the updated reference ends elsewhere.
#[test]
fn a_total_unknown_returns_to_the_input_mesh_after_a_cycle() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let pitch = Motion::PitchPlunge {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        pitch: 10f64.to_radians(),
        plunge: [0.0, 0.1, 0.0],
        period: Some(8),
    };
    let end = |settings: Settings| {
        let mut d = Deformer::new(&mesh, &[attach(&["airfoil"], pitch.clone())], settings).unwrap();
        let sweeps: Vec<usize> = (1..=8).map(|n| d.step(n).unwrap().iterations).collect();
        let free = d.roles().iter().map(|r| *r == NodeRole::Free);
        let moved = d
            .displacement()
            .chunks(2)
            .zip(free)
            .filter(|(_, free)| *free)
            .map(|(u, _)| u[0].abs().max(u[1].abs()))
            .fold(0.0, f64::max);
        (sweeps, moved)
    };
    for reference in [Reference::Fixed, Reference::Anchored] {
        let mut settings = Settings::new(8);
        settings.reference = reference;
        let (sweeps, moved) = end(settings);
        // sin(2πn/8) vanishes at steps 4 and 8: the boundary is at the input mesh.
        let idle: Vec<bool> = sweeps.iter().map(|&k| k == 0).collect();
        let expected = [false, false, false, true, false, false, false, true];
        assert_eq!(idle, expected, "{reference:?}: {sweeps:?}");
        assert_eq!(moved, 0.0, "{reference:?}");
    }
    let (sweeps, moved) = end(Settings::robust(8));
    assert_eq!(sweeps, [0; 8]);
    // Round-off of the coordinates.
    assert!(moved <= 1e-13, "{moved}");
    let (_, moved) = end(Settings::new(8));
    assert!(moved > 1e-6, "{moved}");
}

/// The linear predictor changes where the sweeps start, not what they
/// solve: both predictors reach the same meshes, the linear one in fewer
/// sweeps once two steps are solved (with the fixed reference a motion
/// linear in time is predicted exactly).
#[test]
fn linear_predictor_reaches_the_same_meshes_in_fewer_sweeps() {
    let mesh = square(16);
    let lift = Motion::Translation {
        displacement: [0.0, 0.2, 0.0],
    };
    for reference in [Reference::Updated, Reference::Fixed, Reference::Anchored] {
        let run = |predictor: Predictor| {
            let mut settings = Settings::new(6);
            settings.reference = reference;
            settings.predictor = predictor;
            settings.solve.tolerance = 1e-10;
            let attachments = [
                attach(&["top"], lift.clone()),
                attach(&["left", "right", "bottom"], Motion::Fixed),
            ];
            let mut d = Deformer::new(&mesh, &attachments, settings).unwrap();
            let sweeps: Vec<usize> = (1..=6).map(|n| d.step(n).unwrap().iterations).collect();
            (d.current().coords.clone(), sweeps)
        };
        let (previous, slow) = run(Predictor::Previous);
        let (linear, fast) = run(Predictor::Linear);
        let gap = previous
            .iter()
            .zip(&linear)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(gap < 1e-8, "{reference:?}: meshes differ by {gap}");
        let first = if reference == Reference::Updated {
            2
        } else {
            1
        };
        assert_eq!(slow[..first], fast[..first], "{reference:?}");
        assert!(
            fast[first..].iter().sum::<usize>() < slow[first..].iter().sum::<usize>(),
            "{reference:?}: {fast:?} vs {slow:?}"
        );
    }
}

#[test]
fn sliding_walls_let_nodes_move_along_them() {
    let mesh = square(6);
    let attachments = [
        attach(
            &["right"],
            Motion::Translation {
                displacement: [0.2, 0.0, 0.0],
            },
        ),
        attach(&["bottom", "top"], Motion::Slide { normal: None }),
    ];
    let mut settings = Settings::new(2);
    settings.solve.tolerance = 1e-12;
    let mut d = Deformer::new(&mesh, &attachments, settings).unwrap();
    // Corner nodes lie on the fixed left wall or the moving right wall.
    assert_eq!(d.roles()[0], NodeRole::Fixed);
    assert_eq!(d.roles()[1], NodeRole::Slide(0));
    assert_eq!(d.roles()[6], NodeRole::Fixed);
    d.step(2).unwrap();
    let x = &d.current().coords;
    for i in 1..6 {
        // Bottom nodes stay on y = 0 and moved right.
        assert!(x[2 * i + 1].abs() < 1e-12);
        assert!(x[2 * i] > mesh.coords[2 * i] + 1e-3);
    }
    // The right wall moved by 0.2 exactly.
    assert_eq!(x[2 * 6], 1.2);
}

#[test]
fn moving_group_wins_over_fixed_group() {
    let mesh = square(4);
    let attachments = [
        attach(&["bottom"], Motion::Fixed),
        attach(
            &["left"],
            Motion::Translation {
                displacement: [0.0, 0.1, 0.0],
            },
        ),
    ];
    let mut d = Deformer::new(&mesh, &attachments, Settings::new(1)).unwrap();
    d.step(1).unwrap();
    // Node 0 is on both groups and follows the moving one.
    assert_eq!(&d.current().coords[0..2], &[0.0, 0.1]);
    // Node 1 is only on the fixed group.
    assert_eq!(&d.current().coords[2..4], &[0.25, 0.0]);
}

#[test]
fn inversion_stops_with_the_step_element_place_and_volume() {
    let mesh = square(1);
    let push = Motion::Translation {
        displacement: [2.0, 0.0, 0.0],
    };
    let mut d = Deformer::new(&mesh, &[attach(&["left"], push)], Settings::new(2)).unwrap();
    // Step 1: the left wall reaches x = 1, the cells are flat.
    let e = d.step(1).unwrap_err();
    assert_eq!(
        e.to_string(),
        "step 1: element 1 inverted at (1.000000, 0.333333), signed volume 0.000e0 (2 inverted element(s))"
    );
    assert_eq!(d.current_step(), 0);
    assert_eq!(d.current().coords, mesh.coords);
    let failed = d.failed().unwrap();
    assert_eq!(failed.report.inverted, 2);
    assert_eq!(failed.inverted, vec![true, true]);
    let e = d.step(2).unwrap_err();
    assert_eq!(
        e.to_string(),
        "step 2: element 1 inverted at (1.333333, 0.333333), signed volume -5.000e-1 (2 inverted element(s))"
    );
}

#[test]
fn given_positions_each_step_match_the_translation_they_trace() {
    let mesh = square(4);
    let d = [0.1, 0.05, 0.0];
    let translation = Motion::Translation { displacement: d };
    let given = Motion::Positions(PositionSource::Given(HashMap::new()));
    let fixed = attach(&["bottom"], Motion::Fixed);
    let mut by_motion = Deformer::new(
        &mesh,
        &[attach(&["left"], translation), fixed.clone()],
        Settings::new(3),
    )
    .unwrap();
    let mut by_data =
        Deformer::new(&mesh, &[attach(&["left"], given), fixed], Settings::new(3)).unwrap();
    assert_eq!(
        by_data.step(1).unwrap_err().to_string(),
        "invalid setting: the positions give no position for node index 0 of a moving group"
    );
    assert_eq!(
        by_data
            .set_motion(1, Motion::Fixed)
            .unwrap_err()
            .to_string(),
        "invalid setting: attachment 1: only a moving motion can replace a moving motion"
    );
    assert_eq!(
        by_data
            .set_motion(2, Motion::Fixed)
            .unwrap_err()
            .to_string(),
        "invalid setting: there is no attachment 2 (the deformer has 2)"
    );
    for n in 1..=3 {
        let f = n as f64 / 3.0;
        let left = mesh.group("left").unwrap().nodes();
        let positions = left
            .iter()
            .map(|&i| {
                (
                    i,
                    vec![mesh.point(i)[0] + f * d[0], mesh.point(i)[1] + f * d[1]],
                )
            })
            .collect();
        by_data
            .set_motion(0, Motion::Positions(PositionSource::Given(positions)))
            .unwrap();
        let a = by_motion.advance().unwrap();
        let b = by_data.advance().unwrap();
        assert_eq!((a.step, a.iterations), (b.step, b.iterations));
        assert_eq!(by_motion.current().coords, by_data.current().coords);
    }
}

#[test]
fn unknown_group_is_named() {
    let mesh = square(2);
    let e = Deformer::new(&mesh, &[attach(&["wing"], Motion::Fixed)], Settings::new(1))
        .err()
        .unwrap();
    assert_eq!(
        e.to_string(),
        "unknown group 'wing' (the mesh has: left, right, bottom, top)"
    );
}

/// Settings with the recommended near-wall treatments (the blend on).
fn recommended(steps: usize) -> Settings {
    let mut s = Settings::new(steps);
    s.robust = Robust::recommended();
    s
}

#[test]
fn a_rigid_pitch_is_blended_and_leaves_the_springs_nothing() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let rotation = Motion::Rotation {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        angle: 30f64.to_radians(),
    };
    let mut d = Deformer::new(&mesh, &[attach(&["airfoil"], rotation)], recommended(10)).unwrap();
    let farfield = mesh.group("farfield").unwrap().nodes();
    for n in 1..=10 {
        let r = d.step(n).unwrap();
        assert_eq!((r.inverted, r.iterations), (0, 0), "step {n}");
        assert!(r.stages.is_empty(), "step {n}: {:?}", r.stages);
        assert!(r.min_quality > 0.3, "step {n}: {}", r.min_quality);
    }
    let x = &d.current().coords;
    for &i in &farfield {
        assert_eq!(&x[2 * i..2 * i + 2], mesh.point(i));
    }
    // Every free node turned by between 0 and 30° about the quarter chord.
    for i in 0..mesh.node_count() {
        let p = mesh.point(i);
        let (a, b) = ([p[0] - 0.25, p[1]], [x[2 * i] - 0.25, x[2 * i + 1]]);
        let turned = (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
        assert!(
            (-1e-9..=30f64.to_radians() + 1e-9).contains(&turned),
            "node {i} turned {turned}"
        );
    }
}

#[test]
fn a_translation_between_sliding_walls_keeps_them_in_their_planes() {
    let mesh = square(8);
    let attachments = [
        attach(
            &["right"],
            Motion::Translation {
                displacement: [-0.3, 0.0, 0.0],
            },
        ),
        attach(&["bottom", "top"], Motion::Slide { normal: None }),
    ];
    let mut d = Deformer::new(&mesh, &attachments, recommended(3)).unwrap();
    for n in 1..=3 {
        let r = d.step(n).unwrap();
        assert_eq!((r.inverted, r.iterations), (0, 0));
    }
    let x = &d.current().coords;
    for i in 0..mesh.node_count() {
        let p = mesh.point(i);
        if p[1] == 0.0 || p[1] == 1.0 {
            assert_eq!(x[2 * i + 1], p[1], "node {i} left its wall");
        }
        // A translation along the walls: every node moves along x only,
        // by the share its weight gives, the right wall by all of it.
        assert!((x[2 * i + 1] - p[1]).abs() < 1e-12);
        assert!((-0.3 - 1e-12..=1e-12).contains(&(x[2 * i] - p[0])));
    }
}

#[test]
fn a_deforming_body_leaves_the_springs_its_deformation() {
    let mesh = square(8);
    // The right wall bends: its nodes move by 0.1 y (1 − y), not a rigid motion.
    let table: HashMap<usize, Vec<f64>> = mesh
        .group("right")
        .unwrap()
        .nodes()
        .into_iter()
        .map(|i| {
            let p = mesh.point(i);
            (i, vec![p[0] - 0.1 * p[1] * (1.0 - p[1]), p[1]])
        })
        .collect();
    let attachments = [attach(
        &["right"],
        Motion::Positions(PositionSource::Given(table.clone())),
    )];
    let mut d = Deformer::new(&mesh, &attachments, recommended(1)).unwrap();
    let r = d.step(1).unwrap();
    assert!(r.converged && r.iterations > 0, "{r:?}");
    let x = &d.current().coords;
    for (i, p) in &table {
        assert_eq!(&x[2 * i..2 * i + 2], p.as_slice());
    }
    // The interior follows the bend: the middle row moved left by less
    // than the wall's middle node (0.025), the bottom and top rows stayed.
    let node = |i: usize, j: usize| j * 9 + i;
    for i in 1..8 {
        let m = node(i, 4);
        let dx = x[2 * m] - mesh.point(m)[0];
        assert!(dx < -1e-4 && dx > -0.025, "node {m}: {dx}");
        for j in [0, 8] {
            let k = node(i, j);
            assert_eq!(&x[2 * k..2 * k + 2], mesh.point(k));
        }
    }
}

/// `square(n)` with two of its sides (`bottom` and `top`, a channel's two
/// walls, or `bottom` and `right`) made one group, `walls`.
fn square_with_walls(n: usize, sides: [&str; 2]) -> Mesh {
    let mut mesh = square(n);
    let mut walls = mesh.group(sides[0]).unwrap().clone();
    for (kind, nodes) in mesh.group(sides[1]).unwrap().facets.iter() {
        walls.facets.push(kind, nodes);
    }
    walls.name = "walls".into();
    mesh.groups.retain(|g| !sides.contains(&g.name.as_str()));
    mesh.groups.push(walls);
    mesh
}

#[test]
fn a_group_of_two_parallel_walls_slides() {
    let mesh = square_with_walls(6, ["bottom", "top"]);
    let attachments = [
        attach(
            &["right"],
            Motion::Translation {
                displacement: [0.2, 0.0, 0.0],
            },
        ),
        attach(&["walls"], Motion::Slide { normal: None }),
    ];
    let mut settings = Settings::new(2);
    settings.solve.tolerance = 1e-12;
    let mut d = Deformer::new(&mesh, &attachments, settings).unwrap();
    assert_eq!(d.normals(), [[0.0, 1.0, 0.0]]);
    d.step(2).unwrap();
    let x = &d.current().coords;
    // Bottom nodes 1..6 and top nodes 43..48 stay on their wall and moved right.
    for i in (1..6).chain(43..48) {
        assert_eq!(d.roles()[i], NodeRole::Slide(0));
        assert_eq!(
            x[2 * i + 1],
            mesh.coords[2 * i + 1],
            "node {i} left its wall"
        );
        assert!(
            x[2 * i] > mesh.coords[2 * i] + 1e-3,
            "node {i} did not slide"
        );
    }
}

#[test]
fn a_group_that_is_not_planar_asks_for_a_normal_or_a_split() {
    let mesh = square_with_walls(2, ["bottom", "right"]);
    let attachments = [
        attach(
            &["top"],
            Motion::Translation {
                displacement: [0.1, 0.0, 0.0],
            },
        ),
        attach(&["walls"], Motion::Slide { normal: None }),
    ];
    let e = Deformer::new(&mesh, &attachments, Settings::new(1))
        .err()
        .unwrap();
    assert_eq!(
        e.to_string(),
        "invalid setting: group 'walls' is not made of parallel planes (its facet centred at \
         (0.250000, 0.000000) is at 45.00° from the plane of normal (-0.707107, 0.707107), \
         more than 5.7e-5°): \
         give the slide motion a `normal` (`--slide GROUP:NX,NY[,NZ]`) or split the group \
         into its planes"
    );
    // With a normal the same group slides along it.
    let attachments = [
        attachments[0].clone(),
        attach(
            &["walls"],
            Motion::Slide {
                normal: Some([0.0, 1.0, 0.0]),
            },
        ),
    ];
    assert!(Deformer::new(&mesh, &attachments, Settings::new(1)).is_ok());
}

#[test]
fn a_slide_normal_across_the_groups_plane_is_refused_and_cad_noise_is_a_plane() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/meshes/symmetry-slice.msh");
    let mut mesh = crate::io::read(&path).unwrap();
    let slide = |mesh: &Mesh, normal: Option<[f64; 3]>| {
        let attachments = [
            attach(
                &["body"],
                Motion::Translation {
                    displacement: [1.0, 0.0, 0.0],
                },
            ),
            attach(&["symmetry_y"], Motion::Slide { normal }),
        ];
        Deformer::new(mesh, &attachments, Settings::new(1)).map(|d| d.normals()[0])
    };
    assert_eq!(
        slide(&mesh, Some([0.0, 0.0, 1.0])).unwrap_err().to_string(),
        "invalid setting: the slide normal (0.000000, 0.000000, 1.000000) given for group \
         'symmetry_y' is at 90.00° from the group's own plane (normal (0.000000, -1.000000, \
         0.000000)): its nodes would leave that plane; give its normal or none"
    );
    assert!(slide(&mesh, Some([0.0, 1.0, 1e-4])).is_ok());
    // The plane y = 0 written with ±10⁻⁷ of noise, as CAD exports do.
    let plane = mesh.group("symmetry_y").unwrap().nodes();
    for (k, &i) in plane.iter().enumerate() {
        mesh.coords[3 * i + 1] = if k % 2 == 0 { 1e-7 } else { -1e-7 };
    }
    let n = slide(&mesh, None).unwrap();
    assert!((n[1].abs() - 1.0).abs() < 1e-6, "{n:?}");
}

#[test]
fn nodes_where_two_slide_planes_meet_slide_along_the_line_and_where_three_meet_stay() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/meshes/symmetry-slice.msh");
    let mesh = crate::io::read(&path).unwrap();
    let slide = |groups: &[&str]| {
        let attachments = [
            attach(
                &["body"],
                Motion::Translation {
                    displacement: [1.0, 0.0, 0.0],
                },
            ),
            attach(groups, Motion::Slide { normal: None }),
        ];
        Deformer::new(&mesh, &attachments, Settings::new(1)).unwrap()
    };
    let on = |name: &str, i: usize| mesh.group(name).unwrap().nodes().contains(&i);
    let at = |x: f64, y: f64, z: f64| {
        (0..mesh.node_count())
            .find(|&i| mesh.point(i) == [x, y, z])
            .unwrap()
    };
    // Two planes: the x axis between the inlet and the body is a line.
    let d = slide(&["symmetry_y", "symmetry_z"]);
    let line: Vec<usize> = (0..mesh.node_count())
        .filter(|&i| on("symmetry_y", i) && on("symmetry_z", i))
        .filter(|&i| !on("inlet", i) && !on("outlet", i) && !on("body", i))
        .collect();
    assert!(!line.is_empty());
    for &i in &line {
        let NodeRole::Line(k) = d.roles()[i] else {
            panic!("node {i} is {:?}", d.roles()[i]);
        };
        let t = d.normals()[k];
        assert!((t[0].abs() - 1.0).abs() < 1e-12 && t[1] == 0.0 && t[2] == 0.0);
    }
    assert_eq!(d.roles()[at(0.0, 0.0, 0.0)], NodeRole::Fixed);
    // A plane that meets a fixed group: fixed there.
    assert_eq!(d.roles()[at(0.0, 6.0, 0.0)], NodeRole::Fixed);
    // A third plane, the inlet: its corner with both is fixed, its edge
    // with one of them is a line along the other's in-plane axis.
    let d = slide(&["symmetry_y", "symmetry_z", "inlet"]);
    assert_eq!(d.roles()[at(0.0, 0.0, 0.0)], NodeRole::Fixed);
    let edge = (0..mesh.node_count())
        .find(|&i| on("inlet", i) && on("symmetry_y", i) && !on("symmetry_z", i) && !on("top", i))
        .unwrap();
    let NodeRole::Line(k) = d.roles()[edge] else {
        panic!("node {edge} is {:?}", d.roles()[edge]);
    };
    assert!((d.normals()[k][2].abs() - 1.0).abs() < 1e-12);
}

#[test]
fn a_step_reports_the_seconds_of_its_springs_and_of_its_check() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let rotation = Motion::Rotation {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        angle: 2f64.to_radians(),
    };
    let mut d = Deformer::new(&mesh, &[attach(&["airfoil"], rotation)], Settings::new(2)).unwrap();
    for n in 1..=2 {
        let r = d.step(n).unwrap();
        assert!(
            r.springs_seconds > 0.0 && r.springs_seconds <= r.form_seconds,
            "{r:?}"
        );
        assert!(r.check_seconds > 0.0, "{r:?}");
        let parts = r.form_seconds + r.solve_seconds + r.check_seconds;
        assert!(parts <= r.seconds, "{r:?}");
    }
}
