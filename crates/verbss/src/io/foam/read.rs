//! Reading the five files of a `polyMesh` directory into their lists.

use std::path::{Path, PathBuf};

use super::file::{self, end, header, label_below};
use super::interfaces::Coupled;
use super::lex::Lexer;
use crate::error::{Error, Result};
use crate::io::{shown, MAX_GROUPS};

/// A boundary patch of the `boundary` file.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Patch {
    /// The patch name.
    pub name: String,
    /// Its `type` (`wall`, `patch`, `empty`, …).
    pub kind: String,
    /// Its faces: `start_face .. start_face + n_faces`.
    pub start_face: usize,
    /// How many faces.
    pub n_faces: usize,
    /// The line of its name in the `boundary` file.
    pub line: usize,
    /// Its coupling entries (`neighbourPatch`, `transform`, …).
    pub coupled: Coupled,
}

/// The lists of a `polyMesh` directory, checked against each other.
pub(super) struct PolyMesh {
    /// The directory.
    pub dir: PathBuf,
    /// `x y z` of each point.
    pub points: Vec<f64>,
    /// The line of each point in the `points` file.
    pub point_lines: Vec<u32>,
    /// Face `f`'s points are `face_nodes[face_offsets[f]..face_offsets[f + 1]]`.
    pub face_offsets: Vec<usize>,
    /// The points of all faces, face after face.
    pub face_nodes: Vec<usize>,
    /// The cell that owns each face (the face's normal points out of it).
    pub owner: Vec<usize>,
    /// The line of each face's owner in the `owner` file.
    pub owner_lines: Vec<u32>,
    /// The other cell of each internal face (faces `0..neighbour.len()`).
    pub neighbour: Vec<usize>,
    /// The boundary patches, in file order.
    pub patches: Vec<Patch>,
}

impl PolyMesh {
    /// The number of faces.
    pub fn n_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }

    /// The points of face `f`.
    pub fn face(&self, f: usize) -> &[usize] {
        &self.face_nodes[self.face_offsets[f]..self.face_offsets[f + 1]]
    }

    /// The path of file `name` of the directory.
    pub fn file(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }
}

/// The bytes of `dir/name`; a missing file gets a message naming it (and
/// saying so when only a compressed `name.gz` is there).
fn bytes_of(dir: &Path, name: &str) -> Result<(PathBuf, Vec<u8>)> {
    let path = dir.join(name);
    crate::io::regular_input(&path)?;
    match std::fs::read(&path) {
        Ok(b) => Ok((path, b)),
        Err(source) if dir.join(format!("{name}.gz")).is_file() => Err(Error::Io {
            path: path.clone(),
            source: std::io::Error::new(
                source.kind(),
                format!(
                    "only {name}.gz is there: compressed polyMesh files are not supported \
                     (gunzip them, or write the case with `writeCompression off;`)"
                ),
            ),
        }),
        Err(source) => Err(Error::Io { path, source }),
    }
}

/// Reads `points`, `faces`, `owner`, `neighbour` and `boundary` of `dir`.
pub(super) fn read(dir: &Path) -> Result<PolyMesh> {
    let (points, point_lines) = points(dir)?;
    let n_points = points.len() / 3;
    let (face_offsets, face_nodes) = faces(dir, n_points)?;
    let n_faces = face_offsets.len() - 1;
    let (owner, owner_lines) = labels(dir, "owner", "cell labels", n_faces, n_faces)?;
    if owner.len() != n_faces {
        return Err(parse_err(
            &dir.join("owner"),
            1,
            format!(
                "{} owners for the {n_faces} faces (expected one per face)",
                owner.len()
            ),
        ));
    }
    let (neighbour, _) = labels(dir, "neighbour", "cell labels", n_faces, n_faces)?;
    let patches = boundary(dir)?;
    check_patches(dir, &patches, neighbour.len(), n_faces)?;
    Ok(PolyMesh {
        dir: dir.to_path_buf(),
        points,
        point_lines,
        face_offsets,
        face_nodes,
        owner,
        owner_lines,
        neighbour,
        patches,
    })
}

fn parse_err(path: &Path, line: usize, message: String) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    }
}

/// `points`: a list of `(x y z)`.
fn points(dir: &Path) -> Result<(Vec<f64>, Vec<u32>)> {
    let (path, bytes) = bytes_of(dir, "points")?;
    let mut lx = Lexer::new(&bytes, &path);
    if let Some(arch) = header(&mut lx)?.binary {
        let (data, line) = file::raw_list(&mut lx, "points", 3 * arch.scalar)?;
        let xyz = file::raw_scalars(&lx, line, data, arch.scalar)?;
        end(&mut lx)?;
        let lines = vec![line as u32; xyz.len() / 3];
        return Ok((xyz, lines));
    }
    let (xyz, lines) = file::list(&mut lx, "points", 0, 7, |lx, t| {
        if t.text != "(" {
            return Err(lx.err(
                t.line,
                format!("expected a point (x y z), found '{}'", shown(t.text)),
            ));
        }
        let p = [lx.scalar("x")?, lx.scalar("y")?, lx.scalar("z")?];
        lx.expect(")", "after the 3 coordinates of a point")?;
        Ok(p)
    })?;
    end(&mut lx)?;
    Ok((xyz.into_iter().flatten().collect(), lines))
}

/// `faces`: a `faceList` of `k(p0 … pk-1)`, or a `faceCompactList` (the
/// offsets, then the points); every point below `n_points`.
fn faces(dir: &Path, n_points: usize) -> Result<(Vec<usize>, Vec<usize>)> {
    let (path, bytes) = bytes_of(dir, "faces")?;
    let mut lx = Lexer::new(&bytes, &path);
    let head = header(&mut lx)?;
    let mut nodes = Vec::new();
    let mut offsets = vec![0];
    if head.class.as_deref() == Some("faceCompactList") {
        let line = lx.next_line()?;
        let starts;
        if let Some(arch) = head.binary {
            let (data, at) = file::raw_list(&mut lx, "face offsets", arch.label)?;
            starts = file::raw_labels(&lx, at, data, arch.label, "face offset", usize::MAX)?;
            let (data, at) = file::raw_list(&mut lx, "face points", arch.label)?;
            nodes = file::raw_labels(&lx, at, data, arch.label, "point label", n_points)?;
        } else {
            (starts, _) = file::list(&mut lx, "face offsets", 0, 2, |lx, t| {
                label_below(lx, t, "face offset", usize::MAX)
            })?;
            (nodes, _) = file::list(&mut lx, "face points", 0, 2, |lx, t| {
                label_below(lx, t, "point label", n_points)
            })?;
        }
        let bad = starts.first() != Some(&0)
            || starts.last() != Some(&nodes.len())
            || starts.windows(2).any(|w| w[1] < w[0].saturating_add(3));
        if bad {
            return Err(lx.err(
                line,
                format!(
                    "the face offsets do not start at 0, grow by 3 or more and end at {} \
                     (the number of face points)",
                    nodes.len()
                ),
            ));
        }
        offsets = starts;
    } else if head.binary.is_some() {
        return Err(lx.err(
            lx.line(),
            "a binary faces file of class faceList (expected faceCompactList, as OpenFOAM \
             writes binary faces)"
                .into(),
        ));
    } else {
        file::list(&mut lx, "faces", 0, 8, |lx, t| {
            let k = label_below(lx, t, "face size", usize::MAX)?;
            if k < 3 {
                return Err(lx.err(t.line, format!("a face of {k} points (expected 3 or more)")));
            }
            lx.expect("(", "after the face size")?;
            for _ in 0..k {
                let p = lx.expect_any("a point label")?;
                nodes.push(label_below(lx, p, "point label", n_points)?);
            }
            lx.expect(")", &format!("after the {k} points of a face"))?;
            offsets.push(nodes.len());
            Ok(())
        })?;
    }
    end(&mut lx)?;
    Ok((offsets, nodes))
}

/// A list of labels below `bound` (`N{label}` allowed up to `max_uniform`),
/// with the line of each.
fn labels(
    dir: &Path,
    name: &str,
    what: &str,
    bound: usize,
    max_uniform: usize,
) -> Result<(Vec<usize>, Vec<u32>)> {
    let (path, bytes) = bytes_of(dir, name)?;
    let mut lx = Lexer::new(&bytes, &path);
    let list = match header(&mut lx)?.binary {
        Some(arch) => {
            let (data, line) = file::raw_list(&mut lx, what, arch.label)?;
            let labels = file::raw_labels(&lx, line, data, arch.label, "cell label", bound)?;
            let lines = vec![line as u32; labels.len()];
            (labels, lines)
        }
        None => file::list(&mut lx, what, max_uniform, 2, |lx, t| {
            label_below(lx, t, "cell label", bound)
        })?,
    };
    end(&mut lx)?;
    Ok(list)
}

/// Fails unless each patch's faces are boundary faces (from the first face
/// that has no neighbour to the last face), no face in two patches.
fn check_patches(dir: &Path, patches: &[Patch], n_internal: usize, n_faces: usize) -> Result<()> {
    let mut order: Vec<&Patch> = patches.iter().filter(|p| p.n_faces > 0).collect();
    order.sort_by_key(|p| p.start_face);
    let mut free = n_internal;
    for p in order {
        let end = p
            .start_face
            .checked_add(p.n_faces)
            .filter(|&e| e <= n_faces);
        let message = if p.start_face < free {
            format!(
                "patch '{}' starts at face {} (expected {free} or later: faces below {n_internal} \
                 are internal, and no face is in two patches)",
                p.name, p.start_face
            )
        } else if let Some(e) = end {
            free = e;
            continue;
        } else {
            format!(
                "patch '{}' runs past the last face (startFace {} + nFaces {} > {n_faces} faces)",
                p.name, p.start_face, p.n_faces
            )
        };
        return Err(parse_err(&dir.join("boundary"), p.line, message));
    }
    Ok(())
}

/// `boundary`: a list of `name { type T; nFaces N; startFace S; … }`.
fn boundary(dir: &Path) -> Result<Vec<Patch>> {
    let (path, bytes) = bytes_of(dir, "boundary")?;
    let mut lx = Lexer::new(&bytes, &path);
    header(&mut lx)?;
    let (patches, _) = file::list(&mut lx, "patches", 0, 8, |lx, t| {
        if matches!(t.text, "(" | ")" | "{" | "}" | ";") {
            return Err(lx.err(t.line, format!("expected a patch name, found '{}'", t.text)));
        }
        lx.expect("{", &format!("after the patch name {}", shown(t.text)))?;
        let (mut kind, mut n_faces, mut start_face) = (None, None, None);
        let mut coupled = Coupled::default();
        loop {
            let key = lx.expect_any("a patch entry or '}'")?;
            match key.text {
                "}" => break,
                "type" => kind = Some(lx.expect_any("the patch type")?.text.to_string()),
                "nFaces" => n_faces = Some(lx.label("nFaces (a count)")?.0),
                "startFace" => start_face = Some(lx.label("startFace (a face label)")?.0),
                _ if coupled.entry(lx, key.text, key.line)? => {}
                _ => {
                    lx.skip_value(key.text, key.line)?;
                    continue;
                }
            }
            lx.expect(";", &format!("after {}", key.text))?;
        }
        let missing =
            |entry: &str| lx.err(t.line, format!("patch '{}' has no {entry}", shown(t.text)));
        Ok(Patch {
            name: t.text.to_string(),
            kind: kind.ok_or_else(|| missing("type"))?,
            n_faces: n_faces.ok_or_else(|| missing("nFaces"))?,
            start_face: start_face.ok_or_else(|| missing("startFace"))?,
            line: t.line,
            coupled,
        })
    })?;
    end(&mut lx)?;
    let mut names: Vec<&Patch> = patches.iter().collect();
    names.sort_by(|a, b| (&a.name, a.line).cmp(&(&b.name, b.line)));
    if let Some(w) = names.windows(2).find(|w| w[0].name == w[1].name) {
        return Err(parse_err(
            &path,
            w[1].line,
            format!(
                "patch '{}' is given twice (first at line {}): each patch needs a name of its own",
                w[1].name, w[0].line
            ),
        ));
    }
    if patches.len() > MAX_GROUPS {
        return Err(parse_err(
            &path,
            1,
            format!(
                "{} patches is more than {MAX_GROUPS} (the most verbss reads)",
                patches.len()
            ),
        ));
    }
    Ok(patches)
}
