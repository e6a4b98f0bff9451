//! The reader against hostile files: bounded markers, a byte-order mark, a
//! duplicated element.

use std::path::Path;

use super::*;
use crate::io::MAX_GROUPS;

/// A unit square of two triangles with `markers` markers of one line each.
fn square(markers: usize) -> String {
    let mut s = format!(
        "NDIME= 2\nNELEM= 2\n5 0 1 2\n5 0 2 3\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\nNMARK= {markers}\n"
    );
    for k in 0..markers {
        s += &format!("MARKER_TAG= m{k}\nMARKER_ELEMS= 1\n3 0 1\n");
    }
    s
}

fn read(text: &str) -> Result<Mesh> {
    parse(text.as_bytes(), Path::new("s.su2"))
}

#[test]
fn markers_are_bounded() {
    assert_eq!(read(&square(MAX_GROUPS)).unwrap().groups.len(), MAX_GROUPS);
    let text = square(1).replace("NMARK= 1", "NMARK= 400000");
    assert_eq!(
        read(&text).unwrap_err().to_string(),
        "s.su2:10: NMARK= 400000 is more than 65536 markers (the most verbss reads)"
    );
}

#[test]
fn a_byte_order_mark_is_skipped_and_a_duplicated_element_named() {
    let plain = square(1);
    assert_eq!(
        read(&format!("\u{feff}{plain}")).unwrap(),
        read(&plain).unwrap()
    );
    let twice = plain.replace("5 0 2 3", "5 2 1 0");
    assert_eq!(
        read(&twice).unwrap_err().to_string(),
        "s.su2:2: invalid mesh: elements 1 and 2 have the same nodes (a duplicated element)"
    );
}
