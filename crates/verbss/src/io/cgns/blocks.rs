//! A CGNS zone read in blocks: the headers (sections, boundary conditions)
//! whole, the coordinates and the connectivity only over the ranges asked
//! for (`cg_coord_read` over a range, `cg_elements_partial_read`). What a
//! process of a distributed read needs to read its own share of the file
//! and nothing more; the checks and the names are the whole-file reader's.

use std::path::{Path, PathBuf};

use super::error;
use crate::error::Result;
use crate::mesh::{Cells, Mesh};

/// The numbers of a boundary condition's point set: vertex numbers, or
/// element numbers (1-based, as in the file).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Numbers {
    /// `first..=last` (empty when `last < first`).
    Range(i64, i64),
    /// A list, in file order.
    List(Vec<i64>),
}

impl Numbers {
    /// How many numbers the set holds.
    pub fn len(&self) -> u64 {
        match self {
            Numbers::Range(first, last) if last < first => 0,
            Numbers::Range(first, last) => last.abs_diff(*first).saturating_add(1),
            Numbers::List(list) => list.len() as u64,
        }
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The `k`-th number of the set (`k < len`).
    pub fn get(&self, k: u64) -> i64 {
        match self {
            Numbers::Range(first, _) => first + k as i64,
            Numbers::List(list) => list[k as usize],
        }
    }

    /// The numbers in order.
    pub fn iter(&self) -> impl Iterator<Item = i64> + '_ {
        (0..self.len()).map(|k| self.get(k))
    }
}

/// A boundary condition (`ZoneBC/BC_t`) of the zone.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Condition {
    /// Its own name.
    pub name: String,
    /// `boundary condition 'NAME' of zone …`, for messages.
    pub place: String,
    /// The group it makes: its family at the top, else its own name.
    pub group: String,
    /// Its points.
    pub numbers: Numbers,
    /// Whether the points are element numbers (else vertex numbers).
    pub of_elements: bool,
    /// Whether it is at `CellCenter`.
    pub(super) at_cell_center: bool,
}

impl Condition {
    /// Whether the condition is a region rather than a boundary, given
    /// `all_cells`: whether every element it names is a cell of the zone's
    /// own dimension. A region (Gmsh writes its volume physical groups so)
    /// is at `CellCenter`, names at least one element and fewer than the
    /// zone's `elements`, and makes no group.
    pub fn is_region(&self, elements: u64, all_cells: bool) -> bool {
        let size = match self.numbers {
            Numbers::Range(first, last) => first <= last && last.abs_diff(first) < elements,
            Numbers::List(ref list) => !list.is_empty(),
        };
        self.at_cell_center && size && all_cells
    }

    /// The message for element `number`, which is not a facet of a zone of
    /// dimension `dim`.
    pub fn not_a_facet(&self, number: i64, dim: usize) -> String {
        format!(
            "{} names element {number}, which is not a boundary element of the zone ({} in {dim}D)",
            self.place,
            if dim == 2 { "BAR_2" } else { "TRI_3 or QUAD_4" }
        )
    }

    /// The message for vertex `number`, outside the zone's `1..=vertices`.
    pub fn outside(&self, number: i64, vertices: u64) -> String {
        format!(
            "{} names vertex {number}, outside the zone's 1..={vertices}",
            self.place
        )
    }
}

/// An element section's header.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SectionHead {
    /// Its name.
    pub name: String,
    /// The number of its first element.
    pub first: i64,
    /// How many elements it holds.
    pub count: u64,
    /// Whether it may hold cells of the zone's dimension (its type is of
    /// that dimension, or `MIXED`).
    pub cells: bool,
    /// Whether it may hold facets (elements of one dimension less).
    pub facets: bool,
}

impl SectionHead {
    /// Whether the section makes a group of its own, named after it: it
    /// holds facets, no condition holds any of them (`covered`), and no
    /// condition and none of the `groups` so far has its name.
    pub fn own_group(&self, covered: bool, conditions: &[Condition], groups: &[String]) -> bool {
        self.facets
            && !covered
            && !conditions.iter().any(|c| c.name == self.name)
            && !groups.contains(&self.name)
    }
}

/// Zone 1 of base 1 of a CGNS file, open for reading in blocks. While it
/// is open it holds the library's process-wide lock (the library is not
/// thread-safe): any other CGNS file of the process waits until it is
/// dropped.
pub struct Blocks {
    /// The file.
    pub path: PathBuf,
    /// `zone 'Z' (zone 1 of base 'B')`, for messages.
    pub at: String,
    /// The base's cell dimension, 2 or 3.
    pub dim: usize,
    /// The zone's vertex count.
    pub vertices: u64,
    /// The element sections, in file order.
    pub sections: Vec<SectionHead>,
    /// The boundary conditions, in file order.
    pub conditions: Vec<Condition>,
    #[cfg(with_cgns)]
    open: Open,
    #[cfg(not(with_cgns))]
    never: std::convert::Infallible,
}

/// The open file, its zone and its sections' headers.
#[cfg(with_cgns)]
struct Open {
    file: super::ffi::File,
    head: super::zone::Head,
    sections: Vec<super::ffi::SectionInfo>,
}

impl Blocks {
    /// Opens the CGNS file `path` and reads its headers, with the
    /// whole-file reader's checks; a base of several zones is refused (a
    /// distributed read takes single-zone files).
    pub fn open(path: &Path) -> Result<Blocks> {
        #[cfg(not(with_cgns))]
        return Err(super::unavailable(path));
        #[cfg(with_cgns)]
        {
            use super::{ffi, zone};
            let fail = |m: String| error(path, m);
            let (file, head) = zone::open(path)?;
            if head.zones > 1 {
                return Err(fail(format!(
                    "base '{}' holds {} zones: a distributed read takes single-zone files \
                     (`verbss deform` reads zone 1 of several)",
                    head.base, head.zones
                )));
            }
            let count = file.sections(1, 1).map_err(fail)?;
            let sections = (1..=count)
                .map(|s| zone::section(&file, &head.at, s, false))
                .collect::<std::result::Result<Vec<_>, _>>()
                .map_err(fail)?;
            let conditions = zone::conditions(&file, &head).map_err(fail)?;
            let dim = head.dim;
            let heads = sections
                .iter()
                .map(|info| {
                    let of = zone::kind_of(info.kind).map(crate::mesh::CellKind::dim);
                    SectionHead {
                        name: info.name.clone(),
                        first: i64::from(info.start),
                        count: (i64::from(info.end) - i64::from(info.start) + 1) as u64,
                        cells: info.kind == ffi::MIXED || of == Some(dim),
                        facets: info.kind == ffi::MIXED || of == Some(dim - 1),
                    }
                })
                .collect();
            Ok(Blocks {
                path: path.to_path_buf(),
                at: head.at.clone(),
                dim,
                vertices: head.vertices as u64,
                sections: heads,
                conditions,
                open: Open {
                    file,
                    head,
                    sections,
                },
            })
        }
    }

    /// The number of elements of all sections.
    pub fn elements(&self) -> u64 {
        self.sections.iter().map(|s| s.count).sum()
    }

    /// The section that holds element `number`, if any.
    pub fn section_of(&self, number: i64) -> Option<usize> {
        self.sections
            .iter()
            .position(|s| number >= s.first && ((number - s.first) as u64) < s.count)
    }

    /// The coordinates of the `count` nodes from `first` (numbered from 0),
    /// `dim` per node.
    pub fn coordinates(&self, first: u64, count: u64) -> Result<Vec<f64>> {
        #[cfg(not(with_cgns))]
        {
            let _ = (first, count);
            match self.never {}
        }
        #[cfg(with_cgns)]
        super::zone::coordinates(
            &self.open.file,
            &self.open.head,
            (first as usize, count as usize),
        )
        .map_err(|m| error(&self.path, m))
    }

    /// The `count` elements of section `section` (an index of
    /// [`Blocks::sections`]) from element number `first`, decoded as the
    /// whole-file reader decodes them.
    pub fn read_elements(&self, section: usize, first: i64, count: u64) -> Result<Cells> {
        #[cfg(not(with_cgns))]
        {
            let _ = (section, first, count);
            match self.never {}
        }
        #[cfg(with_cgns)]
        {
            let fail = |m: String| error(&self.path, m);
            if count == 0 {
                return Ok(Cells::new());
            }
            let last = first + count as i64 - 1;
            let size =
                |v: i64| super::ffi::CgSize::try_from(v).map_err(|_| fail(format!("element {v}")));
            super::zone::elements(
                &self.open.file,
                &self.open.head,
                (section as i32 + 1, &self.open.sections[section]),
                (size(first)?, size(last)?),
            )
            .map_err(fail)
        }
    }
}

/// Checks `mesh`, read from the zone `at` (`zone 'Z' (zone 1 of base
/// 'B')`) of the CGNS file `path`, as the whole-file reader checks its
/// mesh: an invalid mesh is reported with the file and the zone.
pub fn validate(mesh: &Mesh, path: &Path, at: &str) -> Result<()> {
    mesh.validate()
        .map_err(|e| crate::io::invalid_at(e, |m| error(path, format!("{at}: {m}"))))
}
