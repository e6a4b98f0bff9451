//! Reading zone 1 of base 1 of a CGNS file into a [`Mesh`].

use std::collections::HashMap;
use std::path::Path;

use super::blocks::{validate, Condition, SectionHead};
use super::zone::{self, Head};
use super::{error, ffi, Source};
use crate::error::Result;
use crate::io::MAX_GROUPS;
use crate::mesh::{CellKind, Cells, FileOrigin, Group, Mesh};

/// An element section: its header and its elements (an `NFACE_n`
/// section's as signed face numbers).
struct Section {
    head: SectionHead,
    cells: Cells,
    nface: Vec<Vec<i64>>,
}

/// Reads zone 1 of base 1 of the CGNS file `path`.
pub fn read(path: &Path) -> Result<Mesh> {
    let fail = |m: String| error(path, m);
    let (file, head) = zone::open(path)?;
    let (n, dim) = (head.vertices, head.dim);
    let coords = zone::coordinates(&file, &head, (0, n)).map_err(fail)?;
    let sections = sections(&file, &head).map_err(fail)?;
    let conditions = zone::conditions(&file, &head).map_err(fail)?;
    drop(file);
    let groups = groups(&head, &conditions, &sections).map_err(fail)?;
    let mut cells = Cells::new();
    let mut cell_tags = Vec::new();
    for s in &sections {
        for (i, (kind, _)) in s.cells.iter().enumerate() {
            if kind.dim() == dim {
                cells.push_from(&s.cells, i, |v| v);
                cell_tags.push((s.head.first + i as i64) as u64);
            }
        }
        for (i, faces) in s.nface.iter().enumerate() {
            let number = s.head.first + i as i64;
            polytope(&sections, dim, faces, &mut cells).map_err(|m| {
                fail(format!(
                    "{at}: section '{}': cell {number} {m}",
                    s.head.name,
                    at = head.at
                ))
            })?;
            cell_tags.push(number as u64);
        }
    }
    let Head {
        base,
        zone,
        zones,
        at,
        ..
    } = head;
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
                zones,
            }),
            ..FileOrigin::default()
        },
    };
    validate(&mesh, path, &at)?;
    Ok(mesh)
}

/// The zone's element sections, in file order. An `NGON_n` section's faces
/// are facets that conditions may name but never a group of their own
/// (they are the mesh's faces, inside ones included).
fn sections(file: &super::ffi::File, head: &Head) -> std::result::Result<Vec<Section>, String> {
    let count = file.sections(1, 1)?;
    (1..=count)
        .map(|s| {
            let info = zone::section(file, &head.at, s, true)?;
            let place = format!("section '{}' of {}", info.name, head.at);
            let first = i64::from(info.start);
            let (mut cells, mut nface) = (Cells::new(), Vec::new());
            if matches!(info.kind, ffi::NGON_N | ffi::NFACE_N) {
                let (data, offsets) =
                    file.elements_and_offsets((1, 1, s), info.kind, (info.start, info.end))?;
                if info.kind == ffi::NGON_N {
                    cells =
                        zone::ngon(&data, &offsets, (head.vertices, head.dim), (first, &place))?;
                } else {
                    nface = zone::nface(&data, &offsets, (first, &place))?;
                }
            } else {
                cells = zone::elements(file, head, (s, &info), (info.start, info.end))?;
            }
            Ok(Section {
                head: SectionHead {
                    name: info.name,
                    first,
                    count: (cells.len() + nface.len()) as u64,
                    cells: true,
                    facets: info.kind != ffi::NGON_N
                        && cells.kinds.iter().any(|k| k.dim() + 1 == head.dim),
                },
                cells,
                nface,
            })
        })
        .collect()
}

/// The nodes of face element `number` of an `NGON_n` section.
fn face(sections: &[Section], number: i64) -> Option<&[usize]> {
    sections.iter().find_map(|s| {
        let e = usize::try_from(number - s.head.first).ok()?;
        (e < s.cells.len()).then(|| s.cells.cell(e))
    })
}

/// Appends the cell of the `NFACE_n` faces `faces` (signed element
/// numbers): in 3D the polyhedron of those faces, each reversed where its
/// number is negative (its normal points in); in 2D the polygon their
/// edges chain into.
fn polytope(
    sections: &[Section],
    dim: usize,
    faces: &[i64],
    cells: &mut Cells,
) -> std::result::Result<(), String> {
    let mut list = Vec::with_capacity(faces.len());
    for &f in faces {
        let nodes = face(sections, f.abs())
            .ok_or_else(|| format!("names face {f}, which no NGON_n section holds"))?;
        let mut nodes = nodes.to_vec();
        if f < 0 {
            nodes.reverse();
        }
        list.push(nodes);
    }
    if dim == 3 {
        cells.push_polyhedron(list.iter().map(Vec::as_slice));
        return Ok(());
    }
    let start = list
        .first()
        .filter(|e| e.len() == 2)
        .ok_or("has no edges")?;
    let mut ring = start.clone();
    let mut used = vec![false; list.len()];
    used[0] = true;
    while ring.len() < list.len() {
        let last = *ring.last().expect("started");
        let next = (0..list.len())
            .find(|&k| !used[k] && list[k].len() == 2 && list[k].contains(&last))
            .ok_or("has edges that do not close a polygon")?;
        used[next] = true;
        let e = &list[next];
        ring.push(if e[0] == last { e[1] } else { e[0] });
    }
    cells.push(CellKind::Polygon, &ring);
    Ok(())
}

/// The boundary groups: one per family (or boundary condition without
/// one), then one per section of facets that no condition is named after.
fn groups(
    head: &Head,
    conditions: &[Condition],
    sections: &[Section],
) -> std::result::Result<Vec<Group>, String> {
    let (n, dim, at) = (head.vertices, head.dim, &head.at);
    let mut order: Vec<usize> = (0..sections.len()).collect();
    order.sort_by_key(|&s| sections[s].head.first);
    // Element `number`: its section, kind and nodes.
    let element = |number: i64| -> Option<(usize, CellKind, &[usize])> {
        let i = order.partition_point(|&s| sections[s].head.first <= number);
        let k = *order.get(i.checked_sub(1)?)?;
        let s = &sections[k];
        let e = usize::try_from(number - s.head.first).ok()?;
        (e < s.cells.len()).then(|| (k, s.cells.kinds[e], s.cells.cell(e)))
    };
    let facet = |number: i64| element(number).filter(|(_, kind, _)| kind.dim() + 1 == dim);
    let is_cell = |number: i64| element(number).is_some_and(|(_, kind, _)| kind.dim() == dim);
    let elements: u64 = sections.iter().map(|s| s.head.count).sum();
    // Sections whose facets a condition holds: no group of their own.
    let mut covered = vec![false; sections.len()];
    let mut groups: Vec<Group> = Vec::new();
    let mut index: HashMap<String, usize> = HashMap::new();
    for c in conditions {
        let all_cells = c.of_elements && c.numbers.iter().all(is_cell);
        if c.is_region(elements, all_cells) {
            continue;
        }
        let g = *index.entry(c.group.clone()).or_insert_with(|| {
            groups.push(Group {
                name: c.group.clone(),
                tag: None,
                facets: Cells::new(),
            });
            groups.len() - 1
        });
        let facets = &mut groups[g].facets;
        for number in c.numbers.iter() {
            if c.of_elements {
                let (section, kind, nodes) =
                    facet(number).ok_or_else(|| c.not_a_facet(number, dim))?;
                facets.push(kind, nodes);
                covered[section] = true;
            } else if (1..=n as i64).contains(&number) {
                facets.push(CellKind::Vertex, &[number as usize - 1]);
            } else {
                return Err(c.outside(number, n as u64));
            }
        }
    }
    for (s, covered) in sections.iter().zip(covered) {
        let names: Vec<String> = groups.iter().map(|g| g.name.clone()).collect();
        if !s.head.own_group(covered, conditions, &names) {
            continue;
        }
        let mut facets = Cells::new();
        for (kind, nodes) in s.cells.iter().filter(|(k, _)| k.dim() + 1 == dim) {
            facets.push(kind, nodes);
        }
        groups.push(Group {
            name: s.head.name.clone(),
            tag: None,
            facets,
        });
    }
    if groups.len() > MAX_GROUPS {
        return Err(format!(
            "{at} has {} boundary groups, more than {MAX_GROUPS} (the most verbss reads)",
            groups.len()
        ));
    }
    Ok(groups)
}
