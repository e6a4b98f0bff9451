//! The HDF5 library under the CGNS library, reached through the CGNS
//! library's own link to it (`dladdr` of `cg_open`, then `dlsym` in that
//! library and what it links: no HDF5 headers or link of verbss's own):
//! what an HDF5 CGNS file's groups hold, read before the node layer trusts
//! it. The node layer reads a node's `name`, `label` and `type` attributes
//! with their stored size into buffers of 33 and 3 bytes, its `flags` into
//! one `int`, and the dimensions of its data into 12 places: a longer
//! attribute or a higher rank overflows them.
//!
//! The HDF5 calls used are those of HDF5 1.8 to 1.14 with the same
//! signatures; `H5Lget_info2` is preferred to `H5Lget_info` where both
//! exist, both starting their result with the link's type.

use std::ffi::{c_char, c_int, c_uint, c_void, CStr};
use std::path::Path;
use std::sync::{MutexGuard, OnceLock};

use super::{c_name, LIBRARY};

/// HDF5's `hid_t` (64 bits since 1.10).
type Hid = i64;

/// `H5P_DEFAULT`, `H5E_DEFAULT`, `H5F_ACC_RDONLY`.
const DEFAULT: Hid = 0;
const READ_ONLY: c_uint = 0;
/// `H5I_GROUP`, `H5I_DATASET`.
const GROUP: c_int = 2;
const DATASET: c_int = 5;
/// `H5T_STRING`.
const STRING: c_int = 3;
/// `H5L_TYPE_HARD`.
const HARD: c_int = 0;

#[repr(C)]
struct DlInfo {
    fname: *const c_char,
    fbase: *mut c_void,
    sname: *const c_char,
    saddr: *mut c_void,
}

extern "C" {
    fn dladdr(addr: *const c_void, info: *mut DlInfo) -> c_int;
    fn dlopen(name: *const c_char, flags: c_int) -> *mut c_void;
    fn dlsym(handle: *mut c_void, name: *const c_char) -> *mut c_void;
}

/// `H5L_iterate_t` (`H5L_iterate2_t`): the group, a link's name, its
/// `H5L_info_t` (`H5L_info2_t`, both starting with the link's type), the
/// caller's data.
type Visit = unsafe extern "C" fn(Hid, *const c_char, *const c_int, *mut c_void) -> c_int;

/// What [`visit`] gathers of a group's links.
struct Links {
    /// Each link's name and whether it is a hard link.
    found: Vec<(String, bool)>,
    most: usize,
    /// Why the iteration stopped early, if it did.
    stop: Option<String>,
}

/// Gathers one link into the [`Links`] behind `data`; stops (returns 1)
/// past `most` links or at a name longer than 1024 bytes.
unsafe extern "C" fn visit(
    _: Hid,
    name: *const c_char,
    info: *const c_int,
    data: *mut c_void,
) -> c_int {
    // SAFETY: `data` is the `Links` that `Group::links` passed, `name` a
    // zero-terminated string and `info` a link info of HDF5's, valid for
    // this call.
    let (links, name, kind) = unsafe { (&mut *data.cast::<Links>(), CStr::from_ptr(name), *info) };
    let len = name.to_bytes().len();
    if links.found.len() == links.most {
        links.stop = Some(format!("more than {} children", links.most));
        return 1;
    }
    if len > 1024 {
        links.stop = Some(format!("a link name of {len} bytes (at most 1024)"));
        return 1;
    }
    links
        .found
        .push((name.to_string_lossy().into_owned(), kind == HARD));
    0
}

/// The HDF5 functions used.
struct Api {
    set_auto: unsafe extern "C" fn(Hid, *const c_void, *mut c_void) -> c_int,
    is_hdf5: unsafe extern "C" fn(*const c_char) -> c_int,
    fopen: unsafe extern "C" fn(*const c_char, c_uint, Hid) -> Hid,
    fclose: unsafe extern "C" fn(Hid) -> c_int,
    oopen: unsafe extern "C" fn(Hid, *const c_char, Hid) -> Hid,
    oclose: unsafe extern "C" fn(Hid) -> c_int,
    id_type: unsafe extern "C" fn(Hid) -> c_int,
    iterate: unsafe extern "C" fn(Hid, c_int, c_int, *mut u64, Visit, *mut c_void) -> c_int,
    aexists: unsafe extern "C" fn(Hid, *const c_char) -> c_int,
    aopen: unsafe extern "C" fn(Hid, *const c_char, Hid) -> Hid,
    aclose: unsafe extern "C" fn(Hid) -> c_int,
    atype: unsafe extern "C" fn(Hid) -> Hid,
    aspace: unsafe extern "C" fn(Hid) -> Hid,
    tclass: unsafe extern "C" fn(Hid) -> c_int,
    tsize: unsafe extern "C" fn(Hid) -> usize,
    tclose: unsafe extern "C" fn(Hid) -> c_int,
    dspace: unsafe extern "C" fn(Hid) -> Hid,
    points: unsafe extern "C" fn(Hid) -> i64,
    rank: unsafe extern "C" fn(Hid) -> c_int,
    sclose: unsafe extern "C" fn(Hid) -> c_int,
}

/// The functions, found once.
fn api() -> Result<&'static Api, String> {
    static API: OnceLock<Result<Api, String>> = OnceLock::new();
    API.get_or_init(load).as_ref().map_err(Clone::clone)
}

/// Finds the functions in the CGNS library and what it links. Each pointer
/// is transmuted to the type of the field it is stored in.
#[allow(clippy::missing_transmute_annotations)]
fn load() -> Result<Api, String> {
    let mut info = DlInfo {
        fname: std::ptr::null(),
        fbase: std::ptr::null_mut(),
        sname: std::ptr::null(),
        saddr: std::ptr::null_mut(),
    };
    // SAFETY: the address of a function of the CGNS library and an
    // out-pointer; `dlopen` with RTLD_NOW | RTLD_NOLOAD only finds a
    // library already loaded (else the program itself, with its links).
    let handle = unsafe {
        let found = dladdr(super::sys::cg_open as *const c_void, &mut info) != 0;
        let library = if found && !info.fname.is_null() {
            dlopen(info.fname, 2 | 4)
        } else {
            std::ptr::null_mut()
        };
        if library.is_null() {
            dlopen(std::ptr::null(), 2)
        } else {
            library
        }
    };
    if handle.is_null() {
        return Err("the CGNS library's HDF5 library cannot be found".into());
    }
    let find = |names: &[&str]| -> Result<*mut c_void, String> {
        for name in names {
            let c = c_name(name)?;
            // SAFETY: a handle of a loaded library and a valid C string.
            let p = unsafe { dlsym(handle, c.as_ptr()) };
            if !p.is_null() {
                return Ok(p);
            }
        }
        Err(format!("the HDF5 function {} cannot be found", names[0]))
    };
    macro_rules! function {
        ($($name:literal),+) => {{
            let p = find(&[$($name),+])?;
            // SAFETY: the HDF5 function of that name, of the signature of
            // the field it is stored in (HDF5 1.8 to 1.14).
            unsafe { std::mem::transmute::<*mut c_void, _>(p) }
        }};
    }
    let api = Api {
        set_auto: function!("H5Eset_auto2"),
        is_hdf5: function!("H5Fis_hdf5"),
        fopen: function!("H5Fopen"),
        fclose: function!("H5Fclose"),
        oopen: function!("H5Oopen"),
        oclose: function!("H5Oclose"),
        id_type: function!("H5Iget_type"),
        iterate: function!("H5Literate2", "H5Literate"),
        aexists: function!("H5Aexists"),
        aopen: function!("H5Aopen"),
        aclose: function!("H5Aclose"),
        atype: function!("H5Aget_type"),
        aspace: function!("H5Aget_space"),
        tclass: function!("H5Tget_class"),
        tsize: function!("H5Tget_size"),
        tclose: function!("H5Tclose"),
        dspace: function!("H5Dget_space"),
        points: function!("H5Sget_simple_extent_npoints"),
        rank: function!("H5Sget_simple_extent_ndims"),
        sclose: function!("H5Sclose"),
    };
    // SAFETY: turns HDF5's printing of its error stack off (no function).
    unsafe { (api.set_auto)(DEFAULT, std::ptr::null(), std::ptr::null_mut()) };
    Ok(api)
}

/// An attribute: whether it is a string, the bytes of one value, how many
/// values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Attribute {
    pub string: bool,
    pub size: usize,
    pub values: i64,
}

/// What a link of a group leads to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Object {
    Group,
    Dataset {
        /// Its rank.
        rank: i32,
    },
    /// A soft or external link (not followed), or another kind of object.
    Other,
}

/// An HDF5 file open for reading; closed when dropped, with the library's
/// lock held.
pub struct H5File {
    api: &'static Api,
    file: Hid,
    _lock: MutexGuard<'static, ()>,
}

/// An open group (or the file's root).
pub struct Group<'a> {
    api: &'a Api,
    id: Hid,
}

impl H5File {
    /// Opens `path`, when it is an HDF5 file (`None`: it is not, say ADF).
    pub fn open(path: &Path) -> Result<Option<H5File>, String> {
        let api = api()?;
        let lock = LIBRARY.lock().unwrap_or_else(|p| p.into_inner());
        let name = c_name(&path.to_string_lossy())?;
        // SAFETY: a valid C string.
        if unsafe { (api.is_hdf5)(name.as_ptr()) } <= 0 {
            return Ok(None);
        }
        // SAFETY: a valid C string and flags.
        let file = unsafe { (api.fopen)(name.as_ptr(), READ_ONLY, DEFAULT) };
        if file < 0 {
            return Err("HDF5 cannot open it (is another process writing it?)".into());
        }
        super::keep_from_children(path);
        Ok(Some(H5File {
            api,
            file,
            _lock: lock,
        }))
    }

    /// The root group.
    pub fn root(&self) -> Result<Group<'_>, String> {
        let dot = c_name(".")?;
        // SAFETY: an open file and a valid C string.
        let id = unsafe { (self.api.oopen)(self.file, dot.as_ptr(), DEFAULT) };
        if id < 0 {
            return Err("HDF5 cannot open its root group".into());
        }
        Ok(Group { api: self.api, id })
    }
}

impl Drop for H5File {
    fn drop(&mut self) {
        // SAFETY: an open file; its groups were closed before (they borrow it).
        unsafe { (self.api.fclose)(self.file) };
    }
}

impl<'a> Group<'a> {
    /// The group's links (name, whether hard), in the order of their
    /// names, or why not: more than `most`, or a name over 1024 bytes.
    /// One pass over the group (`H5Literate`): linear in its size.
    pub fn links(&self, most: usize) -> Result<Vec<(String, bool)>, String> {
        let mut links = Links {
            found: Vec::new(),
            most,
            stop: None,
        };
        let mut at = 0u64;
        // SAFETY: an open group, the name index in increasing order, an
        // out-pointer, and `visit` with the `Links` it expects.
        let code = unsafe {
            (self.api.iterate)(
                self.id,
                0,
                0,
                &mut at,
                visit,
                (&mut links as *mut Links).cast(),
            )
        };
        match links.stop {
            Some(why) => Err(why),
            None if code < 0 => Err("HDF5 cannot list a group".into()),
            None => Ok(links.found),
        }
    }

    /// What the link `name` leads to; a soft or external link (`hard`
    /// false) is not followed.
    pub fn object(&self, name: &str, hard: bool) -> Result<Object, String> {
        if !hard {
            return Ok(Object::Other);
        }
        let c = c_name(name)?;
        // SAFETY: an open group and a hard link's name.
        let id = unsafe { (self.api.oopen)(self.id, c.as_ptr(), DEFAULT) };
        if id < 0 {
            return Err(format!("HDF5 cannot open {name:?}"));
        }
        // SAFETY: an open object; its dataspace closed after use.
        let object = unsafe {
            match (self.api.id_type)(id) {
                GROUP => Object::Group,
                DATASET => {
                    let space = (self.api.dspace)(id);
                    let rank = (self.api.rank)(space);
                    (self.api.sclose)(space);
                    Object::Dataset { rank }
                }
                _ => Object::Other,
            }
        };
        // SAFETY: opened above.
        unsafe { (self.api.oclose)(id) };
        Ok(object)
    }

    /// The group `name` (a hard link to a group, see [`Group::object`]).
    pub fn group(&self, name: &str) -> Result<Group<'a>, String> {
        let c = c_name(name)?;
        // SAFETY: an open group and a valid C string.
        let id = unsafe { (self.api.oopen)(self.id, c.as_ptr(), DEFAULT) };
        if id < 0 {
            return Err(format!("HDF5 cannot open {name:?}"));
        }
        Ok(Group { api: self.api, id })
    }

    /// The attribute `name` of the group, if it has one.
    pub fn attribute(&self, name: &str) -> Result<Option<Attribute>, String> {
        let c = c_name(name)?;
        // SAFETY: an open group and a valid C string.
        match unsafe { (self.api.aexists)(self.id, c.as_ptr()) } {
            0 => return Ok(None),
            n if n < 0 => return Err(format!("HDF5 cannot read the attribute {name:?}")),
            _ => {}
        }
        // SAFETY: an existing attribute; its type and dataspace closed after use.
        unsafe {
            let a = (self.api.aopen)(self.id, c.as_ptr(), DEFAULT);
            if a < 0 {
                return Err(format!("HDF5 cannot open the attribute {name:?}"));
            }
            let (t, s) = ((self.api.atype)(a), (self.api.aspace)(a));
            let attribute = Attribute {
                string: (self.api.tclass)(t) == STRING,
                size: (self.api.tsize)(t),
                values: (self.api.points)(s),
            };
            (self.api.tclose)(t);
            (self.api.sclose)(s);
            (self.api.aclose)(a);
            Ok(Some(attribute))
        }
    }
}

impl Drop for Group<'_> {
    fn drop(&mut self) {
        // SAFETY: an open group.
        unsafe { (self.api.oclose)(self.id) };
    }
}
