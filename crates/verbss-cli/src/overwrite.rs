//! The input mesh is never an output unless the user says so, and what an
//! output cannot keep of it is said.

use std::path::Path;

use anyhow::bail;
use verbss::io::su2::Anchor;
use verbss::io::{foam, Format};
use verbss::mesh::Mesh;

/// Fails when `output` is the mesh `input` (the same file, or the same
/// OpenFOAM polyMesh), unless `overwrite` (`--overwrite`). An OpenFOAM
/// output that gets its points in a new time directory (`time_dir`, as
/// `deform` writes into the input case) leaves `constant/polyMesh` as it
/// was, and passes.
pub fn refuse_input_as_output(
    input: &Path,
    output: &Path,
    overwrite: bool,
    time_dir: bool,
) -> anyhow::Result<()> {
    let both_foam = [input, output]
        .iter()
        .all(|p| matches!(Format::from_path(p), Ok(Format::Foam)));
    let same = if both_foam {
        foam::same_polymesh(input, output)
    } else {
        match (input.canonicalize(), output.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        }
    };
    if same && !overwrite && !(both_foam && time_dir) {
        bail!(
            "{}: the output is the input mesh {} (give --overwrite to replace it)",
            output.display(),
            input.display()
        );
    }
    Ok(())
}

/// Says on standard error that `output`, not an SU2 file, leaves out the
/// other zones of a multi-zone SU2 input and the sections of the SU2 input
/// that verbss does not use (FFD boxes, periodic data), naming their first
/// three keywords.
pub fn note_lost_su2_blocks(mesh: &Mesh, output: &Path) {
    if mesh.origin.su2_skipped.is_empty() || matches!(Format::from_path(output), Ok(Format::Su2)) {
        return;
    }
    let (zones, sections): (Vec<_>, Vec<_>) = mesh
        .origin
        .su2_skipped
        .iter()
        .partition(|b| matches!(b.after, Anchor::ZonesBefore | Anchor::ZonesAfter));
    if !zones.is_empty() {
        eprintln!(
            "note: {} leaves out the other zones of the multi-zone SU2 input \
             (only an .su2 output keeps them)",
            output.display()
        );
    }
    let keywords = sections.iter().flat_map(|b| {
        b.text.lines().filter_map(|l| {
            Some(format!(
                "{}=",
                l.split('%').next()?.split_once('=')?.0.trim()
            ))
        })
    });
    let mut named: Vec<String> = Vec::new();
    for k in keywords {
        if named.len() == 3 {
            named.push("…".into());
            break;
        }
        if !named.contains(&k) {
            named.push(k);
        }
    }
    if named.is_empty() {
        return;
    }
    eprintln!(
        "note: {} leaves out the input's SU2 sections {} (only an .su2 output keeps them)",
        output.display(),
        named.join(", ")
    );
}
