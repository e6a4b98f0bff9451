//! MSH 4.1: `$Nodes` and `$Elements`
//! come in blocks, one per (entity, element type); binary counts and tags are
//! 64-bit (`size_t`), entity tags and types 32-bit.

use std::io;

use super::cursor::{f64_at, i32_at, u64_at, Cursor, Mark};
use super::entities::Entities;
use super::model::{
    kind_of_type, type_of_kind, unknown_node, zero_tag, Elements, NodeIndex, Nodes,
};
use super::write::{runs, Out, Plan};
use super::{close, early_end};
use crate::error::Result;
use crate::mesh::{CellKind, Cells};

/// Bytes of a binary block header: three `int`s and a `size_t`.
const BLOCK_HEADER: usize = 3 * 4 + 8;

/// Reads the four `size_t` (or ASCII) numbers heading `$Nodes` and `$Elements`
/// (in a binary file, after the keyword's line break): block count and item
/// count (the smallest and largest tag are not needed).
pub(super) fn section_header(c: &mut Cursor, items: &str) -> Result<(usize, usize)> {
    if c.binary() {
        let blocks = c.count_le("the number of blocks")?;
        let n = c.count_le(items)?;
        c.take(16, "the smallest and largest tag")?;
        Ok((blocks, n))
    } else {
        let blocks = c.count("the number of blocks")?;
        let n = c.count(items)?;
        c.uint("the smallest tag")?;
        c.uint("the largest tag")?;
        Ok((blocks, n))
    }
}

/// A block header: `(entity dimension, entity tag, third int, count, mark)`.
pub(super) type BlockHeader = (usize, i32, i32, usize, Mark);

/// Reads the header of block `b` of the `blocks` that `section` declares
/// (`$Nodes`: third int the parametric flag; `$Elements`: the element type).
pub(super) fn next_block(
    c: &mut Cursor,
    section: &str,
    blocks: usize,
    b: usize,
) -> Result<BlockHeader> {
    if !c.binary() {
        early_end(c, || {
            format!("{section} declares {blocks} blocks but ends after {b}")
        })?;
    }
    match section {
        "$Nodes" => block_header(c, "the parametric flag", "a node block header"),
        _ => block_header(c, "an element type", "an element block header"),
    }
}

/// Reads a block header: `(entity dimension, entity tag, third int, count)`.
fn block_header(c: &mut Cursor, third: &str, what: &str) -> Result<BlockHeader> {
    let (dim, tag, x, n, mark) = if c.binary() {
        let h = c.take(BLOCK_HEADER, what)?;
        let mark = c.mark();
        let n = u64_at(h, 12);
        let n = usize::try_from(n).map_err(|_| c.error(format!("block size {n} is too large")))?;
        (i32_at(h, 0), i32_at(h, 4), i32_at(h, 8), n, mark)
    } else {
        let dim = c.int("an entity dimension")?;
        let mark = c.mark();
        let tag = c.int("an entity tag")?;
        let x = c.int(third)?;
        let n = c.count("a block size")?;
        (dim, tag, x, n, mark)
    };
    let dim = usize::try_from(dim)
        .ok()
        .filter(|&d| d <= 3)
        .ok_or_else(|| c.error_at(mark, format!("entity dimension {dim} (expected 0 to 3)")))?;
    Ok((dim, tag, x, n, mark))
}

/// Reads the body of `$Nodes` and its closing keyword.
pub(super) fn read_nodes(c: &mut Cursor) -> Result<Nodes> {
    if c.binary() {
        c.newline()?;
    }
    let (blocks, total) = section_header(c, "the number of nodes")?;
    let mut nodes = Nodes::default();
    for b in 0..blocks {
        let (dim, _, parametric, n, mark) = next_block(c, "$Nodes", blocks, b)?;
        let params = node_parameters(c, dim, parametric, mark)?;
        read_node_block(c, b, n, params, &mut nodes)?;
    }
    if nodes.len() != total {
        return Err(c.error_at(
            c.here(),
            format!(
                "$Nodes declares {total} nodes but its blocks hold {}",
                nodes.len()
            ),
        ));
    }
    close(c, "$EndNodes", blocks, "blocks")?;
    Ok(nodes)
}

/// The parametric coordinates per node of a block on an entity of
/// dimension `dim` with flag `parametric` (read at `mark`).
pub(super) fn node_parameters(
    c: &Cursor,
    dim: usize,
    parametric: i32,
    mark: Mark,
) -> Result<usize> {
    match parametric {
        0 => Ok(0),
        1 => Ok(dim),
        _ => Err(c.error_at(
            mark,
            format!("parametric flag {parametric} (expected 0 or 1)"),
        )),
    }
}

/// Bytes of the body of a binary node block: `n` tags, then `n` times
/// `x y z` and `params` parametric coordinates.
pub(super) fn node_block_bytes(n: usize, params: usize) -> Option<usize> {
    n.checked_mul(8 * (4 + params))
}

/// Reads the `n` nodes of block `b` (after its header) into `nodes`.
pub(super) fn read_node_block(
    c: &mut Cursor,
    b: usize,
    n: usize,
    params: usize,
    nodes: &mut Nodes,
) -> Result<()> {
    if c.binary() {
        let reals = 8 * (3 + params);
        let tags = c.take_n(n, 8, "the node tags of a block")?;
        let tags_at = c.mark().offset;
        let xyz = c.take_n(n, reals, "the node coordinates of a block")?;
        let xyz_at = c.mark().offset;
        nodes.reserve(n);
        for i in 0..n {
            let tag = u64_at(tags, 8 * i);
            if tag == 0 {
                return Err(c.error_at_offset(tags_at + 8 * i, zero_tag("node")));
            }
            let p = [
                f64_at(xyz, reals * i),
                f64_at(xyz, reals * i + 8),
                f64_at(xyz, reals * i + 16),
            ];
            let at = Mark {
                offset: xyz_at + reals * i,
                line: 0,
            };
            nodes.push(c, at, at.offset + 24, tag, p)?;
        }
        return Ok(());
    }
    let mut tags = Vec::with_capacity(n.min(c.remaining() / 2));
    for i in 0..n {
        early_end(c, || {
            format!("node block {} declares {n} nodes but ends after {i}", b + 1)
        })?;
        let tag = c.uint("a node tag")?;
        if tag == 0 {
            return Err(c.error(zero_tag("node")));
        }
        tags.push(tag);
    }
    nodes.reserve(n.min(c.remaining() / 6));
    for (i, &tag) in tags.iter().enumerate() {
        let mut v = [0.0; 6];
        let mut mark = c.here();
        let mut end = 0;
        for (k, slot) in v[..3 + params].iter_mut().enumerate() {
            early_end(c, || {
                format!(
                    "node block {} declares {n} nodes but holds coordinates for {i}",
                    b + 1
                )
            })?;
            *slot = c.float("a coordinate")?;
            if k == 0 {
                mark = c.mark();
            }
            if k == 2 {
                end = c.here().offset;
            }
        }
        nodes.push(c, mark, end, tag, [v[0], v[1], v[2]])?;
    }
    Ok(())
}

/// Reads the body of `$Elements` and its closing keyword.
pub(super) fn read_elements(
    c: &mut Cursor,
    index: &NodeIndex,
    entities: &Entities,
) -> Result<Elements> {
    if c.binary() {
        c.newline()?;
    }
    let (blocks, total) = section_header(c, "the number of elements")?;
    let mut elements = Elements::with_physicals(entities.physicals.clone());
    let mut read = 0;
    for b in 0..blocks {
        let header = next_block(c, "$Elements", blocks, b)?;
        let kind = element_kind(c, header)?;
        start_element_block(c, header, entities, &mut elements)?;
        read_element_block(c, b, kind, header.3, &mut |t| index.get(t), &mut elements)?;
        read += header.3;
    }
    if read != total {
        return Err(c.error_at(
            c.here(),
            format!("$Elements declares {total} elements but its blocks hold {read}"),
        ));
    }
    close(c, "$EndElements", blocks, "blocks")?;
    Ok(elements)
}

/// The element kind of an element block, which must match its entity's dimension.
pub(super) fn element_kind(c: &Cursor, (dim, _, etype, _, mark): BlockHeader) -> Result<CellKind> {
    let kind = kind_of_type(etype).map_err(|m| c.error_at(mark, m))?;
    if kind.dim() != dim {
        return Err(c.error_at(
            mark,
            format!(
                "an element block on an entity of dimension {dim} holds {} elements (dimension {})",
                kind.name(),
                kind.dim()
            ),
        ));
    }
    Ok(kind)
}

/// Bytes of the body of a binary block of `n` elements of `kind`: per
/// element its tag and node tags.
pub(super) fn element_block_bytes(n: usize, kind: CellKind) -> Option<usize> {
    n.checked_mul(8 * (1 + kind.node_count()))
}

/// Gives the elements of the block from now on the physical tags of its entity.
pub(super) fn start_element_block(
    c: &Cursor,
    (dim, entity, _, _, mark): BlockHeader,
    entities: &Entities,
    elements: &mut Elements,
) -> Result<()> {
    let physicals = match entities.map.get(&(dim, entity)) {
        Some(r) => r.clone(),
        None if !entities.present => 0..0,
        None => {
            return Err(c.error_at(
                mark,
                format!(
                    "element block on entity {entity} of dimension {dim}, which neither \
                     $Entities nor $PartitionedEntities lists"
                ),
            ))
        }
    };
    elements
        .set_run(dim, physicals)
        .map_err(|m| c.error_at(mark, m))
}

/// Reads the `n` elements of `kind` of block `b` (after its header) into
/// `elements`, each node tag's index by `node_of` (`None`: no such node).
pub(super) fn read_element_block(
    c: &mut Cursor,
    b: usize,
    kind: CellKind,
    n: usize,
    node_of: &mut impl FnMut(u64) -> Option<usize>,
    elements: &mut Elements,
) -> Result<()> {
    let mut ids = [0usize; 8];
    let nn = kind.node_count();
    if c.binary() {
        let size = 8 * (1 + nn);
        let data = c.take_n(n, size, "an element block")?;
        let start = c.mark().offset;
        elements.reserve(kind, n);
        for (e, rec) in data.chunks_exact(size).enumerate() {
            let at = start + e * size;
            let tag = u64_at(rec, 0);
            if tag == 0 {
                return Err(c.error_at_offset(at, zero_tag("element")));
            }
            for (k, id) in ids[..nn].iter_mut().enumerate() {
                let node = u64_at(rec, 8 * (1 + k));
                *id = node_of(node)
                    .ok_or_else(|| c.error_at_offset(at + 8 * (1 + k), unknown_node(tag, node)))?;
            }
            elements.push(kind, tag, &ids[..nn]);
        }
        return Ok(());
    }
    elements.reserve(kind, n.min(c.remaining() / (2 * (1 + nn))));
    for e in 0..n {
        early_end(c, || {
            format!(
                "element block {} declares {n} elements but ends after {e}",
                b + 1
            )
        })?;
        let tag = c.uint("an element tag")?;
        if tag == 0 {
            return Err(c.error(zero_tag("element")));
        }
        for id in &mut ids[..nn] {
            let node = c.uint("a node tag")?;
            *id = node_of(node).ok_or_else(|| c.error(unknown_node(tag, node)))?;
        }
        elements.push(kind, tag, &ids[..nn]);
    }
    Ok(())
}

/// Writes the whole file.
pub(super) fn write(out: &mut Out, plan: &Plan) -> io::Result<()> {
    let mesh = plan.mesh;
    let dim = mesh.dim;
    out.format("4.1")?;
    out.names(plan)?;

    out.text("$Entities\n")?;
    let mut counts = [0u64; 4];
    counts[dim] = 1;
    for g in &plan.groups {
        counts[g.dim] += 1;
    }
    for n in counts {
        out.size(n)?;
    }
    out.end_line()?;
    for d in 0..4 {
        for g in plan.groups.iter().filter(|g| g.dim == d) {
            out.int(g.entity)?;
            let facets = &g.group.facets;
            if d == 0 {
                let p = facets.nodes.first().map_or([0.0; 3], |&i| plan.xyz(i));
                floats(out, &p)?;
            } else {
                bounding_box(out, plan, facets.nodes.iter().copied())?;
            }
            out.size(1)?;
            out.int(g.physical)?;
            if d > 0 {
                out.size(0)?;
            }
            out.end_line()?;
        }
        if d == dim {
            out.int(1)?;
            bounding_box(out, plan, 0..mesh.node_count())?;
            out.size(1)?;
            out.int(plan.domain.0)?;
            out.size(0)?;
            out.end_line()?;
        }
    }
    out.close("$EndEntities")?;

    out.text("$Nodes\n")?;
    let n = mesh.node_count() as u64;
    let (min, max) = min_max(mesh.node_tags.iter().copied());
    for v in [u64::from(n > 0), n, min, max] {
        out.size(v)?;
    }
    out.end_line()?;
    if n > 0 {
        out.int(dim as i32)?;
        out.int(1)?;
        out.int(0)?;
        out.size(n)?;
        out.end_line()?;
        for &tag in &mesh.node_tags {
            out.size(tag)?;
            out.end_line()?;
        }
        for i in 0..mesh.node_count() {
            floats(out, &plan.xyz(i))?;
            out.end_line()?;
        }
    }
    out.close("$EndNodes")?;

    out.text("$Elements\n")?;
    let facets = plan.facet_count() as u64;
    let cell_runs = runs(&mesh.cells);
    let group_runs: Vec<_> = plan.groups.iter().map(|g| runs(&g.group.facets)).collect();
    let blocks = cell_runs.len() + group_runs.iter().map(Vec::len).sum::<usize>();
    let facet_tags = plan.facet_tags.iter().flatten().copied();
    let (min, max) = min_max(mesh.cell_tags.iter().copied().chain(facet_tags));
    for v in [blocks as u64, mesh.cell_count() as u64 + facets, min, max] {
        out.size(v)?;
    }
    out.end_line()?;
    let mut tags = mesh.cell_tags.iter().copied();
    write_blocks(out, plan, &mesh.cells, &cell_runs, (dim, 1), &mut tags)?;
    for ((g, r), tags) in plan.groups.iter().zip(&group_runs).zip(&plan.facet_tags) {
        let mut tags = tags.iter().copied();
        write_blocks(out, plan, &g.group.facets, r, (g.dim, g.entity), &mut tags)?;
    }
    out.close("$EndElements")
}

/// Writes element blocks for `runs` of `cells` on `entity`, tags from `tags`.
fn write_blocks(
    out: &mut Out,
    plan: &Plan,
    cells: &Cells,
    runs: &[(crate::mesh::CellKind, usize, usize)],
    entity: (usize, i32),
    tags: &mut impl Iterator<Item = u64>,
) -> io::Result<()> {
    for &(kind, first, end) in runs {
        out.int(entity.0 as i32)?;
        out.int(entity.1)?;
        out.int(type_of_kind(kind))?;
        out.size((end - first) as u64)?;
        out.end_line()?;
        for c in first..end {
            out.size(tags.next().unwrap_or(0))?;
            for &node in cells.cell(c) {
                out.size(plan.mesh.node_tags[node])?;
            }
            out.end_line()?;
        }
    }
    Ok(())
}

/// Writes the given floats.
fn floats(out: &mut Out, values: &[f64]) -> io::Result<()> {
    values.iter().try_for_each(|&v| out.float(v))
}

/// Writes `min x y z, max x y z` of the given nodes.
fn bounding_box(out: &mut Out, plan: &Plan, nodes: impl Iterator<Item = usize>) -> io::Result<()> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for i in nodes {
        let p = plan.xyz(i);
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if lo[0] > hi[0] {
        (lo, hi) = ([0.0; 3], [0.0; 3]);
    }
    floats(out, &lo)?;
    floats(out, &hi)
}

/// Smallest and largest value (0 and 0 when there is none).
fn min_max(values: impl Iterator<Item = u64>) -> (u64, u64) {
    values
        .fold(None, |acc: Option<(u64, u64)>, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
        .unwrap_or((0, 0))
}
