//! The mesh model: flat coordinates, cells as kind + offsets + node indices,
//! named boundary groups with their facets.

mod faces;
mod interface;
mod kind;
pub mod kinds;
pub mod samples;

pub use faces::{FaceList, Faces, Local};
pub use interface::{Coupling, Interface, Transform};
pub use kind::{CellKind, KindTable};

use std::collections::hash_map::{DefaultHasher, Entry};
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

use crate::error::{Error, Result};

/// A list of cells of mixed kinds in compressed form: cell `c` has kind
/// `kinds[c]` and nodes `nodes[offsets[c]..offsets[c + 1]]` (0-based node
/// indices); a polyhedron's faces are in `faces`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Cells {
    /// Kind of each cell.
    pub kinds: Vec<CellKind>,
    /// Start of each cell's node list in `nodes`, plus the end: `len() + 1` entries.
    pub offsets: Vec<usize>,
    /// Node indices of all cells, concatenated.
    pub nodes: Vec<usize>,
    /// The faces of the polyhedra (local node indices, outward).
    pub faces: Faces,
}

impl Cells {
    /// An empty list.
    pub fn new() -> Self {
        Cells {
            kinds: Vec::new(),
            offsets: vec![0],
            nodes: Vec::new(),
            faces: Faces::default(),
        }
    }

    /// Appends one cell of a fixed kind, or a polygon (nodes in cyclic
    /// order); a polyhedron goes through [`Cells::push_polyhedron`].
    pub fn push(&mut self, kind: CellKind, nodes: &[usize]) {
        debug_assert!(kind == CellKind::Polygon || nodes.len() == kind.node_count());
        self.kinds.push(kind);
        self.nodes.extend_from_slice(nodes);
        self.offsets.push(self.nodes.len());
    }

    /// Appends a polyhedron given by its faces, each a list of node indices
    /// counter-clockwise seen from outside: its nodes are the faces' nodes
    /// in the order they first appear.
    pub fn push_polyhedron<'a>(&mut self, faces: impl IntoIterator<Item = &'a [usize]> + Clone) {
        let mut nodes: Vec<usize> = Vec::new();
        for face in faces.clone() {
            for &v in face {
                if !nodes.contains(&v) {
                    nodes.push(v);
                }
            }
        }
        self.push_polyhedron_on(&nodes, faces)
            .expect("every face node is listed");
    }

    /// Appends the polyhedron of nodes `nodes` (distinct) and faces `faces`
    /// (node indices, counter-clockwise seen from outside); the first face
    /// node not among `nodes`, if any, is refused.
    pub fn push_polyhedron_on<'a>(
        &mut self,
        nodes: &[usize],
        faces: impl IntoIterator<Item = &'a [usize]>,
    ) -> std::result::Result<(), usize> {
        let mut local: Vec<Vec<usize>> = Vec::new();
        for face in faces {
            let mut l = Vec::with_capacity(face.len());
            for &v in face {
                l.push(nodes.iter().position(|&u| u == v).ok_or(v)?);
            }
            local.push(l);
        }
        self.faces
            .push(self.kinds.len(), local.iter().map(Vec::as_slice));
        self.kinds.push(CellKind::Polyhedron);
        self.nodes.extend_from_slice(nodes);
        self.offsets.push(self.nodes.len());
        Ok(())
    }

    /// Appends cell `c` of `other` with its nodes mapped by `map`.
    pub fn push_from(&mut self, other: &Cells, c: usize, map: impl Fn(usize) -> usize) {
        let nodes: Vec<usize> = other.cell(c).iter().map(|&v| map(v)).collect();
        if let Some(faces) = other.faces.of(c) {
            self.faces.push(self.kinds.len(), faces.iter());
        }
        self.kinds.push(other.kinds[c]);
        self.nodes.extend_from_slice(&nodes);
        self.offsets.push(self.nodes.len());
    }

    /// The local topology (edges, facets) of cell `c`.
    pub fn local(&self, c: usize) -> Local<'_> {
        Local::of(
            self.kinds[c],
            self.offsets[c + 1] - self.offsets[c],
            self.faces.of(c),
        )
    }

    /// The first cell of a general kind (polygon or polyhedron), if any.
    pub fn first_general(&self) -> Option<usize> {
        self.kinds.iter().position(|k| k.is_general())
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// The nodes of cell `c`.
    pub fn cell(&self, c: usize) -> &[usize] {
        &self.nodes[self.offsets[c]..self.offsets[c + 1]]
    }

    /// Iterates over `(kind, nodes)` of every cell.
    pub fn iter(&self) -> impl Iterator<Item = (CellKind, &[usize])> + '_ {
        (0..self.len()).map(move |c| (self.kinds[c], self.cell(c)))
    }
}

/// The most nodes a cell of a fixed kind has (the hexahedron's 8): a
/// [`CellNodes`] holds this many in place.
pub const MAX_CELL_NODES: usize = 8;

/// A solver's copy of [`Cells`] with 32-bit offsets and node indices: 21
/// bytes a tetrahedron instead of 41.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct CompactCells {
    /// Kind of each cell.
    pub kinds: Vec<CellKind>,
    offsets: Vec<u32>,
    nodes: Vec<u32>,
    faces: Faces,
}

impl CompactCells {
    /// The cells `order[0], order[1], …` of `cells`, in that order (a mesh
    /// has fewer than 2³² nodes and node references, as the graphs assume).
    pub fn ordered(cells: &Cells, order: impl ExactSizeIterator<Item = usize>) -> CompactCells {
        let mut compact = CompactCells {
            kinds: Vec::with_capacity(order.len()),
            offsets: Vec::with_capacity(order.len() + 1),
            nodes: Vec::new(),
            faces: Faces::default(),
        };
        compact.offsets.push(0);
        for (k, c) in order.enumerate() {
            if let Some(faces) = cells.faces.of(c) {
                compact.faces.push(k, faces.iter());
            }
            compact.kinds.push(cells.kinds[c]);
            compact
                .nodes
                .extend(cells.cell(c).iter().map(|&v| v as u32));
            compact.offsets.push(compact.nodes.len() as u32);
        }
        compact
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether there is no cell.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// The nodes of cell `c`, widened to indices (held in place up to
    /// [`MAX_CELL_NODES`], on the heap for a larger polyhedron).
    pub fn cell(&self, c: usize) -> CellNodes {
        let stored = &self.nodes[self.offsets[c] as usize..self.offsets[c + 1] as usize];
        let mut nodes = [0; MAX_CELL_NODES];
        let mut wide = Vec::new();
        if stored.len() > MAX_CELL_NODES {
            wide.extend(stored.iter().map(|&v| v as usize));
        } else {
            for (n, &v) in nodes.iter_mut().zip(stored) {
                *n = v as usize;
            }
        }
        CellNodes {
            nodes,
            len: stored.len(),
            wide,
        }
    }

    /// The local topology (edges, facets) of cell `c`.
    pub fn local(&self, c: usize) -> Local<'_> {
        let n = (self.offsets[c + 1] - self.offsets[c]) as usize;
        Local::of(self.kinds[c], n, self.faces.of(c))
    }
}

/// The nodes of one cell of [`CompactCells`]; dereferences to `&[usize]`.
#[derive(Debug, Clone)]
pub struct CellNodes {
    nodes: [usize; MAX_CELL_NODES],
    len: usize,
    wide: Vec<usize>,
}

impl std::ops::Deref for CellNodes {
    type Target = [usize];

    fn deref(&self) -> &[usize] {
        if self.len > MAX_CELL_NODES {
            &self.wide
        } else {
            &self.nodes[..self.len]
        }
    }
}

/// A named boundary group (a Gmsh physical group, an SU2 marker): its facets.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Group {
    /// The group's name.
    pub name: String,
    /// The physical tag the file gave it, if any (Gmsh).
    pub tag: Option<i32>,
    /// The group's facets (lines in 2D, triangles/quads in 3D, or single vertices).
    pub facets: Cells,
}

impl Group {
    /// The distinct nodes of the group, sorted.
    pub fn nodes(&self) -> Vec<usize> {
        let mut nodes = self.facets.nodes.clone();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

/// An unstructured 2D or 3D hybrid mesh.
///
/// Node `i` has coordinates `coords[D*i..D*i+D]`. Node and cell order are the
/// file's order; `node_tags`/`cell_tags` keep the file's own numbers (Gmsh tags,
/// SU2 indices + 1) so that a mesh is written back with the numbering it was read with.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// Spatial dimension, 2 or 3.
    pub dim: usize,
    /// Node coordinates, `dim` numbers per node.
    pub coords: Vec<f64>,
    /// The file's number of each node (≥ 1).
    pub node_tags: Vec<u64>,
    /// The volume cells (cells of dimension `dim`).
    pub cells: Cells,
    /// The file's number of each cell (≥ 1).
    pub cell_tags: Vec<u64>,
    /// Named boundary groups.
    pub groups: Vec<Group>,
    /// What the writers keep of the file the mesh was read from (empty for
    /// a mesh built in memory).
    pub origin: FileOrigin,
}

/// What the writers keep of the file a mesh was read from, by format; all
/// empty for a mesh built in memory or read from a VTU file.
#[derive(Debug, Clone, Default)]
pub struct FileOrigin {
    /// The sections of the SU2 file that verbss does not use (FFD boxes,
    /// periodic data, …), verbatim: writing the mesh as SU2 puts them back.
    pub su2_skipped: Vec<crate::io::su2::Skipped>,
    /// The Gmsh file: writing the mesh back in the same MSH version and
    /// encoding, with its nodes, cells, tags and groups unchanged, changes
    /// only the coordinates in it.
    pub gmsh: Option<Arc<crate::io::gmsh::Source>>,
    /// The CGNS file: writing the mesh as CGNS copies that file and replaces
    /// only its coordinates.
    pub cgns: Option<crate::io::cgns::Source>,
    /// The OpenFOAM polyMesh, which writing the mesh as a case keeps (all but
    /// its points).
    pub foam: Option<Box<crate::io::foam::Origin>>,
    /// Whether the file's convention fixes every cell's orientation
    /// (OpenFOAM: a face's normal points out of its owner), so that each
    /// cell as read is positively oriented by definition, whatever its
    /// shape ([`crate::quality::orientation`]).
    pub oriented: bool,
    /// The interfaces the file declares between its groups (OpenFOAM's
    /// coupled patches): what `deform` accepts of their coincident nodes
    /// and keeps of their transforms.
    pub interfaces: Vec<Interface>,
}

/// Two meshes are equal when everything but the file they came from is
/// (the SU2 sections kept for writing included).
impl PartialEq for Mesh {
    fn eq(&self, other: &Mesh) -> bool {
        self.dim == other.dim
            && self.coords == other.coords
            && self.node_tags == other.node_tags
            && self.cells == other.cells
            && self.cell_tags == other.cell_tags
            && self.groups == other.groups
            && self.origin.su2_skipped == other.origin.su2_skipped
    }
}

impl Mesh {
    /// A mesh with tags `1..=n` for nodes and cells, checked with [`Mesh::validate`].
    pub fn new(dim: usize, coords: Vec<f64>, cells: Cells, groups: Vec<Group>) -> Result<Mesh> {
        let n = coords.len().checked_div(dim).unwrap_or(0);
        let mesh = Mesh {
            dim,
            node_tags: (1..=n as u64).collect(),
            cell_tags: (1..=cells.len() as u64).collect(),
            coords,
            cells,
            groups,
            origin: FileOrigin::default(),
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.coords.len() / self.dim
    }

    /// The diagonal of the nodes' bounding box, `|max − min|` (0 for no node).
    pub fn diagonal(&self) -> f64 {
        let mut lo = vec![f64::INFINITY; self.dim];
        let mut hi = vec![f64::NEG_INFINITY; self.dim];
        for p in self.coords.chunks(self.dim) {
            for d in 0..self.dim {
                (lo[d], hi[d]) = (lo[d].min(p[d]), hi[d].max(p[d]));
            }
        }
        lo.iter()
            .zip(&hi)
            .map(|(a, b)| if b >= a { (b - a) * (b - a) } else { 0.0 })
            .sum::<f64>()
            .sqrt()
    }

    /// Number of volume cells.
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Coordinates of node `i`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.coords[self.dim * i..self.dim * (i + 1)]
    }

    /// The group called `name`, or an error listing the groups that exist
    /// (or, for a mesh without any, saying how Gmsh adds them).
    pub fn group(&self, name: &str) -> Result<&Group> {
        self.groups.iter().find(|g| g.name == name).ok_or_else(|| {
            let name = name.to_string();
            if self.groups.is_empty() {
                Error::NoGroups {
                    name,
                    dim: self.dim,
                }
            } else {
                Error::UnknownGroup {
                    name,
                    available: self.group_names().join(", "),
                }
            }
        })
    }

    /// Names of all groups, in file order.
    pub fn group_names(&self) -> Vec<String> {
        self.groups.iter().map(|g| g.name.clone()).collect()
    }

    /// Checks the structural invariants: dimension 2 or 3, finite coordinates,
    /// tags as many as nodes/cells, cells of dimension `dim` with the right node
    /// count, facets of lower dimension, every node index in range.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidMesh(m));
        if self.dim != 2 && self.dim != 3 {
            return bad(format!("dimension {} (expected 2 or 3)", self.dim));
        }
        if !self.coords.len().is_multiple_of(self.dim) {
            return bad(format!(
                "{} coordinates is not a multiple of the dimension {}",
                self.coords.len(),
                self.dim
            ));
        }
        let n = self.node_count();
        if let Some(i) = self.coords.iter().position(|x| !x.is_finite()) {
            return bad(format!("node {} has a non-finite coordinate", i / self.dim));
        }
        if self.node_tags.len() != n {
            return bad(format!(
                "{} node tags for {} nodes",
                self.node_tags.len(),
                n
            ));
        }
        if self.cell_tags.len() != self.cells.len() {
            return bad(format!(
                "{} cell tags for {} cells",
                self.cell_tags.len(),
                self.cells.len()
            ));
        }
        check_cells(&self.cells, n, "cell", |k| k.dim() == self.dim)?;
        if let Some((a, b)) = repeated_cell(&self.cells) {
            return bad(format!(
                "elements {} and {} have the same nodes (a duplicated element)",
                self.cell_tags[a], self.cell_tags[b]
            ));
        }
        for g in &self.groups {
            check_cells(&g.facets, n, &format!("group '{}' facet", g.name), |k| {
                k.dim() < self.dim
            })?;
        }
        Ok(())
    }
}

/// Two cells with the same node set, if any (found by a hash of the sorted
/// nodes, then compared).
fn repeated_cell(cells: &Cells) -> Option<(usize, usize)> {
    let sorted = |c: usize| {
        let mut key = cells.cell(c).to_vec();
        key.sort_unstable();
        key
    };
    let mut first = HashMap::with_capacity(cells.len());
    let mut key = [usize::MAX; MAX_CELL_NODES];
    for c in 0..cells.len() {
        let nodes = cells.cell(c);
        let mut h = DefaultHasher::new();
        if nodes.len() <= MAX_CELL_NODES {
            key.fill(usize::MAX);
            key[..nodes.len()].copy_from_slice(nodes);
            key.sort_unstable();
            key.hash(&mut h);
        } else {
            sorted(c).hash(&mut h);
        }
        match first.entry(h.finish()) {
            Entry::Vacant(e) => {
                e.insert(c);
            }
            Entry::Occupied(e) if sorted(*e.get()) == sorted(c) => return Some((*e.get(), c)),
            Entry::Occupied(_) => {}
        }
    }
    None
}

fn check_cells(
    cells: &Cells,
    n: usize,
    what: &str,
    kind_ok: impl Fn(CellKind) -> bool,
) -> Result<()> {
    if cells.offsets.len() != cells.len() + 1 || cells.offsets.last() != Some(&cells.nodes.len()) {
        return Err(Error::InvalidMesh(format!(
            "{what} offsets are inconsistent"
        )));
    }
    for (c, (kind, nodes)) in cells.iter().enumerate() {
        if !kind_ok(kind) {
            return Err(Error::InvalidMesh(format!(
                "{what} {c} is a {} of the wrong dimension",
                kind.name()
            )));
        }
        if let Some(&bad) = nodes.iter().find(|&&i| i >= n) {
            return Err(Error::InvalidMesh(format!(
                "{what} {c} uses node {bad} but the mesh has {n} nodes"
            )));
        }
        let shape = match kind {
            CellKind::Polygon => polygon_shape(nodes),
            CellKind::Polyhedron => polyhedron_shape(nodes, cells.faces.of(c)),
            _ if nodes.len() != kind.node_count() => Err(format!(
                "has {} nodes (expected {})",
                nodes.len(),
                kind.node_count()
            )),
            _ => Ok(()),
        };
        if let Err(why) = shape {
            return Err(Error::InvalidMesh(format!(
                "{what} {c} ({}) {why}",
                kind.name()
            )));
        }
    }
    Ok(())
}

/// Why the nodes of a polygon do not make one: fewer than 3, or a node twice.
fn polygon_shape(nodes: &[usize]) -> std::result::Result<(), String> {
    if nodes.len() < 3 {
        return Err(format!("has {} nodes (expected 3 or more)", nodes.len()));
    }
    let mut sorted = nodes.to_vec();
    sorted.sort_unstable();
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Err("has a node twice".into());
    }
    Ok(())
}

/// Why the faces of a polyhedron do not close it: fewer than 4 faces, a
/// face of fewer than 3 nodes, a node on no face, or a side `a → b` of a
/// face that no other face runs back `b → a` exactly once (an open or
/// inconsistently oriented surface).
fn polyhedron_shape(nodes: &[usize], faces: Option<FaceList>) -> std::result::Result<(), String> {
    let Some(faces) = faces else {
        return Err("has no faces".into());
    };
    if faces.len() < 4 {
        return Err(format!("has {} faces (expected 4 or more)", faces.len()));
    }
    let mut sides = Vec::new();
    let mut used = vec![false; nodes.len()];
    for (f, face) in faces.iter().enumerate() {
        if face.len() < 3 || face.iter().any(|&l| l >= nodes.len()) {
            return Err(format!(
                "has a face ({f}) of fewer than 3 nodes or out of its nodes"
            ));
        }
        for k in 0..face.len() {
            used[face[k]] = true;
            sides.push((face[k], face[(k + 1) % face.len()]));
        }
    }
    if let Some(l) = used.iter().position(|&u| !u) {
        return Err(format!("has node {} on none of its faces", nodes[l]));
    }
    sides.sort_unstable();
    if sides.windows(2).any(|w| w[0] == w[1]) {
        return Err(
            "has two faces that run along one side the same way (faces not oriented \
                    consistently outward)"
                .into(),
        );
    }
    if let Some(&(a, b)) = sides
        .iter()
        .find(|&&(a, b)| sides.binary_search(&(b, a)).is_err())
    {
        return Err(format!(
            "is not closed: its side {}-{} belongs to one face only",
            nodes[a], nodes[b]
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Mesh {
        let mut cells = Cells::new();
        cells.push(CellKind::Triangle, &[0, 1, 2]);
        cells.push(CellKind::Triangle, &[0, 2, 3]);
        let mut facets = Cells::new();
        facets.push(CellKind::Line, &[0, 1]);
        let g = Group {
            name: "bottom".into(),
            tag: None,
            facets,
        };
        Mesh::new(2, vec![0., 0., 1., 0., 1., 1., 0., 1.], cells, vec![g]).unwrap()
    }

    #[test]
    fn builds_and_counts() {
        let m = square();
        assert_eq!(m.node_count(), 4);
        assert_eq!(m.cell_count(), 2);
        assert_eq!(m.point(2), &[1.0, 1.0]);
        assert_eq!(m.group("bottom").unwrap().nodes(), vec![0, 1]);
    }

    #[test]
    fn a_mesh_without_groups_says_how_gmsh_adds_them() {
        let mut m = square();
        m.groups.clear();
        assert_eq!(
            m.group("wall").unwrap_err().to_string(),
            "unknown group 'wall': the mesh has no boundary groups. A Gmsh mesh gets them from \
             physical groups: add `Physical Curve(\"wall\") = {1, 2};` to the .geo file, or \
             call `gmsh.model.addPhysicalGroup(1, [1, 2], name=\"wall\")` in Python, with the \
             tags of the curves on that boundary, and mesh again"
        );
        m.dim = 3;
        let e = m.group("wall").unwrap_err().to_string();
        assert!(e.contains("`Physical Surface(\"wall\") = {1, 2};`"), "{e}");
        assert!(e.contains("addPhysicalGroup(2, [1, 2]"), "{e}");
    }

    #[test]
    fn unknown_group_lists_the_groups() {
        let e = square().group("wing").unwrap_err();
        assert_eq!(e.to_string(), "unknown group 'wing' (the mesh has: bottom)");
    }

    #[test]
    fn rejects_out_of_range_node() {
        let mut m = square();
        m.cells.nodes[5] = 9;
        assert_eq!(
            m.validate().unwrap_err().to_string(),
            "invalid mesh: cell 1 uses node 9 but the mesh has 4 nodes"
        );
    }

    #[test]
    fn rejects_nan() {
        let mut m = square();
        m.coords[3] = f64::NAN;
        assert_eq!(
            m.validate().unwrap_err().to_string(),
            "invalid mesh: node 1 has a non-finite coordinate"
        );
    }
}
