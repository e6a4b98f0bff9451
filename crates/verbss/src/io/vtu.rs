//! VTK XML unstructured grids (`.vtu`).
//!
//! # What verbss writes
//!
//! One `<Piece>` of an `UnstructuredGrid`, `version="1.0"`, little endian,
//! `header_type="UInt64"`, every array `format="binary"`: base64 of the 8-byte
//! byte count, then base64 of the data (the two encoded one after the other,
//! as VTK itself does), no compression. ParaView, VTK and meshio read this.
//!
//! - `Points`: `Float64`, always 3 components (a 2D mesh gets `z = 0`), so
//!   coordinates survive a round trip bit for bit.
//! - `Cells`: `connectivity` and `offsets` as `Int64`, `types` as `UInt8` with
//!   the VTK numbers 1 vertex, 3 line, 5 triangle, 9 quad, 10 tetra,
//!   12 hexahedron, 13 wedge, 14 pyramid. The volume cells come first in mesh
//!   order, then the facets of group 0, group 1, … in group order. VTK
//!   numbers a wedge's two triangles the other way round from the mesh (and
//!   Gmsh): nodes `0 1 2 3 4 5` of a mesh wedge are written `0 2 1 3 5 4`, and
//!   read back the same way, as meshio does.
//! - Groups (VTU has none): the `Int32` cell-data array `group` is 0 on volume
//!   cells and `k + 1` on the facets of group `k`; `<FieldData>` holds one
//!   `Int32` array per group, named after the group, with the values
//!   `k + 1, facet dimension` and, if the group has a Gmsh physical tag, the
//!   tag as a third value. This is meshio's own `field_data` convention
//!   (`name → [id, dim]`), so meshio reads the names back in `field_data`
//!   (it cannot read `String` arrays, hence no `String` array).
//! - Numbering: the point-data array `node_tag` and the cell-data array
//!   `cell_tag` (`Int64`, 0 on facets) keep the mesh's node and cell tags.
//! - [`Fields`]: `Float64` point data and cell data; a cell field has one row
//!   per volume cell and is padded with NaN on the facet rows.
//!
//! # What verbss reads
//!
//! Its own files and those of ParaView/VTK and meshio: `ascii`, inline
//! `binary` (base64, `UInt32` or `UInt64` headers, each part encoded on its
//! own or all together, zlib-compressed or not) and `appended` data (`raw` or
//! `base64`), either byte order, any integer or float type. The dimension is 2
//! when every `z` is 0 and no cell is 3D, else 3; the cells of that dimension
//! become the volume cells, in file order. The lower-dimensional cells become
//! group facets: by the `group` array and the `<FieldData>` names above when
//! present; facets without a named group go to a group called `boundary`.
//! Every other point/cell data array is returned in [`Fields`] (cell data
//! restricted to the volume cells).
//!
//! # Why hand-written
//!
//! The format is small, and the parser must name the line or byte offset of
//! every fault and never allocate from a count that a header merely claims.
//! `vtkio` 0.7 is a release candidate whose errors carry no position and which
//! builds its own model that would have to be converted again; so `quick-xml`
//! tokenises the XML, `base64` and `flate2` decode the binary arrays, and this
//! module does the rest.

use std::borrow::Cow;
use std::io::{Read, Write};
use std::path::Path;

use base64::engine::general_purpose::{GeneralPurpose, GeneralPurposeConfig, STANDARD};
use base64::engine::DecodePaddingMode;
use base64::Engine;
use quick_xml::errors::SyntaxError;
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells, Group, Mesh};

/// Name of the cell-data array that maps cells to groups.
const GROUP_ARRAY: &str = "group";
/// Name of the cell-data array with the cell tags.
const CELL_TAG_ARRAY: &str = "cell_tag";
/// Name of the point-data array with the node tags.
const NODE_TAG_ARRAY: &str = "node_tag";
/// Name of the group that collects facets without a named group.
const UNNAMED_GROUP: &str = "boundary";

/// Point and cell data written beside the mesh.
///
/// Values are tuple-major: the `components` values of node (or cell) `i` are
/// `values[components*i .. components*(i+1)]`, as in VTK.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fields {
    /// Point data: name, components per node, values (`components × nodes`).
    pub point: Vec<(String, usize, Vec<f64>)>,
    /// Cell data: name, components per cell, values (`components × cells`),
    /// one row per volume cell.
    pub cell: Vec<(String, usize, Vec<f64>)>,
}

/// A `.vtu` file read back: the mesh and its fields.
#[derive(Debug, Clone, PartialEq)]
pub struct VtuData {
    /// The mesh.
    pub mesh: Mesh,
    /// Its point and cell data.
    pub fields: Fields,
}

/// The VTK cell-type number of a kind.
fn vtk_type(kind: CellKind) -> u8 {
    match kind {
        CellKind::Vertex => 1,
        CellKind::Line => 3,
        CellKind::Triangle => 5,
        CellKind::Quad => 9,
        CellKind::Tetra => 10,
        CellKind::Hexahedron => 12,
        CellKind::Wedge => 13,
        CellKind::Pyramid => 14,
    }
}

/// VTK numbers a wedge's triangles the other way round (its triangle 0-1-2
/// faces away from 3-4-5, the mesh's faces towards it): local node `i` of a
/// VTK cell is local node `vtk_local(kind, i)` of the mesh's cell, and back.
fn vtk_local(kind: CellKind, i: usize) -> usize {
    const WEDGE: [usize; 6] = [0, 2, 1, 3, 5, 4];
    if kind == CellKind::Wedge {
        WEDGE[i]
    } else {
        i
    }
}

/// The kind with VTK cell-type number `t`, if verbss supports it.
fn kind_of_vtk(t: i64) -> Option<CellKind> {
    CellKind::ALL
        .into_iter()
        .find(|&k| i64::from(vtk_type(k)) == t)
}

// ---------------------------------------------------------------- writing

/// Reads a `.vtu` file.
pub fn read(path: &Path) -> Result<VtuData> {
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse(&bytes, path)
}

/// Writes `mesh` and `fields` to `path` atomically (see [`crate::io::write_atomic`]).
pub fn write(path: &Path, mesh: &Mesh, fields: &Fields) -> Result<()> {
    crate::io::write_atomic(path, |w| write_to(w, mesh, fields))
}

/// Writes `mesh` and `fields` as a `.vtu` file (layout in the module doc).
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] if a field has the wrong
/// length (`components × nodes` or `components × volume cells`), no
/// component, a duplicate name, or one of the reserved names `node_tag`
/// (point data), `group` or `cell_tag` (cell data).
pub fn write_to(w: &mut dyn Write, mesh: &Mesh, fields: &Fields) -> std::io::Result<()> {
    check_fields(mesh, fields)?;
    let n = mesh.node_count();
    let volume = mesh.cell_count();
    let facets: Vec<(i32, CellKind, &[usize])> = mesh
        .groups
        .iter()
        .zip(1..)
        .flat_map(|(g, id)| g.facets.iter().map(move |(kind, nodes)| (id, kind, nodes)))
        .collect();
    let total = volume + facets.len();
    let all_cells = || {
        mesh.cells
            .iter()
            .chain(facets.iter().map(|&(_, kind, nodes)| (kind, nodes)))
    };
    let connectivity = all_cells().map(|(_, nodes)| nodes.len()).sum();

    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    write_group_names(w, mesh)?;
    writeln!(
        w,
        r#"    <Piece NumberOfPoints="{n}" NumberOfCells="{total}">"#
    )?;
    writeln!(w, "      <Points>")?;
    let z = |i: usize| if mesh.dim == 3 { mesh.point(i)[2] } else { 0.0 };
    let points = (0..n).flat_map(|i| [mesh.point(i)[0], mesh.point(i)[1], z(i)]);
    data_array(w, "Points", 3, 3 * n, points)?;
    writeln!(w, "      </Points>")?;

    writeln!(w, "      <Cells>")?;
    let nodes = all_cells()
        .flat_map(|(kind, nodes)| (0..nodes.len()).map(move |i| nodes[vtk_local(kind, i)] as i64));
    data_array(w, "connectivity", 1, connectivity, nodes)?;
    let ends = all_cells().scan(0i64, |end, (_, nodes)| {
        *end += nodes.len() as i64;
        Some(*end)
    });
    data_array(w, "offsets", 1, total, ends)?;
    data_array(w, "types", 1, total, all_cells().map(|(k, _)| vtk_type(k)))?;
    writeln!(w, "      </Cells>")?;

    writeln!(w, "      <PointData>")?;
    let node_tags = mesh.node_tags.iter().map(|&t| t as i64);
    data_array(w, NODE_TAG_ARRAY, 1, n, node_tags)?;
    for (name, comps, values) in &fields.point {
        data_array(w, name, *comps, values.len(), values.iter().copied())?;
    }
    writeln!(w, "      </PointData>")?;

    writeln!(w, "      <CellData>")?;
    let groups = std::iter::repeat_n(0, volume).chain(facets.iter().map(|f| f.0));
    data_array(w, GROUP_ARRAY, 1, total, groups)?;
    let tags = mesh.cell_tags.iter().map(|&t| t as i64);
    let tags = tags.chain(std::iter::repeat_n(0, facets.len()));
    data_array(w, CELL_TAG_ARRAY, 1, total, tags)?;
    for (name, comps, values) in &fields.cell {
        let pad = std::iter::repeat_n(f64::NAN, comps * facets.len());
        let values = values.iter().copied().chain(pad);
        data_array(w, name, *comps, comps * total, values)?;
    }
    writeln!(w, "      </CellData>")?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "</VTKFile>")
}

/// Rejects fields that do not fit the mesh (see [`write_to`]).
fn check_fields(mesh: &Mesh, fields: &Fields) -> std::io::Result<()> {
    let lists = [
        (
            "point",
            &fields.point,
            mesh.node_count(),
            &[NODE_TAG_ARRAY][..],
        ),
        (
            "cell",
            &fields.cell,
            mesh.cell_count(),
            &[GROUP_ARRAY, CELL_TAG_ARRAY][..],
        ),
    ];
    for (what, list, count, reserved) in lists {
        for (i, (name, comps, values)) in list.iter().enumerate() {
            let message = if reserved.contains(&name.as_str()) {
                format!("{what} field name '{name}' is reserved")
            } else if list[..i].iter().any(|f| &f.0 == name) {
                format!("{what} field '{name}' is given twice")
            } else if *comps == 0 || values.len() != comps * count {
                format!(
                    "{what} field '{name}' has {} values (expected {comps} × {count})",
                    values.len()
                )
            } else {
                continue;
            };
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                message,
            ));
        }
    }
    Ok(())
}

/// Writes `<FieldData>` with one `Int32` array `[k + 1, dim, (tag)]` per group.
fn write_group_names(w: &mut dyn Write, mesh: &Mesh) -> std::io::Result<()> {
    if mesh.groups.is_empty() {
        return Ok(());
    }
    writeln!(w, "    <FieldData>")?;
    for (k, g) in mesh.groups.iter().enumerate() {
        let dim = g.facets.kinds.iter().map(|k| k.dim()).max();
        let mut values = vec![k as i64 + 1, dim.unwrap_or(mesh.dim - 1) as i64];
        values.extend(g.tag.map(i64::from));
        let text: Vec<String> = values.iter().map(i64::to_string).collect();
        writeln!(
            w,
            r#"      <DataArray type="Int32" Name="{}" NumberOfTuples="{}" format="ascii">{}</DataArray>"#,
            quick_xml::escape::escape(g.name.as_str()),
            values.len(),
            text.join(" ")
        )?;
    }
    writeln!(w, "    </FieldData>")
}

/// A number type that [`data_array`] writes.
trait Scalar: Copy {
    /// The VTK type name.
    const VTK: &'static str;
    /// Size in bytes.
    const SIZE: usize;
    /// Appends the little-endian bytes.
    fn put(self, out: &mut Vec<u8>);
}

macro_rules! scalar {
    ($t:ty, $name:literal) => {
        impl Scalar for $t {
            const VTK: &'static str = $name;
            const SIZE: usize = std::mem::size_of::<$t>();
            fn put(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    };
}
scalar!(u8, "UInt8");
scalar!(i32, "Int32");
scalar!(i64, "Int64");
scalar!(f64, "Float64");

/// Writes one binary `<DataArray>` of `count` values: base64 of the `UInt64`
/// byte count, then base64 of the values, streamed.
fn data_array<T: Scalar>(
    w: &mut dyn Write,
    name: &str,
    components: usize,
    count: usize,
    values: impl Iterator<Item = T>,
) -> std::io::Result<()> {
    const CHUNK: usize = 1 << 16;
    let comps = if components == 1 {
        String::new()
    } else {
        format!(r#" NumberOfComponents="{components}""#)
    };
    write!(
        w,
        r#"        <DataArray type="{}" Name="{}"{comps} format="binary">"#,
        T::VTK,
        quick_xml::escape::escape(name)
    )?;
    let bytes = (count * T::SIZE) as u64;
    w.write_all(STANDARD.encode(bytes.to_le_bytes()).as_bytes())?;
    let mut written = 0;
    {
        let mut encoder = base64::write::EncoderWriter::new(&mut *w, &STANDARD);
        let mut buf = Vec::with_capacity(CHUNK + 8);
        for v in values {
            v.put(&mut buf);
            written += 1;
            if buf.len() >= CHUNK {
                encoder.write_all(&buf)?;
                buf.clear();
            }
        }
        encoder.write_all(&buf)?;
        encoder.finish()?;
    }
    debug_assert_eq!(written, count, "DataArray '{name}'");
    writeln!(w, "</DataArray>")
}

// ---------------------------------------------------------------- reading

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
                local[vtk_local(kind, k)] = match usize::try_from(i) {
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

#[cfg(test)]
mod tests {
    use super::*;

    const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/vtu/");

    fn cells(list: &[(CellKind, &[usize])]) -> Cells {
        let mut cells = Cells::new();
        for (kind, nodes) in list {
            cells.push(*kind, nodes);
        }
        cells
    }

    fn group(name: &str, tag: Option<i32>, facets: &[(CellKind, &[usize])]) -> Group {
        Group {
            name: name.into(),
            tag,
            facets: cells(facets),
        }
    }

    /// Two triangles and a quad on [0,2]×[0,1] scaled by 0.1, as in
    /// scripts/make_vtu_fixtures.py.
    fn mesh_2d(scale: f64) -> Mesh {
        let coords = [0., 0., 1., 0., 2., 0., 0., 1., 1., 1., 2., 1.];
        let cells = cells(&[
            (CellKind::Triangle, &[1, 2, 5]),
            (CellKind::Triangle, &[1, 5, 4]),
            (CellKind::Quad, &[0, 1, 4, 3]),
        ]);
        let coords = coords.iter().map(|x| x * scale).collect();
        Mesh::new(2, coords, cells, Vec::new()).unwrap()
    }

    /// A hexahedron, a wedge, a pyramid and a tetrahedron, as in
    /// scripts/make_vtu_fixtures.py.
    fn mesh_3d(scale: f64) -> Mesh {
        let coords = [
            0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 0., 0., 1., 1., 0., 1., 1., 1., 1., 0.,
            1., 1., 2., 0., 0., 2., 0., 1., 0.5, 0.5, 1.5, 1.5, 0.25, 1.5,
        ];
        let cells = cells(&[
            (CellKind::Hexahedron, &[0, 1, 2, 3, 4, 5, 6, 7]),
            (CellKind::Wedge, &[1, 8, 2, 5, 9, 6]),
            (CellKind::Pyramid, &[4, 5, 6, 7, 10]),
            (CellKind::Tetra, &[5, 9, 6, 11]),
        ]);
        let coords = coords.iter().map(|x| x * scale).collect();
        Mesh::new(3, coords, cells, Vec::new()).unwrap()
    }

    fn round_trip(mesh: &Mesh, fields: &Fields) -> VtuData {
        let mut bytes = Vec::new();
        write_to(&mut bytes, mesh, fields).unwrap();
        parse(&bytes, Path::new("t.vtu")).unwrap()
    }

    #[test]
    fn round_trip_2d_keeps_mesh_groups_tags_and_fields() {
        let mut mesh = mesh_2d(0.1);
        mesh.node_tags = vec![10, 20, 30, 40, 50, 60];
        mesh.cell_tags = vec![7, 9, 8];
        mesh.groups = vec![
            group(
                "bottom",
                Some(3),
                &[(CellKind::Line, &[0, 1]), (CellKind::Line, &[1, 2])],
            ),
            group(
                "top <&\"'>",
                None,
                &[(CellKind::Line, &[5, 4]), (CellKind::Line, &[4, 3])],
            ),
            group("corner", None, &[(CellKind::Vertex, &[0])]),
        ];
        mesh.validate().unwrap();
        let u: Vec<f64> = (0..12).map(|i| f64::from(i) / 7.0).collect();
        let fields = Fields {
            point: vec![("u".into(), 2, u)],
            cell: vec![("rho".into(), 1, vec![1.0 / 3.0, -2.5, 1e-300])],
        };
        let back = round_trip(&mesh, &fields);
        assert_eq!(back.mesh, mesh);
        assert_eq!(back.fields, fields);
    }

    #[test]
    fn round_trip_3d_keeps_every_volume_kind() {
        let mut mesh = mesh_3d(1.0 / 3.0);
        mesh.groups = vec![
            group(
                "floor",
                Some(5),
                &[
                    (CellKind::Quad, &[0, 3, 2, 1]),
                    (CellKind::Triangle, &[1, 2, 8]),
                ],
            ),
            group("apex", None, &[(CellKind::Vertex, &[10])]),
            group("empty", Some(-4), &[]),
            group("edge", None, &[(CellKind::Line, &[0, 1])]),
        ];
        mesh.validate().unwrap();
        let v: Vec<f64> = (0..36).map(|i| (f64::from(i) * 0.37).sin()).collect();
        let fields = Fields {
            point: vec![("v".into(), 3, v), ("phi".into(), 1, vec![0.5; 12])],
            cell: vec![("q".into(), 2, vec![1., 2., 3., 4., 5., 6., 7., 8.])],
        };
        let back = round_trip(&mesh, &fields);
        assert_eq!(back.mesh, mesh);
        assert_eq!(back.fields, fields);
    }

    #[test]
    fn written_file_has_the_documented_layout() {
        let mut mesh = mesh_2d(1.0);
        mesh.groups = vec![group("wall", Some(2), &[(CellKind::Line, &[0, 1])])];
        let mut bytes = Vec::new();
        write_to(&mut bytes, &mesh, &Fields::default()).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.contains(r#"header_type="UInt64""#));
        assert!(text.contains(
            r#"<DataArray type="Int32" Name="wall" NumberOfTuples="3" format="ascii">1 1 2</DataArray>"#
        ));
        assert!(text.contains(r#"<Piece NumberOfPoints="6" NumberOfCells="4">"#));
        // types: 5 5 9 3 as UInt8 after an 8-byte count of 4.
        let types = STANDARD.encode(4u64.to_le_bytes()) + &STANDARD.encode([5u8, 5, 9, 3]);
        assert!(text.contains(&format!(r#"Name="types" format="binary">{types}<"#)));
    }

    #[test]
    fn writer_rejects_fields_that_do_not_fit() {
        let mesh = mesh_2d(1.0);
        let err = |fields: Fields| {
            write_to(&mut Vec::new(), &mesh, &fields)
                .unwrap_err()
                .to_string()
        };
        let point = |name: &str, c, n| Fields {
            point: vec![(name.to_string(), c, vec![0.0; n])],
            cell: Vec::new(),
        };
        assert_eq!(
            err(point("u", 2, 6)),
            "point field 'u' has 6 values (expected 2 × 6)"
        );
        assert_eq!(
            err(point("node_tag", 1, 6)),
            "point field name 'node_tag' is reserved"
        );
        assert_eq!(
            err(Fields {
                point: Vec::new(),
                cell: vec![("group".into(), 1, vec![0.0; 3])],
            }),
            "cell field name 'group' is reserved"
        );
        assert_eq!(
            err(Fields {
                point: Vec::new(),
                cell: vec![("a".into(), 1, vec![0.0; 3]), ("a".into(), 1, vec![0.0; 3])],
            }),
            "cell field 'a' is given twice"
        );
    }

    #[test]
    fn reads_meshio_zlib_file() {
        let data = read(Path::new(&format!("{FIXTURES}meshio_2d_zlib.vtu"))).unwrap();
        let mut expected = mesh_2d(1.0);
        expected.groups = vec![group(
            "boundary",
            None,
            &[
                (CellKind::Line, &[0, 1]),
                (CellKind::Line, &[1, 2]),
                (CellKind::Line, &[5, 4]),
                (CellKind::Line, &[4, 3]),
            ],
        )];
        assert_eq!(data.mesh, expected);
        let u = expected.coords.iter().map(|x| x * 0.5).collect();
        let fields = Fields {
            point: vec![("u".into(), 2, u)],
            cell: vec![("pressure".into(), 1, vec![1.5, 2.5, 3.5])],
        };
        assert_eq!(data.fields, fields);
    }

    #[test]
    fn reads_meshio_ascii_and_uint64_header_files() {
        let mut expected = mesh_3d(1.0);
        expected.groups = vec![group(
            "boundary",
            None,
            &[
                (CellKind::Quad, &[0, 3, 2, 1]),
                (CellKind::Triangle, &[1, 2, 8]),
            ],
        )];
        for name in ["meshio_3d_ascii.vtu", "meshio_3d_raw64.vtu"] {
            let data = read(Path::new(&format!("{FIXTURES}{name}"))).unwrap();
            assert_eq!(data.mesh, expected, "{name}");
            assert_eq!(data.fields, Fields::default(), "{name}");
        }
    }

    /// The 2D test mesh with appended data: `encoding` raw or base64,
    /// optionally zlib-compressed in 16-byte blocks, in either byte order.
    fn appended_file(base64: bool, zlib: bool, big: bool) -> Vec<u8> {
        let mesh = mesh_2d(0.1);
        let to = |v: &[u8]| {
            if big {
                v.iter().rev().copied().collect()
            } else {
                v.to_vec()
            }
        };
        let points: Vec<u8> = (0..6)
            .flat_map(|i| [mesh.point(i)[0], mesh.point(i)[1], 0.0])
            .flat_map(|x| to(&x.to_le_bytes()))
            .collect();
        let ints = |v: &[i32]| -> Vec<u8> { v.iter().flat_map(|x| to(&x.to_le_bytes())).collect() };
        let arrays = [
            ("Float64", "Points", points),
            (
                "Int32",
                "connectivity",
                ints(&[1, 2, 5, 1, 5, 4, 0, 1, 4, 3]),
            ),
            ("Int32", "offsets", ints(&[3, 6, 10])),
            ("UInt8", "types", vec![5, 5, 9]),
        ];
        let word = |x: usize| to(&(x as u32).to_le_bytes());
        let mut data = Vec::new();
        let mut tags = Vec::new();
        for (ty, name, payload) in arrays {
            let comps = if name == "Points" {
                r#" NumberOfComponents="3""#
            } else {
                ""
            };
            tags.push(format!(
                r#"<DataArray type="{ty}" Name="{name}"{comps} format="appended" offset="{}"/>"#,
                data.len()
            ));
            let (header, body) = if zlib {
                let blocks: Vec<Vec<u8>> = payload
                    .chunks(16)
                    .map(|b| {
                        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), Default::default());
                        z.write_all(b).unwrap();
                        z.finish().unwrap()
                    })
                    .collect();
                let last = payload.len() % 16;
                let mut h = [word(blocks.len()), word(16), word(last)].concat();
                h.extend(blocks.iter().flat_map(|b| word(b.len())));
                (h, blocks.concat())
            } else {
                (word(payload.len()), payload)
            };
            if base64 {
                data.extend(STANDARD.encode(header).bytes());
                data.extend(STANDARD.encode(body).bytes());
            } else {
                data.extend(header);
                data.extend(body);
            }
        }
        let order = if big { "BigEndian" } else { "LittleEndian" };
        let compressor = if zlib {
            r#" compressor="vtkZLibDataCompressor""#
        } else {
            ""
        };
        let encoding = if base64 { "base64" } else { "raw" };
        let mut file = format!(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" \
             byte_order=\"{order}\"{compressor}>\n<UnstructuredGrid>\n\
             <Piece NumberOfPoints=\"6\" NumberOfCells=\"3\">\n<Points>\n{}\n</Points>\n\
             <Cells>\n{}\n{}\n{}\n</Cells>\n</Piece>\n</UnstructuredGrid>\n\
             <AppendedData encoding=\"{encoding}\">\n   _",
            tags[0], tags[1], tags[2], tags[3]
        )
        .into_bytes();
        file.extend(data);
        file.extend(b"\n</AppendedData>\n</VTKFile>\n");
        file
    }

    #[test]
    fn reads_appended_raw_and_base64_in_both_byte_orders() {
        for base64 in [false, true] {
            for zlib in [false, true] {
                for big in [false, true] {
                    let file = appended_file(base64, zlib, big);
                    let data = parse(&file, Path::new("a.vtu"))
                        .unwrap_or_else(|e| panic!("{base64} {zlib} {big}: {e}"));
                    assert_eq!(data.mesh, mesh_2d(0.1), "{base64} {zlib} {big}");
                }
            }
        }
    }

    /// A one-triangle ascii file; the tests below break one thing in it.
    const TRI: &str = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0">
<UnstructuredGrid>
<Piece NumberOfPoints="3" NumberOfCells="1">
<Points>
<DataArray type="Float64" Name="Points" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0</DataArray>
</Points>
<Cells>
<DataArray type="Int32" Name="connectivity" format="ascii">0 1 2</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5</DataArray>
</Cells>
</Piece>
</UnstructuredGrid>
</VTKFile>
"#;

    fn error(text: &str) -> String {
        parse(text.as_bytes(), Path::new("x.vtu"))
            .unwrap_err()
            .to_string()
    }

    fn broken(from: &str, to: &str) -> String {
        assert!(TRI.contains(from), "{from}");
        error(&TRI.replacen(from, to, 1))
    }

    #[test]
    fn the_unbroken_triangle_reads() {
        let mesh = parse(TRI.as_bytes(), Path::new("x.vtu")).unwrap().mesh;
        assert_eq!(mesh.dim, 2);
        assert_eq!(mesh.cells, cells(&[(CellKind::Triangle, &[0, 1, 2])]));
        assert!(mesh.groups.is_empty());
    }

    #[test]
    fn error_not_xml() {
        assert_eq!(
            error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"),
            "x.vtu:1: not a VTK XML file (expected <VTKFile type=\"UnstructuredGrid\">)"
        );
        assert_eq!(
            error(""),
            "x.vtu:1: not a VTK XML file (expected <VTKFile type=\"UnstructuredGrid\">)"
        );
        assert_eq!(
            broken("<VTKFile", "<Mesh"),
            "x.vtu:2: not a VTK XML file (expected <VTKFile type=\"UnstructuredGrid\">)"
        );
        assert_eq!(
            broken("UnstructuredGrid\" version", "PolyData\" version"),
            "x.vtu:2: VTKFile type=\"PolyData\" (expected \"UnstructuredGrid\")"
        );
        assert_eq!(
            broken("</Points>", "</Cells>"),
            "x.vtu:7: malformed XML: ill-formed document: expected `</Points>`, but `</Cells>` was found"
        );
    }

    #[test]
    fn error_missing_sections() {
        // TRI without the lines from `from` to `to` (both included).
        let cut = |from: &str, to: &str| {
            let (head, rest) = TRI.split_once(from).unwrap();
            head.to_string() + rest.split_once(to).unwrap().1
        };
        assert_eq!(
            error(&cut("<Piece", "</Piece>\n")),
            "x.vtu:3: missing <Piece> in <UnstructuredGrid>"
        );
        assert_eq!(
            error(&cut("<Points>", "</Points>\n")),
            "x.vtu:4: missing <Points> in <Piece>"
        );
        assert_eq!(
            error(&cut("<Cells>", "</Cells>\n")),
            "x.vtu:4: missing <Cells> in <Piece>"
        );
        assert_eq!(
            broken(r#"Name="offsets""#, r#"Name="offset""#),
            "x.vtu:8: missing DataArray 'offsets' in <Cells>"
        );
        assert_eq!(
            broken("<UnstructuredGrid>", "<Grid>"),
            "x.vtu:14: malformed XML: ill-formed document: expected `</Grid>`, but `</UnstructuredGrid>` was found"
        );
    }

    #[test]
    fn error_counts_that_disagree() {
        assert_eq!(
            broken(r#"NumberOfPoints="3""#, r#"NumberOfPoints="4""#),
            "x.vtu:6: DataArray 'Points': 9 values but NumberOfPoints=4 needs 12"
        );
        assert_eq!(
            broken(r#"NumberOfPoints="3""#, r#"NumberOfPoints="99999999999999""#),
            "x.vtu:6: DataArray 'Points': 9 values but NumberOfPoints=99999999999999 needs 299999999999997"
        );
        assert_eq!(
            broken(r#"NumberOfPoints="3""#, r#"NumberOfPoints="-3""#),
            "x.vtu:4: Piece NumberOfPoints=\"-3\" is not a count"
        );
        assert_eq!(
            broken(">3</DataArray>", ">3 3</DataArray>"),
            "x.vtu:10: DataArray 'offsets': 2 values but NumberOfCells=1"
        );
        assert_eq!(
            broken(">5</DataArray>", ">9</DataArray>"),
            "x.vtu:10: DataArray 'offsets': cell 0 (quad) has 3 nodes (expected 4)"
        );
        assert_eq!(
            broken(">3</DataArray>", ">4</DataArray>"),
            "x.vtu:10: DataArray 'offsets': cell 0 ends at 4, outside 0..=3"
        );
        assert_eq!(
            broken(">0 1 2</DataArray>", ">0 1 2 0</DataArray>"),
            "x.vtu:10: DataArray 'offsets': the last cell ends at 3 but connectivity has 4 values"
        );
        let cell_data = "</Cells>\n<CellData><DataArray type=\"Float64\" Name=\"p\" format=\"ascii\">1 2</DataArray></CellData>";
        assert_eq!(
            broken("</Cells>", cell_data),
            "x.vtu:13: DataArray 'p': 2 values but 1 × NumberOfCells=1 are needed"
        );
    }

    #[test]
    fn error_bad_numbers_and_types() {
        assert_eq!(
            broken("0 0 0 1 0 0", "0 0 0 1 0\n\nx"),
            "x.vtu:8: DataArray 'Points': \"x\" is not a number"
        );
        assert_eq!(
            broken(
                r#"type="Int32" Name="connectivity""#,
                r#"type="Float32" Name="connectivity""#
            ),
            "x.vtu:9: DataArray 'connectivity': expected an integer type"
        );
        assert_eq!(
            broken(r#"type="UInt8""#, r#"type="Char""#),
            "x.vtu:11: DataArray 'types': unknown type \"Char\""
        );
        assert_eq!(
            broken(
                r#"Name="types" format="ascii""#,
                r#"Name="types" format="hex""#
            ),
            "x.vtu:11: DataArray 'types': unknown format \"hex\""
        );
        assert_eq!(
            broken("<VTKFile type", "<VTKFile compressor=\"vtkLZ4DataCompressor\" type"),
            "x.vtu:2: VTKFile compressor=\"vtkLZ4DataCompressor\" (expected vtkZLibDataCompressor or none)"
        );
    }

    #[test]
    fn error_bad_base64() {
        let binary = r#"format="binary">AAAA!AAA</DataArray>"#;
        assert_eq!(
            broken(r#"format="ascii">0 1 2</DataArray>"#, binary),
            "x.vtu:9: DataArray 'connectivity': invalid base64 character '!' at position 4"
        );
        let short = r#"format="binary">DAAAAAAA</DataArray>"#;
        assert_eq!(
            broken(r#"format="ascii">0 1 2</DataArray>"#, short),
            "x.vtu:9: DataArray 'connectivity': truncated: header claims 12 bytes but only 2 remain"
        );
        let cut = r#"format="binary">DAAAAAAAA</DataArray>"#;
        assert_eq!(
            broken(r#"format="ascii">0 1 2</DataArray>"#, cut),
            "x.vtu:9: DataArray 'connectivity': base64 data of 9 characters is cut short"
        );
    }

    #[test]
    fn error_connectivity_out_of_range() {
        assert_eq!(
            broken(">0 1 2<", ">0 1 7<"),
            "x.vtu:9: DataArray 'connectivity': cell 0 uses point 7 but NumberOfPoints=3"
        );
        assert_eq!(
            broken(">0 1 2<", ">0 -1 2<"),
            "x.vtu:9: DataArray 'connectivity': cell 0 uses point -1 but NumberOfPoints=3"
        );
    }

    #[test]
    fn error_unknown_cell_type() {
        assert_eq!(
            broken(">5</DataArray>", ">22</DataArray>"),
            "x.vtu:11: DataArray 'types': cell 0 has unknown VTK type 22 (supported: 1 vertex, \
             3 line, 5 triangle, 9 quad, 10 tetra, 12 hexahedron, 13 wedge, 14 pyramid)"
        );
    }

    #[test]
    fn error_nan_coordinates_and_surface_meshes() {
        assert_eq!(
            broken("0 0 0 1 0 0", "0 0 0 NaN 0 0"),
            "x.vtu:6: DataArray 'Points': point 1 has a non-finite coordinate (NaN)"
        );
        assert_eq!(
            broken("0 0 0 1 0 0", "0 0 1 1 0 0"),
            "x.vtu:4: no 3D cells but point 0 has z = 1 (surface meshes are not supported)"
        );
        assert_eq!(
            broken(">5</DataArray>", ">3</DataArray>"),
            "x.vtu:10: DataArray 'offsets': cell 0 (line) has 3 nodes (expected 2)"
        );
    }

    #[test]
    fn error_truncated_file() {
        let cut = &TRI[..TRI.find("0 1 2</DataArray>").unwrap() + 2];
        assert_eq!(
            error(cut),
            "x.vtu:9: truncated file: end of file inside <DataArray>"
        );
        let cut = &TRI[..TRI.find("<Cells>").unwrap() + 4];
        assert_eq!(
            error(cut),
            "x.vtu:8: truncated file: tag not closed: `>` not found before end of input"
        );
        let file = appended_file(false, false, false);
        let start = file.windows(2).position(|w| w == b" _").unwrap() + 2;
        // Points take 4 + 144 bytes; keep connectivity's header and 2 bytes.
        let cut = &file[..start + 148 + 4 + 2];
        assert_eq!(
            parse(cut, Path::new("x.vtu")).unwrap_err().to_string(),
            format!(
                "x.vtu: byte {}: DataArray 'connectivity': truncated: header claims 40 bytes but only 2 remain",
                start + 4 + 144 + 4
            )
        );
    }

    #[test]
    fn huge_claims_do_not_allocate() {
        let mut file = appended_file(false, true, false);
        let start = file.windows(2).position(|w| w == b" _").unwrap() + 2;
        // The first zlib header claims 2^32 - 1 blocks.
        file[start..start + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        assert_eq!(
            parse(&file, Path::new("x.vtu")).unwrap_err().to_string(),
            format!(
                "x.vtu: byte {}: DataArray 'Points': truncated: header claims 17179869180 bytes but only {} remain",
                start + 12,
                file.len() - start - 12
            )
        );
    }
}
