//! Multi-zone SU2 files through the commands: `deform --zone K` moves one
//! zone and writes the others back byte for byte, `quality` reports every
//! zone, `convert` and `run` choose a zone.

use std::path::{Path, PathBuf};

mod common;

use common::{stderr, verbss};
use verbss::io::su2;
use verbss::mesh::{samples, Mesh};

/// Writes the zones as one multi-zone SU2 file `name` in `dir`.
fn zones_file(dir: &Path, name: &str, zones: &[Mesh]) -> PathBuf {
    let mut text = Vec::new();
    su2::write_zones_to(&mut text, zones).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The usual fluid–structure file: a fluid zone around an airfoil, then the
/// solid airfoil.
fn fsi(dir: &Path) -> PathBuf {
    let zones = [samples::fluid_around_an_airfoil(), samples::solid_airfoil()];
    zones_file(dir, "fsi.su2", &zones)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Zone `k` of `path` without the other zones' text.
fn zone(path: &Path, k: usize) -> Mesh {
    let mut mesh = verbss::io::read_zone(path, k).unwrap().0;
    mesh.origin.su2_skipped.clear();
    mesh
}

/// Deforms `input` with `args` into `output`; gives standard error.
fn deform(input: &Path, output: &Path, args: &[&str]) -> String {
    let o = verbss(&[&["deform", s(input), "-o", s(output)], args].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    stderr(&o)
}

/// Checks that `after` is `before` with other coordinates.
fn same_but_coordinates(before: &Mesh, after: &Mesh) {
    assert_ne!(after.coords, before.coords);
    let mut after = after.clone();
    after.coords.clone_from(&before.coords);
    assert_eq!(&after, before);
}

#[test]
fn deform_moves_the_chosen_zone_and_keeps_the_other_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let input = fsi(dir.path());
    let text = std::fs::read_to_string(&input).unwrap();
    let split = text.find("IZONE= 2").unwrap();

    let out = dir.path().join("fluid.su2");
    let pitch = ["--moving", "airfoil", "--rotate", "3", "--center", "0.25,0"];
    let note = deform(&input, &out, &pitch);
    let expected = format!(
        "note: {} has 2 zones; using zone 1 (choose one with --zone K)\nstep 1/1: ",
        input.display()
    );
    assert!(note.starts_with(&expected), "{note}");
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(written.ends_with(&text[split..]), "{written}");
    same_but_coordinates(&zone(&input, 1), &zone(&out, 1));
    assert_eq!(zone(&out, 2), zone(&input, 2));
    let chosen = dir.path().join("fluid1.su2");
    let progress = deform(&input, &chosen, &[&pitch[..], &["--zone", "1"]].concat());
    assert!(progress.starts_with("step 1/1: "), "{progress}");
    assert_eq!(std::fs::read(&chosen).unwrap(), written.as_bytes());

    let out = dir.path().join("solid.su2");
    let args = [
        "--zone",
        "2",
        "--moving",
        "interface",
        "--translate",
        "0,0.01",
        "--quiet",
    ];
    assert_eq!(deform(&input, &out, &args), "");
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(
        written.starts_with(&text[..split + "IZONE= 2\n".len()]),
        "{written}"
    );
    same_but_coordinates(&zone(&input, 2), &zone(&out, 2));
    assert_eq!(zone(&out, 1), zone(&input, 1));
}

#[test]
fn a_3d_zone_is_deformed_and_the_other_kept() {
    let dir = tempfile::tempdir().unwrap();
    let mut hybrid = samples::hex_wedge_pyramid_tet();
    hybrid.groups.iter_mut().for_each(|g| g.tag = None);
    let tets = samples::jittered_grid(3, 3, 2, || 0.0).unwrap();
    let input = zones_file(dir.path(), "two.su2", &[hybrid, tets]);
    let text = std::fs::read_to_string(&input).unwrap();
    let out = dir.path().join("moved.su2");
    let args = [
        "--zone",
        "2",
        "--moving",
        "left",
        "--translate",
        "0.05,0,0",
        "-q",
    ];
    deform(&input, &out, &args);
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(written.starts_with(&text[..text.find("IZONE= 2\n").unwrap()]));
    same_but_coordinates(&zone(&input, 2), &zone(&out, 2));
    assert_eq!(zone(&out, 1), zone(&input, 1));
}

#[test]
fn a_zone_that_is_not_there_is_refused_and_a_group_of_another_zone_named() {
    let dir = tempfile::tempdir().unwrap();
    let input = fsi(dir.path());
    let out = dir.path().join("out.su2");
    let refused = |args: &[&str], message: String| {
        let o = verbss(&[&["deform", s(&input), "-o", s(&out)], args].concat());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert_eq!(stderr(&o), message);
    };
    let moving = ["--moving", "interface", "--translate", "0,0.01"];
    refused(
        &[&moving[..], &["--zone", "3"]].concat(),
        format!(
            "error: {}:1: zone 3 asked for, but NZONE= 2 (zones 1 to 2)\n",
            input.display()
        ),
    );
    refused(
        &[&moving[..], &["--zone", "1"]].concat(),
        "error: unknown group 'interface' (the mesh has: airfoil, farfield); zone 2 has it \
         (give --zone 2)\n"
            .into(),
    );
    let o = verbss(&["quality", s(&input), "--zone", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--zone"), "{}", stderr(&o));
}

#[test]
fn quality_reports_every_zone_or_the_one_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let input = fsi(dir.path());
    let json = |args: &[&str]| -> serde_json::Value {
        let o = verbss(&[&["quality", s(&input), "--json"], args].concat());
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let all = json(&[]);
    let zones = all["zones"].as_array().unwrap();
    let counts: Vec<_> = zones
        .iter()
        .map(|z| {
            (
                z["zone"].as_u64(),
                z["nodes"].as_u64(),
                z["elements"].as_u64(),
            )
        })
        .collect();
    assert_eq!(
        counts,
        [(Some(1), Some(12), Some(16)), (Some(2), Some(5), Some(4))]
    );
    let solid = verbss::quality::summary_json(&zone(&input, 2));
    assert_eq!(json(&["--zone", "2"]), solid);
    let mut second = zones[1].clone();
    second.as_object_mut().unwrap().remove("zone");
    assert_eq!(second, solid);

    let o = verbss(&["quality", s(&input)]);
    let table = String::from_utf8(o.stdout).unwrap();
    let headings: Vec<&str> = table.lines().filter(|l| !l.starts_with(' ')).collect();
    let name = input.display();
    assert_eq!(
        headings,
        [format!("{name} zone 1 of 2"), format!("{name} zone 2 of 2")]
    );
    assert!(
        table.contains("    airfoil      4\n    farfield     4\n"),
        "{table}"
    );
    assert!(table.contains("    interface    4\n"), "{table}");
}

#[test]
fn convert_writes_one_zone_to_other_formats_and_every_zone_to_su2() {
    let dir = tempfile::tempdir().unwrap();
    let input = fsi(dir.path());
    let vtu = dir.path().join("zone.vtu");
    let o = verbss(&["convert", s(&input), s(&vtu)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "note: {} has 2 zones; using zone 1 (choose one with --zone K)\n\
             note: {} leaves out the other zones of the multi-zone SU2 input \
             (only an .su2 output keeps them)\n",
            input.display(),
            vtu.display()
        )
    );
    assert_eq!(verbss::io::read(&vtu).unwrap().node_count(), 12);
    let o = verbss(&["convert", s(&input), s(&vtu), "--zone", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(verbss::io::read(&vtu).unwrap().node_count(), 5);

    let copy = dir.path().join("copy.su2");
    let o = verbss(&["convert", s(&input), s(&copy)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    assert_eq!(
        std::fs::read(&copy).unwrap(),
        std::fs::read(&input).unwrap()
    );
}

#[test]
fn a_case_file_names_its_zone() {
    let dir = tempfile::tempdir().unwrap();
    let input = fsi(dir.path());
    let case = dir.path().join("solid.toml");
    std::fs::write(
        &case,
        "mesh = \"fsi.su2\"\nzone = 2\nsteps = 2\n[[motion]]\nkind = \"translation\"\n\
         groups = [\"interface\"]\ndisplacement = [0.0, 0.01]\n[output]\nseries = false\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let o = verbss(&["run", s(&case), "--out", s(&out), "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let result = out.join("fsi.su2");
    same_but_coordinates(&zone(&input, 2), &zone(&result, 2));
    assert_eq!(zone(&result, 1), zone(&input, 1));
    let text = std::fs::read_to_string(&input).unwrap();
    let written = std::fs::read_to_string(&result).unwrap();
    assert!(written.starts_with(&text[..text.find("IZONE= 2\n").unwrap()]));
}

#[test]
fn the_example_file_is_the_fluid_and_solid_zones() {
    let dir = tempfile::tempdir().unwrap();
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/meshes/fsi_airfoil.su2");
    assert_eq!(
        std::fs::read(example).unwrap(),
        std::fs::read(fsi(dir.path())).unwrap()
    );
}
