//! MSH 2.2: `$Nodes` as `tag x y z`, `$Elements` as
//! `tag type ntags physical elementary … nodes` (binary: runs of one type
//! behind a `type count ntags` header, all integers 32-bit).

use std::io;

use super::cursor::{f64_at, i32_at, Cursor, Mark};
use super::model::{
    kind_of_type, type_of_kind, unknown_node, zero_tag, Elements, NodeIndex, Nodes,
};
use super::write::{invalid, runs, Out, Plan};
use super::{close, early_end};
use crate::error::Result;

/// Bytes of a binary node: `int tag`, three `double`s.
const NODE_BYTES: usize = 4 + 3 * 8;

/// Reads the body of `$Nodes` and its closing keyword.
pub(super) fn read_nodes(c: &mut Cursor) -> Result<Nodes> {
    let n = c.count("the number of nodes")?;
    let mut nodes = Nodes::default();
    if c.binary() {
        c.newline()?;
        let data = c.take_n(n, NODE_BYTES, "$Nodes")?;
        let start = c.mark().offset;
        nodes.reserve(n);
        for (i, rec) in data.chunks_exact(NODE_BYTES).enumerate() {
            let at = start + i * NODE_BYTES;
            let tag = i32_at(rec, 0);
            if tag <= 0 {
                return Err(c.error_at_offset(
                    at,
                    format!("node tag {tag} is not allowed (tags start at 1)"),
                ));
            }
            let p = [f64_at(rec, 4), f64_at(rec, 12), f64_at(rec, 20)];
            let mark = Mark {
                offset: at + 4,
                line: 0,
            };
            nodes.push(c, mark, at + 4 + 24, tag as u64, p)?;
        }
    } else {
        nodes.reserve(n.min(c.remaining() / 8));
        for i in 0..n {
            early_end(c, || {
                format!("$Nodes declares {n} nodes but ends after {i}")
            })?;
            let tag = c.uint("a node tag")?;
            if tag == 0 {
                return Err(c.error(zero_tag("node")));
            }
            let x = c.float("a coordinate")?;
            let mark = c.mark();
            let p = [x, c.float("a coordinate")?, c.float("a coordinate")?];
            nodes.push(c, mark, c.here().offset, tag, p)?;
        }
    }
    close(c, "$EndNodes", n, "nodes")?;
    Ok(nodes)
}

/// Reads the body of `$Elements` and its closing keyword.
pub(super) fn read_elements(c: &mut Cursor, index: &NodeIndex) -> Result<Elements> {
    let n = c.count("the number of elements")?;
    let mut elements = Elements::default();
    let mut ids = [0usize; 8];
    if c.binary() {
        c.newline()?;
        let mut read = 0;
        while read < n {
            let header = c.take(12, "an element header")?;
            let at = c.mark().offset;
            let kind = kind_of_type(i32_at(header, 0)).map_err(|m| c.error_at_offset(at, m))?;
            let (count, ntags) = (i32_at(header, 4), i32_at(header, 8));
            let count = usize::try_from(count)
                .ok()
                .filter(|&k| k <= n - read)
                .ok_or_else(|| {
                    c.error_at_offset(
                        at + 4,
                        format!(
                            "element header announces {count} elements but {} of the {n} declared remain",
                            n - read
                        ),
                    )
                })?;
            let ntags = usize::try_from(ntags).map_err(|_| {
                c.error_at_offset(at + 8, format!("negative number of tags {ntags}"))
            })?;
            let nn = kind.node_count();
            let size = 4 * (1 + ntags + nn);
            let data = c.take_n(count, size, "an element run")?;
            let start = c.mark().offset;
            elements.reserve(kind, count);
            for (e, rec) in data.chunks_exact(size).enumerate() {
                let at = start + e * size;
                let tag = i32_at(rec, 0);
                if tag <= 0 {
                    return Err(c.error_at_offset(
                        at,
                        format!("element tag {tag} is not allowed (tags start at 1)"),
                    ));
                }
                let tag = tag as u64;
                for (k, id) in ids[..nn].iter_mut().enumerate() {
                    let node = i32_at(rec, 4 * (1 + ntags + k));
                    *id = u64::try_from(node)
                        .ok()
                        .and_then(|t| index.get(t))
                        .ok_or_else(|| c.error_at_offset(at, unknown_node(tag, node)))?;
                }
                let physical = if ntags > 0 { i32_at(rec, 4) } else { 0 };
                elements
                    .set_physical(kind.dim(), physical)
                    .map_err(|m| c.error_at_offset(at, m))?;
                elements.push(kind, tag, &ids[..nn]);
            }
            read += count;
        }
    } else {
        for i in 0..n {
            early_end(c, || {
                format!("$Elements declares {n} elements but ends after {i}")
            })?;
            let tag = c.uint("an element tag")?;
            if tag == 0 {
                return Err(c.error(zero_tag("element")));
            }
            let etype = c.int("an element type")?;
            let kind = kind_of_type(etype).map_err(|m| c.error(m))?;
            let ntags = c.count("the number of tags")?;
            let mut physical = 0;
            for t in 0..ntags {
                let v = c.int("a tag")?;
                if t == 0 {
                    physical = v;
                }
            }
            let nn = kind.node_count();
            for id in &mut ids[..nn] {
                let node = c.uint("a node tag")?;
                *id = index
                    .get(node)
                    .ok_or_else(|| c.error(unknown_node(tag, node)))?;
            }
            elements
                .set_physical(kind.dim(), physical)
                .map_err(|m| c.error(m))?;
            elements.push(kind, tag, &ids[..nn]);
        }
    }
    close(c, "$EndElements", n, "elements")?;
    Ok(elements)
}

/// A tag as MSH 2.2's 32-bit integer.
fn int_tag(tag: u64, what: &str) -> io::Result<i32> {
    i32::try_from(tag).map_err(|_| {
        invalid(format!(
            "{what} tag {tag} does not fit the 32-bit integers of MSH 2.2 (write MSH 4.1)"
        ))
    })
}

/// Writes the whole file.
pub(super) fn write(out: &mut Out, plan: &Plan) -> io::Result<()> {
    let mesh = plan.mesh;
    out.format("2.2")?;
    out.names(plan)?;
    out.text(&format!("$Nodes\n{}\n", mesh.node_count()))?;
    for (i, &tag) in mesh.node_tags.iter().enumerate() {
        let p = plan.xyz(i);
        let tag = int_tag(tag, "node")?;
        out.int(tag)?;
        out.float(p[0])?;
        out.float(p[1])?;
        out.float(p[2])?;
        out.end_line()?;
    }
    out.close("$EndNodes")?;
    let total = mesh.cell_count() + plan.facet_count();
    out.text(&format!("$Elements\n{total}\n"))?;
    let mut tags = mesh.cell_tags.iter().copied();
    write_cells(out, plan, &mesh.cells, &mut tags, plan.domain.0, 1)?;
    for (g, tags) in plan.groups.iter().zip(&plan.facet_tags) {
        let mut tags = tags.iter().copied();
        write_cells(out, plan, &g.group.facets, &mut tags, g.physical, g.entity)?;
    }
    out.close("$EndElements")
}

/// Writes `cells` with tags from `tags`, physical tag `physical` and entity `entity`.
fn write_cells(
    out: &mut Out,
    plan: &Plan,
    cells: &crate::mesh::Cells,
    tags: &mut impl Iterator<Item = u64>,
    physical: i32,
    entity: i32,
) -> io::Result<()> {
    for (kind, first, end) in runs(cells) {
        let etype = type_of_kind(kind);
        if out.binary() {
            out.int(etype)?;
            out.int(int_tag((end - first) as u64, "element count")?)?;
            out.int(2)?;
        }
        for c in first..end {
            out.int(int_tag(tags.next().unwrap_or(0), "element")?)?;
            if !out.binary() {
                out.int(etype)?;
                out.int(2)?;
            }
            out.int(physical)?;
            out.int(entity)?;
            for &node in cells.cell(c) {
                out.int(int_tag(plan.mesh.node_tags[node], "node")?)?;
            }
            out.end_line()?;
        }
    }
    Ok(())
}
