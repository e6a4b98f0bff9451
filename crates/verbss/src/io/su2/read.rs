//! The SU2 reader: a line-by-line state machine over the file's sections.

mod entries;
mod stream;
mod zones;

pub use stream::{stream, Chunk, Outline};
pub(super) use zones::{parse_zone, parse_zones};

use std::collections::HashMap;
use std::path::Path;

use super::{Anchor, Skipped};
use crate::error::{Error, Result};
use crate::io::shown;
use crate::io::MAX_GROUPS;
use crate::mesh::{Cells, FileOrigin, Group, Mesh};

/// [`Mesh::validate`] with its message given at line `line` of `path` (the
/// `NELEM=` line: what it finds is about whole elements).
pub fn validate_at(mesh: &Mesh, path: &Path, line: usize) -> Result<()> {
    mesh.validate().map_err(|e| {
        crate::io::invalid_at(e, |message| Error::Parse {
            path: path.to_path_buf(),
            line,
            message,
        })
    })
}

/// One non-blank line with its comment removed.
enum Line<'a> {
    /// `KEY= value`: the key as written, upper-cased without `_` and spaces
    /// (`MARKERTAG`), and the value trimmed.
    Keyword {
        raw: &'a str,
        key: String,
        value: &'a str,
    },
    /// Anything else: whitespace-separated numbers.
    Data(&'a str),
}

/// A section with data lines.
#[derive(Clone, Copy, PartialEq)]
enum Block {
    Points,
    Elements,
    Marker,
}

impl Block {
    fn what(self) -> &'static str {
        match self {
            Block::Points => "points",
            Block::Elements => "elements",
            Block::Marker => "marker elements",
        }
    }

    fn keyword(self) -> &'static str {
        match self {
            Block::Points => "NPOIN=",
            Block::Elements => "NELEM=",
            Block::Marker => "MARKER_ELEMS=",
        }
    }
}

/// A section's progress: its kind, announced count, data lines read, keyword line.
struct Section {
    block: Block,
    count: usize,
    done: usize,
    line: usize,
}

/// The largest node index a section uses and the first line where it appears.
struct MaxRef {
    index: usize,
    line: usize,
}

/// A marker: its name, the line of its `MARKER_TAG=`, its facets.
struct Marker {
    name: String,
    line: usize,
    elems_seen: bool,
    facets: Cells,
}

/// What the reader has read so far, apart from where it stands in the bytes:
/// a streamed read carries it from one chunk of lines to the next.
pub(super) struct State {
    /// `(value, line)` of `NDIME=`, `NPOIN=`, `NELEM=`, `NMARK=`.
    ndime: Option<(usize, usize)>,
    npoin: Option<(usize, usize)>,
    nelem: Option<(usize, usize)>,
    nmark: Option<(usize, usize)>,
    /// The points read (and not yet taken by a streamed read).
    coords: Vec<f64>,
    /// The elements read (and not yet taken by a streamed read).
    cells: Cells,
    markers: Vec<Marker>,
    /// The line of each marker's `MARKER_TAG=`, by name.
    marker_lines: HashMap<String, usize>,
    /// One entry per element or marker section, in file order.
    max_refs: Vec<MaxRef>,
    /// The section whose data lines are being read.
    open: Option<Section>,
    /// The section just read to its end, for "more data than announced" messages.
    closed: Option<Section>,
    /// The last keyword line: `(keyword, line)`.
    last_keyword: Option<(String, usize)>,
    /// Inside sections verbss does not use: where they began (byte offset)
    /// and the section before them. Their data lines are not parsed.
    skipping: Option<(usize, Anchor)>,
    /// The last section read, where a skipped block starting now would stand.
    anchor: Anchor,
    /// The skipped blocks read so far (none in a streamed read).
    skipped: Vec<Skipped>,
}

impl State {
    /// Nothing read yet.
    fn new() -> Self {
        State {
            ndime: None,
            npoin: None,
            nelem: None,
            nmark: None,
            coords: Vec::new(),
            cells: Cells::new(),
            markers: Vec::new(),
            marker_lines: HashMap::new(),
            max_refs: Vec::new(),
            open: None,
            closed: None,
            last_keyword: None,
            skipping: None,
            anchor: Anchor::Start,
            skipped: Vec::new(),
        }
    }
}

/// Line-by-line reader: where it stands in the bytes, and its [`State`].
pub(super) struct Parser<'a> {
    bytes: &'a [u8],
    path: &'a Path,
    pos: usize,
    line: usize,
    /// Byte offset of the current line.
    line_start: usize,
    /// Byte offset just past the line read before the current one (blank
    /// and comment lines not counted): where the current line's leading
    /// comments begin.
    gap_start: usize,
    /// Byte offset just past the current line.
    line_end: usize,
    /// Whether `bytes` is one chunk of a streamed read: skipped sections
    /// are not kept (they may span chunks) and `NZONE=` is refused.
    streamed: bool,
    state: State,
}

impl<'a> Parser<'a> {
    pub(super) fn new(bytes: &'a [u8], path: &'a Path) -> Self {
        Parser {
            bytes,
            path,
            pos: crate::io::bom(bytes),
            line: 0,
            line_start: 0,
            gap_start: 0,
            line_end: 0,
            streamed: false,
            state: State::new(),
        }
    }

    fn err(&self, line: usize, message: String) -> Error {
        Error::Parse {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    /// Room for `n` announced entries of at least `per` numbers each, capped
    /// by what the rest of the file can hold (every number takes at least
    /// two bytes).
    fn capacity(&self, n: usize, per: usize) -> usize {
        n.min(self.bytes.len().saturating_sub(self.pos) / (2 * per))
    }

    /// The spatial dimension (`NDIME=` was read before any section that needs it).
    fn dim(&self) -> usize {
        self.state.ndime.map_or(0, |d| d.0)
    }

    /// The next non-blank line without its `%` comment, or `None` at the end.
    fn next_line(&mut self) -> Result<Option<Line<'a>>> {
        while self.pos < self.bytes.len() {
            let rest = &self.bytes[self.pos..];
            let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
            self.line_start = self.pos;
            self.pos += end + 1;
            self.line += 1;
            let raw = rest[..end].strip_suffix(b"\r").unwrap_or(&rest[..end]);
            let text = std::str::from_utf8(raw).map_err(|e| {
                self.err(
                    self.line,
                    format!(
                        "non-UTF-8 byte 0x{:02x} at column {} (expected SU2 ASCII text, \
                         found binary data)",
                        raw[e.valid_up_to()],
                        e.valid_up_to() + 1
                    ),
                )
            })?;
            let text = text.split('%').next().unwrap_or("").trim();
            if text.is_empty() {
                continue;
            }
            self.gap_start = self.line_end;
            self.line_end = self.pos.min(self.bytes.len());
            return Ok(Some(match text.split_once('=') {
                Some((key, value)) => Line::Keyword {
                    raw: key.trim(),
                    key: key
                        .chars()
                        .filter(|c| !c.is_whitespace() && *c != '_')
                        .collect::<String>()
                        .to_ascii_uppercase(),
                    value: value.trim(),
                },
                None => Line::Data(text),
            }));
        }
        Ok(None)
    }

    /// A parser of the zone in `bytes[start..end]`, whose first line is line
    /// `first_line` of the file.
    fn within(
        bytes: &'a [u8],
        path: &'a Path,
        start: usize,
        end: usize,
        first_line: usize,
    ) -> Self {
        let mut parser = Parser::new(&bytes[..end], path);
        parser.pos = start;
        parser.line = first_line - 1;
        parser.line_start = start;
        parser.gap_start = start;
        parser.line_end = start;
        parser
    }

    /// Reads to the end: the mesh, and the byte offset where what it read
    /// ends (past its last line or skipped block; trailing comments not included).
    pub(super) fn run(mut self) -> Result<(Mesh, usize)> {
        self.read_all()?;
        let end = match self.state.skipping {
            Some(_) => self.bytes.len(),
            None => self.line_end,
        };
        Ok((self.finish()?, end))
    }

    /// Reads every line of `bytes`.
    fn read_all(&mut self) -> Result<()> {
        while let Some(line) = self.next_line()? {
            match line {
                Line::Data(text) => self.data(text)?,
                Line::Keyword { raw, key, value } => self.keyword(raw, key, value)?,
            }
        }
        Ok(())
    }

    /// A data line: the next entry of the open section, skipped, or an error.
    fn data(&mut self, text: &str) -> Result<()> {
        let Some(open) = &mut self.state.open else {
            if self.state.skipping.is_some() {
                return Ok(());
            }
            let message = match (&self.state.closed, &self.state.last_keyword) {
                (Some(c), _) => format!(
                    "unexpected data line '{}' after the {} {} announced by {} at line {} \
                     (the count disagrees with the data)",
                    shown(text),
                    c.count,
                    c.block.what(),
                    c.block.keyword(),
                    c.line
                ),
                (None, Some((key, line))) => format!(
                    "unexpected data line '{}' after {key}= at line {line} \
                     (expected a keyword line)",
                    shown(text)
                ),
                (None, None) => format!(
                    "unexpected data line '{}' (expected NDIME= first)",
                    shown(text)
                ),
            };
            return Err(self.err(self.line, message));
        };
        open.done += 1;
        let block = open.block;
        if open.done == open.count {
            self.state.closed = self.state.open.take();
        }
        match block {
            Block::Points => self.point(text),
            Block::Elements => self.element(text),
            Block::Marker => self.marker_element(text),
        }
    }

    /// A keyword line: opens a section, or starts skipping an unknown one.
    fn keyword(&mut self, raw: &'a str, key: String, value: &'a str) -> Result<()> {
        let line = self.line;
        if let Some(open) = &self.state.open {
            return Err(self.err(
                line,
                format!(
                    "found {raw}= after {} of the {} {} announced by {} at line {} \
                     (the count disagrees with the data)",
                    open.done,
                    open.count,
                    open.block.what(),
                    open.block.keyword(),
                    open.line
                ),
            ));
        }
        self.state.closed = None;
        let skipped_from = self.state.skipping.take();
        match key.as_str() {
            "NDIME" => {
                self.once(self.state.ndime, "NDIME=")?;
                let d = self.count(value, "NDIME=")?;
                if d != 2 && d != 3 {
                    return Err(self.err(line, format!("NDIME= {d} (expected 2 or 3)")));
                }
                self.state.ndime = Some((d, line));
                self.state.anchor = Anchor::Dimension;
            }
            "NPOIN" => {
                self.need_dim("NPOIN=")?;
                self.once(self.state.npoin, "NPOIN=")?;
                let n = self.count(value, "NPOIN=")?;
                self.state.coords = Vec::with_capacity(self.capacity(n, self.dim()) * self.dim());
                self.state.npoin = Some((n, line));
                self.state.anchor = Anchor::Points;
                self.start(Block::Points, n);
            }
            "NELEM" => {
                self.need_dim("NELEM=")?;
                self.once(self.state.nelem, "NELEM=")?;
                let n = self.count(value, "NELEM=")?;
                let cap = self.capacity(n, 4);
                self.state.cells.kinds.reserve(cap);
                self.state.cells.offsets.reserve(cap);
                self.state.nelem = Some((n, line));
                self.state.anchor = Anchor::Elements;
                self.start(Block::Elements, n);
            }
            "NMARK" => {
                self.need_dim("NMARK=")?;
                self.once(self.state.nmark, "NMARK=")?;
                let n = self.count(value, "NMARK=")?;
                if n > MAX_GROUPS {
                    return Err(self.err(
                        line,
                        format!(
                            "NMARK= {n} is more than {MAX_GROUPS} markers (the most verbss reads)"
                        ),
                    ));
                }
                self.state.nmark = Some((n, line));
                self.state.anchor = Anchor::MarkerCount;
            }
            "NZONE" if self.streamed && self.count(value, "NZONE=")? > 1 => {
                return Err(self.err(
                    line,
                    format!(
                        "NZONE= {value}: a multi-zone file (expected one zone: a streamed read \
                         takes single-zone files)"
                    ),
                ));
            }
            "MARKERTAG" => self.marker_tag(value)?,
            "MARKERELEMS" => {
                let Some(m) = self.state.markers.last() else {
                    return Err(self.err(line, "MARKER_ELEMS= before MARKER_TAG=".into()));
                };
                if m.elems_seen {
                    return Err(self.err(
                        line,
                        format!(
                            "second MARKER_ELEMS= for marker '{}' (MARKER_TAG= at line {})",
                            m.name, m.line
                        ),
                    ));
                }
                let n = self.count(value, "MARKER_ELEMS=")?;
                let cap = self.capacity(n, 2);
                let m = self.state.markers.last_mut().expect("checked above");
                m.elems_seen = true;
                m.facets.kinds.reserve(cap);
                m.facets.offsets.reserve(cap);
                self.start(Block::Marker, n);
            }
            _ => {
                self.state.skipping = skipped_from.or(Some((self.gap_start, self.state.anchor)));
            }
        }
        if let (None, Some(from)) = (self.state.skipping, skipped_from) {
            self.keep_skipped(from, self.line_start);
        }
        self.state.last_keyword = Some((raw.to_string(), line));
        Ok(())
    }

    /// Keeps the skipped block that began at byte `start` after `after`, up to byte `end`.
    fn keep_skipped(&mut self, (start, after): (usize, Anchor), end: usize) {
        if self.streamed {
            return;
        }
        let text = &self.bytes[start..end.min(self.bytes.len())];
        self.state.skipped.push(Skipped {
            after,
            text: String::from_utf8_lossy(text).into_owned(),
        });
    }

    /// `MARKER_TAG= name`: starts a new marker.
    fn marker_tag(&mut self, name: &'a str) -> Result<()> {
        let line = self.line;
        let Some((nmark, nmark_line)) = self.state.nmark else {
            return Err(self.err(line, "MARKER_TAG= before NMARK=".into()));
        };
        self.check_marker_elems()?;
        if self.state.markers.len() == nmark {
            return Err(self.err(
                line,
                format!(
                    "MARKER_TAG= {name} is one more marker than the {nmark} announced by \
                     NMARK= at line {nmark_line} (the count disagrees with the data)"
                ),
            ));
        }
        if name.is_empty() {
            return Err(self.err(line, "empty MARKER_TAG= (expected a name)".into()));
        }
        if let Some(first) = self.state.marker_lines.insert(name.to_string(), line) {
            return Err(self.err(
                line,
                format!("marker '{name}' given twice (first at line {first})"),
            ));
        }
        self.state.markers.push(Marker {
            name: name.to_string(),
            line,
            elems_seen: false,
            facets: Cells::new(),
        });
        self.state.anchor = Anchor::Marker(self.state.markers.len() - 1);
        Ok(())
    }

    /// Fails when the last marker has no `MARKER_ELEMS=`.
    fn check_marker_elems(&self) -> Result<()> {
        match self.state.markers.last() {
            Some(m) if !m.elems_seen => Err(self.err(
                self.line,
                format!(
                    "marker '{}' (MARKER_TAG= at line {}) has no MARKER_ELEMS=",
                    m.name, m.line
                ),
            )),
            _ => Ok(()),
        }
    }

    /// Opens a section of `count` data lines.
    fn start(&mut self, block: Block, count: usize) {
        let section = Section {
            block,
            count,
            done: 0,
            line: self.line,
        };
        if block != Block::Points {
            self.state.max_refs.push(MaxRef { index: 0, line: 0 });
        }
        if count == 0 {
            self.state.closed = Some(section);
        } else {
            self.state.open = Some(section);
        }
    }

    fn need_dim(&self, keyword: &str) -> Result<()> {
        match self.state.ndime {
            Some(_) => Ok(()),
            None => Err(self.err(
                self.line,
                format!("{keyword} before NDIME= (expected NDIME= 2 or 3 first)"),
            )),
        }
    }

    fn once(&self, seen: Option<(usize, usize)>, keyword: &str) -> Result<()> {
        match seen {
            None => Ok(()),
            Some((_, first)) => Err(self.err(
                self.line,
                format!(
                    "{keyword} given twice (first at line {first}; a multi-zone file starts \
                     with NZONE= N and gives each zone after its IZONE= K line)"
                ),
            )),
        }
    }

    /// The count after a keyword; `NPOIN=` may add the number of domain points.
    fn count(&self, value: &str, keyword: &str) -> Result<usize> {
        let mut tokens = value.split_whitespace();
        let first = tokens.next();
        let extra_ok = keyword == "NPOIN=";
        let n = first.and_then(|t| t.parse::<usize>().ok());
        let rest_ok = tokens
            .enumerate()
            .all(|(k, t)| extra_ok && k == 0 && t.parse::<usize>().is_ok_and(|d| Some(d) <= n));
        match n {
            Some(n) if rest_ok => Ok(n),
            _ => Err(self.err(
                self.line,
                format!("expected a count after {keyword}, found '{}'", shown(value)),
            )),
        }
    }
    /// Checks what only the end of the file tells and builds the mesh.
    fn finish(mut self) -> Result<Mesh> {
        if let Some(from) = self.state.skipping.take() {
            self.keep_skipped(from, self.bytes.len());
        }
        let (dim, npoin) = self.check_end()?;
        let last = self.line.max(1);
        let (path, nelem) = (self.path, self.state.nelem);
        let mesh = Mesh {
            dim,
            node_tags: (1..=npoin as u64).collect(),
            cell_tags: (1..=self.state.cells.len() as u64).collect(),
            coords: self.state.coords,
            cells: self.state.cells,
            groups: self
                .state
                .markers
                .into_iter()
                .map(|m| Group {
                    name: m.name,
                    tag: None,
                    facets: m.facets,
                })
                .collect(),
            origin: FileOrigin {
                su2_skipped: self.state.skipped,
                ..FileOrigin::default()
            },
        };
        validate_at(&mesh, path, nelem.map_or(last, |(_, line)| line))?;
        Ok(mesh)
    }

    /// Checks what only the end of the file tells: no section left open,
    /// `NDIME=`, `NPOIN=` and `NELEM=` given, every marker complete, every
    /// node index below `NPOIN=`. Gives `NDIME=` and `NPOIN=`.
    pub(super) fn check_end(&self) -> Result<(usize, usize)> {
        let last = self.line.max(1);
        if let Some(open) = &self.state.open {
            return Err(self.err(
                last,
                format!(
                    "file ends after {} of the {} {} announced by {} at line {}",
                    open.done,
                    open.count,
                    open.block.what(),
                    open.block.keyword(),
                    open.line
                ),
            ));
        }
        let Some((dim, _)) = self.state.ndime else {
            return Err(self.err(last, "missing NDIME= (expected NDIME= 2 or 3)".into()));
        };
        let Some((npoin, npoin_line)) = self.state.npoin else {
            return Err(self.err(last, "missing NPOIN= (the file has no points)".into()));
        };
        if self.state.nelem.is_none() {
            return Err(self.err(last, "missing NELEM= (the file has no elements)".into()));
        }
        self.check_marker_elems()?;
        if let Some((nmark, line)) = self.state.nmark {
            if self.state.markers.len() < nmark {
                return Err(self.err(
                    last,
                    format!(
                        "file ends after {} of the {nmark} markers announced by NMARK= at line {line}",
                        self.state.markers.len()
                    ),
                ));
            }
        }
        if let Some(bad) = self
            .state
            .max_refs
            .iter()
            .find(|m| m.line > 0 && m.index >= npoin)
        {
            return Err(self.err(
                bad.line,
                format!(
                    "node index {} out of range (NPOIN= {npoin} at line {npoin_line}: {})",
                    bad.index,
                    match npoin {
                        0 => "no points".to_string(),
                        n => format!("indices 0 to {}", n - 1),
                    }
                ),
            ));
        }
        Ok((dim, npoin))
    }
}
