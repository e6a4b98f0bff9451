//! A mesh read from a file is written back as that file with only its node
//! coordinates changed, unless its structure or the encoding changed.

use std::path::Path;

use super::{assert_same, mixed_3d, written, ENCODINGS};
use crate::io::gmsh::parse;
use crate::mesh::Mesh;

/// A section the reader skips, appended to every file.
const COMMENTS: &[u8] = b"$Comments\nkept as it is\n$EndComments\n";

/// `mesh` written in `encoding`, with [`COMMENTS`] appended, and read back.
fn file_and_mesh(mesh: &Mesh, (version, binary): (crate::io::MshVersion, bool)) -> (Vec<u8>, Mesh) {
    let mut bytes = written(mesh, version, binary);
    bytes.extend_from_slice(COMMENTS);
    let read = parse(&bytes, Path::new("t.msh")).unwrap();
    (bytes, read)
}

#[test]
fn an_unchanged_mesh_is_written_back_byte_for_byte() {
    for encoding in ENCODINGS {
        let (bytes, read) = file_and_mesh(&mixed_3d(), encoding);
        assert!(
            written(&read, encoding.0, encoding.1) == bytes,
            "{encoding:?}"
        );
    }
}

#[test]
fn a_moved_mesh_changes_only_its_coordinates() {
    for encoding in ENCODINGS {
        let (bytes, mut read) = file_and_mesh(&mixed_3d(), encoding);
        read.coords[0] += 0.5;
        read.coords[4] = -1.0 / 3.0;
        let out = written(&read, encoding.0, encoding.1);
        let back = parse(&out, Path::new("t.msh")).unwrap();
        assert_same(&back, &read);
        assert!(out.ends_with(COMMENTS), "{encoding:?}");
        // Only the bytes of nodes 0 and 1, inside $Nodes, differ.
        let same_start = bytes.iter().zip(&out).take_while(|(a, b)| a == b).count();
        let same_end = bytes
            .iter()
            .rev()
            .zip(out.iter().rev())
            .take_while(|(a, b)| a == b)
            .count();
        let find = |key: &[u8]| bytes.windows(key.len()).position(|w| w == key).unwrap();
        assert!(same_start > find(b"$Nodes\n"), "{encoding:?}");
        assert!(
            out.len() - same_end < find(b"$EndNodes\n") + out.len() - bytes.len(),
            "{encoding:?}"
        );
        assert!(out.len() - same_end - same_start < 100, "{encoding:?}");
    }
}

#[test]
fn a_changed_mesh_or_another_encoding_is_written_anew() {
    for encoding in ENCODINGS {
        let (_, read) = file_and_mesh(&mixed_3d(), encoding);
        let mut fresh = read.clone();
        fresh.origin.gmsh = None;
        for other in ENCODINGS.iter().filter(|&&e| e != encoding) {
            assert!(
                written(&read, other.0, other.1) == written(&fresh, other.0, other.1),
                "{encoding:?} as {other:?}"
            );
        }
        let mut fewer = read.clone();
        fewer.groups.pop();
        fresh.groups.pop();
        let out = written(&fewer, encoding.0, encoding.1);
        assert!(
            out == written(&fresh, encoding.0, encoding.1),
            "{encoding:?}"
        );
        assert!(!out.ends_with(COMMENTS), "{encoding:?}");
    }
}

/// With its bytes moved to a temporary file, the source writes the same
/// file as with them in memory, and again on a second write.
#[test]
fn a_spilled_source_writes_the_same_file() {
    let dir = tempfile::tempdir().unwrap();
    for encoding in ENCODINGS {
        let (_, mut read) = file_and_mesh(&mixed_3d(), encoding);
        read.coords[0] += 0.5;
        read.coords[5] = 1.0 / 7.0;
        let held = written(&read, encoding.0, encoding.1);
        let source = read.origin.gmsh.as_ref().unwrap();
        source.spill(dir.path()).unwrap();
        assert!(format!("{source:?}").contains("temporary file"));
        assert!(
            written(&read, encoding.0, encoding.1) == held,
            "{encoding:?}"
        );
        assert!(
            written(&read, encoding.0, encoding.1) == held,
            "{encoding:?}"
        );
    }
}
