//! The `.vtu` reader (what it accepts is in the parent module's doc).

use std::cell::Cell;
use std::path::Path;

use super::assemble::assemble;
use super::binary::{decode_base64, inflate_budget, BlockError, Layout, Ty, Values};
use super::xml::{collect_offsets, parse_tree, Appended, Ctx, Element};
use super::VtuData;
use crate::error::Result;
use crate::io::MAX_GROUPS;
use crate::mesh::{CellKind, Cells};

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

/// One decoded `<DataArray>`.
pub(super) struct Array<'e> {
    pub(super) el: &'e Element,
    pub(super) name: String,
    pub(super) components: usize,
    pub(super) values: Values,
}

/// The most values an array may hold: a count, or a count per component.
#[derive(Clone, Copy)]
enum Limit {
    Values(usize),
    Tuples(usize),
}

/// The file-wide settings needed to decode arrays.
pub(super) struct VtkFile<'a, 'c> {
    pub(super) ctx: &'c Ctx<'a>,
    layout: Layout,
    appended: Option<Appended<'a>>,
    /// Sorted `offset`s of the appended arrays (to cut base64 appended data).
    offsets: Vec<usize>,
    /// Bytes the zlib blocks not yet read may still inflate to.
    budget: Cell<u64>,
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
            layout: Layout {
                big_endian,
                header64,
                zlib,
            },
            appended,
            offsets,
            budget: Cell::new(inflate_budget(ctx.bytes.len())),
        })
    }

    /// Decodes a `<DataArray>` that `why` (for messages) limits to `limit`.
    fn array<'e>(&self, el: &'e Element, limit: Limit, why: &str) -> Result<Array<'e>> {
        self.decode(el, limit, why)?.ok_or_else(|| {
            let max = match limit {
                Limit::Values(m) => m.to_string(),
                Limit::Tuples(t) => format!("{t} tuples"),
            };
            self.ctx.at(
                el.pos,
                format!(
                    "DataArray '{}': holds more than the {max} that {why} needs",
                    el.attr("Name").unwrap_or("")
                ),
            )
        })
    }

    /// Decodes a `<DataArray>`; `None`, before any inflating, when its binary
    /// block claims more than `limit` values.
    fn decode<'e>(&self, el: &'e Element, limit: Limit, why: &str) -> Result<Option<Array<'e>>> {
        let name = el.attr("Name").unwrap_or("").to_string();
        let err = |m: String| self.ctx.at(el.pos, format!("DataArray '{name}': {m}"));
        let ty_name = el.attr("type").unwrap_or("");
        let ty = Ty::parse(ty_name).ok_or_else(|| err(format!("unknown type \"{ty_name}\"")))?;
        let components: usize = match el.attr("NumberOfComponents") {
            None | Some("") => 1,
            Some(c) => match c.parse() {
                Ok(c) if c > 0 => c,
                _ => return Err(err(format!("NumberOfComponents=\"{c}\" is not a count"))),
            },
        };
        let max = match limit {
            Limit::Values(m) => m,
            Limit::Tuples(t) => components.checked_mul(t).ok_or_else(|| {
                err(format!(
                    "NumberOfComponents={components} cannot match {why} (too many values)"
                ))
            })?,
        };
        let values = match el.attr("format").unwrap_or("ascii") {
            "ascii" => self.ascii(el, ty, &name, max)?,
            "binary" => {
                let text: Vec<u8> = el
                    .text
                    .iter()
                    .flat_map(|&(s, e)| &self.ctx.bytes[s..e])
                    .copied()
                    .filter(|b| !b.is_ascii_whitespace())
                    .collect();
                let stream = decode_base64(&text).map_err(|(_, m)| err(m))?;
                self.layout
                    .block_values(&stream, ty, max, &self.budget)
                    .map_err(|(_, m)| err(m))?
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
                    let next = self.offsets.partition_point(|&o| o <= offset);
                    let end = self
                        .offsets
                        .get(next)
                        .map_or(app.data.len(), |&o| o.min(app.data.len()));
                    let stream = decode_base64(&app.data[offset..end]).map_err(at)?;
                    self.layout
                        .block_values(&stream, ty, max, &self.budget)
                        .map_err(|(_, m)| at((0, m)))?
                } else {
                    self.layout
                        .block_values(&app.data[offset..], ty, max, &self.budget)
                        .map_err(at)?
                }
            }
            other => return Err(err(format!("unknown format \"{other}\""))),
        };
        Ok(values.map(|values| Array {
            el,
            name,
            components,
            values,
        }))
    }

    /// Parses the whitespace-separated numbers of an ascii array; `None`,
    /// before any parsing, when there are more than `max` (the caller checks
    /// the count). The numbers are counted first and get exactly their room.
    fn ascii(&self, el: &Element, ty: Ty, name: &str, max: usize) -> Result<Option<Values>> {
        let tokens = |&(start, end): &(usize, usize)| {
            self.ctx.bytes[start..end]
                .split(|b| b.is_ascii_whitespace())
                .filter(|t| !t.is_empty())
                .count()
        };
        let count: usize = el.text.iter().map(tokens).sum();
        if count > max {
            return Ok(None);
        }
        let mut values = Values::with_capacity(ty, count)
            .map_err(|(_, m)| self.ctx.at(el.pos, format!("DataArray '{name}': {m}")))?;
        for &(start, end) in &el.text {
            let mut i = start;
            for token in self.ctx.bytes[start..end].split(|b| b.is_ascii_whitespace()) {
                let at = i;
                i += token.len() + 1;
                if token.is_empty() {
                    continue;
                }
                let text = std::str::from_utf8(token).unwrap_or("");
                let ok = match &mut values {
                    Values::Float(v) => text.parse().map(|x| v.push(x)).is_ok(),
                    Values::Int(v) => text.parse().map(|x| v.push(x)).is_ok(),
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
        Ok(Some(values))
    }

    /// The mesh and fields of the file.
    fn build(&self, root: &Element) -> Result<VtuData> {
        let ctx = self.ctx;
        let grid = root
            .child("UnstructuredGrid")
            .ok_or_else(|| ctx.at(root.pos, "missing <UnstructuredGrid> in <VTKFile>".into()))?;
        let piece = grid
            .child("Piece")
            .ok_or_else(|| ctx.at(grid.pos, "missing <Piece> in <UnstructuredGrid>".into()))?;
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
        let points = self.array(
            points_da,
            Limit::Values(n.saturating_mul(3)),
            &format!("NumberOfPoints={n}"),
        )?;
        let coords = self.points(points, n)?;

        let cells_el = section("Cells")?;
        let has = |name: &str| {
            cells_el
                .children_named("DataArray")
                .any(|d| d.attr("Name") == Some(name))
        };
        let general = has("faces");
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
            let (tuples, why) = match name {
                "connectivity" if general => (
                    ncells.saturating_mul(MAX_GENERAL),
                    format!("NumberOfCells={ncells} (at most {MAX_GENERAL} points each)"),
                ),
                "connectivity" => (
                    ncells.saturating_mul(8),
                    format!("NumberOfCells={ncells} (at most 8 points each)"),
                ),
                "faces" => (
                    ncells.saturating_mul(MAX_GENERAL * MAX_GENERAL),
                    format!(
                        "NumberOfCells={ncells} (at most {MAX_GENERAL} faces of {MAX_GENERAL} \
                         points each)"
                    ),
                ),
                _ => (ncells, format!("NumberOfCells={ncells}")),
            };
            self.array(el, Limit::Tuples(tuples), &why)
        };
        let arrays = [
            cell_array("connectivity")?,
            cell_array("offsets")?,
            cell_array("types")?,
        ];
        let faces = if general {
            Some([cell_array("faces")?, cell_array("faceoffsets")?])
        } else {
            None
        };
        let all = self.cells(&arrays, faces.as_ref(), n, ncells)?;
        drop(arrays);
        drop(faces);

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
    pub(super) fn ints<'v>(&self, a: &'v Array, len: Option<usize>) -> Result<&'v [i64]> {
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

    /// All cells of the file, checked: kinds known, node counts right, nodes
    /// in range; a polyhedron's faces from `faces` (the `faces` and
    /// `faceoffsets` arrays).
    fn cells(
        &self,
        [conn, offsets, types]: &[Array; 3],
        faces: Option<&[Array; 2]>,
        n: usize,
        ncells: usize,
    ) -> Result<Cells> {
        let at = |a: &Array, m: String| {
            self.ctx
                .at(a.el.pos, format!("DataArray '{}': {m}", a.name))
        };
        let nodes = self.ints(conn, None)?;
        let ends = self.ints(offsets, Some(ncells))?;
        let kinds = self.ints(types, Some(ncells))?;
        let streams = match faces {
            Some([f, o]) => Some((f, self.ints(f, None)?, o, self.ints(o, Some(ncells))?)),
            None => None,
        };
        let mut cells = Cells::new();
        cells.kinds.reserve_exact(ncells);
        cells.offsets.reserve_exact(ncells);
        cells.nodes.reserve_exact(nodes.len());
        let mut start = 0;
        let mut face_start = 0;
        let mut local = Vec::with_capacity(8);
        for (c, (&end, &t)) in ends.iter().zip(kinds).enumerate() {
            let kind = CellKind::from_vtk_id(t).ok_or_else(|| {
                at(
                    types,
                    format!(
                        "cell {c} has unknown VTK type {t} (supported: 1 vertex, 3 line, \
                         5 triangle, 7 polygon, 9 quad, 10 tetra, 12 hexahedron, 13 wedge, \
                         14 pyramid, 42 polyhedron)"
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
            if !kind.is_general() && end - start != kind.node_count() {
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
            local.clear();
            local.resize(end - start, 0);
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
            if kind == CellKind::Polyhedron {
                let Some((f, stream, o, face_ends)) = &streams else {
                    return Err(at(
                        types,
                        format!("cell {c} is a polyhedron (42) but <Cells> has no 'faces' array"),
                    ));
                };
                let stop = match usize::try_from(face_ends[c]) {
                    Ok(e) if e >= face_start && e <= stream.len() => e,
                    _ => {
                        return Err(at(
                            o,
                            format!(
                                "cell {c} ends its faces at {}, outside {face_start}..={}",
                                face_ends[c],
                                stream.len()
                            ),
                        ))
                    }
                };
                let list = face_stream(&stream[face_start..stop], n)
                    .map_err(|m| at(f, format!("cell {c}: {m}")))?;
                cells
                    .push_polyhedron_on(&local, list.iter().map(Vec::as_slice))
                    .map_err(|p| {
                        at(
                            f,
                            format!("cell {c}: a face uses point {p}, not among the cell's points"),
                        )
                    })?;
                face_start = stop;
            } else {
                cells.push(kind, &local);
            }
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
                let why = format!("{key}={count}");
                let a = self.array(el, Limit::Tuples(count), &why)?;
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
            // Float arrays are decoded too (never beyond 3 values), so that
            // a zlib bomb is refused wherever it is.
            if el.attr("type").and_then(Ty::parse).is_none() {
                continue;
            }
            let Some(a) = self.decode(el, Limit::Values(3), "a group name")? else {
                continue;
            };
            let Values::Int(v) = &a.values else { continue };
            let tag = match v[..] {
                [id, _] if id >= 1 => None,
                [id, _, tag] if id >= 1 => match i32::try_from(tag) {
                    Ok(tag) => Some(tag),
                    Err(_) => continue,
                },
                _ => continue,
            };
            if names.len() == MAX_GROUPS {
                return Err(self.ctx.at(
                    el.pos,
                    format!(
                        "more than {MAX_GROUPS} group names in <FieldData> (the most verbss reads)"
                    ),
                ));
            }
            names.push((v[0], a.name, tag));
        }
        names.sort_by_key(|g| g.0);
        Ok(names)
    }
}

/// The most points and faces of a polyhedron (and points of a polygon) a
/// file's counts may claim, to bound what is decoded.
const MAX_GENERAL: usize = 256;

/// The faces of one polyhedron from its VTK face stream `nFaces, (nPoints,
/// point …) …` (points below `n`).
fn face_stream(stream: &[i64], n: usize) -> std::result::Result<Vec<Vec<usize>>, String> {
    let count = |v: Option<&i64>, what: &str| match v.map(|&v| usize::try_from(v)) {
        Some(Ok(v)) if v <= MAX_GENERAL => Ok(v),
        _ => Err(format!(
            "its face stream has no valid {what} count (at most {MAX_GENERAL})"
        )),
    };
    let mut it = stream.iter();
    let faces = count(it.next(), "face")?;
    let mut out = Vec::with_capacity(faces);
    for _ in 0..faces {
        let m = count(it.next(), "point")?;
        let face: Vec<usize> = it
            .by_ref()
            .take(m)
            .map(|&p| usize::try_from(p).ok().filter(|&p| p < n))
            .collect::<Option<_>>()
            .ok_or_else(|| format!("a face uses a point outside 0..{n}"))?;
        if face.len() != m {
            return Err("its face stream ends inside a face".into());
        }
        out.push(face);
    }
    if it.next().is_some() {
        return Err("its face stream is longer than its faces".into());
    }
    Ok(out)
}
