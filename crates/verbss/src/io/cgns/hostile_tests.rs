//! Hostile CGNS files, made node by node ([`super::nodes`]): each is
//! refused with the node's path before the library reads the tree (many
//! crashed the process inside the library, or in its buffers), or read.

use std::path::{Path, PathBuf};

use super::nodes::{self, section, Node};
use crate::io::read;

/// The valid square changed by `change`, written as `dir/name`.
fn square(dir: &Path, name: &str, change: impl FnOnce(&mut Node)) -> PathBuf {
    let path = dir.join(name);
    nodes::write_square(&path, change).unwrap();
    path
}

/// The message of reading `path`, less the file's name.
fn refusal(path: &Path) -> String {
    let message = read(path).unwrap_err().to_string();
    let prefix = format!("{}: ", path.display());
    message
        .strip_prefix(&prefix)
        .unwrap_or(&message)
        .to_string()
}

/// A family-specified boundary condition `name` of `family` over `set`.
fn condition(name: &str, family: &str, set: Node) -> Node {
    Node::text(name, "BC_t", "FamilySpecified").with([
        Node::text("FamilyName", "FamilyName_t", family),
        Node::text("GridLocation", "GridLocation_t", "EdgeCenter"),
        set,
    ])
}

/// The zone's `ZoneBC` with `conditions`, and a family of each name.
fn with_conditions(base: &mut Node, conditions: Vec<Node>) {
    let families: Vec<Node> = conditions
        .iter()
        .map(|c| Node::empty(&c.name, "Family_t"))
        .collect();
    base.at("Zone")
        .children
        .push(Node::empty("ZoneBC", "ZoneBC_t").with(conditions));
    base.children.extend(families);
}

#[test]
fn the_valid_square_reads_and_its_conditions_name_their_groups() {
    let dir = tempfile::tempdir().unwrap();
    let plain = square(dir.path(), "plain.cgns", |_| {});
    let mesh = read(&plain).unwrap();
    assert_eq!((mesh.node_count(), mesh.cell_count()), (4, 2));
    assert_eq!(mesh.group_names(), ["wall", "lid"]);
    let listed = square(dir.path(), "list.cgns", |base| {
        let list = Node::ints("PointList", "IndexArray_t", &[1, 2], &[3, 4]);
        with_conditions(base, vec![condition("solid", "solid", list)]);
    });
    let mesh = read(&listed).unwrap();
    assert_eq!(mesh.group_names(), ["solid", "lid"]);
    assert_eq!(mesh.group("solid").unwrap().facets.nodes, [0, 1, 1, 2]);
}

/// Issue 43, 1: the library copies a point set's whole stored array into
/// the buffer the reader sized from the point count: a list of index
/// dimension 3 wrote past it (a heap overflow).
#[test]
fn a_point_set_of_another_shape_is_refused_before_the_library_copies_it() {
    let dir = tempfile::tempdir().unwrap();
    let wide = square(dir.path(), "wide.cgns", |base| {
        let list = Node::ints("PointList", "IndexArray_t", &[3, 2], &[3, 4, 3, 4, 3, 4]);
        with_conditions(base, vec![condition("solid", "solid", list)]);
    });
    assert_eq!(
        refusal(&wide),
        "boundary condition 'solid' of zone 'Zone' (zone 1 of base 'Base'): PointList of shape \
         3 × 2 (expected 1 × 2 in an unstructured zone)"
    );
    let range = square(dir.path(), "range.cgns", |base| {
        let range = Node::ints("PointRange", "IndexRange_t", &[4, 2], &[3; 8]);
        with_conditions(base, vec![condition("solid", "solid", range)]);
    });
    assert_eq!(
        refusal(&range),
        "boundary condition 'solid' of zone 'Zone' (zone 1 of base 'Base'): PointRange of shape \
         4 × 2 (expected 1 × 2 in an unstructured zone)"
    );
    let deep = square(dir.path(), "deep.cgns", |base| {
        let list = Node::ints("PointList", "IndexArray_t", &[5, 1], &[3; 5]);
        with_conditions(base, vec![condition("solid", "solid", list)]);
    });
    assert_eq!(
        refusal(&deep),
        "/Base/Zone/ZoneBC/solid/PointList: IndexArray_t node with I4 data of dimensions [5, 1] \
         (expected I4 or I8 data of dimensions [n] or [d, n], d from 1 to 3)"
    );
}

/// Issue 43, 2: a MIXED section's element type indexes the library's
/// tables (a crash in `cg_ElementPartialSize`).
#[test]
fn a_mixed_element_of_an_unknown_type_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = square(dir.path(), "mixed.cgns", |base| {
        *base.at("Zone/Cells") = section("Cells", 20, [1, 2], &[5, 1, 2, 3, 99, 1, 3, 4]);
    });
    assert_eq!(
        refusal(&path),
        "/Base/Zone/Cells: element 2 of this MIXED section is ElementType_t 99 (verbss reads \
         BAR_2, TRI_3, QUAD_4, TETRA_4, PYRA_5, PENTA_6, HEXA_8 and MIXED of those)"
    );
    let short = square(dir.path(), "short.cgns", |base| {
        *base.at("Zone/Cells") = section("Cells", 20, [1, 2], &[5, 1, 2, 3, 5, 1]);
    });
    assert_eq!(
        refusal(&short),
        "/Base/Zone/Cells: ElementConnectivity ends inside element 2 (TRI_3)"
    );
    let offsets = square(dir.path(), "offsets.cgns", |base| {
        let mut cells = section("Cells", 20, [1, 2], &[5, 1, 2, 3, 5, 1, 3, 4]);
        cells.children.push(Node::ints(
            "ElementStartOffset",
            "DataArray_t",
            &[3],
            &[0, 3, 8],
        ));
        *base.at("Zone/Cells") = cells;
    });
    assert_eq!(
        refusal(&offsets),
        "/Base/Zone/Cells: ElementStartOffset gives element 2 at 3 of ElementConnectivity (its \
         elements before end at 4)"
    );
    let good = square(dir.path(), "good.cgns", |base| {
        let mut cells = section("Cells", 20, [1, 2], &[5, 1, 2, 3, 5, 1, 3, 4]);
        cells.children.push(Node::ints(
            "ElementStartOffset",
            "DataArray_t",
            &[3],
            &[0, 4, 8],
        ));
        *base.at("Zone/Cells") = cells;
    });
    assert_eq!(read(&good).unwrap().cell_count(), 2);
}

/// Issue 43, 2: families that belong to each other.
#[test]
fn families_in_a_cycle_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = square(dir.path(), "cycle.cgns", |base| {
        base.children.extend([
            Node::empty("a", "Family_t").with([Node::text("b", "FamilyName_t", "b")]),
            Node::empty("b", "Family_t").with([Node::text("c", "FamilyName_t", "c")]),
            Node::empty("c", "Family_t").with([Node::text("a", "FamilyName_t", "a")]),
        ]);
    });
    let message = refusal(&path);
    assert!(
        message.starts_with("/Base: the families '")
            && message.ends_with("' belong to each other in a cycle (FamilyName_t under Family_t)"),
        "{message}"
    );
    for name in ["'a'", "'b'", "'c'"] {
        assert!(message.contains(name), "{message}");
    }
    let long = square(dir.path(), "long.cgns", |base| {
        base.children
            .push(Node::empty("a", "Family_t").with([Node::text(
                "b",
                "FamilyName_t",
                &"b".repeat(40),
            )]));
    });
    assert_eq!(
        refusal(&long),
        "/Base/a/b: FamilyName_t node with C1 data of dimensions [40] (expected a name of at most \
         32 characters)"
    );
}

/// Issue 43, 3: deep nesting cost the library time and memory quadratic in
/// the depth; the walk stops at 32.
#[test]
fn nodes_nested_deeper_than_32_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = square(dir.path(), "deep.cgns", |base| {
        let mut data = Node::empty("U", "UserDefinedData_t");
        for _ in 0..200 {
            data = Node::empty("U", "UserDefinedData_t").with([data]);
        }
        base.at("Zone").children.push(data);
    });
    let expected = format!(
        "/Base/Zone{}: nodes nested more than 32 deep (a mesh's tree is about 8 deep)",
        "/U".repeat(30)
    );
    assert_eq!(refusal(&path), expected);
}

/// Issue 43, 4: an `ElementRange` to 2^31 − 1 failed in the library with
/// "no CGNS error reported".
#[test]
fn a_range_that_disagrees_with_its_connectivity_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = square(dir.path(), "range.cgns", |base| {
        *base.at("Zone/Cells") = section("Cells", 5, [1, i32::MAX], &[1, 2, 3, 1, 3, 4]);
    });
    assert_eq!(
        refusal(&path),
        "/Base/Zone/Cells: ElementRange 1..2147483647 gives 2147483647 elements of TRI_3 (3 \
         nodes each), but ElementConnectivity holds 6 numbers (2 elements)"
    );
}

/// Nodes the library reads into places of a fixed size, links, and arrays
/// declared far larger than the file.
#[test]
fn fixed_size_nodes_links_and_unstored_arrays_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("version.cgns");
    let mut tree = nodes::square();
    tree[0] = Node::reals("CGNSLibraryVersion", "CGNSLibraryVersion_t", &[3.4; 100]);
    nodes::write(&path, &tree).unwrap();
    assert_eq!(
        refusal(&path),
        "/CGNSLibraryVersion: CGNSLibraryVersion_t node with R8 data of dimensions [100] \
         (expected R4 data of dimensions [1])"
    );
    let zone = square(dir.path(), "zone.cgns", |base| {
        let z = base.at("Zone");
        (z.dims, z.data) = (vec![5, 3], vec![0; 60]);
    });
    assert_eq!(
        refusal(&zone),
        "/Base/Zone: Zone_t node with I4 data of dimensions [5, 3] (expected I4 or I8 data of \
         dimensions [d, 3], d from 1 to 3)"
    );
    let link = square(dir.path(), "link.cgns", |base| {
        base.at("Zone").children.push(Node {
            name: "Elsewhere".into(),
            link: Some(("other.cgns".into(), "/Base/Zone".into())),
            ..Node::default()
        });
    });
    assert_eq!(
        refusal(&link),
        "/Base/Zone/Elsewhere: a CGNS link to another node or file (verbss reads files whose \
         nodes are all in the file)"
    );
    let huge = square(dir.path(), "huge.cgns", |base| {
        base.at("Zone").children.push(Node {
            kind: "R8".into(),
            dims: vec![1 << 30],
            ..Node::empty("Huge", "DataArray_t")
        });
    });
    let message = refusal(&huge);
    assert!(
        message.starts_with("/Base/Zone/Huge: the file's arrays declare more than ")
            && message.ends_with(
                " bytes (64 MiB plus twice the file's size: compressed or unallocated data is not read)"
            ),
        "{message}"
    );
}

/// A node of more children than the bound: `cg_open` took 11 s for 5,000
/// children of one zone, 29 s for 10,000 (docs/reliability.md).
#[test]
fn a_node_of_more_than_4096_children_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = square(dir.path(), "wide.cgns", |base| {
        let zone = base.at("Zone");
        for k in 0..4_097 {
            zone.children
                .push(Node::empty(&format!("U{k}"), "UserDefinedData_t"));
        }
    });
    assert_eq!(
        refusal(&path),
        "/Base/Zone: more than 4096 children (at most 4096 children a node and 65536 nodes a \
         file: the CGNS library's time to open a file grows faster than that)"
    );
}
