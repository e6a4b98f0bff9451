//! The TOML case file: parsed, its motions resolved against a small airfoil
//! grid and, when that works, two steps run (sweeps capped so that a step
//! stays fast).
#![no_main]

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use verbss::case::Case;
use verbss::deform::Deformer;
use verbss::generate::{naca0012, AirfoilGrid};
use verbss::Mesh;
use verbss_fuzz::path;

fn airfoil() -> &'static Mesh {
    static MESH: OnceLock<Mesh> = OnceLock::new();
    MESH.get_or_init(|| {
        let mut grid = AirfoilGrid::default();
        grid.around = 16;
        grid.layers = 4;
        naca0012(&grid).expect("a valid grid")
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(case) = Case::parse(text, path("/nonexistent/fuzz.toml")) else {
        return;
    };
    let mesh = airfoil();
    let Ok(attachments) = case.attachments(mesh) else {
        return;
    };
    let mut settings = case.settings.clone();
    settings.solve.max_iterations = settings.solve.max_iterations.min(200);
    if let Ok(mut deformer) = Deformer::new(mesh, &attachments, settings) {
        for _ in 0..2 {
            if deformer.advance().is_err() {
                break;
            }
        }
    }
});
