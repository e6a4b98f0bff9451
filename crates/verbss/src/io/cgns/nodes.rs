//! CGNS files written node by node, whatever the nodes say: how the tests
//! and the fuzz targets make the hostile files that the reader's check
//! (`io/cgns/check.rs`) must refuse, and the valid ones it must pass.

use std::path::Path;

/// A node of a CGNS tree: its name, label, data type (`MT`, `I4`, `R8`,
/// `C1`, …), dimensions (the first varying fastest), data bytes (none for
/// `MT`; none at all declares the array and stores nothing), children, or
/// a link (`file`, `path`; the file empty for a link within the file).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Node {
    /// Its name.
    pub name: String,
    /// Its label (`Zone_t`, …).
    pub label: String,
    /// Its data type.
    pub kind: String,
    /// The dimensions of its data.
    pub dims: Vec<i64>,
    /// Its data, as bytes in the machine's order.
    pub data: Vec<u8>,
    /// Its children, in order.
    pub children: Vec<Node>,
    /// The node it links to instead, if any.
    pub link: Option<(String, String)>,
}

impl Node {
    /// A node without data.
    pub fn empty(name: &str, label: &str) -> Node {
        Node {
            name: name.into(),
            label: label.into(),
            kind: "MT".into(),
            ..Node::default()
        }
    }

    /// A node of `I4` numbers over `dims`.
    pub fn ints(name: &str, label: &str, dims: &[i64], values: &[i32]) -> Node {
        Node {
            kind: "I4".into(),
            dims: dims.to_vec(),
            data: values.iter().flat_map(|v| v.to_ne_bytes()).collect(),
            ..Node::empty(name, label)
        }
    }

    /// A node of `R8` numbers in one dimension.
    pub fn reals(name: &str, label: &str, values: &[f64]) -> Node {
        Node {
            kind: "R8".into(),
            dims: vec![values.len() as i64],
            data: values.iter().flat_map(|v| v.to_ne_bytes()).collect(),
            ..Node::empty(name, label)
        }
    }

    /// A node of `C1` text.
    pub fn text(name: &str, label: &str, text: &str) -> Node {
        Node {
            kind: "C1".into(),
            dims: vec![text.len() as i64],
            data: text.as_bytes().to_vec(),
            ..Node::empty(name, label)
        }
    }

    /// The node with `children` added.
    pub fn with(mut self, children: impl IntoIterator<Item = Node>) -> Node {
        self.children.extend(children);
        self
    }

    /// The descendant at `path` (names joined by `/`), to change it.
    pub fn at(&mut self, path: &str) -> &mut Node {
        path.split('/').fold(self, |node, name| {
            node.children
                .iter_mut()
                .find(|c| c.name == name)
                .unwrap_or_else(|| panic!("no node {name} in the tree"))
        })
    }
}

/// An element section `name` of element type `kind` numbered `range`.
pub fn section(name: &str, kind: i32, range: [i32; 2], connectivity: &[i32]) -> Node {
    Node::ints(name, "Elements_t", &[2], &[kind, 0]).with([
        Node::ints("ElementRange", "IndexRange_t", &[2], &range),
        Node::ints(
            "ElementConnectivity",
            "DataArray_t",
            &[connectivity.len() as i64],
            connectivity,
        ),
    ])
}

/// The nodes under the root of a valid file, as the library writes them:
/// a unit square of two triangles (elements 1, 2) with edge sections
/// `wall` (3, 4: bottom and right) and `lid` (5: top), zone `Zone` of base
/// `Base` (cell dimension 2).
pub fn square() -> Vec<Node> {
    let zone = Node::ints("Zone", "Zone_t", &[1, 3], &[4, 2, 0]).with([
        Node::text("ZoneType", "ZoneType_t", "Unstructured"),
        Node::empty("GridCoordinates", "GridCoordinates_t").with([
            Node::reals("CoordinateX", "DataArray_t", &[0., 1., 1., 0.]),
            Node::reals("CoordinateY", "DataArray_t", &[0., 0., 1., 1.]),
        ]),
        section("Cells", 5, [1, 2], &[1, 2, 3, 1, 3, 4]),
        section("wall", 3, [3, 4], &[1, 2, 2, 3]),
        section("lid", 3, [5, 5], &[3, 4]),
    ]);
    vec![
        Node {
            kind: "R4".into(),
            dims: vec![1],
            data: 3.4f32.to_ne_bytes().to_vec(),
            ..Node::empty("CGNSLibraryVersion", "CGNSLibraryVersion_t")
        },
        Node::ints("Base", "CGNSBase_t", &[2], &[2, 2]).with([zone]),
    ]
}

/// Writes the [`square`] changed by `change` (given its base) as `path`.
pub fn write_square(path: &Path, change: impl FnOnce(&mut Node)) -> Result<(), String> {
    let mut tree = square();
    change(&mut tree[1]);
    write(path, &tree)
}

/// Writes `nodes` under the root of a new HDF5 CGNS file `path`.
pub fn write(path: &Path, nodes: &[Node]) -> Result<(), String> {
    #[cfg(not(with_cgns))]
    return Err(format!(
        "{nodes:?} not written: {}",
        super::available().unwrap_err()
    ));
    #[cfg(with_cgns)]
    write_nodes(path, nodes)
}

#[cfg(with_cgns)]
fn write_nodes(path: &Path, nodes: &[Node]) -> Result<(), String> {
    use super::ffi::{CgSize, NodeId, Tree};
    let tree = Tree::create(path)?;
    let root = tree.root()?;
    let mut stack: Vec<(NodeId, &Node)> = nodes.iter().rev().map(|n| (root, n)).collect();
    while let Some((parent, node)) = stack.pop() {
        let id = match &node.link {
            Some((file, target)) => tree.write_link(parent, &node.name, (file, target))?,
            None => {
                let dims = node
                    .dims
                    .iter()
                    .map(|&d| CgSize::try_from(d).map_err(|_| format!("dimension {d}")))
                    .collect::<Result<Vec<_>, _>>()?;
                tree.write_node(
                    parent,
                    (&node.name, &node.label, &node.kind),
                    &dims,
                    &node.data,
                )?
            }
        };
        stack.extend(node.children.iter().rev().map(|c| (id, c)));
    }
    Ok(())
}
