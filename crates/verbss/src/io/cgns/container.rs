//! The HDF5 groups of a CGNS file, checked before the node layer reads
//! them: the node layer reads a node's `name`, `label`, `type` and `flags`
//! attributes and its data's dimensions into places of a fixed size (33,
//! 33 and 3 bytes, one integer, 12 dimensions) and follows HDF5 soft and
//! external links. Each group is opened by its path from the root, one at a
//! time, within the node walk's bounds (`MAX_DEPTH`, `MAX_CHILDREN`,
//! `MAX_NODES` of [`super::check`]); a
//! file that is not HDF5 (ADF) is left to the node layer.

use std::path::Path;

use super::check::{crowded, nested, room, shown, MAX_DEPTH};
use super::ffi::{Attribute, Group, H5File, Object};

/// The attributes the node layer reads: name, whether a string, the most
/// bytes of its one value.
const ATTRIBUTES: [(&str, bool, usize); 4] = [
    ("name", true, 33),
    ("label", true, 33),
    ("type", true, 3),
    ("flags", false, 8),
];

/// Checks the HDF5 groups of the file `path` (see the module's doc).
pub(super) fn check(path: &Path) -> Result<(), String> {
    let Some(file) = H5File::open(path).map_err(|m| format!("cannot open as CGNS: {m}"))? else {
        return Ok(());
    };
    let root = file.root()?;
    let mut nodes = 0;
    let mut stack = vec![(String::new(), 0usize)];
    while let Some((at, depth)) = stack.pop() {
        let group = if at.is_empty() {
            file.root()?
        } else {
            root.group(&at[1..])?
        };
        attributes(&group, &at)?;
        let links = group.links(room(nodes)).map_err(|m| crowded(&at, &m))?;
        for (name, hard) in links {
            let path = format!("{at}/{name}");
            match group.object(&name, hard)? {
                Object::Other if name == " link" => {
                    return Err(format!(
                        "{}: a CGNS link to another node or file (verbss reads files whose nodes \
                         are all in the file)",
                        shown(&at)
                    ))
                }
                Object::Other => {
                    return Err(format!(
                        "{path}: an HDF5 soft or external link, or an object that is neither group \
                         nor dataset (verbss reads files whose nodes are all in the file)"
                    ))
                }
                Object::Dataset { rank } if !name.starts_with(' ') || rank > 12 => {
                    return Err(format!(
                        "{path}: an HDF5 dataset of rank {rank} (expected a CGNS node, or a node's \
                         data of rank 12 at most)"
                    ))
                }
                Object::Dataset { .. } => {}
                Object::Group if depth == MAX_DEPTH => return Err(nested(&at)),
                Object::Group => {
                    nodes += 1;
                    stack.push((path, depth + 1));
                }
            }
        }
    }
    Ok(())
}

/// Refuses a group whose attributes would overflow the node layer's places.
fn attributes(group: &Group, at: &str) -> Result<(), String> {
    for (name, string, most) in ATTRIBUTES {
        match group.attribute(name)? {
            None => {}
            Some(Attribute {
                string: s,
                size,
                values: 1,
            }) if s == string && size <= most => {}
            Some(a) => {
                return Err(format!(
                    "{}: the HDF5 attribute '{name}' holds {} value(s) of {} bytes, {} (expected \
                     one {} of at most {most} bytes)",
                    shown(at),
                    a.values,
                    a.size,
                    if a.string { "text" } else { "numbers" },
                    if string { "text" } else { "number" },
                ))
            }
        }
    }
    Ok(())
}
