//! Per-rank `.vtu` pieces and the `.pvtu` that joins them for ParaView, and
//! per-rank MSH 4.1 pieces.
//!
//! Rank `r` writes `NAME_r.vtu`: the cells it owns (those whose first node
//! it owns, [`Part::own_cells`]) with their nodes, point data
//! `displacement` and `node_tag`, cell data `quality`, `rank`, `cell_tag`
//! and `group`. Rank 0 writes `NAME.pvtu` listing the pieces. Or, where no
//! rank holds the whole mesh, rank `r` writes its share as partition `r + 1`
//! of a split set, `NAME_{r+1}.msh` ([`write_msh_piece`]), in the form of
//! `gmsh -part P -part_split`.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use verbss::io::gmsh::partitioned::Share;
use verbss::io::gmsh::split_write::{
    write_split_piece_to, SplitEntity, SplitGroup, SplitModel, SplitParent, SplitPiece,
};
#[cfg(test)]
use verbss::io::gmsh::PieceLabels;
use verbss::io::{vtu, write_atomic};
use verbss::mesh::FileOrigin;
use verbss::{Cells, Mesh, Result};

use crate::part::Part;

/// Writes rank `part.rank`'s piece of the whole-mesh configuration
/// `coords` (displacements from `initial`, per-cell `quality`) as
/// `dir/NAME_RANK.vtu`.
pub fn write_piece(
    dir: &Path,
    name: &str,
    part: &Part,
    initial: &Mesh,
    coords: &[f64],
    quality: &[f64],
) -> Result<()> {
    let dim = part.dim;
    let cells = part.own_cells();
    let mut local = vec![u32::MAX; part.node_count()];
    let mut nodes = Vec::new();
    for &c in &cells {
        for &v in part.cells.cell(c) {
            if local[v] == u32::MAX {
                local[v] = 0;
            }
        }
    }
    for (i, l) in local.iter_mut().enumerate() {
        if *l == 0 {
            *l = nodes.len() as u32;
            nodes.push(i);
        }
    }
    let mut piece_cells = Cells::new();
    for &c in &cells {
        let renumbered: Vec<usize> = part
            .cells
            .cell(c)
            .iter()
            .map(|&v| local[v] as usize)
            .collect();
        piece_cells.push(part.cells.kinds[c], &renumbered);
    }
    let mut points = Vec::with_capacity(dim * nodes.len());
    let mut displacement = vec![0.0; 3 * nodes.len()];
    for (k, &i) in nodes.iter().enumerate() {
        let g = part.global[i] as usize;
        points.extend_from_slice(&coords[dim * g..dim * (g + 1)]);
        for d in 0..dim {
            displacement[3 * k + d] = coords[dim * g + d] - initial.coords[dim * g + d];
        }
    }
    let mesh = Mesh {
        dim,
        coords: points,
        node_tags: nodes.iter().map(|&i| part.node_tags[i]).collect(),
        cells: piece_cells,
        cell_tags: cells.iter().map(|&c| part.cell_tags[c]).collect(),
        groups: Vec::new(),
        origin: FileOrigin::default(),
    };
    let quality = cells
        .iter()
        .map(|&c| quality[part.cell_global[c] as usize])
        .collect();
    write_local_piece(dir, name, part.rank, &mesh, displacement, quality)
}

/// Writes rank `rank`'s piece `dir/NAME_RANK.vtu`: `mesh` (its cells, at
/// their moved coordinates, with their tags), the `displacement` of its
/// nodes (3 numbers each) and the `quality` of its cells.
pub fn write_local_piece(
    dir: &Path,
    name: &str,
    rank: i32,
    mesh: &Mesh,
    displacement: Vec<f64>,
    quality: Vec<f64>,
) -> Result<()> {
    let cells = mesh.cell_count();
    let mut fields = vtu::Fields::default();
    fields.point.push(("displacement".into(), 3, displacement));
    fields.cell.push(("quality".into(), 1, quality));
    fields
        .cell
        .push(("rank".into(), 1, vec![f64::from(rank); cells]));
    vtu::write(&piece_path(dir, name, rank), mesh, &fields)
}

/// `dir/NAME_RANK.vtu`.
pub fn piece_path(dir: &Path, name: &str, rank: i32) -> PathBuf {
    dir.join(format!("{name}_{rank}.vtu"))
}

/// Writes partition `partition` of the split set of `model`,
/// `dir/NAME_PARTITION.msh`, MSH 4.1 (`binary` or ASCII):
/// `share`'s cells and group facets (those of group `k` of the share being
/// group `groups[k]` of the model), its nodes at `coords`, with the input's
/// node and cell tags and the facet tags `facet_tags`
/// ([`msh_facet_tags`]).
pub fn write_msh_piece(
    (dir, name): (&Path, &str),
    share: &Share,
    model: &SplitModel,
    (partition, groups, facet_tags): (usize, &[usize], &[Vec<u64>]),
    coords: &[f64],
    binary: bool,
) -> Result<PathBuf> {
    let path = split_path(dir, name, partition);
    let piece = SplitPiece {
        mesh: &share.mesh,
        coords,
        boundary: &share.boundary,
        groups,
        facet_tags,
        partition,
    };
    write_atomic(&path, |w| write_split_piece_to(w, model, &piece, binary))?;
    Ok(path)
}

/// `dir/NAME_PARTITION.msh`, a file of a split set.
pub fn split_path(dir: &Path, name: &str, partition: usize) -> PathBuf {
    dir.join(format!("{name}_{partition}.msh"))
}

/// A share's groups for the model of a split set: per group, its
/// dimension, tag (0 for none) and name, each ended by a zero byte.
pub fn encode_groups(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    for g in &mesh.groups {
        let dim = g.facets.kinds.first().map_or(mesh.dim - 1, |k| k.dim());
        out.extend(format!("{dim}\t{}\t{}\0", g.tag.unwrap_or(0), g.name).bytes());
    }
    out
}

/// The groups of a split set from every share's [`encode_groups`]: by
/// name, each with its tag where positive and unique within its dimension,
/// else a fresh one above every tag; and the cells' physical group,
/// `domain` where given, else a fresh tag named `domain`.
pub fn split_groups(
    encoded: &[Vec<u8>],
    domain: Option<(i32, String)>,
) -> (Vec<SplitGroup>, (i32, String)) {
    let mut seen: Vec<(String, usize, i32)> = Vec::new();
    for record in encoded.iter().flat_map(|e| e.split(|&b| b == 0)) {
        let text = String::from_utf8_lossy(record);
        let mut fields = text.splitn(3, '\t');
        let (Some(dim), Some(tag), Some(name)) = (fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        if !seen.iter().any(|(n, ..)| n == name) {
            let parse = |s: &str| s.parse().unwrap_or(0);
            seen.push((name.to_string(), parse(dim) as usize, parse(tag)));
        }
    }
    seen.sort();
    let mut next = seen.iter().map(|g| g.2).max().unwrap_or(0).max(0) + 1;
    let mut used = HashSet::new();
    let mut groups = Vec::new();
    for (name, dim, tag) in seen {
        let physical = if tag > 0 && used.insert((dim, tag)) {
            tag
        } else {
            next += 1;
            next - 1
        };
        groups.push(SplitGroup {
            name,
            dim,
            physical,
        });
    }
    let domain = domain
        .filter(|(t, n)| *t > 0 && !n.contains(['"', '\n', '\r']))
        .unwrap_or((next, "domain".into()));
    (groups, domain)
}

/// Partition entities as numbers for an all-gather: per entity its
/// partition, parent (−1 the domain, −2 the boundary, else the group) and
/// bounding box.
pub fn encode_entities(entities: &[SplitEntity]) -> Vec<f64> {
    let mut out = Vec::new();
    for e in entities {
        let parent = match e.parent {
            SplitParent::Domain => -1.0,
            SplitParent::Boundary => -2.0,
            SplitParent::Group(g) => g as f64,
        };
        out.extend([e.partition as f64, parent]);
        out.extend(e.bbox);
    }
    out
}

/// The partition entities of every rank's [`encode_entities`], in order
/// of partition and parent.
pub fn decode_entities(all: &[Vec<f64>]) -> Vec<SplitEntity> {
    let mut out: Vec<SplitEntity> = all
        .iter()
        .flat_map(|e| e.chunks_exact(8))
        .map(|r| SplitEntity {
            partition: r[0] as usize,
            parent: match r[1] as i64 {
                -1 => SplitParent::Domain,
                -2 => SplitParent::Boundary,
                g => SplitParent::Group(g as usize),
            },
            bbox: r[2..8].try_into().unwrap_or([0.0; 6]),
        })
        .collect();
    out.sort_by_key(|e| (e.partition, e.parent));
    out
}

/// The element tags of the group facets of `share` in its MSH piece: the
/// file's, except that a facet in several groups (an element written once
/// per group) and every facet of a file that gave none (SU2) take fresh
/// tags `fresh`, `fresh + 1`, …: at most one per facet.
pub fn msh_facet_tags(share: &Share, fresh: u64) -> Vec<Vec<u64>> {
    let groups = &share.mesh.groups;
    let file = share.labels.facet_tags.as_ref().filter(|tags| {
        tags.len() == groups.len()
            && tags
                .iter()
                .zip(groups)
                .all(|(t, g)| t.len() == g.facets.len())
    });
    let mut taken: HashSet<u64> = share.mesh.cell_tags.iter().copied().collect();
    let mut next = fresh;
    let mut tag = |file_tag: Option<u64>| match file_tag {
        Some(t) if taken.insert(t) => t,
        _ => {
            next += 1;
            next - 1
        }
    };
    groups
        .iter()
        .enumerate()
        .map(|(k, g)| {
            (0..g.facets.len())
                .map(|f| tag(file.map(|tags| tags[k][f])))
                .collect()
        })
        .collect()
}

/// Writes `dir/NAME.pvtu` joining the pieces of ranks `0..ranks`.
pub fn write_pvtu(dir: &Path, name: &str, ranks: i32) -> Result<()> {
    write_atomic(&dir.join(format!("{name}.pvtu")), |w| {
        writeln!(w, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            w,
            r#"<VTKFile type="PUnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
        )?;
        writeln!(w, r#"  <PUnstructuredGrid GhostLevel="0">"#)?;
        writeln!(w, r#"    <PPointData Vectors="displacement">"#)?;
        writeln!(w, r#"      <PDataArray type="Int64" Name="node_tag"/>"#)?;
        writeln!(
            w,
            r#"      <PDataArray type="Float64" Name="displacement" NumberOfComponents="3"/>"#
        )?;
        writeln!(w, "    </PPointData>")?;
        writeln!(w, r#"    <PCellData Scalars="quality">"#)?;
        writeln!(w, r#"      <PDataArray type="Int32" Name="group"/>"#)?;
        writeln!(w, r#"      <PDataArray type="Int64" Name="cell_tag"/>"#)?;
        writeln!(w, r#"      <PDataArray type="Float64" Name="quality"/>"#)?;
        writeln!(w, r#"      <PDataArray type="Float64" Name="rank"/>"#)?;
        writeln!(w, "    </PCellData>")?;
        writeln!(w, "    <PPoints>")?;
        writeln!(
            w,
            r#"      <PDataArray type="Float64" Name="Points" NumberOfComponents="3"/>"#
        )?;
        writeln!(w, "    </PPoints>")?;
        for r in 0..ranks {
            writeln!(w, r#"    <Piece Source="{name}_{r}.vtu"/>"#)?;
        }
        writeln!(w, "  </PUnstructuredGrid>")?;
        writeln!(w, "</VTKFile>")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use verbss::mesh::{CellKind, Group};

    /// Two triangles; the edge 0–1 in two groups, the edge 1–2 in one.
    fn share(labels: PieceLabels) -> Share {
        let mut cells = Cells::new();
        cells.push(CellKind::Triangle, &[0, 1, 2]);
        cells.push(CellKind::Triangle, &[1, 3, 2]);
        let edge = |a: usize, b: usize| {
            let mut facets = Cells::new();
            facets.push(CellKind::Line, &[a, b]);
            facets
        };
        let group = |name: &str, tag: i32, facets: Cells| Group {
            name: name.into(),
            tag: Some(tag),
            facets,
        };
        let mut both = edge(0, 1);
        both.push(CellKind::Line, &[1, 3]);
        Share {
            mesh: Mesh {
                dim: 2,
                coords: vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                node_tags: vec![1, 2, 3, 4],
                cells,
                cell_tags: vec![20, 21],
                groups: vec![group("wall", 1, edge(0, 1)), group("all", 2, both)],
                origin: FileOrigin::default(),
            },
            boundary: vec![true; 4],
            partitions: 1,
            group_nodes: Vec::new(),
            binary: false,
            labels,
        }
    }

    /// The file's facet tags are kept; a facet written a second time (in a
    /// second group) and facets the file gave no tag take fresh ones.
    #[test]
    fn repeated_and_untagged_facets_take_fresh_tags() {
        let file = PieceLabels {
            facet_tags: Some(vec![vec![7], vec![7, 9]]),
            domain: None,
        };
        assert_eq!(msh_facet_tags(&share(file), 100), [vec![7], vec![100, 9]]);
        let none = share(PieceLabels::default());
        assert_eq!(msh_facet_tags(&none, 100), [vec![100], vec![101, 102]]);
    }

    /// The set's groups are every share's, by name, with their own tags
    /// unless taken or missing; the cells' group is the file's, else a
    /// fresh `domain`; the partition entities come back in order.
    #[test]
    fn split_models_agree_across_shares() {
        let s = share(PieceLabels::default());
        let mut other = s.mesh.clone();
        other.groups[0].name = "inlet".into();
        other.groups[1].tag = None;
        let encoded = [encode_groups(&s.mesh), encode_groups(&other)];
        let (groups, domain) = split_groups(&encoded, None);
        let named: Vec<(&str, usize, i32)> = groups
            .iter()
            .map(|g| (g.name.as_str(), g.dim, g.physical))
            .collect();
        // "inlet" and "wall" both say 1: the first by name keeps it.
        assert_eq!(named, [("all", 1, 2), ("inlet", 1, 1), ("wall", 1, 3)]);
        assert_eq!(domain, (4, "domain".to_string()));
        let (_, domain) = split_groups(&encoded, Some((7, "fluid".into())));
        assert_eq!(domain, (7, "fluid".to_string()));
        let entity = |partition, parent| SplitEntity {
            partition,
            parent,
            bbox: [0.0, 1.0, 2.0, 3.0, 4.0, 5.0],
        };
        let two = vec![
            entity(2, SplitParent::Group(1)),
            entity(2, SplitParent::Domain),
        ];
        let one = vec![entity(1, SplitParent::Boundary)];
        let back = decode_entities(&[encode_entities(&two), encode_entities(&one)]);
        assert_eq!(back, [one[0].clone(), two[1].clone(), two[0].clone()]);
    }
}
