//! The boundary conditions and families of a zone: the wrappers of the
//! `cg_boco_*` and `cg_family_*` calls (see the parent module for how their
//! buffers are sized).
#![allow(unsafe_code)]

use std::ffi::c_int;

use super::sys::*;
use super::{
    c_name, check, name_of, to_size, tree, CgSize, FamilyBuf, File, NameBuf, ELEMENT_LIST,
    ELEMENT_RANGE, FAMILY_SPECIFIED, NODE_NOT_FOUND, POINT_LIST, POINT_RANGE,
};

/// A boundary condition's header (`cg_boco_info`).
#[derive(Debug)]
pub struct BocoInfo {
    pub name: String,
    pub point_set: c_int,
    pub count: CgSize,
}

impl File {
    /// The number of boundary conditions of the zone.
    pub fn bocos(&self, b: c_int, z: c_int) -> Result<c_int, String> {
        let mut n = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_nbocos(self.id, b, z, &mut n) })?;
        Ok(n)
    }

    /// Boundary condition `bc`'s header.
    pub fn boco(&self, b: c_int, z: c_int, bc: c_int) -> Result<BocoInfo, String> {
        let mut name: NameBuf = [0; 33];
        let (mut kind, mut set, mut count, mut normal_index) = (0, 0, 0, [0; 3]);
        let (mut normal_size, mut normal_kind, mut datasets) = (0, 0, 0);
        // SAFETY: a 33-byte name buffer and out-pointers; the library writes
        // one normal index per index dimension (at most 3, checked in the tree).
        check(unsafe {
            cg_boco_info(
                self.id,
                b,
                z,
                bc,
                name.as_mut_ptr(),
                &mut kind,
                &mut set,
                &mut count,
                normal_index.as_mut_ptr(),
                &mut normal_size,
                &mut normal_kind,
                &mut datasets,
            )
        })?;
        Ok(BocoInfo {
            name: name_of(&name),
            point_set: set,
            count,
        })
    }

    /// Boundary condition `bc`'s points (2 for a range), its grid location
    /// and its family name, if any.
    pub fn boco_points(
        &self,
        path: (&str, &str),
        (b, z, bc): (c_int, c_int, c_int),
        info: &BocoInfo,
    ) -> Result<(Vec<CgSize>, c_int, Option<String>), String> {
        let (set, count) = match info.point_set {
            POINT_RANGE => ("PointRange", 2),
            ELEMENT_RANGE => ("ElementRange", 2),
            POINT_LIST => ("PointList", info.count),
            ELEMENT_LIST => ("ElementList", info.count),
            t => {
                return Err(format!(
                    "point set type {t} (verbss reads PointRange, PointList, ElementRange, ElementList)"
                ))
            }
        };
        let stored = self.dimensions(&format!(
            "/{}/{}/ZoneBC/{}/{set}",
            path.0, path.1, info.name
        ))?;
        let values: i64 = stored.iter().product();
        // `cg_boco_read` copies the whole stored array (and, converting
        // between I4 and I8, into a buffer of its own sized from `count`):
        // only the shape 1 × count, an unstructured zone's index dimension
        // being 1, fits both.
        if stored.len() != 2 || stored[0] != 1 || values != i64::from(count) {
            let shape: Vec<String> = stored.iter().map(i64::to_string).collect();
            return Err(format!(
                "{set} of shape {} (expected 1 × {count} in an unstructured zone)",
                shape.join(" × ")
            ));
        }
        let mut points: Vec<CgSize> = vec![0; values as usize];
        // SAFETY: a buffer of the stored array's size (checked above to be
        // the count the library reports); no normals asked for.
        check(unsafe {
            cg_boco_read(self.id, b, z, bc, points.as_mut_ptr(), std::ptr::null_mut())
        })?;
        let mut at = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_boco_gridlocation_read(self.id, b, z, bc, &mut at) })?;
        let node = c_name(&format!("/{}/{}/ZoneBC/{}", path.0, path.1, info.name))?;
        // SAFETY: a valid C string.
        check(unsafe { cg_gopath(self.id, node.as_ptr()) })?;
        let mut family: FamilyBuf = [0; 1024];
        // SAFETY: a 1024-byte buffer; the tree's check holds family names to
        // 32 characters.
        let code = unsafe { cg_famname_read(family.as_mut_ptr()) };
        let family = match code {
            NODE_NOT_FOUND => None,
            code => check(code).map(|()| Some(name_of(&family)))?,
        };
        Ok((points, at, family))
    }

    /// The dimensions of the data of the node at `path`, as stored.
    fn dimensions(&self, path: &str) -> Result<Vec<i64>, String> {
        let node = c_name(path)?;
        let (mut cgio, mut root, mut id) = (0, 0.0, 0.0);
        let mut dims: [CgSize; tree::MAX_DIMENSIONS] = [0; tree::MAX_DIMENSIONS];
        let mut n = 0;
        // SAFETY: out-pointers, a valid C string and 12 dimensions
        // (`CGIO_MAX_DIMENSIONS`, the most the node layer writes).
        unsafe {
            check(cg_get_cgio(self.id, &mut cgio))?;
            check(cg_root_id(self.id, &mut root))?;
            tree::check(cgio_get_node_id(cgio, root, node.as_ptr(), &mut id))?;
            tree::check(cgio_get_dimensions(cgio, id, &mut n, dims.as_mut_ptr()))?;
        }
        let n = usize::try_from(n).unwrap_or(0).min(tree::MAX_DIMENSIONS);
        Ok(dims[..n].iter().map(|&d| i64::from(d)).collect())
    }

    /// The family each family of base `b` belongs to (its first
    /// `FamilyName_t` child), by name: Gmsh writes one family per entity,
    /// belonging to the family of its physical group.
    pub fn family_parents(&self, b: c_int) -> Result<Vec<(String, String)>, String> {
        let mut count = 0;
        // SAFETY: an out-pointer.
        check(unsafe { cg_nfamilies(self.id, b, &mut count) })?;
        let mut parents = Vec::new();
        for f in 1..=count {
            let (mut name, mut bocos, mut geometries): (NameBuf, c_int, c_int) = ([0; 33], 0, 0);
            // SAFETY: a 33-byte name buffer and out-pointers.
            check(unsafe {
                cg_family_read(
                    self.id,
                    b,
                    f,
                    name.as_mut_ptr(),
                    &mut bocos,
                    &mut geometries,
                )
            })?;
            let mut names = 0;
            // SAFETY: an out-pointer.
            check(unsafe { cg_nfamily_names(self.id, b, f, &mut names) })?;
            if names >= 1 {
                let (mut node, mut parent): (FamilyBuf, FamilyBuf) = ([0; 1024], [0; 1024]);
                // SAFETY: 1024-byte buffers; the tree's check holds node and
                // family names to 32 characters.
                check(unsafe {
                    cg_family_name_read(self.id, b, f, 1, node.as_mut_ptr(), parent.as_mut_ptr())
                })?;
                parents.push((name_of(&name), name_of(&parent)));
            }
        }
        Ok(parents)
    }

    /// Writes the family `name` under base `b`.
    pub fn write_family(&self, b: c_int, name: &str) -> Result<(), String> {
        let c = c_name(name)?;
        let mut f = 0;
        // SAFETY: a valid C string and an out-pointer.
        check(unsafe { cg_family_write(self.id, b, c.as_ptr(), &mut f) })
    }

    /// Writes a family-specified boundary condition `name` over `points`
    /// (a point set of type `set`) at grid location `at`, of the family
    /// `family` (see [`File::write_family`]). `ElementRange`/`ElementList`
    /// sets take no location: the library stores them at `FaceCenter`.
    #[allow(clippy::too_many_arguments)]
    pub fn write_boco(
        &self,
        path: (&str, &str),
        (b, z): (c_int, c_int),
        (name, family): (&str, &str),
        set: c_int,
        points: &[CgSize],
        at: c_int,
    ) -> Result<(), String> {
        let c = c_name(name)?;
        let family = c_name(family)?;
        let mut bc = 0;
        // SAFETY: `points` holds the `points.len()` points of the set.
        check(unsafe {
            cg_boco_write(
                self.id,
                b,
                z,
                c.as_ptr(),
                FAMILY_SPECIFIED,
                set,
                to_size(points.len())?,
                points.as_ptr(),
                &mut bc,
            )
        })?;
        if !matches!(set, ELEMENT_RANGE | ELEMENT_LIST) {
            // SAFETY: plain integers.
            check(unsafe { cg_boco_gridlocation_write(self.id, b, z, bc, at) })?;
        }
        let node = c_name(&format!("/{}/{}/ZoneBC/{name}", path.0, path.1))?;
        // SAFETY: valid C strings.
        check(unsafe { cg_gopath(self.id, node.as_ptr()) })?;
        // SAFETY: a valid C string.
        check(unsafe { cg_famname_write(family.as_ptr()) })
    }
}
