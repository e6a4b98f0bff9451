//! The streamed read: the file in chunks of lines, each parsed by the
//! whole-file reader's [`Parser`] with the [`State`] the chunk before it
//! left, its points, elements and marker facets handed over and dropped
//! before the next chunk is read.

use std::io::{BufRead, BufReader};
use std::path::Path;

use super::{Parser, State};
use crate::error::{Error, Result};
use crate::mesh::Cells;

/// What one chunk of a streamed read holds: the entries of its lines, in
/// file order.
#[derive(Debug)]
pub struct Chunk {
    /// `NDIME=` (0 until it has been read).
    pub dim: usize,
    /// `NELEM=`, once read.
    pub elements: Option<usize>,
    /// The index in the file of the first point of [`Chunk::coords`].
    pub first_point: usize,
    /// Points, `dim` numbers each.
    pub coords: Vec<f64>,
    /// The index in the file of the first element of [`Chunk::cells`].
    pub first_element: usize,
    /// Volume elements, on the file's node indices.
    pub cells: Cells,
    /// Marker facets: the marker's index in file order, and its facets.
    pub facets: Vec<(usize, Cells)>,
}

/// What a streamed read found in the whole file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Outline {
    /// `NDIME=`.
    pub dim: usize,
    /// `NPOIN=`.
    pub points: usize,
    /// `NELEM=`.
    pub elements: usize,
    /// The line of `NELEM=` (where [`crate::io::su2::validate_at`] puts
    /// what it finds of whole elements).
    pub elements_line: usize,
    /// The markers' names, in file order.
    pub markers: Vec<String>,
    /// The number of chunks handed over.
    pub chunks: usize,
}

/// Reads the single-zone SU2 file at `path` once, `lines` lines at a time
/// (at least 1), and hands each chunk's entries to `each`; a chunk holds at
/// most `lines` points, elements or facets. Checks what the whole-file
/// reader checks line by line, with its messages; at the end what only the
/// end tells (counts, missing sections, node indices below `NPOIN=`). The
/// check of whole cells the whole-file reader adds
/// ([`crate::io::su2::validate_at`], a
/// duplicated element) is left to whoever assembles them. Fails with the first error of the
/// file or of `each`; `each` may have seen chunks before it.
pub fn stream(
    path: &Path,
    lines: usize,
    mut each: impl FnMut(Chunk) -> Result<()>,
) -> Result<Outline> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut reader = BufReader::new(crate::io::open_input(path)?);
    let mut state = State::new();
    let mut buffer = Vec::new();
    let (mut line, mut points, mut elements, mut chunks) = (0, 0, 0, 0);
    loop {
        buffer.clear();
        let mut read = 0;
        while read < lines.max(1) && reader.read_until(b'\n', &mut buffer).map_err(io)? > 0 {
            read += 1;
        }
        let mut parser = Parser::resume(&buffer, path, line, state);
        parser.read_all()?;
        if read == 0 {
            let (dim, npoin) = parser.check_end()?;
            let state = parser.state;
            return Ok(Outline {
                dim,
                points: npoin,
                elements: state.nelem.map_or(0, |n| n.0),
                elements_line: state.nelem.map_or(0, |n| n.1),
                markers: state.markers.into_iter().map(|m| m.name).collect(),
                chunks,
            });
        }
        line = parser.line;
        state = parser.state;
        let chunk = Chunk {
            dim: state.ndime.map_or(0, |d| d.0),
            elements: state.nelem.map(|n| n.0),
            first_point: points,
            coords: std::mem::take(&mut state.coords),
            first_element: elements,
            cells: std::mem::replace(&mut state.cells, Cells::new()),
            facets: state
                .markers
                .iter_mut()
                .enumerate()
                .filter(|(_, m)| !m.facets.is_empty())
                .map(|(k, m)| (k, std::mem::replace(&mut m.facets, Cells::new())))
                .collect(),
        };
        points += chunk.coords.len() / chunk.dim.max(1);
        elements += chunk.cells.len();
        chunks += 1;
        each(chunk)?;
    }
}

impl<'a> Parser<'a> {
    /// A parser of the chunk `bytes` of a streamed read that follows line
    /// `line` of the file, with the state read before it.
    fn resume(bytes: &'a [u8], path: &'a Path, line: usize, state: State) -> Self {
        let mut parser = Parser::new(bytes, path);
        if line > 0 {
            parser.pos = 0;
        }
        parser.line = line;
        parser.streamed = true;
        parser.state = state;
        parser
    }
}
