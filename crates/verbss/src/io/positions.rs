//! Prescribed node positions: where boundary nodes go, node by node.
//!
//! Two layouts, one entry per line:
//!
//! - SU2's surface file (`DV_FILENAME`, `surface_positions.dat`):
//!   `GlobalID x y [z]`, whitespace separated, where `GlobalID` is the 0-based
//!   index of the node in the mesh file's order;
//! - CSV: `id,x,y[,z]`, with an optional header line (`id,x,y`).
//!
//! Each line holds exactly `1 + dim` fields. Blank lines and lines starting
//! with `%` or `#` are ignored. Ids are unique but in any order.

use std::path::Path;

use crate::error::{Error, Result};

/// New positions of some nodes: node `ids[k]` goes to
/// `coords[dim*k..dim*k+dim]`, read at line `lines[k]` of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Positions {
    /// Spatial dimension, 2 or 3.
    pub dim: usize,
    /// The 0-based node index of each entry.
    pub ids: Vec<usize>,
    /// The new coordinates, `dim` numbers per entry.
    pub coords: Vec<f64>,
    /// The 1-based line each entry was read from (for messages).
    pub lines: Vec<usize>,
}

impl Positions {
    /// Number of entries.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether there is no entry.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The new coordinates of entry `k`.
    pub fn point(&self, k: usize) -> &[f64] {
        &self.coords[self.dim * k..self.dim * (k + 1)]
    }

    /// Checks every id against a mesh of `nodes` nodes (ids `0..nodes`);
    /// `path` names the positions file in the message, which says when the
    /// ids look 1-based (0 absent, `nodes` present).
    pub fn check_against(&self, nodes: usize, path: &Path) -> Result<()> {
        let Some(k) = self.ids.iter().position(|&id| id >= nodes) else {
            return Ok(());
        };
        let one_based = !self.ids.contains(&0) && self.ids.iter().all(|&id| id <= nodes);
        Err(Error::Parse {
            path: path.to_path_buf(),
            line: self.lines[k],
            message: format!(
                "node id {} out of range (the mesh has {nodes} nodes: {}){}",
                self.ids[k],
                match nodes {
                    0 => "no valid id".to_string(),
                    n => format!("ids 0 to {}", n - 1),
                },
                if one_based {
                    "; the ids look 1-based (no id 0, the largest equal to the node count): \
                     ids are 0-based node indices in the mesh file's order, so subtract 1 \
                     from each"
                } else {
                    ""
                }
            ),
        })
    }
}

impl Positions {
    /// Checks that every id is a node where `on(id)` is true (the nodes of
    /// the moving groups `groups`); `on(id)` is `None` for an id this
    /// process does not hold (another checks it); `path` names the
    /// positions file.
    pub fn check_on(
        &self,
        on: impl Fn(usize) -> Option<bool>,
        groups: &str,
        path: &Path,
    ) -> Result<()> {
        match self.ids.iter().position(|&id| on(id) == Some(false)) {
            None => Ok(()),
            Some(k) => {
                // Every id minus 1 on the moving groups: Gmsh's node tags,
                // or another 1-based numbering.
                let one_based = self
                    .ids
                    .iter()
                    .all(|&id| id > 0 && on(id - 1) != Some(false));
                Err(Error::Parse {
                    path: path.to_path_buf(),
                    line: self.lines[k],
                    message: format!(
                        "node id {} is not on a moving group ({groups}): its position would be \
                         ignored{}",
                        self.ids[k],
                        if one_based {
                            "; the ids look 1-based (each id minus 1 is a node of the moving \
                             groups): ids are 0-based node indices in the mesh file's order, \
                             so subtract 1 from each"
                        } else {
                            ""
                        }
                    ),
                })
            }
        }
    }
}

/// Reads a positions file of dimension `dim`.
pub fn read(path: &Path, dim: usize) -> Result<Positions> {
    parse(&crate::io::read_bytes(path)?, path, dim)
}

/// Parses a positions file's bytes (`dim` is 2 or 3); `path` is only used in
/// error messages. Fails on a line with the wrong number of fields, a field
/// that is not a number, a non-finite coordinate, a repeated id, or no entry.
pub fn parse(bytes: &[u8], path: &Path, dim: usize) -> Result<Positions> {
    if dim != 2 && dim != 3 {
        return Err(Error::InvalidSetting(format!(
            "positions of dimension {dim} (expected 2 or 3)"
        )));
    }
    let err = |line: usize, message: String| Error::Parse {
        path: path.to_path_buf(),
        line,
        message,
    };
    let layout = if dim == 2 { "id x y" } else { "id x y z" };
    let cap = bytes.len() / 4;
    let mut p = Positions {
        dim,
        ids: Vec::with_capacity(cap / (dim + 1)),
        coords: Vec::with_capacity(cap),
        lines: Vec::with_capacity(cap / (dim + 1)),
    };
    let mut first_content = true;
    let mut fields: Vec<&str> = Vec::with_capacity(dim + 1);
    let bytes = &bytes[super::bom(bytes)..];
    for (k, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = k + 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let text = std::str::from_utf8(raw).map_err(|e| {
            err(
                line,
                format!(
                    "non-UTF-8 byte 0x{:02x} at column {} (expected a text line '{layout}')",
                    raw[e.valid_up_to()],
                    e.valid_up_to() + 1
                ),
            )
        })?;
        let text = text.trim();
        if text.is_empty() || text.starts_with(['%', '#']) {
            continue;
        }
        fields.clear();
        if text.contains(',') {
            fields.extend(text.split(',').map(str::trim));
        } else {
            fields.extend(text.split_whitespace());
        }
        let header =
            std::mem::take(&mut first_content) && fields.iter().all(|f| f.parse::<f64>().is_err());
        if header {
            continue;
        }
        if fields.len() != dim + 1 {
            return Err(err(
                line,
                format!(
                    "{} fields (expected {} fields '{layout}')",
                    fields.len(),
                    dim + 1
                ),
            ));
        }
        let id = fields[0].parse::<usize>().map_err(|_| {
            err(
                line,
                format!(
                    "expected a node id (an integer ≥ 0), found '{}'",
                    fields[0].escape_debug()
                ),
            )
        })?;
        for f in &fields[1..] {
            let x: f64 = f.parse().map_err(|_| {
                err(
                    line,
                    format!("expected a coordinate, found '{}'", f.escape_debug()),
                )
            })?;
            if !x.is_finite() {
                return Err(err(
                    line,
                    format!("non-finite coordinate '{f}' (expected a finite number)"),
                ));
            }
            if x.abs() > crate::motion::MAX_COORDINATE {
                return Err(err(
                    line,
                    format!(
                        "coordinate '{f}' of node {} is beyond ±1e100 (a position that far from \
                         the mesh would overflow the solve)",
                        fields[0]
                    ),
                ));
            }
            p.coords.push(x);
        }
        p.ids.push(id);
        p.lines.push(line);
    }
    if p.is_empty() {
        return Err(err(
            bytes.split(|&b| b == b'\n').count().max(1),
            format!("no positions in the file (expected lines '{layout}')"),
        ));
    }
    let mut order: Vec<usize> = (0..p.len()).collect();
    order.sort_unstable_by_key(|&k| (p.ids[k], p.lines[k]));
    if let Some(w) = order.windows(2).find(|w| p.ids[w[0]] == p.ids[w[1]]) {
        return Err(err(
            p.lines[w[1]],
            format!(
                "node id {} given twice (first at line {})",
                p.ids[w[1]], p.lines[w[0]]
            ),
        ));
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/su2/");

    fn error(text: &str, dim: usize) -> String {
        parse(text.as_bytes(), Path::new("p.dat"), dim)
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn surface_bump_moves_the_naca0012_airfoil() {
        let path = format!("{DIR}surface_bump.dat");
        let p = read(Path::new(&path), 2).unwrap();
        assert_eq!(p.len(), 200);
        assert_eq!((p.ids[0], p.point(0)), (199, &[1.0, 0.0][..]));
        assert_eq!(
            (p.ids[1], p.point(1)),
            (0, &[0.99975001812, -3.63289651901644e-05][..])
        );
        let mesh = crate::io::read(Path::new(&format!("{DIR}mesh_NACA0012_inv.su2"))).unwrap();
        p.check_against(mesh.node_count(), Path::new(&path))
            .unwrap();
        let mut ids = p.ids.clone();
        ids.sort_unstable();
        assert_eq!(ids, mesh.group("airfoil").unwrap().nodes());
    }

    #[test]
    fn csv_with_header_and_whitespace_layouts_agree() {
        let csv = "\"PointID\",\"x\",\"y\",\"z\"\n3, 1.5, -2, 0.25\r\n0,0,0,1e-3\n";
        let ws = "# comment\n\n3\t1.5 -2 0.25\n0 0 0 1e-3\n";
        let a = parse(csv.as_bytes(), Path::new("a.csv"), 3).unwrap();
        let b = parse(ws.as_bytes(), Path::new("b.dat"), 3).unwrap();
        assert_eq!(a.ids, [3, 0]);
        assert_eq!(a.coords, [1.5, -2.0, 0.25, 0.0, 0.0, 1e-3]);
        assert_eq!(a.lines, [2, 3]);
        assert_eq!((b.ids, b.coords), (a.ids, a.coords));
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(
            error("0 1 2\n1 1 2 3\n", 2),
            "p.dat:2: 4 fields (expected 3 fields 'id x y')"
        );
        assert_eq!(
            error("0,1\n", 3),
            "p.dat:1: 2 fields (expected 4 fields 'id x y z')"
        );
        assert_eq!(
            error("0 1 2\n1 one 2\n", 2),
            "p.dat:2: expected a coordinate, found 'one'"
        );
        assert_eq!(
            error("0 1 2\n-1 1 2\n", 2),
            "p.dat:2: expected a node id (an integer ≥ 0), found '-1'"
        );
        assert_eq!(
            error("0 1 2\nid x y\n", 2),
            "p.dat:2: expected a node id (an integer ≥ 0), found 'id'"
        );
        assert_eq!(
            error("0 1 NaN\n", 2),
            "p.dat:1: non-finite coordinate 'NaN' (expected a finite number)"
        );
        assert_eq!(
            error("4 0 0\n2 0 0\n\n4 1 1\n", 2),
            "p.dat:4: node id 4 given twice (first at line 1)"
        );
        assert_eq!(
            error("% nothing\n", 2),
            "p.dat:2: no positions in the file (expected lines 'id x y')"
        );
        assert_eq!(
            error("0 1 2\n1 \u{0}\u{1}\n", 2),
            "p.dat:2: 2 fields (expected 3 fields 'id x y')"
        );
        let e = parse(b"0 1 2\n1 \xff 2\n", Path::new("p.dat"), 2).unwrap_err();
        assert_eq!(
            e.to_string(),
            "p.dat:2: non-UTF-8 byte 0xff at column 3 (expected a text line 'id x y')"
        );
        assert_eq!(
            error("0 1 2\n", 4),
            "invalid setting: positions of dimension 4 (expected 2 or 3)"
        );
    }

    #[test]
    fn ids_checked_against_the_mesh() {
        let p = parse(b"0 0 0\n\n5 1 1\n", Path::new("p.dat"), 2).unwrap();
        p.check_against(6, Path::new("p.dat")).unwrap();
        assert_eq!(
            p.check_against(5, Path::new("p.dat"))
                .unwrap_err()
                .to_string(),
            "p.dat:3: node id 5 out of range (the mesh has 5 nodes: ids 0 to 4)"
        );
    }

    #[test]
    fn ids_that_look_one_based_get_the_hint() {
        let p = parse(b"5 0 0\n1 1 1\n", Path::new("p.dat"), 2).unwrap();
        assert_eq!(
            p.check_against(5, Path::new("p.dat"))
                .unwrap_err()
                .to_string(),
            "p.dat:1: node id 5 out of range (the mesh has 5 nodes: ids 0 to 4); the ids look \
             1-based (no id 0, the largest equal to the node count): ids are 0-based node \
             indices in the mesh file's order, so subtract 1 from each"
        );
        let past = parse(b"6 0 0\n1 1 1\n", Path::new("p.dat"), 2).unwrap();
        let e = past.check_against(5, Path::new("p.dat")).unwrap_err();
        assert!(!e.to_string().contains("1-based"), "{e}");
    }

    #[test]
    fn surface_ids_that_look_one_based_get_the_hint() {
        // Nodes 2 and 3 move; the file names them 3 and 4, as Gmsh's tags.
        let on = [false, false, true, true, false, false];
        let p = parse(b"3 0 0\n4 1 1\n", Path::new("p.dat"), 2).unwrap();
        let at = |id: usize| Some(on.get(id).copied().unwrap_or(false));
        let e = p.check_on(at, "wall", Path::new("p.dat")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "p.dat:2: node id 4 is not on a moving group (wall): its position would be \
             ignored; the ids look 1-based (each id minus 1 is a node of the moving groups): \
             ids are 0-based node indices in the mesh file's order, so subtract 1 from each"
        );
        let stray = parse(b"2 0 0\n5 1 1\n", Path::new("p.dat"), 2).unwrap();
        let e = stray.check_on(at, "wall", Path::new("p.dat")).unwrap_err();
        assert!(!e.to_string().contains("1-based"), "{e}");
    }

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let p = parse("\u{feff}3 0.5 1\n".as_bytes(), Path::new("p.dat"), 2).unwrap();
        assert_eq!((p.ids, p.coords), (vec![3], vec![0.5, 1.0]));
    }

    #[test]
    fn missing_file() {
        let path = format!("{DIR}no_such_positions.dat");
        assert_eq!(
            read(Path::new(&path), 2).unwrap_err().to_string(),
            format!("{path}: No such file or directory (os error 2)")
        );
    }
}
