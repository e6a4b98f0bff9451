//! Per-rank `.vtu` pieces and the `.pvtu` that joins them for ParaView, and
//! per-rank MSH 4.1 pieces.
//!
//! Rank `r` writes `NAME_r.vtu`: the cells it owns (those whose first node
//! it owns, [`Part::own_cells`]) with their nodes, point data
//! `displacement` and `node_tag`, cell data `quality`, `rank`, `cell_tag`
//! and `group`. Rank 0 writes `NAME.pvtu` listing the pieces. Or, where no
//! rank holds the whole mesh, rank `r` writes its share as `NAME_r.msh`
//! ([`write_msh_piece`]).

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use verbss::io::gmsh::partitioned::Share;
use verbss::io::gmsh::{write_piece_to, PieceLabels};
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

/// Writes rank `rank`'s piece `dir/NAME_RANK.msh`, MSH 4.1 (binary or
/// ASCII as the input): `share`'s cells and group facets, its nodes at
/// `coords`, with the input's node and cell tags, the facet tags of
/// [`msh_facet_tags`] from `fresh` on, and the input's physical groups
/// ([`verbss::io::gmsh::write_piece_to`]); Gmsh merges the ranks' pieces
/// into the whole mesh (a node on several pieces has one tag).
pub fn write_msh_piece(
    dir: &Path,
    name: &str,
    rank: i32,
    share: &Share,
    fresh: u64,
    coords: &[f64],
) -> Result<PathBuf> {
    let path = dir.join(format!("{name}_{rank}.msh"));
    let labels = PieceLabels {
        facet_tags: Some(msh_facet_tags(share, fresh)),
        domain: share.labels.domain.clone(),
    };
    write_atomic(&path, |w| {
        write_piece_to(w, &share.mesh, coords, &labels, share.binary)
    })?;
    Ok(path)
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
}
