//! The node tree of a CGNS file, checked before the CGNS library reads it.
//!
//! `cg_open` reads the whole tree into memory and trusts it: data of another
//! size than it expects overflow its buffers, a `MIXED` section's element
//! types index its tables, and deep nesting costs it time and memory
//! quadratic in the depth. So the tree is first walked with the node layer
//! ([`Tree`]), which reads one node at a time into buffers sized from what
//! it reports, within hard bounds, and the file is refused when it holds
//!
//! - a link (to another file or within this one): verbss reads files whose
//!   nodes are all their own;
//! - nodes nested more than [`MAX_DEPTH`] deep, a node of more than
//!   [`MAX_CHILDREN`] children, or more than [`MAX_NODES`] nodes;
//! - a data type other than the standard's, or a dimension below 1;
//! - arrays declaring more bytes than 64 MiB plus twice the file's size
//!   (a file's arrays are stored in it; more is compressed or unallocated
//!   data, which the library would inflate);
//! - a node the library reads into a place of fixed size, of another type or
//!   shape ([`FIXED`]), or a family name longer than 32 characters;
//! - families that belong to each other in a cycle (`FamilyName_t` under
//!   `Family_t`);
//! - an element section whose `ElementRange`, `ElementConnectivity` and
//!   `ElementStartOffset` disagree, or a `MIXED` section holding an element
//!   type verbss does not read.
//!
//! Each message names the node by its path in the file. The walk is linear
//! in the number of nodes and in the size of the `MIXED` sections, read in
//! blocks of [`BLOCK`] numbers.

use std::collections::HashMap;
use std::path::Path;

use super::ffi::{NodeHead, NodeId, Tree, MIXED, NFACE_N, NGON_N};
use super::zone::{kind_of, type_name, READ};

/// The deepest a node may be nested below the root (a mesh's tree is
/// about 8 deep: base, zone, boundary conditions, condition, data set, …).
pub const MAX_DEPTH: usize = 32;

/// The most nodes a file may hold: `cg_open` takes about half a
/// millisecond a node (docs/reliability.md).
pub const MAX_NODES: usize = 65_536;

/// The most children a node may have: `cg_open`'s time grows faster than
/// the number of children of one node (about 1 s for 1,000, 11 s for 5,000).
pub const MAX_CHILDREN: usize = 4_096;

/// How many numbers of a `MIXED` section are read at a time.
const BLOCK: usize = 1 << 16;

/// The data types of the standard, with the bytes of one value.
const TYPES: [(&str, u64); 12] = [
    ("MT", 0),
    ("LK", 0),
    ("C1", 1),
    ("B1", 1),
    ("I4", 4),
    ("U4", 4),
    ("R4", 4),
    ("I8", 8),
    ("U8", 8),
    ("R8", 8),
    ("X4", 8),
    ("X8", 16),
];

/// The shape a node's data must have.
#[derive(Clone, Copy)]
enum Shape {
    /// These dimensions exactly.
    Exactly(&'static [i64]),
    /// Two dimensions: an index dimension 1 to 3, then this many.
    Indexed(i64),
    /// `[n]`, or `[d, n]` with `d` an index dimension 1 to 3.
    List,
}

/// The nodes the library reads into places of a fixed size: label, data
/// types, shape.
const FIXED: [(&str, &[&str], Shape); 8] = [
    ("DimensionalUnits_t", &["C1"], Shape::Exactly(&[32, 5])),
    ("AdditionalUnits_t", &["C1"], Shape::Exactly(&[32, 3])),
    ("CGNSLibraryVersion_t", &["R4"], Shape::Exactly(&[1])),
    ("CGNSBase_t", &["I4"], Shape::Exactly(&[2])),
    ("Zone_t", &["I4", "I8"], Shape::Indexed(3)),
    ("Elements_t", &["I4"], Shape::Exactly(&[2])),
    ("IndexArray_t", &["I4", "I8"], Shape::List),
    ("Ordinal_t", &["I4"], Shape::Exactly(&[1])),
];

/// The labels whose `C1` data is free text; any other's is a name or the
/// name of a value, which the library may copy into a place of 33 bytes.
const FREE_TEXT: [&str; 4] = [
    "Descriptor_t",
    "DataArray_t",
    "GeometryFile_t",
    "UserDefinedData_t",
];

/// A node on the way: its id, head and path.
struct Node {
    id: NodeId,
    head: NodeHead,
    path: String,
    depth: usize,
}

/// The walk's counts and what it gathers.
struct Walk<'a> {
    tree: &'a Tree,
    nodes: usize,
    bytes: u64,
    budget: u64,
    /// Per base: each family and the families it belongs to.
    families: HashMap<String, Vec<(String, String)>>,
}

/// Checks the node tree of the CGNS file `path` (see the module's doc).
pub(super) fn check(path: &Path) -> Result<(), String> {
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    super::container::check(path)?;
    let tree = Tree::open(path).map_err(|m| format!("cannot open as CGNS: {m}"))?;
    let mut walk = Walk {
        tree: &tree,
        nodes: 0,
        bytes: 0,
        budget: (64 << 20) + 2 * size,
        families: HashMap::new(),
    };
    let root = tree.root()?;
    let mut stack = walk.children(root, "", 0)?;
    while let Some(node) = stack.pop() {
        let children = walk.children(node.id, &node.path, node.depth)?;
        walk.node(&node, &children)?;
        tree.release(node.id);
        stack.extend(children.into_iter().rev());
    }
    for (base, families) in &walk.families {
        cycle(base, families)?;
    }
    Ok(())
}

impl Walk<'_> {
    /// The children of the node `id` at `path`, each checked on its own.
    fn children(&mut self, id: NodeId, path: &str, depth: usize) -> Result<Vec<Node>, String> {
        let ids = self
            .tree
            .children(id, room(self.nodes))
            .map_err(|m| crowded(path, &m))?;
        if !ids.is_empty() && depth == MAX_DEPTH {
            return Err(nested(path));
        }
        self.nodes += ids.len();
        let mut nodes = Vec::with_capacity(ids.len());
        for id in ids {
            if let Some(target) = self.tree.link(id)? {
                return Err(format!(
                    "{path}/…: a node links to {target} (verbss reads files whose nodes are all in the file)"
                ));
            }
            let head = self.tree.head(id)?;
            let path = format!("{path}/{}", head.name);
            self.data(&path, &head)?;
            nodes.push(Node {
                id,
                head,
                path,
                depth: depth + 1,
            });
        }
        Ok(nodes)
    }

    /// Checks a node's data type, dimensions and bytes, and the shape of
    /// the [`FIXED`] nodes.
    fn data(&mut self, path: &str, head: &NodeHead) -> Result<(), String> {
        let kind = head.kind.as_str();
        let width = TYPES
            .iter()
            .find(|t| t.0 == kind)
            .map(|t| t.1)
            .ok_or_else(|| {
                format!("{path}: data type {kind:?} (expected MT, C1, I4, I8, R4, R8, …)")
            })?;
        if width == 0 {
            return Ok(());
        }
        if head.dims.is_empty() || head.dims.iter().any(|&d| d < 1) {
            return Err(format!(
                "{path}: {kind} data of dimensions {:?} (expected each at least 1)",
                head.dims
            ));
        }
        let values = head
            .dims
            .iter()
            .try_fold(1u64, |n, &d| n.checked_mul(d as u64))
            .and_then(|n| n.checked_mul(width));
        self.bytes = values.map_or(u64::MAX, |b| self.bytes.saturating_add(b));
        if self.bytes > self.budget {
            return Err(format!(
                "{path}: the file's arrays declare more than {} bytes (64 MiB plus twice the file's size: \
                 compressed or unallocated data is not read)",
                self.budget
            ));
        }
        let label = head.label.as_str();
        let units = label.ends_with("Units_t");
        if kind == "C1"
            && !units
            && !FREE_TEXT.contains(&label)
            && (head.dims.len() != 1 || head.dims[0] > 32)
        {
            return Err(format!(
                "{path}: {label} node with C1 data of dimensions {:?} (expected a name of at most 32 characters)",
                head.dims
            ));
        }
        if let Some((_, types, shape)) = FIXED.iter().find(|f| f.0 == label) {
            let d = head.dims.as_slice();
            let fits = match *shape {
                Shape::Exactly(e) => d == e,
                Shape::Indexed(n) => d.len() == 2 && (1..=3).contains(&d[0]) && d[1] == n,
                Shape::List => d.len() == 1 || (d.len() == 2 && (1..=3).contains(&d[0])),
            };
            if !types.contains(&kind) || !fits {
                return Err(format!(
                    "{path}: {} node with {kind} data of dimensions {d:?} (expected {} data {})",
                    head.label,
                    types.join(" or "),
                    shape.describe()
                ));
            }
        }
        Ok(())
    }

    /// The checks of a node with its children: sections and families.
    fn node(&mut self, node: &Node, children: &[Node]) -> Result<(), String> {
        match node.head.label.as_str() {
            "Elements_t" => section(self.tree, node, children),
            "Family_t" if node.depth == 2 => {
                let base = node.path[1..].split('/').next().unwrap_or("").to_string();
                for c in children.iter().filter(|c| c.head.label == "FamilyName_t") {
                    let parent = self.tree.read_text(c.id, c.head.dims[0] as usize)?;
                    let parent = parent.trim_end_matches(['\0', ' ']).to_string();
                    self.families
                        .entry(base.clone())
                        .or_default()
                        .push((node.head.name.clone(), parent));
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }
}

impl Shape {
    /// The shape, for messages.
    fn describe(self) -> String {
        match self {
            Shape::Exactly(d) => format!("of dimensions {d:?}"),
            Shape::Indexed(n) => format!("of dimensions [d, {n}], d from 1 to 3"),
            Shape::List => "of dimensions [n] or [d, n], d from 1 to 3".into(),
        }
    }
}

/// The most children the next node may have, `nodes` counted so far.
pub(super) fn room(nodes: usize) -> usize {
    MAX_CHILDREN.min(MAX_NODES - nodes)
}

/// The message for the node at `path`, whose children are `why` too many.
pub(super) fn crowded(path: &str, why: &str) -> String {
    format!(
        "{}: {why} (at most {MAX_CHILDREN} children a node and {MAX_NODES} nodes a file: the \
         CGNS library's time to open a file grows faster than that)",
        shown(path)
    )
}

/// The message for the children of the node at `path`, at [`MAX_DEPTH`].
pub(super) fn nested(path: &str) -> String {
    format!("{path}: nodes nested more than {MAX_DEPTH} deep (a mesh's tree is about 8 deep)")
}

/// The path as shown: `/` for the root.
pub(super) fn shown(path: &str) -> &str {
    if path.is_empty() {
        "/"
    } else {
        path
    }
}

/// Refuses families of `base` that belong to each other in a cycle.
fn cycle(base: &str, families: &[(String, String)]) -> Result<(), String> {
    let mut parents: HashMap<&str, Vec<&str>> = HashMap::new();
    for (family, parent) in families {
        parents.entry(family).or_default().push(parent);
    }
    // 1: on the current chain, 2: done.
    let mut state: HashMap<&str, u8> = HashMap::new();
    for start in parents.keys() {
        let mut chain: Vec<(&str, usize)> = vec![(start, 0)];
        while let Some(&(family, next)) = chain.last() {
            if next == 0 {
                match state.get(family) {
                    Some(2) => {
                        chain.pop();
                        continue;
                    }
                    Some(_) => {
                        let names: Vec<&str> = chain.iter().map(|c| c.0).collect();
                        let from = names.iter().position(|&n| n == family).unwrap_or(0);
                        return Err(format!(
                            "/{base}: the families {} belong to each other in a cycle (FamilyName_t under Family_t)",
                            names[from..].iter().map(|n| format!("'{n}'")).collect::<Vec<_>>().join(" → ")
                        ));
                    }
                    None => {
                        state.insert(family, 1);
                    }
                }
            }
            let up = parents.get(family).map_or(&[][..], Vec::as_slice);
            if let Some(&parent) = up.get(next) {
                chain.last_mut().expect("on the chain").1 += 1;
                chain.push((parent, 0));
            } else {
                state.insert(family, 2);
                chain.pop();
            }
        }
    }
    Ok(())
}

/// An element section's range, connectivity and offsets checked against
/// each other, and a `MIXED` section's element types.
fn section(tree: &Tree, node: &Node, children: &[Node]) -> Result<(), String> {
    let path = &node.path;
    let child = |name: &str| children.iter().find(|c| c.head.name == name);
    let kind = tree.read_i64(node.id, (0, 1))?[0];
    if kind == i64::from(NGON_N) || kind == i64::from(NFACE_N) {
        // Refused by the reader, naming the section.
        return Ok(());
    }
    let range = child("ElementRange").ok_or_else(|| format!("{path}: no ElementRange"))?;
    if !matches!(range.head.kind.as_str(), "I4" | "I8") || range.head.dims != [2] {
        return Err(format!(
            "{path}/ElementRange: {} data of dimensions {:?} (expected I4 or I8 data of dimensions [2])",
            range.head.kind, range.head.dims
        ));
    }
    let (start, end) = match tree.read_i64(range.id, (0, 2))?[..] {
        [s, e] => (s, e),
        _ => unreachable!("two values read"),
    };
    if start < 1 || end < start {
        return Err(format!(
            "{path}: ElementRange {start}..{end} (expected 1 ≤ start ≤ end)"
        ));
    }
    let count = end - start + 1;
    let connectivity = child("ElementConnectivity")
        .filter(|c| matches!(c.head.kind.as_str(), "I4" | "I8") && c.head.dims.len() == 1)
        .ok_or_else(|| {
            format!("{path}: no ElementConnectivity of I4 or I8 numbers in one dimension")
        })?;
    let len = connectivity.head.dims[0];
    let name = type_name(kind as i32);
    if kind != i64::from(MIXED) {
        if let Some(k) = kind_of(kind as i32) {
            let per = k.node_count() as i64;
            if count.checked_mul(per) != Some(len) {
                return Err(format!(
                    "{path}: ElementRange {start}..{end} gives {count} elements of {name} ({per} nodes each), \
                     but ElementConnectivity holds {len} numbers ({} elements)",
                    len / per
                ));
            }
        }
        return Ok(());
    }
    let offsets = child("ElementStartOffset");
    if let Some(o) = offsets {
        if !matches!(o.head.kind.as_str(), "I4" | "I8") || o.head.dims != [count + 1] {
            return Err(format!(
                "{path}/ElementStartOffset: {} data of dimensions {:?} (expected I4 or I8 data of \
                 dimensions [{}]: one more than the {count} elements of ElementRange {start}..{end})",
                o.head.kind,
                o.head.dims,
                count + 1
            ));
        }
    }
    let mut data = Blocks::new(tree, connectivity.id, len as usize);
    let mut starts = offsets.map(|o| Blocks::new(tree, o.id, count as usize + 1));
    let mut pos = 0usize;
    for e in 0..count as usize {
        let number = start + e as i64;
        if let Some(starts) = &mut starts {
            let at = starts.get(e)?;
            if at != Some(pos as i64) {
                return Err(format!(
                    "{path}: ElementStartOffset gives element {number} at {} of ElementConnectivity \
                     (its elements before end at {pos})",
                    at.map_or("nothing".into(), |a| a.to_string())
                ));
            }
        }
        let code = data
            .get(pos)?
            .ok_or_else(|| format!("{path}: ElementConnectivity ends before element {number} of ElementRange {start}..{end}"))?;
        let k = i32::try_from(code).ok().and_then(kind_of).ok_or_else(|| {
            format!(
                "{path}: element {number} of this MIXED section is {} (verbss reads {READ})",
                type_name(i32::try_from(code).unwrap_or(i32::MAX))
            )
        })?;
        pos += 1 + k.node_count();
        if pos > len as usize {
            return Err(format!(
                "{path}: ElementConnectivity ends inside element {number} ({})",
                type_name(code as i32)
            ));
        }
    }
    if let Some(starts) = &mut starts {
        if starts.get(count as usize)? != Some(pos as i64) {
            return Err(format!(
                "{path}: the last ElementStartOffset is not the {pos} numbers of the elements"
            ));
        }
    }
    if pos != len as usize {
        return Err(format!(
            "{path}: ElementConnectivity holds {len} numbers, its {count} elements {pos}"
        ));
    }
    Ok(())
}

/// A one-dimensional array of numbers read forwards in blocks.
struct Blocks<'a> {
    tree: &'a Tree,
    id: NodeId,
    len: usize,
    first: usize,
    block: Vec<i64>,
}

impl<'a> Blocks<'a> {
    fn new(tree: &'a Tree, id: NodeId, len: usize) -> Blocks<'a> {
        Blocks {
            tree,
            id,
            len,
            first: 0,
            block: Vec::new(),
        }
    }

    /// Value `k` (from 0, never before one asked for earlier), `None` past
    /// the end.
    fn get(&mut self, k: usize) -> Result<Option<i64>, String> {
        if k >= self.len {
            return Ok(None);
        }
        if k >= self.first + self.block.len() {
            let count = BLOCK.min(self.len - k);
            self.block = self.tree.read_i64(self.id, (k, count))?;
            self.first = k;
        }
        Ok(Some(self.block[k - self.first]))
    }
}
