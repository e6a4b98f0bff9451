//! Multi-zone files: every zone read, one zone rewritten with the others
//! kept byte for byte, clear errors for inconsistent zones.

use std::path::Path;

use super::*;
use crate::mesh::samples;

fn path() -> &'static Path {
    Path::new("z.su2")
}

/// The zones as one multi-zone file.
fn zones_text(zones: &[Mesh]) -> String {
    let mut text = Vec::new();
    write_zones_to(&mut text, zones).unwrap();
    String::from_utf8(text).unwrap()
}

/// A 2D fluid–structure pair and a 3D pair of zones, without the group
/// tags an SU2 file does not hold.
fn cases() -> [Vec<Mesh>; 2] {
    let tets = samples::jittered_grid(3, 3, 2, || 0.0).unwrap();
    let mut hybrid = samples::hex_wedge_pyramid_tet();
    hybrid.groups.iter_mut().for_each(|g| g.tag = None);
    [
        vec![samples::fluid_around_an_airfoil(), samples::solid_airfoil()],
        vec![hybrid, tets],
    ]
}

fn written(mesh: &Mesh) -> String {
    let mut text = Vec::new();
    write_to(&mut text, mesh).unwrap();
    String::from_utf8(text).unwrap()
}

fn error_of(text: &str, zone: usize) -> String {
    parse_zone(text.as_bytes(), path(), zone)
        .unwrap_err()
        .to_string()
}

/// `text` reads as `zones` (whole and zone by zone), and each zone read is
/// written back as `text`.
fn reads_as(text: &str, zones: &[Mesh]) {
    assert_eq!(parse_zones(text.as_bytes(), path()).unwrap(), zones);
    for (k, zone) in zones.iter().enumerate() {
        let (mut mesh, count) = parse_zone(text.as_bytes(), path(), k + 1).unwrap();
        assert_eq!(count, 2);
        assert_eq!(written(&mesh), text, "zone {} written back", k + 1);
        mesh.origin.su2_skipped.clear();
        assert_eq!(&mesh, zone);
    }
}

#[test]
fn every_zone_reads_as_the_mesh_written() {
    for zones in cases() {
        let text = zones_text(&zones);
        reads_as(&text, &zones);
    }
    let text = zones_text(&cases()[0]);
    assert!(text.starts_with("NZONE= 2\nIZONE= 1\nNDIME= 2\nNELEM= 16\n"));
    assert!(text.contains("3\t11\t8\nIZONE= 2\nNDIME= 2\nNELEM= 4\n"));
}

#[test]
fn a_moved_zone_is_rewritten_and_the_others_kept_byte_for_byte() {
    for zones in cases() {
        let text = zones_text(&zones);
        let split = text.find("IZONE= 2").unwrap();
        let (first, second) = text.split_at(split);
        for k in [1, 2] {
            let (mut mesh, _) = parse_zone(text.as_bytes(), path(), k).unwrap();
            mesh.coords.iter_mut().for_each(|x| *x += 0.25);
            let out = written(&mesh);
            let (kept, moved) = match k {
                1 => (second, &zones[0]),
                _ => (first, &zones[1]),
            };
            assert!(
                out.starts_with(kept) || out.ends_with(kept),
                "zone {k}: {out}"
            );
            let (back, _) = parse_zone(out.as_bytes(), path(), k).unwrap();
            let expected: Vec<f64> = moved.coords.iter().map(|x| x + 0.25).collect();
            assert_eq!(back.coords, expected);
            let mut other = parse_zone(out.as_bytes(), path(), 3 - k).unwrap().0;
            other.origin.su2_skipped.clear();
            assert_eq!(other, zones[2 - k]);
        }
    }
}

/// A fluid–structure file as SU2 writes one (an older SU2 adds its
/// `AOA_OFFSET=` lines), with comments, blank lines and an FFD box.
const AS_SU2_WRITES: &str = "NZONE= 2
IZONE= 1
NDIME= 2
AOA_OFFSET= 0
NELEM= 2
5\t0\t1\t2\t0
5\t0\t2\t3\t1
NPOIN= 4
0\t0\t0
1\t0\t1
1\t1\t2
0\t1\t3
NMARK= 1
MARKER_TAG= wall
MARKER_ELEMS= 1
3\t0\t1
FFD_NBOX= 1
FFD_TAG= BOX
% the solid zone
IZONE= 2

NDIME= 2
NELEM= 1
5\t0\t1\t2\t0
NPOIN= 3
0\t0\t0
1\t0\t1
1\t1\t2
NMARK= 1
MARKER_TAG= wall_solid
MARKER_ELEMS= 1
3\t0\t1
";

#[test]
fn a_file_as_su2_writes_it_keeps_its_blocks_and_other_zone() {
    let (fluid, count) = parse_zone(AS_SU2_WRITES.as_bytes(), path(), 1).unwrap();
    assert_eq!((count, fluid.node_count(), fluid.cell_count()), (2, 4, 2));
    let out = written(&fluid);
    let solid = &AS_SU2_WRITES[AS_SU2_WRITES.find("% the solid").unwrap()..];
    assert!(
        out.ends_with(&format!("FFD_NBOX= 1\nFFD_TAG= BOX\n{solid}")),
        "{out}"
    );
    assert!(out.starts_with("NZONE= 2\nIZONE= 1\nNDIME= 2\nAOA_OFFSET= 0\nNELEM= 2\n"));

    let (solid_zone, _) = parse_zone(AS_SU2_WRITES.as_bytes(), path(), 2).unwrap();
    assert_eq!(solid_zone.group_names(), ["wall_solid"]);
    let out = written(&solid_zone);
    let fluid_text = &AS_SU2_WRITES[..AS_SU2_WRITES.find("\nNDIME= 2\nNELEM= 1").unwrap()];
    assert!(out.starts_with(fluid_text), "{out}");
    let names: Vec<Vec<String>> = parse_zones(out.as_bytes(), path())
        .unwrap()
        .iter()
        .map(Mesh::group_names)
        .collect();
    assert_eq!(names, [["wall"], ["wall_solid"]]);
}

#[test]
fn a_single_zone_file_is_zone_1_of_1() {
    let text = written(&samples::solid_airfoil());
    let (mesh, count) = parse_zone(text.as_bytes(), path(), 1).unwrap();
    assert_eq!((mesh, count), (samples::solid_airfoil(), 1));
    let with_nzone = format!("NZONE= 1\n{text}");
    let (mesh, _) = parse_zone(with_nzone.as_bytes(), path(), 1).unwrap();
    assert_eq!(written(&mesh), with_nzone);
    assert_eq!(
        error_of(&text, 2),
        "invalid setting: z.su2: zone 2 asked for, but the file has one zone (no IZONE= lines)"
    );
}

/// Issue 43, 16: SU2's own fluid–structure meshes give the file's `NDIME=`
/// before `NZONE=`, then again in each zone; SU2 reads each zone from after
/// its `IZONE=` line. Before or after `NZONE=`, the file reads as without it,
/// and an SU2 output keeps it where it stood.
#[test]
fn a_file_ndime_before_the_zones_is_read_as_su2_reads_it() {
    let zones = cases()[0].clone();
    let text = zones_text(&zones);
    let after = text.replacen("NZONE= 2\n", "NZONE= 2\nNDIME= 2\n", 1);
    for text in [format!("NDIME= 2\n{text}"), after] {
        reads_as(&text, &zones);
    }
}

#[test]
fn inconsistent_zones_are_named_with_their_line() {
    let text = zones_text(&cases()[0]);
    let second = text.lines().position(|l| l == "IZONE= 2").unwrap() + 1;
    let first_ndime = 3;
    let replaced = |line: usize, by: &str| {
        let mut lines: Vec<&str> = text.lines().collect();
        lines[line - 1] = by;
        lines.join("\n") + "\n"
    };
    let end = text.lines().count();
    let cases = [
        (replaced(second, "IZONE= 3"), 1, format!("z.su2:{second}: IZONE= 3 out of order (expected IZONE= 2)")),
        (replaced(2, "IZONE= 2"), 1, "z.su2:2: IZONE= 2 out of order (expected IZONE= 1)".into()),
        (replaced(1, "% no NZONE"), 1, "z.su2:2: IZONE= without NZONE= (a multi-zone file starts with NZONE= N)".into()),
        (replaced(1, "NZONE= 3"), 1, format!("z.su2:{end}: file ends after 2 of the 3 zones announced by NZONE= at line 1")),
        (replaced(1, "NZONE= 1"), 1, format!("z.su2:{second}: IZONE= 2 is one more zone than the 1 announced by NZONE= at line 1")),
        (replaced(2, "% no IZONE= 1"), 1, format!("z.su2:{}: NELEM= before IZONE= 1 (NZONE= 2 at line 1: expected IZONE= 1 before the first zone's sections)", first_ndime + 1)),
        (format!("NELEM= 0\n{text}"), 1, "z.su2:2: NZONE= after NELEM= at line 1 (expected NZONE= first)".into()),
        (format!("NZONE= 2\n{text}"), 1, "z.su2:2: NZONE= given twice (first at line 1)".into()),
        (replaced(1, "NZONE= 0"), 1, "z.su2:1: NZONE= 0 (expected 1 to 65536 zones)".into()),
        (replaced(1, "NZONE= 99999999999999999999"), 1, "z.su2:1: expected a count after NZONE=, found '99999999999999999999'".into()),
        (replaced(second, "IZONE= two"), 1, format!("z.su2:{second}: expected a count after IZONE=, found 'two'")),
        (text.clone(), 3, "z.su2:1: zone 3 asked for, but NZONE= 2 (zones 1 to 2)".into()),
        (text.clone(), 0, "z.su2:1: zone 0 asked for, but NZONE= 2 (zones 1 to 2)".into()),
        (replaced(second + 1, "NDIME= 4"), 1, format!("z.su2:{}: NDIME= 4 (expected 2 or 3)", second + 1)),
    ];
    for (text, zone, message) in cases {
        assert_eq!(error_of(&text, zone), message);
    }
    let one = written(&samples::solid_airfoil());
    assert_eq!(
        error_of(&format!("{one}{one}"), 1),
        format!(
            "z.su2:{}: NDIME= given twice (first at line 1; a multi-zone file starts with \
             NZONE= N and gives each zone after its IZONE= K line)",
            one.lines().count() + 1
        )
    );
}

#[test]
fn hostile_zone_counts_are_bounded() {
    let many = "NZONE= 65537\nIZONE= 1\n";
    assert_eq!(
        error_of(many, 1),
        "z.su2:1: NZONE= 65537 (expected 1 to 65536 zones)"
    );
    let mut empty = String::from("NZONE= 65536\n");
    for k in 1..=65536 {
        empty += &format!("IZONE= {k}\n");
    }
    assert_eq!(
        error_of(&empty, 1),
        "z.su2:2: missing NDIME= (expected NDIME= 2 or 3)"
    );
    let tiny = "NDIME= 2\nNELEM= 0\nNPOIN= 0\n";
    let mut zones = String::from("NZONE= 20000\n");
    for k in 1..=20000 {
        zones += &format!("IZONE= {k}\n{tiny}");
    }
    let meshes = parse_zones(zones.as_bytes(), path()).unwrap();
    assert_eq!(meshes.len(), 20000);
    let (last, count) = parse_zone(zones.as_bytes(), path(), 20000).unwrap();
    assert_eq!((last.node_count(), count), (0, 20000));
}
