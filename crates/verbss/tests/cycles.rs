//! Periodic motions with the default settings come back to the mesh they
//! started from (docs/reliability.md, "Long runs"): two cycles of each long
//! run on a small mesh, every step valid, every cycle closed to 10⁻⁹ of the
//! mesh's size. The figures of 20 cycles on the full meshes come from
//! `cargo run --release -p verbss --example long_run`.

use std::path::Path;

use verbss::case::Case;
use verbss::deform::Deformer;
use verbss::generate::{naca0012, AirfoilGrid};
use verbss::mesh::Mesh;
use verbss::motion::{Attachment, Motion};
use verbss::settings::{Reference, Settings};
use verbss::solve::{Method, Solver};

/// The largest node distance between two coordinate sets.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Runs `lead` steps, then `count` cycles of `period` steps with `settings`
/// (every step must be valid); gives the coordinates after the lead and at
/// the end of each cycle.
fn cycle_ends(
    mesh: &Mesh,
    attachments: &[Attachment],
    settings: Settings,
    lead: usize,
    period: usize,
    count: usize,
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mut d = Deformer::new(mesh, attachments, settings).unwrap();
    for _ in 0..lead {
        d.advance().unwrap();
    }
    let origin = d.current().coords.clone();
    let ends = (0..count)
        .map(|_| {
            for _ in 0..period {
                d.advance().unwrap();
            }
            d.current().coords.clone()
        })
        .collect();
    (origin, ends)
}

/// Two cycles as [`cycle_ends`]: the largest node distance from the mesh
/// after the lead at the end of each cycle, relative to the mesh's size.
fn cycles(
    mesh: &Mesh,
    attachments: &[Attachment],
    settings: Settings,
    lead: usize,
    period: usize,
) -> Vec<f64> {
    let (origin, ends) = cycle_ends(mesh, attachments, settings, lead, period, 2);
    let size = mesh.diagonal();
    ends.iter().map(|e| distance(e, &origin) / size).collect()
}

fn pitch_plunge(pitch_deg: f64, plunge: f64, period: usize) -> Vec<Attachment> {
    vec![Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::PitchPlunge {
            center: [0.25, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            pitch: pitch_deg.to_radians(),
            plunge: [0.0, plunge, 0.0],
            period: Some(period),
        },
    }]
}

/// The robust preset's reference follows the motions' kind: anchored for
/// periodic motions, updated for one-way ones; the paper's method is
/// updated.
#[test]
fn the_default_reference_follows_the_motions_kind() {
    assert_eq!(Settings::robust(1).reference, Reference::Auto);
    assert_eq!(Settings::paper(1).reference, Reference::Updated);
    let periodic = &pitch_plunge(15.0, 0.0, 8)[0].motion;
    let one_way = Motion::Rotation {
        center: [0.0; 3],
        axis: [0.0, 0.0, 1.0],
        angle: 1.0,
    };
    assert_eq!(
        Reference::Auto.resolved([periodic, &Motion::Fixed]),
        Reference::Anchored
    );
    assert_eq!(
        Reference::Auto.resolved([periodic, &one_way]),
        Reference::Updated
    );
    assert_eq!(
        Reference::Auto.resolved([&Motion::Fixed]),
        Reference::Updated
    );
    let case = |method: &str, kind: &str| {
        let text = format!(
            "mesh = \"m.su2\"\nsteps = 4\n[solver]\nmethod = \"{method}\"\n\
             [[motion]]\nkind = \"{kind}\"\ngroups = [\"airfoil\"]\ncenter = [0.25, 0.0]\n\
             {}\n[[motion]]\nkind = \"fixed\"\ngroups = [\"farfield\"]\n",
            if kind == "rotation" {
                "angle_deg = 10.0"
            } else {
                "pitch_deg = 10.0\nplunge = [0.0, 0.0]"
            }
        );
        Case::parse(&text, Path::new("c.toml"))
            .unwrap()
            .settings
            .reference
    };
    // A case file leaves the choice to the deformer, which makes it once
    // for every front end (`Reference::resolved`).
    assert_eq!(case("robust", "pitch-plunge"), Reference::Auto);
    assert_eq!(case("robust", "rotation"), Reference::Auto);
    assert_eq!(case("verbss", "pitch-plunge"), Reference::Updated);
    let mesh = naca0012(&AirfoilGrid::default()).unwrap();
    for (attachments, expected) in [
        (pitch_plunge(15.0, 0.0, 8), Reference::Anchored),
        (
            vec![Attachment {
                groups: vec!["airfoil".into()],
                motion: one_way.clone(),
            }],
            Reference::Updated,
        ),
    ] {
        let d = Deformer::new(&mesh, &attachments, Settings::robust(4)).unwrap();
        assert_eq!(d.settings().reference, expected);
    }
}

/// The demo's pitch–plunge (θ₀ = 40°, h₀ = 0.2) on a coarse O-grid, 16 steps a cycle.
#[test]
fn the_demo_pitch_plunge_returns_to_the_input_mesh() {
    let mut grid = AirfoilGrid::default();
    (grid.around, grid.layers) = (60, 14);
    let mesh = naca0012(&grid).unwrap();
    let drift = cycles(
        &mesh,
        &pitch_plunge(40.0, 0.2, 16),
        Settings::robust(32),
        0,
        16,
    );
    assert!(drift.iter().all(|&d| d <= 1e-9), "{drift:?}");
}

/// The RANS C-grid (Gmsh, first cell 10⁻⁵ chord) pitching ±15°, 16 steps a cycle.
#[test]
fn a_rans_grid_pitching_returns_to_the_input_mesh() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mesh = verbss::io::read(&root.join("cases/meshes/cgrid-113x33.msh")).unwrap();
    let drift = cycles(
        &mesh,
        &pitch_plunge(15.0, 0.0, 16),
        Settings::robust(32),
        0,
        16,
    );
    assert!(drift.iter().all(|&d| d <= 1e-9), "{drift:?}");
}

/// The two undulating fish of `cases/two-fish.toml` on a coarse mesh
/// (`two_fish.py --size 0.07`), 12 steps a cycle after a 2-step ramp.
fn coarse_fish() -> (Mesh, Vec<Attachment>, f64) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut case = Case::read(&root.join("cases/two-fish.toml")).unwrap();
    case.mesh = root.join("cases/meshes/two-fish-coarse.msh");
    let mesh = verbss::io::read(&case.mesh).unwrap();
    let mut attachments = case.attachments(&mesh).unwrap();
    for a in &mut attachments {
        if let Motion::Undulation { ramp, .. } = &mut a.motion {
            *ramp = 2;
        }
    }
    (mesh, attachments, case.settings.dt * 5.0)
}

/// The fish deform, so the springs solve every step; solved exactly, each
/// cycle ends on the mesh the ramp ended on.
#[test]
fn the_undulating_fish_come_back_to_the_same_mesh() {
    let (mesh, attachments, dt) = coarse_fish();
    let mut settings = Settings::robust(26);
    settings.dt = dt;
    (settings.solve.method, settings.solve.solver) = (Method::BallVertex, Solver::Direct);
    let drift = cycles(&mesh, &attachments, settings, 2, 12);
    assert!(drift.iter().all(|&d| d <= 1e-9), "{drift:?}");
}

/// With the default sweeps, which stop at their tolerance, the mesh at the
/// end of a cycle is the solution for the boundary's position to that
/// tolerance: the same at the end of every cycle (no drift; the ramp's
/// last step, solved from another start, differs from it by the stop's
/// error only, docs/reliability.md "Long runs").
#[test]
fn the_undulating_fish_do_not_drift_with_the_default_sweeps() {
    let (mesh, attachments, dt) = coarse_fish();
    let mut settings = Settings::robust(2 + 3 * 12);
    settings.dt = dt;
    let (origin, ends) = cycle_ends(&mesh, &attachments, settings, 2, 12, 3);
    let size = mesh.diagonal();
    let per_cycle: Vec<f64> = ends
        .windows(2)
        .map(|w| distance(&w[1], &w[0]) / size)
        .collect();
    assert!(per_cycle.iter().all(|&d| d <= 1e-12), "{per_cycle:?}");
    let from_ramp = distance(&ends[0], &origin) / size;
    assert!(from_ramp <= 1e-4, "{from_ramp:e}");
}
