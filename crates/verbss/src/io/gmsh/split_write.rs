//! Writing one file of a split set ([`super::split`]): a piece of a larger
//! mesh as partition `k` of `K`, in the form of `gmsh -part K -part_split`.
//!
//! Every file of the set repeats one model ([`SplitModel`]):
//! `$PhysicalNames`; `$Entities` with the domain (entity 1 of the mesh
//! dimension `D`, the cells' physical group, bounded by entity 1 of
//! dimension `D − 1`, the boundary, which has no physical group) and one
//! entity per physical group of facets (tag `g + 2`, `g` from 0); and
//! `$PartitionedEntities` listing every partition's pieces of these
//! entities ([`SplitEntity`]), each with its parent, its one partition, its
//! bounding box and its parent's physical group. A file's `$Nodes` and
//! `$Elements` hold only its own partition's blocks: the cells on its piece
//! of the domain, the facets of each group on its piece of the group; its
//! nodes on the boundary's piece (the nodes on the mesh's boundary) or on
//! the domain's (the others). A node of several partitions is in each of
//! their files, with one tag. The partitioned reader thus finds the
//! boundary from the entities and the groups from the facets.

use std::io::{self, Write};

use super::model::type_of_kind;
use super::write::{invalid, runs, Out};
use crate::mesh::{Cells, Mesh};

/// A physical group of facets of a split set.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitGroup {
    /// Its name.
    pub name: String,
    /// The dimension of its facets.
    pub dim: usize,
    /// Its physical tag.
    pub physical: i32,
}

/// The model entity a partition entity is a piece of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SplitParent {
    /// The domain: the cells and the nodes inside.
    Domain,
    /// The boundary: the nodes on the mesh's boundary.
    Boundary,
    /// Group `g` of [`SplitModel::groups`]: its facets.
    Group(usize),
}

/// A partition entity: the piece of `parent` in `partition` (from 1), with
/// the bounding box `min x y z, max x y z` of its nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct SplitEntity {
    /// The partition.
    pub partition: usize,
    /// The model entity.
    pub parent: SplitParent,
    /// The bounding box of its nodes.
    pub bbox: [f64; 6],
}

/// What every file of a split set repeats (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct SplitModel {
    /// The mesh dimension.
    pub dim: usize,
    /// The physical groups of facets, entity `g + 2` each.
    pub groups: Vec<SplitGroup>,
    /// The cells' physical tag and name.
    pub domain: (i32, String),
    /// The number of partitions `K`.
    pub partitions: usize,
    /// Every partition's entities, in order of partition and parent.
    pub entities: Vec<SplitEntity>,
}

/// One partition's piece as written: a mesh whose groups are all of the
/// model's groups, at `coords`.
pub struct SplitPiece<'a> {
    /// The cells, group facets, node and cell tags.
    pub mesh: &'a Mesh,
    /// The nodes' coordinates as written.
    pub coords: &'a [f64],
    /// Per node: whether it is on the mesh's boundary.
    pub boundary: &'a [bool],
    /// Per group of `mesh`: its index in [`SplitModel::groups`].
    pub groups: &'a [usize],
    /// Per group of `mesh`: its facets' element tags.
    pub facet_tags: &'a [Vec<u64>],
    /// Its partition (from 1).
    pub partition: usize,
}

impl SplitPiece<'_> {
    /// `x y z` of node `i`.
    fn xyz(&self, i: usize) -> [f64; 3] {
        let d = self.mesh.dim;
        let p = &self.coords[d * i..d * (i + 1)];
        [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
    }

    /// The bounding box of nodes `nodes` (zeros when there is none).
    fn bbox(&self, nodes: impl Iterator<Item = usize>) -> [f64; 6] {
        let mut b = [
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for i in nodes {
            let p = self.xyz(i);
            for k in 0..3 {
                b[k] = b[k].min(p[k]);
                b[k + 3] = b[k + 3].max(p[k]);
            }
        }
        if b[0] > b[3] {
            b = [0.0; 6];
        }
        b
    }

    /// This piece's partition entities: the domain's, the boundary's
    /// where it has boundary nodes, each group's where it has facets.
    pub fn entities(&self) -> Vec<SplitEntity> {
        let n = self.mesh.node_count();
        let entity = |parent, bbox| SplitEntity {
            partition: self.partition,
            parent,
            bbox,
        };
        let mut out = vec![entity(SplitParent::Domain, self.bbox(0..n))];
        if self.boundary.iter().any(|&b| b) {
            let on = (0..n).filter(|&i| self.boundary[i]);
            out.push(entity(SplitParent::Boundary, self.bbox(on)));
        }
        let mut groups: Vec<(usize, &Cells)> = self
            .groups
            .iter()
            .zip(&self.mesh.groups)
            .filter(|(_, g)| !g.facets.is_empty())
            .map(|(&k, g)| (k, &g.facets))
            .collect();
        groups.sort_by_key(|&(k, _)| k);
        for (k, facets) in groups {
            let bbox = self.bbox(facets.nodes.iter().copied());
            out.push(entity(SplitParent::Group(k), bbox));
        }
        out
    }
}

impl SplitModel {
    /// The model entity `(dimension, tag)` of `parent`.
    fn model_entity(&self, parent: SplitParent) -> (usize, i32) {
        match parent {
            SplitParent::Domain => (self.dim, 1),
            SplitParent::Boundary => (self.dim - 1, 1),
            SplitParent::Group(g) => (self.groups[g].dim, g as i32 + 2),
        }
    }

    /// The physical tags of `parent`.
    fn physicals(&self, parent: SplitParent) -> Vec<i32> {
        match parent {
            SplitParent::Domain => vec![self.domain.0],
            SplitParent::Boundary => Vec::new(),
            SplitParent::Group(g) => vec![self.groups[g].physical],
        }
    }

    /// The tag of partition entity `e` of [`SplitModel::entities`]: after
    /// every model entity's.
    fn tag(&self, e: usize) -> i32 {
        (self.groups.len() + 2 + e) as i32
    }

    /// The tag of `partition`'s piece of `parent`.
    fn tag_of(&self, partition: usize, parent: SplitParent) -> Option<i32> {
        self.entities
            .iter()
            .position(|e| e.partition == partition && e.parent == parent)
            .map(|e| self.tag(e))
    }

    /// The union of the bounding boxes of the pieces of `parent`.
    fn bbox(&self, parent: SplitParent) -> [f64; 6] {
        let mut b: Option<[f64; 6]> = None;
        for e in self.entities.iter().filter(|e| e.parent == parent) {
            let u = b.get_or_insert(e.bbox);
            for k in 0..3 {
                u[k] = u[k].min(e.bbox[k]);
                u[k + 3] = u[k + 3].max(e.bbox[k + 3]);
            }
        }
        b.unwrap_or([0.0; 6])
    }
}

/// Writes `piece` as its partition's file of the split set of `model`,
/// MSH 4.1, ASCII or binary (see the module documentation).
pub fn write_split_piece_to(
    w: &mut dyn Write,
    model: &SplitModel,
    piece: &SplitPiece,
    binary: bool,
) -> io::Result<()> {
    let mesh = piece.mesh;
    check(model, piece)?;
    let mut out = Out::new(w, binary);
    out.format("4.1")?;
    names(&mut out, model)?;
    entities(&mut out, model)?;
    partitioned(&mut out, model)?;
    nodes(&mut out, model, piece)?;

    out.text("$Elements\n")?;
    let own = |parent| model.tag_of(piece.partition, parent);
    let domain = own(SplitParent::Domain).ok_or_else(|| {
        invalid(format!(
            "the set's partition entities have no piece of the domain in partition {}",
            piece.partition
        ))
    })?;
    let mut blocks = vec![(mesh.dim, domain, &mesh.cells, mesh.cell_tags.as_slice())];
    for ((g, &k), tags) in mesh.groups.iter().zip(piece.groups).zip(piece.facet_tags) {
        if let Some(tag) = own(SplitParent::Group(k)).filter(|_| !g.facets.is_empty()) {
            blocks.push((model.groups[k].dim, tag, &g.facets, tags.as_slice()));
        }
    }
    let all = blocks.iter().flat_map(|b| b.3.iter().copied());
    let (min, max) = all
        .clone()
        .fold((u64::MAX, 0), |(lo, hi), t| (lo.min(t), hi.max(t)));
    let runs: Vec<_> = blocks.iter().map(|b| runs(b.2)).collect();
    let count = runs.iter().map(Vec::len).sum::<usize>() as u64;
    for v in [count, all.count() as u64, min.min(max), max] {
        out.size(v)?;
    }
    out.end_line()?;
    for ((dim, tag, cells, tags), runs) in blocks.iter().zip(&runs) {
        for &(kind, first, end) in runs {
            out.int(*dim as i32)?;
            out.int(*tag)?;
            out.int(type_of_kind(kind))?;
            out.size((end - first) as u64)?;
            out.end_line()?;
            for c in first..end {
                out.size(tags[c])?;
                for &v in cells.cell(c) {
                    out.size(mesh.node_tags[v])?;
                }
                out.end_line()?;
            }
        }
    }
    out.close("$EndElements")?;
    out.finish()
}

/// Fails where `piece` does not fit `model` or itself.
fn check(model: &SplitModel, piece: &SplitPiece) -> io::Result<()> {
    let mesh = piece.mesh;
    mesh.validate().map_err(|e| invalid(e.to_string()))?;
    let n = mesh.node_count();
    if mesh.dim != model.dim
        || piece.coords.len() != mesh.coords.len()
        || piece.boundary.len() != n
        || piece.groups.len() != mesh.groups.len()
        || piece.facet_tags.len() != mesh.groups.len()
        || piece.partition == 0
        || piece.partition > model.partitions
    {
        return Err(invalid(format!(
            "a piece of {n} nodes and {} groups as partition {} of a {}D set of {} partitions: \
             the sizes do not fit",
            mesh.groups.len(),
            piece.partition,
            model.dim,
            model.partitions
        )));
    }
    for ((g, &k), tags) in mesh.groups.iter().zip(piece.groups).zip(piece.facet_tags) {
        let fits = model.groups.get(k).is_some_and(|m| m.name == g.name);
        if !fits || tags.len() != g.facets.len() {
            return Err(invalid(format!(
                "group '{}' of the piece is not group {k} of the set, or has {} facet tags for \
                 {} facets",
                g.name,
                tags.len(),
                g.facets.len()
            )));
        }
    }
    Ok(())
}

/// `$PhysicalNames`: the groups, then the cells'.
fn names(out: &mut Out, model: &SplitModel) -> io::Result<()> {
    out.text(&format!("$PhysicalNames\n{}\n", model.groups.len() + 1))?;
    for g in &model.groups {
        out.text(&format!("{} {} \"{}\"\n", g.dim, g.physical, g.name))?;
    }
    let (tag, name) = &model.domain;
    out.text(&format!("{} {tag} \"{name}\"\n", model.dim))?;
    out.text("$EndPhysicalNames\n")
}

/// The model's parents by dimension, in order of tag.
fn parents(model: &SplitModel) -> [Vec<SplitParent>; 4] {
    let mut by_dim: [Vec<SplitParent>; 4] = Default::default();
    by_dim[model.dim].push(SplitParent::Domain);
    by_dim[model.dim - 1].push(SplitParent::Boundary);
    for (g, group) in model.groups.iter().enumerate() {
        by_dim[group.dim].push(SplitParent::Group(g));
    }
    by_dim
}

/// An entity's coordinates (a point's `x y z`), physical tags and, above
/// dimension 0, bounding entities.
fn entity_body(
    out: &mut Out,
    dim: usize,
    bbox: &[f64; 6],
    physicals: &[i32],
    bounding: &[i32],
) -> io::Result<()> {
    let coords = if dim == 0 { &bbox[..3] } else { &bbox[..] };
    coords.iter().try_for_each(|&x| out.float(x))?;
    out.size(physicals.len() as u64)?;
    physicals.iter().try_for_each(|&p| out.int(p))?;
    if dim > 0 {
        out.size(bounding.len() as u64)?;
        bounding.iter().try_for_each(|&b| out.int(b))?;
    }
    out.end_line()
}

/// `$Entities`: the domain, bounded by the boundary, and the groups.
fn entities(out: &mut Out, model: &SplitModel) -> io::Result<()> {
    out.text("$Entities\n")?;
    let by_dim = parents(model);
    by_dim.iter().try_for_each(|p| out.size(p.len() as u64))?;
    out.end_line()?;
    for (dim, list) in by_dim.iter().enumerate() {
        for &parent in list {
            out.int(model.model_entity(parent).1)?;
            let bounding: &[i32] = if parent == SplitParent::Domain {
                &[1]
            } else {
                &[]
            };
            let physicals = model.physicals(parent);
            entity_body(out, dim, &model.bbox(parent), &physicals, bounding)?;
        }
    }
    out.close("$EndEntities")
}

/// `$PartitionedEntities`: every partition's pieces, no ghost entity.
fn partitioned(out: &mut Out, model: &SplitModel) -> io::Result<()> {
    out.text("$PartitionedEntities\n")?;
    out.size(model.partitions as u64)?;
    out.end_line()?;
    out.size(0)?;
    out.end_line()?;
    let dim_of = |e: &SplitEntity| model.model_entity(e.parent).0;
    for d in 0..4 {
        out.size(model.entities.iter().filter(|e| dim_of(e) == d).count() as u64)?;
    }
    out.end_line()?;
    for d in 0..4 {
        for (i, e) in model
            .entities
            .iter()
            .enumerate()
            .filter(|(_, e)| dim_of(e) == d)
        {
            let (pd, pt) = model.model_entity(e.parent);
            out.int(model.tag(i))?;
            out.int(pd as i32)?;
            out.int(pt)?;
            out.size(1)?;
            out.int(e.partition as i32)?;
            entity_body(out, d, &e.bbox, &model.physicals(e.parent), &[])?;
        }
    }
    out.close("$EndPartitionedEntities")
}

/// `$Nodes`: the piece's nodes on the boundary's piece, then the others on
/// the domain's.
fn nodes(out: &mut Out, model: &SplitModel, piece: &SplitPiece) -> io::Result<()> {
    out.text("$Nodes\n")?;
    let n = piece.mesh.node_count();
    let tags = &piece.mesh.node_tags;
    let mut blocks = Vec::new();
    for (parent, on) in [(SplitParent::Boundary, true), (SplitParent::Domain, false)] {
        let list: Vec<usize> = (0..n).filter(|&i| piece.boundary[i] == on).collect();
        if let (false, Some(tag)) = (list.is_empty(), model.tag_of(piece.partition, parent)) {
            blocks.push((model.model_entity(parent).0, tag, list));
        }
    }
    let (min, max) = tags
        .iter()
        .fold((u64::MAX, 0), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    for v in [blocks.len() as u64, n as u64, min.min(max), max] {
        out.size(v)?;
    }
    out.end_line()?;
    for (dim, tag, list) in &blocks {
        out.int(*dim as i32)?;
        out.int(*tag)?;
        out.int(0)?;
        out.size(list.len() as u64)?;
        out.end_line()?;
        for &i in list {
            out.size(tags[i])?;
            out.end_line()?;
        }
        for &i in list {
            piece.xyz(i).iter().try_for_each(|&x| out.float(x))?;
            out.end_line()?;
        }
    }
    out.close("$EndNodes")
}
