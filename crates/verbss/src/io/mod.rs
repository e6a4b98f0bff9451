//! Mesh files in and out: Gmsh MSH 2.2/4.1, SU2, VTK XML (`.vtu`, `.pvd`),
//! CGNS (`.cgns`, with the CGNS library).
//! OpenFOAM polyMesh.
//!
//! Every format implements one interface, [`MeshFormat`] (read a file's
//! zones, write a moved mesh); [`read`] and [`write()`] choose the format by
//! extension ([`Format::from_path`]: a directory or a path without an
//! extension is an OpenFOAM case). One rank's part of a file is read by
//! the `verbss-mpi` command's `PartFormat`, which Gmsh (partitioned, through
//! [`gmsh::partitioned`]), SU2 and CGNS implement.

use std::fs::File;
use std::io::{BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::mesh::Mesh;

pub mod cgns;
pub mod foam;
mod format;
pub mod gmsh;
pub mod outputs;
pub mod positions;
pub mod pvd;
pub mod su2;
pub mod vtu;

pub use format::{read, read_zone, read_zones, write, write_moved, Format, MeshFormat};

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
    let Some(what) = special_kind(path) else {
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

/// What `path` (links followed) is when it is a FIFO (`a FIFO`), a device
/// or a socket; `None` for anything else, or nothing.
fn special_kind(path: &Path) -> Option<&'static str> {
    use std::os::unix::fs::FileTypeExt;
    let kind = std::fs::metadata(path).ok()?.file_type();
    if kind.is_fifo() {
        Some("a FIFO")
    } else if kind.is_char_device() || kind.is_block_device() {
        Some("a device")
    } else if kind.is_socket() {
        Some("a socket")
    } else {
        None
    }
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
/// refused (writing into one would block or go nowhere; the commands refuse
/// them before a run: [`outputs::check`]).
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    if is_special(path) {
        return Err(io_err(std::io::Error::other(
            "a device, FIFO or socket: give a regular file to write",
        )));
    }
    fill_and_rename(&link_target(path), fill).map_err(io_err)
}

/// [`write_atomic`] without following a link: a symbolic link at `path` is
/// itself replaced by the new file (its target untouched), as is a FIFO or
/// device.
pub fn write_replacing(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    fill_and_rename(path, fill).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Fills the temporary file beside `target` and renames it over `target`;
/// on failure removes it.
fn fill_and_rename(
    target: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let tmp = temp_path(target);
    let result = (|| {
        let file = File::create(&tmp)?;
        let mut w = BufWriter::new(file);
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, target)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
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
