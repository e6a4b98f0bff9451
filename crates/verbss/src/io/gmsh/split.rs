//! A set of files of one partitioned mesh, one file a partition, as
//! `gmsh -part K -part_split -o NAME.msh` writes them: `NAME_1.msh` to
//! `NAME_K.msh`.
//!
//! Every file of such a set repeats the whole mesh's `$PhysicalNames`,
//! `$Entities` and `$PartitionedEntities` (`K` partitions), and holds of
//! `$Nodes` and `$Elements` only the blocks of its own partition: its
//! partition's elements and every node they use. [`read_split`] reads
//! partition `k` from file `NAME_k.msh` alone ([`super::partitioned::read_share`])
//! and joins the partitions asked for into one [`Share`], a node of
//! several of them once.

use std::collections::HashMap;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use super::partitioned::{partition_count, read_share, Share};
use crate::error::{Error, Result};
use crate::mesh::{Cells, Group};

/// `NAME_k.msh` beside `first`, the set's first file `NAME_1.msh`.
pub fn split_file(first: &Path, k: usize) -> Result<PathBuf> {
    let stem = split_stem(first)?;
    Ok(first.with_file_name(format!("{stem}_{k}.msh")))
}

/// `NAME` of a set's first file `NAME_1.msh`; fails for another name.
fn split_stem(first: &Path) -> Result<String> {
    first
        .file_name()
        .and_then(|n| n.to_str())
        .and_then(|n| n.strip_suffix("_1.msh"))
        .filter(|stem| !stem.is_empty())
        .map(str::to_string)
        .ok_or_else(|| {
            Error::InvalidSetting(format!(
                "{}: a split set is named by its first file, NAME_1.msh (as `gmsh -part K \
                 -part_split -o NAME.msh` writes NAME_1.msh to NAME_K.msh)",
                first.display()
            ))
        })
}

/// The number of partitions `K` of the split set whose first file is
/// `first` (`NAME_1.msh`), checking that `NAME_1.msh` to `NAME_K.msh`
/// exist and that no `NAME_{K+1}.msh` does (a file of another set).
pub fn split_count(first: &Path) -> Result<usize> {
    split_stem(first)?;
    let count = partition_count(first)?;
    if count == 0 {
        return Err(Error::InvalidSetting(format!(
            "{}: not a partitioned file (no $PartitionedEntities): a split set is written by \
             `gmsh -part K -part_split -format msh41` or `verbss-mpi deform --pieces`",
            first.display()
        )));
    }
    for k in 2..=count {
        let file = split_file(first, k)?;
        if !file.is_file() {
            return Err(Error::InvalidSetting(format!(
                "{}: missing: {} declares {count} partitions, in files _1 to _{count} (a \
                 single partitioned file holding every partition is not a split set: read it \
                 without --split)",
                file.display(),
                first.display()
            )));
        }
    }
    let extra = split_file(first, count + 1)?;
    if extra.exists() {
        return Err(Error::InvalidSetting(format!(
            "{} exists, but {} declares {count} partitions: remove the files of another set",
            extra.display(),
            first.display()
        )));
    }
    Ok(count)
}

/// Reads partitions `wanted` of the split set whose first file is `first`:
/// partition `k` from `NAME_k.msh` only, which must declare as many
/// partitions as `NAME_1.msh` and hold elements of partition `k`.
pub fn read_split(first: &Path, wanted: RangeInclusive<usize>) -> Result<Share> {
    let count = split_count(first)?;
    if wanted.is_empty() || *wanted.start() == 0 || *wanted.end() > count {
        return Err(Error::InvalidSetting(format!(
            "partitions {}..={} of the set {}, which has {count} (numbered from 1)",
            wanted.start(),
            wanted.end(),
            first.display()
        )));
    }
    let mut joined: Option<Share> = None;
    for k in wanted {
        let file = split_file(first, k)?;
        let declared = partition_count(&file)?;
        if declared != count {
            return Err(Error::InvalidSetting(format!(
                "{} declares {declared} partitions, {} {count}: the files are not of one set",
                file.display(),
                first.display()
            )));
        }
        let other = || format!("is {} partition {k} of the set?", file.display());
        // `read_share` fails where the file holds no element of partition `k`.
        let share = read_share(&file, k..=k)
            .map_err(|e| Error::InvalidMesh(format!("{e} ({})", other())))?;
        joined = Some(match joined {
            None => share,
            Some(mut all) => {
                join(&mut all, share);
                all
            }
        });
    }
    joined.ok_or_else(|| Error::InvalidSetting("no partition asked for".into()))
}

/// Adds `other` (a partition of the same file set) to `all`: a node both
/// hold (by tag) once, on the boundary or a group when either says so.
fn join(all: &mut Share, other: Share) {
    let dim = all.mesh.dim;
    let mut index: HashMap<u64, usize> = all
        .mesh
        .node_tags
        .iter()
        .enumerate()
        .map(|(i, &t)| (t, i))
        .collect();
    let mut map = Vec::with_capacity(other.mesh.node_count());
    for (i, &tag) in other.mesh.node_tags.iter().enumerate() {
        let next = all.mesh.node_tags.len();
        let at = *index.entry(tag).or_insert(next);
        if at == next {
            all.mesh.node_tags.push(tag);
            all.mesh
                .coords
                .extend_from_slice(&other.mesh.coords[dim * i..dim * (i + 1)]);
            all.boundary.push(false);
        }
        all.boundary[at] |= other.boundary[i];
        map.push(at);
    }
    let renumber = |cells: &Cells, into: &mut Cells| {
        for (kind, nodes) in cells.iter() {
            let nodes: Vec<usize> = nodes.iter().map(|&v| map[v]).collect();
            into.push(kind, &nodes);
        }
    };
    renumber(&other.mesh.cells, &mut all.mesh.cells);
    all.mesh.cell_tags.extend(&other.mesh.cell_tags);
    let other_tags = other.labels.facet_tags.unwrap_or_default();
    for (g, group) in other.mesh.groups.iter().enumerate() {
        let k = match all.mesh.groups.iter().position(|h| h.name == group.name) {
            Some(k) => k,
            None => {
                all.mesh.groups.push(Group {
                    name: group.name.clone(),
                    tag: group.tag,
                    facets: Cells::new(),
                });
                if let Some(tags) = all.labels.facet_tags.as_mut() {
                    tags.push(Vec::new());
                }
                all.mesh.groups.len() - 1
            }
        };
        renumber(&group.facets, &mut all.mesh.groups[k].facets);
        if let Some(tags) = all.labels.facet_tags.as_mut() {
            tags[k].extend(other_tags.get(g).into_iter().flatten());
        }
    }
    for (name, nodes) in other.group_nodes {
        let mapped = nodes.iter().map(|&i| map[i]);
        match all.group_nodes.iter_mut().find(|(n, _)| *n == name) {
            Some((_, list)) => {
                list.extend(mapped);
                list.sort_unstable();
                list.dedup();
            }
            None => all.group_nodes.push((name, mapped.collect())),
        }
    }
}
