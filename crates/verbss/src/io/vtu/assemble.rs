//! The last step of the `.vtu` reader: the cells split into volume cells and
//! groups, the tags and fields, the mesh checked.

use std::collections::HashMap;

use super::read::{Array, VtkFile};
use super::xml::Element;
use super::{Fields, VtuData, CELL_TAG_ARRAY, GROUP_ARRAY, NODE_TAG_ARRAY, UNNAMED_GROUP};
use crate::error::Result;
use crate::mesh::{Cells, FileOrigin, Group, Mesh};

/// Removes the array called `name` from `arrays`.
fn take_array<'e>(arrays: &mut Vec<Array<'e>>, name: &str) -> Option<Array<'e>> {
    let i = arrays.iter().position(|a| a.name == name)?;
    Some(arrays.remove(i))
}

/// Tags from an integer array (each ≥ 1), or `1..=count` when there is none,
/// of the `count` entries at `keep` (all when `None`).
fn tags(
    file: &VtkFile,
    array: Option<Array>,
    what: &str,
    count: usize,
    keep: Option<&[usize]>,
) -> Result<Vec<u64>> {
    let Some(a) = array else {
        return Ok((1..=count as u64).collect());
    };
    let values = file.ints(&a, None)?;
    (0..count)
        .map(|k| keep.map_or(k, |keep| keep[k]))
        .map(|i| {
            u64::try_from(values[i])
                .ok()
                .filter(|&t| t >= 1)
                .ok_or_else(|| {
                    file.ctx.at(
                        a.el.pos,
                        format!(
                            "DataArray '{}': {what} {i} has tag {} (tags are ≥ 1)",
                            a.name, values[i]
                        ),
                    )
                })
        })
        .collect()
}

/// Splits the cells into volume cells and groups and builds the mesh (module doc).
pub(super) fn assemble(
    file: &VtkFile,
    piece: &Element,
    coords: Vec<f64>,
    all: Cells,
    mut point_data: Vec<Array>,
    mut cell_data: Vec<Array>,
    names: Vec<(i64, String, Option<i32>)>,
) -> Result<VtuData> {
    let ctx = file.ctx;
    let n = coords.len() / 3;
    let top = all
        .kinds
        .iter()
        .map(|k| k.dim())
        .max()
        .ok_or_else(|| ctx.at(piece.pos, "the file has no cells".into()))?;
    let off_plane = (0..n).find(|&i| coords[3 * i + 2] != 0.0);
    let dim = if top <= 2 && off_plane.is_none() {
        2
    } else {
        3
    };
    if top < dim {
        let message = match off_plane {
            Some(i) if dim == 3 => format!(
                "no 3D cells but point {i} has z = {} (surface meshes are not supported)",
                coords[3 * i + 2]
            ),
            _ => "no 2D or 3D cells (only lines and vertices)".to_string(),
        };
        return Err(ctx.at(piece.pos, message));
    }

    let group_array = take_array(&mut cell_data, GROUP_ARRAY);
    let group_ids = match &group_array {
        Some(a) => Some(file.ints(a, None)?),
        None => None,
    };
    let mut groups: Vec<Group> = names
        .iter()
        .map(|(_, name, tag)| Group {
            name: name.clone(),
            tag: *tag,
            facets: Cells::new(),
        })
        .collect();
    // The first group of each id (a map: a facet-by-name scan is quadratic).
    let mut by_id = HashMap::new();
    for (k, g) in names.iter().enumerate() {
        by_id.entry(g.0).or_insert(k);
    }
    // All cells volume cells (no group facets): no copy.
    let (volume, cells) = if all.kinds.iter().all(|k| k.dim() == dim) {
        ((0..all.len()).collect(), all)
    } else {
        let mut volume = Vec::new();
        let mut cells = Cells::new();
        let mut unnamed = None;
        for (c, (kind, nodes)) in all.iter().enumerate() {
            if kind.dim() == dim {
                volume.push(c);
                cells.push_from(&all, c, |v| v);
                continue;
            }
            let named = by_id.get(&group_ids.map_or(0, |g| g[c])).copied();
            let k = named.unwrap_or_else(|| {
                *unnamed.get_or_insert_with(|| {
                    groups.push(Group {
                        name: UNNAMED_GROUP.to_string(),
                        tag: None,
                        facets: Cells::new(),
                    });
                    groups.len() - 1
                })
            });
            groups[k].facets.push(kind, nodes);
        }
        (volume, cells)
    };

    let node_tags = tags(
        file,
        take_array(&mut point_data, NODE_TAG_ARRAY),
        "point",
        n,
        None,
    )?;
    let cell_tags = tags(
        file,
        take_array(&mut cell_data, CELL_TAG_ARRAY),
        "cell",
        volume.len(),
        Some(&volume),
    )?;
    let fields = Fields {
        point: point_data
            .into_iter()
            .map(|a| (a.name, a.components, a.values.into_f64()))
            .collect(),
        cell: cell_data
            .into_iter()
            .map(|a| {
                let values = a.values.into_f64();
                let rows = volume
                    .iter()
                    .flat_map(|&c| &values[c * a.components..(c + 1) * a.components]);
                (a.name, a.components, rows.copied().collect())
            })
            .collect(),
    };
    let mut coords = coords;
    if dim == 2 {
        // x y z to x y, in place.
        for i in 0..n {
            coords.copy_within(3 * i..3 * i + 2, 2 * i);
        }
        coords.truncate(2 * n);
        coords.shrink_to_fit();
    }
    let mesh = Mesh {
        dim,
        coords,
        node_tags,
        cells,
        cell_tags,
        groups,
        origin: FileOrigin::default(),
    };
    mesh.validate()
        .map_err(|e| crate::io::invalid_at(e, |m| ctx.at(piece.pos, m)))?;
    Ok(VtuData { mesh, fields })
}
