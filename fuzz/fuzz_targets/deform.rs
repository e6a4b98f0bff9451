//! The stepper on small generated meshes of every kind with fuzzed node
//! jitter (tangled inputs included), method, reference, step count and
//! motion parameters (NaN, infinities and huge values included). A step
//! either succeeds with every cell valid or fails with an error; it never
//! panics, and a successful step has finite coordinates.
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::deform::Deformer;
use verbss::settings::{Reference, Settings};
use verbss::mesh::samples::jittered_grid;
use verbss::motion::{Attachment, Motion};
use verbss::solve::{Method, Solver};
use verbss_fuzz::Bytes;

fuzz_target!(
    init: {
        // The sparse LU panics on an exact zero pivot and the solver catches
        // that panic and reports a singular system (as the `verbss` binary
        // does, that caught panic is kept quiet): libFuzzer's hook would
        // abort on it before it is caught.
        let abort = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !info.location().is_some_and(|l| l.file().contains("/faer-")) {
                abort(info);
            }
        }));
    },
    |data: &[u8]| {
    let mut b = Bytes(data);
    let head = b.u8();
    let dim = 2 + usize::from(head % 2);
    let n = 2 + usize::from(b.u8() % if dim == 2 { 4 } else { 2 });
    let kind = b.u8();
    let method = b.u8();
    let reference = b.u8();
    let steps = 1 + usize::from(b.u8() % 3);
    let which = b.u8();
    let v = [b.f64(), b.f64(), b.f64()];
    let amount = b.f64();
    let mut jitter = Bytes(b.0);
    let Some(mesh) = jittered_grid(dim, n, kind, || 0.3 * jitter.unit()) else {
        return;
    };
    let motion = match which % 4 {
        0 => Motion::Translation { displacement: v },
        1 => Motion::Rotation {
            center: v,
            axis: [0.0, 0.0, 1.0],
            angle: amount,
        },
        2 => Motion::PitchPlunge {
            center: [0.5, 0.5, 0.5],
            axis: v,
            pitch: amount,
            plunge: [0.0, 0.1, 0.0],
            period: Some(steps),
        },
        _ => Motion::Slide { normal: Some(v) },
    };
    let mut settings = Settings::new(steps);
    settings.reference = if reference % 2 == 0 {
        Reference::Updated
    } else {
        Reference::Fixed
    };
    settings.solve.max_iterations = 200;
    (settings.solve.method, settings.solve.solver) = match method % 5 {
        0 => (Method::Verbss, Solver::Sor),
        1 => (Method::BallVertex, Solver::Sor),
        2 => (Method::BallVertex, Solver::Direct),
        3 => (Method::Spring, Solver::Sor),
        _ => (Method::Laplacian, Solver::Sor),
    };
    let groups = vec![if which & 4 == 0 { "left" } else { "walls" }.to_string()];
    let Ok(mut deformer) = Deformer::new(&mesh, &[Attachment { groups, motion }], settings) else {
        return;
    };
    for _ in 0..steps {
        match deformer.advance() {
            Ok(report) => {
                assert_eq!(report.inverted, 0);
                assert!(deformer.current().coords.iter().all(|x| x.is_finite()));
            }
            Err(_) => break,
        }
    }
}
);
