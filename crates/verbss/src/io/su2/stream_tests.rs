//! The streamed read against the whole-file reader: the same entries in
//! chunks, the same messages.

use std::path::{Path, PathBuf};

use super::*;
use crate::mesh::Cells;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/su2/");

/// Appends `more` to `all`.
fn extend(all: &mut Cells, more: &Cells) {
    for (kind, nodes) in more.iter() {
        all.push(kind, nodes);
    }
}

/// The file at `path` streamed `lines` lines at a time and put together
/// again, with the outline and the number of chunks that held entries.
fn reassembled(path: &Path, lines: usize) -> Result<(Mesh, Outline, usize)> {
    let mut coords = Vec::new();
    let mut cells = Cells::new();
    let mut facets: Vec<Cells> = Vec::new();
    let mut dim = 0;
    let mut full = 0;
    let outline = stream(path, lines, |chunk| {
        assert_eq!(chunk.first_point, coords.len() / chunk.dim.max(1));
        assert_eq!(chunk.first_element, cells.len());
        let entries = chunk.coords.len() / chunk.dim.max(1)
            + chunk.cells.len()
            + chunk.facets.iter().map(|f| f.1.len()).sum::<usize>();
        assert!(
            entries <= lines,
            "{entries} entries in a chunk of {lines} lines"
        );
        full += usize::from(entries > 0);
        dim = chunk.dim;
        coords.extend_from_slice(&chunk.coords);
        extend(&mut cells, &chunk.cells);
        for (k, f) in &chunk.facets {
            facets.resize_with(facets.len().max(k + 1), Cells::new);
            extend(&mut facets[*k], f);
        }
        Ok(())
    })?;
    assert_eq!(outline.dim, dim);
    let mesh = Mesh {
        dim,
        node_tags: (1..=outline.points as u64).collect(),
        cell_tags: (1..=cells.len() as u64).collect(),
        coords,
        cells,
        groups: outline
            .markers
            .iter()
            .enumerate()
            .map(|(k, name)| crate::mesh::Group {
                name: name.clone(),
                tag: None,
                facets: facets.get(k).cloned().unwrap_or_else(Cells::new),
            })
            .collect(),
        origin: Default::default(),
    };
    Ok((mesh, outline, full))
}

#[test]
fn chunks_give_the_whole_file_reader_s_mesh() {
    for name in ["mesh_RAE2822_turb_ffd.su2", "mesh_brick_tets_ffd.su2"] {
        let path = PathBuf::from(DIR).join(name);
        let whole = parse(&std::fs::read(&path).unwrap(), &path).unwrap();
        for lines in [1, 97, 1_000_000] {
            let (mesh, outline, full) = reassembled(&path, lines).unwrap();
            assert_eq!(mesh.coords, whole.coords, "{name} by {lines}");
            assert_eq!(mesh.cells, whole.cells, "{name} by {lines}");
            assert_eq!(mesh.groups, whole.groups, "{name} by {lines}");
            assert_eq!(outline.elements, whole.cells.len());
            assert_eq!(outline.points, whole.node_count());
            let entries = whole.node_count()
                + whole.cells.len()
                + whole.groups.iter().map(|g| g.facets.len()).sum::<usize>();
            assert!(
                full >= entries.div_ceil(lines),
                "{name} by {lines}: {full} chunks"
            );
            assert!(outline.chunks >= full);
        }
    }
}

/// Every error of the whole-file reader on these files is the streamed
/// read's, word for word, whatever the chunk.
#[test]
fn errors_are_the_whole_file_reader_s() {
    let dir = tempfile::tempdir().unwrap();
    let good = "NDIME= 2\nNELEM= 2\n5 0 1 2\n9 0 1 2 3\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\n\
                NMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n3 0 1\n";
    let bad = [
        good.replace("NPOIN= 4\n0 0\n1 0\n1 1\n0 1\n", "NPOIN= 4\n0 0\n1 0\n"),
        good.replace("1 1\n", "1 x\n"),
        good.replace("3 0 1\n", "3 0 7\n"),
        good.replace("5 0 1 2\n", "10 0 1 2 3\n"),
        good.replace("NDIME= 2\n", ""),
        good.replace("MARKER_ELEMS= 1\n3 0 1\n", ""),
    ];
    for (k, text) in bad.iter().enumerate() {
        let path = dir.path().join(format!("bad{k}.su2"));
        std::fs::write(&path, text).unwrap();
        let expected = parse(text.as_bytes(), &path).unwrap_err().to_string();
        for lines in [1, 3, 100] {
            let e = reassembled(&path, lines).unwrap_err().to_string();
            assert_eq!(e, expected, "file {k} by {lines}");
        }
    }
    let path = dir.path().join("zones.su2");
    std::fs::write(&path, format!("NZONE= 2\nIZONE= 1\n{good}IZONE= 2\n{good}")).unwrap();
    assert_eq!(
        parse_zones(&std::fs::read(&path).unwrap(), &path)
            .unwrap()
            .len(),
        2
    );
    assert_eq!(
        reassembled(&path, 5).unwrap_err().to_string(),
        format!(
            "{}:1: NZONE= 2: a multi-zone file (expected one zone: a streamed read takes \
             single-zone files)",
            path.display()
        )
    );
}
