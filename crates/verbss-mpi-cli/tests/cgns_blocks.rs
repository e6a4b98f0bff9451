//! `verbss-mpi deform IN.cgns -o OUT.pvtu` on 1, 2 and 3 ranks: every rank
//! reads its own blocks of the file, PT-Scotch cuts it, every rank holds and
//! writes only its part (docs/distributed.md).
//!
//! Each run is held to the single-process stepper to 1e-10 of the largest
//! displacement; the ranks' lines say how many cells each holds (all of them
//! once in all, none all of them on 2 or 3 ranks) and how many nodes (none
//! all of them on 2 or 3 ranks). A bad file stops every rank with one
//! message and exit code 2.

use std::path::{Path, PathBuf};

use verbss::mesh::CellKind;
use verbss::motion::Motion;
use verbss::settings::Reference;
use verbss::{io, Mesh};
use verbss_testkit::needs;

mod common;
mod like_one_process;

use like_one_process::{
    asset, deforms_like_one_process, node_index, ptscotch_ready, rank_lines, single,
    verbss_mpi_with,
};

/// Whether MPI, PT-Scotch and the CGNS library are here; otherwise the
/// test skips.
fn ready() -> bool {
    ptscotch_ready()
        && needs(
            "the CGNS library (Debian: libcgns-dev)",
            io::cgns::available(),
        )
}

/// `mesh` written as a fresh CGNS file `dir/name`, read back whole.
fn as_cgns(dir: &Path, name: &str, mesh: &Mesh) -> (PathBuf, Mesh) {
    let path = dir.join(name);
    io::write(&path, mesh, &io::WriteOptions::default()).unwrap();
    let whole = io::read(&path).unwrap();
    (path, whole)
}

/// Checks the ranks' lines of the runs on 1, 2 and 3 ranks of `whole`:
/// every cell once, and on several ranks no rank with all the cells or all
/// the nodes.
fn check_counts(stdouts: &[String], whole: &Mesh) {
    let (cells, nodes) = (whole.cell_count(), whole.node_count());
    for (k, stdout) in stdouts.iter().enumerate() {
        let np = k + 1;
        let ranks = rank_lines(
            stdout,
            [
                ": PT-Scotch part ",
                " cells read in blocks by every rank",
                " nodes and ",
                " cells read;",
            ],
        );
        assert_eq!(ranks.len(), np, "{stdout}");
        let mut sum = 0;
        for (r, &[rank, of, held_nodes, held_cells]) in ranks.iter().enumerate() {
            assert_eq!(rank, r);
            assert_eq!(of, cells);
            assert!(np == 1 || held_cells < cells, "{np} ranks: rank {r}");
            assert!(np == 1 || held_nodes < nodes, "{np} ranks: rank {r}");
            assert!(np > 1 || held_nodes == nodes, "{stdout}");
            sum += held_cells;
        }
        assert_eq!(sum, cells, "{np} ranks");
    }
}

#[test]
fn a_2d_hybrid_cgns_file_is_read_in_blocks_cut_and_deformed_on_one_to_three_ranks() {
    if !ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let msh = io::read(&asset("gmsh/channel_hole_v41_ascii.msh")).unwrap();
    // Triangles and quads: one MIXED section, read in blocks of it.
    let (cgns, whole) = as_cgns(dir.path(), "channel.cgns", &msh);
    for kind in [CellKind::Triangle, CellKind::Quad] {
        assert!(whole.cells.kinds.contains(&kind), "{kind:?}");
    }
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    let motion = ["--translate", "0.02,0.01"];
    let stdouts = deforms_like_one_process(&cgns, "wall", &motion, Reference::Updated, scale, &[]);
    check_counts(&stdouts, &whole);
}

#[test]
fn the_tetrahedral_brick_as_cgns_is_read_in_blocks_cut_and_deformed_on_one_to_three_ranks() {
    if !ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let su2 = io::read(&asset("su2/mesh_brick_tets_ffd.su2")).unwrap();
    let (cgns, whole) = as_cgns(dir.path(), "brick.cgns", &su2);
    let motion = ["--translate", "0,0,0.05"];
    let stdouts = deforms_like_one_process(&cgns, "z_p", &motion, Reference::Fixed, 0.05, &[]);
    check_counts(&stdouts, &whole);
}

/// Gmsh's own CGNS files (`scripts/gmsh_channel_cgns.py`): a section per
/// entity, boundary conditions over element ranges at `CellCenter` in
/// families under the physical groups' families, and the region `fluid`
/// over the cells, which makes no group. Read in blocks, their groups and
/// the moved meshes are the single process's, in 2D and 3D.
#[test]
fn files_written_by_gmsh_are_read_in_blocks_with_their_physical_groups() {
    if !ready()
        || !needs(
            "python3 with gmsh (pip install gmsh)",
            verbss_testkit::python(&["gmsh"]),
        )
    {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/gmsh_channel_cgns.py");
    let o = std::process::Command::new("python3")
        .arg(&script)
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for (dim, motion) in [(2, "0.03,0.05"), (3, "0.03,0.05,0.02")] {
        let cgns = dir.path().join(format!("channel{dim}.cgns"));
        let whole = io::read(&cgns).unwrap();
        assert_eq!(whole.dim, dim);
        let scale = motion
            .split(',')
            .map(|x| x.parse::<f64>().unwrap().powi(2))
            .sum::<f64>()
            .sqrt();
        let motion = ["--translate", motion];
        let stdouts =
            deforms_like_one_process(&cgns, "cylinder", &motion, Reference::Updated, scale, &[]);
        check_counts(&stdouts, &whole);
    }
}

/// A condition over an element list in a family (`solid`) and a section of
/// edges that no condition holds (`lid`, a group of its own), on a square
/// of two triangles: moving either group moves its nodes and only them, as
/// on one process, on 1 to 3 ranks (some of which hold nothing, so the
/// gathered mesh is compared).
#[test]
fn a_condition_over_a_list_and_a_section_of_its_own_make_the_groups() {
    if !ready() {
        return;
    }
    let square = asset("cgns/list_and_own_section.cgns");
    let whole = io::read(&square).unwrap();
    assert_eq!(whole.group_names(), ["solid", "lid"]);
    let index = node_index(&whole);
    for group in ["solid", "lid"] {
        let displacement = [0.01, 0.02, 0.0];
        let motion = Motion::Translation { displacement };
        let (one, _) = single(&whole, group, motion, 1, Reference::Fixed);
        let moved = whole.group(group).unwrap().nodes();
        for np in 1..=3 {
            let dir = tempfile::tempdir().unwrap();
            let out = dir.path().join("moved.pvtu");
            let all = dir.path().join("all.vtu");
            let args = [
                "deform",
                square.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--moving",
                group,
                "--translate",
                "0.01,0.02",
                "--method",
                "verbss",
                "--gather",
                all.to_str().unwrap(),
            ];
            let o = verbss_mpi_with(np, &args, dir.path(), &[]);
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            let gathered = io::read(&all).unwrap();
            for (i, t) in gathered.node_tags.iter().enumerate() {
                let g = index[t];
                let shift = [0, 1].map(|d| gathered.point(i)[d] - whole.point(g)[d]);
                assert_eq!(shift, [0, 1].map(|d| one.point(g)[d] - whole.point(g)[d]));
                let expected = if moved.contains(&g) {
                    [0.01, 0.02]
                } else {
                    [0.0; 2]
                };
                for d in 0..2 {
                    assert!(
                        (shift[d] - expected[d]).abs() < 1e-15,
                        "{group}, {np} ranks"
                    );
                }
            }
            assert_eq!(gathered.node_count(), whole.node_count());
        }
    }
}

/// `verbss-mpi deform PATH -o moved.pvtu` on 3 ranks must fail with exit
/// code 2 and one message: `expected` after the file's name, from rank 0
/// or as what another rank found.
fn refused_on_three_ranks(path: &Path, expected: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("moved.pvtu");
    let args = [
        "deform",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "wall",
        "--translate",
        "0.01,0",
        "--method",
        "verbss",
    ];
    let o = verbss_mpi_with(3, &args, dir.path(), &[]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{}: {stderr}", path.display());
    let errors = stderr.lines().filter(|l| l.starts_with("error: ")).count();
    assert_eq!(errors, 1, "{stderr}");
    let said = format!("{}: {expected}", path.display());
    let by_rank_0 = stderr.matches(&format!("error: {said}")).count();
    let by_another = stderr
        .matches(&format!(" found an invalid cell: {said}"))
        .count();
    assert_eq!(by_rank_0 + by_another, 1, "{stderr}");
}

/// A structured zone, conditions naming elements no section holds (a few,
/// and two thousand million), a duplicated element and a file that is not
/// CGNS: the whole-file reader's message; a polyhedral section (which the
/// whole-file reader reads), a second zone, which the whole-file reader
/// leaves out, and a zone without cells: refused.
#[test]
fn a_bad_cgns_file_stops_every_rank_with_one_message() {
    if !ready() {
        return;
    }
    // `huge_range`: a condition over 2,000,000,000 elements, found bad
    // without any rank spelling out its block of them; `duplicated`: found
    // after the cut by the rank that holds both copies.
    for name in [
        "structured",
        "condition_outside",
        "huge_range",
        "duplicated",
    ] {
        let path = asset(&format!("bad/{name}.cgns"));
        let whole = io::read(&path).unwrap_err().to_string();
        let expected = whole
            .strip_prefix(&format!("{}: ", path.display()))
            .unwrap_or_else(|| panic!("{whole}"));
        refused_on_three_ranks(&path, expected);
    }
    // Polyhedral sections are read from a whole file only.
    refused_on_three_ranks(
        &asset("bad/polyhedral.cgns"),
        "section 'Faces' of zone 'Zone' (zone 1 of base 'Base') is NGON_n: polyhedral sections \
         are not supported here (verbss reads them from a whole file, not in blocks; here it \
         reads BAR_2, TRI_3, QUAD_4, TETRA_4, PYRA_5, PENTA_6, HEXA_8 and MIXED of those)",
    );
    let dir = tempfile::tempdir().unwrap();
    let text = dir.path().join("text.cgns");
    std::fs::write(&text, "NDIME= 2\n").unwrap();
    refused_on_three_ranks(&text, "cannot open as CGNS");
    let two = asset("bad/two_zones.cgns");
    assert_eq!(io::read(&two).unwrap().cell_count(), 2);
    refused_on_three_ranks(
        &two,
        "base 'Base' holds 2 zones: a distributed read takes single-zone files",
    );
    // No section of cells: nothing to cut.
    refused_on_three_ranks(
        &asset("bad/no_cells.cgns"),
        "zone 'Zone' (zone 1 of base 'Base') holds no cells of dimension 2",
    );
}
