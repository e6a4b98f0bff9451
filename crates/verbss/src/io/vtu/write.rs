//! The `.vtu` writer (layout in the parent module's doc).

use std::io::Write;

use base64::engine::general_purpose::STANDARD;
use base64::Engine;
use flate2::write::ZlibEncoder;
use flate2::Compression;

use super::{Fields, CELL_TAG_ARRAY, GROUP_ARRAY, NODE_TAG_ARRAY};
use crate::mesh::{CellKind, Mesh};

/// Writes `mesh` and `fields` as a `.vtu` file (layout in the module doc).
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] if a field has the wrong
/// length (`components × nodes` or `components × volume cells`), no
/// component, a duplicate name, or one of the reserved names `node_tag`
/// (point data), `group` or `cell_tag` (cell data); a node or element tag
/// above 2^63 − 1.
pub fn write_to(w: &mut dyn Write, mesh: &Mesh, fields: &Fields) -> std::io::Result<()> {
    write_moved_to(w, mesh, &mesh.coords, fields)
}

/// [`write_to`] with the nodes at `coords` (`dim` numbers per node) instead
/// of the mesh's own: a moved mesh written without a copy of its cells.
pub fn write_moved_to(
    w: &mut dyn Write,
    mesh: &Mesh,
    coords: &[f64],
    fields: &Fields,
) -> std::io::Result<()> {
    check_fields(mesh, fields)?;
    if coords.len() != mesh.coords.len() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "{} coordinates for {} nodes of dimension {}",
                coords.len(),
                mesh.node_count(),
                mesh.dim
            ),
        ));
    }
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
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">"#
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    write_group_names(w, mesh)?;
    writeln!(
        w,
        r#"    <Piece NumberOfPoints="{n}" NumberOfCells="{total}">"#
    )?;
    writeln!(w, "      <Points>")?;
    let dim = mesh.dim;
    let z = |i: usize| if dim == 3 { coords[3 * i + 2] } else { 0.0 };
    let points = (0..n).flat_map(|i| [coords[dim * i], coords[dim * i + 1], z(i)]);
    data_array(w, "Points", 3, 3 * n, points)?;
    writeln!(w, "      </Points>")?;

    writeln!(w, "      <Cells>")?;
    let nodes = all_cells()
        .flat_map(|(kind, nodes)| (0..nodes.len()).map(move |i| nodes[kind.vtk_local(i)] as i64));
    data_array(w, "connectivity", 1, connectivity, nodes)?;
    let ends = all_cells().scan(0i64, |end, (_, nodes)| {
        *end += nodes.len() as i64;
        Some(*end)
    });
    data_array(w, "offsets", 1, total, ends)?;
    data_array(w, "types", 1, total, all_cells().map(|(k, _)| k.vtk_id()))?;
    if !mesh.cells.faces.is_empty() {
        write_faces(w, mesh, total)?;
    }
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

/// The polyhedra's faces as VTK writes them: `faces`, each polyhedron's
/// stream `nFaces, (nPoints, point …) …` (point numbers), and
/// `faceoffsets`, the end of each cell's stream in `faces` (−1 for a cell
/// that is not a polyhedron), `total` cells in all.
fn write_faces(w: &mut dyn Write, mesh: &Mesh, total: usize) -> std::io::Result<()> {
    let mut stream: Vec<i64> = Vec::new();
    let mut ends = vec![-1i64; total];
    for (c, faces) in mesh.cells.faces.iter() {
        let nodes = mesh.cells.cell(c);
        stream.push(faces.len() as i64);
        for face in faces.iter() {
            stream.push(face.len() as i64);
            stream.extend(face.iter().map(|&l| nodes[l] as i64));
        }
        ends[c] = stream.len() as i64;
    }
    data_array(w, "faces", 1, stream.len(), stream.into_iter())?;
    data_array(w, "faceoffsets", 1, total, ends.into_iter())
}

/// Rejects fields that do not fit the mesh (see [`write_to`]).
fn check_fields(mesh: &Mesh, fields: &Fields) -> std::io::Result<()> {
    // Tags are written as Int64: a larger one would not read back.
    for (what, tags) in [("node", &mesh.node_tags), ("element", &mesh.cell_tags)] {
        if let Some(t) = tags.iter().find(|&&t| i64::try_from(t).is_err()) {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("{what} tag {t} is above {} (VTU tags are Int64)", i64::MAX),
            ));
        }
    }
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
    /// Appends the little-endian bytes.
    fn put(self, out: &mut Vec<u8>);
}

macro_rules! scalar {
    ($t:ty, $name:literal) => {
        impl Scalar for $t {
            const VTK: &'static str = $name;
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

/// Bytes of values per zlib block (VTK's own block size).
const BLOCK: usize = 1 << 15;

/// Writes one binary `<DataArray>` of `count` values, zlib-compressed as VTK
/// does: the values' bytes cut into blocks of [`BLOCK`] bytes, each
/// deflated on its own; base64 of the `UInt64` header `[blocks, BLOCK,
/// last block's size, compressed size of each block]`, then base64 of the
/// compressed blocks.
fn data_array<T: Scalar>(
    w: &mut dyn Write,
    name: &str,
    components: usize,
    count: usize,
    values: impl Iterator<Item = T>,
) -> std::io::Result<()> {
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
    let mut compressed: Vec<Vec<u8>> = Vec::new();
    let mut last = 0;
    let mut written = 0;
    let mut buf = Vec::with_capacity(BLOCK + 8);
    // zlib's fastest level: a quarter of the default's time on coordinates
    // and connectivity, for files about 5% larger (BENCHMARKS.md).
    let mut flush = |buf: &mut Vec<u8>, take: usize| -> std::io::Result<()> {
        let mut z = ZlibEncoder::new(Vec::new(), Compression::fast());
        z.write_all(&buf[..take])?;
        compressed.push(z.finish()?);
        last = take;
        buf.drain(..take);
        Ok(())
    };
    for v in values {
        v.put(&mut buf);
        written += 1;
        if buf.len() >= BLOCK {
            flush(&mut buf, BLOCK)?;
        }
    }
    if !buf.is_empty() {
        let take = buf.len();
        flush(&mut buf, take)?;
    }
    debug_assert_eq!(written, count, "DataArray '{name}'");
    let mut header = Vec::with_capacity(8 * (3 + compressed.len()));
    for word in [compressed.len(), BLOCK, last]
        .into_iter()
        .chain(compressed.iter().map(Vec::len))
    {
        header.extend_from_slice(&(word as u64).to_le_bytes());
    }
    w.write_all(STANDARD.encode(&header).as_bytes())?;
    {
        let mut encoder = base64::write::EncoderWriter::new(&mut *w, &STANDARD);
        for block in &compressed {
            encoder.write_all(block)?;
        }
        encoder.finish()?;
    }
    writeln!(w, "</DataArray>")
}
