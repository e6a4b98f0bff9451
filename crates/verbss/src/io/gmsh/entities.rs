//! MSH 4.1 `$Entities` and `$PartitionedEntities`: the physical tags of
//! each geometric entity, which the element blocks refer to, the entities
//! bounding each model entity, and the parent and partitions of each
//! partition entity.

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
    /// The number of partitions `$PartitionedEntities` declares (0 without one).
    pub partitions: usize,
    /// Per partition entity: its parent model entity and its partitions.
    pub partitioned: HashMap<(usize, i32), Partitioned>,
    /// Per model entity of dimension 1 to 3: the tags (sign dropped) of the
    /// entities one dimension lower that bound it.
    pub bounding: HashMap<(usize, i32), Vec<i32>>,
}

/// A partition entity of `$PartitionedEntities`.
pub(super) struct Partitioned {
    /// The model entity `(dimension, tag)` it is a piece of; of the
    /// partitioned dimension itself for the entities between partitions.
    pub parent: (usize, i32),
    /// The partitions (1-based) it belongs to.
    pub partitions: Vec<i32>,
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
        entities.partitions = c.count_le("the number of partitions")?;
        let ghosts = c.count_le("the number of ghost entities")?;
        c.take_n(ghosts, 8, "the ghost entities")?;
    } else {
        entities.partitions = c.count("the number of partitions")?;
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
                read_binary(c, dim, partitioned, entities)?
            } else {
                read_ascii(c, dim, partitioned, entities)?
            };
            // A partition entity of a model entity of another dimension
            // (a piece of the boundary between partitions) is never part of
            // a physical group, whatever tags the file gives it (its
            // parent's, say): its elements are no group's facets.
            let between = entities.partitioned.get(&(dim, tag));
            if between.is_some_and(|p| p.parent.0 != dim) {
                entities.physicals.truncate(start);
            }
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

/// Reads one binary entity of dimension `dim` into `entities` (its physical
/// tags appended to `physicals`); returns its tag.
fn read_binary(
    c: &mut Cursor,
    dim: usize,
    partitioned: bool,
    entities: &mut Entities,
) -> Result<i32> {
    let tag = c.i32_le("an entity tag")?;
    let parent = if partitioned {
        let p = c.take(8, "the parent entity")?;
        let np = c.count_le("a number of partitions")?;
        let parts = c.take_n(np, 4, "partition tags")?;
        let partitions = parts.chunks_exact(4).map(|b| i32_at(b, 0)).collect();
        Some((i32_at(p, 0), i32_at(p, 4), partitions))
    } else {
        None
    };
    // A point stores x y z, the others a bounding box.
    c.take(if dim == 0 { 24 } else { 48 }, "an entity's coordinates")?;
    let np = c.count_le("a number of physical tags")?;
    let tags = c.take_n(np, 4, "physical tags")?;
    entities
        .physicals
        .extend(tags.chunks_exact(4).map(|b| i32_at(b, 0)));
    let mut bounding = Vec::new();
    if dim > 0 {
        let nb = c.count_le("a number of bounding entities")?;
        let tags = c.take_n(nb, 4, "bounding entities")?;
        bounding.extend(tags.chunks_exact(4).map(|b| i32_at(b, 0)));
    }
    record(c, entities, (dim, tag), parent, bounding)?;
    Ok(tag)
}

/// Reads one ASCII entity of dimension `dim` into `entities` (its physical
/// tags appended to `physicals`); returns its tag.
fn read_ascii(
    c: &mut Cursor,
    dim: usize,
    partitioned: bool,
    entities: &mut Entities,
) -> Result<i32> {
    let tag = c.int("an entity tag")?;
    let parent = if partitioned {
        let parent_dim = c.int("a parent entity dimension")?;
        let parent_tag = c.int("a parent entity tag")?;
        let np = c.count("a number of partitions")?;
        let mut partitions = Vec::with_capacity(np.min(c.remaining() / 2));
        for _ in 0..np {
            partitions.push(c.int("a partition tag")?);
        }
        Some((parent_dim, parent_tag, partitions))
    } else {
        None
    };
    for _ in 0..if dim == 0 { 3 } else { 6 } {
        c.float("a coordinate")?;
    }
    let np = c.count("a number of physical tags")?;
    for _ in 0..np {
        entities.physicals.push(c.int("a physical tag")?);
    }
    let mut bounding = Vec::new();
    if dim > 0 {
        let nb = c.count("a number of bounding entities")?;
        for _ in 0..nb {
            bounding.push(c.int("a bounding entity tag")?);
        }
    }
    record(c, entities, (dim, tag), parent, bounding)?;
    Ok(tag)
}

/// Keeps a partition entity's parent `(dimension, tag)` and partitions, or
/// a model entity's bounding entities (their tags' signs dropped).
fn record(
    c: &Cursor,
    entities: &mut Entities,
    entity: (usize, i32),
    parent: Option<(i32, i32, Vec<i32>)>,
    bounding: Vec<i32>,
) -> Result<()> {
    match parent {
        Some((dim, tag, partitions)) => {
            let dim = usize::try_from(dim)
                .ok()
                .filter(|&d| d <= 3)
                .ok_or_else(|| {
                    c.error(format!("parent entity dimension {dim} (expected 0 to 3)"))
                })?;
            entities.partitioned.insert(
                entity,
                Partitioned {
                    parent: (dim, tag),
                    partitions,
                },
            );
        }
        None if entity.0 > 0 => {
            entities
                .bounding
                .insert(entity, bounding.iter().map(|t| t.abs()).collect());
        }
        None => {}
    }
    Ok(())
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
