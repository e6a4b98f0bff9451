//! SU2 native ASCII meshes (`.su2`).
//!
//! A file is a list of sections, each opened by a keyword line:
//!
//! ```text
//! NDIME= 2                      % spatial dimension, 2 or 3
//! NELEM= 2                      % volume elements: VTK type id, node indices, [index]
//! 5  0 1 2  0
//! 5  0 2 3  1
//! NPOIN= 4                      % points: x y [z] [index]
//! 0 0  0
//! 1 0  1
//! 1 1  2
//! 0 1  3
//! NMARK= 1                      % boundary markers
//! MARKER_TAG= wall
//! MARKER_ELEMS= 1               % marker facets: VTK type id, node indices
//! 3  0 1
//! ```
//!
//! Node indices are 0-based positions in the `NPOIN=` list. Element type ids
//! are VTK's: 1 vertex, 3 line, 5 triangle, 9 quadrilateral, 10 tetrahedron,
//! 12 hexahedron, 13 prism, 14 pyramid. SU2 numbers nodes as VTK does, which
//! differs from verbss (Gmsh) for the prism only: see [`CellKind::vtk_local`].
//!
//! The reader accepts what SU2 and other tools write: `%` comments, blank
//! lines, sections in any order after `NDIME=`, keywords in any case with or
//! without `_` and spaces (`MARKER_TAG=`, `MARKERTAG =`), trailing indices after
//! coordinates and node lists, `NPOIN= n n_domain`. Sections it does not use
//! (`FFD_NBOX=`, `NPERIODIC=` and any other unknown keyword) are skipped with
//! their data lines. Node tags are `index + 1`, cell tags `element index + 1`.

use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells, Group, Mesh};

/// The SU2 (VTK) element type ids, their kinds and the names used in messages.
const TYPES: [(u32, CellKind, &str); 8] = [
    (1, CellKind::Vertex, "vertex"),
    (3, CellKind::Line, "line"),
    (5, CellKind::Triangle, "triangle"),
    (9, CellKind::Quad, "quadrilateral"),
    (10, CellKind::Tetra, "tetrahedron"),
    (12, CellKind::Hexahedron, "hexahedron"),
    (13, CellKind::Wedge, "prism"),
    (14, CellKind::Pyramid, "pyramid"),
];

/// The SU2 type id of a kind.
fn type_id(kind: CellKind) -> u32 {
    TYPES
        .iter()
        .find(|t| t.1 == kind)
        .map(|t| t.0)
        .expect("every kind has an SU2 type id")
}

/// Parses an SU2 file's bytes; `path` is only used in error messages.
///
/// Checks everything [`Mesh::validate`] checks, but reports it with the line:
/// every count against its data, every node index against `NPOIN=`, every
/// coordinate finite, every element type allowed where it stands.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh> {
    Parser::new(bytes, path).run()
}

/// Writes `mesh` in SU2 format: `NDIME=`, `NELEM=` (elements with their index),
/// `NPOIN=` (coordinates in shortest round-trip form, so that reading the file
/// back gives the same bits, with their index), `NMARK=` and one marker per group.
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] for a group name an SU2 file
/// cannot hold (empty, with surrounding spaces, a `%` or a control character).
pub fn write_to(w: &mut dyn Write, mesh: &Mesh) -> std::io::Result<()> {
    for g in &mesh.groups {
        let name = g.name.as_str();
        if name.is_empty()
            || name.trim() != name
            || name.contains('%')
            || name.chars().any(char::is_control)
        {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("group name {name:?} cannot be written as an SU2 MARKER_TAG"),
            ));
        }
    }
    writeln!(w, "NDIME= {}", mesh.dim)?;
    writeln!(w, "NELEM= {}", mesh.cells.len())?;
    for (c, (kind, nodes)) in mesh.cells.iter().enumerate() {
        write_element(w, kind, nodes)?;
        writeln!(w, "\t{c}")?;
    }
    writeln!(w, "NPOIN= {}", mesh.node_count())?;
    for i in 0..mesh.node_count() {
        for x in mesh.point(i) {
            write!(w, "{x:?}\t")?;
        }
        writeln!(w, "{i}")?;
    }
    writeln!(w, "NMARK= {}", mesh.groups.len())?;
    for g in &mesh.groups {
        writeln!(w, "MARKER_TAG= {}", g.name)?;
        writeln!(w, "MARKER_ELEMS= {}", g.facets.len())?;
        for (kind, nodes) in g.facets.iter() {
            write_element(w, kind, nodes)?;
            writeln!(w)?;
        }
    }
    Ok(())
}

/// Writes `type n1 … nk` without the end of line, in SU2's (VTK's) node order.
fn write_element(w: &mut dyn Write, kind: CellKind, nodes: &[usize]) -> std::io::Result<()> {
    write!(w, "{}", type_id(kind))?;
    for i in 0..nodes.len() {
        write!(w, "\t{}", nodes[kind.vtk_local(i)])?;
    }
    Ok(())
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

/// Line-by-line reader state.
struct Parser<'a> {
    bytes: &'a [u8],
    path: &'a Path,
    pos: usize,
    line: usize,
    /// `(value, line)` of `NDIME=`, `NPOIN=`, `NELEM=`, `NMARK=`.
    ndime: Option<(usize, usize)>,
    npoin: Option<(usize, usize)>,
    nelem: Option<(usize, usize)>,
    nmark: Option<(usize, usize)>,
    coords: Vec<f64>,
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
    /// Inside a section verbss does not use: its data lines are ignored.
    skipping: bool,
}

impl<'a> Parser<'a> {
    fn new(bytes: &'a [u8], path: &'a Path) -> Self {
        Parser {
            bytes,
            path,
            pos: 0,
            line: 0,
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
            skipping: false,
        }
    }

    fn err(&self, line: usize, message: String) -> Error {
        Error::Parse {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    /// A capacity for `n` announced entries of `per` numbers each, capped by
    /// what the file can hold (every number takes at least two bytes).
    fn capacity(&self, n: usize, per: usize) -> usize {
        n.saturating_mul(per).min(self.bytes.len() / 2)
    }

    /// The spatial dimension (`NDIME=` was read before any section that needs it).
    fn dim(&self) -> usize {
        self.ndime.map_or(0, |d| d.0)
    }

    /// The next non-blank line without its `%` comment, or `None` at the end.
    fn next_line(&mut self) -> Result<Option<Line<'a>>> {
        while self.pos < self.bytes.len() {
            let rest = &self.bytes[self.pos..];
            let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
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

    fn run(mut self) -> Result<Mesh> {
        while let Some(line) = self.next_line()? {
            match line {
                Line::Data(text) => self.data(text)?,
                Line::Keyword { raw, key, value } => self.keyword(raw, key, value)?,
            }
        }
        self.finish()
    }

    /// A data line: the next entry of the open section, skipped, or an error.
    fn data(&mut self, text: &str) -> Result<()> {
        let Some(open) = &mut self.open else {
            if self.skipping {
                return Ok(());
            }
            let message = match (&self.closed, &self.last_keyword) {
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
            self.closed = self.open.take();
        }
        match block {
            Block::Points => self.point(text),
            Block::Elements => self.element(text),
            Block::Marker => self.marker_element(text),
        }
    }

    /// A keyword line: opens a section, or starts skipping an unknown one.
    fn keyword(&mut self, raw: &str, key: String, value: &str) -> Result<()> {
        let line = self.line;
        if let Some(open) = &self.open {
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
        self.skipping = false;
        self.closed = None;
        match key.as_str() {
            "NDIME" => {
                self.once(self.ndime, "NDIME=")?;
                let d = self.count(value, "NDIME=")?;
                if d != 2 && d != 3 {
                    return Err(self.err(line, format!("NDIME= {d} (expected 2 or 3)")));
                }
                self.ndime = Some((d, line));
            }
            "NPOIN" => {
                self.need_dim("NPOIN=")?;
                self.once(self.npoin, "NPOIN=")?;
                let n = self.count(value, "NPOIN=")?;
                self.coords = Vec::with_capacity(self.capacity(n, self.dim()));
                self.npoin = Some((n, line));
                self.start(Block::Points, n);
            }
            "NELEM" => {
                self.need_dim("NELEM=")?;
                self.once(self.nelem, "NELEM=")?;
                let n = self.count(value, "NELEM=")?;
                let cap = self.capacity(n, 1);
                self.cells.kinds.reserve(cap);
                self.cells.offsets.reserve(cap);
                self.nelem = Some((n, line));
                self.start(Block::Elements, n);
            }
            "NMARK" => {
                self.need_dim("NMARK=")?;
                self.once(self.nmark, "NMARK=")?;
                self.nmark = Some((self.count(value, "NMARK=")?, line));
            }
            "MARKERTAG" => self.marker_tag(value)?,
            "MARKERELEMS" => {
                let Some(m) = self.markers.last() else {
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
                let cap = self.capacity(n, 1);
                let m = self.markers.last_mut().expect("checked above");
                m.elems_seen = true;
                m.facets.kinds.reserve(cap);
                m.facets.offsets.reserve(cap);
                self.start(Block::Marker, n);
            }
            _ => self.skipping = true,
        }
        self.last_keyword = Some((raw.to_string(), line));
        Ok(())
    }

    /// `MARKER_TAG= name`: starts a new marker.
    fn marker_tag(&mut self, name: &str) -> Result<()> {
        let line = self.line;
        let Some((nmark, nmark_line)) = self.nmark else {
            return Err(self.err(line, "MARKER_TAG= before NMARK=".into()));
        };
        self.check_marker_elems()?;
        if self.markers.len() == nmark {
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
        if let Some(first) = self.marker_lines.insert(name.to_string(), line) {
            return Err(self.err(
                line,
                format!("marker '{name}' given twice (first at line {first})"),
            ));
        }
        self.markers.push(Marker {
            name: name.to_string(),
            line,
            elems_seen: false,
            facets: Cells::new(),
        });
        Ok(())
    }

    /// Fails when the last marker has no `MARKER_ELEMS=`.
    fn check_marker_elems(&self) -> Result<()> {
        match self.markers.last() {
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
            self.max_refs.push(MaxRef { index: 0, line: 0 });
        }
        if count == 0 {
            self.closed = Some(section);
        } else {
            self.open = Some(section);
        }
    }

    fn need_dim(&self, keyword: &str) -> Result<()> {
        match self.ndime {
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
                    "{keyword} given twice (first at line {first}; \
                     multi-zone files are not supported)"
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

    /// `x y [z] [index …]`.
    fn point(&mut self, text: &str) -> Result<()> {
        let dim = self.dim();
        let mut tokens = text.split_whitespace();
        for k in 0..dim {
            let Some(t) = tokens.next() else {
                return Err(self.err(
                    self.line,
                    format!(
                        "expected NDIME= {dim} coordinates, found {k} in '{}'",
                        shown(text)
                    ),
                ));
            };
            let x: f64 = t.parse().map_err(|_| {
                self.err(
                    self.line,
                    format!("expected a coordinate, found '{}'", shown(t)),
                )
            })?;
            if !x.is_finite() {
                return Err(self.err(
                    self.line,
                    format!(
                        "non-finite coordinate '{}' (expected a finite number)",
                        shown(t)
                    ),
                ));
            }
            self.coords.push(x);
        }
        self.trailing_indices(tokens, &format!("the {dim} coordinates"))
    }

    /// Anything after a point's coordinates or an element's nodes must be an index.
    fn trailing_indices<'t>(
        &self,
        tokens: impl Iterator<Item = &'t str>,
        after: &str,
    ) -> Result<()> {
        for t in tokens {
            if t.parse::<u64>().is_err() {
                return Err(self.err(
                    self.line,
                    format!("expected an index after {after}, found '{}'", shown(t)),
                ));
            }
        }
        Ok(())
    }

    /// A volume element line `type n1 … nk [index …]`.
    fn element(&mut self, text: &str) -> Result<()> {
        let dim = self.dim();
        let kind = self.element_kind(text, |k| k.dim() == dim)?;
        let mut cells = std::mem::take(&mut self.cells);
        let done = self.element_nodes(text, kind, &mut cells);
        self.cells = cells;
        done
    }

    /// A marker element line `type n1 … nk [index …]`.
    fn marker_element(&mut self, text: &str) -> Result<()> {
        let dim = self.dim();
        let kind = self.element_kind(text, |k| k.dim() < dim)?;
        let mut m = self.markers.pop().expect("a marker section has a marker");
        let done = self.element_nodes(text, kind, &mut m.facets);
        self.markers.push(m);
        done
    }

    /// The kind named by the line's type id, which must pass `allowed`.
    fn element_kind(&self, text: &str, allowed: impl Fn(CellKind) -> bool) -> Result<CellKind> {
        let first = text.split_whitespace().next().unwrap_or("");
        let expected = || {
            let names: Vec<String> = TYPES
                .iter()
                .filter(|t| allowed(t.1))
                .map(|t| format!("{} {}", t.0, t.2))
                .collect();
            let (last, rest) = names.split_last().expect("every place allows a kind");
            if rest.is_empty() {
                last.clone()
            } else {
                format!("{} or {last}", rest.join(", "))
            }
        };
        let Ok(id) = first.parse::<u32>() else {
            return Err(self.err(
                self.line,
                format!(
                    "expected an SU2 element type ({}), found '{}'",
                    expected(),
                    shown(first)
                ),
            ));
        };
        match TYPES.iter().find(|t| t.0 == id) {
            Some(&(_, kind, _)) if allowed(kind) => Ok(kind),
            Some(&(_, _, name)) => Err(self.err(
                self.line,
                format!(
                    "SU2 element type {id} ({name}) does not belong in the {} of a {}D mesh \
                     (expected {})",
                    self.open_what(),
                    self.dim(),
                    expected()
                ),
            )),
            None => Err(self.err(
                self.line,
                format!(
                    "unsupported SU2 element type {id} (expected {})",
                    expected()
                ),
            )),
        }
    }

    /// What the section being read holds (the section may have just been closed).
    fn open_what(&self) -> &'static str {
        self.open
            .as_ref()
            .or(self.closed.as_ref())
            .map_or("elements", |s| s.block.what())
    }

    /// Reads the node indices after the type id into `cells`.
    fn element_nodes(&mut self, text: &str, kind: CellKind, cells: &mut Cells) -> Result<()> {
        let n = kind.node_count();
        let mut tokens = text.split_whitespace().skip(1);
        let start = cells.nodes.len();
        for k in 0..n {
            let Some(t) = tokens.next() else {
                return Err(self.err(
                    self.line,
                    format!(
                        "{} (type {}) needs {n} node indices, found {k}",
                        kind_name(kind),
                        type_id(kind)
                    ),
                ));
            };
            let Ok(i) = t.parse::<usize>() else {
                return Err(self.err(
                    self.line,
                    format!("expected a node index, found '{}'", shown(t)),
                ));
            };
            cells.nodes.push(i);
        }
        let mut stored = [0usize; 8];
        stored[..n].copy_from_slice(&cells.nodes[start..]);
        for (k, slot) in cells.nodes[start..].iter_mut().enumerate() {
            *slot = stored[kind.vtk_local(k)];
        }
        cells.kinds.push(kind);
        cells.offsets.push(cells.nodes.len());
        let top = cells.nodes[start..].iter().copied().max().unwrap_or(0);
        let line = self.line;
        let max = self
            .max_refs
            .last_mut()
            .expect("an element section has a max");
        if max.line == 0 || top > max.index {
            *max = MaxRef { index: top, line };
        }
        self.trailing_indices(tokens, &format!("the {n} node indices"))
    }

    /// Checks what only the end of the file tells and builds the mesh.
    fn finish(self) -> Result<Mesh> {
        let last = self.line.max(1);
        if let Some(open) = &self.open {
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
        let Some((dim, _)) = self.ndime else {
            return Err(self.err(last, "missing NDIME= (expected NDIME= 2 or 3)".into()));
        };
        let Some((npoin, npoin_line)) = self.npoin else {
            return Err(self.err(last, "missing NPOIN= (the file has no points)".into()));
        };
        if self.nelem.is_none() {
            return Err(self.err(last, "missing NELEM= (the file has no elements)".into()));
        }
        self.check_marker_elems()?;
        if let Some((nmark, line)) = self.nmark {
            if self.markers.len() < nmark {
                return Err(self.err(
                    last,
                    format!(
                        "file ends after {} of the {nmark} markers announced by NMARK= at line {line}",
                        self.markers.len()
                    ),
                ));
            }
        }
        if let Some(bad) = self
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
        let mesh = Mesh {
            dim,
            node_tags: (1..=npoin as u64).collect(),
            cell_tags: (1..=self.cells.len() as u64).collect(),
            coords: self.coords,
            cells: self.cells,
            groups: self
                .markers
                .into_iter()
                .map(|m| Group {
                    name: m.name,
                    tag: None,
                    facets: m.facets,
                })
                .collect(),
        };
        mesh.validate()?;
        Ok(mesh)
    }
}

/// The SU2/VTK name of a kind, as used in messages.
fn kind_name(kind: CellKind) -> &'static str {
    TYPES
        .iter()
        .find(|t| t.1 == kind)
        .map(|t| t.2)
        .expect("every kind has an SU2 name")
}

/// A token or line as quoted in messages: printable, at most 40 characters.
fn shown(text: &str) -> String {
    let mut s: String = text.chars().take(40).flat_map(char::escape_debug).collect();
    if text.chars().count() > 40 {
        s.push('…');
    }
    s
}

#[cfg(test)]
mod tests;
