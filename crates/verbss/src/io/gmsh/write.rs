//! What both MSH writers share: the plan (physical tags, entities, fresh
//! facet tags) and an output that writes the same records as ASCII or binary.

use std::collections::HashSet;
use std::io::{self, Write};

use crate::mesh::{CellKind, Cells, Group, Mesh};

/// A group as it will be written: its dimension, physical tag and entity tag.
pub(super) struct PlannedGroup<'a> {
    /// The group.
    pub group: &'a Group,
    /// Dimension of its facets.
    pub dim: usize,
    /// Physical tag: the group's own if it has a positive, unused one, else a fresh one.
    pub physical: i32,
    /// Entity tag, numbered from 1 within each dimension; the volume cells are
    /// entity 1 of dimension `mesh.dim`.
    pub entity: i32,
}

/// What a plan takes from the file a mesh was read from, where it fits.
pub(super) struct Labels<'a> {
    /// The element tag of each facet of each group.
    pub facet_tags: Option<&'a [Vec<u64>]>,
    /// The cells' physical tag and name.
    pub domain: Option<(i32, &'a str)>,
}

/// Everything the writers need beyond the mesh itself.
pub(super) struct Plan<'a> {
    /// The mesh.
    pub mesh: &'a Mesh,
    /// Its nodes' coordinates as written (`dim` numbers per node).
    pub coords: &'a [f64],
    /// Its groups, in order.
    pub groups: Vec<PlannedGroup<'a>>,
    /// The element tag of each facet of each group: the file's, when the
    /// mesh was read from one, is unchanged and they are all distinct from
    /// each other and from the cell tags; else numbered on from the largest
    /// cell tag.
    pub facet_tags: Vec<Vec<u64>>,
    /// Physical tag and name of the volume cells: Gmsh saves only elements
    /// of physical groups once there are any, and meshio expects every
    /// element block to carry one. Those of the file the mesh was read from
    /// ([`super::Source::domain`]), else a fresh tag named [`DOMAIN`].
    pub domain: (i32, &'a str),
}

/// Name of the physical group of the volume cells when the mesh's file gave
/// none. The readers ignore physical groups of the mesh's own dimension, so
/// it never becomes a group.
pub(super) const DOMAIN: &str = "domain";

/// An `InvalidInput` error.
pub(super) fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

impl<'a> Plan<'a> {
    /// Checks the mesh and assigns physical tags and entities; the nodes are
    /// written at `coords`, the facet tags and the cells' physical group are
    /// those of the file the mesh was read from ([`super::Source`]), if any.
    pub fn new(mesh: &'a Mesh, coords: &'a [f64]) -> io::Result<Plan<'a>> {
        let source = mesh.origin.gmsh.as_ref();
        let labels = Labels {
            facet_tags: source.and_then(|s| s.facet_tags(mesh)),
            domain: source.and_then(|s| s.domain()),
        };
        Plan::labelled(mesh, coords, labels)
    }

    /// [`Plan::new`] with the facet tags and the cells' physical group of
    /// `labels`, where they fit the mesh.
    pub fn labelled(mesh: &'a Mesh, coords: &'a [f64], labels: Labels<'a>) -> io::Result<Plan<'a>> {
        mesh.validate().map_err(|e| invalid(e.to_string()))?;
        // Fresh physical tags: after the groups' own, from 1 when those reach
        // i32::MAX, never one a group has.
        let taken: HashSet<i32> = mesh.groups.iter().filter_map(|g| g.tag).collect();
        let mut next = taken
            .iter()
            .max()
            .map_or(1, |&t| t.max(0).checked_add(1).unwrap_or(1));
        let mut fresh = || loop {
            let t = next;
            next = next
                .checked_add(1)
                .ok_or_else(|| invalid("no physical tag is left for the groups".into()))?;
            if !taken.contains(&t) {
                return Ok::<i32, io::Error>(t);
            }
        };
        let mut used = HashSet::new();
        let mut entities = [0i32; 4];
        let mut groups = Vec::with_capacity(mesh.groups.len());
        for group in &mesh.groups {
            if group.name.contains(['"', '\n', '\r']) {
                return Err(invalid(format!(
                    "group name {:?} holds a quote or a line break, which MSH cannot store",
                    group.name
                )));
            }
            let dims: Vec<usize> = group.facets.kinds.iter().map(|k| k.dim()).collect();
            let dim = dims.first().copied().unwrap_or(mesh.dim - 1);
            if let Some(other) = dims.iter().find(|&&d| d != dim) {
                return Err(invalid(format!(
                    "group '{}' mixes facets of dimension {dim} and {other}; \
                     a Gmsh physical group has one dimension",
                    group.name
                )));
            }
            let physical = match group.tag {
                Some(t) if t > 0 && used.insert((dim, t)) => t,
                _ => fresh()?,
            };
            entities[dim] += 1;
            groups.push(PlannedGroup {
                group,
                dim,
                physical,
                entity: entities[dim],
            });
        }
        let facet_tags = match labels.facet_tags {
            Some(tags)
                if fits(mesh, tags)
                    && distinct(mesh.cell_tags.iter().chain(tags.iter().flatten())) =>
            {
                tags.to_vec()
            }
            _ => fresh_facet_tags(mesh)?,
        };

        // Groups have a lower dimension: the file's tag cannot clash.
        let domain = match labels.domain {
            Some((tag, name)) if tag > 0 && !name.contains(['"', '\n', '\r']) => (tag, name),
            _ => (fresh()?, DOMAIN),
        };
        Ok(Plan {
            mesh,
            coords,
            groups,
            facet_tags,
            domain,
        })
    }

    /// Number of group facets.
    pub fn facet_count(&self) -> usize {
        self.groups.iter().map(|g| g.group.facets.len()).sum()
    }

    /// `x y z` of node `i` (`z = 0` in 2D).
    pub fn xyz(&self, i: usize) -> [f64; 3] {
        let d = self.mesh.dim;
        let p = &self.coords[d * i..d * (i + 1)];
        [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
    }
}

/// Whether `tags` holds one tag per facet of each group of `mesh`.
fn fits(mesh: &Mesh, tags: &[Vec<u64>]) -> bool {
    tags.len() == mesh.groups.len()
        && tags
            .iter()
            .zip(&mesh.groups)
            .all(|(t, g)| t.len() == g.facets.len())
}

/// Whether no two of `tags` are equal.
fn distinct<'t>(tags: impl Iterator<Item = &'t u64>) -> bool {
    let mut seen = HashSet::new();
    tags.into_iter().all(|t| seen.insert(*t))
}

/// Element tags for the group facets of `mesh`, numbered on from the largest
/// cell tag, or from 1 when that would pass `u64::MAX` and the cell tags
/// leave room below.
fn fresh_facet_tags(mesh: &Mesh) -> io::Result<Vec<Vec<u64>>> {
    let facets: u64 = mesh.groups.iter().map(|g| g.facets.len() as u64).sum();
    let max = mesh.cell_tags.iter().copied().max().unwrap_or(0);
    let min = mesh.cell_tags.iter().copied().min().unwrap_or(0);
    let first = match max.checked_add(facets) {
        Some(_) => max + 1,
        None if min > facets => 1,
        None => {
            return Err(invalid(format!(
                "element tags {min} to {max} leave no room for the tags of the {facets} \
                 group facets"
            )))
        }
    };
    let mut next = first..;
    Ok(mesh
        .groups
        .iter()
        .map(|g| next.by_ref().take(g.facets.len()).collect())
        .collect())
}

/// Runs of consecutive cells of one kind: `(kind, first, end)`.
pub(super) fn runs(cells: &Cells) -> Vec<(CellKind, usize, usize)> {
    let mut out: Vec<(CellKind, usize, usize)> = Vec::new();
    for (c, &kind) in cells.kinds.iter().enumerate() {
        match out.last_mut() {
            Some(run) if run.0 == kind => run.2 = c + 1,
            _ => out.push((kind, c, c + 1)),
        }
    }
    out
}

/// Bytes are handed to the writer in chunks of about this size.
const CHUNK: usize = 1 << 16;

/// Writes records either as ASCII (values separated by spaces, one record a
/// line, floats in shortest round-trip form) or as little-endian binary.
pub(super) struct Out<'w> {
    w: &'w mut dyn Write,
    buf: Vec<u8>,
    binary: bool,
    line_start: bool,
}

impl<'w> Out<'w> {
    /// An output on `w`.
    pub fn new(w: &'w mut dyn Write, binary: bool) -> Self {
        Out {
            w,
            buf: Vec::with_capacity(CHUNK + 256),
            binary,
            line_start: true,
        }
    }

    /// Whether the output is binary.
    pub fn binary(&self) -> bool {
        self.binary
    }

    fn spill(&mut self) -> io::Result<()> {
        if self.buf.len() >= CHUNK {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn separate(&mut self) {
        if !self.line_start {
            self.buf.push(b' ');
        }
        self.line_start = false;
    }

    /// Raw text, in either encoding.
    pub fn text(&mut self, s: &str) -> io::Result<()> {
        self.buf.extend_from_slice(s.as_bytes());
        self.line_start = s.ends_with('\n');
        self.spill()
    }

    /// A `size_t` value (8 bytes in binary).
    pub fn size(&mut self, v: u64) -> io::Result<()> {
        if self.binary {
            self.buf.extend_from_slice(&v.to_le_bytes());
        } else {
            self.separate();
            write!(self.buf, "{v}")?;
        }
        self.spill()
    }

    /// An `int` value (4 bytes in binary).
    pub fn int(&mut self, v: i32) -> io::Result<()> {
        if self.binary {
            self.buf.extend_from_slice(&v.to_le_bytes());
        } else {
            self.separate();
            write!(self.buf, "{v}")?;
        }
        self.spill()
    }

    /// A `double` value (8 bytes in binary; shortest round-trip text in ASCII).
    pub fn float(&mut self, v: f64) -> io::Result<()> {
        if self.binary {
            self.buf.extend_from_slice(&v.to_le_bytes());
        } else {
            self.separate();
            write!(self.buf, "{v:?}")?;
        }
        self.spill()
    }

    /// Ends an ASCII record line (nothing in binary).
    pub fn end_line(&mut self) -> io::Result<()> {
        if !self.binary {
            self.buf.push(b'\n');
            self.line_start = true;
        }
        Ok(())
    }

    /// `$MeshFormat` for `version`, with the binary check integer 1.
    pub fn format(&mut self, version: &str) -> io::Result<()> {
        let kind = if self.binary { 1 } else { 0 };
        self.text(&format!("$MeshFormat\n{version} {kind} 8\n"))?;
        if self.binary {
            self.buf.extend_from_slice(&1i32.to_le_bytes());
            self.text("\n")?;
        }
        self.text("$EndMeshFormat\n")
    }

    /// `$PhysicalNames` (always ASCII): the groups, then the volume cells'.
    pub fn names(&mut self, plan: &Plan) -> io::Result<()> {
        self.text(&format!("$PhysicalNames\n{}\n", plan.groups.len() + 1))?;
        for g in &plan.groups {
            self.text(&format!("{} {} \"{}\"\n", g.dim, g.physical, g.group.name))?;
        }
        let (tag, name) = plan.domain;
        self.text(&format!("{} {tag} \"{name}\"\n", plan.mesh.dim))?;
        self.text("$EndPhysicalNames\n")
    }

    /// Closes a section: a line break after binary data, then `keyword`.
    pub fn close(&mut self, keyword: &str) -> io::Result<()> {
        if self.binary {
            self.buf.push(b'\n');
        }
        self.text(keyword)?;
        self.text("\n")
    }

    /// Hands the rest of the bytes to the writer.
    pub fn finish(mut self) -> io::Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        self.w.flush()
    }
}
