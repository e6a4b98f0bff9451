use super::*;
use crate::near_wall::Layer;
use crate::solve::{Accel, Method, Solver};

#[test]
fn named_values_give_what_the_command_line_builds_in_any_order() {
    assert_eq!(
        Settings::named::<&str, &str>(3, &[]).unwrap(),
        Settings::robust(3)
    );
    let given = [
        ("rigid_layer", "0.1"),
        ("method", "verbss"),
        ("omega", "1.5"),
        ("substeps", "3"),
        ("stiffening", "2"),
        ("blend", "on"),
        ("predictor", "linear"),
        ("reference", "initial"),
        ("absolute_tolerance", "on"),
        ("tolerance", "1e-8"),
        ("max_iterations", "50"),
        ("threads", "2"),
        ("accel", "amg"),
    ];
    let mut expected = Settings::paper(4);
    expected.reference = Reference::Fixed;
    expected.predictor = Predictor::Linear;
    let s = &mut expected.solve;
    (s.omega, s.tolerance, s.absolute_tolerance) = (1.5, 1e-8, true);
    (s.max_iterations, s.threads, s.accel, s.escalate) = (50, 2, Accel::Amg, false);
    let r = &mut expected.robust;
    (r.layer, r.substeps, r.stiffening, r.blend) = (Layer::Thickness(0.1), 3, 2.0, true);
    assert_eq!(Settings::named(4, &given).unwrap(), expected);
    // A solver given means exactly that solver, as on the command line.
    let direct = Settings::named(1, &[("method", "ball-vertex"), ("solver", "direct")]).unwrap();
    assert_eq!(
        (direct.solve.solver, direct.solve.escalate),
        (Solver::Direct, false)
    );
    assert!(
        Settings::named(1, &[("tolerance", "1e-3")])
            .unwrap()
            .solve
            .escalate
    );
    // ... unless escalation is asked for too, in either order.
    for order in [
        [("omega", "1.2"), ("escalate", "on")],
        [("escalate", "on"), ("omega", "1.2")],
    ] {
        let s = Settings::named(1, &order).unwrap();
        assert_eq!((s.solve.omega, s.solve.escalate), (1.2, true));
    }
}

#[test]
fn the_presets_are_the_table_columns() {
    let robust = Settings::robust(5);
    assert_eq!(robust.robust, Robust::recommended());
    assert_eq!(robust.reference, Reference::Auto);
    assert_eq!(robust.solve.method, Method::Verbss);
    assert!(robust.solve.escalate);
    let paper = Settings::paper(5);
    assert_eq!(paper.robust, Robust::off());
    assert_eq!(paper.reference, Reference::Updated);
    for preset in [
        Preset::Robust,
        Preset::Verbss,
        Preset::BallVertex,
        Preset::Spring,
        Preset::Laplacian,
    ] {
        let s = preset.settings(7);
        assert_eq!(s.preset(), preset);
        // One worker per core on every front end.
        assert_eq!(s.solve.threads, 0);
        for setting in TABLE {
            assert_eq!(
                setting.get(&s).text(),
                Setting::named(setting.name)
                    .unwrap()
                    .values
                    .parse(setting.name, setting.value_in(preset))
                    .unwrap()
                    .text(),
                "{} under {preset}",
                setting.name
            );
        }
    }
}

/// Every setting's value, given back by name, gives the same settings: a
/// report's `settings` re-creates the run.
#[test]
fn the_values_given_back_are_the_same_settings() {
    let mut odd = Settings::named(
        9,
        &[
            ("method", "spring"),
            ("rigid_layer", "0.0123456789"),
            ("omega", "1.2345678901234567"),
            ("tolerance", "3.3e-9"),
            ("threads", "3"),
            ("reference", "anchored"),
            ("predictor", "linear"),
        ],
    )
    .unwrap();
    odd.robust.substeps = 4;
    for s in [Settings::robust(9), Settings::paper(9), odd] {
        let values: Vec<(&str, String)> =
            s.values().into_iter().map(|(n, v)| (n, v.text())).collect();
        assert_eq!(values.len(), TABLE.len());
        assert_eq!(Settings::named(9, &values).unwrap(), s);
    }
}

#[test]
fn every_range_of_the_table_is_checked() {
    let cases = [
        ("omega", "2.5", "omega must be a number in (0, 2) (got 2.5)"),
        ("omega", "0", "omega must be a number in (0, 2) (got 0)"),
        (
            "tolerance",
            "-1",
            "tolerance must be a finite number ≥ 0 (got -1)",
        ),
        (
            "tolerance",
            "inf",
            "tolerance must be a finite number ≥ 0 (got inf)",
        ),
        (
            "stiffening",
            "1e308000",
            "stiffening must be a finite number ≥ 0 (got inf)",
        ),
        (
            "substeps",
            "40",
            "substeps must be a whole number from 0 to 30 (got 40)",
        ),
        (
            "substeps",
            "99999999999",
            "substeps must be a whole number from 0 to 30 (got 99999999999)",
        ),
        (
            "max_iterations",
            "0",
            "max_iterations must be a whole number ≥ 1 (got 0)",
        ),
        (
            "threads",
            "-1",
            "threads must be a whole number from 0 to 4096 (got -1)",
        ),
        (
            "rigid_layer",
            "-1",
            "rigid_layer must be off, auto or a positive wall distance (got -1)",
        ),
    ];
    for (name, value, message) in cases {
        let e = Settings::check(name, value).unwrap_err().to_string();
        assert_eq!(e, format!("invalid setting: {message}"), "{name} = {value}");
    }
    // The same ranges hold for settings made as structs.
    let mut s = Settings::robust(1);
    s.solve.omega = 1e300;
    assert_eq!(
        s.validate().unwrap_err().to_string(),
        "invalid setting: omega must be a number in (0, 2) (got 1e300)"
    );
    let mut s = Settings::robust(1);
    s.robust.substeps = 31;
    assert_eq!(
        s.validate().unwrap_err().to_string(),
        "invalid setting: substeps must be a whole number from 0 to 30 (got 31)"
    );
}

#[test]
fn wrong_names_and_spellings_are_named() {
    let cases = [
        (
            "omegga",
            "1.5",
            "unknown setting 'omegga' (expected method, reference, predictor, rigid_layer, \
             stiffening, substeps, blend, relocate, solver, accel, escalate, omega, tolerance, \
             absolute_tolerance, max_iterations or threads)",
        ),
        (
            "method",
            "fast",
            "unknown method 'fast' (expected robust, verbss, ball-vertex, spring or laplacian)",
        ),
        (
            "omega",
            "fast",
            "omega must be a number in (0, 2) (got 'fast')",
        ),
        (
            "threads",
            "1.5",
            "threads must be a whole number from 0 to 4096 (got '1.5')",
        ),
        ("blend", "yes", "blend must be on or off (got 'yes')"),
        (
            "reference",
            "current",
            "unknown reference 'current' (expected auto, updated, fixed or anchored)",
        ),
    ];
    for (name, value, message) in cases {
        let e = Settings::check(name, value).unwrap_err().to_string();
        assert_eq!(e, format!("invalid setting: {message}"), "{name} = {value}");
    }
    let e = Settings::named(1, &[("accel", "amg"), ("method", "ball-vertex")]).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("invalid setting: accel amg solves"),
        "{e}"
    );
}

#[test]
fn auto_is_the_motions_reference() {
    let periodic = Motion::PitchPlunge {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        pitch: 0.1,
        plunge: [0.0, 0.1, 0.0],
        period: None,
    };
    let one_way = Motion::Translation {
        displacement: [1.0, 0.0, 0.0],
    };
    assert_eq!(
        Reference::Auto.resolved([&periodic, &Motion::Fixed]),
        Reference::Anchored
    );
    assert_eq!(
        Reference::Auto.resolved([&periodic, &one_way]),
        Reference::Updated
    );
    assert_eq!(
        Reference::Auto.resolved([&Motion::Fixed]),
        Reference::Updated
    );
    assert_eq!(Reference::Fixed.resolved([&periodic]), Reference::Fixed);
}

#[test]
fn a_slide_normal_has_the_mesh_dimension() {
    let own = Attachment::slide("sym", None, 3).unwrap();
    assert_eq!(own.motion, Motion::Slide { normal: None });
    let given = Attachment::slide("sym", Some(&[0.0, 2.0]), 2).unwrap();
    assert_eq!(given.groups, ["sym"]);
    assert_eq!(
        given.motion,
        Motion::Slide {
            normal: Some([0.0, 1.0, 0.0])
        }
    );
    let e = Attachment::slide("sym", Some(&[0.0, 0.0, 1.0]), 2).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: the slide normal of group 'sym' has z = 1 on a 2D mesh: give \
         NX,NY (or NX,NY,0)"
    );
    let flat = Attachment::slide("sym", Some(&[0.0, 1.0, 0.0]), 2).unwrap();
    assert_eq!(
        flat.motion,
        Motion::Slide {
            normal: Some([0.0, 1.0, 0.0])
        }
    );
    let e = Attachment::slide("sym", Some(&[1.0, 0.0, 1.0, 0.0]), 3).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: the slide normal of group 'sym' has 4 numbers, expected 3 \
         (the mesh's dimension)"
    );
    let e = Attachment::slide("sym", Some(&[0.0, 0.0]), 2).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: the slide normal of group 'sym' must be a finite non-zero \
         vector (got 0, 0)"
    );
}

/// docs/case-file.md's table of the `[solver]` settings is [`markdown_table`].
#[test]
fn the_docs_table_is_the_table() {
    let doc = include_str!("../../../../docs/case-file.md");
    let start = "<!-- settings table: generated from crates/verbss/src/settings/table.rs -->\n";
    let from = doc.find(start).expect("the docs mark the table") + start.len();
    let to = from + doc[from..].find("<!-- end of settings table -->").unwrap();
    assert_eq!(
        &doc[from..to],
        markdown_table(),
        "docs/case-file.md's settings table differs from the table: paste markdown_table()"
    );
}
