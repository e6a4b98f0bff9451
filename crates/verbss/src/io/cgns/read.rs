//! Reading zone 1 of base 1 of a CGNS file into a [`Mesh`].

use std::collections::{HashMap, HashSet};
use std::ffi::c_int;
use std::path::Path;

use super::ffi::{self, CgSize, File, Mode, SectionInfo};
use super::{error, Source};
use crate::error::Result;
use crate::io::MAX_GROUPS;
use crate::mesh::{CellKind, Cells, FileOrigin, Group, Mesh};

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
const READ: &str = "BAR_2, TRI_3, QUAD_4, TETRA_4, PYRA_5, PENTA_6, HEXA_8 and MIXED of those";

/// The name of an `ElementType_t` value.
fn type_name(kind: c_int) -> String {
    usize::try_from(kind)
        .ok()
        .and_then(|k| TYPE_NAMES.get(k))
        .map_or_else(|| format!("ElementType_t {kind}"), |n| n.to_string())
}

/// The verbss kind of an `ElementType_t` value.
fn kind_of(kind: c_int) -> Option<CellKind> {
    KINDS.iter().find(|k| k.0 == kind).map(|k| k.1)
}

/// An element section: its name, its first element number, its elements.
struct Section {
    name: String,
    start: i64,
    cells: Cells,
}

/// Reads zone 1 of base 1 of the CGNS file `path`.
pub fn read(path: &Path) -> Result<Mesh> {
    let fail = |m: String| error(path, m);
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
    let dim = cell_dim as usize;
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
    let n = usize::try_from(vertices)
        .ok()
        .filter(|&n| n > 0)
        .ok_or_else(|| fail(format!("{at} has {vertices} vertices")))?;
    let coords = coordinates(&file, &at, n, dim).map_err(fail)?;
    let sections = sections(&file, &at, n, dim).map_err(fail)?;
    let groups = groups(&file, (&base, &zone), &at, n, dim, &sections).map_err(fail)?;
    drop(file);
    let mut cells = Cells::new();
    let mut cell_tags = Vec::new();
    for s in &sections {
        for (i, (kind, nodes)) in s.cells.iter().enumerate() {
            if kind.dim() == dim {
                cells.push(kind, nodes);
                cell_tags.push((s.start + i as i64) as u64);
            }
        }
    }
    let mesh = Mesh {
        dim,
        coords,
        node_tags: (1..=n as u64).collect(),
        cells,
        cell_tags,
        groups,
        origin: FileOrigin {
            cgns: Some(Source {
                path: path.to_path_buf(),
                base,
                zone,
                zones: zones as usize,
            }),
            ..FileOrigin::default()
        },
    };
    mesh.validate()
        .map_err(|e| crate::io::invalid_at(e, |m| fail(format!("{at}: {m}"))))?;
    Ok(mesh)
}

/// The zone's `n` nodes' coordinates, `dim` per node; in 2D a `CoordinateZ`
/// must be 0 everywhere.
fn coordinates(
    file: &File,
    at: &str,
    n: usize,
    dim: usize,
) -> std::result::Result<Vec<f64>, String> {
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
        axes.push(file.read_coordinate(1, 1, name, n)?);
    }
    if dim == 2 && has(names[2]) {
        let z = file.read_coordinate(1, 1, names[2], n)?;
        if let Some((i, v)) = z.iter().enumerate().find(|(_, &v)| v != 0.0) {
            return Err(format!(
                "{at}: node {} has CoordinateZ = {v}; a 2D base must lie in the plane z = 0",
                i + 1
            ));
        }
    }
    Ok((0..n * dim).map(|k| axes[k % dim][k / dim]).collect())
}

/// The zone's element sections, in file order.
fn sections(
    file: &File,
    at: &str,
    n: usize,
    dim: usize,
) -> std::result::Result<Vec<Section>, String> {
    let count = file.sections(1, 1)?;
    (1..=count)
        .map(|s| {
            let info = file.section(1, 1, s)?;
            let place = format!("section '{}' of {at}", info.name);
            match info.kind {
                ffi::NGON_N | ffi::NFACE_N => {
                    return Err(format!(
                    "{place} is {}: polyhedral sections are not supported (verbss reads {READ})",
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
            let data = file.elements(1, 1, &info, s)?;
            let cells = decode(&info, &data, n, &place)?;
            if let Some(k) = cells.kinds.iter().find(|k| k.dim() > dim) {
                return Err(format!(
                    "{place} holds {} elements in a base of cell dimension {dim}",
                    k.name()
                ));
            }
            Ok(Section {
                name: info.name,
                start: i64::from(info.start),
                cells,
            })
        })
        .collect()
}

/// A section's elements from its connectivity (`MIXED`: each element's
/// type before its nodes), 1-based node numbers checked against `n`.
fn decode(
    info: &SectionInfo,
    data: &[CgSize],
    n: usize,
    place: &str,
) -> std::result::Result<Cells, String> {
    let count = (i64::from(info.end) - i64::from(info.start) + 1) as usize;
    let mut cells = Cells::new();
    let mut nodes = Vec::with_capacity(8);
    let mut pos = 0;
    for e in 0..count {
        let number = i64::from(info.start) + e as i64;
        let code = if info.kind == ffi::MIXED {
            pos += 1;
            data.get(pos - 1).map_or(-1, |&t| t as c_int)
        } else {
            info.kind
        };
        let kind = kind_of(code).ok_or_else(|| {
            format!(
                "{place}: element {number} is {} (verbss reads {READ})",
                type_name(code)
            )
        })?;
        let end = pos + kind.node_count();
        let stored = data
            .get(pos..end)
            .ok_or_else(|| format!("{place}: the connectivity ends inside element {number}"))?;
        nodes.clear();
        for &v in stored {
            let v = i64::from(v);
            if v < 1 || v > n as i64 {
                return Err(format!(
                    "{place}: element {number} has node {v}, outside the zone's 1..={n}"
                ));
            }
            nodes.push(v as usize - 1);
        }
        cells.push(kind, &nodes);
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

/// The boundary groups: one per family (or boundary condition without
/// one), then one per section of facets that no condition is named after.
fn groups(
    file: &File,
    names: (&str, &str),
    at: &str,
    n: usize,
    dim: usize,
    sections: &[Section],
) -> std::result::Result<Vec<Group>, String> {
    let bocos = file.bocos(1, 1)?;
    if bocos as usize > MAX_GROUPS {
        return Err(format!(
            "{at} has {bocos} boundary conditions, more than {MAX_GROUPS} (the most verbss reads)"
        ));
    }
    let parents: HashMap<String, String> = file.family_parents(1)?.into_iter().collect();
    let mut order: Vec<usize> = (0..sections.len()).collect();
    order.sort_by_key(|&s| sections[s].start);
    // Element `number`: its section, kind and nodes.
    let element = |number: i64| -> Option<(usize, CellKind, &[usize])> {
        let i = order.partition_point(|&s| sections[s].start <= number);
        let k = *order.get(i.checked_sub(1)?)?;
        let s = &sections[k];
        let e = usize::try_from(number - s.start).ok()?;
        (e < s.cells.len()).then(|| (k, s.cells.kinds[e], s.cells.cell(e)))
    };
    let facet = |number: i64| element(number).filter(|(_, kind, _)| kind.dim() + 1 == dim);
    let is_cell = |number: i64| element(number).is_some_and(|(_, kind, _)| kind.dim() == dim);
    let elements: usize = sections.iter().map(|s| s.cells.len()).sum();
    // Sections whose facets a condition holds: no group of their own.
    let mut covered = vec![false; sections.len()];
    let mut groups: Vec<Group> = Vec::new();
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut condition_names = HashSet::new();
    for bc in 1..=bocos {
        let info = file.boco(1, 1, bc)?;
        let (points, location, family) = file.boco_points(names, (1, 1, bc), &info)?;
        let place = format!("boundary condition '{}' of {at}", info.name);
        let numbers: Box<dyn Iterator<Item = i64>> = match info.point_set {
            ffi::POINT_RANGE | ffi::ELEMENT_RANGE => {
                Box::new(i64::from(points[0])..=i64::from(points[1]))
            }
            ffi::POINT_LIST | ffi::ELEMENT_LIST => Box::new(points.iter().map(|&p| i64::from(p))),
            t => return Err(format!("{place} has point set type {t} (verbss reads PointRange, PointList, ElementRange, ElementList)")),
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
        // A condition at `CellCenter` over cells of the zone's own dimension
        // is a region, not a boundary (Gmsh writes its volume physical
        // groups so): no group.
        let region = location == ffi::CELL_CENTER
            && match info.point_set {
                ffi::POINT_RANGE | ffi::ELEMENT_RANGE => {
                    let (first, last) = (i64::from(points[0]), i64::from(points[1]));
                    first <= last && last - first < elements as i64 && (first..=last).all(is_cell)
                }
                _ => !points.is_empty() && points.iter().all(|&p| is_cell(p.into())),
            };
        condition_names.insert(info.name.clone());
        if region {
            continue;
        }
        let name = family
            .map(|f| top_family(&parents, f))
            .unwrap_or_else(|| info.name.clone());
        let g = *index.entry(name.clone()).or_insert_with(|| {
            groups.push(Group {
                name,
                tag: None,
                facets: Cells::new(),
            });
            groups.len() - 1
        });
        let facets = &mut groups[g].facets;
        for number in numbers {
            if of_elements {
                let (section, kind, nodes) = facet(number).ok_or_else(|| {
                    format!("{place} names element {number}, which is not a boundary element of the zone ({} in {dim}D)", if dim == 2 { "BAR_2" } else { "TRI_3 or QUAD_4" })
                })?;
                facets.push(kind, nodes);
                covered[section] = true;
            } else if (1..=n as i64).contains(&number) {
                facets.push(CellKind::Vertex, &[number as usize - 1]);
            } else {
                return Err(format!(
                    "{place} names vertex {number}, outside the zone's 1..={n}"
                ));
            }
        }
    }
    for (s, covered) in sections.iter().zip(covered) {
        if covered || condition_names.contains(&s.name) || index.contains_key(&s.name) {
            continue;
        }
        let mut facets = Cells::new();
        for (kind, nodes) in s.cells.iter().filter(|(k, _)| k.dim() + 1 == dim) {
            facets.push(kind, nodes);
        }
        if !facets.is_empty() {
            index.insert(s.name.clone(), groups.len());
            groups.push(Group {
                name: s.name.clone(),
                tag: None,
                facets,
            });
        }
    }
    if groups.len() > MAX_GROUPS {
        return Err(format!(
            "{at} has {} boundary groups, more than {MAX_GROUPS} (the most verbss reads)",
            groups.len()
        ));
    }
    Ok(groups)
}
