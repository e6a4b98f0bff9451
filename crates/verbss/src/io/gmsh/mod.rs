//! Gmsh MSH 2.2 and 4.1, ASCII and binary, read and write.
//!
//! # What is read
//!
//! A file is a list of sections `$Name … $EndName`. The reader takes
//! `$MeshFormat` (version 2.2 or 4.1, file type 0 ASCII or 1 binary, data size
//! 8; binary files hold the integer 1 after the format line to show their byte
//! order, and must be little-endian), `$PhysicalNames`, `$Entities` and
//! `$PartitionedEntities` (4.1: the physical tags of each geometric entity),
//! `$Nodes`, `$Elements` and `$Periodic` (its links, each node of a slave
//! entity the image of a master node: the mesh's periodic interfaces,
//! [`crate::mesh::Coupling::Linked`]), and skips every other section
//! (`$NodeData`, …). Element types: 15 point,
//! 1 line, 2 triangle, 3 quadrangle, 4 tetrahedron, 5 hexahedron, 6 prism,
//! 7 pyramid; any other type (higher order, …) is an error.
//!
//! The mesh dimension `D` is the largest element dimension in the file. Its
//! elements become [`Mesh::cells`] in file order, with their tags as
//! `cell_tags`. Elements of lower dimension that carry a physical tag `p`
//! become one [`Group`](crate::mesh::Group) per `(dimension, p)`, named by
//! `$PhysicalNames` (or `p` written as text), in order of first appearance; an
//! element with several physical tags joins each group. Lower-dimensional
//! elements without a physical tag are dropped, and so are the physical groups
//! of the cells themselves. MSH 2.2 repeats an element once per physical group
//! (with a new tag each time): consecutive identical cells are read as one.
//! Node tags may be sparse and in any order; they are kept as `node_tags`.
//! Gmsh always stores `z`: when `D = 2` every node must have `z = 0`.
//!
//! A partitioned MSH 4.1 file (`gmsh -part N`) reads whole as above;
//! [`partitioned::read_share`] reads only some of its partitions.
//!
//! # What is written
//!
//! A mesh read from a file, written in that file's version and encoding with
//! its nodes, cells, tags and groups unchanged, is that file with only the
//! node coordinates replaced ([`Source`]): everything the reader skipped or
//! did not model is kept byte for byte. Any other mesh is written anew:
//!
//! `$PhysicalNames` (one per group), for 4.1 `$Entities` (one entity per group
//! with the group's physical tag, one for the cells with none), `$Nodes` (one
//! block, the mesh's node tags), `$Elements`: the cells with their
//! `cell_tags`, then each group's facets: with the element tags of the file
//! the mesh was read from, when it is unchanged and they are distinct, else
//! numbered on from the largest cell tag. The cells' physical group keeps
//! the file's tag and name when the file gave them one, else it is `domain`. A group keeps its `tag` as physical tag unless it has none or it is
//! taken; then it gets a fresh one. In 2D, `z = 0` is written. ASCII floats use
//! the shortest text that reads back to the same `f64`, so writing and reading
//! back gives the same mesh, bit for bit, in all four encodings (empty groups
//! excepted: they have no elements to carry them). A piece of a larger mesh
//! (a rank's share of a partitioned file) is written as one file of a set
//! of partitions, as `gmsh -part K -part_split` writes them
//! ([`split_write`]), keeping the file's facet tags and cells' physical
//! group ([`PieceLabels`]), and [`split`] reads such a set back.
//!
//! # Why a reader of our own
//!
//! The `mshio` crate reads MSH 4.1 only (no 2.2, no writer), and its errors do
//! not say where in the file the problem is. This reader handles both versions
//! with one byte cursor, names the line (ASCII) or byte offset (binary) of
//! every error, never allocates for a header count the remaining bytes cannot
//! hold, and reads binary blocks in place with `from_le_bytes`, with no heap
//! allocation per element.

mod cursor;
mod entities;
mod model;
pub mod partitioned;
mod periodic;
mod source;
pub mod split;
pub mod split_write;
mod stream;
mod v22;
mod v41;
mod write;

/// Gmsh MSH 2.2 and 4.1, ASCII and binary.
pub struct Msh;

impl super::MeshFormat for Msh {
    fn name(&self) -> &'static str {
        "Gmsh MSH"
    }

    fn read_zone(&self, path: &Path, zone: usize) -> Result<(Mesh, usize)> {
        super::format::one_zone(path, zone, || parse(&super::read_bytes(path)?, path))
    }

    fn write_moved(
        &self,
        path: &Path,
        mesh: &Mesh,
        coords: &[f64],
        options: &super::WriteOptions,
    ) -> Result<()> {
        super::write_atomic(path, |w| {
            write_moved_to(w, mesh, coords, options.msh_version, options.binary)
        })
    }

    fn stores_general_cells(&self, _: &Mesh) -> bool {
        false
    }
}

#[cfg(test)]
mod hostile_tests;
#[cfg(test)]
mod split_tests;
#[cfg(test)]
mod tests;

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use super::{MshVersion, MAX_GROUPS};
use crate::error::Result;
use crate::mesh::Mesh;
use cursor::{show, Cursor, Mark};
use model::{finish, Elements, Names, NodeIndex, Nodes};
pub use source::Source;

/// Parses a Gmsh file's bytes; `path` is only used in error messages.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Mesh> {
    let mut c = Cursor::new(bytes, path);
    let version = read_format(&mut c)?;
    let mut names = Names::new();
    let mut entities = entities::Entities::default();
    let mut nodes: Option<(Nodes, NodeIndex)> = None;
    let mut elements: Option<(Elements, Mark)> = None;
    let mut links = Vec::new();
    while let Some(tok) = c.next_token() {
        let section = c.mark();
        match tok {
            b"$PhysicalNames" => read_names(&mut c, &mut names)?,
            b"$Entities" if version == MshVersion::V41 => {
                entities::read_entities(&mut c, &mut entities)?;
            }
            b"$PartitionedEntities" if version == MshVersion::V41 => {
                entities::read_partitioned(&mut c, &mut entities)?;
            }
            b"$Nodes" => {
                if nodes.is_some() {
                    return Err(c.error("a second $Nodes section (one is expected)"));
                }
                let read = match version {
                    MshVersion::V22 => v22::read_nodes(&mut c)?,
                    MshVersion::V41 => v41::read_nodes(&mut c)?,
                };
                let index = NodeIndex::build(&read.tags).map_err(|t| {
                    c.error_at(section, format!("node tag {t} is given to two nodes"))
                })?;
                nodes = Some((read, index));
            }
            b"$Elements" => {
                if elements.is_some() {
                    return Err(c.error("a second $Elements section (one is expected)"));
                }
                let Some((_, index)) = &nodes else {
                    return Err(c.error("$Elements comes before $Nodes"));
                };
                let read = match version {
                    MshVersion::V22 => v22::read_elements(&mut c, index)?,
                    MshVersion::V41 => v41::read_elements(&mut c, index, &entities)?,
                };
                elements = Some((read, section));
            }
            b"$Periodic" => links.extend(periodic::read(&mut c, version)?),
            t if t.len() > 1 && t[0] == b'$' && !t.starts_with(b"$End") => {
                let name = String::from_utf8_lossy(&t[1..]).into_owned();
                c.skip_past(&format!("$End{name}"))?;
            }
            t => {
                return Err(c.error(format!(
                    "expected a section header such as $Nodes, found {}",
                    show(t)
                )))
            }
        }
    }
    let end = c.here();
    let Some((mut nodes, _)) = nodes else {
        return Err(c.error_at(end, "unexpected end of file: no $Nodes section"));
    };
    let Some(elements) = elements else {
        return Err(c.error_at(end, "unexpected end of file: no $Elements section"));
    };
    let spans = std::mem::take(&mut nodes.spans);
    let (mut mesh, structure) =
        finish(&c, nodes, elements, &names, version == MshVersion::V22, end)?;
    mesh.origin.interfaces = periodic::interfaces(&c, &links, &mesh.node_tags)?;
    let source = Source::new(bytes, (version, c.binary()), spans, structure, &mesh);
    mesh.origin.gmsh = Some(Arc::new(source));
    Ok(mesh)
}

/// Writes `mesh` as MSH `version`, ASCII or binary.
///
/// A mesh read from a Gmsh file of that version and encoding, with its
/// nodes, cells, tags and groups unchanged, is written as that file with
/// only the node coordinates replaced ([`Source`]).
///
/// Fails with `InvalidInput` when the mesh cannot be stored: it does not pass
/// [`Mesh::validate`], a group mixes facet dimensions or has a quote or a line
/// break in its name, or (2.2) a tag does not fit a 32-bit integer.
pub fn write_to(
    w: &mut dyn Write,
    mesh: &Mesh,
    version: MshVersion,
    binary: bool,
) -> std::io::Result<()> {
    write_moved_to(w, mesh, &mesh.coords, version, binary)
}

/// [`write_to`] with the nodes at `coords` (`dim` numbers per node) instead
/// of the mesh's own.
pub fn write_moved_to(
    w: &mut dyn Write,
    mesh: &Mesh,
    coords: &[f64],
    version: MshVersion,
    binary: bool,
) -> std::io::Result<()> {
    if let Some(source) = mesh
        .origin
        .gmsh
        .as_ref()
        .filter(|s| s.fits(mesh, version, binary))
    {
        return source.write(w, mesh.dim, coords);
    }
    let plan = write::Plan::new(mesh, coords)?;
    let mut out = write::Out::new(w, binary);
    match version {
        MshVersion::V22 => v22::write(&mut out, &plan)?,
        MshVersion::V41 => v41::write(&mut out, &plan)?,
    }
    out.finish()
}

/// What a piece of a larger mesh keeps of the file it was read from, so
/// that pieces written apart agree with each other and with the file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PieceLabels {
    /// The file's element tag of each facet of each group of the piece;
    /// `None` numbers them on from the piece's largest cell tag.
    pub facet_tags: Option<Vec<Vec<u64>>>,
    /// The file's physical tag and name of the cells; `None` gives them a
    /// fresh tag named `domain`.
    pub domain: Option<(i32, String)>,
}

/// Reads `$MeshFormat … $EndMeshFormat`; switches the cursor to binary mode
/// for binary files.
fn read_format(c: &mut Cursor) -> Result<MshVersion> {
    match c.next_token() {
        Some(b"$MeshFormat") => {}
        Some(t) => {
            return Err(c.error(format!(
                "expected $MeshFormat at the start of a Gmsh file, found {}",
                show(t)
            )))
        }
        None => return Err(c.error("the file is empty (expected $MeshFormat)")),
    }
    let v = c.token("the format version")?;
    let version = match v {
        b"2" | b"2.0" | b"2.1" | b"2.2" => MshVersion::V22,
        b"4.1" => MshVersion::V41,
        _ => {
            return Err(c.error(format!(
                "unsupported MSH version {} (verbss reads 2.2 and 4.1)",
                String::from_utf8_lossy(v)
            )))
        }
    };
    let file_type = c.uint("the file type")?;
    if file_type > 1 {
        return Err(c.error(format!(
            "expected file type 0 (ASCII) or 1 (binary), found {file_type}"
        )));
    }
    let size = c.uint("the data size")?;
    if size != 8 {
        return Err(c.error(format!("data size {size} is not supported (expected 8)")));
    }
    if file_type == 1 {
        c.set_binary();
        c.newline()?;
        match c.i32_le("the byte-order check")? {
            1 => {}
            0x0100_0000 => {
                return Err(
                    c.error("the binary file is big-endian; verbss reads little-endian files")
                )
            }
            one => {
                return Err(c.error(format!(
                    "expected the integer 1 after the format line, found {one}"
                )))
            }
        }
    }
    c.keyword("$EndMeshFormat")?;
    Ok(version)
}

/// Reads `$PhysicalNames`: lines `dimension tag "name"`.
fn read_names(c: &mut Cursor, names: &mut Names) -> Result<()> {
    let n = c.count("the number of physical names")?;
    for i in 0..n {
        early_end(c, || {
            format!("$PhysicalNames declares {n} names but ends after {i}")
        })?;
        let dim = c.count("a physical dimension")?;
        if dim > 3 {
            return Err(c.error(format!("physical dimension {dim} (expected 0 to 3)")));
        }
        let tag = c.int("a physical tag")?;
        let rest = c.rest_of_line().trim_ascii();
        let name = match rest {
            [b'"', inner @ .., b'"'] => String::from_utf8_lossy(inner).into_owned(),
            _ => {
                return Err(c.error(format!(
                    "expected a physical name in double quotes, found {}",
                    show(rest)
                )))
            }
        };
        names.insert((dim, tag), name);
        if names.len() > 4 * MAX_GROUPS {
            return Err(c.error(format!(
                "more than {} physical names ({MAX_GROUPS} groups of each dimension are \
                 the most verbss reads)",
                4 * MAX_GROUPS
            )));
        }
    }
    close(c, "$EndPhysicalNames", n, "names")
}

/// Fails with `message` when the section ends (a `$` keyword comes) where an
/// entry was expected.
fn early_end(c: &mut Cursor, message: impl FnOnce() -> String) -> Result<()> {
    if c.at_section_mark() {
        return Err(c.error_at(c.here(), message()));
    }
    Ok(())
}

/// Reads the keyword closing a section that declared `n` `things`.
fn close(c: &mut Cursor, keyword: &str, n: usize, things: &str) -> Result<()> {
    let tok = c.token(keyword)?;
    if tok == keyword.as_bytes() {
        return Ok(());
    }
    Err(c.error(format!(
        "expected {keyword} after {n} {things}, found {}: the section holds more than it declares",
        show(tok)
    )))
}
