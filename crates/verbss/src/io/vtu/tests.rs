//! Round trips, meshio fixtures, appended data and every reader error.

use std::io::Write;
use std::path::Path;

use base64::engine::general_purpose::STANDARD;
use base64::Engine;

use super::*;
use crate::mesh::{samples, CellKind, Cells, Group};

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/vtu/");

fn cells(list: &[(CellKind, &[usize])]) -> Cells {
    let mut cells = Cells::new();
    for (kind, nodes) in list {
        cells.push(*kind, nodes);
    }
    cells
}

fn group(name: &str, tag: Option<i32>, facets: &[(CellKind, &[usize])]) -> Group {
    Group {
        name: name.into(),
        tag,
        facets: cells(facets),
    }
}

/// [`samples::two_triangles_and_a_quad`] without its groups, scaled: the
/// mesh of scripts/make_vtu_fixtures.py at 0.1.
fn mesh_2d(scale: f64) -> Mesh {
    scaled(samples::two_triangles_and_a_quad(), scale)
}

/// [`samples::hex_wedge_pyramid_tet`] without its groups, scaled, as in
/// scripts/make_vtu_fixtures.py.
fn mesh_3d(scale: f64) -> Mesh {
    scaled(samples::hex_wedge_pyramid_tet(), scale)
}

/// `mesh` without groups, every coordinate times `scale`.
fn scaled(mut mesh: Mesh, scale: f64) -> Mesh {
    mesh.groups.clear();
    for x in &mut mesh.coords {
        *x *= scale;
    }
    mesh
}

fn round_trip(mesh: &Mesh, fields: &Fields) -> VtuData {
    let mut bytes = Vec::new();
    write_to(&mut bytes, mesh, fields).unwrap();
    parse(&bytes, Path::new("t.vtu")).unwrap()
}

#[test]
fn round_trip_2d_keeps_mesh_groups_tags_and_fields() {
    let mut mesh = mesh_2d(0.1);
    mesh.node_tags = vec![10, 20, 30, 40, 50, 60];
    mesh.cell_tags = vec![7, 9, 8];
    mesh.groups = vec![
        group(
            "bottom",
            Some(3),
            &[(CellKind::Line, &[0, 1]), (CellKind::Line, &[1, 2])],
        ),
        group(
            "top <&\"'>",
            None,
            &[(CellKind::Line, &[5, 4]), (CellKind::Line, &[4, 3])],
        ),
        group("corner", None, &[(CellKind::Vertex, &[0])]),
    ];
    mesh.validate().unwrap();
    let u: Vec<f64> = (0..12).map(|i| f64::from(i) / 7.0).collect();
    let fields = Fields {
        point: vec![("u".into(), 2, u)],
        cell: vec![("rho".into(), 1, vec![1.0 / 3.0, -2.5, 1e-300])],
    };
    let back = round_trip(&mesh, &fields);
    assert_eq!(back.mesh, mesh);
    assert_eq!(back.fields, fields);
}

#[test]
fn round_trip_3d_keeps_every_volume_kind() {
    let mut mesh = mesh_3d(1.0 / 3.0);
    mesh.groups = vec![
        group(
            "floor",
            Some(5),
            &[
                (CellKind::Quad, &[0, 3, 2, 1]),
                (CellKind::Triangle, &[1, 2, 8]),
            ],
        ),
        group("apex", None, &[(CellKind::Vertex, &[10])]),
        group("empty", Some(-4), &[]),
        group("edge", None, &[(CellKind::Line, &[0, 1])]),
    ];
    mesh.validate().unwrap();
    let v: Vec<f64> = (0..36).map(|i| (f64::from(i) * 0.37).sin()).collect();
    let fields = Fields {
        point: vec![("v".into(), 3, v), ("phi".into(), 1, vec![0.5; 12])],
        cell: vec![("q".into(), 2, vec![1., 2., 3., 4., 5., 6., 7., 8.])],
    };
    let back = round_trip(&mesh, &fields);
    assert_eq!(back.mesh, mesh);
    assert_eq!(back.fields, fields);
}

#[test]
fn written_file_has_the_documented_layout() {
    let mut mesh = mesh_2d(1.0);
    mesh.groups = vec![group("wall", Some(2), &[(CellKind::Line, &[0, 1])])];
    let mut bytes = Vec::new();
    write_to(&mut bytes, &mesh, &Fields::default()).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    assert!(text.contains(r#"header_type="UInt64""#));
    assert!(text.contains(
        r#"<DataArray type="Int32" Name="wall" NumberOfTuples="3" format="ascii">1 1 2</DataArray>"#
    ));
    assert!(text.contains(r#"<Piece NumberOfPoints="6" NumberOfCells="4">"#));
    // types: 5 5 9 3 as UInt8, one zlib block: the header [1, 32768, 4,
    // compressed size], then the block (zlib's fastest level, as written).
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    z.write_all(&[5u8, 5, 9, 3]).unwrap();
    let block = z.finish().unwrap();
    let header: Vec<u8> = [1, 32768, 4, block.len() as u64]
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .collect();
    let types = STANDARD.encode(header) + &STANDARD.encode(block);
    assert!(text.contains(&format!(r#"Name="types" format="binary">{types}<"#)));
}

#[test]
fn writer_rejects_fields_that_do_not_fit() {
    let mesh = mesh_2d(1.0);
    let err = |fields: Fields| {
        write_to(&mut Vec::new(), &mesh, &fields)
            .unwrap_err()
            .to_string()
    };
    let point = |name: &str, c, n| Fields {
        point: vec![(name.to_string(), c, vec![0.0; n])],
        cell: Vec::new(),
    };
    assert_eq!(
        err(point("u", 2, 6)),
        "point field 'u' has 6 values (expected 2 × 6)"
    );
    assert_eq!(
        err(point("node_tag", 1, 6)),
        "point field name 'node_tag' is reserved"
    );
    assert_eq!(
        err(Fields {
            point: Vec::new(),
            cell: vec![("group".into(), 1, vec![0.0; 3])],
        }),
        "cell field name 'group' is reserved"
    );
    assert_eq!(
        err(Fields {
            point: Vec::new(),
            cell: vec![("a".into(), 1, vec![0.0; 3]), ("a".into(), 1, vec![0.0; 3])],
        }),
        "cell field 'a' is given twice"
    );
}

#[test]
fn reads_meshio_zlib_file() {
    let data = read(Path::new(&format!("{FIXTURES}meshio_2d_zlib.vtu"))).unwrap();
    let mut expected = mesh_2d(1.0);
    expected.groups = vec![group(
        "boundary",
        None,
        &[
            (CellKind::Line, &[0, 1]),
            (CellKind::Line, &[1, 2]),
            (CellKind::Line, &[5, 4]),
            (CellKind::Line, &[4, 3]),
        ],
    )];
    assert_eq!(data.mesh, expected);
    let u = expected.coords.iter().map(|x| x * 0.5).collect();
    let fields = Fields {
        point: vec![("u".into(), 2, u)],
        cell: vec![("pressure".into(), 1, vec![1.5, 2.5, 3.5])],
    };
    assert_eq!(data.fields, fields);
}

#[test]
fn reads_meshio_ascii_and_uint64_header_files() {
    let mut expected = mesh_3d(1.0);
    expected.groups = vec![group(
        "boundary",
        None,
        &[
            (CellKind::Quad, &[0, 3, 2, 1]),
            (CellKind::Triangle, &[1, 2, 8]),
        ],
    )];
    for name in ["meshio_3d_ascii.vtu", "meshio_3d_raw64.vtu"] {
        let data = read(Path::new(&format!("{FIXTURES}{name}"))).unwrap();
        assert_eq!(data.mesh, expected, "{name}");
        assert_eq!(data.fields, Fields::default(), "{name}");
    }
}

/// The 2D test mesh with appended data: `encoding` raw or base64,
/// optionally zlib-compressed in 16-byte blocks, in either byte order.
fn appended_file(base64: bool, zlib: bool, big: bool) -> Vec<u8> {
    let mesh = mesh_2d(0.1);
    let to = |v: &[u8]| {
        if big {
            v.iter().rev().copied().collect()
        } else {
            v.to_vec()
        }
    };
    let points: Vec<u8> = (0..6)
        .flat_map(|i| [mesh.point(i)[0], mesh.point(i)[1], 0.0])
        .flat_map(|x| to(&x.to_le_bytes()))
        .collect();
    let ints = |v: &[i32]| -> Vec<u8> { v.iter().flat_map(|x| to(&x.to_le_bytes())).collect() };
    let arrays = [
        ("Float64", "Points", points),
        (
            "Int32",
            "connectivity",
            ints(&[1, 2, 5, 1, 5, 4, 0, 1, 4, 3]),
        ),
        ("Int32", "offsets", ints(&[3, 6, 10])),
        ("UInt8", "types", vec![5, 5, 9]),
    ];
    let word = |x: usize| to(&(x as u32).to_le_bytes());
    let mut data = Vec::new();
    let mut tags = Vec::new();
    for (ty, name, payload) in arrays {
        let comps = if name == "Points" {
            r#" NumberOfComponents="3""#
        } else {
            ""
        };
        tags.push(format!(
            r#"<DataArray type="{ty}" Name="{name}"{comps} format="appended" offset="{}"/>"#,
            data.len()
        ));
        let (header, body) = if zlib {
            let blocks: Vec<Vec<u8>> = payload
                .chunks(16)
                .map(|b| {
                    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), Default::default());
                    z.write_all(b).unwrap();
                    z.finish().unwrap()
                })
                .collect();
            let last = payload.len() % 16;
            let mut h = [word(blocks.len()), word(16), word(last)].concat();
            h.extend(blocks.iter().flat_map(|b| word(b.len())));
            (h, blocks.concat())
        } else {
            (word(payload.len()), payload)
        };
        if base64 {
            data.extend(STANDARD.encode(header).bytes());
            data.extend(STANDARD.encode(body).bytes());
        } else {
            data.extend(header);
            data.extend(body);
        }
    }
    let order = if big { "BigEndian" } else { "LittleEndian" };
    let compressor = if zlib {
        r#" compressor="vtkZLibDataCompressor""#
    } else {
        ""
    };
    let encoding = if base64 { "base64" } else { "raw" };
    let mut file = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" \
         byte_order=\"{order}\"{compressor}>\n<UnstructuredGrid>\n\
         <Piece NumberOfPoints=\"6\" NumberOfCells=\"3\">\n<Points>\n{}\n</Points>\n\
         <Cells>\n{}\n{}\n{}\n</Cells>\n</Piece>\n</UnstructuredGrid>\n\
         <AppendedData encoding=\"{encoding}\">\n   _",
        tags[0], tags[1], tags[2], tags[3]
    )
    .into_bytes();
    file.extend(data);
    file.extend(b"\n</AppendedData>\n</VTKFile>\n");
    file
}

#[test]
fn reads_appended_raw_and_base64_in_both_byte_orders() {
    for base64 in [false, true] {
        for zlib in [false, true] {
            for big in [false, true] {
                let file = appended_file(base64, zlib, big);
                let data = parse(&file, Path::new("a.vtu"))
                    .unwrap_or_else(|e| panic!("{base64} {zlib} {big}: {e}"));
                assert_eq!(data.mesh, mesh_2d(0.1), "{base64} {zlib} {big}");
            }
        }
    }
}

/// A one-triangle ascii file; the tests below break one thing in it.
const TRI: &str = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0">
<UnstructuredGrid>
<Piece NumberOfPoints="3" NumberOfCells="1">
<Points>
<DataArray type="Float64" Name="Points" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0</DataArray>
</Points>
<Cells>
<DataArray type="Int32" Name="connectivity" format="ascii">0 1 2</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5</DataArray>
</Cells>
</Piece>
</UnstructuredGrid>
</VTKFile>
"#;

fn error(text: &str) -> String {
    parse(text.as_bytes(), Path::new("x.vtu"))
        .unwrap_err()
        .to_string()
}

fn broken(from: &str, to: &str) -> String {
    assert!(TRI.contains(from), "{from}");
    error(&TRI.replacen(from, to, 1))
}

#[test]
fn the_unbroken_triangle_reads() {
    let mesh = parse(TRI.as_bytes(), Path::new("x.vtu")).unwrap().mesh;
    assert_eq!(mesh.dim, 2);
    assert_eq!(mesh.cells, cells(&[(CellKind::Triangle, &[0, 1, 2])]));
    assert!(mesh.groups.is_empty());
}

#[test]
fn error_not_xml() {
    assert_eq!(
        error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"),
        "x.vtu:1: not a VTK XML file (expected <VTKFile type=\"UnstructuredGrid\">)"
    );
    assert_eq!(
        error(""),
        "x.vtu:1: not a VTK XML file (expected <VTKFile type=\"UnstructuredGrid\">)"
    );
    assert_eq!(
        broken("<VTKFile", "<Mesh"),
        "x.vtu:2: not a VTK XML file (expected <VTKFile type=\"UnstructuredGrid\">)"
    );
    assert_eq!(
        broken("UnstructuredGrid\" version", "PolyData\" version"),
        "x.vtu:2: VTKFile type=\"PolyData\" (expected \"UnstructuredGrid\")"
    );
    assert_eq!(
        broken("</Points>", "</Cells>"),
        "x.vtu:7: malformed XML: ill-formed document: expected `</Points>`, but `</Cells>` was found"
    );
}

#[test]
fn error_missing_sections() {
    // TRI without the lines from `from` to `to` (both included).
    let cut = |from: &str, to: &str| {
        let (head, rest) = TRI.split_once(from).unwrap();
        head.to_string() + rest.split_once(to).unwrap().1
    };
    assert_eq!(
        error(&cut("<Piece", "</Piece>\n")),
        "x.vtu:3: missing <Piece> in <UnstructuredGrid>"
    );
    assert_eq!(
        error(&cut("<Points>", "</Points>\n")),
        "x.vtu:4: missing <Points> in <Piece>"
    );
    assert_eq!(
        error(&cut("<Cells>", "</Cells>\n")),
        "x.vtu:4: missing <Cells> in <Piece>"
    );
    assert_eq!(
        broken(r#"Name="offsets""#, r#"Name="offset""#),
        "x.vtu:8: missing DataArray 'offsets' in <Cells>"
    );
    assert_eq!(
        broken("<UnstructuredGrid>", "<Grid>"),
        "x.vtu:14: malformed XML: ill-formed document: expected `</Grid>`, but `</UnstructuredGrid>` was found"
    );
}

#[test]
fn error_counts_that_disagree() {
    assert_eq!(
        broken(r#"NumberOfPoints="3""#, r#"NumberOfPoints="4""#),
        "x.vtu:6: DataArray 'Points': 9 values but NumberOfPoints=4 needs 12"
    );
    assert_eq!(
        broken(r#"NumberOfPoints="3""#, r#"NumberOfPoints="99999999999999""#),
        "x.vtu:6: DataArray 'Points': 9 values but NumberOfPoints=99999999999999 needs 299999999999997"
    );
    assert_eq!(
        broken(r#"NumberOfPoints="3""#, r#"NumberOfPoints="-3""#),
        "x.vtu:4: Piece NumberOfPoints=\"-3\" is not a count"
    );
    assert_eq!(
        broken(">3</DataArray>", ">3 3</DataArray>"),
        "x.vtu:10: DataArray 'offsets': holds more than the 1 tuples that NumberOfCells=1 needs"
    );
    assert_eq!(
        broken(">5</DataArray>", ">9</DataArray>"),
        "x.vtu:10: DataArray 'offsets': cell 0 (quad) has 3 nodes (expected 4)"
    );
    assert_eq!(
        broken(">3</DataArray>", ">4</DataArray>"),
        "x.vtu:10: DataArray 'offsets': cell 0 ends at 4, outside 0..=3"
    );
    assert_eq!(
        broken(">0 1 2</DataArray>", ">0 1 2 0</DataArray>"),
        "x.vtu:10: DataArray 'offsets': the last cell ends at 3 but connectivity has 4 values"
    );
    let cell_data = "</Cells>\n<CellData><DataArray type=\"Float64\" Name=\"p\" format=\"ascii\">1 2</DataArray></CellData>";
    assert_eq!(
        broken("</Cells>", cell_data),
        "x.vtu:13: DataArray 'p': holds more than the 1 tuples that NumberOfCells=1 needs"
    );
}

#[test]
fn error_bad_numbers_and_types() {
    assert_eq!(
        broken("0 0 0 1 0 0", "0 0 0 1 0\n\nx"),
        "x.vtu:8: DataArray 'Points': \"x\" is not a number"
    );
    assert_eq!(
        broken(
            r#"type="Int32" Name="connectivity""#,
            r#"type="Float32" Name="connectivity""#
        ),
        "x.vtu:9: DataArray 'connectivity': expected an integer type"
    );
    assert_eq!(
        broken(r#"type="UInt8""#, r#"type="Char""#),
        "x.vtu:11: DataArray 'types': unknown type \"Char\""
    );
    assert_eq!(
        broken(
            r#"Name="types" format="ascii""#,
            r#"Name="types" format="hex""#
        ),
        "x.vtu:11: DataArray 'types': unknown format \"hex\""
    );
    assert_eq!(
        broken("<VTKFile type", "<VTKFile compressor=\"vtkLZ4DataCompressor\" type"),
        "x.vtu:2: VTKFile compressor=\"vtkLZ4DataCompressor\" (expected vtkZLibDataCompressor or none)"
    );
}

#[test]
fn error_bad_base64() {
    let binary = r#"format="binary">AAAA!AAA</DataArray>"#;
    assert_eq!(
        broken(r#"format="ascii">0 1 2</DataArray>"#, binary),
        "x.vtu:9: DataArray 'connectivity': invalid base64 character '!' at position 4"
    );
    let short = r#"format="binary">DAAAAAAA</DataArray>"#;
    assert_eq!(
        broken(r#"format="ascii">0 1 2</DataArray>"#, short),
        "x.vtu:9: DataArray 'connectivity': truncated: header claims 12 bytes but only 2 remain"
    );
    let cut = r#"format="binary">DAAAAAAAA</DataArray>"#;
    assert_eq!(
        broken(r#"format="ascii">0 1 2</DataArray>"#, cut),
        "x.vtu:9: DataArray 'connectivity': base64 data of 9 characters is cut short"
    );
}

#[test]
fn error_connectivity_out_of_range() {
    assert_eq!(
        broken(">0 1 2<", ">0 1 7<"),
        "x.vtu:9: DataArray 'connectivity': cell 0 uses point 7 but NumberOfPoints=3"
    );
    assert_eq!(
        broken(">0 1 2<", ">0 -1 2<"),
        "x.vtu:9: DataArray 'connectivity': cell 0 uses point -1 but NumberOfPoints=3"
    );
}

#[test]
fn error_unknown_cell_type() {
    assert_eq!(
        broken(">5</DataArray>", ">22</DataArray>"),
        "x.vtu:11: DataArray 'types': cell 0 has unknown VTK type 22 (supported: 1 vertex, \
         3 line, 5 triangle, 7 polygon, 9 quad, 10 tetra, 12 hexahedron, 13 wedge, 14 pyramid, \
         42 polyhedron)"
    );
}

#[test]
fn error_nan_coordinates_and_surface_meshes() {
    assert_eq!(
        broken("0 0 0 1 0 0", "0 0 0 NaN 0 0"),
        "x.vtu:6: DataArray 'Points': point 1 has a non-finite coordinate (NaN)"
    );
    assert_eq!(
        broken("0 0 0 1 0 0", "0 0 1 1 0 0"),
        "x.vtu:4: no 3D cells but point 0 has z = 1 (surface meshes are not supported)"
    );
    assert_eq!(
        broken(">5</DataArray>", ">3</DataArray>"),
        "x.vtu:10: DataArray 'offsets': cell 0 (line) has 3 nodes (expected 2)"
    );
}

#[test]
fn error_truncated_file() {
    let cut = &TRI[..TRI.find("0 1 2</DataArray>").unwrap() + 2];
    assert_eq!(
        error(cut),
        "x.vtu:9: truncated file: end of file inside <DataArray>"
    );
    let cut = &TRI[..TRI.find("<Cells>").unwrap() + 4];
    assert_eq!(
        error(cut),
        "x.vtu:8: truncated file: tag not closed: `>` not found before end of input"
    );
    let file = appended_file(false, false, false);
    let start = file.windows(2).position(|w| w == b" _").unwrap() + 2;
    // Points take 4 + 144 bytes; keep connectivity's header and 2 bytes.
    let cut = &file[..start + 148 + 4 + 2];
    assert_eq!(
        parse(cut, Path::new("x.vtu")).unwrap_err().to_string(),
        format!(
            "x.vtu: byte {}: DataArray 'connectivity': truncated: header claims 40 bytes but only 2 remain",
            start + 4 + 144 + 4
        )
    );
}

#[test]
fn huge_claims_do_not_allocate() {
    let mut file = appended_file(false, true, false);
    let start = file.windows(2).position(|w| w == b" _").unwrap() + 2;
    // The first zlib header claims 2^32 - 1 blocks.
    file[start..start + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    assert_eq!(
        parse(&file, Path::new("x.vtu")).unwrap_err().to_string(),
        format!(
            "x.vtu: byte {}: DataArray 'Points': truncated: header claims 17179869180 bytes but only {} remain",
            start + 12,
            file.len() - start - 12
        )
    );
}

#[test]
fn arrays_are_written_in_zlib_blocks_and_read_back_bit_for_bit() {
    // 41 × 41 nodes: the 40,344-byte coordinate array spans two 32 KiB blocks.
    let mesh = samples::square_of_triangles(40);
    let mut bytes = Vec::new();
    write_to(&mut bytes, &mesh, &Fields::default()).unwrap();
    let text = String::from_utf8(bytes.clone()).unwrap();
    assert!(text.contains(r#"compressor="vtkZLibDataCompressor""#));
    let mut points = text.split(r#"Name="Points" NumberOfComponents="3" format="binary">"#);
    let encoded = points.nth(1).unwrap();
    // The header's first three words: 2 blocks of 32,768 bytes, the last of 7,576.
    let header = STANDARD.decode(&encoded[..32]).unwrap();
    let words: Vec<u64> = header
        .chunks(8)
        .map(|w| u64::from_le_bytes(w.try_into().unwrap()))
        .collect();
    assert_eq!(words[..3], [2, 32768, 41 * 41 * 24 - 32768]);
    let back = parse(&bytes, Path::new("t.vtu")).unwrap();
    assert_eq!(
        (back.mesh.coords, back.mesh.cells),
        (mesh.coords, mesh.cells)
    );
}
