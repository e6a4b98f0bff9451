//! The node layer under the mid-level library (`cgns_io.h`): a file's node
//! tree read node by node, without the mid-level library's in-memory tree
//! (`cg_open` reads the whole tree and trusts what it finds), so that
//! [`crate::io::cgns`] can check the tree first; and a tree written node by
//! node, as hostile files are made in the tests and the fuzz targets.
//!
//! Every buffer is sized from what the layer itself reports or is told to
//! fill: names and labels 33 bytes (32 characters and the zero, the layer
//! cuts longer ones), data types 33 bytes (2 characters are stored), 12
//! dimensions (`CGIO_MAX_DIMENSIONS`), link paths from `cgio_link_size`,
//! data over the hyperslab asked for.

use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::Path;
use std::sync::MutexGuard;

use super::sys::*;
use super::{c_name, name_of, CgSize, NameBuf, LIBRARY};

/// `CGIO_MODE_READ`, `CGIO_MODE_WRITE`.
const READ: c_int = 0;
const WRITE: c_int = 1;
/// `CGIO_FILE_NONE` (any, when reading), `CGIO_FILE_HDF5`.
const ANY_FORMAT: c_int = 0;
const HDF5: c_int = 2;
/// `CGIO_MAX_DIMENSIONS`.
pub const MAX_DIMENSIONS: usize = 12;

/// A node of an open [`Tree`] (the layer's id).
pub type NodeId = f64;

/// What a node says of itself.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeHead {
    pub name: String,
    pub label: String,
    /// The data type (`MT`, `I4`, `I8`, `R4`, `R8`, `C1`, …).
    pub kind: String,
    /// The dimensions of its data, as the layer gives them (C order
    /// reversed: the first varies fastest).
    pub dims: Vec<i64>,
}

/// A CGNS file open at the node layer; closed when dropped. It holds the
/// library's process-wide lock, as [`super::File`] does.
pub struct Tree {
    cgio: c_int,
    _lock: MutexGuard<'static, ()>,
}

impl Tree {
    /// Opens `path` for reading (HDF5 or ADF underneath).
    pub fn open(path: &Path) -> Result<Tree, String> {
        Tree::start(path, READ, ANY_FORMAT)
    }

    /// Creates the HDF5 file `path`, empty but for its root.
    pub fn create(path: &Path) -> Result<Tree, String> {
        Tree::start(path, WRITE, HDF5)
    }

    fn start(path: &Path, mode: c_int, kind: c_int) -> Result<Tree, String> {
        let lock = LIBRARY.lock().unwrap_or_else(|p| p.into_inner());
        let name = c_name(&path.to_string_lossy())?;
        let mut cgio = 0;
        // SAFETY: a valid C string and an out-pointer.
        check(unsafe { cgio_open_file(name.as_ptr(), mode, kind, &mut cgio) })?;
        super::keep_from_children(path);
        Ok(Tree { cgio, _lock: lock })
    }

    /// The root node.
    pub fn root(&self) -> Result<NodeId, String> {
        let mut id = 0.0;
        // SAFETY: an out-pointer.
        check(unsafe { cgio_get_root_id(self.cgio, &mut id) })?;
        Ok(id)
    }

    /// Where `id` links to (`FILE:PATH`, `PATH` within this file), when it
    /// is a link; a link's own head is not asked for (that follows it).
    pub fn link(&self, id: NodeId) -> Result<Option<String>, String> {
        let mut len = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cgio_is_link(self.cgio, id, &mut len) })?;
        if len <= 0 {
            return Ok(None);
        }
        let (mut file_len, mut name_len) = (0, 0);
        // SAFETY: out-pointers.
        check(unsafe { cgio_link_size(self.cgio, id, &mut file_len, &mut name_len) })?;
        let size = |n: c_int| usize::try_from(n).unwrap_or(0) + 1;
        let mut file = vec![0 as c_char; size(file_len)];
        let mut name = vec![0 as c_char; size(name_len)];
        // SAFETY: buffers of the sizes the layer reported, plus the zero.
        check(unsafe { cgio_get_link(self.cgio, id, file.as_mut_ptr(), name.as_mut_ptr()) })?;
        let text = |b: &[c_char]| {
            let bytes: Vec<u8> = b
                .iter()
                .take_while(|&&c| c != 0)
                .map(|&c| c as u8)
                .collect();
            String::from_utf8_lossy(&bytes).into_owned()
        };
        Ok(Some(match text(&file) {
            f if f.is_empty() => text(&name),
            f => format!("{f}:{}", text(&name)),
        }))
    }

    /// The node's name, label, data type and dimensions.
    pub fn head(&self, id: NodeId) -> Result<NodeHead, String> {
        let (mut name, mut label, mut kind): (NameBuf, NameBuf, NameBuf) =
            ([0; 33], [0; 33], [0; 33]);
        let mut dims: [CgSize; MAX_DIMENSIONS] = [0; MAX_DIMENSIONS];
        let mut n = 0;
        // SAFETY: 33-byte buffers (the layer writes at most 32 characters
        // and the zero), 12 dimensions (`CGIO_MAX_DIMENSIONS`).
        unsafe {
            check(cgio_get_name(self.cgio, id, name.as_mut_ptr()))?;
            check(cgio_get_label(self.cgio, id, label.as_mut_ptr()))?;
            check(cgio_get_data_type(self.cgio, id, kind.as_mut_ptr()))?;
            check(cgio_get_dimensions(
                self.cgio,
                id,
                &mut n,
                dims.as_mut_ptr(),
            ))?;
        }
        let n = usize::try_from(n).unwrap_or(0).min(MAX_DIMENSIONS);
        Ok(NodeHead {
            name: name_of(&name),
            label: name_of(&label),
            kind: name_of(&kind),
            dims: dims[..n].iter().map(|&d| i64::from(d)).collect(),
        })
    }

    /// The node's children, or an error when it has more than `most`.
    pub fn children(&self, id: NodeId, most: usize) -> Result<Vec<NodeId>, String> {
        let mut n = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cgio_number_children(self.cgio, id, &mut n) })?;
        let n = usize::try_from(n).unwrap_or(0);
        if n > most {
            return Err(format!("{n} children"));
        }
        if n == 0 {
            return Ok(Vec::new());
        }
        let mut ids = vec![0.0; n];
        let mut got = 0;
        // SAFETY: a buffer of the `n` ids asked for.
        check(unsafe {
            cgio_children_ids(self.cgio, id, 1, n as c_int, &mut got, ids.as_mut_ptr())
        })?;
        ids.truncate(usize::try_from(got).unwrap_or(0).min(n));
        Ok(ids)
    }

    /// Lets go of a node the tree no longer needs.
    pub fn release(&self, id: NodeId) {
        // SAFETY: an id of this file; a failure leaves nothing to undo.
        unsafe { cgio_release_id(self.cgio, id) };
    }

    /// Values `first..first + count` (from 0) of an integer node of one
    /// dimension, as `i64`, read in the node's own type (`I4` or `I8`) and
    /// widened here.
    pub fn read_i64(&self, id: NodeId, (first, count): (usize, usize)) -> Result<Vec<i64>, String> {
        match self.data_type(id)?.as_str() {
            "I4" => {
                let mut data = vec![0i32; count];
                self.read_range(id, "I4", (first, count), data.as_mut_ptr().cast())?;
                Ok(data.into_iter().map(i64::from).collect())
            }
            _ => {
                let mut data = vec![0i64; count];
                self.read_range(id, "I8", (first, count), data.as_mut_ptr().cast())?;
                Ok(data)
            }
        }
    }

    /// The characters of a `C1` node of one dimension of `count` values.
    pub fn read_text(&self, id: NodeId, count: usize) -> Result<String, String> {
        let mut data = vec![0u8; count];
        self.read_range(id, "C1", (0, count), data.as_mut_ptr().cast())?;
        Ok(String::from_utf8_lossy(&data).into_owned())
    }

    /// The node's data type (`I4`, `C1`, …).
    fn data_type(&self, id: NodeId) -> Result<String, String> {
        let mut kind: NameBuf = [0; 33];
        // SAFETY: a 33-byte buffer (at most 32 characters and the zero).
        check(unsafe { cgio_get_data_type(self.cgio, id, kind.as_mut_ptr()) })?;
        Ok(name_of(&kind))
    }

    /// Reads a hyperslab of one dimension into `data`, which holds `count`
    /// values of type `kind`, the node's own type: the values are read as
    /// stored (the library converts types in HDF5 files only, not in ADF
    /// ones), so any other type is refused before the read.
    fn read_range(
        &self,
        id: NodeId,
        kind: &str,
        (first, count): (usize, usize),
        data: *mut c_void,
    ) -> Result<(), String> {
        if count == 0 {
            return Ok(());
        }
        let stored = self.data_type(id)?;
        if stored != kind {
            return Err(format!("{stored} data where {kind} data was expected"));
        }
        let size = |n: usize| CgSize::try_from(n).map_err(|_| format!("{n} values"));
        let (start, end, one, all) = (size(first + 1)?, size(first + count)?, 1, size(count)?);
        // SAFETY: `data` holds the `count` values of the memory hyperslab
        // 1..=count of the node's own type `kind`; the file hyperslab has
        // as many.
        check(unsafe {
            cgio_read_data(
                self.cgio, id, &start, &end, &one, 1, &all, &one, &all, &one, data,
            )
        })
    }

    /// Writes a node under `parent`: `data` holds the bytes of the values
    /// of type `kind` over `dims`, or nothing (the array declared, none
    /// of it stored).
    pub fn write_node(
        &self,
        parent: NodeId,
        (name, label, kind): (&str, &str, &str),
        dims: &[CgSize],
        data: &[u8],
    ) -> Result<NodeId, String> {
        let width = match kind {
            "MT" => 0,
            "C1" | "B1" => 1,
            "I4" | "U4" | "R4" => 4,
            "I8" | "U8" | "R8" | "X4" => 8,
            "X8" => 16,
            _ => return Err(format!("data type {kind:?}")),
        };
        let values: usize = dims.iter().map(|&d| d.max(0) as usize).product();
        if dims.len() > MAX_DIMENSIONS || !(data.is_empty() || data.len() == values * width) {
            return Err(format!("{} bytes over dimensions {dims:?}", data.len()));
        }
        let (name, label, kind) = (c_name(name)?, c_name(label)?, c_name(kind)?);
        let mut id = 0.0;
        // SAFETY: valid C strings, `dims.len()` dimensions, and data that
        // spans them (checked above), or none; an out-pointer.
        unsafe {
            check(cgio_create_node(self.cgio, parent, name.as_ptr(), &mut id))?;
            check(cgio_set_label(self.cgio, id, label.as_ptr()))?;
            if width > 0 {
                check(cgio_set_dimensions(
                    self.cgio,
                    id,
                    kind.as_ptr(),
                    dims.len() as c_int,
                    dims.as_ptr(),
                ))?;
            }
            if width > 0 && !data.is_empty() {
                check(cgio_write_all_data(self.cgio, id, data.as_ptr().cast()))?;
            }
        }
        Ok(id)
    }

    /// Writes a link `name` under `parent` to node `target` of `file`
    /// (empty: this file).
    pub fn write_link(
        &self,
        parent: NodeId,
        name: &str,
        (file, target): (&str, &str),
    ) -> Result<NodeId, String> {
        let (name, file, target) = (c_name(name)?, c_name(file)?, c_name(target)?);
        let mut id = 0.0;
        // SAFETY: valid C strings and an out-pointer.
        check(unsafe {
            cgio_create_link(
                self.cgio,
                parent,
                name.as_ptr(),
                file.as_ptr(),
                target.as_ptr(),
                &mut id,
            )
        })?;
        Ok(id)
    }
}

impl Drop for Tree {
    fn drop(&mut self) {
        // SAFETY: an open file of this process; a failure while closing
        // leaves nothing to report.
        unsafe { cgio_close_file(self.cgio) };
    }
}

/// `Ok` for 0, else the layer's message.
pub(super) fn check(code: c_int) -> Result<(), String> {
    if code == 0 {
        return Ok(());
    }
    // `CGIO_MAX_ERROR_LENGTH` is 80: twice that, zeroed.
    let mut message = [0 as c_char; 161];
    // SAFETY: a buffer longer than the layer's longest message.
    unsafe { cgio_error_message(message.as_mut_ptr()) };
    message[160] = 0;
    // SAFETY: zero-terminated above.
    let text = unsafe { CStr::from_ptr(message.as_ptr()) };
    Err(text.to_string_lossy().trim().to_string())
}
