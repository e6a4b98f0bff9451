//! Tests of the SU2 reader and writer.

use super::*;
use crate::mesh::Cells;

#[test]
fn a_vtk_numbered_prism_reads_positively_oriented_and_writes_back() {
    // VTK/SU2 prism: triangle 0-1-2 faces away from 3-4-5.
    let text = "NDIME= 3\nNPOIN= 6\n0 0 0\n0 1 0\n1 0 0\n0 0 1\n0 1 1\n1 0 1\n\
                    NELEM= 1\n13 0 1 2 3 4 5\nNMARK= 0\n";
    let m = parse(text.as_bytes(), Path::new("prism.su2")).unwrap();
    assert_eq!(m.cells.cell(0), &[0, 2, 1, 3, 5, 4]);
    assert_eq!(crate::quality::orientation(&m), vec![1]);
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    assert!(String::from_utf8(out)
        .unwrap()
        .contains("13\t0\t1\t2\t3\t4\t5"));
}

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/su2/");

/// A unit square of two triangles with one marker; lines are numbered in comments.
const SQUARE: &str = "\
NDIME= 2
NELEM= 2
5 0 1 2 0
5 0 2 3 1
NPOIN= 4
0 0 0
1 0 1
1 1 2
0 1 3
NMARK= 1
MARKER_TAG= wall
MARKER_ELEMS= 1
3 0 1
";

fn parse_str(text: &str) -> Result<Mesh> {
    parse(text.as_bytes(), Path::new("t.su2"))
}

fn error(text: &str) -> String {
    parse_str(text).unwrap_err().to_string()
}

/// `SQUARE` with line `n` (1-based) replaced by `by`.
fn square_with(n: usize, by: &str) -> String {
    let mut lines: Vec<&str> = SQUARE.lines().collect();
    lines[n - 1] = by;
    lines.join("\n") + "\n"
}

fn real(name: &str) -> Mesh {
    crate::io::read(Path::new(&format!("{DIR}{name}"))).unwrap()
}

fn count(cells: &Cells, kind: CellKind) -> usize {
    cells.kinds.iter().filter(|&&k| k == kind).count()
}

fn group_sizes(mesh: &Mesh) -> Vec<(String, usize)> {
    mesh.groups
        .iter()
        .map(|g| (g.name.clone(), g.nodes().len()))
        .collect()
}

fn round_trip(mesh: &Mesh) {
    let mut text = Vec::new();
    write_to(&mut text, mesh).unwrap();
    let back = parse(&text, Path::new("rt.su2")).unwrap();
    assert_eq!(&back, mesh);
    let bits = |m: &Mesh| m.coords.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&back), bits(mesh));
    let mut again = Vec::new();
    write_to(&mut again, &back).unwrap();
    assert_eq!(again, text);
}

#[test]
fn naca0012() {
    let m = real("mesh_NACA0012_inv.su2");
    assert_eq!((m.dim, m.node_count()), (2, 5233));
    assert_eq!(count(&m.cells, CellKind::Triangle), 10216);
    assert_eq!(m.cell_count(), 10216);
    assert_eq!(
        group_sizes(&m),
        [("airfoil".to_string(), 200), ("farfield".to_string(), 50)]
    );
    assert!(m
        .groups
        .iter()
        .all(|g| count(&g.facets, CellKind::Line) == g.facets.len()));
    assert_eq!(m.cells.cell(0), &[417, 69, 311]);
    assert_eq!(m.point(0), &[9.9975001812e-01, -3.632896519016437e-05]);
    assert_eq!((m.node_tags[0], m.node_tags[5232]), (1, 5233));
    assert_eq!((m.cell_tags[0], m.cell_tags[10215]), (1, 10216));
    round_trip(&m);
}

#[test]
fn rae2822_hybrid_with_ffd_and_periodic_blocks() {
    let m = real("mesh_RAE2822_turb_ffd.su2");
    assert_eq!((m.dim, m.node_count()), (2, 13937));
    assert_eq!(count(&m.cells, CellKind::Triangle), 18042);
    assert_eq!(count(&m.cells, CellKind::Quad), 4800);
    assert_eq!(m.cell_count(), 22842);
    assert_eq!(
        group_sizes(&m),
        [("AIRFOIL".to_string(), 192), ("FARFIELD".to_string(), 40)]
    );
    round_trip(&m);
    let file = std::fs::read_to_string(format!("{DIR}mesh_RAE2822_turb_ffd.su2")).unwrap();
    let blocks = &file[file.find("NPERIODIC=").unwrap()..];
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    assert!(String::from_utf8(out).unwrap().ends_with(blocks));
}

/// A brick mesh on [0,2]×[0,1]×[0,1]: six markers, each on its face.
fn check_brick(m: &Mesh, nodes: usize, kind: CellKind, cells: usize, facet: CellKind) {
    assert_eq!((m.dim, m.node_count()), (3, nodes));
    assert_eq!((count(&m.cells, kind), m.cell_count()), (cells, cells));
    let sizes: Vec<_> = [400, 400, 800, 800, 800, 800]
        .into_iter()
        .zip(["x_m", "x_p", "y_m", "y_p", "z_m", "z_p"])
        .map(|(n, name)| (name.to_string(), n))
        .collect();
    assert_eq!(group_sizes(m), sizes);
    for (g, (axis, value)) in
        m.groups
            .iter()
            .zip([(0, 0.0), (0, 2.0), (1, 0.0), (1, 1.0), (2, 0.0), (2, 1.0)])
    {
        assert_eq!(count(&g.facets, facet), g.facets.len(), "{}", g.name);
        for n in g.nodes() {
            assert!(
                (m.point(n)[axis] - value).abs() < 1e-12,
                "{} node {n}",
                g.name
            );
        }
    }
}

#[test]
fn brick_tets() {
    let m = real("mesh_brick_tets_ffd.su2");
    check_brick(&m, 11703, CellKind::Tetra, 59156, CellKind::Triangle);
    round_trip(&m);
}

#[test]
fn brick_hexes() {
    let m = real("mesh_brick_hex_ffd.su2");
    check_brick(&m, 16000, CellKind::Hexahedron, 14079, CellKind::Quad);
    round_trip(&m);
}

#[test]
fn square_reads_and_round_trips() {
    let m = parse_str(SQUARE).unwrap();
    assert_eq!(m.coords, [0., 0., 1., 0., 1., 1., 0., 1.]);
    assert_eq!(m.cells.nodes, [0, 1, 2, 0, 2, 3]);
    assert_eq!(m.group("wall").unwrap().facets.nodes, [0, 1]);
    round_trip(&m);
}

#[test]
fn every_kind_and_vertex_markers_round_trip() {
    let text = "\
NDIME= 3
NELEM= 4
10 0 1 2 3
12 0 1 2 3 4 5 6 7
13 0 1 2 3 4 5
14 0 1 2 3 4
NPOIN= 8
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
NMARK= 2
MARKER_TAG= bottom
MARKER_ELEMS= 2
9 0 1 2 3
5 0 1 2
MARKER_TAG= probe
MARKER_ELEMS= 1
1 6
";
    let m = parse_str(text).unwrap();
    let kinds = [
        CellKind::Tetra,
        CellKind::Hexahedron,
        CellKind::Wedge,
        CellKind::Pyramid,
    ];
    assert_eq!(m.cells.kinds, kinds);
    assert_eq!(m.groups[1].facets.kinds, [CellKind::Vertex]);
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    assert!(String::from_utf8(out)
        .unwrap()
        .ends_with("MARKER_ELEMS= 1\n1\t6\n"));
    round_trip(&m);
}

#[test]
fn coordinates_keep_every_bit() {
    let coords = vec![
        0.1 + 0.2,
        -0.0,
        1e-300,
        -123456.789e10,
        f64::MIN_POSITIVE,
        f64::MAX,
    ];
    let mut cells = Cells::new();
    cells.push(CellKind::Triangle, &[0, 1, 2]);
    let m = Mesh::new(2, coords, cells, Vec::new()).unwrap();
    round_trip(&m);
}

#[test]
fn quirks_order_spellings_comments_trailing_indices_and_skipped_blocks() {
    let text = "\
% written by hand\r
NDIME=2\r
\r
NPOIN= 4 4\r
0 0 0 7\r
1 0 1\r
1 1\r
0 1 3 % last point\r
  ndime_extra = ignored\r
1 2 3\r
NMARK = 1\r
markertag=wall\r
Marker_Elems =1\r
3 0 1 0\r
NELEM= 2\r
5 0 1 2 0\r
5 0 2 3\r
NPERIODIC= 1\r
PERIODIC_INDEX= 0\r
0.0 0.0 0.0\r
FFD_NBOX= 1\r
FFD_TAG= MAIN_BOX\r
FFD_CORNER_POINTS= 4\r
-1e-08\t-0.07\r
FFD_SURFACE_POINTS= 1\r
wall\t0\t1.0\t2.0\r
";
    let mut m = parse_str(text).unwrap();
    let skipped: Vec<(Anchor, &str)> = m
        .origin
        .su2_skipped
        .iter()
        .map(|b| (b.after, b.text.as_str()))
        .collect();
    assert_eq!(
        skipped,
        [
            (Anchor::Points, "  ndime_extra = ignored\r\n1 2 3\r\n"),
            (
                Anchor::Elements,
                &text[text.find("NPERIODIC").unwrap()..] as &str
            )
        ]
    );
    m.origin.su2_skipped.clear();
    assert_eq!(m, parse_str(SQUARE).unwrap());
}

/// A file in the writer's own layout, with skipped blocks after every
/// section: writing what was read gives the same bytes.
const SKIPPED_EVERYWHERE: &str = "\
NZONE= 1
NDIME= 2
FFD_NBOX= 0
NELEM= 2
5\t0\t1\t2\t0
5\t0\t2\t3\t1
% a comment kept with its block
EXTRA= a b c
1 2 3

NPOIN= 4
0.0\t0.0\t0
1.0\t0.0\t1
1.0\t1.0\t2
0.0\t1.0\t3
NPERIODIC= 1
PERIODIC_INDEX= 0
0.0\t0.0\t0.0
NMARK= 2
AFTER_NMARK= 1
MARKER_TAG= wall
MARKER_ELEMS= 1
3\t0\t1
AFTER_WALL= 2
MARKER_TAG= rest
MARKER_ELEMS= 3
3\t1\t2
3\t2\t3
3\t3\t0
FFD_NBOX= 1
FFD_TAG= MAIN_BOX
FFD_CORNER_POINTS= 4
-1e-08\t-0.07
1.00000001\t-0.07
1.00000001\t0.07
-1e-08\t0.07
FFD_SURFACE_POINTS= 1
wall\t0\t0.25\t0.5\t0.5
";

#[test]
fn skipped_blocks_are_written_back_verbatim_where_they_were() {
    let m = parse_str(SKIPPED_EVERYWHERE).unwrap();
    let anchors: Vec<Anchor> = m.origin.su2_skipped.iter().map(|b| b.after).collect();
    use Anchor::*;
    assert_eq!(
        anchors,
        [
            Start,
            Dimension,
            Elements,
            Points,
            MarkerCount,
            Marker(0),
            Marker(1)
        ]
    );
    assert_eq!(
        m.origin.su2_skipped[2].text,
        "% a comment kept with its block\nEXTRA= a b c\n1 2 3\n\n"
    );
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    assert_eq!(String::from_utf8(out).unwrap(), SKIPPED_EVERYWHERE);
    round_trip(&m);
}

#[test]
fn skipped_blocks_of_groups_that_are_gone_follow_the_last_marker() {
    let mut m = parse_str(SKIPPED_EVERYWHERE).unwrap();
    m.groups.pop();
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    let text = String::from_utf8(out).unwrap();
    let ffd = &SKIPPED_EVERYWHERE[SKIPPED_EVERYWHERE.find("FFD_NBOX= 1").unwrap()..];
    assert!(
        text.ends_with(&format!("3\t0\t1\nAFTER_WALL= 2\n{ffd}")),
        "{text}"
    );
    m.groups.clear();
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(
        text.ends_with(&format!("NMARK= 0\nAFTER_NMARK= 1\nAFTER_WALL= 2\n{ffd}")),
        "{text}"
    );
}

#[test]
fn a_skipped_block_at_an_end_without_newline_gets_one() {
    let text = format!("{SQUARE}FFD_NBOX= 0");
    let m = parse_str(&text).unwrap();
    assert_eq!(m.origin.su2_skipped[0].text, "FFD_NBOX= 0");
    let mut out = Vec::new();
    write_to(&mut out, &m).unwrap();
    assert!(String::from_utf8(out)
        .unwrap()
        .ends_with("3\t0\t1\nFFD_NBOX= 0\n"));
}

#[test]
fn writer_rejects_names_su2_cannot_hold() {
    let mut m = parse_str(SQUARE).unwrap();
    m.groups[0].name = "50% span".into();
    let e = write_to(&mut Vec::new(), &m).unwrap_err();
    assert_eq!(
        e.to_string(),
        "group name \"50% span\" cannot be written as an SU2 MARKER_TAG"
    );
}

#[test]
fn missing_file() {
    let path = format!("{DIR}no_such_mesh.su2");
    let e = crate::io::read(Path::new(&path)).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{path}: No such file or directory (os error 2)")
    );
}

#[test]
fn truncated_file() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/bad/truncated.su2"
    );
    let e = crate::io::read(Path::new(path)).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{path}:7: file ends after 2 of the 4 points announced by NPOIN= at line 5")
    );
    let cut: String = SQUARE.lines().take(11).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        error(&cut),
        "t.su2:11: marker 'wall' (MARKER_TAG= at line 11) has no MARKER_ELEMS="
    );
    let cut: String = SQUARE.lines().take(3).map(|l| format!("{l}\n")).collect();
    assert_eq!(
        error(&cut),
        "t.su2:3: file ends after 1 of the 2 elements announced by NELEM= at line 2"
    );
}

#[test]
fn counts_that_disagree_with_the_data() {
    assert_eq!(
        error(&square_with(5, "NPOIN= 5")),
        "t.su2:10: found NMARK= after 4 of the 5 points announced by NPOIN= at line 5 \
             (the count disagrees with the data)"
    );
    assert_eq!(
        error(&square_with(5, "NPOIN= 3")),
        "t.su2:9: unexpected data line '0 1 3' after the 3 points announced by NPOIN= \
             at line 5 (the count disagrees with the data)"
    );
    assert_eq!(
        error(&square_with(2, "NELEM= 3")),
        "t.su2:5: found NPOIN= after 2 of the 3 elements announced by NELEM= at line 2 \
             (the count disagrees with the data)"
    );
    assert_eq!(
        error(&square_with(10, "NMARK= 2")),
        "t.su2:13: file ends after 1 of the 2 markers announced by NMARK= at line 10"
    );
    assert_eq!(
        error(&format!("{SQUARE}MARKER_TAG= top\nMARKER_ELEMS= 0\n")),
        "t.su2:14: MARKER_TAG= top is one more marker than the 1 announced by NMARK= at \
             line 10 (the count disagrees with the data)"
    );
    assert_eq!(
        error(&square_with(12, "MARKER_ELEMS= 0")),
        "t.su2:13: unexpected data line '3 0 1' after the 0 marker elements announced by \
             MARKER_ELEMS= at line 12 (the count disagrees with the data)"
    );
}

#[test]
fn huge_counts_do_not_allocate() {
    assert_eq!(
        error("NDIME= 3\nNPOIN= 18446744073709551615\n0 0 0\n"),
        "t.su2:3: file ends after 1 of the 18446744073709551615 points announced by \
             NPOIN= at line 2"
    );
    assert_eq!(
        error("NDIME= 3\nNELEM= 99999999999999\n"),
        "t.su2:2: file ends after 0 of the 99999999999999 elements announced by NELEM= \
             at line 2"
    );
}

#[test]
fn node_index_out_of_range() {
    assert_eq!(
        error(&square_with(4, "5 0 2 4 1")),
        "t.su2:4: node index 4 out of range (NPOIN= 4 at line 5: indices 0 to 3)"
    );
    assert_eq!(
        error(&square_with(13, "3 0 9")),
        "t.su2:13: node index 9 out of range (NPOIN= 4 at line 5: indices 0 to 3)"
    );
}

#[test]
fn non_finite_coordinates() {
    assert_eq!(
        error(&square_with(7, "nan 0 1")),
        "t.su2:7: non-finite coordinate 'nan' (expected a finite number)"
    );
    assert_eq!(
        error(&square_with(8, "1 -inf 2")),
        "t.su2:8: non-finite coordinate '-inf' (expected a finite number)"
    );
}

#[test]
fn element_types() {
    assert_eq!(
        error(&square_with(3, "7 0 1 2 0")),
        "t.su2:3: unsupported SU2 element type 7 (expected 5 triangle or 9 quadrilateral)"
    );
    assert_eq!(
        error(&square_with(4, "10 0 1 2 3")),
        "t.su2:4: SU2 element type 10 (tetrahedron) does not belong in the elements of a \
             2D mesh (expected 5 triangle or 9 quadrilateral)"
    );
    assert_eq!(
        error(&square_with(13, "5 0 1 2")),
        "t.su2:13: SU2 element type 5 (triangle) does not belong in the marker elements \
             of a 2D mesh (expected 1 vertex or 3 line)"
    );
    assert_eq!(
        error("NDIME= 3\nNELEM= 1\n22 0 1 2 3 4 5\n"),
        "t.su2:3: unsupported SU2 element type 22 (expected 10 tetrahedron, \
             12 hexahedron, 13 prism or 14 pyramid)"
    );
    assert_eq!(
        error(&square_with(3, "5 0 1")),
        "t.su2:3: triangle (type 5) needs 3 node indices, found 2"
    );
}

#[test]
fn non_numeric_junk() {
    assert_eq!(
        error(&square_with(3, "5 0 x 2 0")),
        "t.su2:3: expected a node index, found 'x'"
    );
    assert_eq!(
        error(&square_with(3, "triangle 0 1 2")),
        "t.su2:3: expected an SU2 element type (5 triangle or 9 quadrilateral), \
             found 'triangle'"
    );
    assert_eq!(
        error(&square_with(6, "0 zero 0")),
        "t.su2:6: expected a coordinate, found 'zero'"
    );
    assert_eq!(
        error(&square_with(6, "0 0 0.5 0")),
        "t.su2:6: expected an index after the 2 coordinates, found '0.5'"
    );
    assert_eq!(
        error(&square_with(6, "0")),
        "t.su2:6: expected NDIME= 2 coordinates, found 1 in '0'"
    );
    assert_eq!(
        error(&square_with(5, "NPOIN= many")),
        "t.su2:5: expected a count after NPOIN=, found 'many'"
    );
    assert_eq!(
        error(&square_with(10, "garbage")),
        "t.su2:10: unexpected data line 'garbage' after the 4 points announced by NPOIN= \
             at line 5 (the count disagrees with the data)"
    );
}

#[test]
fn binary_junk() {
    let mut bytes = SQUARE.as_bytes().to_vec();
    let at = SQUARE.find("1 0 1").unwrap() + 2;
    bytes[at] = 0xff;
    let e = parse(&bytes, Path::new("t.su2")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "t.su2:7: non-UTF-8 byte 0xff at column 3 (expected SU2 ASCII text, found binary data)"
    );
}

#[test]
fn dimension() {
    assert_eq!(
        error(&square_with(1, "NDIME= 4")),
        "t.su2:1: NDIME= 4 (expected 2 or 3)"
    );
    assert_eq!(
        error(&square_with(1, "NDIME= 1")),
        "t.su2:1: NDIME= 1 (expected 2 or 3)"
    );
    assert_eq!(
        error(&square_with(1, "% no dimension")),
        "t.su2:2: NELEM= before NDIME= (expected NDIME= 2 or 3 first)"
    );
    assert_eq!(
        error(""),
        "t.su2:1: missing NDIME= (expected NDIME= 2 or 3)"
    );
    assert_eq!(
        error(&format!("{SQUARE}NDIME= 2\n")),
        "t.su2:14: NDIME= given twice (first at line 1; a multi-zone file starts with NZONE= N and gives each zone after its IZONE= K line)"
    );
}

#[test]
fn missing_sections_and_marker_structure() {
    assert_eq!(
        error("NDIME= 2\nNELEM= 0\n"),
        "t.su2:2: missing NPOIN= (the file has no points)"
    );
    assert_eq!(
        error("NDIME= 2\nNPOIN= 0\n"),
        "t.su2:2: missing NELEM= (the file has no elements)"
    );
    assert_eq!(
        error(&square_with(10, "% no NMARK")),
        "t.su2:11: MARKER_TAG= before NMARK="
    );
    assert_eq!(
        error(&square_with(11, "MARKER_TAG=")),
        "t.su2:11: empty MARKER_TAG= (expected a name)"
    );
    assert_eq!(
        error(&format!(
            "{}MARKER_TAG= wall\nMARKER_ELEMS= 0\n",
            square_with(10, "NMARK= 2")
        )),
        "t.su2:14: marker 'wall' given twice (first at line 11)"
    );
}
