//! Hostile mesh and case files, built by each test: every one ends with exit
//! 2 and a message naming the file, where in it and what was expected (or
//! with the right result), never with a panic, an abort or a blow-up.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{verbss, SQUARE};

use base64::Engine;

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

/// `verbss quality` on `path` in a child killed after 30 s.
fn quality_within_30_s(path: &Path) -> (Option<i32>, String) {
    within_30_s(&["quality", path.to_str().unwrap()])
}

/// `verbss ARGS` in a child killed after 30 s (a hang fails the test
/// instead of stalling the suite): the exit code and stderr.
fn within_30_s(args: &[&str]) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run verbss");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
    while child.try_wait().expect("wait").is_none() {
        if std::time::Instant::now() > deadline {
            child.kill().expect("kill");
            panic!("verbss {args:?} still running after 30 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().expect("output");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// An MSH 4.1 unit square: its lines, `lines` of them, on a curve with
/// physical tags 1..=`tags`.
fn msh_with_tags(lines: usize, tags: usize) -> String {
    let tag_list: Vec<String> = (1..=tags).map(|t| t.to_string()).collect();
    let mut s = format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 1 1 0\n1 0 0 0 1 0 0 {tags} {} 0\n\
         1 0 0 0 1 1 0 0 0\n$EndEntities\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n\
         1 1 0\n0 1 0\n$EndNodes\n$Elements\n2 {} 1 {}\n1 1 1 {lines}\n",
        tag_list.join(" "),
        lines + 2,
        lines + 2
    );
    for e in 1..=lines {
        s += &format!("{e} 1 2\n");
    }
    s += &format!(
        "2 1 2 2\n{} 1 2 3\n{} 1 3 4\n$EndElements\n",
        lines + 1,
        lines + 2
    );
    s
}

#[test]
fn msh_physical_tags_do_not_multiply_elements() {
    let dir = tempfile::tempdir().unwrap();
    let path = file(dir.path(), "few.msh", msh_with_tags(3, 2));
    assert_eq!(quality_within_30_s(&path).0, Some(0));
    let path = file(dir.path(), "tags.msh", msh_with_tags(1000, 20_000));
    let (code, err) = quality_within_30_s(&path);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("tags.msh:")
            && err.contains("the physical groups would hold 20000000 elements, more than 1056576"),
        "{err}"
    );
}

#[test]
fn msh_unknown_section_search_is_linear() {
    // Closing keyword `$End$End…$End!`, text `$End$End…`: a window-by-window
    // search compares 4,000 bytes at each of 1,000,000 places.
    let dir = tempfile::tempdir().unwrap();
    let name = format!("{}!", "$End".repeat(1000));
    let text = format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n${name}\n{}\n",
        "$End".repeat(1_000_000)
    );
    let path = file(dir.path(), "section.msh", text);
    let (code, err) = quality_within_30_s(&path);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("section.msh:4: unexpected end of file: no $End$End"),
        "{err}"
    );
}

#[test]
fn su2_many_markers_parse_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let n = 300_000;
    let mut text = format!("{}NMARK= {n}\n", &SQUARE[..SQUARE.find("NMARK").unwrap()]);
    for i in 0..n {
        text += &format!("MARKER_TAG= m{i}\nMARKER_ELEMS= 1\n3 0 1\n");
    }
    let path = file(dir.path(), "markers.su2", text);
    assert_eq!(quality_within_30_s(&path).0, Some(0));
}

#[test]
fn vtu_many_attributes_parse_in_linear_time() {
    let dir = tempfile::tempdir().unwrap();
    let attrs: String = (0..200_000).map(|i| format!(" a{i}=\"{i}\"")).collect();
    let text = vtu("", "", "").replacen("<VTKFile ", &format!("<VTKFile{attrs} "), 1);
    let path = file(dir.path(), "attrs.vtu", text);
    assert_eq!(quality_within_30_s(&path).0, Some(0));
    let text = vtu("", "", "").replacen("<VTKFile ", "<VTKFile a=\"1\" a=\"2\" ", 1);
    let path = file(dir.path(), "twice.vtu", text);
    let (code, err) = quality_within_30_s(&path);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("twice.vtu:2: malformed XML: duplicated attribute a"),
        "{err}"
    );
}

#[test]
fn vtu_many_group_names_parse_in_linear_time() {
    // 100,000 FieldData names and 100,000 facets naming the last one.
    let dir = tempfile::tempdir().unwrap();
    let n = 100_000;
    let names: String = (1..=n)
        .map(|i| {
            format!("<DataArray type=\"Int32\" Name=\"g{i}\" format=\"ascii\">{i} 1</DataArray>\n")
        })
        .collect();
    let lines = " 0 1".repeat(n);
    let offsets: String = (0..n).map(|i| format!(" {}", 8 + 2 * i)).collect();
    let text = vtu("", "", &names)
        .replace(
            "NumberOfCells=\"2\"",
            &format!("NumberOfCells=\"{}\"", n + 2),
        )
        .replace(">0 1 2 0 2 3<", &format!(">0 1 2 0 2 3{lines}<"))
        .replace(">3 6<", &format!(">3 6{offsets}<"))
        .replace(">5 5<", &format!(">5 5{}<", " 3".repeat(n)))
        .replace(
            "<CellData>",
            &format!(
                "<CellData><DataArray type=\"Int32\" Name=\"group\" format=\"ascii\">0 0{}</DataArray>",
                format!(" {n}").repeat(n)
            ),
        );
    let path = file(dir.path(), "names.vtu", text);
    let (code, err) = quality_within_30_s(&path);
    assert_eq!(code, Some(0), "{err}");
}

#[test]
fn render_windows_are_clipped_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    let naca = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/su2/mesh_NACA0012_inv.su2"
    );
    let png = dir.path().join("z.png");
    let png = png.to_str().unwrap();
    // Trailing-edge zooms: edges far longer than the window are clipped.
    for view in ["0.9999999,1.0000001,-1e-7,1e-7", "0,1e-300,0,1e-300"] {
        let view = format!("--view={view}");
        let (code, err) = within_30_s(&["render", naca, "-o", png, &view]);
        assert_eq!(code, Some(0), "{view}: {err}");
    }
    let (code, err) = within_30_s(&[
        "render",
        naca,
        "-o",
        png,
        "--view=-1e308,1e308,-1e308,1e308",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("expected finite x0 < x1 and y0 < y1 (with finite x1 - x0 and y1 - y0)"),
        "{err}"
    );
    let (code, err) = within_30_s(&["render", naca, "-o", png, "--view=1,1.000000000000001,0,1"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("above 1e-12 of the coordinates"), "{err}");
    let (code, err) = within_30_s(&["render", naca, "-o", png, "--azimuth", "NaN"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("'NaN' is not a finite angle in degrees"),
        "{err}"
    );
}

#[test]
fn gif_of_a_3d_mesh_has_one_frame_size_and_is_renamed_into_place() {
    let dir = tempfile::tempdir().unwrap();
    let brick = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/su2/mesh_brick_tets_ffd.su2"
    );
    let out = dir.path().join("moved.su2");
    let gif = dir.path().join("moved.gif");
    let o = verbss(&[
        "deform",
        brick,
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "x_p",
        "--translate",
        "0.2,0,0.05",
        "--steps",
        "3",
        "--gif",
        gif.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.exists());
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(&gif).unwrap())
        .unwrap();
    let mut sizes = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        sizes.push((frame.width, frame.height));
    }
    assert_eq!(sizes.len(), 4, "{sizes:?}");
    assert!(sizes.iter().all(|s| *s == sizes[0]), "{sizes:?}");
    // No temporary file is left beside the outputs.
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["moved.gif", "moved.su2"]);
}

#[test]
fn a_gif_that_cannot_be_written_does_not_cost_the_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let square = file(dir.path(), "square.su2", SQUARE);
    let blocker = file(dir.path(), "blocker", "a regular file");
    let out = dir.path().join("moved.su2");
    let gif = blocker.join("moved.gif");
    let o = verbss(&[
        "deform",
        square.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "rest",
        "--translate",
        "0.01,0",
        "--gif",
        gif.to_str().unwrap(),
        "--quiet",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("warning: no GIF: cannot create the folder"),
        "{err}"
    );
    assert!(out.exists());
}

#[test]
fn vtu_output_refuses_tags_it_cannot_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let t = 1u64 << 63;
    let msh = format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 {t} {}\n2 1 0 4\n{t}\n{}\n{}\n{}\n\
         0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n$Elements\n1 2 1 2\n2 1 2 2\n1 {t} {} {}\n\
         2 {t} {} {}\n$EndElements\n",
        t + 3,
        t + 1,
        t + 2,
        t + 3,
        t + 1,
        t + 2,
        t + 2,
        t + 3
    );
    let input = file(dir.path(), "big.msh", msh);
    let out = dir.path().join("big.vtu");
    let o = verbss(&["convert", input.to_str().unwrap(), out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("big.vtu: node tag 9223372036854775808 is above 9223372036854775807 (VTU tags are Int64)"),
        "{err}"
    );
    assert!(!out.exists());
}

/// The zlib stream of `n` zero bytes.
fn zeros_zlib(n: usize) -> Vec<u8> {
    use std::io::Write;
    let mut z = Vec::new();
    let mut e = flate2::write::ZlibEncoder::new(&mut z, flate2::Compression::best());
    e.write_all(&vec![0u8; n]).unwrap();
    e.finish().unwrap();
    z
}

#[test]
fn the_worst_hostile_files_stay_under_512_mb() {
    // Real zlib bombs (64 MB of zeros in 64 KB, honest headers) in Points,
    // PointData and FieldData, and the largest parse fixtures above: the
    // peak resident memory of every child this test binary ran.
    let dir = tempfile::tempdir().unwrap();
    let n = 64 << 20;
    let z = zeros_zlib(n);
    let bomb = binary(
        "u",
        "1",
        &block(&[1, n as u32, n as u32, z.len() as u32], &z),
    );
    let points = vtu("", "", "").replace(
        r#"<DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 1 1 0 0 1 0</DataArray>"#,
        &bomb.replace(r#"NumberOfComponents="1""#, r#"NumberOfComponents="3""#),
    );
    let fixtures = [
        file(dir.path(), "points.vtu", points),
        file(dir.path(), "pointdata.vtu", vtu(&bomb, "", "")),
        file(dir.path(), "fielddata.vtu", vtu("", "", &bomb)),
        file(dir.path(), "tags.msh", msh_with_tags(1000, 20_000)),
    ];
    for f in &fixtures {
        let (code, err) = quality_within_30_s(f);
        assert!(matches!(code, Some(0 | 2)), "{}: {err}", f.display());
    }
    // SAFETY: getrusage only writes the struct it is given.
    let peak_kb = unsafe {
        let mut usage: libc::rusage = std::mem::zeroed();
        assert_eq!(libc::getrusage(libc::RUSAGE_CHILDREN, &mut usage), 0);
        usage.ru_maxrss
    };
    println!("peak resident memory of the children: {peak_kb} KB");
    assert!(peak_kb < 512 * 1024, "{peak_kb} KB");
}
