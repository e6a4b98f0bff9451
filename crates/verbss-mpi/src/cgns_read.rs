//! A single-zone unstructured CGNS file read by every rank in blocks, into
//! the [`Scattered`] of the SU2 read, for the same cut
//! (`crate::repartition`): no rank reads the whole coordinate or
//! connectivity arrays.
//!
//! Every rank opens the file read-only with the serial CGNS library and
//! reads its headers (sections, boundary conditions; [`Blocks`]). Then, of
//! `P` ranks, rank `r` reads (block `r` of `count` being the indices
//! `⌈r·count/P⌉ .. ⌈(r+1)·count/P⌉`, [`block`]):
//!
//! * block `r` of the `N` nodes' coordinates, and sends node `g` to its
//!   directory rank `g mod P` (one all-to-all);
//! * block `r` of each boundary condition's points: the elements it names
//!   (read in runs of consecutive numbers) or its vertices. Whether it is a
//!   region and whether every element is a facet are agreed over the ranks,
//!   so every rank makes the same groups as the whole-file reader, and a
//!   bad point is reported as that reader reports the first one (of a
//!   range longer than the zone's elements or vertices, only the first
//!   of them and one more are looked at: one of them is bad);
//! * block `r` of the elements of the sections that may hold cells or make
//!   a group of their own (a section of facets that no condition holds):
//!   the cells are its block of cells, the facets' nodes go to their group;
//! * each `(node, group)` pair goes to the node's directory rank (one
//!   all-to-all).
//!
//! An error on any rank stops every rank, with one message (`share::agree`).

use std::path::Path;

use verbss::io::cgns::blocks::{Blocks, Condition, Numbers};
use verbss::mesh::{CellKind, Cells};
use verbss::{Error, Result};

use crate::scatter::{block, decode_facets, CellsAt, Facet, Scattered};
use crate::share::agree;
use crate::Comm;

/// An element read: its number, and its section, kind and nodes (from 0)
/// when a section holds it.
type Element = (i64, Option<(usize, CellKind, Vec<u64>)>);

/// The elements `numbers` of `zone`, in order, read in runs of consecutive
/// numbers of one section.
fn read_numbered(zone: &Blocks, numbers: &[i64]) -> Result<Vec<Element>> {
    let mut read = Vec::with_capacity(numbers.len());
    let mut at = 0;
    while at < numbers.len() {
        let (first, section) = (numbers[at], zone.section_of(numbers[at]));
        let Some(s) = section else {
            read.push((first, None));
            at += 1;
            continue;
        };
        let mut end = at + 1;
        while end < numbers.len()
            && numbers[end] == numbers[end - 1] + 1
            && zone.section_of(numbers[end]) == section
        {
            end += 1;
        }
        let cells = zone.read_elements(s, first, (end - at) as u64)?;
        for (k, (kind, nodes)) in cells.iter().enumerate() {
            let nodes = nodes.iter().map(|&v| v as u64).collect();
            read.push((first + k as i64, Some((s, kind, nodes))));
        }
        at = end;
    }
    Ok(read)
}

/// The first of the ranks' `bad` numbers in rank order, on every rank
/// (collective): each rank's block comes after the lower ranks', so it is
/// the first in the file's order.
fn first_bad(comm: &Comm, bad: Option<i64>) -> Option<i64> {
    let mine = bad.map_or([0, 0], |b| [1, b as u64]);
    comm.all_gather(&mine)
        .iter()
        .find(|m| m[0] == 1)
        .map(|m| m[1] as i64)
}

/// The index of group `name`, added when new.
fn group_index(groups: &mut Vec<String>, name: &str) -> u64 {
    let g = groups.iter().position(|n| n == name).unwrap_or_else(|| {
        groups.push(name.to_string());
        groups.len() - 1
    });
    g as u64
}

/// What the groups' facets and vertices send to the directory ranks.
#[derive(Default)]
struct OnGroups {
    /// `(node, group)` pairs, to the nodes' directory ranks.
    pairs: Vec<(u64, u64)>,
    /// The facets, to their lowest node's directory rank.
    facets: Vec<Facet>,
}

/// This rank's block of the points of condition `c` (collective): the
/// `(node, group)` pairs of its facets or vertices into `pairs`, and the
/// sections of its facets marked `covered`; nothing when it is a region.
fn condition_block(
    comm: &Comm,
    zone: &Blocks,
    c: &Condition,
    groups: &mut Vec<String>,
    (pairs, covered): (&mut OnGroups, &mut [u64]),
) -> Result<()> {
    let (size, rank) = (comm.size() as usize, comm.rank() as usize);
    let fail = |message: String| Error::Cgns {
        path: zone.path.clone(),
        message,
    };
    // A range of distinct numbers longer than the `most` the zone holds
    // names one it lacks within its first `most + 1`, where the checks
    // below find the first bad one: the rest is never spelled out (nor is
    // such a range a region).
    let most = if c.of_elements {
        zone.elements()
    } else {
        zone.vertices
    };
    let count = match c.numbers {
        Numbers::Range(..) => c.numbers.len().min(most + 1),
        Numbers::List(_) => c.numbers.len(),
    };
    let numbers: Vec<i64> = block(count, size, rank).map(|k| c.numbers.get(k)).collect();
    let dim = zone.dim;
    if !c.of_elements {
        let vertices = zone.vertices;
        let bad = numbers
            .iter()
            .copied()
            .find(|&v| v < 1 || v as u64 > vertices);
        if let Some(b) = first_bad(comm, bad) {
            return Err(fail(c.outside(b, vertices)));
        }
        let g = group_index(groups, &c.group);
        pairs
            .pairs
            .extend(numbers.iter().map(|&v| (v as u64 - 1, g)));
        return Ok(());
    }
    let read = agree(
        comm,
        read_numbered(zone, &numbers),
        "could not read a condition",
    )?;
    let kind_of = |e: &Element| e.1.as_ref().map(|(_, kind, _)| kind.dim());
    let all_cells = read.iter().all(|e| kind_of(e) == Some(dim));
    let all_cells = comm.min(u64::from(all_cells)) == 1;
    if c.is_region(zone.elements(), all_cells) {
        return Ok(());
    }
    let bad = read
        .iter()
        .find(|e| kind_of(e) != Some(dim - 1))
        .map(|e| e.0);
    if let Some(b) = first_bad(comm, bad) {
        return Err(fail(c.not_a_facet(b, dim)));
    }
    let g = group_index(groups, &c.group);
    for (s, kind, nodes) in read.into_iter().filter_map(|e| e.1) {
        covered[s] = 1;
        pairs.pairs.extend(nodes.iter().map(|&v| (v, g)));
        pairs.facets.push(Facet::new(g, kind, nodes));
    }
    Ok(())
}

/// This rank's block of the elements of the sections that may hold cells
/// or make a group of their own (`own[s]`), in file order: its cells
/// (numbers from 0, and the cells) and, into `pairs`, the `(node, group)`
/// pairs of the facets of those groups, counted in `facets`.
fn element_block(
    comm: &Comm,
    zone: &Blocks,
    own: &[Option<u64>],
    (pairs, facets): (&mut OnGroups, &mut [u64]),
) -> Result<(Vec<u64>, Cells)> {
    let (size, rank) = (comm.size() as usize, comm.rank() as usize);
    let wanted: Vec<usize> = (0..zone.sections.len())
        .filter(|&s| zone.sections[s].cells || own[s].is_some())
        .collect();
    let total = wanted.iter().map(|&s| zone.sections[s].count).sum();
    let mine = block(total, size, rank);
    let (mut numbers, mut cells) = (Vec::new(), Cells::new());
    let mut offset = 0;
    for s in wanted {
        let head = &zone.sections[s];
        let (lo, hi) = (
            mine.start.clamp(offset, offset + head.count),
            mine.end.clamp(offset, offset + head.count),
        );
        offset += head.count;
        if lo == hi {
            continue;
        }
        let first = head.first + (lo - (offset - head.count)) as i64;
        let read = zone.read_elements(s, first, hi - lo)?;
        for (k, (kind, nodes)) in read.iter().enumerate() {
            if kind.dim() == zone.dim {
                numbers.push((first + k as i64 - 1) as u64);
                cells.push(kind, nodes);
            } else if let Some(g) = own[s].filter(|_| kind.dim() + 1 == zone.dim) {
                facets[g as usize] += 1;
                let nodes: Vec<u64> = nodes.iter().map(|&v| v as u64).collect();
                pairs.pairs.extend(nodes.iter().map(|&v| (v, g)));
                pairs.facets.push(Facet::new(g, kind, nodes));
            }
        }
    }
    Ok((numbers, cells))
}

/// Reads the CGNS file at `path` in blocks on every rank (collective; see
/// the module documentation).
pub fn read(comm: &Comm, path: &Path) -> Result<Scattered> {
    let size = comm.size() as usize;
    let ranks = size as u64;
    let zone = agree(comm, Blocks::open(path), "could not open the file")?;
    let dim = zone.dim;
    // The coordinates, to the directories.
    let nodes = block(zone.vertices, size, comm.rank() as usize);
    let read = zone.coordinates(nodes.start, nodes.end - nodes.start);
    let x = agree(comm, read, "could not read the coordinates")?;
    let mut out: Vec<Vec<f64>> = vec![Vec::new(); size];
    for (g, p) in nodes.zip(x.chunks(dim)) {
        out[(g % ranks) as usize].extend_from_slice(p);
    }
    // Each rank sends its nodes in increasing order, the lower ranks the
    // lower nodes: the directory's coordinates come in the order of its nodes.
    let coords = comm.all_to_all(&out).concat();
    drop(out);
    // The conditions' groups, in file order.
    let mut groups = Vec::new();
    let mut pairs = OnGroups::default();
    let mut covered = vec![0u64; zone.sections.len()];
    for c in &zone.conditions {
        condition_block(comm, &zone, c, &mut groups, (&mut pairs, &mut covered))?;
    }
    let covered = comm.sums(&covered);
    // The sections of facets that make groups of their own.
    let mut own = vec![None; zone.sections.len()];
    for (s, head) in zone.sections.iter().enumerate() {
        if head.own_group(covered[s] > 0, &zone.conditions, &groups) {
            own[s] = Some(groups.len() as u64);
            groups.push(head.name.clone());
        }
    }
    let mut facets = vec![0u64; groups.len()];
    let read = element_block(comm, &zone, &own, (&mut pairs, &mut facets));
    let (cell_index, cells) = agree(comm, read, "could not read its elements")?;
    // A MIXED section's group without facets is no group (as on one process).
    let facets = comm.sums(&facets);
    let keep: Vec<bool> = (0..groups.len())
        .map(|g| facets[g] > 0 || !own.contains(&Some(g as u64)))
        .collect();
    let renumber: Vec<u64> = keep
        .iter()
        .scan(0u64, |next, &k| {
            *next += u64::from(k);
            Some(*next - 1)
        })
        .collect();
    let mut to: Vec<Vec<u64>> = vec![Vec::new(); size];
    for (v, g) in pairs.pairs {
        to[(v % ranks) as usize].extend([v, renumber[g as usize]]);
    }
    let on_marker = comm.all_to_all(&to);
    drop(to);
    let mut to: Vec<Vec<u64>> = vec![Vec::new(); size];
    for mut facet in pairs.facets {
        facet.marker = renumber[facet.marker as usize];
        facet.encode(&mut to[facet.directory(size)]);
    }
    let facets = decode_facets(&comm.all_to_all(&to));
    drop(to);
    let mut on_marker: Vec<(u64, u64)> = on_marker
        .iter()
        .flat_map(|list| list.chunks(2).map(|p| (p[0], p[1])))
        .collect();
    on_marker.sort_unstable();
    on_marker.dedup();
    let elements = comm.sum(cell_index.len() as u64);
    if elements == 0 {
        return Err(Error::Cgns {
            path: path.to_path_buf(),
            message: format!("{} holds no cells of dimension {dim}", zone.at),
        });
    }
    let markers = groups
        .into_iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(name, _)| name)
        .collect();
    Ok(Scattered {
        path: path.to_path_buf(),
        dim,
        points: zone.vertices,
        elements,
        cells_at: CellsAt::Zone(zone.at.clone()),
        markers,
        chunks: 0,
        cell_index,
        cell_kinds: cells.kinds.clone(),
        cell_nodes: cells
            .iter()
            .flat_map(|(_, n)| n.iter().map(|&v| v as u64))
            .collect(),
        coords,
        on_marker,
        facets,
    })
}
