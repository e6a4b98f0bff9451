//! Hostile CGNS files through the `verbss` binary (issue 43, 1–4): each
//! crashed the process (inside the CGNS library or in its buffers), took
//! half a minute, or failed with "no CGNS error reported". Each now ends
//! with exit code 2 and one line naming the file and the node, in
//! `quality`, `convert` and `deform`.

use std::path::{Path, PathBuf};
use std::time::Instant;

mod common;

use common::{stderr, verbss};
use verbss::io::cgns::available;
use verbss::io::cgns::nodes::{self, section, Node};
use verbss_testkit::needs;

/// The valid square changed by `change`, written as `dir/name`.
fn square(dir: &Path, name: &str, change: impl FnOnce(&mut Node)) -> PathBuf {
    let path = dir.join(name);
    nodes::write_square(&path, change).unwrap();
    path
}

/// Runs `quality`, `convert` and `deform` on `path`: each exits with 2 and
/// `error: PATH: message` alone.
fn refused(path: &Path, message: &str) {
    let dir = path.parent().unwrap();
    let out = dir.join("out.su2");
    let (p, o) = (path.to_str().unwrap(), out.to_str().unwrap());
    for args in [
        vec!["quality", p],
        vec!["convert", p, o],
        vec![
            "deform",
            p,
            "-o",
            o,
            "--moving",
            "lid",
            "--translate",
            "0,0.01",
        ],
    ] {
        let run = verbss(&args);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {}", stderr(&run));
        assert_eq!(
            stderr(&run),
            format!("error: {}: {message}\n", path.display()),
            "{args:?}"
        );
        assert!(!out.exists());
    }
}

#[test]
fn hostile_cgns_files_are_refused_with_the_node_named() {
    if !needs("the CGNS library (Debian: libcgns-dev)", available()) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plain = square(d, "plain.cgns", |_| {});
    let o = verbss(&["quality", plain.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // 1: a point list of index dimension 5 (the heap overflow).
    let wide = square(d, "wide.cgns", |base| {
        let list = Node::ints("PointList", "IndexArray_t", &[5, 2], &[3; 10]);
        base.at("Zone").children.push(
            Node::empty("ZoneBC", "ZoneBC_t")
                .with([Node::text("lid", "BC_t", "BCWall").with([list])]),
        );
    });
    refused(
        &wide,
        "/Base/Zone/ZoneBC/lid/PointList: IndexArray_t node with I4 data of dimensions [5, 2] \
         (expected I4 or I8 data of dimensions [n] or [d, n], d from 1 to 3)",
    );
    // 2: a MIXED element of type 99; families naming each other.
    let mixed = square(d, "mixed.cgns", |base| {
        *base.at("Zone/Cells") = section("Cells", 20, [1, 2], &[5, 1, 2, 3, 99, 1, 3, 4]);
    });
    refused(
        &mixed,
        "/Base/Zone/Cells: element 2 of this MIXED section is ElementType_t 99 (verbss reads \
         BAR_2, TRI_3, QUAD_4, TETRA_4, PYRA_5, PENTA_6, HEXA_8 and MIXED of those)",
    );
    let families = square(d, "families.cgns", |base| {
        base.children.extend([
            Node::empty("a", "Family_t").with([Node::text("b", "FamilyName_t", "b")]),
            Node::empty("b", "Family_t").with([Node::text("a", "FamilyName_t", "a")]),
        ]);
    });
    let o = verbss(&["quality", families.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("/Base: the families '")
            && stderr(&o).contains("' belong to each other in a cycle"),
        "{}",
        stderr(&o)
    );
    // 3: user data nested 2,000 deep (the file had 20,000): refused at depth 32.
    let deep = square(d, "deep.cgns", |base| {
        let mut data = Node::empty("U", "UserDefinedData_t");
        for _ in 0..2_000 {
            data = Node::empty("U", "UserDefinedData_t").with([data]);
        }
        base.at("Zone").children.push(data);
    });
    let start = Instant::now();
    refused(
        &deep,
        &format!(
            "/Base/Zone{}: nodes nested more than 32 deep (a mesh's tree is about 8 deep)",
            "/U".repeat(30)
        ),
    );
    eprintln!("three runs on 2,000-deep user data: {:?}", start.elapsed());
    // 4: an ElementRange to 2^31 - 1.
    let range = square(d, "range.cgns", |base| {
        *base.at("Zone/Cells") = section("Cells", 5, [1, i32::MAX], &[1, 2, 3, 1, 3, 4]);
    });
    refused(
        &range,
        "/Base/Zone/Cells: ElementRange 1..2147483647 gives 2147483647 elements of TRI_3 (3 \
         nodes each), but ElementConnectivity holds 6 numbers (2 elements)",
    );
}
