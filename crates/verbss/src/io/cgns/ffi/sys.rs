//! The CGNS mid-level library's functions that verbss calls, as declared
//! in `cgnslib.h` (enums as `c_int`, `cgsize_t` as [`CgSize`]).

use std::ffi::{c_char, c_int, c_void};

use super::CgSize;

#[link(name = "cgns")]
extern "C" {
    pub fn cg_open(name: *const c_char, mode: c_int, file: *mut c_int) -> c_int;
    pub fn cg_close(file: c_int) -> c_int;
    pub fn cg_get_error() -> *const c_char;
    pub fn cg_nbases(file: c_int, n: *mut c_int) -> c_int;
    pub fn cg_base_read(
        f: c_int,
        b: c_int,
        name: *mut c_char,
        cell: *mut c_int,
        phys: *mut c_int,
    ) -> c_int;
    pub fn cg_base_write(
        f: c_int,
        name: *const c_char,
        cell: c_int,
        phys: c_int,
        b: *mut c_int,
    ) -> c_int;
    pub fn cg_nzones(f: c_int, b: c_int, n: *mut c_int) -> c_int;
    pub fn cg_zone_type(f: c_int, b: c_int, z: c_int, kind: *mut c_int) -> c_int;
    pub fn cg_zone_read(
        f: c_int,
        b: c_int,
        z: c_int,
        name: *mut c_char,
        size: *mut CgSize,
    ) -> c_int;
    pub fn cg_zone_write(
        f: c_int,
        b: c_int,
        name: *const c_char,
        size: *const CgSize,
        kind: c_int,
        z: *mut c_int,
    ) -> c_int;
    pub fn cg_ncoords(f: c_int, b: c_int, z: c_int, n: *mut c_int) -> c_int;
    pub fn cg_coord_info(
        f: c_int,
        b: c_int,
        z: c_int,
        c: c_int,
        kind: *mut c_int,
        name: *mut c_char,
    ) -> c_int;
    pub fn cg_coord_read(
        f: c_int,
        b: c_int,
        z: c_int,
        name: *const c_char,
        kind: c_int,
        min: *const CgSize,
        max: *const CgSize,
        data: *mut c_void,
    ) -> c_int;
    pub fn cg_coord_write(
        f: c_int,
        b: c_int,
        z: c_int,
        kind: c_int,
        name: *const c_char,
        data: *const c_void,
        c: *mut c_int,
    ) -> c_int;
    pub fn cg_coord_partial_write(
        f: c_int,
        b: c_int,
        z: c_int,
        kind: c_int,
        name: *const c_char,
        min: *const CgSize,
        max: *const CgSize,
        data: *const c_void,
        c: *mut c_int,
    ) -> c_int;
    pub fn cg_nsections(f: c_int, b: c_int, z: c_int, n: *mut c_int) -> c_int;
    pub fn cg_section_read(
        f: c_int,
        b: c_int,
        z: c_int,
        s: c_int,
        name: *mut c_char,
        kind: *mut c_int,
        start: *mut CgSize,
        end: *mut CgSize,
        nbndry: *mut c_int,
        parent_flag: *mut c_int,
    ) -> c_int;
    pub fn cg_ElementPartialSize(
        f: c_int,
        b: c_int,
        z: c_int,
        s: c_int,
        start: CgSize,
        end: CgSize,
        size: *mut CgSize,
    ) -> c_int;
    pub fn cg_elements_partial_read(
        f: c_int,
        b: c_int,
        z: c_int,
        s: c_int,
        start: CgSize,
        end: CgSize,
        nodes: *mut CgSize,
        parents: *mut CgSize,
    ) -> c_int;
    pub fn cg_poly_elements_partial_read(
        f: c_int,
        b: c_int,
        z: c_int,
        s: c_int,
        start: CgSize,
        end: CgSize,
        nodes: *mut CgSize,
        offsets: *mut CgSize,
        parents: *mut CgSize,
    ) -> c_int;
    pub fn cg_section_write(
        f: c_int,
        b: c_int,
        z: c_int,
        name: *const c_char,
        kind: c_int,
        start: CgSize,
        end: CgSize,
        nbndry: c_int,
        nodes: *const CgSize,
        s: *mut c_int,
    ) -> c_int;
    pub fn cg_poly_section_write(
        f: c_int,
        b: c_int,
        z: c_int,
        name: *const c_char,
        kind: c_int,
        start: CgSize,
        end: CgSize,
        nbndry: c_int,
        nodes: *const CgSize,
        offsets: *const CgSize,
        s: *mut c_int,
    ) -> c_int;
    pub fn cg_nbocos(f: c_int, b: c_int, z: c_int, n: *mut c_int) -> c_int;
    pub fn cg_boco_info(
        f: c_int,
        b: c_int,
        z: c_int,
        bc: c_int,
        name: *mut c_char,
        kind: *mut c_int,
        set: *mut c_int,
        points: *mut CgSize,
        normal_index: *mut c_int,
        normal_size: *mut CgSize,
        normal_kind: *mut c_int,
        datasets: *mut c_int,
    ) -> c_int;
    pub fn cg_boco_read(
        f: c_int,
        b: c_int,
        z: c_int,
        bc: c_int,
        points: *mut CgSize,
        normals: *mut c_void,
    ) -> c_int;
    pub fn cg_boco_write(
        f: c_int,
        b: c_int,
        z: c_int,
        name: *const c_char,
        kind: c_int,
        set: c_int,
        count: CgSize,
        points: *const CgSize,
        bc: *mut c_int,
    ) -> c_int;
    pub fn cg_boco_gridlocation_read(
        f: c_int,
        b: c_int,
        z: c_int,
        bc: c_int,
        at: *mut c_int,
    ) -> c_int;
    pub fn cg_boco_gridlocation_write(f: c_int, b: c_int, z: c_int, bc: c_int, at: c_int) -> c_int;
    pub fn cg_family_write(f: c_int, b: c_int, name: *const c_char, fam: *mut c_int) -> c_int;
    pub fn cg_nfamilies(f: c_int, b: c_int, n: *mut c_int) -> c_int;
    pub fn cg_family_read(
        f: c_int,
        b: c_int,
        fam: c_int,
        name: *mut c_char,
        bocos: *mut c_int,
        geometries: *mut c_int,
    ) -> c_int;
    pub fn cg_nfamily_names(f: c_int, b: c_int, fam: c_int, n: *mut c_int) -> c_int;
    pub fn cg_family_name_read(
        f: c_int,
        b: c_int,
        fam: c_int,
        k: c_int,
        name: *mut c_char,
        family: *mut c_char,
    ) -> c_int;
    pub fn cg_gopath(f: c_int, path: *const c_char) -> c_int;
    pub fn cg_famname_read(name: *mut c_char) -> c_int;
    pub fn cg_famname_write(name: *const c_char) -> c_int;
    pub fn cg_get_cgio(f: c_int, cgio: *mut c_int) -> c_int;
    pub fn cg_root_id(f: c_int, root: *mut f64) -> c_int;
}

// The node layer (`cgns_io.h`) under the mid-level library: what
// `super::tree` reads and writes a node tree with.
#[link(name = "cgns")]
extern "C" {
    pub fn cgio_open_file(name: *const c_char, mode: c_int, kind: c_int, cgio: *mut c_int)
        -> c_int;
    pub fn cgio_close_file(cgio: c_int) -> c_int;
    pub fn cgio_error_message(message: *mut c_char) -> c_int;
    pub fn cgio_get_root_id(cgio: c_int, root: *mut f64) -> c_int;
    pub fn cgio_get_node_id(cgio: c_int, parent: f64, path: *const c_char, id: *mut f64) -> c_int;
    pub fn cgio_release_id(cgio: c_int, id: f64) -> c_int;
    pub fn cgio_is_link(cgio: c_int, id: f64, len: *mut c_int) -> c_int;
    pub fn cgio_link_size(cgio: c_int, id: f64, file: *mut c_int, name: *mut c_int) -> c_int;
    pub fn cgio_get_link(cgio: c_int, id: f64, file: *mut c_char, name: *mut c_char) -> c_int;
    pub fn cgio_number_children(cgio: c_int, id: f64, n: *mut c_int) -> c_int;
    pub fn cgio_children_ids(
        cgio: c_int,
        id: f64,
        start: c_int,
        max: c_int,
        n: *mut c_int,
        ids: *mut f64,
    ) -> c_int;
    pub fn cgio_get_name(cgio: c_int, id: f64, name: *mut c_char) -> c_int;
    pub fn cgio_get_label(cgio: c_int, id: f64, label: *mut c_char) -> c_int;
    pub fn cgio_get_data_type(cgio: c_int, id: f64, kind: *mut c_char) -> c_int;
    pub fn cgio_get_dimensions(cgio: c_int, id: f64, n: *mut c_int, dims: *mut CgSize) -> c_int;
    #[allow(clippy::too_many_arguments)]
    pub fn cgio_read_data(
        cgio: c_int,
        id: f64,
        s_start: *const CgSize,
        s_end: *const CgSize,
        s_stride: *const CgSize,
        m_dims: c_int,
        m_size: *const CgSize,
        m_start: *const CgSize,
        m_end: *const CgSize,
        m_stride: *const CgSize,
        data: *mut c_void,
    ) -> c_int;
    pub fn cgio_create_node(cgio: c_int, parent: f64, name: *const c_char, id: *mut f64) -> c_int;
    pub fn cgio_set_label(cgio: c_int, id: f64, label: *const c_char) -> c_int;
    pub fn cgio_set_dimensions(
        cgio: c_int,
        id: f64,
        kind: *const c_char,
        n: c_int,
        dims: *const CgSize,
    ) -> c_int;
    pub fn cgio_write_all_data(cgio: c_int, id: f64, data: *const c_void) -> c_int;
    pub fn cgio_create_link(
        cgio: c_int,
        parent: f64,
        name: *const c_char,
        file: *const c_char,
        name_in_file: *const c_char,
        id: *mut f64,
    ) -> c_int;
}
