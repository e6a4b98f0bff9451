//! The reader against hostile files: what it skips, what it bounds and the
//! zlib arrays it decodes streaming.

use std::io::Write;
use std::path::Path;

use base64::engine::general_purpose::STANDARD;
use base64::Engine;

use super::xml::MAX_ARRAYS;
use super::*;
use crate::io::MAX_GROUPS;

/// A unit square of two triangles; `field_data`, `point_data` go in their sections.
fn square(field_data: &str, point_data: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" compressor="vtkZLibDataCompressor">
<UnstructuredGrid>
<FieldData>{field_data}</FieldData>
<Piece NumberOfPoints="4" NumberOfCells="2">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 1 1 0 0 1 0</DataArray></Points>
<Cells>
<DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 0 2 3</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3 6</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5 5</DataArray>
</Cells>
<PointData>{point_data}</PointData>
</Piece>
</UnstructuredGrid>
</VTKFile>
"#
    )
}

fn read(text: &str) -> Result<VtuData> {
    parse(text.as_bytes(), Path::new("x.vtu"))
}

fn error(text: &str) -> String {
    read(text).unwrap_err().to_string()
}

/// The zlib stream of `data`.
fn zlib(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

/// A binary `Float64` point-data array `u`: UInt32 header `words`, then `data`.
fn binary(words: &[u32], data: &[u8]) -> String {
    let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    bytes.extend(data);
    format!(
        r#"<DataArray type="Float64" Name="u" format="binary">{}</DataArray>"#,
        STANDARD.encode(bytes)
    )
}

#[test]
fn unknown_elements_are_skipped_with_what_they_hold() {
    let plain = read(&square("", "")).unwrap();
    // A million empty elements, an unknown element with a repeated attribute
    // and 50 levels of nesting: none of them is kept.
    let noise = format!(
        "{}<x a=\"1\" a=\"2\">{}{}</x>",
        "<e/>".repeat(1_000_000),
        "<y>".repeat(50),
        "</y>".repeat(50)
    );
    assert_eq!(read(&square(&noise, &noise)).unwrap(), plain);
    // Attributes the reader does not use are not kept or compared.
    let attrs: String = (0..100_000).map(|i| format!(" a{i}=\"\"")).collect();
    let text = square("", "").replacen("<VTKFile ", &format!("<VTKFile{attrs} "), 1);
    assert_eq!(read(&text).unwrap(), plain);
    // A used attribute given twice is an error.
    let text = square("", "").replacen(r#"type="Int32""#, r#"type="Int32" type="Int8""#, 1);
    assert_eq!(
        error(&text),
        "x.vtu:8: malformed XML: duplicated attribute type"
    );
}

#[test]
fn a_byte_order_mark_cdata_and_escaped_names_read() {
    let plain = read(&square("", "")).unwrap();
    let text = format!("\u{feff}{}", square("", ""))
        .replace(
            ">0 1 2 0 2 3<",
            "><![CDATA[0 1 2]]> <!-- a comment -->0 2 3<",
        )
        .replace("\"connectivity\"", "\"connectivit&#121;\"");
    assert_eq!(read(&text).unwrap(), plain);
}

#[test]
fn arrays_and_group_names_are_bounded() {
    let arrays = r#"<DataArray type="Int8"/>"#.repeat(MAX_ARRAYS + 1);
    assert_eq!(
        error(&square(&arrays, "")),
        "x.vtu:4: more than 131072 <DataArray>s in <FieldData>"
    );
    assert_eq!(
        error(&square("", &arrays)),
        "x.vtu:12: more than 131072 <DataArray>s in <PointData>"
    );
    let names: String = (1..=MAX_GROUPS + 1)
        .map(|i| {
            format!("<DataArray type=\"Int32\" Name=\"g{i}\" format=\"ascii\">{i} 1</DataArray>\n")
        })
        .collect();
    assert_eq!(
        error(&square(&names, "")),
        "x.vtu:65540: more than 65536 group names in <FieldData> (the most verbss reads)"
    );
}

#[test]
fn zlib_values_are_decoded_across_blocks_in_both_byte_orders() {
    let values: [f64; 4] = [1.5, -2.25, 3e300, 4.0];
    for big in [false, true] {
        let bytes: Vec<u8> = values
            .iter()
            .flat_map(|v| {
                if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                }
            })
            .collect();
        // Blocks of 12 bytes: values straddle blocks.
        let blocks: Vec<Vec<u8>> = bytes.chunks(12).map(zlib).collect();
        let mut words: Vec<u32> = vec![3, 12, 8];
        words.extend(blocks.iter().map(|b| b.len() as u32));
        let mut head: Vec<u8> = words
            .iter()
            .flat_map(|w| {
                if big {
                    w.to_be_bytes()
                } else {
                    w.to_le_bytes()
                }
            })
            .collect();
        head.extend(blocks.concat());
        let array = format!(
            r#"<DataArray type="Float64" Name="u" format="binary">{}</DataArray>"#,
            STANDARD.encode(head)
        );
        let mut text = square("", &array);
        if big {
            text = text.replacen("LittleEndian", "BigEndian", 1);
        }
        let read = read(&text).unwrap_or_else(|e| panic!("{big}: {e}"));
        assert_eq!(read.fields.point, vec![("u".into(), 1, values.to_vec())]);
    }
}

#[test]
fn zlib_bombs_are_refused_before_inflating() {
    // Headers claiming 2.6 GB over garbage, in point data and in field data.
    let bomb = binary(&[1, 2_600_000_000, 2_600_000_000, 8], b"garbage!");
    let budget = "DataArray 'u': zlib blocks claiming 2600000000 bytes (2600000000 bytes once \
                  decoded) exceed what is left";
    assert!(error(&square("", &bomb)).contains(budget));
    assert!(error(&square(&bomb, "")).contains(budget));
    // A real 1 MiB block of zeros within the budget: more than the points need.
    let z = zlib(&[0; 1 << 20]);
    let bomb = binary(&[1, 1 << 20, 1 << 20, z.len() as u32], &z);
    assert_eq!(
        error(&square("", &bomb)),
        "x.vtu:12: DataArray 'u': holds more than the 4 tuples that NumberOfPoints=4 needs"
    );
    // A header that understates what its block inflates to.
    let bomb = binary(&[1, 32, 32, z.len() as u32], &z);
    assert_eq!(
        error(&square("", &bomb)),
        "x.vtu:12: DataArray 'u': zlib block 0 inflates to 33 bytes (header says 32)"
    );
}

#[test]
fn a_duplicated_cell_names_the_file() {
    let text = square("", "").replace(">0 1 2 0 2 3<", ">0 1 2 2 0 1<");
    assert_eq!(
        error(&text),
        "x.vtu:5: invalid mesh: elements 1 and 2 have the same nodes (a duplicated element)"
    );
}
