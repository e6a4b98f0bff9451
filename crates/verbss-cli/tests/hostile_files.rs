//! Hostile mesh and case files, built by each test: every one ends with exit
//! 2 and a message naming the file, where in it and what was expected (or
//! with the right result), never with a panic, an abort or a blow-up. The
//! peak memory of the worst of them is measured in `hostile_memory.rs`.

mod common;
mod hostile;

use common::{verbss, SQUARE};
use hostile::{
    binary, block, file, msh_with_tags, read, refused, run, su2_with_markers, vtu, zeros_zlib,
    VTU_POINTS,
};

#[test]
fn vtu_reads_back_when_valid() {
    let dir = tempfile::tempdir().unwrap();
    read(&file(dir.path(), "square.vtu", vtu("", "", "")));
}

#[test]
fn vtu_zlib_header_claiming_more_blocks_than_the_data_holds() {
    // Issue 23, 1: 4 blocks claimed in 16 bytes; the sizes would end past the data.
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
    // Issue 23, 2: 2^63 components in CellData, 2^62 in PointData.
    let dir = tempfile::tempdir().unwrap();
    let cell = r#"<DataArray type="Float64" Name="c" NumberOfComponents="9223372036854775808" format="ascii">1 2</DataArray>"#;
    let path = file(dir.path(), "cells.vtu", vtu("", cell, ""));
    refused(
        &path,
        "cells.vtu:13: DataArray 'c': NumberOfComponents=9223372036854775808 cannot match NumberOfCells=2 (too many values)",
    );
    let point = r#"<DataArray type="Float64" Name="p" NumberOfComponents="4611686018427387904" format="ascii">1 2 3 4</DataArray>"#;
    let path = file(dir.path(), "points.vtu", vtu(point, "", ""));
    refused(
        &path,
        "points.vtu:12: DataArray 'p': NumberOfComponents=4611686018427387904 cannot match NumberOfPoints=4 (too many values)",
    );
}

#[test]
fn vtu_nesting_is_bounded() {
    // Issue 23, 4: 200,000 nested elements.
    let dir = tempfile::tempdir().unwrap();
    let deep = format!("{}{}", "<a>".repeat(200_000), "</a>".repeat(200_000));
    let path = file(dir.path(), "deep.vtu", vtu("", "", &deep));
    refused(&path, "deep.vtu:4: elements nested more than 64 deep");
}

#[test]
fn vtu_zlib_bombs_are_refused_before_inflating() {
    // Issue 23, 5. Headers claiming 2.6 GB over garbage, in PointData and in
    // FieldData: refused before any inflating (which would report the garbage).
    let dir = tempfile::tempdir().unwrap();
    let budget = "DataArray 'u': zlib blocks claiming 2600000000 bytes (2600000000 bytes once \
                  decoded) exceed what is left";
    let bomb = binary(
        "u",
        "1",
        &block(&[1, 2_600_000_000, 2_600_000_000, 8], b"garbage!"),
    );
    let path = file(dir.path(), "bomb.vtu", vtu(&bomb, "", ""));
    refused(&path, &format!("bomb.vtu:12: {budget}"));
    let path = file(dir.path(), "field.vtu", vtu("", "", &bomb));
    refused(&path, &format!("field.vtu:4: {budget}"));
    // A real one: 40,000 blocks of 65,536 zeros (2.6 GB in 3.3 MB), honest headers.
    let z = zeros_zlib(1 << 16);
    let mut words = vec![40_000, 1 << 16, 1 << 16];
    words.extend(std::iter::repeat_n(z.len() as u32, 40_000));
    let real = binary("u", "1", &block(&words, &z.repeat(40_000)));
    let path = file(dir.path(), "real.vtu", vtu(&real, "", ""));
    refused(
        &path,
        "real.vtu:12: DataArray 'u': zlib blocks claiming 2621440000 bytes",
    );
    // A block header of 4 GB for one-byte values (32 GB once decoded).
    let bytes =
        binary("u", "1", &block(&[1, 0, 0xFFFF_FFF0, 8], b"garbage!")).replace("Float64", "UInt8");
    let path = file(dir.path(), "bytes.vtu", vtu(&bytes, "", ""));
    refused(
        &path,
        "bytes.vtu:12: DataArray 'u': zlib blocks claiming 4294967280 bytes (34359738240 bytes once decoded)",
    );
    // Counts that the data backs: 10,000,000 points at the origin in 300 KB.
    let n = 10_000_000;
    let z = zeros_zlib(24 << 16);
    let mut words = vec![n / (1 << 16), 24 << 16, 24 << 16];
    words.extend(std::iter::repeat_n(z.len() as u32, n as usize >> 16));
    let points = binary("p", "3", &block(&words, &z.repeat(n as usize >> 16)));
    let text = vtu("", "", "").replace(VTU_POINTS, &points).replace(
        "NumberOfPoints=\"4\"",
        &format!("NumberOfPoints=\"{}\"", n >> 16 << 16),
    );
    let path = file(dir.path(), "points.vtu", text);
    refused(
        &path,
        "points.vtu:6: DataArray 'p': zlib blocks claiming 239075328 bytes",
    );
    // A header that understates what its block inflates to.
    let z = zeros_zlib(1 << 20);
    let array = binary("u", "1", &block(&[1, 32, 32, z.len() as u32], &z));
    let path = file(dir.path(), "under.vtu", vtu(&array, "", ""));
    refused(
        &path,
        "under.vtu:12: DataArray 'u': zlib block 0 inflates to 33 bytes (header says 32)",
    );
}

#[test]
fn msh_physical_tags_do_not_multiply_elements() {
    // Issue 23, 6: 20,000 physical tags on one curve (705 KB with 60,000 lines).
    let dir = tempfile::tempdir().unwrap();
    read(&file(dir.path(), "few.msh", msh_with_tags(3, 2)));
    let path = file(dir.path(), "tags.msh", msh_with_tags(60_000, 20_000));
    refused(
        &path,
        "tags.msh:60028: the physical groups would hold 1200000000 elements, more than 1528576",
    );
}

#[test]
fn vtu_many_attributes_parse_in_linear_time() {
    // Issue 23, 7: 400,000 attributes on <VTKFile> (4.7 MB).
    let dir = tempfile::tempdir().unwrap();
    let attrs: String = (0..400_000).map(|i| format!(" a{i}=\"{i}\"")).collect();
    let text = vtu("", "", "").replacen("<VTKFile ", &format!("<VTKFile{attrs} "), 1);
    read(&file(dir.path(), "attrs.vtu", text));
    let text = vtu("", "", "").replacen("<VTKFile ", "<VTKFile type=\"a\" ", 1);
    refused(
        &file(dir.path(), "twice.vtu", text),
        "twice.vtu:2: malformed XML: duplicated attribute type",
    );
}

#[test]
fn msh_unknown_section_search_is_linear() {
    // Issue 23, 7: an unknown section `$` before a million `$End`s (4 MB),
    // and one whose closing keyword `$End$End…$End!` is 4 KB long.
    let dir = tempfile::tempdir().unwrap();
    let ends = "$End".repeat(1_000_000);
    let text = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$\n{ends}\n");
    refused(
        &file(dir.path(), "dollar.msh", text),
        "dollar.msh:4: expected a section header such as $Nodes, found '$'",
    );
    let text = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$$\n{ends}\n");
    refused(
        &file(dir.path(), "dollars.msh", text),
        "dollars.msh:5: expected a section header such as $Nodes, found 'End$End$End$End$End$End$...'",
    );
    let name = format!("{}!", "$End".repeat(1000));
    let text = format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n${name}\n{ends}\n");
    refused(
        &file(dir.path(), "section.msh", text),
        "section.msh:4: unexpected end of file: no $End$End",
    );
}

#[test]
fn su2_markers_are_bounded() {
    // Issue 23, 7: 400,000 MARKER_TAGs (14 MB): refused at NMARK=; 65,536 read.
    let dir = tempfile::tempdir().unwrap();
    refused(
        &file(dir.path(), "many.su2", su2_with_markers(400_000)),
        "many.su2:10: NMARK= 400000 is more than 65536 markers (the most verbss reads)",
    );
    read(&file(dir.path(), "most.su2", su2_with_markers(65_536)));
}

/// A VTU file with `n` FieldData group names and `n` facets in the last group.
fn vtu_with_names(n: usize) -> String {
    let names: String = (1..=n)
        .map(|i| {
            format!("<DataArray type=\"Int32\" Name=\"g{i}\" format=\"ascii\">{i} 1</DataArray>\n")
        })
        .collect();
    let offsets: String = (0..n).map(|i| format!(" {}", 8 + 2 * i)).collect();
    vtu("", "", &names)
        .replace(
            "NumberOfCells=\"2\"",
            &format!("NumberOfCells=\"{}\"", n + 2),
        )
        .replace(">0 1 2 0 2 3<", &format!(">0 1 2 0 2 3{}<", " 0 1".repeat(n)))
        .replace(">3 6<", &format!(">3 6{offsets}<"))
        .replace(">5 5<", &format!(">5 5{}<", " 3".repeat(n)))
        .replace(
            "<CellData>",
            &format!(
                "<CellData><DataArray type=\"Int32\" Name=\"group\" format=\"ascii\">0 0{}</DataArray>",
                format!(" {n}").repeat(n)
            ),
        )
}

#[test]
fn vtu_group_names_are_bounded() {
    // Issue 23, 7: 300,000 FieldData names and facets naming the last (34 MB).
    let dir = tempfile::tempdir().unwrap();
    refused(
        &file(dir.path(), "names.vtu", vtu_with_names(300_000)),
        "names.vtu:131076: more than 131072 <DataArray>s in <FieldData>",
    );
    read(&file(dir.path(), "most.vtu", vtu_with_names(65_536)));
}

#[test]
fn a_duplicated_element_is_refused_by_every_reader() {
    // Issue 23, 16.
    let dir = tempfile::tempdir().unwrap();
    let twice = "invalid mesh: elements 1 and 2 have the same nodes (a duplicated element)";
    let text = SQUARE.replace("5 0 2 3", "5 2 0 1");
    refused(
        &file(dir.path(), "twice.su2", text),
        &format!("twice.su2:2: {twice}"),
    );
    let text = vtu("", "", "").replace(">0 1 2 0 2 3<", ">0 1 2 1 2 0<");
    refused(
        &file(dir.path(), "twice.vtu", text),
        &format!("twice.vtu:5: {twice}"),
    );
    let text = msh_with_tags(1, 1).replace("3 1 3 4\n", "3 3 2 1\n");
    refused(
        &file(dir.path(), "twice.msh", text),
        "twice.msh:21: invalid mesh: elements 2 and 3 have the same nodes",
    );
}

#[test]
fn msh_element_tags_at_the_top_convert_to_a_readable_msh() {
    // Found by fuzzing: the facets' fresh tags wrapped to 0 past u64::MAX.
    let dir = tempfile::tempdir().unwrap();
    let text = msh_with_tags(1, 1)
        .replace("\n2 1 2 3\n", "\n18446744073709551614 1 2 3\n")
        .replace("\n3 1 3 4\n", "\n18446744073709551615 1 3 4\n");
    let input = file(dir.path(), "top.msh", text);
    let out = dir.path().join("out.msh");
    let r = run(&["convert", input.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    read(&out);
}

#[test]
fn case_step_patterns_are_checked() {
    // Issue 23, 3, and other patterns the step number cannot fill.
    let dir = tempfile::tempdir().unwrap();
    file(dir.path(), "square.su2", SQUARE);
    for (pattern, message) in [
        (
            "p_{step:0100000}.dat",
            "asks for 100000 digits (at most 20)",
        ),
        (
            "p_{step:099999999999999999999999}.dat",
            "asks for 99999999999999999999999 digits (at most 20)",
        ),
        (
            "p_{step:x}.dat",
            "has \"{step:x}.dat…\" (expected {step} or {step:0W}, W the number of digits)",
        ),
    ] {
        let case = file(
            dir.path(),
            "case.toml",
            format!("mesh = \"square.su2\"\nsteps = 2\n\n[[motion]]\nkind = \"positions\"\ngroups = [\"rest\"]\nfiles = \"{pattern}\"\n"),
        );
        let r = run(&["run", case.to_str().unwrap()]);
        assert_eq!(r.code, Some(2), "{}", r.stderr);
        // The pattern is quoted joined to the case file's folder.
        let expected = format!("{pattern}\" {message}");
        let start = "case.toml:4: invalid setting: the file pattern \"";
        assert!(
            r.stderr.contains(start) && r.stderr.contains(&expected),
            "{expected} in {}",
            r.stderr
        );
    }
}

#[test]
fn case_files_are_small() {
    let dir = tempfile::tempdir().unwrap();
    let keys: String = (0..100_000).map(|k| format!("k{k} = 1\n")).collect();
    let case = file(
        dir.path(),
        "big.toml",
        format!("mesh = \"square.su2\"\n{keys}"),
    );
    let r = run(&["run", case.to_str().unwrap()]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    let size = std::fs::metadata(&case).unwrap().len();
    let expected = format!("big.toml:1: the case file is {size} bytes (at most 1048576)");
    assert!(r.stderr.contains(&expected), "{}", r.stderr);
}

#[test]
fn byte_order_marks_are_skipped() {
    let dir = tempfile::tempdir().unwrap();
    read(&file(dir.path(), "bom.su2", format!("\u{feff}{SQUARE}")));
    read(&file(
        dir.path(),
        "bom.vtu",
        format!("\u{feff}{}", vtu("", "", "")),
    ));
    read(&file(
        dir.path(),
        "bom.msh",
        format!("\u{feff}{}", msh_with_tags(1, 1)),
    ));
}

/// A binary MSH 2.2 unit square (two triangles), `edit`ed before it is cut
/// to `len` bytes.
fn binary_msh(edit: impl Fn(&mut Vec<u8>), len: Option<usize>) -> Vec<u8> {
    let int = |v: i32| v.to_le_bytes();
    let mut b = b"$MeshFormat\n2.2 1 8\n".to_vec();
    b.extend(int(1));
    b.extend(b"\n$EndMeshFormat\n$Nodes\n4\n");
    for (i, (x, y)) in [(0., 0.), (1., 0.), (1., 1.), (0., 1.)]
        .into_iter()
        .enumerate()
    {
        b.extend(int(i as i32 + 1));
        for v in [x, y, 0.0f64] {
            b.extend(v.to_le_bytes());
        }
    }
    b.extend(b"\n$EndNodes\n$Elements\n2\n");
    for v in [2, 2, 2, 1, 1, 1, 1, 2, 3, 2, 1, 1, 1, 3, 4] {
        b.extend(int(v));
    }
    b.extend(b"\n$EndElements\n");
    edit(&mut b);
    b.truncate(len.unwrap_or(b.len()));
    b
}

#[test]
fn every_reader_names_the_place_of_what_is_wrong() {
    let dir = tempfile::tempdir().unwrap();
    let msh = msh_with_tags(1, 1);
    let square = vtu("", "", "");
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "nan.su2",
            SQUARE.replace("1 1\n", "nan 1\n").into(),
            "nan.su2:8: non-finite coordinate 'nan'",
        ),
        (
            "big.su2",
            SQUARE.replace("1 1\n", "1e400 1\n").into(),
            "big.su2:8: non-finite coordinate '1e400'",
        ),
        (
            "neg.su2",
            SQUARE.replace("NELEM= 2", "NELEM= -2").into(),
            "neg.su2:2: expected a count after NELEM=, found '-2'",
        ),
        (
            "huge.su2",
            SQUARE
                .replace("NELEM= 2", "NELEM= 18446744073709551615")
                .into(),
            "huge.su2:5: found NPOIN= after 2 of the 18446744073709551615 elements",
        ),
        (
            "node.su2",
            SQUARE.replace("5 0 2 3", "5 0 2 9").into(),
            "node.su2:4: node index 9 out of range (NPOIN= 4 at line 5: indices 0 to 3)",
        ),
        (
            "zones.su2",
            format!("NZONE= 2\nIZONE= 1\n{SQUARE}IZONE= 3\n{SQUARE}").into(),
            "zones.su2:21: IZONE= 3 out of order (expected IZONE= 2)",
        ),
        (
            "bin.su2",
            b"NDIME= 2\n\x00\xff\xfe".to_vec(),
            "bin.su2:2: non-UTF-8 byte 0xff at column 2",
        ),
        (
            "nan.msh",
            msh.replace("\n1 1 0\n0 1 0\n", "\nnan 1 0\n0 1 0\n").into(),
            "nan.msh:18: node 3 has a non-finite coordinate (NaN)",
        ),
        (
            "node.msh",
            msh.replace("3 1 3 4\n", "3 1 3 9\n").into(),
            "node.msh:27: element 3 refers to node 9, which $Nodes does not define",
        ),
        (
            "count.msh",
            msh.replace("1 4 1 4\n", "1 18446744073709551615 1 4\n")
                .into(),
            "count.msh:19: $Nodes declares 18446744073709551615 nodes but its blocks hold 4",
        ),
        (
            "order.msh",
            msh.replace("$Nodes", "$Elements\n$EndElements\n$Nodes")
                .into(),
            "order.msh:9: $Elements comes before $Nodes",
        ),
        (
            "version.msh",
            msh.replace("4.1 0 8", "4.0 0 8").into(),
            "version.msh:2: unsupported MSH version 4.0",
        ),
        (
            "cut.msh",
            binary_msh(|_| {}, Some(120)),
            "cut.msh: byte 49: unexpected end of file: $Nodes needs 112 bytes, only 71 remain",
        ),
        (
            "endian.msh",
            binary_msh(|b| b[20..24].copy_from_slice(&1i32.to_be_bytes()), None),
            "endian.msh: byte 20: the binary file is big-endian",
        ),
        (
            "tags.msh",
            binary_msh(
                |b| b[192..196].copy_from_slice(&(-5i32).to_le_bytes()),
                None,
            ),
            "tags.msh: byte 192: negative number of tags -5",
        ),
        (
            "nan.vtu",
            square
                .replace("0 0 0 1 0 0 1 1 0", "0 0 0 nan 0 0 1 1 0")
                .into(),
            "nan.vtu:6: DataArray '': point 1 has a non-finite coordinate (NaN)",
        ),
        (
            "node.vtu",
            square.replace("0 1 2 0 2 3", "0 1 2 0 2 -1").into(),
            "node.vtu:8: DataArray 'connectivity': cell 1 uses point -1 but NumberOfPoints=4",
        ),
        (
            "cells.vtu",
            square
                .replace(
                    "NumberOfCells=\"2\"",
                    "NumberOfCells=\"18446744073709551615\"",
                )
                .into(),
            "cells.vtu:9: DataArray 'offsets': 2 values but NumberOfCells=18446744073709551615",
        ),
        (
            "pieces.vtu",
            square.replace("</Piece>", "</Piece><Piece/>").into(),
            "pieces.vtu:14: a second <Piece> (only single-piece files are supported)",
        ),
        (
            "cut.vtu",
            square[..square.len() / 2].into(),
            "cut.vtu:6: truncated file",
        ),
        (
            "b64.vtu",
            vtu(&binary("u", "1", "@@@@"), "", "").into(),
            "b64.vtu:12: DataArray 'u': invalid base64 character '@' at position 0",
        ),
        (
            "zlib.vtu",
            vtu(
                &binary("u", "1", &block(&[1, 8, 8, 4], b"\x78\x9c\xff\xff")),
                "",
                "",
            )
            .into(),
            "zlib.vtu:12: DataArray 'u': zlib block 0:",
        ),
        ("empty.vtu", Vec::new(), "empty.vtu:1: not a VTK XML file"),
    ];
    for (name, text, message) in cases {
        refused(&file(dir.path(), name, text), message);
    }
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
        let r = run(&["render", naca, "-o", png, &view]);
        assert_eq!(r.code, Some(0), "{view}: {}", r.stderr);
    }
    let r = run(&[
        "render",
        naca,
        "-o",
        png,
        "--view=-1e308,1e308,-1e308,1e308",
    ]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr
            .contains("expected finite x0 < x1 and y0 < y1 (with finite x1 - x0 and y1 - y0)"),
        "{}",
        r.stderr
    );
    let r = run(&["render", naca, "-o", png, "--view=1,1.000000000000001,0,1"]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains("above 1e-12 of the coordinates"),
        "{}",
        r.stderr
    );
    let r = run(&["render", naca, "-o", png, "--azimuth", "NaN"]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains("'NaN' is not a finite angle in degrees"),
        "{}",
        r.stderr
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
        "{}",
        err
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
        "{}",
        err
    );
    assert!(!out.exists());
}
