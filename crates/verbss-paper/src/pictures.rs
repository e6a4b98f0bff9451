//! Pictures of a case's mesh coloured by element quality (the paper's
//! figures): 2D meshes whole or in a window, 3D meshes as a planar cut or as
//! the surfaces of some groups.

use std::path::Path;

use verbss::deform::Snapshot;
use verbss::mesh::Mesh;
use verbss_render::{Camera, Options, Scene, Section, State};

use crate::cases::{PaperCase, View};

/// Width of the pictures in pixels.
const WIDTH: u32 = 1000;

/// Writes `state` of `mesh` as `out/<case>-<what>.png` with `title` in its
/// header; returns the file name.
pub fn write(
    case: &PaperCase,
    mesh: &Mesh,
    state: &Snapshot,
    out: &Path,
    what: &str,
    title: &str,
) -> anyhow::Result<String> {
    let (section, camera, window) = match &case.view {
        View::Plane(window) => (Section::All, Camera::default(), *window),
        View::Cut { axis, at, window } => (
            Section::Cut {
                axis: *axis,
                at: *at,
            },
            Camera::default(),
            *window,
        ),
        View::Surface { groups, camera } => (
            Section::Groups(groups.iter().map(|g| g.to_string()).collect()),
            Camera {
                azimuth: camera.0,
                elevation: camera.1,
            },
            None,
        ),
    };
    let quality = state.qualities(mesh);
    let view = State {
        coords: &state.coords,
        quality: &quality,
        inverted: &state.inverted,
    };
    let scene = Scene::new(mesh, view, &section, camera)?;
    let mut options = Options::default();
    options.width = WIDTH;
    options.view = window;
    options.title = title.to_string();
    let name = format!("{}-{what}.png", case.name);
    verbss_render::png(&scene, &options)?.write_png(&out.join(&name))?;
    Ok(name)
}
