//! The crate's only `unsafe` code: safe wrappers of the CGNS mid-level
//! library calls that the reader and the writers use, and of the node layer
//! under it ([`Tree`]).
//!
//! Every wrapper hands the library buffers sized from the counts the library
//! itself reported, or from the stored array's own dimensions where the
//! library copies the whole array (a boundary condition's point set). Some
//! buffers have a fixed size that only a well-formed tree respects: names
//! of 33 bytes (the node layer cuts names at 32 characters), family names
//! of 1024 (at most 32 characters), 9 zone sizes and 3 normal indices (an
//! index dimension of at most 3); the reader checks the tree for these
//! before the library opens the file (`io::cgns::check`). The library keeps
//! global state (open files, the last error, the `cg_gopath` position) and
//! is not thread-safe: a [`File`] or [`Tree`] holds a process-wide lock
//! from opening to closing.
#![allow(unsafe_code)]

use std::ffi::{c_char, c_int, c_void, CStr, CString};
use std::path::Path;
use std::sync::{Mutex, MutexGuard};

/// The library's `cgsize_t`: 64 bits wide when it was built so.
#[cfg(cgns_size64)]
pub type CgSize = i64;
/// The library's `cgsize_t`: 64 bits wide when it was built so.
#[cfg(not(cgns_size64))]
pub type CgSize = i32;

/// `CG_MODE_READ`, `CG_MODE_WRITE`, `CG_MODE_MODIFY`.
#[derive(Debug, Clone, Copy)]
pub enum Mode {
    Read = 0,
    Write = 1,
    Modify = 2,
}

/// `ZoneType_t` `Structured`.
pub const STRUCTURED: c_int = 2;
/// `ZoneType_t` `Unstructured`.
pub const UNSTRUCTURED: c_int = 3;
/// `DataType_t` `RealSingle`.
pub const REAL_SINGLE: c_int = 3;
/// `DataType_t` `RealDouble`.
pub const REAL_DOUBLE: c_int = 4;
/// `ElementType_t` `MIXED`.
pub const MIXED: c_int = 20;
/// `ElementType_t` `NGON_n`.
pub const NGON_N: c_int = 22;
/// `ElementType_t` `NFACE_n`.
pub const NFACE_N: c_int = 23;
/// `BCType_t` `FamilySpecified`.
pub const FAMILY_SPECIFIED: c_int = 25;
/// `PointSetType_t` `PointList`.
pub const POINT_LIST: c_int = 2;
/// `PointSetType_t` `PointRange`.
pub const POINT_RANGE: c_int = 4;
/// `PointSetType_t` `ElementRange`.
pub const ELEMENT_RANGE: c_int = 6;
/// `PointSetType_t` `ElementList`.
pub const ELEMENT_LIST: c_int = 7;
/// `GridLocation_t` `Vertex`.
pub const VERTEX: c_int = 2;
/// `GridLocation_t` `CellCenter` (Gmsh writes its boundary conditions
/// there, naming the boundary elements).
pub const CELL_CENTER: c_int = 3;
/// `GridLocation_t` `FaceCenter`.
pub const FACE_CENTER: c_int = 4;
/// `GridLocation_t` `EdgeCenter`.
pub const EDGE_CENTER: c_int = 8;

/// `CG_NODE_NOT_FOUND`.
const NODE_NOT_FOUND: c_int = 2;

/// Marks the descriptors this process holds on `path` close-on-exec.
///
/// HDF5 opens a file without `O_CLOEXEC` and locks it (`flock`). A child
/// process that another thread starts while the file is open inherits the
/// descriptor, and with it the lock, which then outlives the file's close
/// here: the next open of that file fails until the child exits. Called
/// right after each open, with the library's lock held.
#[cfg(target_os = "linux")]
fn keep_from_children(path: &Path) {
    extern "C" {
        fn fcntl(fd: c_int, cmd: c_int, ...) -> c_int;
    }
    const F_GETFD: c_int = 1;
    const F_SETFD: c_int = 2;
    const FD_CLOEXEC: c_int = 1;
    let (Ok(file), Ok(descriptors)) = (path.canonicalize(), std::fs::read_dir("/proc/self/fd"))
    else {
        return;
    };
    for entry in descriptors.flatten() {
        let fd = entry
            .file_name()
            .to_str()
            .and_then(|n| n.parse::<c_int>().ok());
        if let (Some(fd), Ok(target)) = (fd, std::fs::read_link(entry.path())) {
            if target == file {
                // SAFETY: `fcntl` on a descriptor of this process, which
                // only reads and sets its flags.
                unsafe {
                    let flags = fcntl(fd, F_GETFD);
                    if flags >= 0 {
                        fcntl(fd, F_SETFD, flags | FD_CLOEXEC);
                    }
                }
            }
        }
    }
}

/// Elsewhere there is no `/proc/self/fd` to find the descriptors in.
#[cfg(not(target_os = "linux"))]
fn keep_from_children(_path: &Path) {}

mod boco;
mod hdf5;
mod sys;
mod tree;

pub use hdf5::{Attribute, Group, H5File, Object};
use sys::*;
pub use tree::{NodeHead, NodeId, Tree};

/// The lock every open [`File`] holds.
static LIBRARY: Mutex<()> = Mutex::new(());

/// A CGNS name buffer: 32 characters and the terminating zero.
type NameBuf = [c_char; 33];

/// A buffer for a family name, which CGNS 4 may write as a path of names.
type FamilyBuf = [c_char; 1024];

/// The text of a name buffer the library filled.
fn name_of<const N: usize>(buf: &[c_char; N]) -> String {
    // SAFETY: the library wrote a zero-terminated string into the buffer,
    // and the last byte is zero from its initialisation.
    unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

/// A name as the library takes it; `None` when it holds a zero byte.
fn c_name(name: &str) -> Result<CString, String> {
    CString::new(name).map_err(|_| format!("the name {name:?} holds a zero byte"))
}

/// An element section's header (`cg_section_read`).
#[derive(Debug)]
pub struct SectionInfo {
    pub name: String,
    pub kind: c_int,
    pub start: CgSize,
    pub end: CgSize,
}

/// An open CGNS file; closed when dropped.
pub struct File {
    id: c_int,
    /// Whether `cg_close` is still to be called.
    open: bool,
    _lock: MutexGuard<'static, ()>,
}

impl File {
    /// Opens `path` (or creates it, in [`Mode::Write`]).
    pub fn open(path: &Path, mode: Mode) -> Result<File, String> {
        let lock = LIBRARY.lock().unwrap_or_else(|p| p.into_inner());
        let name = c_name(&path.to_string_lossy())?;
        let mut id = 0;
        // SAFETY: a valid C string and an out-pointer.
        check(unsafe { cg_open(name.as_ptr(), mode as c_int, &mut id) })?;
        keep_from_children(path);
        Ok(File {
            id,
            open: true,
            _lock: lock,
        })
    }

    /// Closes the file, reporting the library's error (writes are flushed here).
    pub fn close(mut self) -> Result<(), String> {
        self.open = false;
        // SAFETY: `id` is an open file of this process.
        check(unsafe { cg_close(self.id) })
    }

    /// The number of bases.
    pub fn bases(&self) -> Result<c_int, String> {
        let mut n = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_nbases(self.id, &mut n) })?;
        Ok(n)
    }

    /// Base `b`'s name, cell dimension and physical dimension.
    pub fn base(&self, b: c_int) -> Result<(String, c_int, c_int), String> {
        let mut name: NameBuf = [0; 33];
        let (mut cell, mut phys) = (0, 0);
        // SAFETY: a 33-byte name buffer and out-pointers.
        check(unsafe { cg_base_read(self.id, b, name.as_mut_ptr(), &mut cell, &mut phys) })?;
        Ok((name_of(&name), cell, phys))
    }

    /// Writes a base; returns its index.
    pub fn write_base(&self, name: &str, cell: c_int, phys: c_int) -> Result<c_int, String> {
        let name = c_name(name)?;
        let mut b = 0;
        // SAFETY: a valid C string and an out-pointer.
        check(unsafe { cg_base_write(self.id, name.as_ptr(), cell, phys, &mut b) })?;
        Ok(b)
    }

    /// The number of zones of base `b`.
    pub fn zones(&self, b: c_int) -> Result<c_int, String> {
        let mut n = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_nzones(self.id, b, &mut n) })?;
        Ok(n)
    }

    /// Zone `z`'s type (`ZoneType_t`).
    pub fn zone_type(&self, b: c_int, z: c_int) -> Result<c_int, String> {
        let mut kind = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_zone_type(self.id, b, z, &mut kind) })?;
        Ok(kind)
    }

    /// An unstructured zone's name and sizes: vertices, cells.
    pub fn zone(&self, b: c_int, z: c_int) -> Result<(String, CgSize, CgSize), String> {
        let mut name: NameBuf = [0; 33];
        // Nine entries: what a 3D structured zone fills, the most there is.
        let mut size: [CgSize; 9] = [0; 9];
        // SAFETY: a 33-byte name buffer and 9 sizes: three per index
        // dimension, which the tree's check holds to at most 3.
        check(unsafe { cg_zone_read(self.id, b, z, name.as_mut_ptr(), size.as_mut_ptr()) })?;
        Ok((name_of(&name), size[0], size[1]))
    }

    /// Writes a zone of type `kind` ([`UNSTRUCTURED`]: `size` is the
    /// vertex count, the cell count and 0; [`STRUCTURED`]: three numbers per
    /// index dimension).
    pub fn write_zone(
        &self,
        b: c_int,
        name: &str,
        kind: c_int,
        size: &[CgSize],
    ) -> Result<c_int, String> {
        let name = c_name(name)?;
        let mut z = 0;
        // SAFETY: a valid C string, the sizes the library reads for the
        // base's dimension (the callers pass them all) and an out-pointer.
        check(unsafe { cg_zone_write(self.id, b, name.as_ptr(), size.as_ptr(), kind, &mut z) })?;
        Ok(z)
    }

    /// The names and data types of the zone's coordinate arrays.
    pub fn coordinates(&self, b: c_int, z: c_int) -> Result<Vec<(String, c_int)>, String> {
        let mut n = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_ncoords(self.id, b, z, &mut n) })?;
        (1..=n)
            .map(|c| {
                let mut name: NameBuf = [0; 33];
                let mut kind = 0;
                // SAFETY: a 33-byte name buffer and an out-pointer.
                check(unsafe { cg_coord_info(self.id, b, z, c, &mut kind, name.as_mut_ptr()) })?;
                Ok((name_of(&name), kind))
            })
            .collect()
    }

    /// Reads the values of the coordinate array `name` at the `count`
    /// vertices from `first` (numbered from 0), as doubles (none when
    /// `count` is 0, which the library would refuse).
    pub fn read_coordinate(
        &self,
        b: c_int,
        z: c_int,
        name: &str,
        (first, count): (usize, usize),
    ) -> Result<Vec<f64>, String> {
        let c = c_name(name)?;
        let mut data = vec![0.0f64; count];
        if count == 0 {
            return Ok(data);
        }
        let (min, max): (CgSize, CgSize) = (to_size(first + 1)?, to_size(first + count)?);
        // SAFETY: the buffer holds the `count` values of the range min..=max.
        check(unsafe {
            cg_coord_read(
                self.id,
                b,
                z,
                c.as_ptr(),
                REAL_DOUBLE,
                &min,
                &max,
                data.as_mut_ptr().cast(),
            )
        })?;
        Ok(data)
    }

    /// Writes a new coordinate array `name` in double precision.
    pub fn write_coordinate(
        &self,
        b: c_int,
        z: c_int,
        name: &str,
        data: &[f64],
    ) -> Result<(), String> {
        let c = c_name(name)?;
        let mut index = 0;
        // SAFETY: the zone was written with `data.len()` vertices.
        check(unsafe {
            cg_coord_write(
                self.id,
                b,
                z,
                REAL_DOUBLE,
                c.as_ptr(),
                data.as_ptr().cast(),
                &mut index,
            )
        })
    }

    /// Overwrites the values of the existing coordinate array `name`, kept
    /// in its data type `kind` ([`REAL_SINGLE`] or [`REAL_DOUBLE`]).
    pub fn overwrite_coordinate(
        &self,
        b: c_int,
        z: c_int,
        name: &str,
        kind: c_int,
        data: &[f64],
    ) -> Result<(), String> {
        let c = c_name(name)?;
        let (min, max): (CgSize, CgSize) = (1, to_size(data.len())?);
        let singles: Vec<f32>;
        let values: *const c_void = if kind == REAL_SINGLE {
            singles = data.iter().map(|&v| v as f32).collect();
            singles.as_ptr().cast()
        } else {
            data.as_ptr().cast()
        };
        let mut index = 0;
        // SAFETY: `values` holds the `data.len()` values of the range, of type `kind`.
        check(unsafe {
            cg_coord_partial_write(
                self.id,
                b,
                z,
                kind,
                c.as_ptr(),
                &min,
                &max,
                values,
                &mut index,
            )
        })
    }

    /// The number of element sections of the zone.
    pub fn sections(&self, b: c_int, z: c_int) -> Result<c_int, String> {
        let mut n = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_nsections(self.id, b, z, &mut n) })?;
        Ok(n)
    }

    /// Section `s`'s header.
    pub fn section(&self, b: c_int, z: c_int, s: c_int) -> Result<SectionInfo, String> {
        let mut name: NameBuf = [0; 33];
        let (mut kind, mut start, mut end, mut nbndry, mut parents) = (0, 0, 0, 0, 0);
        // SAFETY: a 33-byte name buffer and out-pointers.
        check(unsafe {
            cg_section_read(
                self.id,
                b,
                z,
                s,
                name.as_mut_ptr(),
                &mut kind,
                &mut start,
                &mut end,
                &mut nbndry,
                &mut parents,
            )
        })?;
        Ok(SectionInfo {
            name: name_of(&name),
            kind,
            start,
            end,
        })
    }

    /// The connectivity of elements `start..=end` of section `index`, of
    /// element type `kind`, as stored (for `MIXED`, each element's type
    /// before its nodes): the whole section or a block of it.
    pub fn elements(
        &self,
        at: (c_int, c_int, c_int),
        kind: c_int,
        range: (CgSize, CgSize),
    ) -> Result<Vec<CgSize>, String> {
        Ok(self.elements_and_offsets(at, kind, range)?.0)
    }

    /// [`File::elements`] and, for `MIXED`, `NGON_n` and `NFACE_n`, where each
    /// element starts in the connectivity (`end − start + 2` offsets from
    /// 0; empty for the other types).
    pub fn elements_and_offsets(
        &self,
        (b, z, index): (c_int, c_int, c_int),
        kind: c_int,
        (start, end): (CgSize, CgSize),
    ) -> Result<(Vec<CgSize>, Vec<CgSize>), String> {
        let count = usize::try_from(end - start + 1)
            .map_err(|_| format!("the element range {start}..{end} is empty"))?;
        let mut size: CgSize = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_ElementPartialSize(self.id, b, z, index, start, end, &mut size) })?;
        let mut nodes: Vec<CgSize> =
            vec![0; usize::try_from(size).map_err(|_| format!("{size} connectivity entries"))?];
        let mut offsets: Vec<CgSize> = Vec::new();
        // No parent data asked for (a null pointer).
        let code = if matches!(kind, MIXED | NGON_N | NFACE_N) {
            offsets.resize(count + 1, 0);
            // SAFETY: buffers of the data size and count + 1 offsets; the
            // tree's check made sure every element type the library steps
            // through is one it knows and that the offsets agree.
            unsafe {
                cg_poly_elements_partial_read(
                    self.id,
                    b,
                    z,
                    index,
                    start,
                    end,
                    nodes.as_mut_ptr(),
                    offsets.as_mut_ptr(),
                    std::ptr::null_mut(),
                )
            }
        } else {
            // SAFETY: a buffer of the data size.
            unsafe {
                cg_elements_partial_read(
                    self.id,
                    b,
                    z,
                    index,
                    start,
                    end,
                    nodes.as_mut_ptr(),
                    std::ptr::null_mut(),
                )
            }
        };
        check(code)?;
        Ok((nodes, offsets))
    }

    /// Writes an element section of one `kind` numbered `start..=end`; for
    /// `MIXED`, `nodes` gives each element's type before its nodes (for
    /// `NGON_n`/`NFACE_n`, its node count) and `offsets` where each element
    /// starts in `nodes`.
    #[allow(clippy::too_many_arguments)]
    pub fn write_section(
        &self,
        b: c_int,
        z: c_int,
        name: &str,
        kind: c_int,
        (start, end): (CgSize, CgSize),
        nodes: &[CgSize],
        offsets: &[CgSize],
    ) -> Result<(), String> {
        let c = c_name(name)?;
        let mut s = 0;
        // SAFETY: `nodes` (and `offsets` for MIXED) describe the `end - start + 1` elements.
        let code = unsafe {
            if matches!(kind, MIXED | NGON_N | NFACE_N) {
                cg_poly_section_write(
                    self.id,
                    b,
                    z,
                    c.as_ptr(),
                    kind,
                    start,
                    end,
                    0,
                    nodes.as_ptr(),
                    offsets.as_ptr(),
                    &mut s,
                )
            } else {
                cg_section_write(
                    self.id,
                    b,
                    z,
                    c.as_ptr(),
                    kind,
                    start,
                    end,
                    0,
                    nodes.as_ptr(),
                    &mut s,
                )
            }
        };
        check(code)
    }
}

impl Drop for File {
    fn drop(&mut self) {
        if self.open {
            // SAFETY: `id` is an open file of this process; an error while
            // closing a file that already failed leaves nothing to report.
            unsafe { cg_close(self.id) };
        }
    }
}

/// A count as the library's size type.
pub fn to_size(n: usize) -> Result<CgSize, String> {
    CgSize::try_from(n).map_err(|_| format!("{n} is more than the CGNS library's size type holds"))
}

/// `Ok` for `CG_OK`, else the library's message.
fn check(code: c_int) -> Result<(), String> {
    if code == 0 {
        return Ok(());
    }
    // SAFETY: the library returns a static zero-terminated message.
    let message = unsafe { CStr::from_ptr(cg_get_error()) };
    Err(message.to_string_lossy().trim().to_string())
}
