use std::path::Path;

use verbss_testkit::needs;

use super::available;
use super::blocks::{Blocks, Numbers};
use crate::io::{read, write, WriteOptions};
use crate::mesh::{samples, CellKind, Cells, Group, Mesh};

/// The package these tests need.
const LIBRARY: &str = "the CGNS library (Debian: libcgns-dev)";

/// `mesh` without what depends on its source: group tags and the CGNS file.
fn plain(mut mesh: Mesh) -> Mesh {
    mesh.origin.cgns = None;
    for g in &mut mesh.groups {
        g.tag = None;
    }
    mesh
}

/// Writes `mesh` to `dir/name` and reads it back.
fn write_read(dir: &Path, name: &str, mesh: &Mesh) -> Mesh {
    let path = dir.join(name);
    write(&path, mesh, &WriteOptions::default()).unwrap();
    read(&path).unwrap()
}

#[test]
fn a_hybrid_3d_mesh_round_trips_through_a_fresh_file() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mesh = samples::hex_wedge_pyramid_tet();
    let back = write_read(dir.path(), "hybrid.cgns", &mesh);
    let source = back.origin.cgns.clone().unwrap();
    assert_eq!(
        (source.base.as_str(), source.zone.as_str(), source.zones),
        ("Base", "Zone", 1)
    );
    assert_eq!(source.path, dir.path().join("hybrid.cgns"));
    assert_eq!(back.cell_tags, [1, 2, 3, 4]);
    assert_eq!(plain(back.clone()), plain(mesh));
    // Written again, the mesh read from CGNS is a copy of its file: equal again.
    let again = write_read(dir.path(), "again.cgns", &back);
    assert_eq!(plain(again), plain(back));
}

#[test]
fn a_2d_mesh_of_triangles_and_quads_round_trips_as_a_mixed_section() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mesh = samples::two_triangles_and_a_quad();
    let back = write_read(dir.path(), "mixed.cgns", &mesh);
    assert_eq!(
        back.cells.kinds,
        [CellKind::Triangle, CellKind::Triangle, CellKind::Quad]
    );
    assert_eq!(plain(back), plain(mesh));
}

#[test]
fn a_group_of_single_nodes_round_trips_as_a_vertex_condition() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = samples::square_of_triangles(3);
    let mut probes = Cells::new();
    for v in [5, 6, 9] {
        probes.push(CellKind::Vertex, &[v]);
    }
    mesh.groups.push(Group {
        name: "probes".into(),
        tag: None,
        facets: probes,
    });
    let back = write_read(dir.path(), "probes.cgns", &mesh);
    assert_eq!(back.group("probes").unwrap().nodes(), [5, 6, 9]);
    assert_eq!(plain(back), plain(mesh));
}

#[test]
fn writing_a_mesh_read_from_cgns_replaces_its_coordinates_only() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = write_read(dir.path(), "in.cgns", &samples::hex_wedge_pyramid_tet());
    for (k, x) in mesh.coords.iter_mut().enumerate() {
        *x += 0.01 * k as f64;
    }
    let moved = write_read(dir.path(), "out.cgns", &mesh);
    assert_eq!(moved.coords, mesh.coords);
    assert_eq!(
        moved.origin.cgns.as_ref().unwrap().path,
        dir.path().join("out.cgns")
    );
    assert_eq!(plain(moved), plain(mesh));
}

#[test]
fn a_group_name_that_cgns_cannot_hold_is_refused() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = samples::square_of_triangles(2);
    mesh.groups[0].name = "a/b".into();
    let path = dir.path().join("bad.cgns");
    let e = write(&path, &mesh, &WriteOptions::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: the group name 'a/b' is no CGNS name (1 to 32 characters, no '/')",
            path.display()
        )
    );
    assert!(!path.exists());
}

#[test]
fn blocks_read_any_range_of_the_whole_reader_s_coordinates_and_cells() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    for mesh in [
        samples::hex_wedge_pyramid_tet(),
        samples::two_triangles_and_a_quad(),
    ] {
        let whole = write_read(dir.path(), "whole.cgns", &mesh);
        let zone = Blocks::open(&dir.path().join("whole.cgns")).unwrap();
        let (n, dim) = (whole.node_count() as u64, whole.dim);
        assert_eq!((zone.vertices, zone.dim), (n, dim));
        for first in 0..n {
            for count in 0..=n - first {
                let (from, to) = (first as usize * dim, (first + count) as usize * dim);
                assert_eq!(
                    zone.coordinates(first, count).unwrap(),
                    whole.coords[from..to]
                );
            }
        }
        // The cells' section (MIXED in 2D) read in every block of it.
        let cells = zone.sections.iter().position(|s| s.cells).unwrap();
        let head = &zone.sections[cells];
        assert_eq!(head.count, whole.cell_count() as u64);
        for start in 0..head.count {
            for count in 1..=head.count - start {
                let block = zone
                    .read_elements(cells, head.first + start as i64, count)
                    .unwrap();
                for (k, (kind, nodes)) in block.iter().enumerate() {
                    let c = start as usize + k;
                    assert_eq!((kind, nodes), (whole.cells.kinds[c], whole.cells.cell(c)));
                }
                assert_eq!(block.len() as u64, count);
            }
        }
        let groups: Vec<&str> = zone.conditions.iter().map(|c| c.group.as_str()).collect();
        assert_eq!(groups, whole.group_names());
    }
}

/// Files written through the library as other tools write them.
#[cfg(with_cgns)]
mod fixtures {
    use super::*;
    use crate::io::cgns::ffi::{self, CgSize, File, Mode};
    use std::path::PathBuf;

    /// A unit square of two triangles (elements 1, 2), edges `wall` (3, 4:
    /// bottom and right) and `lid` (5: top), in a 2D base `Base`.
    pub fn square(path: &Path, extra: impl FnOnce(&File, i32, i32)) -> PathBuf {
        let file = File::open(path, Mode::Write).unwrap();
        let b = file.write_base("Base", 2, 2).unwrap();
        let z = file
            .write_zone(b, "Zone", ffi::UNSTRUCTURED, &[4, 2, 0])
            .unwrap();
        file.write_coordinate(b, z, "CoordinateX", &[0., 1., 1., 0.])
            .unwrap();
        file.write_coordinate(b, z, "CoordinateY", &[0., 0., 1., 1.])
            .unwrap();
        let section = |name: &str, kind: i32, range: (CgSize, CgSize), nodes: &[CgSize]| {
            file.write_section(b, z, name, kind, range, nodes, &[])
                .unwrap();
        };
        section("Cells", 5, (1, 2), &[1, 2, 3, 1, 3, 4]);
        section("wall", 3, (3, 4), &[1, 2, 2, 3]);
        section("lid", 3, (5, 5), &[3, 4]);
        extra(&file, b, z);
        file.close().unwrap();
        path.to_path_buf()
    }
}

#[cfg(with_cgns)]
mod hand_written {
    use super::fixtures::square;
    use super::*;
    use crate::io::cgns::ffi;

    /// The message of reading `path`, which must fail.
    fn read_error(path: &Path) -> String {
        read(path).unwrap_err().to_string()
    }

    #[test]
    fn sections_of_edges_are_groups_and_conditions_take_their_family_name() {
        let dir = tempfile::tempdir().unwrap();
        let plain_square = read(&square(&dir.path().join("s.cgns"), |_, _, _| {})).unwrap();
        assert_eq!(plain_square.group_names(), ["wall", "lid"]);
        assert_eq!(
            plain_square.group("wall").unwrap().facets.nodes,
            [0, 1, 1, 2]
        );
        assert_eq!(plain_square.cell_tags, [1, 2]);
        let path = square(&dir.path().join("bc.cgns"), |f, b, z| {
            let names = ("Base", "Zone");
            f.write_family(b, "solid").unwrap();
            f.write_family(b, "tip").unwrap();
            f.write_boco(
                names,
                (b, z),
                ("wall", "solid"),
                ffi::POINT_RANGE,
                &[3, 3],
                ffi::EDGE_CENTER,
            )
            .unwrap();
            f.write_boco(
                names,
                (b, z),
                ("right", "solid"),
                ffi::ELEMENT_LIST,
                &[4],
                ffi::VERTEX,
            )
            .unwrap();
            f.write_boco(
                names,
                (b, z),
                ("corner", "tip"),
                ffi::POINT_LIST,
                &[3],
                ffi::VERTEX,
            )
            .unwrap();
        });
        let mesh = read(&path).unwrap();
        // `wall` is named by a condition: its section is no group of its own.
        assert_eq!(mesh.group_names(), ["solid", "tip", "lid"]);
        let solid = mesh.group("solid").unwrap();
        assert_eq!(solid.facets.kinds, [CellKind::Line, CellKind::Line]);
        assert_eq!(solid.facets.nodes, [0, 1, 1, 2]);
        assert_eq!(mesh.group("tip").unwrap().facets.kinds, [CellKind::Vertex]);
        assert_eq!(mesh.group("tip").unwrap().nodes(), [2]);
    }

    #[test]
    fn a_condition_on_a_cell_names_the_condition_and_the_element() {
        let dir = tempfile::tempdir().unwrap();
        let path = square(&dir.path().join("bc.cgns"), |f, b, z| {
            f.write_family(b, "in").unwrap();
            f.write_boco(
                ("Base", "Zone"),
                (b, z),
                ("in", "in"),
                ffi::POINT_LIST,
                &[2],
                ffi::EDGE_CENTER,
            )
            .unwrap();
        });
        assert_eq!(
            read_error(&path),
            format!(
                "{}: boundary condition 'in' of zone 'Zone' (zone 1 of base 'Base') names element 2, \
                 which is not a boundary element of the zone (BAR_2 in 2D)",
                path.display()
            )
        );
    }

    #[test]
    fn polyhedral_sections_are_refused_in_blocks_with_the_zone_and_section() {
        let dir = tempfile::tempdir().unwrap();
        let path = square(&dir.path().join("ngon.cgns"), |f, b, z| {
            f.write_section(b, z, "Faces", ffi::NGON_N, (6, 6), &[2, 1, 2], &[0, 3])
                .unwrap();
        });
        let e = Blocks::open(&path).err().unwrap().to_string();
        assert_eq!(
            e,
            format!(
                "{}: section 'Faces' of zone 'Zone' (zone 1 of base 'Base') is NGON_n: polyhedral \
                 sections are not supported here (verbss reads them from a whole file, not in \
                 blocks; here it reads BAR_2, TRI_3, QUAD_4, TETRA_4, PYRA_5, PENTA_6, HEXA_8 and \
                 MIXED of those)",
                path.display()
            )
        );
    }

    #[test]
    fn nodes_outside_the_zone_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = square(&dir.path().join("far.cgns"), |f, b, z| {
            f.write_section(b, z, "far", 3, (6, 6), &[4, 9], &[])
                .unwrap();
        });
        assert_eq!(
            read_error(&path),
            format!(
                "{}: section 'far' of zone 'Zone' (zone 1 of base 'Base'): element 6 has node 9, \
                 outside the zone's 1..=4",
                path.display()
            )
        );
    }

    #[test]
    fn a_structured_zone_is_refused_and_a_second_zone_is_left_out() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("structured.cgns");
        let file = ffi::File::open(&path, ffi::Mode::Write).unwrap();
        let b = file.write_base("Grid", 2, 2).unwrap();
        file.write_zone(b, "Block", ffi::STRUCTURED, &[2, 2, 1, 1, 0, 0])
            .unwrap();
        file.close().unwrap();
        assert_eq!(
            read_error(&path),
            format!(
                "{}: zone 'Block' (zone 1 of base 'Grid') is structured: verbss reads unstructured zones only",
                path.display()
            )
        );
        let two = square(&dir.path().join("two.cgns"), |f, b, _| {
            // The library lists zones by name: `Zone` stays zone 1.
            let z = f
                .write_zone(b, "Zone2", ffi::UNSTRUCTURED, &[3, 1, 0])
                .unwrap();
            f.write_coordinate(b, z, "CoordinateX", &[5., 6., 5.])
                .unwrap();
            f.write_coordinate(b, z, "CoordinateY", &[5., 5., 6.])
                .unwrap();
            f.write_section(b, z, "Cells", 5, (1, 1), &[1, 2, 3], &[])
                .unwrap();
        });
        let mesh = read(&two).unwrap();
        assert_eq!((mesh.node_count(), mesh.cell_count()), (4, 2));
        assert_eq!(mesh.origin.cgns.unwrap().zones, 2);
    }

    #[test]
    fn blocks_give_the_whole_reader_s_sections_conditions_and_groups() {
        let dir = tempfile::tempdir().unwrap();
        let path = square(&dir.path().join("bc.cgns"), |f, b, z| {
            f.write_family(b, "solid").unwrap();
            f.write_boco(
                ("Base", "Zone"),
                (b, z),
                ("wall", "solid"),
                ffi::POINT_LIST,
                &[3, 4],
                ffi::EDGE_CENTER,
            )
            .unwrap();
        });
        let zone = Blocks::open(&path).unwrap();
        let heads: Vec<(&str, i64, u64, bool, bool)> = zone
            .sections
            .iter()
            .map(|s| (s.name.as_str(), s.first, s.count, s.cells, s.facets))
            .collect();
        assert_eq!(
            heads,
            [
                ("Cells", 1, 2, true, false),
                ("wall", 3, 2, false, true),
                ("lid", 5, 1, false, true)
            ]
        );
        assert_eq!(zone.elements(), 5);
        assert_eq!(zone.section_of(4), Some(1));
        assert_eq!(zone.section_of(6), None);
        let wall = &zone.conditions[0];
        assert_eq!((wall.group.as_str(), wall.of_elements), ("solid", true));
        assert_eq!(wall.numbers, Numbers::List(vec![3, 4]));
        assert_eq!(wall.numbers.iter().collect::<Vec<_>>(), [3, 4]);
        // The widest range counts without overflowing; a reversed one is empty.
        assert_eq!(Numbers::Range(i64::MIN, i64::MAX).len(), u64::MAX);
        assert_eq!(Numbers::Range(7, 9).len(), 3);
        assert!(Numbers::Range(9, 7).is_empty());
        assert!(!wall.is_region(5, false));
        // `wall` is covered (and a condition's name), `lid` a group of its own.
        let groups = vec!["solid".to_string()];
        assert!(!zone.sections[1].own_group(false, &zone.conditions, &groups));
        assert!(zone.sections[2].own_group(false, &zone.conditions, &groups));
        // An open file holds the library's lock: closed before the next.
        drop(zone);
        assert_eq!(read(&path).unwrap().group_names(), ["solid", "lid"]);
        let two = square(&dir.path().join("two.cgns"), |f, b, _| {
            f.write_zone(b, "Zone2", ffi::UNSTRUCTURED, &[3, 1, 0])
                .unwrap();
        });
        assert_eq!(
            Blocks::open(&two).err().unwrap().to_string(),
            format!(
                "{}: base 'Base' holds 2 zones: a distributed read takes single-zone files \
                 (`verbss deform` reads zone 1 of several)",
                two.display()
            )
        );
    }
}

#[cfg(with_cgns)]
mod polyhedra;

/// HDF5 opens and locks its files without close-on-exec: a child process
/// started while a file is open would hold its lock after verbss closes it,
/// and the next open of the file would fail until the child exits. A child
/// started while a file is open for modifying does not hold it.
#[test]
fn a_child_process_started_while_a_file_is_open_does_not_hold_it() {
    if !needs(LIBRARY, available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("held.cgns");
    let mesh = samples::hex_wedge_pyramid_tet();
    write(&path, &mesh, &WriteOptions::default()).unwrap();
    let file = super::ffi::File::open(&path, super::ffi::Mode::Modify).unwrap();
    let mut child = std::process::Command::new("sleep")
        .arg("5")
        .spawn()
        .unwrap();
    file.close().unwrap();
    let back = read(&path);
    child.kill().unwrap();
    child.wait().unwrap();
    assert_eq!(back.unwrap().node_count(), mesh.node_count());
}
