//! Times the pictures of a 2D mesh of about 100,000 triangles (the built-in
//! NACA0012 O-grid at 500 × 101 nodes): building the scene, the PNG at 1600 px
//! (plotters' frame + scanline fill + edges), its encoding, and the SVG.
//!
//! `cargo run --release -p verbss-render --example render_timing [-- OUT_DIR]`
//! writes `timing.png` and `timing.svg` to OUT_DIR (default: the system's
//! temporary folder).

use std::path::PathBuf;
use std::time::Instant;

use verbss::generate::{naca0012, AirfoilGrid};
use verbss::quality;
use verbss_render::{Camera, Options, Scene, Section, State};

fn main() -> verbss::Result<()> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(std::env::temp_dir);
    let mut grid = AirfoilGrid::default();
    grid.around = 500;
    grid.layers = 101;
    let mesh = naca0012(&grid)?;
    let q = quality::qualities(&mesh, &mesh.coords, &quality::orientation(&mesh));
    let inverted = vec![false; mesh.cell_count()];
    let state = State {
        coords: &mesh.coords,
        quality: &q,
        inverted: &inverted,
    };
    let time = |what: &str, start: Instant| {
        println!("{what:<28} {:8.1} ms", 1e3 * start.elapsed().as_secs_f64())
    };
    println!("{} cells, {} nodes", mesh.cell_count(), mesh.node_count());
    let t = Instant::now();
    let scene = Scene::new(&mesh, state, &Section::All, Camera::default())?;
    time("scene", t);
    for (name, view) in [("whole", None), ("zoom", Some([-0.2, 1.2, -0.4, 0.4]))] {
        let mut options = Options::default();
        options.view = view;
        let t = Instant::now();
        let image = verbss_render::png(&scene, &options)?;
        time(&format!("png 1600 px, {name}"), t);
        let t = Instant::now();
        let bytes = image.png_bytes()?;
        time(&format!("png encoding ({} kB)", bytes.len() / 1024), t);
        image.write_png(&out.join(format!("timing_{name}.png")))?;
    }
    let t = Instant::now();
    let doc = verbss_render::svg(&scene, &Options::default())?;
    time(&format!("svg ({} MB)", doc.len() / (1 << 20)), t);
    std::fs::write(out.join("timing.svg"), doc).map_err(|source| verbss::Error::Io {
        path: out.join("timing.svg"),
        source,
    })?;
    Ok(())
}
