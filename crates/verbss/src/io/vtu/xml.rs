//! The XML side of the `.vtu` reader: the tree of the elements the reader
//! uses, built without recursion, and error positions.
//!
//! Only `VTKFile`, `UnstructuredGrid`, `FieldData`, `Piece`, its `Points`,
//! `Cells`, `PointData` and `CellData`, their `DataArray`s and `AppendedData`
//! are kept, each with the attributes the reader needs; any other element is
//! skipped with everything inside it. What the tree holds is thus bounded by
//! [`MAX_ARRAYS`] arrays per section, whatever the file holds.

use std::path::Path;

use quick_xml::errors::SyntaxError;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use crate::error::{Error, Result};

/// How deep elements may nest (a `.vtu` file needs 6 levels).
const MAX_DEPTH: usize = 64;

/// The most `<DataArray>`s a `<FieldData>`, `<PointData>` or `<CellData>` may hold.
pub(super) const MAX_ARRAYS: usize = 1 << 17;

/// The file being read, for error messages.
pub(super) struct Ctx<'a> {
    pub(super) bytes: &'a [u8],
    pub(super) path: &'a Path,
}

impl Ctx<'_> {
    /// An error at the line holding byte `pos`.
    pub(super) fn at(&self, pos: usize, message: String) -> Error {
        let pos = pos.min(self.bytes.len());
        Error::Parse {
            path: self.path.to_path_buf(),
            line: 1 + self.bytes[..pos].iter().filter(|&&b| b == b'\n').count(),
            message,
        }
    }

    /// An error at byte `offset` of the file.
    pub(super) fn at_byte(&self, offset: usize, message: String) -> Error {
        Error::Binary {
            path: self.path.to_path_buf(),
            offset: offset as u64,
            message,
        }
    }
}

/// One kept XML element: name, the attributes the reader uses, the byte
/// ranges of its text (`DataArray` only), its kept children.
pub(super) struct Element {
    pub(super) name: &'static str,
    attrs: Vec<(&'static str, String)>,
    pub(super) text: Vec<(usize, usize)>,
    pub(super) children: Vec<Element>,
    /// Byte offset of its `<`.
    pub(super) pos: usize,
}

impl Element {
    pub(super) fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.as_str())
    }

    pub(super) fn children_named<'e>(
        &'e self,
        name: &'e str,
    ) -> impl Iterator<Item = &'e Element> + 'e {
        self.children.iter().filter(move |c| c.name == name)
    }

    pub(super) fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }
}

/// The attributes the reader uses, by element.
fn known_attrs(name: &str) -> &'static [&'static str] {
    match name {
        "VTKFile" => &["type", "byte_order", "header_type", "compressor"],
        "Piece" => &["NumberOfPoints", "NumberOfCells"],
        "DataArray" => &["type", "Name", "NumberOfComponents", "format", "offset"],
        "AppendedData" => &["encoding"],
        _ => &[],
    }
}

/// What becomes of a child element named `name` of `parent`.
enum Fate {
    Keep(&'static str),
    Skip,
}

/// Decides whether a child named `name` joins `parent` (the first of each
/// section, the arrays of the sections, the first `DataArray` of `Points`
/// and the first `connectivity`, `offsets`, `types`, `faces` and
/// `faceoffsets` of `Cells`), fails
/// on a second `<Piece>` or too many arrays.
fn fate(ctx: &Ctx, parent: &Element, e: &BytesStart, pos: usize) -> Result<Fate> {
    const SECTIONS: [&str; 8] = [
        "UnstructuredGrid",
        "AppendedData",
        "FieldData",
        "Points",
        "Cells",
        "PointData",
        "CellData",
        "Piece",
    ];
    let name = e.name();
    let name = name.as_ref();
    let allowed: &[&'static str] = match parent.name {
        "VTKFile" => &["UnstructuredGrid", "AppendedData"],
        "UnstructuredGrid" => &["FieldData", "Piece"],
        "Piece" => &["Points", "Cells", "PointData", "CellData"],
        "FieldData" | "Points" | "Cells" | "PointData" | "CellData" => &["DataArray"],
        _ => &[],
    };
    let Some(&child) = allowed.iter().find(|n| n.as_bytes() == name) else {
        return Ok(Fate::Skip);
    };
    if SECTIONS.contains(&child) && parent.child(child).is_some() {
        if child == "Piece" {
            return Err(ctx.at(
                pos,
                "a second <Piece> (only single-piece files are supported)".into(),
            ));
        }
        return Ok(Fate::Skip);
    }
    let keep = match parent.name {
        "Points" => parent.children.is_empty(),
        "Cells" => {
            let malformed = |e: String| ctx.at(pos, format!("malformed XML: {e}"));
            let array = match e.try_get_attribute("Name") {
                Ok(Some(a)) => Some(a.unescape_value().map_err(|e| malformed(e.to_string()))?),
                Ok(None) => None,
                Err(e) => return Err(malformed(e.to_string())),
            };
            ["connectivity", "offsets", "types", "faces", "faceoffsets"]
                .iter()
                .any(|&n| {
                    array.as_deref() == Some(n)
                        && parent
                            .children_named(child)
                            .all(|c| c.attr("Name") != Some(n))
                })
        }
        "FieldData" | "PointData" | "CellData" if parent.children.len() == MAX_ARRAYS => {
            return Err(ctx.at(
                pos,
                format!("more than {MAX_ARRAYS} <DataArray>s in <{}>", parent.name),
            ))
        }
        _ => true,
    };
    Ok(if keep { Fate::Keep(child) } else { Fate::Skip })
}

/// The `<AppendedData>` section: the bytes after its `_`.
#[derive(Clone, Copy)]
pub(super) struct Appended<'a> {
    /// File offset of `data[0]`.
    pub(super) start: usize,
    pub(super) data: &'a [u8],
    pub(super) base64: bool,
}

/// Reads the XML into a tree of the kept elements, up to the end of
/// `<VTKFile>` or the start of the appended data (which need not be XML).
pub(super) fn parse_tree<'a>(ctx: &Ctx<'a>) -> Result<(Element, Option<Appended<'a>>)> {
    let bytes = ctx.bytes;
    // quick-xml skips a byte-order mark but leaves it out of its positions.
    let skip = crate::io::bom(bytes);
    let mut reader = Reader::from_reader(&bytes[skip..]);
    let at = |r: &Reader<&[u8]>| skip + r.buffer_position() as usize;
    let mut stack: Vec<Element> = Vec::new();
    // Depth of the skipped element being read through (0: none), and of all.
    let (mut skipped, mut depth) = (0usize, 0usize);
    let not_vtk = |pos| {
        ctx.at(
            pos,
            r#"not a VTK XML file (expected <VTKFile type="UnstructuredGrid">)"#.to_string(),
        )
    };
    let appended = loop {
        let pos = at(&reader);
        let event = match reader.read_event() {
            Ok(event) => event,
            Err(quick_xml::Error::Syntax(e)) if e != SyntaxError::InvalidBangMarkup => {
                return Err(ctx.at(bytes.len(), format!("truncated file: {e}")))
            }
            Err(e) => {
                let at = skip + reader.error_position() as usize;
                return Err(ctx.at(at, format!("malformed XML: {e}")));
            }
        };
        let (e, open) = match event {
            Event::Start(e) => (e, true),
            Event::Empty(e) => (e, false),
            Event::End(_) => {
                depth -= 1;
                if skipped > 0 {
                    skipped -= 1;
                    continue;
                }
                let el = stack.pop().expect("quick-xml checks end tags");
                match stack.last_mut() {
                    Some(parent) => parent.children.push(el),
                    None => return Ok((el, None)),
                }
                continue;
            }
            Event::Text(t) => {
                match stack.last_mut() {
                    Some(el) if skipped == 0 && el.name == "DataArray" => {
                        el.text.push((pos, at(&reader)));
                    }
                    Some(_) => {}
                    None if t.iter().all(u8::is_ascii_whitespace) => {}
                    None => return Err(not_vtk(pos)),
                }
                continue;
            }
            Event::CData(t) => {
                if let Some(el) = stack
                    .last_mut()
                    .filter(|el| skipped == 0 && el.name == "DataArray")
                {
                    // The text between `<![CDATA[` and `]]>`.
                    el.text.push((pos + 9, pos + 9 + t.len()));
                }
                continue;
            }
            Event::Eof => match stack.last() {
                None => return Err(not_vtk(pos)),
                Some(el) => {
                    return Err(ctx.at(
                        bytes.len(),
                        format!("truncated file: end of file inside <{}>", el.name),
                    ))
                }
            },
            _ => continue,
        };
        if open {
            if depth == MAX_DEPTH {
                return Err(ctx.at(pos, format!("elements nested more than {MAX_DEPTH} deep")));
            }
            depth += 1;
        }
        let name = match stack.last() {
            _ if skipped > 0 => {
                skipped += usize::from(open);
                continue;
            }
            None if e.name().as_ref() == b"VTKFile" => "VTKFile",
            None => return Err(not_vtk(pos)),
            Some(parent) => match fate(ctx, parent, &e, pos)? {
                Fate::Keep(name) => name,
                Fate::Skip => {
                    skipped = usize::from(open);
                    continue;
                }
            },
        };
        let el = element(ctx, &e, name, pos)?;
        if open && name == "AppendedData" {
            let start = at(&reader);
            let appended = appended_section(ctx, &el, start)?;
            stack.push(el);
            break appended;
        }
        match (open, stack.last_mut()) {
            (true, _) => stack.push(el),
            (false, Some(parent)) => parent.children.push(el),
            (false, None) => return Ok((el, None)),
        }
    };
    let mut root = stack.pop().expect("AppendedData was pushed");
    while let Some(mut parent) = stack.pop() {
        parent.children.push(root);
        root = parent;
    }
    Ok((root, Some(appended)))
}

/// The element `name` from a start tag at byte `pos`, with the attributes
/// the reader uses (each at most once); every attribute is checked.
fn element(ctx: &Ctx, e: &BytesStart, name: &'static str, pos: usize) -> Result<Element> {
    let malformed = |e: String| ctx.at(pos, format!("malformed XML: {e}"));
    let known = known_attrs(name);
    let mut attrs: Vec<(&'static str, String)> = Vec::new();
    // quick-xml's duplicate check is quadratic: only the attributes used are
    // checked, against the few already kept.
    for a in e.attributes().with_checks(false) {
        let a = a.map_err(|e| malformed(e.to_string()))?;
        let Some(&key) = known.iter().find(|k| k.as_bytes() == a.key.as_ref()) else {
            continue;
        };
        if attrs.iter().any(|(k, _)| *k == key) {
            return Err(malformed(format!("duplicated attribute {key}")));
        }
        let value = a.unescape_value().map_err(|e| malformed(e.to_string()))?;
        attrs.push((key, value.into_owned()));
    }
    Ok(Element {
        name,
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

/// Collects the `offset` attributes of all appended `<DataArray>`s.
pub(super) fn collect_offsets(root: &Element, out: &mut Vec<usize>) {
    let mut todo = vec![root];
    while let Some(el) = todo.pop() {
        if el.name == "DataArray" && el.attr("format") == Some("appended") {
            out.extend(el.attr("offset").and_then(|o| o.parse::<usize>().ok()));
        }
        todo.extend(&el.children);
    }
}
