//! Files written by verbss open in other tools: meshio reads every format,
//! Gmsh's own API reads the `.msh` files, and both report the node and cell
//! counts verbss wrote (scripts/check_external_readers.py does the reading).
//!
//! Needs `python3` with `meshio`, `gmsh` and `numpy`; without them the tests
//! skip with a notice (`verbss_testkit::needs`).

use std::path::{Path, PathBuf};
use std::process::Command;

use verbss::io::{MshVersion, WriteOptions};
use verbss::mesh::samples::{as_general, hex_wedge_pyramid_tet, two_triangles_and_a_quad};
use verbss::Mesh;
use verbss_testkit::{needs, python};

const SCRIPT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scripts/check_external_readers.py"
);

/// Whether python3 can import meshio, gmsh and numpy (else the test skips,
/// see `verbss_testkit::needs`).
fn python_ready() -> bool {
    needs(
        "python3 with meshio, gmsh and numpy (pip install meshio gmsh numpy)",
        python(&["meshio", "gmsh", "numpy"]),
    )
}

/// Writes each mesh under `dir` with the given file name (format chosen by
/// extension), runs the check script on all of them and compares the counts
/// it reports with the mesh.
fn check(dir: &Path, files: &[(&str, &Mesh, WriteOptions)]) {
    let paths: Vec<PathBuf> = files
        .iter()
        .map(|(name, mesh, options)| {
            let path = dir.join(name);
            verbss::io::write(&path, mesh, options).unwrap();
            path
        })
        .collect();
    let out = Command::new("python3")
        .arg(SCRIPT)
        .args(&paths)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{SCRIPT} failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reports: Vec<serde_json::Value> = stdout
        .lines()
        .filter(|l| l.starts_with('{'))
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(reports.len(), files.len(), "{stdout}");
    for ((name, mesh, _), report) in files.iter().zip(&reports) {
        let facets: usize = mesh.groups.iter().map(|g| g.facets.len()).sum();
        let cells = (mesh.cell_count() + facets) as u64;
        let nodes = mesh.node_count() as u64;
        let m = &report["meshio"];
        assert_eq!(m["points"], nodes, "{name}: meshio points");
        assert_eq!(m["cells"], cells, "{name}: meshio cells");
        if name.ends_with(".msh") {
            assert_eq!(report["gmsh"]["nodes"], nodes, "{name}: gmsh nodes");
            assert_eq!(report["gmsh"]["elements"], cells, "{name}: gmsh elements");
        }
        if name.ends_with(".vtu") {
            let mut names = mesh.group_names();
            names.sort();
            assert_eq!(m["field_data"], serde_json::json!(names), "{name}");
        }
    }
}

fn msh(version: MshVersion, binary: bool) -> WriteOptions {
    let mut options = WriteOptions::default();
    options.msh_version = version;
    options.binary = binary;
    options
}

#[test]
fn vtu_files_open_in_meshio() {
    if !python_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (m2, m3) = (two_triangles_and_a_quad(), hex_wedge_pyramid_tet());
    check(
        dir.path(),
        &[
            ("hybrid_2d.vtu", &m2, WriteOptions::default()),
            ("mixed_3d.vtu", &m3, WriteOptions::default()),
        ],
    );
}

/// Polygons (VTK 7) and polyhedra (VTK 42 with `faces`): meshio reads a
/// file of polyhedra only (it refuses polyhedra beside other cells, which
/// VTK and ParaView read).
#[test]
fn vtu_polygons_and_polyhedra_open_in_meshio() {
    if !python_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let polygons = as_general(&two_triangles_and_a_quad());
    let mut polyhedra = as_general(&hex_wedge_pyramid_tet());
    polyhedra.groups.clear();
    check(
        dir.path(),
        &[
            ("polygons_2d.vtu", &polygons, WriteOptions::default()),
            ("polyhedra_3d.vtu", &polyhedra, WriteOptions::default()),
        ],
    );
}

#[test]
fn msh_files_open_in_meshio_and_gmsh() {
    if !python_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (m2, m3) = (two_triangles_and_a_quad(), hex_wedge_pyramid_tet());
    let mut files = Vec::new();
    for (version, v) in [(MshVersion::V22, "v22"), (MshVersion::V41, "v41")] {
        for (binary, b) in [(false, "ascii"), (true, "binary")] {
            files.push((format!("hybrid_2d_{v}_{b}.msh"), &m2, msh(version, binary)));
            files.push((format!("mixed_3d_{v}_{b}.msh"), &m3, msh(version, binary)));
        }
    }
    let files: Vec<_> = files
        .iter()
        .map(|(name, mesh, options)| (name.as_str(), *mesh, options.clone()))
        .collect();
    check(dir.path(), &files);
}

#[test]
fn su2_files_open_in_meshio() {
    if !python_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (m2, m3) = (two_triangles_and_a_quad(), hex_wedge_pyramid_tet());
    check(
        dir.path(),
        &[
            ("hybrid_2d.su2", &m2, WriteOptions::default()),
            ("mixed_3d.su2", &m3, WriteOptions::default()),
        ],
    );
}
