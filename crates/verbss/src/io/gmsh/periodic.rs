//! `$Periodic`: the periodic links of a Gmsh file (MSH 2.2, whose section is
//! ASCII in binary files too, and 4.1, ASCII or binary), each an entity
//! whose nodes are the images of a master entity's by an affine transform
//! (16 numbers, a 4 × 4 matrix by rows, taking the master onto the slave).
//! The links of one transform are one periodic interface of node pairs
//! ([`Coupling::Linked`]); without a transform, the mean translation from
//! each master node to its slave.

use std::collections::HashMap;

use super::cursor::{f64_at, Cursor, Mark};
use super::MshVersion;
use crate::error::Result;
use crate::mesh::{Coupling, Interface, Transform};

/// One link as read: its slave and master entities `(dim, tag)`, its
/// transform, and its (slave, master) node tags.
pub(super) struct Link {
    slave: (i32, i32),
    master: i32,
    affine: Option<[f64; 16]>,
    nodes: Vec<(u64, u64)>,
    mark: Mark,
}

/// Reads the section after `$Periodic`, up to and including `$EndPeriodic`.
pub(super) fn read(c: &mut Cursor, version: MshVersion) -> Result<Vec<Link>> {
    let binary = c.binary() && version == MshVersion::V41;
    if binary {
        c.newline()?;
    }
    let count = |c: &mut Cursor, what: &str| {
        if binary {
            c.count_le(what)
        } else {
            c.count(what)
        }
    };
    let int = |c: &mut Cursor, what: &str| {
        if binary {
            c.i32_le(what)
        } else {
            c.int(what)
        }
    };
    let n = count(c, "the number of periodic links")?;
    let mut links = Vec::new();
    for _ in 0..n {
        let mark = c.here();
        let dim = int(c, "a periodic link's dimension")?;
        let slave = int(c, "a periodic link's entity")?;
        let master = int(c, "a periodic link's master entity")?;
        let mut affine = None;
        let values = |c: &mut Cursor, k: usize| -> Result<[f64; 16]> {
            let mut a = [0.0; 16];
            if binary {
                let data = c.take_n(k, 8, "the affine transform")?;
                for (j, v) in a.iter_mut().enumerate().take(k) {
                    *v = f64_at(data, 8 * j);
                }
            } else {
                for v in a.iter_mut().take(k) {
                    *v = c.float("a number of the affine transform")?;
                }
            }
            Ok(a)
        };
        let nodes = match version {
            MshVersion::V41 => {
                let k = count(c, "the number of affine values")?;
                if k != 0 && k != 16 {
                    return Err(c.error(format!(
                        "a periodic link with {k} affine values (expected 0 or 16)"
                    )));
                }
                if k == 16 {
                    affine = Some(values(c, 16)?);
                }
                count(c, "the number of periodic nodes")?
            }
            MshVersion::V22 => {
                let t = c.token("Affine or the number of periodic nodes")?;
                if t == b"Affine" {
                    affine = Some(values(c, 16)?);
                    c.count("the number of periodic nodes")?
                } else {
                    std::str::from_utf8(t)
                        .ok()
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(|| {
                            c.error(format!(
                                "expected Affine or the number of periodic nodes, found {}",
                                super::cursor::show(t)
                            ))
                        })?
                }
            }
        };
        let mut pairs = Vec::new();
        for _ in 0..nodes {
            let pair = if binary {
                (c.u64_le("a periodic node")?, c.u64_le("its master node")?)
            } else {
                (c.uint("a periodic node")?, c.uint("its master node")?)
            };
            pairs.push(pair);
        }
        links.push(Link {
            slave: (dim, slave),
            master,
            affine,
            nodes: pairs,
            mark,
        });
    }
    c.keyword("$EndPeriodic")?;
    Ok(links)
}

/// The links of one transform, gathered.
struct Gathered {
    affine: Option<[f64; 16]>,
    /// (master, slave) node indices.
    pairs: Vec<(usize, usize)>,
    /// The master and slave entities of the highest dimension's link.
    names: [String; 2],
    dim: i32,
}

/// The links as interfaces, one per transform, their nodes numbered as the
/// mesh's (`node_tags`); a node tag that is not the mesh's is an error at
/// its link.
pub(super) fn interfaces(c: &Cursor, links: &[Link], node_tags: &[u64]) -> Result<Vec<Interface>> {
    let index: HashMap<u64, usize> = node_tags.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let mut found: Vec<Gathered> = Vec::new();
    for link in links {
        let (dim, slave) = link.slave;
        let of = |t: u64| {
            index.get(&t).copied().ok_or_else(|| {
                c.error_at(
                    link.mark,
                    format!(
                        "the periodic link of entity {slave} names node {t}, which $Nodes does \
                         not have"
                    ),
                )
            })
        };
        let pairs = link
            .nodes
            .iter()
            .map(|&(s, m)| Ok((of(m)?, of(s)?)))
            .collect::<Result<Vec<_>>>()?;
        let entity = ["point", "curve", "surface", "volume"]
            .get(dim as usize)
            .copied()
            .unwrap_or("entity");
        let names = [
            format!("{entity} {}", link.master),
            format!("{entity} {slave}"),
        ];
        match found.iter_mut().find(|f| f.affine == link.affine) {
            Some(f) => {
                f.pairs.extend(pairs);
                if dim > f.dim {
                    (f.names, f.dim) = (names, dim);
                }
            }
            None => found.push(Gathered {
                affine: link.affine,
                pairs,
                names,
                dim,
            }),
        }
    }
    Ok(found
        .into_iter()
        .map(|mut f| {
            f.pairs.sort_unstable();
            f.pairs.dedup();
            Interface {
                sides: f.names.map(|n| vec![n]),
                coupling: Coupling::Linked {
                    transform: f
                        .affine
                        .map(|a| Transform::Affine(std::array::from_fn(|k| a[k]))),
                    pairs: f.pairs,
                },
            }
        })
        .collect())
}
