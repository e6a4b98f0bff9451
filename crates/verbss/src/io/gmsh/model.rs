//! What a Gmsh file holds before it becomes a [`Mesh`]: nodes with their tags,
//! elements sorted by dimension with their physical tags, physical names.

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use super::cursor::{Cursor, Mark};
use crate::error::Result;
use crate::io::MAX_GROUPS;
use crate::mesh::{CellKind, Cells, FileOrigin, Group, Mesh};

/// Element types verbss reads, as Gmsh numbers them: `(type, kind)`.
const TYPES: [(i32, CellKind); 8] = [
    (15, CellKind::Vertex),
    (1, CellKind::Line),
    (2, CellKind::Triangle),
    (3, CellKind::Quad),
    (4, CellKind::Tetra),
    (5, CellKind::Hexahedron),
    (6, CellKind::Wedge),
    (7, CellKind::Pyramid),
];

/// The kind of Gmsh element type `t`, or the error message for an unsupported one.
pub(super) fn kind_of_type(t: i32) -> std::result::Result<CellKind, String> {
    TYPES
        .iter()
        .find(|(n, _)| *n == t)
        .map(|&(_, k)| k)
        .ok_or_else(|| {
            format!(
                "element type {t} is not supported (verbss reads the linear types 15 point, \
             1 line, 2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron, 6 prism, 7 pyramid)"
            )
        })
}

/// The Gmsh element type number of `kind`.
pub(super) fn type_of_kind(kind: CellKind) -> i32 {
    TYPES
        .iter()
        .find(|(_, k)| *k == kind)
        .map_or(0, |&(t, _)| t)
}

/// The message for a node or element tag 0.
pub(super) fn zero_tag(what: &str) -> String {
    format!("{what} tag 0 is not allowed (tags start at 1)")
}

/// The message for an element node tag that no node has.
pub(super) fn unknown_node(element: u64, node: impl std::fmt::Display) -> String {
    format!("element {element} refers to node {node}, which $Nodes does not define")
}

/// Physical names by `(dimension, physical tag)`.
pub(super) type Names = HashMap<(usize, i32), String>;

/// The nodes of the file in file order, with their coordinates in 3D.
#[derive(Default)]
pub(super) struct Nodes {
    /// Gmsh tag of each node.
    pub tags: Vec<u64>,
    /// `x y z` of each node.
    pub xyz: Vec<f64>,
    /// Byte range of each node's `x y z` in the file.
    pub spans: Vec<Range<usize>>,
    /// The first node with `z ≠ 0`: its tag, its `z` and where it was read.
    off_plane: Option<(u64, f64, Mark)>,
}

impl Nodes {
    /// Room for `n` more nodes.
    pub fn reserve(&mut self, n: usize) {
        self.tags.reserve(n);
        self.xyz.reserve(3 * n);
        self.spans.reserve(n);
    }

    /// Adds node `tag` at `p`, read from `mark` (the start of `x`) to byte
    /// `end` (the end of `z`); rejects non-finite coordinates.
    pub fn push(
        &mut self,
        c: &Cursor,
        mark: Mark,
        end: usize,
        tag: u64,
        p: [f64; 3],
    ) -> Result<()> {
        if let Some(v) = p.iter().find(|v| !v.is_finite()) {
            return Err(c.error_at(
                mark,
                format!("node {tag} has a non-finite coordinate ({v})"),
            ));
        }
        if p[2] != 0.0 && self.off_plane.is_none() {
            self.off_plane = Some((tag, p[2], mark));
        }
        self.tags.push(tag);
        self.xyz.extend_from_slice(&p);
        self.spans.push(mark.offset..end);
        Ok(())
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.tags.len()
    }

    /// Appends node `i` of `from`.
    pub fn push_from(&mut self, from: &Nodes, i: usize) {
        let (tag, p) = (from.tags[i], &from.xyz[3 * i..3 * i + 3]);
        if p[2] != 0.0 && self.off_plane.is_none() {
            let mark = Mark {
                offset: from.spans[i].start,
                line: 0,
            };
            self.off_plane = Some((tag, p[2], mark));
        }
        self.tags.push(tag);
        self.xyz.extend_from_slice(p);
        self.spans.push(from.spans[i].clone());
    }
}

/// Node tag → node index: a table when tags are dense enough, a hash map otherwise.
pub(super) enum NodeIndex {
    /// `table[tag]` is the index, `usize::MAX` where no node has the tag.
    Dense(Vec<usize>),
    /// Sparse tags.
    Sparse(HashMap<u64, usize>),
}

impl NodeIndex {
    /// Indexes `tags`; fails with the first tag given twice.
    pub fn build(tags: &[u64]) -> std::result::Result<NodeIndex, u64> {
        let max = tags.iter().copied().max().unwrap_or(0);
        if max <= 2 * tags.len() as u64 + 1024 {
            let mut table = vec![usize::MAX; max as usize + 1];
            for (i, &t) in tags.iter().enumerate() {
                if table[t as usize] != usize::MAX {
                    return Err(t);
                }
                table[t as usize] = i;
            }
            Ok(NodeIndex::Dense(table))
        } else {
            let mut map = HashMap::with_capacity(tags.len());
            for (i, &t) in tags.iter().enumerate() {
                if map.insert(t, i).is_some() {
                    return Err(t);
                }
            }
            Ok(NodeIndex::Sparse(map))
        }
    }

    /// The index of the node with `tag`.
    #[inline]
    pub fn get(&self, tag: u64) -> Option<usize> {
        match self {
            NodeIndex::Dense(table) => usize::try_from(tag)
                .ok()
                .and_then(|t| table.get(t))
                .copied()
                .filter(|&i| i != usize::MAX),
            NodeIndex::Sparse(map) => map.get(&tag).copied(),
        }
    }
}

/// Elements of one dimension, in file order, with runs of equal physical tags.
struct Bucket {
    cells: Cells,
    tags: Vec<u64>,
    /// `(first element, physical tags)` of each run; elements before the
    /// first run carry no physical tag.
    runs: Vec<(usize, Range<usize>)>,
}

impl Default for Bucket {
    fn default() -> Self {
        Bucket {
            cells: Cells::new(),
            tags: Vec::new(),
            runs: Vec::new(),
        }
    }
}

/// All elements of the file, sorted into buckets by dimension 0–3.
#[derive(Default)]
pub(super) struct Elements {
    buckets: [Bucket; 4],
    /// Physical tags of all runs, concatenated.
    physicals: Vec<i32>,
    /// `(dimension, physical tag)` pairs in order of first appearance.
    order: Vec<(usize, i32)>,
    seen: HashSet<(usize, i32)>,
    /// The `(dimension, range)`s of `physicals` already in `order`.
    listed: HashSet<(usize, Range<usize>)>,
    /// Where each single tag of [`Elements::set_physical`] is in `physicals`.
    single: HashMap<i32, usize>,
    /// How many `(dimension, physical tag)` pairs of each dimension `order` holds.
    groups: [usize; 4],
}

impl Elements {
    /// Room for `n` more elements of `kind`.
    pub fn reserve(&mut self, kind: CellKind, n: usize) {
        let b = &mut self.buckets[kind.dim()];
        b.cells.kinds.reserve(n);
        b.cells.offsets.reserve(n);
        b.cells.nodes.reserve(n * kind.node_count());
        b.tags.reserve(n);
    }

    /// No elements yet; runs will be ranges of `physicals` (MSH 4.1: the
    /// tags of all entities, so a block copies none).
    pub fn with_physicals(physicals: Vec<i32>) -> Self {
        Elements {
            physicals,
            ..Default::default()
        }
    }

    /// The elements of dimension `dim` pushed from now on carry the one
    /// physical tag `physical`, or none when it is 0 (MSH 2.2).
    pub fn set_physical(&mut self, dim: usize, physical: i32) -> std::result::Result<(), String> {
        let range = match physical {
            0 => 0..0,
            p => {
                let next = self.physicals.len();
                let start = *self.single.entry(p).or_insert(next);
                if start == next {
                    self.physicals.push(p);
                }
                start..start + 1
            }
        };
        self.set_run(dim, range)
    }

    /// The elements of dimension `dim` pushed from now on carry
    /// `physicals[range]` (of [`Elements::with_physicals`]); fails when a
    /// dimension gets more than [`MAX_GROUPS`] physical groups.
    pub fn set_run(&mut self, dim: usize, range: Range<usize>) -> std::result::Result<(), String> {
        let b = &mut self.buckets[dim];
        let same = match b.runs.last() {
            None => range.is_empty(),
            Some((_, r)) => *r == range || (r.is_empty() && range.is_empty()),
        };
        if same {
            return Ok(());
        }
        b.runs.push((b.cells.len(), range.clone()));
        if self.listed.insert((dim, range.clone())) {
            for &p in &self.physicals[range] {
                if self.seen.insert((dim, p)) {
                    if self.groups[dim] == MAX_GROUPS {
                        return Err(format!(
                            "more than {MAX_GROUPS} physical groups of dimension {dim} \
                             (the most verbss reads)"
                        ));
                    }
                    self.groups[dim] += 1;
                    self.order.push((dim, p));
                }
            }
        }
        Ok(())
    }

    /// Appends element `tag` of `kind` on node indices `nodes`.
    #[inline]
    pub fn push(&mut self, kind: CellKind, tag: u64, nodes: &[usize]) {
        let b = &mut self.buckets[kind.dim()];
        b.cells.push(kind, nodes);
        b.tags.push(tag);
    }
}

/// What a file says about its mesh beyond [`Mesh`], for writing it anew.
#[derive(Default)]
pub(super) struct Structure {
    /// The physical group of the cells (tag and name), when they have exactly one.
    pub domain: Option<(i32, String)>,
    /// The element tag of each facet of each group.
    pub facet_tags: Vec<Vec<u64>>,
}

/// Assembles the mesh: the elements of the highest dimension become the
/// cells, lower ones with physical tags the groups; also returns the cells'
/// physical group when they have exactly one.
///
/// `copies`: MSH 2 writes an element once per physical group it belongs to;
/// consecutive identical cells are then one cell. `end` locates errors that
/// concern the file as a whole, the `$Elements` mark those of
/// [`Mesh::validate`].
pub(super) fn finish(
    c: &Cursor,
    nodes: Nodes,
    (mut elements, at): (Elements, Mark),
    names: &Names,
    copies: bool,
    end: Mark,
) -> Result<(Mesh, Structure)> {
    let Some(dim) = (0..4)
        .rev()
        .find(|&d| !elements.buckets[d].cells.is_empty())
    else {
        return Err(c.error_at(end, "the file has no elements"));
    };
    if dim < 2 {
        return Err(c.error_at(
            end,
            format!("the file has no 2D or 3D elements (highest element dimension: {dim})"),
        ));
    }
    let mut coords = nodes.xyz;
    if dim == 2 {
        if let Some((tag, z, mark)) = nodes.off_plane {
            return Err(c.error_at(
                mark,
                format!(
                    "node {tag} has z = {z}, but a mesh without 3D elements must lie in the \
                     plane z = 0 (a surface mesh in 3D space is not a planar 2D mesh)"
                ),
            ));
        }
        // x y z to x y, in place.
        let n = coords.len() / 3;
        for i in 0..n {
            coords.copy_within(3 * i..3 * i + 2, 2 * i);
        }
        coords.truncate(2 * n);
        coords.shrink_to_fit();
    }
    let top = std::mem::take(&mut elements.buckets[dim]);
    let (cells, cell_tags) = if copies {
        drop_copies(top.cells, top.tags)
    } else {
        (top.cells, top.tags)
    };
    if let Some(t) = repeated(&cell_tags) {
        return Err(c.error_at(end, format!("element tag {t} is used by two elements")));
    }
    check_copies(c, &elements, dim, end)?;
    let groups: usize = elements.groups[..dim].iter().sum();
    if groups > MAX_GROUPS {
        return Err(c.error_at(
            end,
            format!("{groups} physical groups below dimension {dim}, more than {MAX_GROUPS} (the most verbss reads)"),
        ));
    }
    let mut index = HashMap::new();
    let mut groups: Vec<Group> = Vec::new();
    let mut facet_tags: Vec<Vec<u64>> = Vec::new();
    for &(d, p) in elements.order.iter().filter(|(d, _)| *d < dim) {
        index.insert((d, p), groups.len());
        groups.push(Group {
            name: names.get(&(d, p)).cloned().unwrap_or_else(|| p.to_string()),
            tag: Some(p),
            facets: Cells::new(),
        });
        facet_tags.push(Vec::new());
    }
    for (d, b) in elements.buckets[..dim].iter().enumerate() {
        for (r, (start, phys)) in b.runs.iter().enumerate() {
            let end = b.runs.get(r + 1).map_or(b.cells.len(), |(s, _)| *s);
            for p in &elements.physicals[phys.clone()] {
                let g = index[&(d, *p)];
                for e in *start..end {
                    groups[g].facets.push(b.cells.kinds[e], b.cells.cell(e));
                    facet_tags[g].push(b.tags[e]);
                }
            }
        }
    }
    let mesh = Mesh {
        dim,
        coords,
        node_tags: nodes.tags,
        cells,
        cell_tags,
        groups,
        origin: FileOrigin::default(),
    };
    mesh.validate()
        .map_err(|e| crate::io::invalid_at(e, |m| c.error_at(at, m)))?;
    let domain = match elements
        .order
        .iter()
        .filter(|(d, _)| *d == dim)
        .collect::<Vec<_>>()[..]
    {
        [&(d, p)] => Some((
            p,
            names.get(&(d, p)).cloned().unwrap_or_else(|| p.to_string()),
        )),
        _ => None,
    };
    Ok((mesh, Structure { domain, facet_tags }))
}

/// Fails when the groups would hold more than 8 copies per element of a
/// dimension below `dim` (plus 2^20): each element is copied into each
/// physical group of its entity.
fn check_copies(c: &Cursor, elements: &Elements, dim: usize, end: Mark) -> Result<()> {
    let (mut count, mut copies) = (0usize, 0usize);
    for b in &elements.buckets[..dim] {
        count += b.cells.len();
        for (r, (start, phys)) in b.runs.iter().enumerate() {
            let end = b.runs.get(r + 1).map_or(b.cells.len(), |(s, _)| *s);
            copies = copies.saturating_add((end - start).saturating_mul(phys.len()));
        }
    }
    let limit = count.saturating_mul(8).saturating_add(1 << 20);
    if copies > limit {
        return Err(c.error_at(
            end,
            format!(
                "the physical groups would hold {copies} elements, more than {limit} \
                 (8 per element of dimension below {dim}, plus 1048576): too many \
                 physical tags per entity"
            ),
        ));
    }
    Ok(())
}

/// Removes each cell identical (same kind, same nodes) to the one before it.
fn drop_copies(cells: Cells, tags: Vec<u64>) -> (Cells, Vec<u64>) {
    let same = |e: usize| {
        e > 0 && cells.kinds[e] == cells.kinds[e - 1] && cells.cell(e) == cells.cell(e - 1)
    };
    if !(0..cells.len()).any(same) {
        return (cells, tags);
    }
    let mut kept = Cells::new();
    let mut kept_tags = Vec::new();
    for e in (0..cells.len()).filter(|&e| !same(e)) {
        kept.push(cells.kinds[e], cells.cell(e));
        kept_tags.push(tags[e]);
    }
    (kept, kept_tags)
}

/// A value that occurs twice in `tags`, if any.
fn repeated(tags: &[u64]) -> Option<u64> {
    if tags.windows(2).all(|w| w[0] < w[1]) {
        return None;
    }
    let mut sorted = tags.to_vec();
    sorted.sort_unstable();
    sorted.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
}
