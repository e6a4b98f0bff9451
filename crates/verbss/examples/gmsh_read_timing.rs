//! Time to read a large Gmsh file: a structured box of `n³` cubes, each split
//! into 6 tetrahedra (Kuhn's split along the main diagonal; `n = 70` gives
//! 2,058,000 tetrahedra), with its six faces as groups, written in each MSH
//! encoding and read back with [`verbss::io::read`].
//!
//! ```sh
//! cargo run --release -p verbss --example gmsh_read_timing          # n = 70
//! cargo run --release -p verbss --example gmsh_read_timing -- 20    # smaller
//! ```
//!
//! The files go to the system's temporary folder and are removed afterwards;
//! `--keep FILE.msh` also leaves the MSH 4.1 binary file at `FILE.msh`, e.g. to
//! time `verbss quality FILE.msh` on it.

use std::time::Instant;

use verbss::io::{MshVersion, WriteOptions};
use verbss::mesh::{CellKind, Cells, Group, Mesh};

/// The box `[0, 1]³` with `n` cubes a side, 6 tetrahedra per cube, and the
/// groups `x_m x_p y_m y_p z_m z_p` (two triangles per cube face).
fn tet_box(n: usize) -> Mesh {
    let m = n + 1;
    let id = |p: [usize; 3]| p[0] + m * (p[1] + m * p[2]);
    let mut coords = Vec::with_capacity(3 * m * m * m);
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                coords.extend([i, j, k].map(|v| v as f64 / n as f64));
            }
        }
    }
    // Kuhn's split: one tetrahedron per path 000 → 111 along the axes (a, b, c);
    // odd permutations are listed with two nodes swapped to keep every
    // tetrahedron positively oriented.
    const PATHS: [([usize; 3], bool); 6] = [
        ([0, 1, 2], false),
        ([1, 2, 0], false),
        ([2, 0, 1], false),
        ([0, 2, 1], true),
        ([2, 1, 0], true),
        ([1, 0, 2], true),
    ];
    let mut cells = Cells::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                for (axes, odd) in PATHS {
                    let mut p = [i, j, k];
                    let mut tet = [id(p), 0, 0, id([i + 1, j + 1, k + 1])];
                    for (slot, &a) in tet[1..3].iter_mut().zip(&axes) {
                        p[a] += 1;
                        *slot = id(p);
                    }
                    if odd {
                        tet.swap(1, 2);
                    }
                    cells.push(CellKind::Tetra, &tet);
                }
            }
        }
    }
    let mut groups = Vec::new();
    for (axis, name) in ["x", "y", "z"].iter().enumerate() {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for (side, at) in [("m", 0), ("p", n)] {
            let mut facets = Cells::new();
            for b in 0..n {
                for a in 0..n {
                    let corner = |da: usize, db: usize| {
                        let mut p = [0; 3];
                        p[axis] = at;
                        p[u] = a + da;
                        p[v] = b + db;
                        id(p)
                    };
                    let (p00, p10, p11, p01) =
                        (corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1));
                    facets.push(CellKind::Triangle, &[p00, p10, p11]);
                    facets.push(CellKind::Triangle, &[p00, p11, p01]);
                }
            }
            groups.push(Group {
                name: format!("{name}_{side}"),
                tag: Some(groups.len() as i32 + 1),
                facets,
            });
        }
    }
    Mesh::new(3, coords, cells, groups).expect("a valid box")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let keep = args
        .iter()
        .position(|a| a == "--keep")
        .map(|k| std::path::PathBuf::from(args.get(k + 1).expect("--keep FILE.msh")));
    let n: usize = match args.first().filter(|a| *a != "--keep") {
        Some(a) => a.parse().expect("the number of cubes a side"),
        None => 70,
    };
    let t = Instant::now();
    let mesh = tet_box(n);
    println!(
        "box of {n}³ cubes: {} nodes, {} tetrahedra, {} boundary triangles (built in {:.2} s)",
        mesh.node_count(),
        mesh.cell_count(),
        mesh.groups.iter().map(|g| g.facets.len()).sum::<usize>(),
        t.elapsed().as_secs_f64()
    );
    if let Some(path) = &keep {
        let mut options = WriteOptions::default();
        options.binary = true;
        verbss::io::write(path, &mesh, &options).expect("write the kept file");
        println!("kept MSH 4.1 binary at {}", path.display());
    }
    for (version, binary) in [
        (MshVersion::V41, true),
        (MshVersion::V22, true),
        (MshVersion::V41, false),
        (MshVersion::V22, false),
    ] {
        let label = format!(
            "MSH {} {}",
            if version == MshVersion::V41 {
                "4.1"
            } else {
                "2.2"
            },
            if binary { "binary" } else { "ASCII" }
        );
        let path = std::env::temp_dir().join(format!("verbss_timing_{}.msh", std::process::id()));
        let mut options = WriteOptions::default();
        options.msh_version = version;
        options.binary = binary;
        let t = Instant::now();
        verbss::io::write(&path, &mesh, &options).expect("write");
        let write_s = t.elapsed().as_secs_f64();
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
        let t = Instant::now();
        let back = verbss::io::read(&path).expect("read");
        let read_s = t.elapsed().as_secs_f64();
        std::fs::remove_file(&path).expect("remove the temporary file");
        assert!(back == mesh, "{label}: the mesh read back differs");
        println!(
            "{label:<17} {:>7.1} MB  write {write_s:>6.2} s  read {read_s:>6.2} s",
            size as f64 / 1e6
        );
    }
}
