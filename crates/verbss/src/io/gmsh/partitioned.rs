//! One share of a partitioned MSH 4.1 file: the partitions a process asks
//! for, read without storing the others.
//!
//! `gmsh -part N` writes, after `$Entities`, a `$PartitionedEntities`
//! section: the number of partitions `N` and one *partition entity* per
//! piece of a model entity in a partition, with its parent model entity and
//! its partitions (1-based). Every node and element block of `$Nodes` and
//! `$Elements` lies on a partition entity: the elements of a partition on
//! entities of that partition alone, the nodes shared by several partitions
//! on entities listing each of them (Gmsh's partition boundaries, whose
//! parent is of the partitioned dimension itself).
//!
//! [`read_share`] streams the file once, up to `$EndElements`: the header
//! sections are read whole (they describe entities, not nodes); of
//! `$Nodes` and `$Elements` it keeps the blocks on entities of the wanted
//! partitions and steps over the others — a binary block by its size, an
//! ASCII block by counting its numbers line by line — without storing
//! them. The share's cells are therefore its partitions' elements of the
//! highest dimension, each in exactly one share; its nodes are those of its
//! partitions' entities and any other node of those elements: Gmsh can put
//! a node on a partition boundary entity that does not list every partition
//! using it (where partitions touch at a single node; the 1,140-cell box of
//! `assets/meshes/gmsh` cut in 6 has four such references), and such nodes
//! are read in a second pass over `$Nodes`, of the blocks skipped the first
//! time, keeping only them. Sections
//! after `$Elements` (`$GhostElements` of `gmsh -part_ghosts`, …) are not
//! read: a share has no ghosts of its own.
//!
//! A node is on the model's boundary ([`Share::boundary`]) when its
//! partition entity's parent is a boundary entity: an entity of dimension
//! `D − 1` that bounds exactly one entity of dimension `D` (`$Entities`'
//! bounding lists), or an entity bounding one of those, recursively. For a
//! conforming mesh this is the set of nodes on faces that belong to one
//! cell of the whole mesh, the boundary of `verbss deform`. In the same way
//! a node is on a physical group ([`Share::group_nodes`]) when its parent
//! is one of the group's model entities or bounds one, recursively, or when
//! a facet of the group that the share holds has it. The first rule alone
//! would let every share that holds a node agree on its groups, but Gmsh
//! can put a node of a model curve or point on a partition entity whose
//! parent is only one of the faces beside it (the box cut in 6 again): a
//! process that reads a share must therefore join its groups with the
//! other shares' for the nodes they hold in common
//! (`verbss_mpi::share::read_rank_share` does).

use std::collections::{HashMap, HashSet};
use std::ops::RangeInclusive;
use std::path::Path;

use super::cursor::{show, Cursor, Mark};
use super::entities::{read_entities, read_partitioned, Entities};
use super::model::{finish, Elements, NodeIndex, Nodes};
use super::stream::Stream;
use super::v41::{
    element_block_bytes, element_kind, next_block, node_block_bytes, node_parameters,
    read_element_block, read_node_block, section_header, start_element_block, BlockHeader,
};
use super::{read_format, read_names, MshVersion, Names, PieceLabels};
use crate::error::Result;
use crate::mesh::Mesh;

/// The partitions a process read from a partitioned MSH 4.1 file.
#[derive(Debug)]
pub struct Share {
    /// The partitions' cells (in file order, with their element tags) and
    /// the facets of their physical groups, on the nodes of the partitions'
    /// entities (in file order, with their node tags).
    pub mesh: Mesh,
    /// Per node of [`Share::mesh`]: whether it is on the model's boundary
    /// (see the module documentation).
    pub boundary: Vec<bool>,
    /// The number of partitions of the file.
    pub partitions: usize,
    /// Every physical group of the file below the mesh dimension, by name,
    /// with the nodes of [`Share::mesh`] on it (increasing; see the module
    /// documentation).
    pub group_nodes: Vec<(String, Vec<usize>)>,
    /// Whether the file is binary.
    pub binary: bool,
    /// The file's element tags of the group facets of [`Share::mesh`] and
    /// the cells' physical group, for writing the share as a piece
    /// ([`super::split_write`]).
    pub labels: PieceLabels,
}

/// What precedes `$Nodes`.
struct Head {
    names: Names,
    entities: Entities,
    binary: bool,
}

/// The number of partitions of a Gmsh file (its `$PartitionedEntities`),
/// 0 when it has none; reads the file only up to `$Nodes`.
pub fn partition_count(path: &Path) -> Result<usize> {
    let mut s = Stream::open(path)?;
    Ok(read_head(&mut s)?.entities.partitions)
}

/// Reads partitions `wanted` (1-based) of the partitioned MSH 4.1 file at
/// `path` (see the module documentation). Fails when the file is not a
/// partitioned MSH 4.1 file, when `wanted` is not within its partitions,
/// when a partition of `wanted` has no element in the file (a file of a
/// split set, which holds one), or where the file is malformed, naming the
/// line (ASCII) or byte offset (binary).
pub fn read_share(path: &Path, wanted: RangeInclusive<usize>) -> Result<Share> {
    let mut s = Stream::open(path)?;
    let head = read_head(&mut s)?;
    let count = head.entities.partitions;
    if count == 0 {
        return Err(s.error_at(
            s.here(),
            "the file has no $PartitionedEntities: it is not partitioned (write it with \
             `gmsh -part N -format msh41`)",
        ));
    }
    if wanted.is_empty() || *wanted.start() == 0 || *wanted.end() > count {
        return Err(crate::Error::InvalidSetting(format!(
            "partitions {}..={} of {}, which has {count} (numbered from 1)",
            wanted.start(),
            wanted.end(),
            path.display()
        )));
    }
    let picked = |c: &Cursor, (dim, tag, ..): BlockHeader, mark: Mark| -> Result<bool> {
        match head.entities.partitioned.get(&(dim, tag)) {
            Some(p) => Ok(p
                .partitions
                .iter()
                .any(|&q| usize::try_from(q).is_ok_and(|q| wanted.contains(&q)))),
            None => Err(c.error_at(
                mark,
                format!(
                    "a block on entity {tag} of dimension {dim}, which $PartitionedEntities \
                     does not list (every block of a partitioned file lies on a partition entity)"
                ),
            )),
        }
    };
    let (mut nodes, mut entity_of_node) = read_nodes(&mut s, &head, &picked, None)?;
    let index = NodeIndex::build(&nodes.tags)
        .map_err(|t| s.error_at(s.here(), format!("node tag {t} is given to two nodes")))?;
    // Nodes of the share's elements on other partitions' entities get the
    // next indices, in the order first met, and are read in a second pass.
    let known = nodes.len();
    let mut elsewhere = Vec::new();
    let mut elsewhere_index = HashMap::new();
    let mut node_of = |tag: u64| {
        index.get(tag).or_else(|| {
            Some(*elsewhere_index.entry(tag).or_insert_with(|| {
                elsewhere.push(tag);
                known + elsewhere.len() - 1
            }))
        })
    };
    // The entities of the kept element blocks that hold elements.
    let held = std::cell::RefCell::new(Vec::new());
    let picked_elements = |c: &Cursor, header: BlockHeader, mark: Mark| -> Result<bool> {
        let keep = picked(c, header, mark)?;
        if keep && header.3 > 0 {
            held.borrow_mut().push((header.0, header.1));
        }
        Ok(keep)
    };
    let (elements, at) = read_elements(&mut s, &head, &mut node_of, &picked_elements)?;
    check_held(&s, &head.entities, &held.into_inner(), wanted.clone(), at)?;
    if !elsewhere.is_empty() {
        let (found, entities) = read_elsewhere(path, &picked, &elsewhere)?;
        for &tag in &elsewhere {
            let Some(i) = found.tags.iter().position(|&t| t == tag) else {
                return Err(s.error_at(
                    at,
                    format!(
                        "an element of partitions {}-{} refers to node {tag}, which $Nodes \
                         does not define",
                        wanted.start(),
                        wanted.end()
                    ),
                ));
            };
            nodes.push_from(&found, i);
            entity_of_node.push(entities[i]);
        }
    }
    let end = s.here();
    let c = Cursor::window(&[], path, end, head.binary);
    let (mesh, structure) = finish(&c, nodes, (elements, at), &head.names, false, end)?;
    let parents: Vec<(usize, i32)> = entity_of_node
        .iter()
        .map(|e| head.entities.partitioned[e].parent)
        .collect();
    let on = |entities: &HashSet<(usize, i32)>| -> Vec<usize> {
        (0..parents.len())
            .filter(|&i| entities.contains(&parents[i]))
            .collect()
    };
    let boundary_entities = closure(&head.entities, boundary_faces(&head.entities, mesh.dim));
    let boundary = parents
        .iter()
        .map(|p| boundary_entities.contains(p))
        .collect();
    let group_nodes = physical_groups(&head, mesh.dim)
        .into_iter()
        .map(|(name, entities)| {
            let mut nodes = on(&closure(&head.entities, entities));
            // Gmsh can put a node of a model curve or point on a partition
            // entity whose parent is a face beside it: the group's facets
            // held here name it too.
            if let Ok(group) = mesh.group(&name) {
                nodes.extend(group.nodes());
                nodes.sort_unstable();
                nodes.dedup();
            }
            (name, nodes)
        })
        .collect();
    Ok(Share {
        mesh,
        boundary,
        partitions: count,
        group_nodes,
        binary: head.binary,
        labels: PieceLabels {
            facet_tags: Some(structure.facet_tags),
            domain: structure.domain,
        },
    })
}

/// Fails unless every partition of `wanted` has elements of the highest
/// dimension in the file (on the entities `held`): a file of a split set
/// (`gmsh -part_split`) declares every partition and holds one.
fn check_held(
    s: &Stream,
    entities: &Entities,
    held: &[(usize, i32)],
    wanted: RangeInclusive<usize>,
    at: Mark,
) -> Result<()> {
    let top = held.iter().map(|&(dim, _)| dim).max();
    let has = |q: usize| {
        held.iter().any(|&(dim, tag)| {
            Some(dim) == top
                && entities.partitioned[&(dim, tag)]
                    .partitions
                    .iter()
                    .any(|&p| usize::try_from(p) == Ok(q))
        })
    };
    match wanted.clone().find(|&q| !has(q)) {
        None => Ok(()),
        Some(q) => Err(s.error_at(
            at,
            format!(
                "no element of partition {q} of the {} it declares is in this file: a file of \
                 a split set (`gmsh -part_split`) holds one partition; read the set with \
                 --split, from its first file NAME_1.msh",
                entities.partitions
            ),
        )),
    }
}

/// Reads the sections before `$Nodes` (and the `$Nodes` line itself).
fn read_head(s: &mut Stream) -> Result<Head> {
    let path = s.path();
    let mut head = Head {
        names: Names::new(),
        entities: Entities::default(),
        binary: false,
    };
    let mut version = None;
    loop {
        let at = s.here();
        let mut buf = Vec::new();
        if !s.line(&mut buf)? {
            return Err(s.error_at(at, "unexpected end of file: no $Nodes section"));
        }
        let skip = if at.offset == 0 {
            crate::io::bom(&buf)
        } else {
            0
        };
        let keyword = buf[skip..].trim_ascii().to_vec();
        if keyword.is_empty() {
            continue;
        }
        if version.is_none() {
            if keyword == b"$MeshFormat" {
                s.section("$EndMeshFormat", at, Some(&mut buf))?;
            }
            let mut c = Cursor::window(&buf[skip..], path, at, false);
            if read_format(&mut c)? != MshVersion::V41 {
                return Err(c.error_at(
                    at,
                    "MSH 2.2 has no partitioned entities: a distributed read needs a \
                     partitioned MSH 4.1 file (`gmsh -part N -format msh41`)",
                ));
            }
            version = Some(MshVersion::V41);
            head.binary = c.binary();
            if head.binary {
                s.set_binary();
            }
            continue;
        }
        let end = match &keyword[..] {
            b"$Nodes" => return Ok(head),
            b"$PhysicalNames" | b"$Entities" | b"$PartitionedEntities" => {
                format!("$End{}", String::from_utf8_lossy(&keyword[1..]))
            }
            [b'$', name @ ..] if !name.starts_with(b"End") => {
                let end = format!("$End{}", String::from_utf8_lossy(name));
                s.section(&end, at, None)?;
                continue;
            }
            _ => {
                return Err(s.error_at(
                    at,
                    format!(
                        "expected a section header such as $Nodes, found {}",
                        show(&keyword)
                    ),
                ))
            }
        };
        s.section(&end, at, Some(&mut buf))?;
        let mut c = Cursor::window(&buf, path, at, head.binary);
        c.next_token();
        match &keyword[..] {
            b"$PhysicalNames" => read_names(&mut c, &mut head.names)?,
            b"$Entities" => read_entities(&mut c, &mut head.entities)?,
            _ => read_partitioned(&mut c, &mut head.entities)?,
        }
    }
}

/// Whether a block is kept: from its header, read by a cursor, at a mark.
type Picked<'a> = dyn Fn(&Cursor, BlockHeader, Mark) -> Result<bool> + 'a;

/// The nodes `tags` from the blocks of `$Nodes` that `kept` did not keep
/// (a second pass over the file at `path`), with their entities, in file
/// order. Gmsh can put a node that elements of a partition use on a
/// partition boundary entity that does not list that partition (seen where
/// partitions touch at a single node).
fn read_elsewhere(path: &Path, kept: &Picked, tags: &[u64]) -> Result<(Nodes, Vec<(usize, i32)>)> {
    let wanted: HashSet<u64> = tags.iter().copied().collect();
    let mut s = Stream::open(path)?;
    let head = read_head(&mut s)?;
    let skipped = |c: &Cursor, header: BlockHeader, mark: Mark| Ok(!kept(c, header, mark)?);
    read_nodes(&mut s, &head, &skipped, Some(&wanted))
}

/// Reads the `$Nodes` section's kept blocks, of them only the nodes
/// `wanted` when given; also returns the entity of each node kept.
fn read_nodes(
    s: &mut Stream,
    head: &Head,
    picked: &Picked,
    wanted: Option<&HashSet<u64>>,
) -> Result<(Nodes, Vec<(usize, i32)>)> {
    let (blocks, total) = read_section_header(s, head, "the number of nodes")?;
    let mut nodes = Nodes::default();
    let mut entity_of_node = Vec::new();
    let mut listed = 0usize;
    for b in 0..blocks {
        let (buf, at) = read_block_header(s, head)?;
        let mut c = Cursor::window(&buf, s.path(), at, head.binary);
        let header = next_block(&mut c, "$Nodes", blocks, b)?;
        let (dim, tag, parametric, n, mark) = header;
        let params = node_parameters(&c, dim, parametric, mark)?;
        listed = listed.saturating_add(n);
        let size = node_block_bytes(n, params)
            .ok_or_else(|| c.error_at(mark, format!("node block size {n} is too large")))?;
        let keep = picked(&c, header, mark)?;
        let body = read_body(s, head, keep, n * (4 + params), size, "a node block")?;
        if let Some((buf, at)) = body {
            let mut c = Cursor::window(&buf, s.path(), at, head.binary);
            match wanted {
                None => read_node_block(&mut c, b, n, params, &mut nodes)?,
                Some(wanted) => {
                    let mut block = Nodes::default();
                    read_node_block(&mut c, b, n, params, &mut block)?;
                    for i in 0..block.len() {
                        if wanted.contains(&block.tags[i]) {
                            nodes.push_from(&block, i);
                        }
                    }
                }
            }
            entity_of_node.resize(nodes.len(), (dim, tag));
        }
    }
    if listed != total {
        return Err(s.error_at(
            s.here(),
            format!("$Nodes declares {total} nodes but its blocks hold {listed}"),
        ));
    }
    close_section(s, "$EndNodes", blocks)?;
    Ok((nodes, entity_of_node))
}

/// Reads the `$Elements` section's kept blocks; also returns where the
/// section starts.
fn read_elements(
    s: &mut Stream,
    head: &Head,
    node_of: &mut impl FnMut(u64) -> Option<usize>,
    picked: &Picked,
) -> Result<(Elements, Mark)> {
    let mut line = Vec::new();
    let start = loop {
        let at = s.here();
        line.clear();
        if !s.line(&mut line)? {
            return Err(s.error_at(at, "unexpected end of file: no $Elements section"));
        }
        match line.trim_ascii() {
            b"" => continue,
            b"$Elements" => break at,
            t => {
                return Err(s.error_at(
                    at,
                    format!("expected $Elements after $EndNodes, found {}", show(t)),
                ))
            }
        }
    };
    let (blocks, total) = read_section_header(s, head, "the number of elements")?;
    let mut elements = Elements::with_physicals(head.entities.physicals.clone());
    let mut listed = 0usize;
    for b in 0..blocks {
        let (buf, at) = read_block_header(s, head)?;
        let mut c = Cursor::window(&buf, s.path(), at, head.binary);
        let header = next_block(&mut c, "$Elements", blocks, b)?;
        let kind = element_kind(&c, header)?;
        let (n, mark) = (header.3, header.4);
        listed = listed.saturating_add(n);
        let size = element_block_bytes(n, kind)
            .ok_or_else(|| c.error_at(mark, format!("element block size {n} is too large")))?;
        let keep = picked(&c, header, mark)?;
        if keep {
            start_element_block(&c, header, &head.entities, &mut elements)?;
        }
        let numbers = n * (1 + kind.node_count());
        if let Some((buf, at)) = read_body(s, head, keep, numbers, size, "an element block")? {
            let mut c = Cursor::window(&buf, s.path(), at, head.binary);
            read_element_block(&mut c, b, kind, n, node_of, &mut elements)?;
        }
    }
    if listed != total {
        return Err(s.error_at(
            s.here(),
            format!("$Elements declares {total} elements but its blocks hold {listed}"),
        ));
    }
    close_section(s, "$EndElements", blocks)?;
    Ok((elements, start))
}

/// Reads the numbers heading `$Nodes` or `$Elements` (after its keyword's
/// line): block count and item count.
fn read_section_header(s: &mut Stream, head: &Head, items: &str) -> Result<(usize, usize)> {
    let at = s.here();
    let mut buf = Vec::new();
    if head.binary {
        s.bytes(32, &mut buf, "the section's counts")?;
    } else {
        s.tokens(4, Some(&mut buf), "the section's counts")?;
    }
    section_header(&mut Cursor::window(&buf, s.path(), at, head.binary), items)
}

/// The bytes of a block header (a line, or 20 bytes in a binary file) and
/// where they start.
fn read_block_header(s: &mut Stream, head: &Head) -> Result<(Vec<u8>, Mark)> {
    let mut buf = Vec::new();
    let mut at = s.here();
    if head.binary {
        s.bytes(20, &mut buf, "a block header")?;
    } else {
        // Blank lines before the header are the cursor's to skip.
        while s.line(&mut buf)? && buf.trim_ascii().is_empty() {
            at = s.here();
            buf.clear();
        }
    }
    Ok((buf, at))
}

/// A block's body: kept (its bytes and where they start) or stepped over:
/// `numbers` ASCII numbers or `size` binary bytes.
fn read_body(
    s: &mut Stream,
    head: &Head,
    keep: bool,
    numbers: usize,
    size: usize,
    what: &str,
) -> Result<Option<(Vec<u8>, Mark)>> {
    let at = s.here();
    match (keep, head.binary) {
        (true, true) => {
            let mut buf = Vec::new();
            s.bytes(size, &mut buf, what)?;
            Ok(Some((buf, at)))
        }
        (true, false) => {
            let mut buf = Vec::new();
            s.tokens(numbers, Some(&mut buf), what)?;
            Ok(Some((buf, at)))
        }
        (false, true) => s.skip(size, what).map(|()| None),
        (false, false) => s.tokens(numbers, None, what).map(|()| None),
    }
}

/// Reads the keyword closing a section of `blocks` blocks.
fn close_section(s: &mut Stream, keyword: &str, blocks: usize) -> Result<()> {
    let mut line = Vec::new();
    loop {
        let at = s.here();
        line.clear();
        if !s.line(&mut line)? {
            return Err(s.error_at(at, format!("unexpected end of file: expected {keyword}")));
        }
        match line.trim_ascii() {
            b"" => continue,
            t if t == keyword.as_bytes() => return Ok(()),
            t => {
                return Err(s.error_at(
                    at,
                    format!(
                        "expected {keyword} after {blocks} blocks, found {}: the section \
                         holds more than it declares",
                        show(t)
                    ),
                ))
            }
        }
    }
}

/// The model entities of dimension `dim − 1` that bound exactly one
/// entity of dimension `dim`: the faces of the model's boundary.
fn boundary_faces(entities: &Entities, dim: usize) -> Vec<(usize, i32)> {
    let mut bounded: HashMap<i32, usize> = HashMap::new();
    for ((d, _), bounding) in &entities.bounding {
        if *d == dim {
            for &t in bounding {
                *bounded.entry(t).or_default() += 1;
            }
        }
    }
    bounded
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(t, _)| (dim - 1, t))
        .collect()
}

/// The physical groups of dimension below `dim`, by name (or tag as text,
/// as the whole-file reader names them), each with its model entities.
fn physical_groups(head: &Head, dim: usize) -> Vec<(String, Vec<(usize, i32)>)> {
    let entities = &head.entities;
    let mut groups: HashMap<(usize, i32), Vec<(usize, i32)>> = HashMap::new();
    for (&(d, tag), range) in &entities.map {
        if d < dim && !entities.partitioned.contains_key(&(d, tag)) {
            for &p in &entities.physicals[range.clone()] {
                groups.entry((d, p)).or_default().push((d, tag));
            }
        }
    }
    let mut named: Vec<(String, Vec<(usize, i32)>)> = groups
        .into_iter()
        .map(|(key, list)| {
            let name = head.names.get(&key).cloned();
            (name.unwrap_or_else(|| key.1.to_string()), list)
        })
        .collect();
    named.sort();
    named
}

/// The entities `start` and every entity bounding one of them, recursively.
fn closure(entities: &Entities, start: Vec<(usize, i32)>) -> HashSet<(usize, i32)> {
    let mut todo = start;
    let mut found = HashSet::new();
    while let Some(e) = todo.pop() {
        if found.insert(e) && e.0 > 0 {
            if let Some(bounding) = entities.bounding.get(&e) {
                todo.extend(bounding.iter().map(|&t| (e.0 - 1, t)));
            }
        }
    }
    found
}
