//! Every file a command writes, checked before the first solve against
//! every file it reads and against each other: compared where they resolve
//! (links followed; a file not made yet by its folder's resolved path and
//! its name), and refused when it is a FIFO, device, socket or directory.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use super::{link_target, special_kind};
use crate::error::{Error, Result};

/// What an input mesh is called in messages (see [`Output::overwrite`]).
pub const MESH: &str = "the input mesh";

/// A file a command reads.
#[derive(Debug, Clone, PartialEq)]
pub struct Input {
    /// What it is, for messages (`the input mesh`, `the positions file`).
    pub what: &'static str,
    /// Its path.
    pub path: PathBuf,
}

/// A file a command will write.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// The option (or case-file key) that names it: `-o`, `--report`, `--every`.
    pub flag: String,
    /// Its path.
    pub path: PathBuf,
    /// It is written by replacing a link at `path` (the files of an
    /// OpenFOAM case), not the link's target.
    pub replaces_link: bool,
    /// Whether it may be the input mesh ([`MESH`]): `Some(true)` when the
    /// user gave `--overwrite`, `Some(false)` when the option would allow
    /// it, `None` where no option does.
    pub overwrite: Option<bool>,
}

impl Output {
    /// The output `path` named by `flag`, written through a link at it.
    pub fn new(flag: impl Into<String>, path: impl Into<PathBuf>) -> Output {
        Output {
            flag: flag.into(),
            path: path.into(),
            replaces_link: false,
            overwrite: None,
        }
    }
}

/// Fails, naming the option and the path, when an output is a FIFO,
/// device, socket or directory, when it would replace an input, or when
/// two outputs are one file.
pub fn check(inputs: &[Input], outputs: &[Output]) -> Result<()> {
    let read: Vec<(PathBuf, &Input)> = inputs
        .iter()
        .map(|i| (resolved(&i.path, true), i))
        .collect();
    let mut written: Vec<(PathBuf, &Output)> = Vec::with_capacity(outputs.len());
    for o in outputs {
        let refuse = |message: String| Error::Output {
            flag: o.flag.clone(),
            path: o.path.clone(),
            message,
        };
        let kind = if o.replaces_link {
            std::fs::symlink_metadata(&o.path).ok().and_then(|m| {
                (!m.file_type().is_symlink())
                    .then(|| special_kind(&o.path))
                    .flatten()
            })
        } else {
            special_kind(&o.path)
        };
        if let Some(what) = kind.or(o.path.is_dir().then_some("a directory")) {
            return Err(refuse(format!(
                "{what}, not a regular file (verbss writes its outputs to regular files only)"
            )));
        }
        let at = resolved(&o.path, !o.replaces_link);
        let allowed = |i: &Input| i.what == MESH && o.overwrite == Some(true);
        if let Some((_, input)) = read.iter().find(|(r, i)| *r == at && !allowed(i)) {
            return Err(refuse(match (input.what, o.overwrite) {
                (MESH, Some(_)) => format!(
                    "the output is the input mesh {} (give --overwrite to replace it)",
                    input.path.display()
                ),
                _ => format!(
                    "it would replace {} {} (verbss never writes over an input file)",
                    input.what,
                    input.path.display()
                ),
            }));
        }
        if let Some((_, other)) = written.iter().find(|(w, _)| *w == at) {
            return Err(refuse(format!(
                "also the output of {} ({}): each output needs its own file",
                other.flag,
                other.path.display()
            )));
        }
        written.push((at, o));
    }
    Ok(())
}

/// Where `path` resolves: canonical when it exists (its links followed
/// when `follow`, also a link to a file not made yet), else its nearest
/// existing folder's canonical path and the rest of it.
pub fn resolved(path: &Path, follow: bool) -> PathBuf {
    if follow {
        if let Ok(p) = path.canonicalize() {
            return p;
        }
    }
    let at = below_existing(path);
    let is_link = std::fs::symlink_metadata(&at).is_ok_and(|m| m.file_type().is_symlink());
    match follow && is_link {
        true => below_existing(&link_target(&at)),
        false => at,
    }
}

/// `path` made absolute: the canonical path of its folder's nearest
/// existing ancestor and the rest of it, its last part not followed.
fn below_existing(path: &Path) -> PathBuf {
    let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut rest: Vec<OsString> = Vec::new();
    let mut at = path.as_path();
    while let (Some(parent), Some(last)) = (at.parent(), at.components().next_back()) {
        rest.push(last.as_os_str().to_os_string());
        at = parent;
        if let Ok(mut p) = at.canonicalize() {
            // What is below the existing folder is no link: `..` is its parent.
            for part in rest.iter().rev() {
                match part.to_str() {
                    Some("..") => {
                        p.pop();
                    }
                    Some(".") => {}
                    _ => p.push(part),
                }
            }
            return p;
        }
    }
    path
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_compared_where_they_resolve() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = dir.path().join("x_0001.vtu");
        std::fs::write(&mesh, "mesh").unwrap();
        std::os::unix::fs::symlink("x_0001.vtu", dir.path().join("link.vtu")).unwrap();
        let inputs = [Input {
            what: MESH,
            path: mesh.clone(),
        }];
        let o = |flag: &str, name: &str| Output::new(flag, dir.path().join("new/..").join(name));
        let e = check(&inputs, &[o("--every", "x_0001.vtu")]).unwrap_err();
        assert!(
            e.to_string()
                .contains("x_0001.vtu: it would replace the input mesh"),
            "{e}"
        );
        let e = check(&inputs, &[o("--report", "link.vtu")]).unwrap_err();
        assert!(e.to_string().starts_with("--report "), "{e}");
        let e = check(&inputs, &[o("-o", "a.vtu"), o("--report", "a.vtu")]).unwrap_err();
        assert!(
            e.to_string().contains("a.vtu: also the output of -o"),
            "{e}"
        );
        let mut replaced = o("-o", "link.vtu");
        replaced.replaces_link = true;
        assert!(check(&inputs, &[replaced]).is_ok());
        let e = check(&inputs, &[Output::new("--html", dir.path())]).unwrap_err();
        assert!(
            e.to_string().contains(": a directory, not a regular file"),
            "{e}"
        );
    }
}
