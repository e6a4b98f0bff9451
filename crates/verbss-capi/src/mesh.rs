//! The mesh from the caller's arrays: VTK cell kinds and node order, and
//! groups of the nodes the caller names (the moving nodes, each sliding
//! plane).

use std::collections::HashSet;

use verbss::{CellKind, Cells, Error, Group};

use crate::error::Failure;

/// Cell kind: 3-node triangle (VTK type id 5).
pub const VERBSS_TRIANGLE: i32 = 5;
/// Cell kind: 4-node quadrilateral (VTK 9).
pub const VERBSS_QUAD: i32 = 9;
/// Cell kind: 4-node tetrahedron (VTK 10).
pub const VERBSS_TETRA: i32 = 10;
/// Cell kind: 8-node hexahedron (VTK 12).
pub const VERBSS_HEXAHEDRON: i32 = 12;
/// Cell kind: 6-node prism (wedge), VTK's node order (VTK 13).
pub const VERBSS_WEDGE: i32 = 13;
/// Cell kind: 5-node pyramid (VTK 14).
pub const VERBSS_PYRAMID: i32 = 14;

fn kind_of(code: i32, cell: usize) -> Result<CellKind, Failure> {
    match CellKind::from_vtk_id(code.into()).filter(|k| k.dim() >= 2 && !k.is_general()) {
        Some(kind) => Ok(kind),
        None => Err(Error::InvalidMesh(format!(
            "cell {cell} has kind {code} (expected 5 triangle, 9 quad, 10 tetra, \
             12 hexahedron, 13 wedge or 14 pyramid)"
        ))
        .into()),
    }
}

/// A 0-based node id below `n`.
fn node_index(id: i64, n: usize, what: impl Fn() -> String) -> Result<usize, Failure> {
    usize::try_from(id).ok().filter(|&i| i < n).ok_or_else(|| {
        Error::InvalidMesh(format!(
            "{} is node {id}, not a node id of the mesh (0 to {})",
            what(),
            n as i64 - 1
        ))
        .into()
    })
}

/// The cells from VTK kinds and concatenated VTK-ordered nodes.
pub(crate) fn cells(kinds: &[i32], nodes: &[i64], n: usize) -> Result<Cells, Failure> {
    let mut cells = Cells::new();
    let mut next = 0;
    let mut local = Vec::with_capacity(8);
    for (c, &code) in kinds.iter().enumerate() {
        let kind = kind_of(code, c)?;
        let count = kind.node_count();
        let Some(stored) = nodes.get(next..next + count) else {
            return Err(too_few(kinds, nodes.len()));
        };
        local.clear();
        for k in 0..count {
            let id = stored[kind.vtk_local(k)];
            local.push(node_index(id, n, || format!("node {k} of cell {c}"))?);
        }
        cells.push(kind, &local);
        next += count;
    }
    if next != nodes.len() {
        return Err(Error::InvalidMesh(format!(
            "`cell_nodes` holds {} node ids but the {} cells use {next}",
            nodes.len(),
            kinds.len()
        ))
        .into());
    }
    Ok(cells)
}

fn too_few(kinds: &[i32], given: usize) -> Failure {
    let needed: usize = kinds
        .iter()
        .enumerate()
        .filter_map(|(c, &k)| kind_of(k, c).ok())
        .map(CellKind::node_count)
        .sum();
    Error::InvalidMesh(format!(
        "`cell_nodes` holds {given} node ids but the {} cells use {needed}",
        kinds.len()
    ))
    .into()
}

/// The group `name` of the distinct nodes `ids` of a mesh of `n` nodes, each
/// a vertex facet, and the nodes in the caller's order; `what(k)` names the
/// `k`-th id in messages ("moving node 3").
pub(crate) fn node_group(
    name: &str,
    ids: &[i64],
    n: usize,
    what: impl Fn(usize) -> String,
) -> Result<(Group, Vec<usize>), Failure> {
    let mut seen = HashSet::new();
    let mut nodes = Vec::with_capacity(ids.len());
    let mut facets = Cells::new();
    for (k, &id) in ids.iter().enumerate() {
        let i = node_index(id, n, || what(k))?;
        if !seen.insert(i) {
            return Err(
                Error::InvalidSetting(format!("{} is node {id}, listed twice", what(k))).into(),
            );
        }
        nodes.push(i);
        facets.push(CellKind::Vertex, &[i]);
    }
    let group = Group {
        name: name.into(),
        tag: None,
        facets,
    };
    Ok((group, nodes))
}

/// Adds to `group` the `facets` (a mesh's boundary facets) whose nodes all
/// lie in it: the facets that give a sliding group its own plane.
pub(crate) fn add_facets_within(group: &mut Group, facets: &Cells, n: usize) {
    let mut inside = vec![false; n];
    for &i in &group.facets.nodes {
        inside[i] = true;
    }
    for (kind, nodes) in facets.iter() {
        if nodes.iter().all(|&i| inside[i]) {
            group.facets.push(kind, nodes);
        }
    }
}
