//! The peak resident memory of `verbss quality` on the hostile files that
//! cost the most: each child's own (`wait4`), below 512 MiB. The figures are
//! printed (`--nocapture`) for docs/reliability.md.
//!
//! A child's peak starts from this process's own peak (Linux keeps it across
//! `fork` and `exec`): the large fixtures are written piece by piece, so that
//! this process stays small, and the run of `verbss --version` printed last
//! shows how much of each figure is this process's.

use std::io::Write;
use std::path::{Path, PathBuf};

mod hostile;

use hostile::{binary, block, file, msh_with_tags, quality, su2_with_markers, vtu, VTU_POINTS};

/// Writes `head`, `body` `count` times, then `tail` as `name` in `dir`.
fn repeated(dir: &Path, name: &str, head: &str, body: &str, count: usize, tail: &str) -> PathBuf {
    let path = dir.join(name);
    let mut w = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
    w.write_all(head.as_bytes()).unwrap();
    for _ in 0..count {
        w.write_all(body.as_bytes()).unwrap();
    }
    w.write_all(tail.as_bytes()).unwrap();
    w.flush().unwrap();
    path
}

/// The most a hostile file may make `verbss` hold.
const LIMIT_KIB: i64 = 512 * 1024;

#[test]
fn the_worst_hostile_files_stay_under_512_mib() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Points at the origin in zlib blocks of 196,608 zeros, as many as the
    // file's budget for zlib data allows (64 MiB of values plus 64 times
    // its 90 KB): read.
    let blocks = 309;
    let z = hostile::zeros_zlib(196_608);
    let mut words = vec![blocks, 196_608, 196_608];
    words.extend(std::iter::repeat_n(z.len() as u32, blocks as usize));
    let points = binary("p", "3", &block(&words, &z.repeat(blocks as usize)));
    let bomb = vtu("", "", "").replace(VTU_POINTS, &points).replace(
        "NumberOfPoints=\"4\"",
        &format!("NumberOfPoints=\"{}\"", blocks * 196_608 / 24),
    );
    // 48 MB of "0 0" points: the most memory per byte of any reader.
    let head = "NDIME= 2\nNELEM= 1\n5 0 1 2\nNPOIN= 12000000\n";
    let dense = repeated(d, "dense.su2", head, "0 0\n", 12_000_000, "");
    // 48 MB of ascii values cut by comments (a text range each).
    let around = vtu(
        "<DataArray type=\"Int64\" Name=\"u\" format=\"ascii\">|</DataArray>",
        "",
        "",
    );
    let (head, tail) = around.split_once('|').unwrap();
    let comments = repeated(d, "comments.vtu", head, "1<!---->", 6_000_000, tail);
    // 48 MB of ascii VTU points at the origin, one triangle: read.
    let around = vtu("", "", "")
        .replace(
            VTU_POINTS,
            "<DataArray type=\"Float64\" NumberOfComponents=\"3\">|</DataArray>",
        )
        .replace("NumberOfPoints=\"4\"", "NumberOfPoints=\"8000000\"");
    let (head, tail) = around.split_once('|').unwrap();
    let points = repeated(d, "points.vtu", head, "0 0 0 ", 8_000_000, tail);
    // 48 MB of MSH 2.2 nodes (tags of 7 digits), one triangle: read.
    let head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2700000\n";
    let tail = "$EndNodes\n$Elements\n1\n1 2 0 1000000 1000001 1001000\n$EndElements\n";
    let nodes = {
        let path = d.join("nodes.msh");
        let mut w = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        w.write_all(head.as_bytes()).unwrap();
        for k in 0..2_700_000 {
            writeln!(w, "{} {} {} 0", 1_000_000 + k, k % 1000, k / 1000).unwrap();
        }
        w.write_all(tail.as_bytes()).unwrap();
        w.flush().unwrap();
        path
    };
    let gmsh_groups = {
        let n = 65_536;
        let mut s = format!(
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n\
             $EndNodes\n$Elements\n{}\n1 2 2 0 1 1 2 3\n",
            n + 1
        );
        for k in 0..n {
            s += &format!("{} 1 2 {} 1 1 2\n", k + 2, k + 1);
        }
        s + "$EndElements\n"
    };
    let fixtures = [
        file(d, "budget.vtu", bomb),
        dense,
        points,
        nodes,
        comments,
        file(
            d,
            "arrays.vtu",
            vtu("", "", &"<DataArray type=\"Int8\"/>".repeat(131_072)),
        ),
        file(d, "markers.su2", su2_with_markers(65_536)),
        file(d, "groups.msh", gmsh_groups),
        file(d, "tags.msh", msh_with_tags(60_000, 20_000)),
    ];
    println!("| file | bytes | exit | peak RSS (MiB) | seconds |");
    for f in &fixtures {
        let start = std::time::Instant::now();
        let r = quality(f);
        let name = f.file_name().unwrap().to_string_lossy();
        println!(
            "| {name} | {} | {:?} | {:.0} | {:.2} |",
            std::fs::metadata(f).unwrap().len(),
            r.code,
            r.peak_kib as f64 / 1024.0,
            start.elapsed().as_secs_f64()
        );
        assert!(matches!(r.code, Some(0 | 2)), "{name}: {}", r.stderr);
        assert!(r.peak_kib < LIMIT_KIB, "{name}: {} KiB", r.peak_kib);
    }
    let own = hostile::run(&["--version"]).peak_kib;
    println!("`verbss --version`: {:.0} MiB", own as f64 / 1024.0);
}
