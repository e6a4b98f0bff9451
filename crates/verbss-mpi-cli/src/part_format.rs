//! One rank's part of a mesh file: what `verbss-mpi` adds to
//! [`verbss::io::MeshFormat`] for the formats it reads rank by rank.
//!
//! | format | where the part comes from |
//! |---|---|
//! | Gmsh MSH 4.1, partitioned (`gmsh -part N`) | the rank's own partitions ([`verbss_mpi::share::read_rank_share`]) |
//! | SU2 | rank 0 streams the file, PT-Scotch cuts it ([`crate::su2`]) |
//! | CGNS | every rank reads blocks, PT-Scotch cuts them ([`crate::cgns`]) |

use std::path::Path;

use verbss::io::gmsh::partitioned::{partition_count, Share};
use verbss::io::{cgns::Cgns, gmsh::Msh, su2::Su2, Format};
use verbss_mpi::share::{partitions_of, read_rank_share};
use verbss_mpi::Comm;

use crate::run::told;

/// A format whose files `verbss-mpi` reads rank by rank.
pub trait PartFormat {
    /// Whether the file at `path` can be read rank by rank.
    fn holds_parts(&self, _path: &Path) -> anyhow::Result<bool> {
        Ok(true)
    }

    /// This rank's share of the file at `path` (collective), and what its
    /// progress line says of where it comes from.
    fn read_part(&self, world: &Comm, path: &Path) -> anyhow::Result<(Share, String)>;
}

/// The part reader of `format`, when it has one.
pub fn part_format(format: Format) -> Option<&'static dyn PartFormat> {
    match format {
        Format::Msh => Some(&Msh),
        Format::Su2 => Some(&Su2),
        Format::Cgns => Some(&Cgns),
        Format::Vtu | Format::Foam => None,
    }
}

impl PartFormat for Msh {
    /// A file partitioned by Gmsh (`$PartitionedEntities`).
    fn holds_parts(&self, path: &Path) -> anyhow::Result<bool> {
        Ok(partition_count(path)? > 0)
    }

    fn read_part(&self, world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
        let share = told(read_rank_share(world, path))?;
        let from = partitions_read(world, &share, path)?;
        Ok((share, from))
    }
}

impl PartFormat for Su2 {
    fn read_part(&self, world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
        crate::su2::read(world, path)
    }
}

impl PartFormat for Cgns {
    fn read_part(&self, world: &Comm, path: &Path) -> anyhow::Result<(Share, String)> {
        crate::cgns::read(world, path)
    }
}

/// What a rank's line says of the Gmsh partitions of `share` (read from
/// `path`): `partitions 1-2 of 3`, once they are checked against the ranks.
pub fn partitions_read(world: &Comm, share: &Share, path: &Path) -> anyhow::Result<String> {
    let size = world.size() as usize;
    let partitions = partitions_of(share.partitions, size, world.rank() as usize, path)?;
    Ok(format!(
        "partitions {}-{} of {}",
        partitions.start(),
        partitions.end(),
        share.partitions
    ))
}
