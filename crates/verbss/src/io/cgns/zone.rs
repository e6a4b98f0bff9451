//! What the whole-file reader ([`super::read`]) and the block reader
//! ([`super::blocks`]) share: opening zone 1 of base 1 with its checks, the
//! element kinds, the section headers, the decoding of connectivity, the
//! coordinates and the boundary conditions with their group names.

use std::collections::HashMap;
use std::ffi::c_int;
use std::path::Path;

use super::blocks::{Condition, Numbers};
use super::error;
use super::ffi::{self, CgSize, File, Mode, SectionInfo};
use crate::error::Result;
use crate::io::MAX_GROUPS;
use crate::mesh::{CellKind, Cells};

/// The names of CGNS's `ElementType_t` values 0 to 23, as used in messages.
const TYPE_NAMES: [&str; 24] = [
    "ElementTypeNull",
    "ElementTypeUserDefined",
    "NODE",
    "BAR_2",
    "BAR_3",
    "TRI_3",
    "TRI_6",
    "QUAD_4",
    "QUAD_8",
    "QUAD_9",
    "TETRA_4",
    "TETRA_10",
    "PYRA_5",
    "PYRA_14",
    "PENTA_6",
    "PENTA_15",
    "PENTA_18",
    "HEXA_8",
    "HEXA_20",
    "HEXA_27",
    "MIXED",
    "PYRA_13",
    "NGON_n",
    "NFACE_n",
];

/// The `ElementType_t` value of each kind verbss reads and writes.
pub(super) const KINDS: [(c_int, CellKind); 7] = [
    (3, CellKind::Line),
    (5, CellKind::Triangle),
    (7, CellKind::Quad),
    (10, CellKind::Tetra),
    (12, CellKind::Pyramid),
    (14, CellKind::Wedge),
    (17, CellKind::Hexahedron),
];

/// The kinds verbss reads, for messages.
pub(super) const READ: &str =
    "BAR_2, TRI_3, QUAD_4, TETRA_4, PYRA_5, PENTA_6, HEXA_8 and MIXED of those";

/// The name of an `ElementType_t` value.
pub(super) fn type_name(kind: c_int) -> String {
    usize::try_from(kind)
        .ok()
        .and_then(|k| TYPE_NAMES.get(k))
        .map_or_else(|| format!("ElementType_t {kind}"), |n| n.to_string())
}

/// The verbss kind of an `ElementType_t` value.
pub(super) fn kind_of(kind: c_int) -> Option<CellKind> {
    KINDS.iter().find(|k| k.0 == kind).map(|k| k.1)
}

/// Zone 1 of base 1 as opened: its names and sizes.
pub(super) struct Head {
    /// The base's name.
    pub base: String,
    /// The zone's name.
    pub zone: String,
    /// The number of zones of the base.
    pub zones: usize,
    /// `zone 'Z' (zone 1 of base 'B')`, for messages.
    pub at: String,
    /// The base's cell dimension, 2 or 3.
    pub dim: usize,
    /// The zone's vertex count.
    pub vertices: usize,
}

/// Opens the CGNS file `path` and checks zone 1 of base 1: a base of cell
/// dimension 2 or 3, an unstructured zone with vertices.
pub(super) fn open(path: &Path) -> Result<(File, Head)> {
    let fail = |m: String| error(path, m);
    crate::io::regular_input(path)?;
    super::check::check(path).map_err(fail)?;
    let file =
        File::open(path, Mode::Read).map_err(|m| fail(format!("cannot open as CGNS: {m}")))?;
    if file.bases().map_err(fail)? < 1 {
        return Err(fail("the file holds no base (CGNSBase_t)".into()));
    }
    let (base, cell_dim, _) = file.base(1).map_err(fail)?;
    if !(2..=3).contains(&cell_dim) {
        return Err(fail(format!(
            "base '{base}' has cell dimension {cell_dim} (verbss reads 2 and 3)"
        )));
    }
    let zones = file.zones(1).map_err(fail)?;
    if zones < 1 {
        return Err(fail(format!("base '{base}' holds no zone")));
    }
    let (zone, vertices, _) = file.zone(1, 1).map_err(fail)?;
    let at = format!("zone '{zone}' (zone 1 of base '{base}')");
    match file.zone_type(1, 1).map_err(fail)? {
        ffi::UNSTRUCTURED => {}
        ffi::STRUCTURED => {
            return Err(fail(format!(
                "{at} is structured: verbss reads unstructured zones only"
            )))
        }
        t => return Err(fail(format!("{at} has zone type {t}, not Unstructured"))),
    }
    let vertices = usize::try_from(vertices)
        .ok()
        .filter(|&n| n > 0)
        .ok_or_else(|| fail(format!("{at} has {vertices} vertices")))?;
    let head = Head {
        base,
        zone,
        zones: zones as usize,
        at,
        dim: cell_dim as usize,
        vertices,
    };
    Ok((file, head))
}

/// The coordinates of the `count` nodes from `first` (numbered from 0),
/// `dim` per node; in 2D a `CoordinateZ` must be 0 there.
pub(super) fn coordinates(
    file: &File,
    head: &Head,
    (first, count): (usize, usize),
) -> std::result::Result<Vec<f64>, String> {
    let (at, dim) = (&head.at, head.dim);
    let present = file.coordinates(1, 1)?;
    let has = |name: &str| present.iter().any(|(p, _)| p == name);
    let names = ["CoordinateX", "CoordinateY", "CoordinateZ"];
    let mut axes = Vec::with_capacity(dim);
    for name in &names[..dim] {
        if !has(name) {
            return Err(format!(
                "{at} has no {name} (verbss reads the Cartesian CoordinateX, CoordinateY and, in 3D, CoordinateZ)"
            ));
        }
        axes.push(file.read_coordinate(1, 1, name, (first, count))?);
    }
    if dim == 2 && has(names[2]) {
        let z = file.read_coordinate(1, 1, names[2], (first, count))?;
        if let Some((i, v)) = z.iter().enumerate().find(|(_, &v)| v != 0.0) {
            return Err(format!(
                "{at}: node {} has CoordinateZ = {v}; a 2D base must lie in the plane z = 0",
                first + i + 1
            ));
        }
    }
    Ok((0..count * dim).map(|k| axes[k % dim][k / dim]).collect())
}

/// Section `s`'s header, its element type checked (only the kinds verbss
/// reads; `NGON_n` and `NFACE_n` where `polyhedra`) and its numbering
/// `1 ≤ start ≤ end`.
pub(super) fn section(
    file: &File,
    at: &str,
    s: c_int,
    polyhedra: bool,
) -> std::result::Result<SectionInfo, String> {
    let info = file.section(1, 1, s)?;
    let place = format!("section '{}' of {at}", info.name);
    match info.kind {
        ffi::NGON_N | ffi::NFACE_N if polyhedra => {}
        ffi::NGON_N | ffi::NFACE_N => {
            return Err(format!(
                "{place} is {}: polyhedral sections are not supported here (verbss reads \
                 them from a whole file, not in blocks; here it reads {READ})",
                type_name(info.kind)
            ))
        }
        ffi::MIXED => {}
        k if kind_of(k).is_none() => {
            return Err(format!(
                "{place} has elements {} (verbss reads {READ})",
                type_name(k)
            ))
        }
        _ => {}
    }
    if info.start < 1 || info.end < info.start {
        return Err(format!(
            "{place} numbers its elements {}..{} (expected 1 ≤ start ≤ end)",
            info.start, info.end
        ));
    }
    Ok(info)
}

/// Elements `first..=last` of section `s` (header `info`), decoded: each
/// of a kind verbss reads, of dimension at most `head.dim`, on nodes of
/// the zone.
pub(super) fn elements(
    file: &File,
    head: &Head,
    (s, info): (c_int, &SectionInfo),
    (first, last): (CgSize, CgSize),
) -> std::result::Result<Cells, String> {
    let place = format!("section '{}' of {}", info.name, head.at);
    let data = file.elements((1, 1, s), info.kind, (first, last))?;
    let numbers = i64::from(first)..=i64::from(last);
    let cells = decode(info.kind, numbers, &data, head.vertices, &place)?;
    if let Some(k) = cells.kinds.iter().find(|k| k.dim() > head.dim) {
        return Err(format!(
            "{place} holds {} elements in a base of cell dimension {}",
            k.name(),
            head.dim
        ));
    }
    Ok(cells)
}

/// The 1-based node numbers `stored` as 0-based indices in `nodes`
/// (cleared first); the first number outside `1..=n`, if any.
fn zero_based(stored: &[CgSize], n: usize, nodes: &mut Vec<usize>) -> std::result::Result<(), i64> {
    nodes.clear();
    for &v in stored {
        let v = i64::from(v);
        if v < 1 || v > n as i64 {
            return Err(v);
        }
        nodes.push(v as usize - 1);
    }
    Ok(())
}

/// The faces of an `NGON_n` section (elements `first..`, connectivity
/// `data` cut by `offsets`) of a zone of cell dimension `dim`, each as the
/// facet of its node count (in 2D a line, in 3D a triangle, quadrilateral
/// or polygon), 1-based node numbers checked against `n`.
pub(super) fn ngon(
    data: &[CgSize],
    offsets: &[CgSize],
    (n, dim): (usize, usize),
    (first, place): (i64, &str),
) -> std::result::Result<Cells, String> {
    let mut cells = Cells::new();
    let mut nodes = Vec::new();
    for (k, w) in offsets.windows(2).enumerate() {
        let number = first + k as i64;
        let range = usize::try_from(w[0]).ok().zip(usize::try_from(w[1]).ok());
        let stored = range
            .and_then(|(a, b)| data.get(a..b))
            .ok_or_else(|| format!("{place}: face {number} has no valid node range"))?;
        let fits = if dim == 2 {
            stored.len() == 2
        } else {
            stored.len() >= 3
        };
        if !fits {
            return Err(format!(
                "{place}: face {number} has {} nodes (expected {} in a base of cell dimension \
                 {dim})",
                stored.len(),
                if dim == 2 { "2" } else { "3 or more" }
            ));
        }
        zero_based(stored, n, &mut nodes).map_err(|v| {
            format!("{place}: face {number} has node {v}, outside the zone's 1..={n}")
        })?;
        cells.push(CellKind::facet_kind(nodes.len()), &nodes);
    }
    Ok(cells)
}

/// The cells of an `NFACE_n` section: each a list of signed face element
/// numbers (negative: the face's normal points into the cell), cut by
/// `offsets`.
pub(super) fn nface(
    data: &[CgSize],
    offsets: &[CgSize],
    (first, place): (i64, &str),
) -> std::result::Result<Vec<Vec<i64>>, String> {
    offsets
        .windows(2)
        .enumerate()
        .map(|(k, w)| {
            let range = usize::try_from(w[0]).ok().zip(usize::try_from(w[1]).ok());
            range
                .and_then(|(a, b)| data.get(a..b))
                .map(|f| f.iter().map(|&v| i64::from(v)).collect())
                .ok_or_else(|| {
                    format!("{place}: cell {} has no valid face range", first + k as i64)
                })
        })
        .collect()
}

/// The elements `numbers` of type `kind` from their connectivity
/// (`MIXED`: each element's type before its nodes), 1-based node numbers
/// checked against `n`.
fn decode(
    kind: c_int,
    numbers: std::ops::RangeInclusive<i64>,
    data: &[CgSize],
    n: usize,
    place: &str,
) -> std::result::Result<Cells, String> {
    let mut cells = Cells::new();
    let mut nodes = Vec::with_capacity(8);
    let mut pos = 0;
    for number in numbers {
        let code = if kind == ffi::MIXED {
            pos += 1;
            data.get(pos - 1).map_or(-1, |&t| t as c_int)
        } else {
            kind
        };
        let element = kind_of(code).ok_or_else(|| {
            format!(
                "{place}: element {number} is {} (verbss reads {READ})",
                type_name(code)
            )
        })?;
        let end = pos + element.node_count();
        let stored = data
            .get(pos..end)
            .ok_or_else(|| format!("{place}: the connectivity ends inside element {number}"))?;
        zero_based(stored, n, &mut nodes).map_err(|v| {
            format!("{place}: element {number} has node {v}, outside the zone's 1..={n}")
        })?;
        cells.push(element, &nodes);
        pos = end;
    }
    Ok(cells)
}

/// The family at the top of `family`'s chain of parents (at most 20 up, the
/// depth of a CGNS path; a cycle stops there).
fn top_family(parents: &HashMap<String, String>, family: String) -> String {
    let mut top = family;
    for _ in 0..20 {
        match parents.get(&top) {
            Some(parent) if *parent != top => top = parent.clone(),
            _ => break,
        }
    }
    top
}

/// The zone's boundary conditions, in file order, with their points and
/// the name of the group each makes (its top family, else its own name).
pub(super) fn conditions(file: &File, head: &Head) -> std::result::Result<Vec<Condition>, String> {
    let at = &head.at;
    let bocos = file.bocos(1, 1)?;
    if bocos as usize > MAX_GROUPS {
        return Err(format!(
            "{at} has {bocos} boundary conditions, more than {MAX_GROUPS} (the most verbss reads)"
        ));
    }
    let parents: HashMap<String, String> = file.family_parents(1)?.into_iter().collect();
    (1..=bocos)
        .map(|bc| {
            let info = file.boco(1, 1, bc)?;
            let place = format!("boundary condition '{}' of {at}", info.name);
            let (points, location, family) = file
                .boco_points((&head.base, &head.zone), (1, 1, bc), &info)
                .map_err(|m| format!("{place}: {m}"))?;
            // `boco_points` reads ranges of 2 points and lists only.
            let numbers = match info.point_set {
                ffi::POINT_RANGE | ffi::ELEMENT_RANGE => {
                    Numbers::Range(i64::from(points[0]), i64::from(points[1]))
                }
                _ => Numbers::List(points.iter().map(|&p| i64::from(p)).collect()),
            };
            let of_elements = match (info.point_set, location) {
                (ffi::ELEMENT_RANGE | ffi::ELEMENT_LIST, _) => true,
                (_, ffi::VERTEX) => false,
                (_, ffi::FACE_CENTER | ffi::EDGE_CENTER | ffi::CELL_CENTER) => true,
                (_, l) => {
                    return Err(format!(
                    "{place} is at grid location {l} (verbss reads Vertex, and FaceCenter, EdgeCenter or CellCenter naming boundary elements)"
                ))
                }
            };
            Ok(Condition {
                group: family
                    .map(|f| top_family(&parents, f))
                    .unwrap_or_else(|| info.name.clone()),
                name: info.name,
                place,
                numbers,
                of_elements,
                at_cell_center: location == ffi::CELL_CENTER,
            })
        })
        .collect()
}
