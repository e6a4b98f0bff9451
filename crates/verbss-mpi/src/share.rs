//! A rank's share of a partitioned MSH 4.1 file (`gmsh -part K`), read by
//! the rank itself: no rank stores or receives the whole mesh (each steps
//! over the other partitions' blocks of the file).
//!
//! **Partitions to ranks.** The file's `K` partitions go to the `P` ranks
//! in contiguous blocks: rank `r` reads partitions `⌊rK/P⌋ + 1 ..=
//! ⌊(r+1)K/P⌋` ([`partitions_of`]), so `K = P` gives one partition per
//! rank and `K = 6, P = 3` two. A file with fewer partitions than ranks is
//! refused (a rank would have nothing).
//!
//! **Reading.** Each rank streams the file once and keeps only its
//! partitions' node and element blocks
//! ([`verbss::io::gmsh::partitioned::read_share`]): its cells, and the nodes
//! of its partitions' entities, each node with its global number (its
//! Gmsh tag − 1), whether it is on the boundary and on which groups.
//!
//! **Ghosts.** The ghost layer comes from one exchange in
//! [`LocalSolver::new`](crate::coupled::LocalSolver::new): each node's
//! owner is the lowest rank holding it, and every rank sends each of its
//! cells to the owners of the cell's nodes, so that an owner holds every
//! cell around its nodes — its own and those of the neighbouring
//! partitions — and their other nodes as ghosts
//! ([`crate::part::Part`]). A rank's memory then holds its partitions plus
//! one layer of cells.
//!
//! **Roles.** The nodes of the moving groups and the other boundary nodes
//! are prescribed ([`NodeRole::Fixed`]), the others free, as in
//! `verbss deform` without sliding groups; every rank holding a node gives
//! it the same role, from the file's entities.

use std::ops::RangeInclusive;
use std::path::Path;

use verbss::io::gmsh::partitioned::Share;
use verbss::solve::NodeRole;
use verbss::{Error, Result};

/// The partitions (1-based) that rank `rank` of `ranks` reads from a file
/// of `partitions` partitions (see the module documentation); `path` names
/// the file in the error.
pub fn partitions_of(
    partitions: usize,
    ranks: usize,
    rank: usize,
    path: &Path,
) -> Result<RangeInclusive<usize>> {
    if partitions < ranks {
        return Err(Error::InvalidSetting(format!(
            "{} has {partitions} partitions, fewer than the {ranks} ranks: start at most \
             {partitions} ranks, or partition the mesh again with `gmsh -part {ranks} \
             -format msh41`",
            path.display()
        )));
    }
    Ok(rank * partitions / ranks + 1..=(rank + 1) * partitions / ranks)
}

/// The global number of each node of `share`: its Gmsh tag − 1.
pub fn global_numbers(share: &Share) -> Vec<u64> {
    share.mesh.node_tags.iter().map(|&t| t - 1).collect()
}

/// The roles of the nodes of `share` and the prescribed displacement
/// (`D` per node) when the groups `moving` move by `displacement(x)`
/// (a function of a node's coordinates): moving nodes and the other
/// boundary nodes fixed, the others free. Fails when a group is not in the
/// file (the same answer on every rank) or `displacement` fails.
pub fn prescribe(
    share: &Share,
    moving: &[String],
    displacement: impl Fn(&[f64]) -> Result<Vec<f64>>,
) -> Result<(Vec<NodeRole>, Vec<f64>)> {
    let mesh = &share.mesh;
    let dim = mesh.dim;
    let mut roles: Vec<NodeRole> = share
        .boundary
        .iter()
        .map(|&b| if b { NodeRole::Fixed } else { NodeRole::Free })
        .collect();
    let mut u = vec![0.0; dim * mesh.node_count()];
    for name in moving {
        let Some((_, nodes)) = share.group_nodes.iter().find(|(g, _)| g == name) else {
            let available: Vec<&str> = share.group_nodes.iter().map(|(g, _)| g.as_str()).collect();
            return Err(Error::UnknownGroup {
                name: name.clone(),
                available: available.join(", "),
            });
        };
        for &i in nodes {
            roles[i] = NodeRole::Fixed;
            u[dim * i..dim * (i + 1)].copy_from_slice(&displacement(mesh.point(i))?);
        }
    }
    Ok((roles, u))
}

#[cfg(with_mpi)]
pub use with_mpi::{agree, read_rank_share, read_rank_split};

#[cfg(with_mpi)]
mod with_mpi {
    use std::collections::HashMap;
    use std::path::Path;

    use verbss::io::gmsh::partitioned::{partition_count, read_share, Share};
    use verbss::io::gmsh::split::{read_split, split_count};
    use verbss::{Error, Result};

    use super::partitions_of;
    use crate::Comm;

    /// Reads this rank's share of the partitioned MSH 4.1 file at `path`
    /// (collective: where one rank fails, every rank returns the error of
    /// the lowest failing rank, so that no rank waits for the others).
    pub fn read_rank_share(comm: &Comm, path: &Path) -> Result<Share> {
        let read = || -> Result<Share> {
            let count = partition_count(path)?;
            if count == 0 {
                // The reader's error: the file is not partitioned.
                return read_share(path, 1..=1);
            }
            let wanted = partitions_of(count, comm.size() as usize, comm.rank() as usize, path)?;
            read_share(path, wanted)
        };
        joined(comm, read())
    }

    /// Reads this rank's share of the split set whose first file is
    /// `first` (`NAME_1.msh`, [`verbss::io::gmsh::split`]): partition `k`
    /// from `NAME_k.msh`, only the files of this rank's partitions
    /// (collective, as [`read_rank_share`]).
    pub fn read_rank_split(comm: &Comm, first: &Path) -> Result<Share> {
        let read = || -> Result<Share> {
            let count = split_count(first)?;
            let wanted = partitions_of(count, comm.size() as usize, comm.rank() as usize, first)?;
            read_split(first, wanted)
        };
        joined(comm, read())
    }

    /// `read` on every rank where every rank read its share, with the
    /// ranks' roles joined (collective).
    fn joined(comm: &Comm, read: Result<Share>) -> Result<Share> {
        let mut share = agree(comm, read, "could not read its share")?;
        join_roles(comm, &mut share);
        Ok(share)
    }

    /// Makes every rank that holds a node agree on whether it is on the
    /// boundary and on which groups (collective): each rank tells the
    /// directory rank of each of its nodes (its file tag mod `P`) what its
    /// share says, and takes back what all the shares say together. A share
    /// can miss a group of a node whose facets only other partitions hold
    /// (`verbss::io::gmsh::partitioned`, module documentation).
    fn join_roles(comm: &Comm, share: &mut Share) {
        let n = share.mesh.node_count();
        // Bit 0: on the boundary; bit k + 1: on group k.
        let words = (share.group_nodes.len() + 1).div_ceil(64);
        let mut bits = vec![0u64; n * words];
        let mut set = |i: usize, bit: usize| bits[i * words + bit / 64] |= 1 << (bit % 64);
        for i in (0..n).filter(|&i| share.boundary[i]) {
            set(i, 0);
        }
        for (k, (_, nodes)) in share.group_nodes.iter().enumerate() {
            for &i in nodes {
                set(i, k + 1);
            }
        }
        let size = comm.size() as u64;
        let mut told: Vec<Vec<u64>> = vec![Vec::new(); size as usize];
        for (i, &tag) in share.mesh.node_tags.iter().enumerate() {
            let to = &mut told[(tag % size) as usize];
            to.push(tag);
            to.extend_from_slice(&bits[i * words..(i + 1) * words]);
        }
        let mut joined: HashMap<u64, Vec<u64>> = HashMap::new();
        for record in comm
            .all_to_all(&told)
            .iter()
            .flat_map(|l| l.chunks_exact(1 + words))
        {
            let all = joined.entry(record[0]).or_insert_with(|| vec![0; words]);
            for (a, b) in all.iter_mut().zip(&record[1..]) {
                *a |= b;
            }
        }
        let agreed = crate::directory::ask(comm, &share.mesh.node_tags, |tag| joined[&tag].clone());
        let on = |i: usize, bit: usize| agreed[i][bit / 64] >> (bit % 64) & 1 == 1;
        for (i, boundary) in share.boundary.iter_mut().enumerate() {
            *boundary = on(i, 0);
        }
        for (k, (_, nodes)) in share.group_nodes.iter_mut().enumerate() {
            *nodes = (0..n).filter(|&i| on(i, k + 1)).collect();
        }
    }

    /// `result` on every rank where every rank's is `Ok` (collective);
    /// otherwise every rank returns an error: the failing ranks their own,
    /// the others the lowest failing rank's, as `rank R WHAT: MESSAGE`. So
    /// that no rank goes on to wait for the others.
    pub fn agree<T>(comm: &Comm, result: Result<T>, what: &str) -> Result<T> {
        let message = result
            .as_ref()
            .err()
            .map_or_else(Vec::new, |e| e.to_string().into_bytes());
        let all = comm.all_gather(&message);
        match all.iter().position(|m| !m.is_empty()) {
            None => result,
            Some(_) if result.is_err() => result,
            Some(r) => Err(Error::InvalidMesh(format!(
                "rank {r} {what}: {}",
                String::from_utf8_lossy(&all[r])
            ))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partitions_go_to_ranks_in_contiguous_blocks() {
        let path = Path::new("m.msh");
        let blocks = |k, p| -> Vec<RangeInclusive<usize>> {
            (0..p)
                .map(|r| partitions_of(k, p, r, path).unwrap())
                .collect()
        };
        assert_eq!(blocks(3, 3), [1..=1, 2..=2, 3..=3]);
        assert_eq!(blocks(3, 2), [1..=1, 2..=3]);
        assert_eq!(blocks(3, 1), [1..=3]);
        assert_eq!(blocks(6, 4), [1..=1, 2..=3, 4..=4, 5..=6]);
        let e = partitions_of(2, 3, 0, path).unwrap_err().to_string();
        assert!(
            e.contains("m.msh has 2 partitions, fewer than the 3 ranks"),
            "{e}"
        );
    }
}
