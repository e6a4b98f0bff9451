//! VTU files of a small mesh: every array in any encoding (ascii, inline
//! binary, appended raw or base64; zlib blocks of any size; UInt32 or UInt64
//! headers; either byte order; any number type), with fuzzed point, cell and
//! component counts, lying block headers and offsets, group names, unknown
//! and nested elements, a second piece, real zlib bombs.

use std::io::Write;

use arbitrary::Arbitrary;
use base64::engine::general_purpose::STANDARD;
use base64::Engine;

use super::{Base, Count, Name};

/// A VTU file, described.
#[derive(Arbitrary, Debug)]
pub struct VtuFile {
    base: Base,
    header64: bool,
    big_endian: bool,
    zlib: bool,
    appended_base64: bool,
    points: Count,
    cells: Count,
    /// The arrays' encodings, used in turn.
    encodings: Vec<Encoding>,
    extras: Vec<Extra>,
    /// Unknown elements around the content of `<FieldData>`.
    depth: u8,
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Format {
    Ascii,
    Binary,
    Appended,
}

#[derive(Arbitrary, Debug, Clone)]
struct Encoding {
    format: Format,
    ty: u8,
    components: Count,
    /// zlib block size less 1; odd: header and data encoded together.
    block: u8,
    lie: Option<Lie>,
}

/// Header words (and an offset) stated instead of the true ones.
#[derive(Arbitrary, Debug, Clone)]
struct Lie {
    blocks: Count,
    full: Count,
    last: Count,
    sizes: Vec<Count>,
    offset: Count,
}

#[derive(Arbitrary, Debug)]
enum Extra {
    PointField(Name),
    CellField(Name),
    GroupName {
        name: Name,
        id: Count,
        dim: u8,
        tag: Option<i32>,
    },
    Unknown {
        name: Name,
        attrs: u8,
        nested: u8,
    },
    /// Zeros (KiB) in 64 KiB zlib blocks, the block size stated as `claim`.
    Bomb {
        section: u8,
        kib: u16,
        claim: Count,
    },
    SecondPiece,
    RepeatedAttribute,
}

enum Values {
    Int(Vec<i64>),
    Float(Vec<f64>),
}

const TYPES: [&str; 10] = [
    "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64", "Float32", "Float64",
];

/// Text safe in an attribute value.
fn escaped(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('"', "&quot;")
}

struct Writer<'f> {
    file: &'f VtuFile,
    next: usize,
    appended: Vec<u8>,
}

impl Writer<'_> {
    fn encoding(&mut self) -> Encoding {
        let e = self
            .file
            .encodings
            .get(self.next % self.file.encodings.len().max(1));
        self.next += 1;
        e.cloned().unwrap_or(Encoding {
            format: Format::Ascii,
            ty: 9,
            components: Count::True,
            block: 0,
            lie: None,
        })
    }

    /// Header words as bytes.
    fn words(&self, words: &[u64]) -> Vec<u8> {
        let (h64, be) = (self.file.header64, self.file.big_endian);
        let mut out = Vec::new();
        for &w in words {
            match (h64, be) {
                (true, false) => out.extend(w.to_le_bytes()),
                (true, true) => out.extend(w.to_be_bytes()),
                (false, false) => out.extend((w as u32).to_le_bytes()),
                (false, true) => out.extend((w as u32).to_be_bytes()),
            }
        }
        out
    }

    /// The binary block (header, then data) of `data`.
    fn block(&self, data: &[u8], e: &Encoding) -> (Vec<u8>, Vec<u8>) {
        let lie = e.lie.as_ref();
        if !self.file.zlib {
            let n = lie.map_or(data.len() as u64, |l| l.blocks.of(data.len()));
            return (self.words(&[n]), data.to_vec());
        }
        // At most 16 blocks (a compressor costs some hundred kilobytes).
        let size = (1 + usize::from(e.block)).max(data.len().div_ceil(16));
        let chunks: Vec<Vec<u8>> = data.chunks(size).map(zlib).collect();
        let last = data.len() - size * chunks.len().saturating_sub(1);
        let mut words = vec![chunks.len() as u64, size as u64, last as u64];
        words.extend(chunks.iter().map(|c| c.len() as u64));
        if let Some(l) = lie {
            words[0] = l.blocks.of(chunks.len());
            words[1] = l.full.of(size);
            words[2] = l.last.of(last);
            for (w, c) in words[3..].iter_mut().zip(&l.sizes) {
                *w = c.of(*w as usize);
            }
        }
        (self.words(&words), chunks.concat())
    }

    /// A `<DataArray>` holding `values`, `components` a tuple.
    fn array(&mut self, name: &str, values: &Values, components: usize) -> String {
        let e = self.encoding();
        let any = e.ty >= 200;
        let ty = match values {
            Values::Float(_) if !any => 8 + usize::from(e.ty % 2),
            Values::Int(_) if !any => usize::from(e.ty % 8),
            _ => usize::from(e.ty % 10),
        };
        let be = self.file.big_endian;
        let mut data = Vec::new();
        let mut text = String::new();
        let count = match values {
            Values::Int(v) => v.len(),
            Values::Float(v) => v.len(),
        };
        for k in 0..count {
            let (i, f) = match values {
                Values::Int(v) => (v[k], v[k] as f64),
                Values::Float(v) => (v[k] as i64, v[k]),
            };
            macro_rules! put {
                ($v:expr) => {{
                    let v = $v;
                    text += &format!("{v} ");
                    data.extend(if be { v.to_be_bytes() } else { v.to_le_bytes() });
                }};
            }
            match ty {
                0 => put!(i as i8),
                1 => put!(i as u8),
                2 => put!(i as i16),
                3 => put!(i as u16),
                4 => put!(i as i32),
                5 => put!(i as u32),
                6 => put!(i),
                7 => put!(i as u64),
                8 => put!(f as f32),
                _ => put!(f),
            }
        }
        let head = format!(
            r#"<DataArray type="{}" Name="{}" NumberOfComponents="{}""#,
            TYPES[ty],
            escaped(name),
            e.components.text(components)
        );
        let (header, body) = match e.format {
            Format::Ascii => return format!(r#"{head} format="ascii">{text}</DataArray>"#),
            _ => self.block(&data, &e),
        };
        if let Format::Binary = e.format {
            let encoded = if e.block % 2 == 1 {
                STANDARD.encode([header, body].concat())
            } else {
                STANDARD.encode(header) + &STANDARD.encode(body)
            };
            return format!(r#"{head} format="binary">{encoded}</DataArray>"#);
        }
        let offset = e.lie.as_ref().map_or(self.appended.len() as u64, |l| {
            l.offset.of(self.appended.len())
        });
        let bytes = [header, body].concat();
        if self.file.appended_base64 {
            self.appended.extend(STANDARD.encode(bytes).bytes());
        } else {
            self.appended.extend(bytes);
        }
        format!(r#"{head} format="appended" offset="{offset}"/>"#)
    }
}

/// The zlib stream of `data`.
fn zlib(data: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(data).expect("in memory");
    e.finish().expect("in memory")
}

impl VtuFile {
    /// The file's bytes (empty when the grid cannot be made).
    pub fn bytes(&self) -> Vec<u8> {
        let Some(mesh) = self.base.mesh() else {
            return Vec::new();
        };
        let mut w = Writer {
            file: self,
            next: 0,
            appended: Vec::new(),
        };
        let n = mesh.node_count();
        let xyz: Vec<f64> = (0..n)
            .flat_map(|i| {
                let p = mesh.point(i);
                [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
            })
            .collect();
        let (mut conn, mut offsets, mut types, mut group) = (vec![], vec![], vec![], vec![]);
        let facets = mesh
            .groups
            .iter()
            .enumerate()
            .flat_map(|(g, grp)| grp.facets.iter().map(move |(k, c)| (g as i64 + 1, k, c)));
        for (g, kind, nodes) in mesh.cells.iter().map(|(k, c)| (0, k, c)).chain(facets) {
            conn.extend((0..nodes.len()).map(|k| nodes[kind.vtk_local(k)] as i64));
            offsets.push(conn.len() as i64);
            types.push(i64::from(kind.vtk_id()));
            group.push(g);
        }
        let total = types.len();
        let points = w.array("Points", &Values::Float(xyz.clone()), 3);
        let cells = [
            w.array("connectivity", &Values::Int(conn), 1),
            w.array("offsets", &Values::Int(offsets), 1),
            w.array("types", &Values::Int(types), 1),
        ]
        .concat();
        let mut cell_data = w.array("group", &Values::Int(group), 1);
        let mut field = String::new();
        for (g, grp) in mesh.groups.iter().enumerate() {
            let dim = mesh.dim as i64 - 1;
            field += &w.array(&grp.name, &Values::Int(vec![g as i64 + 1, dim]), 1);
        }
        let (mut point_data, mut extra_piece, mut repeated) = (String::new(), "", "");
        for extra in &self.extras {
            match extra {
                Extra::PointField(name) => {
                    let x = xyz.iter().step_by(3).copied().collect();
                    point_data += &w.array(&name.text(), &Values::Float(x), 1);
                }
                Extra::CellField(name) => {
                    let v = (0..total).map(|c| c as f64 * 0.5).collect();
                    cell_data += &w.array(&name.text(), &Values::Float(v), 1);
                }
                Extra::GroupName { name, id, dim, tag } => {
                    let mut v = vec![id.of(1) as i64, i64::from(*dim % 4)];
                    v.extend(tag.map(i64::from));
                    field += &w.array(&name.text(), &Values::Int(v), 1);
                }
                Extra::Unknown {
                    name,
                    attrs,
                    nested,
                } => {
                    let a: String = (0..*attrs).map(|k| format!(" a{k}=\"{k}\"")).collect();
                    let tag = format!(
                        "x{}",
                        escaped(&name.text()).replace(['&', ';', ' ', '"', '%', '='], "")
                    );
                    let depth = usize::from(*nested % 80);
                    field += &format!(
                        "<{tag}{a}>{}{}</{tag}>",
                        "<y>".repeat(depth),
                        "</y>".repeat(depth)
                    );
                }
                Extra::Bomb {
                    section,
                    kib,
                    claim,
                } => {
                    let z = zlib(&[0; 1 << 16]);
                    let blocks = usize::from(*kib).div_ceil(64).max(1);
                    let mut words = vec![blocks as u64, claim.of(1 << 16), 1 << 16];
                    words.extend(std::iter::repeat_n(z.len() as u64, blocks));
                    let bytes = [w.words(&words), z.repeat(blocks)].concat();
                    let array = format!(
                        r#"<DataArray type="Float64" Name="bomb" format="binary">{}</DataArray>"#,
                        STANDARD.encode(bytes)
                    );
                    match section % 3 {
                        0 => field += &array,
                        1 => point_data += &array,
                        _ => cell_data += &array,
                    }
                }
                Extra::SecondPiece => {
                    extra_piece = "<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\"/>"
                }
                Extra::RepeatedAttribute => repeated = " type=\"UnstructuredGrid\"",
            }
        }
        let depth = usize::from(self.depth % 80);
        let mut out = format!(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"{repeated} version=\"1.0\" \
             byte_order=\"{}\" header_type=\"{}\"{}>\n<UnstructuredGrid>\n<FieldData>{}{field}{}</FieldData>\n\
             <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n<Points>{points}</Points>\n\
             <Cells>{cells}</Cells>\n<PointData>{point_data}</PointData>\n\
             <CellData>{cell_data}</CellData>\n</Piece>{extra_piece}\n</UnstructuredGrid>\n",
            if self.big_endian { "BigEndian" } else { "LittleEndian" },
            if self.header64 { "UInt64" } else { "UInt32" },
            if self.zlib { " compressor=\"vtkZLibDataCompressor\"" } else { "" },
            "<z>".repeat(depth),
            "</z>".repeat(depth),
            self.points.text(n),
            self.cells.text(total),
        )
        .into_bytes();
        if !w.appended.is_empty() {
            let encoding = if self.appended_base64 {
                "base64"
            } else {
                "raw"
            };
            out.extend(format!("<AppendedData encoding=\"{encoding}\">\n_").bytes());
            out.extend(&w.appended);
            out.extend(b"\n</AppendedData>\n");
        }
        out.extend(b"</VTKFile>\n");
        out
    }
}
