//! The XML side of the `.vtu` reader: the element tree, built without
//! recursion and at most [`MAX_DEPTH`] elements deep, and error positions.

use std::collections::HashSet;
use std::path::Path;

use quick_xml::errors::SyntaxError;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use crate::error::{Error, Result};

/// How deep elements may nest (a `.vtu` file needs 6 levels).
const MAX_DEPTH: usize = 64;

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

/// One XML element: name, attributes, the byte ranges of its text, children.
pub(super) struct Element {
    pub(super) name: String,
    attrs: Vec<(String, String)>,
    pub(super) text: Vec<(usize, usize)>,
    pub(super) children: Vec<Element>,
    /// Byte offset of its `<`.
    pub(super) pos: usize,
}

impl Element {
    pub(super) fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
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

/// The `<AppendedData>` section: the bytes after its `_`.
#[derive(Clone, Copy)]
pub(super) struct Appended<'a> {
    /// File offset of `data[0]`.
    pub(super) start: usize,
    pub(super) data: &'a [u8],
    pub(super) base64: bool,
}

/// Reads the XML into a tree, up to the end of `<VTKFile>` or the start of
/// the appended data (which need not be XML).
pub(super) fn parse_tree<'a>(ctx: &Ctx<'a>) -> Result<(Element, Option<Appended<'a>>)> {
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
            Event::Start(_) if stack.len() == MAX_DEPTH => {
                return Err(ctx.at(pos, format!("elements nested more than {MAX_DEPTH} deep")))
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
    // quick-xml's duplicate check is quadratic: a hash set instead.
    let mut seen = HashSet::new();
    for a in e.attributes().with_checks(false) {
        let a = a.map_err(|e| malformed(e.to_string()))?;
        let value = a.unescape_value().map_err(|e| malformed(e.to_string()))?;
        let key = String::from_utf8_lossy(a.key.as_ref()).into_owned();
        if !seen.insert(key.clone()) {
            return Err(malformed(format!("duplicated attribute {key}")));
        }
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
