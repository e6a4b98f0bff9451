//! A single-zone SU2 file read once by rank 0 and scattered as it is read:
//! no process ever holds the whole mesh.
//!
//! Rank 0 reads the file in chunks of at most `lines` lines
//! ([`verbss::io::su2::stream`], the whole-file reader's line parsing) and,
//! after each chunk, every rank takes part in one round of two all-to-all
//! exchanges that send the chunk's entries where they belong:
//!
//! * element `e` of `E` to rank `⌊eP/E⌋` (contiguous blocks in file order);
//! * point `g` to its *directory* rank `g mod P`, with its coordinates;
//! * each node of a marker facet to the directory rank of the node, as the
//!   pair (node, marker): the directory learns which nodes are on which
//!   markers without any rank holding the facets;
//! * each marker facet to the directory rank of its lowest node, which
//!   hands it on after the cut to the rank holding the cell it bounds
//!   (`repartition`), so that the pieces written carry the markers.
//!
//! Rank 0 therefore holds at most one chunk and the messages made of it. A
//! read error (a bad line, a missing section, a count the data disagree
//! with) ends the rounds: rank 0 broadcasts its message, naming the file and
//! the line, and every rank returns it.

use std::path::{Path, PathBuf};

use verbss::io::su2::{stream, Chunk};
use verbss::mesh::CellKind;
use verbss::{Error, Result};

use crate::ghosts::kind_code;
use crate::Comm;

/// The round codes rank 0 broadcasts.
const ROUND_CHUNK: u64 = 0;
const ROUND_END: u64 = 1;
const ROUND_ERROR: u64 = 2;

/// The record tags of a round's integer message (the points go in its
/// second, floating-point message).
const TAG_ELEMENT: u64 = 0;
const TAG_MARKER: u64 = 1;
const TAG_FACET: u64 = 2;

/// Where the file holds its cells, for the messages of the checks after
/// the cut.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CellsAt {
    /// An SU2 file: the line of `NELEM=`.
    Line(usize),
    /// A CGNS file: `zone 'Z' (zone 1 of base 'B')`.
    Zone(String),
}

impl Default for CellsAt {
    fn default() -> Self {
        CellsAt::Line(0)
    }
}

/// What one rank holds after the read (of an SU2 file here, of a CGNS
/// file by [`crate::cgns_read`]).
#[derive(Debug, Default)]
pub struct Scattered {
    /// The file.
    pub path: PathBuf,
    /// The dimension (SU2 `NDIME=`).
    pub dim: usize,
    /// The number of nodes `N` (SU2 `NPOIN=`).
    pub points: u64,
    /// The number of cells `E` (SU2 `NELEM=`).
    pub elements: u64,
    /// Where the file holds its cells.
    pub cells_at: CellsAt,
    /// The markers' (groups') names, in file order.
    pub markers: Vec<String>,
    /// The number of chunks rank 0 read (SU2; 0 for a CGNS file).
    pub chunks: usize,
    /// This rank's block of cells: the file index of each, increasing.
    pub cell_index: Vec<u64>,
    /// The kind of each cell of the block.
    pub cell_kinds: Vec<CellKind>,
    /// The file's node indices of the block's cells, concatenated.
    pub cell_nodes: Vec<u64>,
    /// The directory's coordinates: node `g ≡ rank (mod P)` at `g / P`.
    pub coords: Vec<f64>,
    /// The directory's nodes on markers: `(node, marker)`, increasing, once each.
    pub on_marker: Vec<(u64, u64)>,
    /// The marker facets whose lowest node is the directory's, sorted by
    /// that node.
    pub facets: Vec<Facet>,
}

/// A facet of a marker, by the file's node indices.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Facet {
    /// Its lowest node.
    pub lowest: u64,
    /// Its marker (group), in file order.
    pub marker: u64,
    /// Its kind's position in [`CellKind::ALL`].
    pub kind: u64,
    /// Its nodes.
    pub nodes: Vec<u64>,
}

impl Facet {
    /// The facet of `marker` of kind `kind` on `nodes`.
    pub fn new(marker: u64, kind: CellKind, nodes: Vec<u64>) -> Facet {
        Facet {
            lowest: nodes.iter().copied().min().unwrap_or(0),
            marker,
            kind: kind_code(kind),
            nodes,
        }
    }

    /// Appends it to `out` as the record `marker kind nodes…`.
    pub fn encode(&self, out: &mut Vec<u64>) {
        out.extend([self.marker, self.kind]);
        out.extend_from_slice(&self.nodes);
    }

    /// The facet of the record at the start of `record`, and the record's length.
    pub fn decode(record: &[u64]) -> (Facet, usize) {
        let kind = CellKind::ALL[record[1] as usize];
        let n = kind.node_count();
        let nodes = record[2..2 + n].to_vec();
        (Facet::new(record[0], kind, nodes), 2 + n)
    }

    /// The directory rank of its lowest node, of `ranks`.
    pub fn directory(&self, ranks: usize) -> usize {
        (self.lowest % ranks as u64) as usize
    }
}

/// Every facet of `records` (lists of [`Facet::encode`]d records), sorted.
pub fn decode_facets(records: &[Vec<u64>]) -> Vec<Facet> {
    let mut facets = Vec::new();
    for list in records {
        let mut at = 0;
        while at < list.len() {
            let (facet, len) = Facet::decode(&list[at..]);
            facets.push(facet);
            at += len;
        }
    }
    facets.sort_unstable();
    facets
}

impl Scattered {
    /// The cells of the block with their nodes.
    pub fn cells(&self) -> impl Iterator<Item = (u64, CellKind, &[u64])> + '_ {
        let mut at = 0;
        self.cell_index
            .iter()
            .zip(&self.cell_kinds)
            .map(move |(&e, &kind)| {
                let nodes = &self.cell_nodes[at..at + kind.node_count()];
                at += kind.node_count();
                (e, kind, nodes)
            })
    }
}

/// Reads the SU2 file at `path` on rank 0, `lines` lines at a time, and
/// scatters it (collective; see the module documentation).
pub fn scatter(comm: &Comm, path: &Path, lines: usize) -> Result<Scattered> {
    let mut mine = Scattered {
        path: path.to_path_buf(),
        ..Scattered::default()
    };
    if comm.rank() != 0 {
        return receive(comm, &mut mine).map(|()| mine);
    }
    let read = stream(path, lines, |chunk| {
        let mut header = [ROUND_CHUNK];
        comm.broadcast(0, &mut header);
        round(comm, &mut mine, Some(&chunk));
        Ok(())
    });
    match read {
        Ok(outline) => {
            let mut header = [
                ROUND_END,
                outline.dim as u64,
                outline.points as u64,
                outline.elements as u64,
                outline.chunks as u64,
                outline.elements_line as u64,
            ];
            comm.broadcast(0, &mut header[..1]);
            comm.broadcast(0, &mut header[1..]);
            let mut names = outline.markers.join("\n").into_bytes();
            broadcast_bytes(comm, &mut names);
            finish(&mut mine, &header[1..], &names);
            Ok(mine)
        }
        Err(e) => {
            comm.broadcast(0, &mut [ROUND_ERROR]);
            let mut message = e.to_string().into_bytes();
            broadcast_bytes(comm, &mut message);
            Err(e)
        }
    }
}

/// The rounds of a rank other than 0, until the end or an error.
fn receive(comm: &Comm, mine: &mut Scattered) -> Result<()> {
    loop {
        let mut header = [0u64];
        comm.broadcast(0, &mut header);
        match header[0] {
            ROUND_CHUNK => round(comm, mine, None),
            ROUND_END => {
                let mut outline = [0u64; 5];
                comm.broadcast(0, &mut outline);
                let mut names = Vec::new();
                broadcast_bytes(comm, &mut names);
                finish(mine, &outline, &names);
                return Ok(());
            }
            _ => {
                let mut message = Vec::new();
                broadcast_bytes(comm, &mut message);
                return Err(Error::InvalidMesh(
                    String::from_utf8_lossy(&message).into_owned(),
                ));
            }
        }
    }
}

/// Rank 0's `bytes` on every rank (collective; `bytes` is resized).
fn broadcast_bytes(comm: &Comm, bytes: &mut Vec<u8>) {
    let mut len = [bytes.len() as u64];
    comm.broadcast(0, &mut len);
    bytes.resize(len[0] as usize, 0);
    comm.broadcast(0, bytes);
}

/// The end: the outline `[dim, points, elements, chunks, elements_line]` and the marker
/// names, one a line.
fn finish(mine: &mut Scattered, outline: &[u64], names: &[u8]) {
    mine.dim = outline[0] as usize;
    mine.points = outline[1];
    mine.elements = outline[2];
    mine.chunks = outline[3] as usize;
    mine.cells_at = CellsAt::Line(outline[4] as usize);
    let names = String::from_utf8_lossy(names);
    mine.markers = if names.is_empty() {
        Vec::new()
    } else {
        names.split('\n').map(str::to_string).collect()
    };
    mine.on_marker.sort_unstable();
    mine.on_marker.dedup();
    mine.facets.sort_unstable();
}

/// One round (collective): rank 0 sends `chunk`'s entries where they
/// belong, every rank keeps what it receives.
fn round(comm: &Comm, mine: &mut Scattered, chunk: Option<&Chunk>) {
    let size = comm.size() as usize;
    let mut records: Vec<Vec<u64>> = vec![Vec::new(); size];
    let mut coords: Vec<Vec<f64>> = vec![Vec::new(); size];
    if let Some(chunk) = chunk {
        let directory = |g: u64| (g % size as u64) as usize;
        if let Some(total) = chunk.elements.filter(|&e| e > 0) {
            for (k, (kind, nodes)) in chunk.cells.iter().enumerate() {
                let e = (chunk.first_element + k) as u64;
                let out = &mut records[block_of(e, total as u64, size)];
                out.extend([TAG_ELEMENT, e, kind_code(kind)]);
                out.extend(nodes.iter().map(|&v| v as u64));
            }
        }
        for (k, x) in chunk.coords.chunks(chunk.dim.max(1)).enumerate() {
            let g = (chunk.first_point + k) as u64;
            coords[directory(g)].extend_from_slice(x);
        }
        for (marker, facets) in &chunk.facets {
            for &v in &facets.nodes {
                let g = v as u64;
                records[directory(g)].extend([TAG_MARKER, g, *marker as u64]);
            }
            for (kind, nodes) in facets.iter() {
                let nodes = nodes.iter().map(|&v| v as u64).collect();
                let facet = Facet::new(*marker as u64, kind, nodes);
                let out = &mut records[facet.directory(size)];
                out.push(TAG_FACET);
                facet.encode(out);
            }
        }
    }
    let records = comm.all_to_all(&records);
    let coords = comm.all_to_all(&coords);
    for (list, x) in records.iter().zip(&coords) {
        let mut at = 0;
        while at < list.len() {
            match list[at] {
                TAG_ELEMENT => {
                    let kind = CellKind::ALL[list[at + 2] as usize];
                    let n = kind.node_count();
                    mine.cell_index.push(list[at + 1]);
                    mine.cell_kinds.push(kind);
                    mine.cell_nodes.extend_from_slice(&list[at + 3..at + 3 + n]);
                    at += 3 + n;
                }
                TAG_FACET => {
                    let (facet, len) = Facet::decode(&list[at + 1..]);
                    mine.facets.push(facet);
                    at += 1 + len;
                }
                _ => {
                    mine.on_marker.push((list[at + 1], list[at + 2]));
                    at += 3;
                }
            }
        }
        // A chunk's points come in increasing order, so the directory's
        // coordinates are in the order of its nodes.
        mine.coords.extend_from_slice(x);
    }
}

/// The block of `index` of `count` on `ranks` ranks: `⌊index·ranks/count⌋`.
pub fn block_of(index: u64, count: u64, ranks: usize) -> usize {
    (u128::from(index) * ranks as u128 / u128::from(count)) as usize
}

/// The indices of `count` whose block ([`block_of`]) is `rank`:
/// `⌈rank·count/ranks⌉ .. ⌈(rank+1)·count/ranks⌉`.
pub fn block(count: u64, ranks: usize, rank: usize) -> std::ops::Range<u64> {
    let bound = |r: usize| (u128::from(count) * r as u128).div_ceil(ranks as u128) as u64;
    bound(rank)..bound(rank + 1)
}

#[cfg(test)]
mod tests {
    use super::{block, block_of};

    #[test]
    fn elements_go_to_ranks_in_contiguous_blocks() {
        let blocks = |count: u64, ranks: usize| -> Vec<usize> {
            (0..count).map(|e| block_of(e, count, ranks)).collect()
        };
        assert_eq!(blocks(7, 3), [0, 0, 0, 1, 1, 2, 2]);
        assert_eq!(blocks(2, 3), [0, 1]);
        assert_eq!(blocks(4, 1), [0, 0, 0, 0]);
        assert_eq!(block_of(u64::MAX - 1, u64::MAX, 1000), 999);
    }

    #[test]
    fn a_rank_s_block_holds_the_indices_of_that_block() {
        for (count, ranks) in [(7, 3), (2, 3), (4, 1), (0, 2), (10, 4)] {
            for rank in 0..ranks {
                let mine: Vec<u64> = (0..count)
                    .filter(|&e| block_of(e, count, ranks) == rank)
                    .collect();
                assert_eq!(block(count, ranks, rank).collect::<Vec<_>>(), mine);
            }
        }
        assert_eq!(block(u64::MAX, 1000, 999).end, u64::MAX);
    }
}
