//! OpenFOAM cases (`constant/polyMesh`) of a small mesh: a jittered grid,
//! or a grid one cell thick with `empty` front and back patches (a 2D
//! case), its faces found from the cells' own facets; each of the five
//! files ASCII or binary (labels of 32 or 64 bits, scalars of 32 or 64),
//! with or without its header and counts, `N{item}` lists, a
//! `faceCompactList`, fuzzed counts, patches (names repeated or odd, types,
//! start faces, sizes), labels and numbers replaced, and the file cut
//! anywhere.

use std::collections::HashMap;
use std::fmt::Write;

use arbitrary::Arbitrary;
use verbss::Mesh;

use super::{Base, Count, Name};

/// A case, described.
#[derive(Arbitrary, Debug)]
pub struct FoamCase {
    base: Base,
    thin: bool,
    files: [Encoding; 5],
    /// Per patch (the groups, then `other`): name, type, stated size and start.
    patches: Vec<(Option<Name>, u8, Count, Count)>,
    counts: [Count; 5],
    /// Numbers replaced: `(file, position, replacement)`.
    edits: Vec<(u8, u16, Number)>,
    /// A file cut after this many bytes: `(file, length)`.
    cut: Option<(u8, u16)>,
}

/// How one file is written.
#[derive(Arbitrary, Debug, Clone, Copy)]
struct Encoding {
    binary: bool,
    wide_labels: bool,
    single: bool,
    header: bool,
    compact: bool,
    uniform: bool,
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Number {
    Int(i64),
    Real(f64),
    Nan,
    Huge,
    Word,
}

const NAMES: [&str; 5] = ["points", "faces", "owner", "neighbour", "boundary"];
const TYPES: [&str; 6] = ["wall", "patch", "empty", "symmetryPlane", "wedge", "cyclic"];

/// The faces of the cells of `mesh` (3D): internal faces first (owner the
/// lower cell), then the boundary faces by the group holding them (`other`
/// last); each with its owner and neighbour.
fn faces(mesh: &Mesh) -> (Vec<Vec<usize>>, Vec<usize>, Vec<usize>, Vec<(String, usize)>) {
    let key = |f: &[usize]| {
        let mut k = f.to_vec();
        k.sort_unstable();
        k
    };
    let mut seen: HashMap<Vec<usize>, usize> = HashMap::new();
    let mut all: Vec<(Vec<usize>, usize, Option<usize>)> = Vec::new();
    for (c, (kind, nodes)) in mesh.cells.iter().enumerate() {
        for facet in kind.table().facets {
            let f: Vec<usize> = facet.iter().map(|&l| nodes[l]).collect();
            match seen.get(&key(&f)) {
                Some(&i) => all[i].2 = Some(c),
                None => {
                    seen.insert(key(&f), all.len());
                    all.push((f, c, None));
                }
            }
        }
    }
    let group_of = |f: &[usize]| {
        mesh.groups
            .iter()
            .position(|g| g.facets.iter().any(|(_, n)| key(n) == key(f)))
            .unwrap_or(mesh.groups.len())
    };
    all.sort_by_key(|(f, _, n)| (n.is_none(), if n.is_none() { group_of(f) } else { 0 }));
    let mut sizes: Vec<(String, usize)> = mesh
        .groups
        .iter()
        .map(|g| (g.name.clone(), 0))
        .chain([("other".to_string(), 0)])
        .collect();
    for (f, _, n) in &all {
        if n.is_none() {
            sizes[group_of(f)].1 += 1;
        }
    }
    let owners = all.iter().map(|f| f.1).collect();
    let neighbours = all.iter().filter_map(|f| f.2).collect();
    (all.into_iter().map(|f| f.0).collect(), owners, neighbours, sizes)
}

impl Number {
    fn text(self) -> String {
        match self {
            Number::Int(v) => v.to_string(),
            Number::Real(v) => format!("{v:e}"),
            Number::Nan => "nan".into(),
            Number::Huge => "1e300".into(),
            Number::Word => "word".into(),
        }
    }
}

impl Encoding {
    fn arch(self) -> (usize, usize) {
        (if self.wide_labels { 8 } else { 4 }, if self.single { 4 } else { 8 })
    }

    fn head(self, class: &str, object: &str) -> String {
        if !self.header && !self.binary {
            return String::new();
        }
        let (label, scalar) = self.arch();
        format!(
            "FoamFile\n{{\n    version 2.0;\n    format {};\n    arch \"LSB;label={};scalar={}\";\n    \
             class {class};\n    object {object};\n}}\n",
            if self.binary { "binary" } else { "ascii" },
            8 * label,
            8 * scalar
        )
    }

    /// A list of labels, ASCII or binary.
    fn labels(self, out: &mut Vec<u8>, values: &[i64], count: Count) {
        let (label, _) = self.arch();
        let n = count.text(values.len());
        if self.binary {
            out.extend(format!("{n}\n(").as_bytes());
            for &v in values {
                if label == 4 {
                    out.extend((v as i32).to_le_bytes());
                } else {
                    out.extend(v.to_le_bytes());
                }
            }
            out.extend(b")\n");
        } else if self.uniform && values.windows(2).all(|w| w[0] == w[1]) && !values.is_empty() {
            out.extend(format!("{n}{{{}}}\n", values[0]).as_bytes());
        } else {
            let items: Vec<String> = values.iter().map(i64::to_string).collect();
            out.extend(format!("{n}\n(\n{}\n)\n", items.join("\n")).as_bytes());
        }
    }
}

impl FoamCase {
    /// The five files' bytes, named, or none when the grid cannot be made.
    pub fn files(&self) -> Option<Vec<(&'static str, Vec<u8>)>> {
        let mut mesh = self.base.mesh()?;
        if mesh.dim == 2 {
            mesh = extrude(&mesh, self.thin)?;
        }
        let (faces, owners, neighbours, sizes) = faces(&mesh);
        let mut files = Vec::new();
        let e = self.files;
        // points
        let mut out = e[0].head("vectorField", "points").into_bytes();
        let n = self.counts[0].text(mesh.node_count());
        let (_, scalar) = e[0].arch();
        if e[0].binary {
            out.extend(format!("{n}\n(").as_bytes());
            for &x in &mesh.coords {
                if scalar == 4 {
                    out.extend((x as f32).to_le_bytes());
                } else {
                    out.extend(x.to_le_bytes());
                }
            }
            out.extend(b")\n");
        } else {
            let mut text = format!("{n}\n(\n");
            for i in 0..mesh.node_count() {
                let p = mesh.point(i);
                let _ = writeln!(text, "({} {} {})", p[0], p[1], p[2]);
            }
            out.extend(text.as_bytes());
            out.extend(b")\n");
        }
        files.push(("points", out));
        // faces
        let compact = e[1].binary || e[1].compact;
        let class = if compact { "faceCompactList" } else { "faceList" };
        let mut out = e[1].head(class, "faces").into_bytes();
        if compact {
            let mut starts = vec![0i64];
            let mut all = Vec::new();
            for f in &faces {
                all.extend(f.iter().map(|&p| p as i64));
                starts.push(all.len() as i64);
            }
            e[1].labels(&mut out, &starts, self.counts[1]);
            e[1].labels(&mut out, &all, Count::True);
        } else {
            let mut text = format!("{}\n(\n", self.counts[1].text(faces.len()));
            for f in &faces {
                let items: Vec<String> = f.iter().map(usize::to_string).collect();
                let _ = writeln!(text, "{}({})", f.len(), items.join(" "));
            }
            out.extend(text.as_bytes());
            out.extend(b")\n");
        }
        files.push(("faces", out));
        for (k, (name, values)) in [("owner", &owners), ("neighbour", &neighbours)].into_iter().enumerate() {
            let mut out = e[2 + k].head("labelList", name).into_bytes();
            let values: Vec<i64> = values.iter().map(|&v| v as i64).collect();
            e[2 + k].labels(&mut out, &values, self.counts[2 + k]);
            files.push((NAMES[2 + k], out));
        }
        // boundary (always ASCII, as OpenFOAM writes it)
        let mut text = e[4].head("polyBoundaryMesh", "boundary");
        let _ = write!(text, "{}\n(\n", self.counts[4].text(sizes.len()));
        let mut start = neighbours.len();
        for (k, (group, size)) in sizes.iter().enumerate() {
            let (name, kind, n, s) = self
                .patches
                .get(k)
                .map_or((None, 0, Count::True, Count::True), |p| (p.0, p.1, p.2, p.3));
            let name = name.map_or(group.clone(), Name::text);
            let kind = if self.thin && (group == "front" || group == "back") && kind % 4 != 3 {
                "empty"
            } else {
                TYPES[usize::from(kind) % TYPES.len()]
            };
            let _ = write!(
                text,
                "    {name}\n    {{\n        type {kind};\n        nFaces {};\n        startFace {};\n    }}\n",
                n.text(*size),
                s.text(start)
            );
            start += size;
        }
        text.push_str(")\n");
        files.push(("boundary", text.into_bytes()));
        for &(file, at, number) in self.edits.iter().take(8) {
            edit(&mut files[usize::from(file) % 5].1, usize::from(at), number);
        }
        if let Some((file, len)) = self.cut {
            files[usize::from(file) % 5].1.truncate(usize::from(len));
        }
        Some(files)
    }
}

/// Replaces the `at`-th number of an ASCII file (modulo their count).
fn edit(bytes: &mut Vec<u8>, at: usize, number: Number) {
    let text = String::from_utf8_lossy(bytes).into_owned();
    let spans: Vec<(usize, usize)> = text
        .char_indices()
        .filter(|&(i, c)| {
            c.is_ascii_digit() && (i == 0 || !text.as_bytes()[i - 1].is_ascii_alphanumeric())
        })
        .map(|(i, _)| {
            let end = text[i..]
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-'))
                .map_or(text.len(), |e| i + e);
            (i, end)
        })
        .collect();
    if spans.is_empty() {
        return;
    }
    let (a, b) = spans[at % spans.len()];
    *bytes = format!("{}{}{}", &text[..a], number.text(), &text[b..]).into_bytes();
}

/// The 2D `mesh` extruded one cell in z (0 to 0.1), with patches `front`
/// and `back` (one cell thick: the 2D case of the reader) or `side` walls.
fn extrude(mesh: &Mesh, thin: bool) -> Option<Mesh> {
    use verbss::{CellKind, Cells, Group};
    let n = mesh.node_count();
    let mut coords = Vec::with_capacity(3 * 2 * n);
    for z in [0.0, 0.1] {
        for i in 0..n {
            let p = mesh.point(i);
            coords.extend([p[0], p[1], z]);
        }
    }
    let mut cells = Cells::new();
    let (mut back, mut front) = (Cells::new(), Cells::new());
    for (kind, nodes) in mesh.cells.iter() {
        let top: Vec<usize> = nodes.iter().map(|&v| v + n).collect();
        let all: Vec<usize> = nodes.iter().chain(&top).copied().collect();
        let solid = if kind == CellKind::Triangle { CellKind::Wedge } else { CellKind::Hexahedron };
        cells.push(solid, &all);
        back.push(CellKind::facet_kind(nodes.len()), nodes);
        front.push(CellKind::facet_kind(top.len()), &top);
    }
    let mut groups: Vec<Group> = mesh
        .groups
        .iter()
        .map(|g| {
            let mut facets = Cells::new();
            for (_, f) in g.facets.iter() {
                if let [a, b] = *f {
                    facets.push(CellKind::Quad, &[a, b, b + n, a + n]);
                }
            }
            Group { name: g.name.clone(), tag: None, facets }
        })
        .collect();
    let names = if thin { ["back", "front"] } else { ["bottom", "top"] };
    for (name, facets) in names.into_iter().zip([back, front]) {
        groups.push(Group { name: name.into(), tag: None, facets });
    }
    Mesh::new(3, coords, cells, groups).ok()
}
