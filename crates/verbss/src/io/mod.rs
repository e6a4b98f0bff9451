//! Mesh files in and out: Gmsh MSH 2.2/4.1, SU2, VTK XML (`.vtu`, `.pvd`),
//! CGNS (`.cgns`, with the CGNS library).
//! OpenFOAM polyMesh.
//!
//! [`read`] and [`write()`] choose the format by extension; a directory or
//! a path without an extension is an OpenFOAM case.

use std::fs::File;
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::mesh::Mesh;

pub mod cgns;
pub mod foam;
pub mod gmsh;
pub mod positions;
pub mod pvd;
pub mod su2;
pub mod vtu;

/// The most groups (SU2 markers, Gmsh physical groups, VTU group names) a
/// reader accepts: real meshes have tens to thousands, and each group costs
/// a few hundred bytes however small the file that names it.
pub const MAX_GROUPS: usize = 1 << 16;

/// The length of the UTF-8 byte-order mark that `bytes` starts with (3), or 0:
/// text readers start after it.
fn bom(bytes: &[u8]) -> usize {
    if bytes.starts_with(b"\xef\xbb\xbf") {
        3
    } else {
        0
    }
}

/// A token or line as quoted in messages: printable, at most 40 characters.
pub(crate) fn shown(text: &str) -> String {
    let mut s: String = text.chars().take(40).flat_map(char::escape_debug).collect();
    if text.chars().count() > 40 {
        s.push('…');
    }
    s
}

/// Names the place in the file (`at`) of a [`Mesh::validate`] failure of a
/// mesh just read; other errors pass unchanged.
fn invalid_at(e: Error, at: impl FnOnce(String) -> Error) -> Error {
    match e {
        Error::InvalidMesh(m) => at(format!("invalid mesh: {m}")),
        e => e,
    }
}

/// Options for [`write()`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct WriteOptions {
    /// Gmsh file-format version: `2.2` or `4.1`.
    pub msh_version: MshVersion,
    /// Binary encoding where the format offers one (Gmsh).
    pub binary: bool,
    /// An OpenFOAM output that is the case the mesh was read from: the time
    /// directory its points go to (`CASE/TIME/polyMesh/points`); `None`
    /// replaces `constant/polyMesh/points` (see [`foam::write`]).
    pub foam_time: Option<String>,
}

/// Gmsh MSH file-format version (`"2.2"` or `"4.1"` in a case file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
pub enum MshVersion {
    /// MSH 2.2.
    #[serde(rename = "2.2")]
    V22,
    /// MSH 4.1.
    #[default]
    #[serde(rename = "4.1")]
    V41,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            msh_version: MshVersion::V41,
            binary: false,
            foam_time: None,
        }
    }
}

impl WriteOptions {
    /// The options that write `mesh` as it was read: a mesh from a Gmsh file
    /// keeps that file's MSH version and encoding (and, unchanged but for its
    /// coordinates, the whole file: see [`gmsh::write_to`]); any other mesh
    /// gets the defaults (MSH 4.1, ASCII).
    pub fn for_mesh(mesh: &Mesh) -> WriteOptions {
        match &mesh.origin.gmsh {
            Some(source) => WriteOptions {
                msh_version: source.version(),
                binary: source.binary(),
                foam_time: None,
            },
            None => WriteOptions::default(),
        }
    }
}

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Gmsh `.msh`.
    Msh,
    /// SU2 `.su2`.
    Su2,
    /// VTK XML unstructured grid `.vtu`.
    Vtu,
    /// CGNS `.cgns` (unstructured zones).
    Cgns,
    /// An OpenFOAM case directory (its `constant/polyMesh`).
    Foam,
}

impl Format {
    /// The format's file extension, without the dot (none for OpenFOAM).
    pub fn extension(self) -> &'static str {
        match self {
            Format::Msh => "msh",
            Format::Su2 => "su2",
            Format::Vtu => "vtu",
            Format::Cgns => "cgns",
            Format::Foam => "",
        }
    }

    /// The format named by a path's extension; a directory or a path
    /// without an extension is an OpenFOAM case ([`foam::is_case`]).
    pub fn from_path(path: &Path) -> Result<Format> {
        if foam::is_case(path) {
            return Ok(Format::Foam);
        }
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        [Format::Msh, Format::Su2, Format::Vtu, Format::Cgns]
            .into_iter()
            .find(|f| ext.as_deref() == Some(f.extension()))
            .ok_or_else(|| Error::UnknownFormat {
                path: path.to_path_buf(),
            })
    }
}

/// Reads a mesh, choosing the format by extension; of a multi-zone SU2
/// file, zone 1 ([`read_zone`] reads another).
pub fn read(path: &Path) -> Result<Mesh> {
    read_zone(path, 1).map(|(mesh, _)| mesh)
}

/// Reads zone `zone` (1-based, SU2's `IZONE=`) of a mesh file and gives its
/// number of zones. Only SU2 files have several; every other file is zone 1
/// of 1. The other zones of an SU2 file are kept for an SU2 output
/// ([`su2::parse_zone`]).
pub fn read_zone(path: &Path, zone: usize) -> Result<(Mesh, usize)> {
    let format = Format::from_path(path)?;
    if format == Format::Su2 {
        return su2::parse_zone(&read_bytes(path)?, path, zone);
    }
    let mesh = read_one(format, path)?;
    if zone != 1 {
        return Err(Error::InvalidSetting(format!(
            "{}: zone {zone} asked for, but verbss reads several zones from SU2 files only",
            path.display()
        )));
    }
    Ok((mesh, 1))
}

/// Reads every zone of a mesh file, in order: one mesh for every file but a
/// multi-zone SU2 file.
pub fn read_zones(path: &Path) -> Result<Vec<Mesh>> {
    match Format::from_path(path)? {
        Format::Su2 => su2::parse_zones(&read_bytes(path)?, path),
        format => Ok(vec![read_one(format, path)?]),
    }
}

/// Reads the mesh of a file in `format` (an SU2 file: zone 1; a CGNS file:
/// its first zone).
fn read_one(format: Format, path: &Path) -> Result<Mesh> {
    match format {
        Format::Msh => gmsh::parse(&read_bytes(path)?, path),
        Format::Su2 => su2::parse(&read_bytes(path)?, path),
        Format::Vtu => vtu::parse(&read_bytes(path)?, path).map(|v| v.mesh),
        Format::Cgns => cgns::read(path),
        Format::Foam => foam::read(path),
    }
}

/// A file's bytes (see [`open_input`]).
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    open_input(path)?
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    Ok(bytes)
}

/// Opens the input file `path`, which must be a regular file (links
/// followed): a FIFO, device or socket is refused before it is opened
/// (opening one can block forever, and its bytes are no mesh).
pub(crate) fn open_input(path: &Path) -> Result<File> {
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    regular_input(path)?;
    File::open(path).map_err(io)
}

/// Refuses `path` when it exists and is a FIFO, device or socket (a
/// missing file is left to whoever opens it).
pub(crate) fn regular_input(path: &Path) -> Result<()> {
    use std::os::unix::fs::FileTypeExt;
    let Ok(kind) = std::fs::metadata(path).map(|m| m.file_type()) else {
        return Ok(());
    };
    let what = if kind.is_fifo() {
        "a FIFO"
    } else if kind.is_char_device() || kind.is_block_device() {
        "a device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        return Ok(());
    };
    Err(Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{what}, not a regular file (verbss reads its inputs from regular files only)"),
        ),
    })
}

/// Writes a mesh, choosing the format by extension (atomically, see
/// [`write_atomic`]; a CGNS mesh read from a CGNS file is a copy of that
/// file with new coordinates, see [`cgns::write`]).
pub fn write(path: &Path, mesh: &Mesh, options: &WriteOptions) -> Result<()> {
    write_moved(path, mesh, &mesh.coords, options)
}

/// [`write()`] with the nodes at `coords` (`dim` numbers per node) instead of
/// the mesh's own: a moved mesh written without a copy of its cells.
pub fn write_moved(path: &Path, mesh: &Mesh, coords: &[f64], options: &WriteOptions) -> Result<()> {
    if coords.len() != mesh.coords.len() {
        return Err(Error::InvalidSetting(format!(
            "{} coordinates for the {} nodes of a {}D mesh",
            coords.len(),
            mesh.node_count(),
            mesh.dim
        )));
    }
    let format = Format::from_path(path)?;
    let fixed_only = match format {
        Format::Msh => Some("Gmsh MSH"),
        Format::Su2 => Some("SU2"),
        Format::Cgns if mesh.origin.cgns.is_none() => Some("CGNS (for a mesh not read from one)"),
        _ => None,
    };
    if let (Some(name), Some(what)) = (fixed_only, general_cell(mesh)) {
        return Err(Error::Unrepresentable {
            path: path.to_path_buf(),
            format: name,
            what,
        });
    }
    match format {
        Format::Msh => write_atomic(path, |w| {
            gmsh::write_moved_to(w, mesh, coords, options.msh_version, options.binary)
        }),
        Format::Su2 => write_atomic(path, |w| su2::write_moved_to(w, mesh, coords)),
        Format::Vtu => write_atomic(path, |w| {
            vtu::write_moved_to(w, mesh, coords, &vtu::Fields::default())
        }),
        Format::Cgns => cgns::write_moved(path, mesh, coords),
        Format::Foam => foam::write_moved(path, mesh, coords, options.foam_time.as_deref()),
    }
}

/// The first polygon or polyhedron of `mesh`, among its cells or its
/// groups' facets, named for a message (`element 17, a polyhedron`).
fn general_cell(mesh: &Mesh) -> Option<String> {
    if let Some(c) = mesh.cells.first_general() {
        return Some(format!(
            "element {}, a {}",
            mesh.cell_tags[c],
            mesh.cells.kinds[c].name()
        ));
    }
    mesh.groups.iter().find_map(|g| {
        g.facets.first_general().map(|f| {
            format!(
                "facet {f} of group '{}', a {} of {} nodes",
                g.name,
                g.facets.kinds[f].name(),
                g.facets.cell(f).len()
            )
        })
    })
}

/// The temporary file beside `path` that an atomic write fills first
/// (`.NAME.PID.tmp`). With [`is_special`] and [`link_target`] it serves
/// writers that fill the temporary file themselves and rename it when done,
/// such as the GIF animation of the `verbss-render` crate.
pub fn temp_path(path: &Path) -> PathBuf {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    dir.join(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes a file through `fill` so that it is never left half-written: the
/// bytes go to a temporary file beside `path`, which is renamed over `path`
/// only once everything was written and flushed. On failure the temporary
/// file is removed and `path` is untouched. A symbolic link is followed (its
/// final target is replaced, the link kept); a device, FIFO or socket is
/// written to directly, never replaced.
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    if is_special(path) {
        let result = (|| {
            let mut w = BufWriter::new(File::options().write(true).open(path)?);
            fill(&mut w)?;
            w.flush()
        })();
        return result.map_err(io_err);
    }
    let target = link_target(path);
    let tmp = temp_path(&target);
    let result = (|| {
        let file = File::create(&tmp)?;
        let mut w = BufWriter::new(file);
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, &target)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(io_err(e));
    }
    Ok(())
}

/// Whether `path` (links followed) is a device, FIFO or socket.
pub fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// The final target of `path` when it is a symbolic link (a chain of at most
/// 40), else `path`.
pub fn link_target(path: &Path) -> PathBuf {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        let Ok(next) = std::fs::read_link(&p) else {
            break;
        };
        p = match p.parent() {
            Some(dir) => dir.join(next),
            None => next,
        };
    }
    p
}

#[cfg(test)]
mod moved_tests;
