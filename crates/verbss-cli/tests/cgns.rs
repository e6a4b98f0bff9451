//! CGNS through the `verbss` binary: `convert` both ways, `quality`,
//! `deform` and `run` of a CGNS mesh. The deformed file is checked with
//! h5py, node by node, against its input: only the coordinate values differ.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{stderr, verbss};
use verbss::io::cgns::available;
use verbss_testkit::{needs, python};

/// Whether the CGNS tests can run (this build has the library).
fn cgns() -> bool {
    needs("the CGNS library (Debian: libcgns-dev)", available())
}

/// `verbss ARGS…`, which must succeed.
fn ok(args: &[&str]) -> String {
    let o = verbss(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stderr(&o)
}

fn naca_su2() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/su2/mesh_NACA0012_inv.su2")
}

/// The NACA 0012 mesh converted to `dir/naca.cgns`.
fn naca_cgns(dir: &Path) -> PathBuf {
    let path = dir.join("naca.cgns");
    ok(&[
        "convert",
        naca_su2().to_str().unwrap(),
        path.to_str().unwrap(),
    ]);
    path
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn su2_converted_to_cgns_and_back_is_the_same_mesh() {
    if !cgns() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let cgns = naca_cgns(dir.path());
    let back = dir.path().join("back.su2");
    ok(&["convert", s(&cgns), s(&back)]);
    let (a, b) = (
        verbss::io::read(&naca_su2()).unwrap(),
        verbss::io::read(&back).unwrap(),
    );
    assert_eq!(
        (&a.coords, &a.cells, &a.cell_tags),
        (&b.coords, &b.cells, &b.cell_tags)
    );
    assert_eq!(a.groups, b.groups);
    let o = verbss(&["quality", s(&cgns), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        (v["nodes"].as_u64(), v["elements"].as_u64()),
        (Some(5233), Some(10216))
    );
    assert_eq!(
        v["groups"],
        serde_json::json!({"airfoil": 200, "farfield": 50})
    );
}

/// Lists, one per line, the HDF5 objects of two files that exist in only
/// one of them or differ in data or attributes.
const DIFF: &str = r#"
import sys, h5py, numpy as np
def objects(path):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            attrs = sorted((k, np.asarray(v).tobytes()) for k, v in obj.attrs.items())
            data = obj[()].tobytes() if isinstance(obj, h5py.Dataset) else None
            out[name] = (attrs, data)
        visit("/", f)
        f.visititems(visit)
    return out
a, b = objects(sys.argv[1]), objects(sys.argv[2])
for name in sorted(set(a) | set(b)):
    if a.get(name) != b.get(name):
        print(name)
"#;

#[test]
fn deforming_a_cgns_mesh_changes_only_its_coordinate_values() {
    if !cgns()
        || !needs(
            "python3 with h5py (pip install h5py)",
            python(&["h5py", "numpy"]),
        )
    {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let input = naca_cgns(dir.path());
    let motion = [
        "--moving", "airfoil", "--rotate", "3", "--center", "0.25,0", "--steps", "2",
    ];
    let (moved, moved_su2) = (dir.path().join("moved.cgns"), dir.path().join("moved.su2"));
    for out in [&moved, &moved_su2] {
        ok(&[&["deform", s(&input), "-o", s(out)][..], &motion[..]].concat());
    }
    let (cgns, su2) = (
        verbss::io::read(&moved).unwrap(),
        verbss::io::read(&moved_su2).unwrap(),
    );
    assert_eq!(cgns.coords, su2.coords);
    assert_ne!(cgns.coords, verbss::io::read(&input).unwrap().coords);
    let o = Command::new("python3")
        .args(["-c", DIFF, s(&input), s(&moved)])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        "Base/Zone/GridCoordinates/CoordinateX/ data\nBase/Zone/GridCoordinates/CoordinateY/ data\n"
    );
}

#[test]
fn a_case_file_runs_on_a_cgns_mesh_and_writes_a_cgns_copy() {
    if !cgns() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let input = naca_cgns(dir.path());
    let case = dir.path().join("case.toml");
    std::fs::write(
        &case,
        "mesh = \"naca.cgns\"\nsteps = 2\n\n[[motion]]\nkind = \"translation\"\n\
         groups = [\"airfoil\"]\ndisplacement = [0.0, 0.02]\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    ok(&["run", s(&case), "--out", s(&out), "--quiet"]);
    let last = verbss::io::read(&out.join("naca.cgns")).unwrap();
    let first = verbss::io::read(&input).unwrap();
    let airfoil = first.group("airfoil").unwrap().nodes();
    for &i in &airfoil {
        assert!((last.point(i)[1] - first.point(i)[1] - 0.02).abs() < 1e-12);
    }
    assert_eq!(last.groups, first.groups);
}

#[test]
fn a_file_of_two_zones_reads_the_first_and_says_so() {
    if !cgns()
        || !needs(
            "python3 with h5py (pip install h5py)",
            python(&["h5py", "numpy"]),
        )
    {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let input = naca_cgns(dir.path());
    let script = r#"
import sys, h5py, numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    f.copy("Base/Zone", "Base/Zone2")
    name = f["Base/Zone2"].attrs.get_id("name")
    f["Base/Zone2"].attrs.modify("name", np.array(b"Zone2", dtype=name.dtype))
"#;
    let o = Command::new("python3")
        .args(["-c", script, s(&input)])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let su2 = dir.path().join("zone1.su2");
    for args in [
        vec!["quality", s(&input)],
        vec!["convert", s(&input), s(&su2)],
    ] {
        let note = ok(&args);
        assert!(
            note.contains(&format!(
                "note: {} has 2 zones in base 'Base'; verbss reads zone 1 ('Zone') only",
                input.display()
            )),
            "{args:?}: {note}"
        );
    }
}

#[test]
fn a_file_that_is_not_cgns_is_refused_with_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("text.cgns");
    std::fs::write(&path, "not a CGNS file\n").unwrap();
    let o = verbss(&["quality", s(&path)]);
    assert_eq!(o.status.code(), Some(2));
    let expected = match available() {
        Ok(()) => format!("error: {}: cannot open as CGNS: ", path.display()),
        Err(why) => format!("error: {}: {why}", path.display()),
    };
    assert!(stderr(&o).starts_with(&expected), "{}", stderr(&o));
}

/// `scripts/gmsh_channel_cgns.py`: Gmsh's own CGNS files of a 2D channel
/// and a 3D box around an obstacle.
fn gmsh_cgns() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/gmsh_channel_cgns.py")
}

/// Files written by another tool: Gmsh's CGNS writer names its boundary
/// conditions per entity (`L_1`, …) at `CellCenter`, in families that
/// belong to the physical group's family, and writes the region `fluid` as
/// a condition over cells. verbss reads the physical groups as its groups,
/// and a deformed file differs from Gmsh's only in the coordinate values.
#[test]
fn files_written_by_gmsh_read_with_their_physical_groups_and_deform_in_place() {
    if !cgns()
        || !needs(
            "python3 with gmsh and h5py (pip install gmsh h5py)",
            python(&["gmsh", "h5py", "numpy"]),
        )
    {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new("python3")
        .args([s(&gmsh_cgns()), s(dir.path())])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    for (dim, motion) in [(2, "0.03,0.05"), (3, "0.03,0.05,0.02")] {
        let input = dir.path().join(format!("channel{dim}.cgns"));
        let mesh = verbss::io::read(&input).unwrap();
        assert_eq!(mesh.dim, dim);
        let mut names: Vec<&str> = mesh.groups.iter().map(|g| g.name.as_str()).collect();
        names.sort_unstable();
        assert_eq!(names, ["cylinder", "inlet", "outlet", "walls"], "{dim}D");
        let moved = dir.path().join(format!("moved{dim}.cgns"));
        ok(&[
            "deform",
            s(&input),
            "-o",
            s(&moved),
            "--moving",
            "cylinder",
            "--translate",
            motion,
            "--quiet",
        ]);
        let after = verbss::io::read(&moved).unwrap();
        let cylinder = mesh.group("cylinder").unwrap().nodes();
        for &i in &cylinder {
            assert!((after.point(i)[1] - mesh.point(i)[1] - 0.05).abs() < 1e-12);
        }
        let o = Command::new("python3")
            .args(["-c", DIFF, s(&input), s(&moved)])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let changed = String::from_utf8_lossy(&o.stdout).into_owned();
        let axes = if dim == 2 { "XY" } else { "XYZ" };
        assert_eq!(changed.lines().count(), axes.len(), "{changed}");
        for (line, axis) in changed.lines().zip(axes.chars()) {
            assert!(
                line.ends_with(&format!("/GridCoordinates/Coordinate{axis}/ data")),
                "{changed}"
            );
        }
    }
}
