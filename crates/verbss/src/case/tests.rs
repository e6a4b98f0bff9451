use super::*;
use crate::near_wall::{Layer, Robust};
use crate::settings::Reference;
use crate::solve::{Accel, Method, Solver};

fn parse(text: &str) -> Result<Case> {
    Case::parse(text, Path::new("cases/c.toml"))
}

fn err(text: &str) -> String {
    parse(text).unwrap_err().to_string()
}

#[test]
fn parses_a_full_case() {
    let c = parse(
        r#"
mesh = "../m/naca.su2"
steps = 160
[solver]
reference = "fixed"
method = "ball-vertex"
solver = "direct"
accel = "auto"
omega = 1.5
tolerance = 1e-5
absolute_tolerance = true
max_iterations = 300
threads = 2
[[motion]]
kind = "pitch-plunge"
groups = ["airfoil"]
center = [0.25, 0.0]
pitch_deg = 40
plunge = [0.0, 0.2]
[[motion]]
kind = "fixed"
groups = ["farfield"]
[output]
dir = "out/naca"
every = 4
final = false
"#,
    )
    .unwrap();
    assert_eq!(c.mesh, PathBuf::from("cases/../m/naca.su2"));
    assert_eq!(c.settings.steps, 160);
    assert_eq!(c.settings.dt, 1.0 / 160.0);
    assert_eq!(c.settings.reference, Reference::Fixed);
    let s = &c.settings.solve;
    assert_eq!(s.method, Method::BallVertex);
    assert_eq!(s.solver, Solver::Direct);
    assert_eq!(s.accel, Accel::Auto);
    assert_eq!(
        (s.omega, s.tolerance, s.max_iterations, s.threads),
        (1.5, 1e-5, 300, 2)
    );
    assert!(s.absolute_tolerance);
    assert_eq!(c.motions.len(), 2);
    assert_eq!(c.motions[0].0, 14);
    // `reference` belongs to the `[solver]` table, where report.json writes it.
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\nreference = \"fixed\"\n"),
        "cases/c.toml:3: `reference` is a setting of the `[solver]` table: move it there"
    );
    assert_eq!(c.output.dir, Some(PathBuf::from("cases/out/naca")));
    assert_eq!(c.output.every, 4);
    assert!(!c.output.final_mesh && c.output.series && c.output.report);
}

#[test]
fn unknown_top_level_key() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\nstep = 4\n"),
        "cases/c.toml:3: unknown field `step`, expected one of `mesh`, `zone`, `steps`, `dt`, `reference`, `solver`, `motion`, `output`"
    );
}

#[test]
fn the_zone_of_a_multi_zone_mesh() {
    let zone = |text: &str| parse(text).unwrap().zone;
    assert_eq!(zone("mesh = \"fsi.su2\"\nzone = 2\nsteps = 3\n"), Some(2));
    assert_eq!(zone("mesh = \"fsi.su2\"\nsteps = 3\n"), None);
    assert_eq!(
        err("mesh = \"fsi.su2\"\nsteps = 3\nzone = 0\n"),
        "cases/c.toml:3: `zone` must be at least 1"
    );
    assert!(err("mesh = \"fsi.su2\"\nzone = -1\nsteps = 3\n").starts_with("cases/c.toml:2: "));
}

#[test]
fn missing_mesh() {
    assert_eq!(err("steps = 3\n"), "cases/c.toml:1: missing field `mesh`");
}

#[test]
fn wrong_type() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = \"ten\"\n"),
        "cases/c.toml:2: invalid type: string \"ten\", expected usize"
    );
}

#[test]
fn unknown_setting_names_the_known_ones() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\n[solver]\nomegga = 1.5\n"),
        "cases/c.toml:4: `solver.omegga`: unknown setting 'omegga' (expected method, \
         reference, predictor, rigid_layer, stiffening, substeps, blend, relocate, solver, accel, \
         escalate, omega, tolerance, absolute_tolerance, max_iterations or threads)"
    );
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\n[solver]\nblend = [1]\n"),
        "cases/c.toml:4: `solver.blend` must be a string, a number or true/false (got [1])"
    );
}

#[test]
fn unknown_method() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\n[solver]\nmethod = \"fem\"\n"),
        "cases/c.toml:4: `solver.method`: unknown method 'fem' (expected robust, verbss, ball-vertex, spring or laplacian)"
    );
}

#[test]
fn near_wall_treatments_follow_the_method_unless_given() {
    let head = "mesh = \"m.su2\"\nsteps = 3\n";
    let robust = parse(head).unwrap().settings.robust;
    assert_eq!(robust, Robust::recommended());
    let paper = parse(&format!("{head}[solver]\nmethod = \"verbss\"\n"))
        .unwrap()
        .settings
        .robust;
    assert_eq!(paper, Robust::off());
    let mixed = parse(&format!(
        "{head}[solver]\nmethod = \"verbss\"\nrigid_layer = 0.2\nsubsteps = 3\nstiffening = 2.0\n"
    ))
    .unwrap()
    .settings
    .robust;
    assert_eq!(mixed.layer, Layer::Thickness(0.2));
    assert_eq!((mixed.substeps, mixed.stiffening), (3, 2.0));
    let off = parse(&format!("{head}[solver]\nrigid_layer = \"off\"\n"))
        .unwrap()
        .settings
        .robust;
    assert_eq!(off.layer, Layer::Off);
    assert_eq!(
        err(&format!("{head}[solver]\nrigid_layer = \"thick\"\n")),
        "cases/c.toml:4: `solver.rigid_layer`: rigid_layer must be off, auto or a positive wall distance (got 'thick')"
    );
    assert_eq!(
        err(&format!("{head}[solver]\nrigid_layer = -0.5\n")),
        "cases/c.toml:4: `solver.rigid_layer`: rigid_layer must be off, auto or a positive wall distance (got -0.5)"
    );
    assert_eq!(
        err(&format!("{head}[solver]\nsubsteps = 40\n")),
        "cases/c.toml:4: `solver.substeps`: substeps must be a whole number from 0 to 30 (got 40)"
    );
    assert_eq!(
        err(&format!("{head}[solver]\nstiffening = -1.0\n")),
        "cases/c.toml:4: `solver.stiffening`: stiffening must be a finite number ≥ 0 (got -1)"
    );
}

#[test]
fn unknown_motion_kind() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\n[[motion]]\nkind = \"spin\"\ngroups = [\"a\"]\n"),
        "cases/c.toml:4: unknown variant `spin`, expected one of `fixed`, `slide`, `translation`, `rotation`, `pitch-plunge`, `undulation`, `bending`, `positions`"
    );
}

#[test]
fn unknown_motion_key() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\n[[motion]]\nkind = \"rotation\"\ngroups = [\"a\"]\ncenter = [0, 0]\nangle = 3\n"),
        "cases/c.toml:3: unknown field `angle`, expected one of `groups`, `center`, `axis`, `angle_deg`"
    );
}

#[test]
fn missing_motion_key() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 3\n[[motion]]\nkind = \"translation\"\ngroups = [\"a\"]\n"),
        "cases/c.toml:3: missing field `displacement`"
    );
}

#[test]
fn out_of_range_values() {
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 0\n"),
        "cases/c.toml:2: `steps` must be at least 1"
    );
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 2\n[solver]\nomega = 2.5\n"),
        "cases/c.toml:4: `solver.omega`: omega must be a number in (0, 2) (got 2.5)"
    );
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 2\n[output]\nevery = 0\n"),
        "cases/c.toml:4: `output.every` must be at least 1"
    );
    assert_eq!(
        err("mesh = \"m.su2\"\nsteps = 2\n[[motion]]\nkind = \"fixed\"\ngroups = []\n"),
        "cases/c.toml:3: `groups` must name at least one group"
    );
}

/// A 2D mesh turns about z: −z turns it the other way, and an axis in its
/// plane is refused (it was taken and ignored).
#[test]
fn a_rotation_axis_on_a_2d_mesh_is_z_or_refused() {
    assert_eq!(rotation_axis(None, 2), Ok([0.0, 0.0, 1.0]));
    assert_eq!(
        rotation_axis(Some(&[0.0, 0.0, -1.0]), 2),
        Ok([0.0, 0.0, -1.0])
    );
    assert_eq!(
        rotation_axis(Some(&[0.0, 0.0, 2.0]), 2),
        Ok([0.0, 0.0, 1.0])
    );
    assert_eq!(
        rotation_axis(Some(&[1.0, 0.0, 0.0]), 2),
        Err(
            "`axis` [1.0, 0.0, 0.0] on a 2D mesh, which turns in its x–y plane (give \
             [0, 0, 1], or [0, 0, -1] for the opposite sense, or leave it out)"
                .to_string()
        )
    );
    assert!(rotation_axis(Some(&[0.0, 1.0]), 2).is_err());
    assert_eq!(
        rotation_axis(Some(&[1.0, 0.0, 0.0]), 3),
        Ok([1.0, 0.0, 0.0])
    );
}

#[test]
fn vectors_must_match_the_dimension() {
    assert_eq!(vector("center", &[1.0, 2.0], 2), Ok([1.0, 2.0, 0.0]));
    assert_eq!(vector("center", &[1.0, 2.0, 0.0], 2), Ok([1.0, 2.0, 0.0]));
    assert_eq!(
        vector("axis", &[1.0, 2.0], 3),
        Err("`axis` has 2 numbers (expected 3 for a 3D mesh)".to_string())
    );
    assert_eq!(
        vector("displacement", &[0.0, 1.0, 1.0], 2),
        Err(
            "`displacement` has a non-zero z on a 2D mesh, which lies in the x–y plane \
             (give 2 numbers, or 3 with z = 0)"
                .to_string()
        )
    );
}
