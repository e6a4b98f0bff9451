//! CGNS files as node trees (`verbss::io::cgns::nodes`): the valid square
//! the library writes, changed by a fuzzed list of edits — any node's label,
//! data type, dimensions (huge, zero, negative, 12 of them) or data, new
//! children of any label and data, removed or copied subtrees, links to
//! this file or another, and user data nested to any depth — then written
//! as a real HDF5 file through the CGNS node layer.

use arbitrary::Arbitrary;
use verbss::io::cgns::nodes::{self, Node};

/// A CGNS file, described.
#[derive(Arbitrary, Debug)]
pub struct CgnsFile {
    edits: Vec<Edit>,
}

/// A change to the tree; `at` picks a node (in depth-first order, modulo
/// the count).
#[derive(Arbitrary, Debug)]
enum Edit {
    Label { at: u16, label: u8 },
    Kind { at: u16, kind: u8 },
    Dims { at: u16, dims: Vec<Dim> },
    Data { at: u16, data: Data },
    Child { at: u16, name: u8, label: u8, kind: u8, data: Data },
    Remove { at: u16 },
    Copy { from: u16, to: u16 },
    Link { at: u16, name: u8, target: u8, other_file: bool },
    Nest { at: u16, depth: u16 },
}

/// A dimension: small, around the true sizes, or extreme.
#[derive(Arbitrary, Debug, Clone, Copy)]
enum Dim {
    Small(u8),
    Zero,
    Negative,
    Big(u32),
    Max,
}

/// Data: numbers from the values the reader branches on, text, or bytes.
#[derive(Arbitrary, Debug)]
enum Data {
    Ints(Vec<Int>),
    Text(u8),
    Bytes(Vec<u8>),
    Reals(Vec<i16>),
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Int {
    Small(i8),
    Type(u8),
    Max,
    Min,
    Any(i32),
}

const LABELS: [&str; 32] = [
    "CGNSLibraryVersion_t",
    "CGNSBase_t",
    "Zone_t",
    "ZoneType_t",
    "GridCoordinates_t",
    "DataArray_t",
    "Elements_t",
    "IndexRange_t",
    "IndexArray_t",
    "ZoneBC_t",
    "BC_t",
    "BCDataSet_t",
    "BCData_t",
    "FamilyName_t",
    "AdditionalFamilyName_t",
    "Family_t",
    "FamilyBC_t",
    "GridLocation_t",
    "UserDefinedData_t",
    "Descriptor_t",
    "Ordinal_t",
    "FlowSolution_t",
    "DataClass_t",
    "DimensionalUnits_t",
    "DimensionalExponents_t",
    "ZoneGridConnectivity_t",
    "GridConnectivity_t",
    "GridConnectivity1to1_t",
    "Rind_t",
    "ReferenceState_t",
    "ConvergenceHistory_t",
    "Gravity_t",
];

const NAMES: [&str; 24] = [
    "Base",
    "Zone",
    "Cells",
    "wall",
    "lid",
    "ZoneBC",
    "ZoneType",
    "GridCoordinates",
    "CoordinateX",
    "CoordinateY",
    "CoordinateZ",
    "ElementRange",
    "ElementConnectivity",
    "ElementStartOffset",
    "PointList",
    "PointRange",
    "ElementList",
    "FamilyName",
    "GridLocation",
    "Ordinal",
    "U",
    "Zone2",
    "a",
    "CGNSLibraryVersion",
];

const KINDS: [&str; 13] = [
    "MT", "C1", "I4", "I8", "R4", "R8", "U4", "U8", "B1", "X4", "X8", "LK", "Q9",
];

const TEXTS: [&str; 14] = [
    "Unstructured",
    "Structured",
    "Vertex",
    "FaceCenter",
    "EdgeCenter",
    "CellCenter",
    "FamilySpecified",
    "BCWall",
    "wall",
    "lid",
    "Zone",
    "",
    "a/b",
    "a name far longer than the thirty-two characters of a CGNS name",
];

impl Dim {
    fn value(self) -> i64 {
        match self {
            Dim::Small(v) => i64::from(v % 12),
            Dim::Zero => 0,
            Dim::Negative => -1,
            Dim::Big(v) => i64::from(v),
            Dim::Max => i64::from(i32::MAX),
        }
    }
}

impl Data {
    /// The bytes, and the dimensions they fill when the node keeps its type.
    fn bytes(&self) -> (String, Vec<i64>, Vec<u8>) {
        match self {
            Data::Ints(v) => {
                let ints: Vec<i32> = v.iter().map(|i| i.value()).collect();
                let bytes = ints.iter().flat_map(|i| i.to_ne_bytes()).collect();
                ("I4".into(), vec![ints.len() as i64], bytes)
            }
            Data::Text(t) => {
                let text = TEXTS[usize::from(*t) % TEXTS.len()];
                ("C1".into(), vec![text.len() as i64], text.as_bytes().to_vec())
            }
            Data::Bytes(b) => ("C1".into(), vec![b.len() as i64], b.clone()),
            Data::Reals(v) => {
                let bytes = v
                    .iter()
                    .flat_map(|&r| (f64::from(r) / 64.0).to_ne_bytes())
                    .collect();
                ("R8".into(), vec![v.len() as i64], bytes)
            }
        }
    }
}

impl Int {
    fn value(self) -> i32 {
        match self {
            Int::Small(v) => i32::from(v),
            Int::Type(t) => [2, 3, 5, 7, 10, 12, 14, 17, 20, 22, 23, 99][usize::from(t) % 12],
            Int::Max => i32::MAX,
            Int::Min => i32::MIN,
            Int::Any(v) => v,
        }
    }
}

/// The nodes of the tree in depth-first order, as paths of child indices.
fn paths(roots: &[Node]) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut stack: Vec<(Vec<usize>, &Node)> = roots
        .iter()
        .enumerate()
        .rev()
        .map(|(i, n)| (vec![i], n))
        .collect();
    while let Some((path, node)) = stack.pop() {
        for (i, c) in node.children.iter().enumerate().rev() {
            let mut p = path.clone();
            p.push(i);
            stack.push((p, c));
        }
        out.push(path);
    }
    out
}

/// The node at `path`.
fn node<'a>(roots: &'a mut [Node], path: &[usize]) -> &'a mut Node {
    let mut n = &mut roots[path[0]];
    for &i in &path[1..] {
        n = &mut n.children[i];
    }
    n
}

/// The depth-first path of an edit's `at`.
fn pick(roots: &[Node], at: u16) -> Option<Vec<usize>> {
    let all = paths(roots);
    (!all.is_empty()).then(|| all[usize::from(at) % all.len()].clone())
}

impl CgnsFile {
    /// The tree's nodes under the root.
    pub fn nodes(&self) -> Vec<Node> {
        let mut roots = nodes::square();
        for edit in self.edits.iter().take(32) {
            apply(&mut roots, edit);
        }
        roots
    }
}

fn apply(roots: &mut Vec<Node>, edit: &Edit) {
    match *edit {
        Edit::Label { at, label } => {
            if let Some(p) = pick(roots, at) {
                node(roots, &p).label = LABELS[usize::from(label) % LABELS.len()].into();
            }
        }
        Edit::Kind { at, kind } => {
            if let Some(p) = pick(roots, at) {
                node(roots, &p).kind = KINDS[usize::from(kind) % KINDS.len()].into();
            }
        }
        Edit::Dims { at, ref dims } => {
            if let Some(p) = pick(roots, at) {
                let n = node(roots, &p);
                n.dims = dims.iter().take(13).map(|d| d.value()).collect();
                n.data.clear();
            }
        }
        Edit::Data { at, ref data } => {
            if let Some(p) = pick(roots, at) {
                let (kind, dims, bytes) = data.bytes();
                let n = node(roots, &p);
                (n.kind, n.dims, n.data) = (kind, dims, bytes);
            }
        }
        Edit::Child {
            at,
            name,
            label,
            kind,
            ref data,
        } => {
            if let Some(p) = pick(roots, at) {
                let (k, dims, bytes) = data.bytes();
                let mut child = Node {
                    name: NAMES[usize::from(name) % NAMES.len()].into(),
                    label: LABELS[usize::from(label) % LABELS.len()].into(),
                    kind: k,
                    dims,
                    data: bytes,
                    ..Node::default()
                };
                if kind % 4 == 0 {
                    child = Node::empty(&child.name, &child.label);
                }
                node(roots, &p).children.push(child);
            }
        }
        Edit::Remove { at } => {
            if let Some(p) = pick(roots, at).filter(|p| p.len() > 1) {
                let (last, parent) = p.split_last().expect("a parent");
                node(roots, parent).children.remove(*last);
            }
        }
        Edit::Copy { from, to } => {
            if let (Some(f), Some(t)) = (pick(roots, from), pick(roots, to)) {
                let copy = node(roots, &f).clone();
                if paths(std::slice::from_ref(&copy)).len() < 64 {
                    node(roots, &t).children.push(copy);
                }
            }
        }
        Edit::Link {
            at,
            name,
            target,
            other_file,
        } => {
            if let Some(p) = pick(roots, at) {
                let file = if other_file { "other.cgns" } else { "" };
                let target = ["/Base/Zone", "/Base", "/", "/Base/Zone/Cells", "/nowhere"]
                    [usize::from(target) % 5];
                node(roots, &p).children.push(Node {
                    name: NAMES[usize::from(name) % NAMES.len()].into(),
                    link: Some((file.into(), target.into())),
                    ..Node::default()
                });
            }
        }
        Edit::Nest { at, depth } => {
            if let Some(p) = pick(roots, at) {
                let mut data = Node::empty("U", "UserDefinedData_t");
                for _ in 0..depth % 64 {
                    data = Node::empty("U", "UserDefinedData_t").with([data]);
                }
                node(roots, &p).children.push(data);
            }
        }
    }
}
