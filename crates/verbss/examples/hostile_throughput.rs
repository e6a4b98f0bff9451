//! How fast the readers get through hostile files, at two sizes: a reader
//! linear in the file size takes four times as long on a file four times as
//! large. Each file is made in memory and parsed once per size; the table
//! gives the seconds, the megabytes per second and the result.
//!
//! ```sh
//! cargo run --release -p verbss --example hostile_throughput [-- MB]
//! ```
//! (`MB`: the larger size, 48 by default; the smaller is a quarter of it.)

use std::path::Path;
use std::time::Instant;

use verbss::io::{gmsh, su2, vtu};

/// `body(k)` for k = 0, 1, … until the text reaches `bytes`.
fn repeat(bytes: usize, body: impl Fn(usize) -> String) -> String {
    let mut out = String::with_capacity(bytes + 64);
    let mut k = 0;
    while out.len() < bytes {
        out += &body(k);
        k += 1;
    }
    out
}

/// A VTU unit square of two triangles: `attrs` on `<VTKFile>`, then
/// `field_data` and `point_data` in their sections.
fn square(attrs: &str, field_data: &str, point_data: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0"{attrs}>
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

/// The first line of an outcome, at most 70 characters.
fn outcome<T>(r: verbss::Result<T>) -> String {
    match r {
        Ok(_) => "read".into(),
        Err(e) => format!(
            "error: {}",
            e.to_string().chars().take(70).collect::<String>()
        ),
    }
}

type Make = fn(usize) -> String;
type Parse = fn(&[u8]) -> String;

const MSH: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";

fn main() {
    let mb: usize = std::env::args()
        .nth(1)
        .map_or(48, |a| a.parse().expect("a size in MB"));
    let vtu: Parse = |b| outcome(vtu::parse(b, Path::new("x.vtu")));
    let msh: Parse = |b| outcome(gmsh::parse(b, Path::new("x.msh")));
    let su2: Parse = |b| outcome(su2::parse(b, Path::new("x.su2")));
    let cases: [(&str, Make, Parse); 8] = [
        (
            "VTU: attributes on <VTKFile>",
            |n| square(&repeat(n, |k| format!(" a{k}=\"\"")), "", ""),
            vtu,
        ),
        (
            "VTU: empty unknown elements",
            |n| square("", &"<e/>".repeat(n / 4), ""),
            vtu,
        ),
        (
            "VTU: ascii values cut by comments",
            |n| {
                let values = "1<!---->".repeat(n / 8);
                square(
                    "",
                    "",
                    &format!("<DataArray type=\"Int64\" Name=\"u\">{values}</DataArray>"),
                )
            },
            vtu,
        ),
        (
            "MSH: section `$` before `$End`s",
            |n| format!("{MSH}$\n{}", "$End".repeat(n / 4)),
            msh,
        ),
        (
            "MSH: section never closed",
            |n| format!("{MSH}$Foo\n{}", "$End$EndFo ".repeat(n / 11)),
            msh,
        ),
        (
            "MSH: 2.2 nodes, one triangle",
            |n| {
                let nodes = repeat(n, |k| format!("{} {} {} 0\n", k + 1, k % 1000, k / 1000));
                let count = nodes.lines().count();
                format!("{MSH}$Nodes\n{count}\n{nodes}$EndNodes\n$Elements\n1\n1 2 0 1 2 1001\n$EndElements\n")
            },
            msh,
        ),
        (
            "SU2: unknown sections",
            |n| {
                format!(
                    "NDIME= 2\nNELEM= 1\n5 0 1 2\nNPOIN= 3\n0 0\n1 0\n0 1\n{}",
                    "X= 1\n1 2\n".repeat(n / 10)
                )
            },
            su2,
        ),
        (
            "SU2: points, one triangle",
            |n| {
                let points = repeat(n, |k| format!("{} {}\n", k % 1000, k / 1000));
                let count = points.lines().count();
                format!("NDIME= 2\nNELEM= 1\n5 0 1 1000\nNPOIN= {count}\n{points}")
            },
            su2,
        ),
    ];
    println!(
        "| file | {} MB | {mb} MB | MB/s ({mb} MB) | result |",
        mb / 4
    );
    println!("|---|---:|---:|---:|---|");
    for (name, make, parse) in cases {
        let mut row = format!("| {name} |");
        let mut last = (0.0, String::new());
        for size in [mb / 4, mb] {
            let bytes = make(size * 1_000_000).into_bytes();
            let start = Instant::now();
            let result = parse(&bytes);
            let s = start.elapsed().as_secs_f64();
            row += &format!(" {s:.3} s |");
            last = (bytes.len() as f64 / 1e6 / s, result);
        }
        println!("{row} {:.0} | {} |", last.0, last.1);
    }
}
