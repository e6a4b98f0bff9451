//! A moved mesh written from its coordinates ([`super::write_moved`]) is
//! the file a copy of the mesh with those coordinates writes, in every
//! format and encoding.

use std::path::Path;

use super::{read, write, write_moved, WriteOptions};
use crate::mesh::Mesh;

fn asset(name: &str) -> Mesh {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/meshes/gmsh");
    read(&dir.join(name)).unwrap()
}

/// Every coordinate moved by a different amount.
fn moved(mesh: &Mesh) -> Vec<f64> {
    mesh.coords
        .iter()
        .enumerate()
        .map(|(k, x)| x + 1e-3 * (k % 7) as f64 - 2e-3)
        .collect()
}

#[test]
fn a_moved_mesh_is_written_as_a_copy_with_its_coordinates_is() {
    let dir = tempfile::tempdir().unwrap();
    for name in [
        "channel_hole_v41_ascii.msh",
        "channel_hole_v22_binary.msh",
        "box_v41_ascii.msh",
    ] {
        let mesh = asset(name);
        let coords = moved(&mesh);
        let mut copy = mesh.clone();
        copy.coords.clone_from(&coords);
        for ext in ["msh", "su2", "vtu"] {
            let options = WriteOptions::for_mesh(&mesh);
            let (a, b) = (
                dir.path().join(format!("a.{ext}")),
                dir.path().join(format!("b.{ext}")),
            );
            write_moved(&a, &mesh, &coords, &options).unwrap();
            write(&b, &copy, &options).unwrap();
            let (a, b) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
            assert!(a == b, "{name} as .{ext}: the files differ");
            assert_eq!(
                read(&dir.path().join(format!("a.{ext}"))).unwrap().coords,
                coords
            );
        }
    }
}

#[test]
fn coordinates_of_the_wrong_length_are_refused() {
    let mesh = asset("box_v41_ascii.msh");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.msh");
    let short = &mesh.coords[..mesh.coords.len() - 1];
    let e = write_moved(&path, &mesh, short, &WriteOptions::default()).unwrap_err();
    assert!(e.to_string().contains("coordinates for the"), "{e}");
    assert!(!path.exists());
}

/// A FIFO (as a device or socket) is refused as a file to write (through
/// the library, as Python and C write): writing into a FIFO would block until someone
/// reads it, and the file would never be whole.
#[test]
fn a_fifo_is_refused_as_a_file_to_write() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("mesh.vtu");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    let mesh = asset("channel_hole_v41_ascii.msh");
    let err = write(&fifo, &mesh, &WriteOptions::default()).unwrap_err();
    assert!(
        err.to_string().contains("a device, FIFO or socket"),
        "{err}"
    );
}
