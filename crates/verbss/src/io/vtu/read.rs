//! The `.vtu` reader (what it accepts is in the parent module's doc).

use std::borrow::Cow;
use std::io::Read;
use std::path::Path;

use base64::engine::general_purpose::{GeneralPurpose, GeneralPurposeConfig};
use base64::engine::DecodePaddingMode;
use base64::Engine;
use quick_xml::errors::SyntaxError;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use super::{
    kind_of_vtk, Fields, VtuData, CELL_TAG_ARRAY, GROUP_ARRAY, NODE_TAG_ARRAY, UNNAMED_GROUP,
};
use crate::error::{Error, Result};
use crate::mesh::{Cells, Group, Mesh};

/// Parses a `.vtu` file's bytes; `path` is only used in error messages.
///
/// Errors name the line of the XML element at fault, or the byte offset in
/// raw appended data.
pub fn parse(bytes: &[u8], path: &Path) -> Result<VtuData> {
    let ctx = Ctx { bytes, path };
    let (root, appended) = parse_tree(&ctx)?;
    let file = VtkFile::new(&ctx, &root, appended)?;
    file.build(&root)
}

/// The file being read, for error messages.
struct Ctx<'a> {
    bytes: &'a [u8],
    path: &'a Path,
}

impl Ctx<'_> {
    /// An error at the line holding byte `pos`.
    fn at(&self, pos: usize, message: String) -> Error {
        let pos = pos.min(self.bytes.len());
        Error::Parse {
            path: self.path.to_path_buf(),
            line: 1 + self.bytes[..pos].iter().filter(|&&b| b == b'\n').count(),
            message,
        }
    }

    /// An error at byte `offset` of the file.
    fn at_byte(&self, offset: usize, message: String) -> Error {
        Error::Binary {
            path: self.path.to_path_buf(),
            offset: offset as u64,
            message,
        }
    }
}

/// One XML element: name, attributes, the byte ranges of its text, children.
struct Element {
    name: String,
    attrs: Vec<(String, String)>,
    text: Vec<(usize, usize)>,
    children: Vec<Element>,
    /// Byte offset of its `<`.
    pos: usize,
}

impl Element {
    fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    fn children_named<'e>(&'e self, name: &'e str) -> impl Iterator<Item = &'e Element> + 'e {
        self.children.iter().filter(move |c| c.name == name)
    }

    fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// The `<AppendedData>` section: the bytes after its `_`.
#[derive(Clone, Copy)]
struct Appended<'a> {
    /// File offset of `data[0]`.
    start: usize,
    data: &'a [u8],
    base64: bool,
}

/// Reads the XML into a tree, up to the end of `<VTKFile>` or the start of
/// the appended data (which need not be XML).
fn parse_tree<'a>(ctx: &Ctx<'a>) -> Result<(Element, Option<Appended<'a>>)> {
    let bytes = ctx.bytes;
    let mut reader = Reader::from_reader(bytes);
    let mut stack: Vec<Element> = Vec::new();
    let not_vtk = |pos| {
        ctx.at(
            pos,
            r#"not a VTK XML file (expected <VTKFile type="UnstructuredGrid">)"#.to_string(),
        )
    };
    let appended = loop {
        let pos = reader.buffer_position() as usize;
        let event = match reader.read_event() {
            Ok(event) => event,
            Err(quick_xml::Error::Syntax(e)) if e != SyntaxError::InvalidBangMarkup => {
                return Err(ctx.at(bytes.len(), format!("truncated file: {e}")))
            }
            Err(e) => {
                let at = reader.error_position() as usize;
                return Err(ctx.at(at, format!("malformed XML: {e}")));
            }
        };
        match event {
            Event::Start(e) | Event::Empty(e)
                if stack.is_empty() && e.name().as_ref() != b"VTKFile" =>
            {
                return Err(not_vtk(pos))
            }
            Event::Start(e) => {
                let el = element(ctx, &e, pos)?;
                if el.name == "AppendedData" {
                    let start = reader.buffer_position() as usize;
                    let appended = appended_section(ctx, &el, start)?;
                    stack.push(el);
                    break appended;
                }
                stack.push(el);
            }
            Event::Empty(e) => {
                let el = element(ctx, &e, pos)?;
                match stack.last_mut() {
                    Some(parent) => parent.children.push(el),
                    None => return Ok((el, None)),
                }
            }
            Event::End(_) => {
                let el = stack.pop().expect("quick-xml checks end tags");
                match stack.last_mut() {
                    Some(parent) => parent.children.push(el),
                    None => return Ok((el, None)),
                }
            }
            Event::Text(t) => match stack.last_mut() {
                Some(el) => el.text.push((pos, reader.buffer_position() as usize)),
                None if t.iter().all(u8::is_ascii_whitespace) => {}
                None => return Err(not_vtk(pos)),
            },
            Event::Eof => match stack.last() {
                None => return Err(not_vtk(pos)),
                Some(el) => {
                    return Err(ctx.at(
                        bytes.len(),
                        format!("truncated file: end of file inside <{}>", el.name),
                    ))
                }
            },
            _ => {}
        }
    };
    let mut root = stack.pop().expect("AppendedData was pushed");
    while let Some(mut parent) = stack.pop() {
        parent.children.push(root);
        root = parent;
    }
    Ok((root, Some(appended)))
}

/// An element from a start tag at byte `pos`.
fn element(ctx: &Ctx, e: &BytesStart, pos: usize) -> Result<Element> {
    let malformed = |e: String| ctx.at(pos, format!("malformed XML: {e}"));
    let mut attrs = Vec::new();
    for a in e.attributes() {
        let a = a.map_err(|e| malformed(e.to_string()))?;
        let value = a.unescape_value().map_err(|e| malformed(e.to_string()))?;
        let key = String::from_utf8_lossy(a.key.as_ref()).into_owned();
        attrs.push((key, value.into_owned()));
    }
    Ok(Element {
        name: String::from_utf8_lossy(e.name().as_ref()).into_owned(),
        attrs,
        text: Vec::new(),
        children: Vec::new(),
        pos,
    })
}

/// The appended data that starts after the `<AppendedData …>` tag ending at `start`.
fn appended_section<'a>(ctx: &Ctx<'a>, el: &Element, start: usize) -> Result<Appended<'a>> {
    let base64 = match el.attr("encoding") {
        Some("raw") => false,
        Some("base64") => true,
        other => {
            return Err(ctx.at(
                el.pos,
                format!(
                    "AppendedData encoding is {} (expected \"raw\" or \"base64\")",
                    other.map_or("missing".to_string(), |e| format!("\"{e}\""))
                ),
            ))
        }
    };
    let rest = &ctx.bytes[start..];
    let skip = rest.iter().take_while(|b| b.is_ascii_whitespace()).count();
    if rest.get(skip) != Some(&b'_') {
        return Err(ctx.at(
            start + skip,
            "AppendedData does not start with '_'".to_string(),
        ));
    }
    let start = start + skip + 1;
    let mut data = &ctx.bytes[start..];
    if base64 {
        let end = data.iter().position(|&b| b == b'<').unwrap_or(data.len());
        data = data[..end].trim_ascii_end();
    }
    Ok(Appended {
        start,
        data,
        base64,
    })
}

/// A number type found in a `type` attribute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl Ty {
    fn parse(s: &str) -> Option<Ty> {
        Some(match s {
            "Int8" => Ty::I8,
            "UInt8" => Ty::U8,
            "Int16" => Ty::I16,
            "UInt16" => Ty::U16,
            "Int32" => Ty::I32,
            "UInt32" => Ty::U32,
            "Int64" => Ty::I64,
            "UInt64" => Ty::U64,
            "Float32" => Ty::F32,
            "Float64" => Ty::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::I64 | Ty::U64 | Ty::F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Ty::F32 | Ty::F64)
    }
}

/// The values of one array.
enum Values {
    Int(Vec<i64>),
    Float(Vec<f64>),
}

impl Values {
    fn len(&self) -> usize {
        match self {
            Values::Int(v) => v.len(),
            Values::Float(v) => v.len(),
        }
    }

    fn into_f64(self) -> Vec<f64> {
        match self {
            Values::Int(v) => v.into_iter().map(|x| x as f64).collect(),
            Values::Float(v) => v,
        }
    }
}

/// One decoded `<DataArray>`.
struct Array<'e> {
    el: &'e Element,
    name: String,
    components: usize,
    values: Values,
}

/// A failure inside a binary block: offset in the block's byte stream, message.
type BlockError = (usize, String);

/// The file-wide settings needed to decode arrays.
struct VtkFile<'a, 'c> {
    ctx: &'c Ctx<'a>,
    big_endian: bool,
    header64: bool,
    zlib: bool,
    appended: Option<Appended<'a>>,
    /// Sorted `offset`s of the appended arrays (to cut base64 appended data).
    offsets: Vec<usize>,
}

impl<'a, 'c> VtkFile<'a, 'c> {
    fn new(ctx: &'c Ctx<'a>, root: &Element, appended: Option<Appended<'a>>) -> Result<Self> {
        let attr_err = |what: &str, v: &str, expected: &str| {
            ctx.at(
                root.pos,
                format!("VTKFile {what}=\"{v}\" (expected {expected})"),
            )
        };
        match root.attr("type") {
            Some("UnstructuredGrid") => {}
            other => {
                return Err(attr_err(
                    "type",
                    other.unwrap_or(""),
                    "\"UnstructuredGrid\"",
                ))
            }
        }
        let big_endian = match root.attr("byte_order") {
            None | Some("LittleEndian") => false,
            Some("BigEndian") => true,
            Some(o) => return Err(attr_err("byte_order", o, "LittleEndian or BigEndian")),
        };
        let header64 = match root.attr("header_type") {
            None | Some("UInt32") => false,
            Some("UInt64") => true,
            Some(h) => return Err(attr_err("header_type", h, "UInt32 or UInt64")),
        };
        let zlib = match root.attr("compressor") {
            None | Some("") => false,
            Some("vtkZLibDataCompressor") => true,
            Some(c) => return Err(attr_err("compressor", c, "vtkZLibDataCompressor or none")),
        };
        let mut offsets = Vec::new();
        collect_offsets(root, &mut offsets);
        offsets.sort_unstable();
        Ok(VtkFile {
            ctx,
            big_endian,
            header64,
            zlib,
            appended,
            offsets,
        })
    }

    /// Decodes a `<DataArray>`.
    fn array<'e>(&self, el: &'e Element) -> Result<Array<'e>> {
        let name = el.attr("Name").unwrap_or("").to_string();
        let err = |m: String| self.ctx.at(el.pos, format!("DataArray '{name}': {m}"));
        let ty_name = el.attr("type").unwrap_or("");
        let ty = Ty::parse(ty_name).ok_or_else(|| err(format!("unknown type \"{ty_name}\"")))?;
        let components = match el.attr("NumberOfComponents") {
            None | Some("") => 1,
            Some(c) => match c.parse() {
                Ok(c) if c > 0 => c,
                _ => return Err(err(format!("NumberOfComponents=\"{c}\" is not a count"))),
            },
        };
        let values = match el.attr("format").unwrap_or("ascii") {
            "ascii" => self.ascii(el, ty, &name)?,
            "binary" => {
                let text: Vec<u8> = el
                    .text
                    .iter()
                    .flat_map(|&(s, e)| &self.ctx.bytes[s..e])
                    .copied()
                    .filter(|b| !b.is_ascii_whitespace())
                    .collect();
                let stream = decode_base64(&text).map_err(|(_, m)| err(m))?;
                self.block_values(&stream, ty).map_err(|(_, m)| err(m))?
            }
            "appended" => {
                let offset = el.attr("offset").unwrap_or("");
                let offset: usize = offset
                    .parse()
                    .map_err(|_| err(format!("offset=\"{offset}\" is not a byte offset")))?;
                let app = self.appended.ok_or_else(|| {
                    err("format=\"appended\" but there is no <AppendedData>".into())
                })?;
                if offset > app.data.len() {
                    return Err(err(format!(
                        "offset {offset} is beyond the end of the appended data ({} bytes)",
                        app.data.len()
                    )));
                }
                let at = |(i, m): BlockError| {
                    self.ctx
                        .at_byte(app.start + offset + i, format!("DataArray '{name}': {m}"))
                };
                if app.base64 {
                    let end = self
                        .offsets
                        .iter()
                        .find(|&&o| o > offset)
                        .map_or(app.data.len(), |&o| o.min(app.data.len()));
                    let stream = decode_base64(&app.data[offset..end]).map_err(at)?;
                    self.block_values(&stream, ty)
                        .map_err(|(_, m)| at((0, m)))?
                } else {
                    self.block_values(&app.data[offset..], ty).map_err(at)?
                }
            }
            other => return Err(err(format!("unknown format \"{other}\""))),
        };
        Ok(Array {
            el,
            name,
            components,
            values,
        })
    }

    /// Parses the whitespace-separated numbers of an ascii array.
    fn ascii(&self, el: &Element, ty: Ty, name: &str) -> Result<Values> {
        let mut ints = Vec::new();
        let mut floats = Vec::new();
        for &(start, end) in &el.text {
            let mut i = start;
            for token in self.ctx.bytes[start..end].split(|b| b.is_ascii_whitespace()) {
                let at = i;
                i += token.len() + 1;
                if token.is_empty() {
                    continue;
                }
                let text = std::str::from_utf8(token).unwrap_or("");
                let ok = if ty.is_float() {
                    text.parse().map(|x| floats.push(x)).is_ok()
                } else {
                    text.parse().map(|x| ints.push(x)).is_ok()
                };
                if !ok {
                    return Err(self.ctx.at(
                        at,
                        format!(
                            "DataArray '{name}': \"{}\" is not a number",
                            String::from_utf8_lossy(token)
                        ),
                    ));
                }
            }
        }
        Ok(if ty.is_float() {
            Values::Float(floats)
        } else {
            Values::Int(ints)
        })
    }

    /// Reads one header word (4 or 8 bytes) at byte `at` of a block.
    fn word(&self, s: &[u8], at: usize) -> std::result::Result<u64, BlockError> {
        let size = if self.header64 { 8 } else { 4 };
        let b = s.get(at..at + size).ok_or_else(|| {
            (
                at,
                format!(
                    "truncated: header needs {size} bytes, {} remain",
                    s.len().saturating_sub(at)
                ),
            )
        })?;
        Ok(match (self.header64, self.big_endian) {
            (true, false) => u64::from_le_bytes(b.try_into().expect("8 bytes")),
            (true, true) => u64::from_be_bytes(b.try_into().expect("8 bytes")),
            (false, false) => u32::from_le_bytes(b.try_into().expect("4 bytes")).into(),
            (false, true) => u32::from_be_bytes(b.try_into().expect("4 bytes")).into(),
        })
    }

    /// The data bytes of a binary block `s` (header, then data): sliced out,
    /// or inflated block by block when zlib-compressed.
    fn block<'s>(&self, s: &'s [u8]) -> std::result::Result<Cow<'s, [u8]>, BlockError> {
        let h = if self.header64 { 8 } else { 4 };
        let too_long = |at: usize, claim: u64| {
            (
                at,
                format!(
                    "truncated: header claims {claim} bytes but only {} remain",
                    s.len().saturating_sub(at)
                ),
            )
        };
        if !self.zlib {
            let n = self.word(s, 0)?;
            return match usize::try_from(n) {
                Ok(n) if n <= s.len() - h => Ok(Cow::Borrowed(&s[h..h + n])),
                _ => Err(too_long(h, n)),
            };
        }
        let blocks = self.word(s, 0)?;
        let full = self.word(s, h)?;
        let last = self.word(s, 2 * h)?;
        let header = match usize::try_from(blocks) {
            Ok(b) if b <= s.len() / h => (3 + b) * h,
            _ => return Err(too_long(3 * h, blocks.saturating_mul(h as u64))),
        };
        let mut start = header;
        let mut out = Vec::new();
        for k in 0..header / h - 3 {
            let size = self.word(s, (3 + k) * h)?;
            let end = match usize::try_from(size) {
                Ok(size) if size <= s.len() - start => start + size,
                _ => return Err(too_long(start, size)),
            };
            let expected = if k + 1 == header / h - 3 && last != 0 {
                last
            } else {
                full
            };
            let before = out.len();
            flate2::read::ZlibDecoder::new(&s[start..end])
                .take(expected.saturating_add(1))
                .read_to_end(&mut out)
                .map_err(|e| (start, format!("zlib block {k}: {e}")))?;
            if (out.len() - before) as u64 != expected {
                return Err((
                    start,
                    format!(
                        "zlib block {k} inflates to {} bytes (header says {expected})",
                        out.len() - before
                    ),
                ));
            }
            start = end;
        }
        Ok(Cow::Owned(out))
    }

    /// The values of a binary block.
    fn block_values(&self, s: &[u8], ty: Ty) -> std::result::Result<Values, BlockError> {
        let data = self.block(s)?;
        let size = ty.size();
        if data.len() % size != 0 {
            return Err((
                0,
                format!(
                    "{} bytes is not a whole number of {size}-byte values",
                    data.len()
                ),
            ));
        }
        let be = self.big_endian;
        macro_rules! conv {
            ($t:ty) => {
                data.chunks_exact(size).map(|c| {
                    let b = c.try_into().expect("chunk of the type's size");
                    if be {
                        <$t>::from_be_bytes(b)
                    } else {
                        <$t>::from_le_bytes(b)
                    }
                })
            };
        }
        Ok(match ty {
            Ty::I8 => Values::Int(conv!(i8).map(i64::from).collect()),
            Ty::U8 => Values::Int(conv!(u8).map(i64::from).collect()),
            Ty::I16 => Values::Int(conv!(i16).map(i64::from).collect()),
            Ty::U16 => Values::Int(conv!(u16).map(i64::from).collect()),
            Ty::I32 => Values::Int(conv!(i32).map(i64::from).collect()),
            Ty::U32 => Values::Int(conv!(u32).map(i64::from).collect()),
            Ty::I64 => Values::Int(conv!(i64).collect()),
            Ty::U64 => Values::Int(
                conv!(u64)
                    .map(|v| {
                        i64::try_from(v).map_err(|_| (0, format!("UInt64 value {v} is too large")))
                    })
                    .collect::<std::result::Result<_, _>>()?,
            ),
            Ty::F32 => Values::Float(conv!(f32).map(f64::from).collect()),
            Ty::F64 => Values::Float(conv!(f64).collect()),
        })
    }

    /// The mesh and fields of the file.
    fn build(&self, root: &Element) -> Result<VtuData> {
        let ctx = self.ctx;
        let grid = root
            .child("UnstructuredGrid")
            .ok_or_else(|| ctx.at(root.pos, "missing <UnstructuredGrid> in <VTKFile>".into()))?;
        let mut pieces = grid.children_named("Piece");
        let piece = pieces
            .next()
            .ok_or_else(|| ctx.at(grid.pos, "missing <Piece> in <UnstructuredGrid>".into()))?;
        if let Some(second) = pieces.next() {
            return Err(ctx.at(
                second.pos,
                "a second <Piece> (only single-piece files are supported)".into(),
            ));
        }
        let count = |key: &str| -> Result<usize> {
            let v = piece.attr(key).unwrap_or("");
            v.parse()
                .map_err(|_| ctx.at(piece.pos, format!("Piece {key}=\"{v}\" is not a count")))
        };
        let n = count("NumberOfPoints")?;
        let ncells = count("NumberOfCells")?;
        let section = |name: &str| {
            piece
                .child(name)
                .ok_or_else(|| ctx.at(piece.pos, format!("missing <{name}> in <Piece>")))
        };

        let points_el = section("Points")?;
        let points_da = points_el
            .child("DataArray")
            .ok_or_else(|| ctx.at(points_el.pos, "missing <DataArray> in <Points>".into()))?;
        let points = self.array(points_da)?;
        let coords = self.points(points, n)?;

        let cells_el = section("Cells")?;
        let cell_array = |name: &str| {
            let el = cells_el
                .children_named("DataArray")
                .find(|d| d.attr("Name") == Some(name))
                .ok_or_else(|| {
                    ctx.at(
                        cells_el.pos,
                        format!("missing DataArray '{name}' in <Cells>"),
                    )
                })?;
            self.array(el)
        };
        let arrays = [
            cell_array("connectivity")?,
            cell_array("offsets")?,
            cell_array("types")?,
        ];
        let all = self.cells(&arrays, n, ncells)?;

        let point_data = self.data(piece.child("PointData"), "NumberOfPoints", n)?;
        let cell_data = self.data(piece.child("CellData"), "NumberOfCells", ncells)?;
        let names = match grid.child("FieldData") {
            Some(f) => self.group_names(f)?,
            None => Vec::new(),
        };
        assemble(self, piece, coords, all, point_data, cell_data, names)
    }

    /// The coordinates, checked against `NumberOfPoints` and for NaN.
    fn points(&self, a: Array, n: usize) -> Result<Vec<f64>> {
        let err = |m: String| {
            self.ctx
                .at(a.el.pos, format!("DataArray '{}': {m}", a.name))
        };
        if a.components != 3 {
            return Err(err(format!(
                "NumberOfComponents is {} (expected 3)",
                a.components
            )));
        }
        let coords = a.values.into_f64();
        if coords.len() != 3 * n {
            return Err(err(format!(
                "{} values but NumberOfPoints={n} needs {}",
                coords.len(),
                3 * n
            )));
        }
        if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
            return Err(err(format!(
                "point {} has a non-finite coordinate ({})",
                i / 3,
                coords[i]
            )));
        }
        Ok(coords)
    }

    /// The integer values of an array with one component, `len` of them if given.
    fn ints<'v>(&self, a: &'v Array, len: Option<usize>) -> Result<&'v [i64]> {
        let err = |m: String| {
            self.ctx
                .at(a.el.pos, format!("DataArray '{}': {m}", a.name))
        };
        let count = a.values.len();
        let values = match &a.values {
            Values::Int(v) => v,
            Values::Float(_) => return Err(err("expected an integer type".into())),
        };
        if a.components != 1 {
            return Err(err(format!(
                "NumberOfComponents is {} (expected 1)",
                a.components
            )));
        }
        match len {
            Some(len) if len != count => {
                Err(err(format!("{count} values but NumberOfCells={len}")))
            }
            _ => Ok(values),
        }
    }

    /// All cells of the file, checked: kinds known, node counts right, nodes in range.
    fn cells(&self, [conn, offsets, types]: &[Array; 3], n: usize, ncells: usize) -> Result<Cells> {
        let at = |a: &Array, m: String| {
            self.ctx
                .at(a.el.pos, format!("DataArray '{}': {m}", a.name))
        };
        let nodes = self.ints(conn, None)?;
        let ends = self.ints(offsets, Some(ncells))?;
        let kinds = self.ints(types, Some(ncells))?;
        let mut cells = Cells::new();
        let mut start = 0;
        for (c, (&end, &t)) in ends.iter().zip(kinds).enumerate() {
            let kind = kind_of_vtk(t).ok_or_else(|| {
                at(
                    types,
                    format!(
                        "cell {c} has unknown VTK type {t} (supported: 1 vertex, 3 line, \
                         5 triangle, 9 quad, 10 tetra, 12 hexahedron, 13 wedge, 14 pyramid)"
                    ),
                )
            })?;
            let end = match usize::try_from(end) {
                Ok(e) if e >= start && e <= nodes.len() => e,
                _ => {
                    return Err(at(
                        offsets,
                        format!("cell {c} ends at {end}, outside {start}..={}", nodes.len()),
                    ))
                }
            };
            if end - start != kind.node_count() {
                return Err(at(
                    offsets,
                    format!(
                        "cell {c} ({}) has {} nodes (expected {})",
                        kind.name(),
                        end - start,
                        kind.node_count()
                    ),
                ));
            }
            let mut local = [0usize; 8];
            for (k, &i) in nodes[start..end].iter().enumerate() {
                local[kind.vtk_local(k)] = match usize::try_from(i) {
                    Ok(i) if i < n => i,
                    _ => {
                        return Err(at(
                            conn,
                            format!("cell {c} uses point {i} but NumberOfPoints={n}"),
                        ))
                    }
                };
            }
            cells.push(kind, &local[..end - start]);
            start = end;
        }
        if start != nodes.len() {
            return Err(at(
                offsets,
                format!(
                    "the last cell ends at {start} but connectivity has {} values",
                    nodes.len()
                ),
            ));
        }
        Ok(cells)
    }

    /// The arrays of a `<PointData>` or `<CellData>` section, `count` tuples each.
    fn data<'e>(
        &self,
        section: Option<&'e Element>,
        key: &str,
        count: usize,
    ) -> Result<Vec<Array<'e>>> {
        let Some(section) = section else {
            return Ok(Vec::new());
        };
        section
            .children_named("DataArray")
            .map(|el| {
                let a = self.array(el)?;
                if a.values.len() != a.components * count {
                    return Err(self.ctx.at(
                        el.pos,
                        format!(
                            "DataArray '{}': {} values but {} × {key}={count} are needed",
                            a.name,
                            a.values.len(),
                            a.components
                        ),
                    ));
                }
                Ok(a)
            })
            .collect()
    }

    /// The group names of `<FieldData>`: `(id, name, tag)` from each integer
    /// array of 2 or 3 values `id ≥ 1, dim, (tag)`; other arrays are not groups.
    fn group_names(&self, field_data: &Element) -> Result<Vec<(i64, String, Option<i32>)>> {
        let mut names = Vec::new();
        for el in field_data.children_named("DataArray") {
            if el.attr("type").and_then(Ty::parse).is_none_or(Ty::is_float) {
                continue;
            }
            let a = self.array(el)?;
            let Values::Int(v) = &a.values else { continue };
            let tag = match v[..] {
                [id, _] if id >= 1 => None,
                [id, _, tag] if id >= 1 => match i32::try_from(tag) {
                    Ok(tag) => Some(tag),
                    Err(_) => continue,
                },
                _ => continue,
            };
            names.push((v[0], a.name, tag));
        }
        names.sort_by_key(|g| g.0);
        Ok(names)
    }
}

/// Removes the array called `name` from `arrays`.
fn take_array<'e>(arrays: &mut Vec<Array<'e>>, name: &str) -> Option<Array<'e>> {
    let i = arrays.iter().position(|a| a.name == name)?;
    Some(arrays.remove(i))
}

/// Tags from an integer array (each ≥ 1), or `1..=count` when there is none.
fn tags(file: &VtkFile, array: Option<Array>, what: &str, keep: &[usize]) -> Result<Vec<u64>> {
    let Some(a) = array else {
        return Ok((1..=keep.len() as u64).collect());
    };
    let values = file.ints(&a, None)?;
    keep.iter()
        .map(|&i| {
            u64::try_from(values[i])
                .ok()
                .filter(|&t| t >= 1)
                .ok_or_else(|| {
                    file.ctx.at(
                        a.el.pos,
                        format!(
                            "DataArray '{}': {what} {i} has tag {} (tags are ≥ 1)",
                            a.name, values[i]
                        ),
                    )
                })
        })
        .collect()
}

/// Splits the cells into volume cells and groups and builds the mesh (module doc).
fn assemble(
    file: &VtkFile,
    piece: &Element,
    coords: Vec<f64>,
    all: Cells,
    mut point_data: Vec<Array>,
    mut cell_data: Vec<Array>,
    names: Vec<(i64, String, Option<i32>)>,
) -> Result<VtuData> {
    let ctx = file.ctx;
    let n = coords.len() / 3;
    let top = all
        .kinds
        .iter()
        .map(|k| k.dim())
        .max()
        .ok_or_else(|| ctx.at(piece.pos, "the file has no cells".into()))?;
    let off_plane = (0..n).find(|&i| coords[3 * i + 2] != 0.0);
    let dim = if top <= 2 && off_plane.is_none() {
        2
    } else {
        3
    };
    if top < dim {
        let message = match off_plane {
            Some(i) if dim == 3 => format!(
                "no 3D cells but point {i} has z = {} (surface meshes are not supported)",
                coords[3 * i + 2]
            ),
            _ => "no 2D or 3D cells (only lines and vertices)".to_string(),
        };
        return Err(ctx.at(piece.pos, message));
    }

    let group_ids = match take_array(&mut cell_data, GROUP_ARRAY) {
        Some(a) => file.ints(&a, None)?.to_vec(),
        None => vec![0; all.len()],
    };
    let mut groups: Vec<Group> = names
        .iter()
        .map(|(_, name, tag)| Group {
            name: name.clone(),
            tag: *tag,
            facets: Cells::new(),
        })
        .collect();
    let mut volume = Vec::new();
    let mut cells = Cells::new();
    let mut unnamed = None;
    for (c, (kind, nodes)) in all.iter().enumerate() {
        if kind.dim() == dim {
            volume.push(c);
            cells.push(kind, nodes);
            continue;
        }
        let named = names.iter().position(|g| g.0 == group_ids[c]);
        let k = named.unwrap_or_else(|| {
            *unnamed.get_or_insert_with(|| {
                groups.push(Group {
                    name: UNNAMED_GROUP.to_string(),
                    tag: None,
                    facets: Cells::new(),
                });
                groups.len() - 1
            })
        });
        groups[k].facets.push(kind, nodes);
    }

    let all_points: Vec<usize> = (0..n).collect();
    let node_tags = tags(
        file,
        take_array(&mut point_data, NODE_TAG_ARRAY),
        "point",
        &all_points,
    )?;
    let cell_tags = tags(
        file,
        take_array(&mut cell_data, CELL_TAG_ARRAY),
        "cell",
        &volume,
    )?;
    let fields = Fields {
        point: point_data
            .into_iter()
            .map(|a| (a.name, a.components, a.values.into_f64()))
            .collect(),
        cell: cell_data
            .into_iter()
            .map(|a| {
                let values = a.values.into_f64();
                let rows = volume
                    .iter()
                    .flat_map(|&c| &values[c * a.components..(c + 1) * a.components]);
                (a.name, a.components, rows.copied().collect())
            })
            .collect(),
    };
    let coords = if dim == 3 {
        coords
    } else {
        coords.chunks_exact(3).flat_map(|p| [p[0], p[1]]).collect()
    };
    let mesh = Mesh {
        dim,
        coords,
        node_tags,
        cells,
        cell_tags,
        groups,
    };
    mesh.validate()?;
    Ok(VtuData { mesh, fields })
}

/// Collects the `offset` attributes of all appended `<DataArray>`s.
fn collect_offsets(el: &Element, out: &mut Vec<usize>) {
    if el.name == "DataArray" && el.attr("format") == Some("appended") {
        out.extend(el.attr("offset").and_then(|o| o.parse::<usize>().ok()));
    }
    for c in &el.children {
        collect_offsets(c, out);
    }
}

/// Decodes base64 text made of one or more padded segments (VTK encodes a
/// header and its data separately, meshio sometimes together): the bytes of
/// all segments, one after the other.
fn decode_base64(text: &[u8]) -> std::result::Result<Vec<u8>, BlockError> {
    const ENGINE: GeneralPurpose = GeneralPurpose::new(
        &base64::alphabet::STANDARD,
        GeneralPurposeConfig::new()
            .with_decode_allow_trailing_bits(true)
            .with_decode_padding_mode(DecodePaddingMode::Indifferent),
    );
    let mut out = Vec::with_capacity(text.len() / 4 * 3);
    let mut start = 0;
    while start < text.len() {
        let end = text[start..]
            .iter()
            .position(|&b| b == b'=')
            .map_or(text.len(), |p| ((start + p) / 4 + 1) * 4)
            .min(text.len());
        ENGINE
            .decode_vec(&text[start..end], &mut out)
            .map_err(|e| match e {
                base64::DecodeError::InvalidByte(i, b)
                | base64::DecodeError::InvalidLastSymbol(i, b) => (
                    start + i,
                    format!(
                        "invalid base64 character '{}' at position {}",
                        b.escape_ascii(),
                        start + i
                    ),
                ),
                _ => (
                    end,
                    format!("base64 data of {} characters is cut short", text.len()),
                ),
            })?;
        start = end;
    }
    Ok(out)
}
