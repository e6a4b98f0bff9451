//! The SU2 writer.

use std::collections::HashMap;
use std::io::Write;

use super::Anchor;
use crate::mesh::{CellKind, Mesh};

/// Writes `mesh` in SU2 format: `NDIME=`, `NELEM=` (elements with their index),
/// `NPOIN=` (coordinates in shortest round-trip form, so that reading the file
/// back gives the same bits, with their index), `NMARK=` and one marker per
/// group, with the mesh's [`FileOrigin::su2_skipped`](crate::mesh::FileOrigin::su2_skipped) blocks put back verbatim after
/// the section each followed (after the last marker when that marker is gone;
/// the other zones of a multi-zone file before and after everything).
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] for a group name an SU2 file
/// cannot hold (empty, with surrounding spaces, a `%` or a control character).
pub fn write_to(w: &mut dyn Write, mesh: &Mesh) -> std::io::Result<()> {
    write_moved_to(w, mesh, &mesh.coords)
}

/// [`write_to`] with the nodes at `coords` (`dim` numbers per node) instead
/// of the mesh's own.
pub fn write_moved_to(w: &mut dyn Write, mesh: &Mesh, coords: &[f64]) -> std::io::Result<()> {
    write_sections(w, mesh, coords, true)
}

/// Writes `zones` as one multi-zone SU2 file, as SU2 writes it: `NZONE= n`,
/// then each zone after its `IZONE= k` line (k from 1), in the layout of
/// [`write_to`] without the zones a mesh was read beside.
pub fn write_zones_to(w: &mut dyn Write, zones: &[Mesh]) -> std::io::Result<()> {
    writeln!(w, "NZONE= {}", zones.len())?;
    for (k, mesh) in zones.iter().enumerate() {
        writeln!(w, "IZONE= {}", k + 1)?;
        write_sections(w, mesh, &mesh.coords, false)?;
    }
    Ok(())
}

/// Writes the sections of `mesh` with its nodes at `coords`, and the other
/// zones of its file when `zones`.
fn write_sections(
    w: &mut dyn Write,
    mesh: &Mesh,
    coords: &[f64],
    zones: bool,
) -> std::io::Result<()> {
    for g in &mesh.groups {
        let name = g.name.as_str();
        if name.is_empty()
            || name.trim() != name
            || name.contains('%')
            || name.chars().any(char::is_control)
        {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!("group name {name:?} cannot be written as an SU2 MARKER_TAG"),
            ));
        }
    }
    let markers = mesh.groups.len();
    let mut skipped: HashMap<Anchor, Vec<&str>> = HashMap::new();
    for b in &mesh.origin.su2_skipped {
        if !zones && matches!(b.after, Anchor::ZonesBefore | Anchor::ZonesAfter) {
            continue;
        }
        let after = match b.after {
            Anchor::Marker(k) if k >= markers => markers
                .checked_sub(1)
                .map_or(Anchor::MarkerCount, Anchor::Marker),
            a => a,
        };
        skipped.entry(after).or_default().push(&b.text);
    }
    let mut put_back = |w: &mut dyn Write, after: Anchor| -> std::io::Result<()> {
        for text in skipped.remove(&after).unwrap_or_default() {
            w.write_all(text.as_bytes())?;
            if !text.ends_with('\n') {
                writeln!(w)?;
            }
        }
        Ok(())
    };
    put_back(w, Anchor::ZonesBefore)?;
    put_back(w, Anchor::Start)?;
    writeln!(w, "NDIME= {}", mesh.dim)?;
    put_back(w, Anchor::Dimension)?;
    writeln!(w, "NELEM= {}", mesh.cells.len())?;
    for (c, (kind, nodes)) in mesh.cells.iter().enumerate() {
        write_element(w, kind, nodes)?;
        writeln!(w, "\t{c}")?;
    }
    put_back(w, Anchor::Elements)?;
    writeln!(w, "NPOIN= {}", mesh.node_count())?;
    for i in 0..mesh.node_count() {
        for x in &coords[mesh.dim * i..mesh.dim * (i + 1)] {
            write!(w, "{x:?}\t")?;
        }
        writeln!(w, "{i}")?;
    }
    put_back(w, Anchor::Points)?;
    writeln!(w, "NMARK= {markers}")?;
    put_back(w, Anchor::MarkerCount)?;
    for (k, g) in mesh.groups.iter().enumerate() {
        writeln!(w, "MARKER_TAG= {}", g.name)?;
        writeln!(w, "MARKER_ELEMS= {}", g.facets.len())?;
        for (kind, nodes) in g.facets.iter() {
            write_element(w, kind, nodes)?;
            writeln!(w)?;
        }
        put_back(w, Anchor::Marker(k))?;
    }
    put_back(w, Anchor::ZonesAfter)
}

/// Writes `type n1 … nk` without the end of line, in SU2's (VTK's) node order.
fn write_element(w: &mut dyn Write, kind: CellKind, nodes: &[usize]) -> std::io::Result<()> {
    write!(w, "{}", kind.vtk_id())?;
    for i in 0..nodes.len() {
        write!(w, "\t{}", nodes[kind.vtk_local(i)])?;
    }
    Ok(())
}
