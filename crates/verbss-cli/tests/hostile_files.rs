//! Hostile mesh and case files, built by each test: every one ends with exit
//! 2 and a message naming the file, where in it and what was expected (or
//! with the right result), never with a panic, an abort or a blow-up.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use base64::Engine;

fn verbss(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args(args)
        .output()
        .expect("run verbss")
}

/// Writes `text` as `name` in `dir`.
fn file(dir: &Path, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write the fixture");
    path
}

/// `verbss quality` on `path` fails with exit 2 and a message holding `message`.
fn refused(path: &Path, message: &str) {
    let out = verbss(&["quality", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(message), "expected {message:?} in: {err}");
    assert!(err.contains(&*path.to_string_lossy()), "{err}");
}

/// A unit square of two triangles in VTU, zlib-compressed binary arrays
/// allowed; `point_data`, `cell_data` and `field_data` go in their sections.
fn vtu(point_data: &str, cell_data: &str, field_data: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt32" compressor="vtkZLibDataCompressor">
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
<CellData>{cell_data}</CellData>
</Piece>
</UnstructuredGrid>
</VTKFile>
"#
    )
}

/// A base64 zlib block: header words `words` (UInt32), then `data`.
fn block(words: &[u32], data: &[u8]) -> String {
    let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    bytes.extend(data);
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// A binary Float64 array called `name` holding `block`.
fn binary(name: &str, components: &str, block: &str) -> String {
    format!(
        r#"<DataArray type="Float64" Name="{name}" NumberOfComponents="{components}" format="binary">{block}</DataArray>"#
    )
}

#[test]
fn vtu_reads_back_when_valid() {
    let dir = tempfile::tempdir().unwrap();
    let path = file(dir.path(), "square.vtu", vtu("", "", ""));
    let out = verbss(&["quality", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
}

#[test]
fn vtu_zlib_header_claiming_more_blocks_than_the_data_holds() {
    // 4 blocks claimed in 16 bytes: the block sizes would end past the data.
    let dir = tempfile::tempdir().unwrap();
    let array = binary("u", "1", &block(&[4, 8, 8, 4], &[]));
    let path = file(dir.path(), "blocks.vtu", vtu(&array, "", ""));
    refused(
        &path,
        "blocks.vtu:12: DataArray 'u': truncated: header claims 16 bytes but only 4 remain",
    );
}

#[test]
fn vtu_component_counts_that_overflow_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cell = r#"<DataArray type="Float64" Name="c" NumberOfComponents="9223372036854775808" format="ascii">1 2</DataArray>"#;
    let path = file(dir.path(), "cells.vtu", vtu("", cell, ""));
    refused(
        &path,
        "DataArray 'c': NumberOfComponents=9223372036854775808 cannot match NumberOfCells=2 (too many values)",
    );
    let point = r#"<DataArray type="Float64" Name="p" NumberOfComponents="4611686018427387904" format="ascii">1 2 3 4</DataArray>"#;
    let path = file(dir.path(), "points.vtu", vtu(point, "", ""));
    refused(
        &path,
        "DataArray 'p': NumberOfComponents=4611686018427387904 cannot match NumberOfPoints=4 (too many values)",
    );
}

#[test]
fn vtu_zlib_bombs_are_not_inflated() {
    // Headers claiming 2.6 GB over garbage: refused (or skipped in
    // FieldData) before any inflating, which would report the garbage.
    let dir = tempfile::tempdir().unwrap();
    let bomb = block(&[1, 2_600_000_000, 2_600_000_000, 8], b"garbage!");
    let array = binary("u", "1", &bomb);
    let path = file(dir.path(), "bomb.vtu", vtu(&array, "", ""));
    refused(
        &path,
        "DataArray 'u': holds more than the 4 tuples that NumberOfPoints=4 needs",
    );
    let path = file(dir.path(), "field.vtu", vtu("", "", &array));
    let out = verbss(&["quality", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    // A header that understates what the stream inflates to.
    let mut z = Vec::new();
    {
        use std::io::Write;
        let mut e = flate2::write::ZlibEncoder::new(&mut z, flate2::Compression::best());
        e.write_all(&vec![0u8; 1 << 20]).unwrap();
        e.finish().unwrap();
    }
    let array = binary("u", "1", &block(&[1, 32, 32, z.len() as u32], &z));
    let path = file(dir.path(), "under.vtu", vtu(&array, "", ""));
    refused(
        &path,
        "DataArray 'u': zlib block 0 inflates to 33 bytes (header says 32)",
    );
}

#[test]
fn vtu_nesting_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let deep = format!("{}{}", "<a>".repeat(200_000), "</a>".repeat(200_000));
    let path = file(dir.path(), "deep.vtu", vtu("", "", &deep));
    refused(&path, "deep.vtu:4: elements nested more than 64 deep");
}

/// The unit square in SU2, groups `left` (x = 0) and `rest`.
const SQUARE: &str = "NDIME= 2
NELEM= 2
5 0 1 2
5 0 2 3
NPOIN= 4
0 0
1 0
1 1
0 1
NMARK= 2
MARKER_TAG= left
MARKER_ELEMS= 1
3 3 0
MARKER_TAG= rest
MARKER_ELEMS= 3
3 0 1
3 1 2
3 2 3
";

#[test]
fn case_step_pattern_width_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    file(dir.path(), "square.su2", SQUARE);
    let case = file(
        dir.path(),
        "case.toml",
        "mesh = \"square.su2\"\nsteps = 2\n\n[[motion]]\nkind = \"positions\"\ngroups = [\"rest\"]\nfiles = \"p_{step:0100000}.dat\"\n",
    );
    let out = verbss(&["run", case.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("case.toml:4: invalid setting: the file pattern")
            && err.contains("asks for 100000 digits (at most 20)"),
        "{err}"
    );
}
