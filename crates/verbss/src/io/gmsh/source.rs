//! The Gmsh file a mesh was read from, kept so that writing the mesh back
//! in the same version and encoding changes only the node coordinates.
//!
//! Everything verbss does not model (`$Entities` with their bounding boxes,
//! `$PartitionedEntities`, `$Periodic`, elements without a physical group,
//! the physical group of the cells, the order and tags of every element) is
//! then written as the file held it, byte for byte: only the `x y z` of each
//! node in `$Nodes` are replaced.

use std::collections::hash_map::DefaultHasher;
use std::fmt;
use std::fs::File;
use std::hash::{Hash, Hasher};
use std::io::{self, BufReader, Read, Seek, SeekFrom, Write};
use std::ops::Range;
use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard};

use super::model::Structure;
use crate::io::MshVersion;
use crate::mesh::{Cells, Mesh};

/// A Gmsh file as read: its bytes, where each node's coordinates are in
/// them, and a fingerprint of the mesh read from it.
pub struct Source {
    version: MshVersion,
    binary: bool,
    bytes: Mutex<Bytes>,
    /// Byte range of `x y z` of each node, in the mesh's node order.
    coords: Vec<Range<usize>>,
    /// [`fingerprint`] of the mesh read from the file.
    fingerprint: u64,
    /// The cells' physical group and the group facets' element tags.
    structure: Structure,
}

/// Where a [`Source`] keeps the file's bytes (behind a lock: a copy is
/// written from them, or they move, one at a time).
enum Bytes {
    /// In memory.
    Held(Arc<[u8]>),
    /// In an unnamed temporary file ([`Source::spill`]), deleted with it.
    Spilled(File),
}

impl fmt::Debug for Source {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let bytes = match &*self.bytes() {
            Bytes::Held(bytes) => format!("{} in memory", bytes.len()),
            Bytes::Spilled(_) => "in a temporary file".to_string(),
        };
        f.debug_struct("Source")
            .field("version", &self.version)
            .field("binary", &self.binary)
            .field("bytes", &bytes)
            .finish()
    }
}

impl Source {
    /// The file `bytes` (MSH version, binary or not) that `mesh` was read
    /// from, with the byte range of each node's coordinates and what else
    /// the file says about the mesh.
    pub(super) fn new(
        bytes: &[u8],
        (version, binary): (MshVersion, bool),
        coords: Vec<Range<usize>>,
        structure: Structure,
        mesh: &Mesh,
    ) -> Source {
        Source {
            version,
            binary,
            bytes: Mutex::new(Bytes::Held(bytes.into())),
            coords,
            fingerprint: fingerprint(mesh),
            structure,
        }
    }

    /// The physical tag and name of the cells' group, when the file gave
    /// them exactly one.
    pub(super) fn domain(&self) -> Option<(i32, &str)> {
        let (tag, name) = self.structure.domain.as_ref()?;
        Some((*tag, name.as_str()))
    }

    /// The element tags of the group facets of `mesh`, as the file gave
    /// them, when `mesh` is the mesh read from the file (coordinates aside).
    pub(super) fn facet_tags(&self, mesh: &Mesh) -> Option<&[Vec<u64>]> {
        (self.fingerprint == fingerprint(mesh)).then_some(&self.structure.facet_tags[..])
    }

    /// The file's MSH version.
    pub fn version(&self) -> MshVersion {
        self.version
    }

    /// Whether the file is binary.
    pub fn binary(&self) -> bool {
        self.binary
    }

    /// Whether `mesh` can be written as this file with its coordinates
    /// replaced: same version and encoding asked for, and the same nodes,
    /// cells, tags and groups as the mesh read from it.
    pub(super) fn fits(&self, mesh: &Mesh, version: MshVersion, binary: bool) -> bool {
        self.version == version
            && self.binary == binary
            && self.coords.len() == mesh.node_count()
            && self.fingerprint == fingerprint(mesh)
    }

    /// Moves the file's bytes out of memory into an unnamed temporary file
    /// in the folder `dir` (deleted when the source is dropped, or when the
    /// process ends): a long run that writes its mesh back as this file
    /// then holds none of it in memory, and a change of the input file
    /// during the run changes nothing in what is written.
    pub fn spill(&self, dir: &Path) -> io::Result<()> {
        let mut bytes = self.bytes();
        if let Bytes::Held(held) = &*bytes {
            let mut file = tempfile::tempfile_in(dir)?;
            file.write_all(held)?;
            *bytes = Bytes::Spilled(file);
        }
        Ok(())
    }

    /// The file's bytes, locked.
    fn bytes(&self) -> MutexGuard<'_, Bytes> {
        self.bytes
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Writes the file with `coords` (`dim` numbers per node) in place of
    /// its own (`z = 0` in 2D): ASCII in shortest round-trip form (a node
    /// that did not move keeps its text), binary as little-endian doubles.
    pub(super) fn write(&self, w: &mut dyn Write, dim: usize, coords: &[f64]) -> io::Result<()> {
        match &*self.bytes() {
            Bytes::Held(bytes) => self.write_from(&mut &bytes[..], w, dim, coords),
            Bytes::Spilled(file) => {
                let mut file: &File = file;
                file.seek(SeekFrom::Start(0))?;
                let mut file = BufReader::with_capacity(1 << 16, file);
                self.write_from(&mut file, w, dim, coords)
            }
        }
    }

    /// [`Source::write`] from `file`, a reader of the file's bytes from the start.
    fn write_from(
        &self,
        file: &mut dyn Read,
        w: &mut dyn Write,
        dim: usize,
        coords: &[f64],
    ) -> io::Result<()> {
        const CHUNK: usize = 1 << 16;
        let mut buf = Vec::with_capacity(CHUNK + 256);
        let mut text = Vec::new();
        let mut copied = 0;
        for (i, span) in self.coords.iter().enumerate() {
            file.take((span.start - copied) as u64)
                .read_to_end(&mut buf)?;
            text.resize(span.len(), 0);
            file.read_exact(&mut text)?;
            let p = &coords[dim * i..dim * (i + 1)];
            let xyz = [p[0], p[1], p.get(2).copied().unwrap_or(0.0)];
            if self.binary {
                for v in xyz {
                    buf.extend_from_slice(&v.to_le_bytes());
                }
            } else if parse_xyz(&text) == Some(xyz) {
                buf.extend_from_slice(&text);
            } else {
                write!(buf, "{:?} {:?} {:?}", xyz[0], xyz[1], xyz[2])?;
            }
            copied = span.end;
            if buf.len() >= CHUNK {
                w.write_all(&buf)?;
                buf.clear();
            }
        }
        w.write_all(&buf)?;
        io::copy(file, w)?;
        w.flush()
    }
}

/// The three numbers of an ASCII `x y z`.
fn parse_xyz(text: &[u8]) -> Option<[f64; 3]> {
    let mut numbers = std::str::from_utf8(text).ok()?.split_ascii_whitespace();
    let mut xyz = [0.0; 3];
    for v in &mut xyz {
        *v = numbers.next()?.parse().ok()?;
    }
    Some(xyz)
}

/// A hash of everything of `mesh` but its coordinates: dimension, node and
/// cell tags, cells, groups.
fn fingerprint(mesh: &Mesh) -> u64 {
    let mut h = DefaultHasher::new();
    let hash_cells = |cells: &Cells, h: &mut DefaultHasher| {
        cells.kinds.hash(h);
        cells.offsets.hash(h);
        cells.nodes.hash(h);
    };
    mesh.dim.hash(&mut h);
    mesh.node_tags.hash(&mut h);
    mesh.cell_tags.hash(&mut h);
    hash_cells(&mesh.cells, &mut h);
    for g in &mesh.groups {
        g.name.hash(&mut h);
        g.tag.hash(&mut h);
        hash_cells(&g.facets, &mut h);
    }
    h.finish()
}
