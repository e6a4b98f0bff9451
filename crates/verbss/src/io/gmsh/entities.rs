//! MSH 4.1 `$Entities` and `$PartitionedEntities`: the physical tags of
//! each geometric entity, which the element blocks refer to.

use std::collections::{HashMap, HashSet};
use std::ops::Range;

use super::cursor::{i32_at, Cursor};
use super::{close, early_end};
use crate::error::Result;

/// The physical tags of each geometric entity `(dimension, tag)`, model and
/// partition entities alike.
#[derive(Default)]
pub(super) struct Entities {
    /// Whether the file had an `$Entities` section.
    pub present: bool,
    /// The range of [`Entities::physicals`] of each entity.
    pub map: HashMap<(usize, i32), Range<usize>>,
    /// The physical tags of all entities, concatenated.
    pub physicals: Vec<i32>,
}

const ENTITY_KINDS: [&str; 4] = ["points", "curves", "surfaces", "volumes"];

/// Reads the body of `$Entities` and its closing keyword: per entity
/// `tag, x y z (points) or a bounding box, physical tags, bounding entities`.
pub(super) fn read_entities(c: &mut Cursor, entities: &mut Entities) -> Result<()> {
    entities.present = true;
    if c.binary() {
        c.newline()?;
    }
    read_all(c, entities, "$Entities", false)?;
    Ok(())
}

/// Reads the body of `$PartitionedEntities` and its closing keyword: the
/// number of partitions, the ghost entities (`tag partition` pairs), then
/// per entity `tag, parent dimension, parent tag, partitions`, followed by
/// what `$Entities` holds for an entity.
pub(super) fn read_partitioned(c: &mut Cursor, entities: &mut Entities) -> Result<()> {
    if c.binary() {
        c.newline()?;
        c.count_le("the number of partitions")?;
        let ghosts = c.count_le("the number of ghost entities")?;
        c.take_n(ghosts, 8, "the ghost entities")?;
    } else {
        c.count("the number of partitions")?;
        let ghosts = c.count("the number of ghost entities")?;
        for i in 0..ghosts {
            early_end(c, || {
                format!("$PartitionedEntities declares {ghosts} ghost entities but ends after {i}")
            })?;
            c.int("a ghost entity tag")?;
            c.int("a partition tag")?;
        }
    }
    read_all(c, entities, "$PartitionedEntities", true)
}

/// Reads the four entity counts and the entities of `section`, then its
/// closing keyword.
fn read_all(
    c: &mut Cursor,
    entities: &mut Entities,
    section: &str,
    partitioned: bool,
) -> Result<()> {
    let mut counts = [0usize; 4];
    for n in &mut counts {
        *n = if c.binary() {
            c.count_le("an entity count")?
        } else {
            c.count("an entity count")?
        };
    }
    for (dim, &n) in counts.iter().enumerate() {
        for i in 0..n {
            if !c.binary() {
                early_end(c, || {
                    format!(
                        "{section} declares {n} {} but ends after {i}",
                        ENTITY_KINDS[dim]
                    )
                })?;
            }
            let start = entities.physicals.len();
            let tag = if c.binary() {
                read_binary(c, dim, partitioned, &mut entities.physicals)?
            } else {
                read_ascii(c, dim, partitioned, &mut entities.physicals)?
            };
            dedupe(&mut entities.physicals, start);
            entities
                .map
                .insert((dim, tag), start..entities.physicals.len());
        }
    }
    close(
        c,
        &format!("$End{}", &section[1..]),
        counts.iter().sum(),
        "entities",
    )
}

/// Reads one binary entity of dimension `dim`; appends its physical tags to
/// `physicals` and returns its tag.
fn read_binary(
    c: &mut Cursor,
    dim: usize,
    partitioned: bool,
    physicals: &mut Vec<i32>,
) -> Result<i32> {
    let tag = c.i32_le("an entity tag")?;
    if partitioned {
        c.take(8, "the parent entity")?;
        let np = c.count_le("a number of partitions")?;
        c.take_n(np, 4, "partition tags")?;
    }
    // A point stores x y z, the others a bounding box.
    c.take(if dim == 0 { 24 } else { 48 }, "an entity's coordinates")?;
    let np = c.count_le("a number of physical tags")?;
    let tags = c.take_n(np, 4, "physical tags")?;
    physicals.extend(tags.chunks_exact(4).map(|b| i32_at(b, 0)));
    if dim > 0 {
        let nb = c.count_le("a number of bounding entities")?;
        c.take_n(nb, 4, "bounding entities")?;
    }
    Ok(tag)
}

/// Reads one ASCII entity of dimension `dim`; appends its physical tags to
/// `physicals` and returns its tag.
fn read_ascii(
    c: &mut Cursor,
    dim: usize,
    partitioned: bool,
    physicals: &mut Vec<i32>,
) -> Result<i32> {
    let tag = c.int("an entity tag")?;
    if partitioned {
        c.int("a parent entity dimension")?;
        c.int("a parent entity tag")?;
        let np = c.count("a number of partitions")?;
        for _ in 0..np {
            c.int("a partition tag")?;
        }
    }
    for _ in 0..if dim == 0 { 3 } else { 6 } {
        c.float("a coordinate")?;
    }
    let np = c.count("a number of physical tags")?;
    for _ in 0..np {
        physicals.push(c.int("a physical tag")?);
    }
    if dim > 0 {
        let nb = c.count("a number of bounding entities")?;
        for _ in 0..nb {
            c.int("a bounding entity tag")?;
        }
    }
    Ok(tag)
}

/// Drops repeated tags from `tags[start..]`, keeping the first of each.
fn dedupe(tags: &mut Vec<i32>, start: usize) {
    let mut seen = HashSet::new();
    let mut kept = start;
    for i in start..tags.len() {
        if seen.insert(tags[i]) {
            tags[kept] = tags[i];
            kept += 1;
        }
    }
    tags.truncate(kept);
}
