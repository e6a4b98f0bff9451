//! Gmsh files of a small mesh: MSH 2.2 or 4.1, ASCII or binary, sections in
//! any order, repeated, missing or unknown (names such as `$` and `$End…`),
//! fuzzed counts, node tags (sparse, huge, repeated), physical tag lists of
//! any length per group (repeats included) and element node references.

use arbitrary::Arbitrary;
use verbss::mesh::CellKind;
use verbss::Mesh;

use super::{Base, Count, Name};

/// A Gmsh file, described.
#[derive(Arbitrary, Debug)]
pub struct MshFile {
    base: Base,
    v41: bool,
    binary: bool,
    sections: Vec<Section>,
    /// Node tag `i` (0-based) is `scale * i + 1 + shift`.
    scale: u8,
    shift: u64,
    /// Physical tags of group `k`: `tags[k % len]`, or `k + 1`.
    tags: Vec<Vec<i32>>,
    names: Vec<(u8, i32, Name)>,
    counts: [Count; 4],
    /// Element node references replaced: `(element, node, tag)`.
    refs: Vec<(u8, u8, u64)>,
    /// Bytes kept of the whole file (all when 0).
    cut: u16,
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Section {
    Format,
    Names,
    Entities,
    Nodes,
    Elements,
    Unknown(Name),
}

/// An element: entity dimension and tag, physical tags, kind, node tags.
type Element = (i32, i32, Vec<i32>, CellKind, Vec<u64>);

/// ASCII or little-endian binary numbers.
struct Out {
    bytes: Vec<u8>,
    binary: bool,
}

impl Out {
    fn text(&mut self, s: &str) {
        self.bytes.extend(s.bytes());
    }
    fn int(&mut self, v: i32) {
        if self.binary {
            self.bytes.extend(v.to_le_bytes());
        } else {
            self.text(&format!("{v} "));
        }
    }
    fn size(&mut self, v: u64) {
        if self.binary {
            self.bytes.extend(v.to_le_bytes());
        } else {
            self.text(&format!("{v} "));
        }
    }
    fn float(&mut self, v: f64) {
        if self.binary {
            self.bytes.extend(v.to_le_bytes());
        } else {
            self.text(&format!("{v} "));
        }
    }
    fn eol(&mut self) {
        if !self.binary {
            self.text("\n");
        }
    }
}

/// The Gmsh type number of a kind.
fn gmsh_type(kind: CellKind) -> i32 {
    match kind {
        CellKind::Vertex => 15,
        CellKind::Line => 1,
        CellKind::Triangle => 2,
        CellKind::Quad => 3,
        CellKind::Tetra => 4,
        CellKind::Hexahedron => 5,
        CellKind::Wedge => 6,
        CellKind::Pyramid => 7,
    }
}

impl MshFile {
    fn node_tag(&self, i: usize) -> u64 {
        u64::from(self.scale.max(1))
            .wrapping_mul(i as u64)
            .wrapping_add(1)
            .wrapping_add(self.shift)
    }

    fn physicals(&self, group: usize) -> Vec<i32> {
        match self.tags.get(group % self.tags.len().max(1)) {
            Some(t) => t.clone(),
            None => vec![group as i32 + 1],
        }
    }

    /// Every element of the mesh, groups' facets included.
    fn elements(&self, mesh: &Mesh) -> Vec<Element> {
        let tags = |c: &[usize]| c.iter().map(|&i| self.node_tag(i)).collect::<Vec<_>>();
        let dim = mesh.dim as i32;
        let mut all: Vec<_> = mesh
            .cells
            .iter()
            .map(|(k, c)| (dim, 1, vec![], k, tags(c)))
            .collect();
        for (g, grp) in mesh.groups.iter().enumerate() {
            for (k, c) in grp.facets.iter() {
                all.push((dim - 1, g as i32 + 2, self.physicals(g), k, tags(c)));
            }
        }
        for &(e, k, tag) in &self.refs {
            let len = all.len();
            if let Some(el) = all.get_mut(usize::from(e) % len.max(1)) {
                let nodes = el.4.len();
                el.4[usize::from(k) % nodes] = tag;
            }
        }
        all
    }

    fn format(&self, o: &mut Out) {
        let v = if self.v41 { "4.1" } else { "2.2" };
        o.text(&format!("$MeshFormat\n{v} {} 8\n", u8::from(self.binary)));
        if self.binary {
            o.bytes.extend(1i32.to_le_bytes());
            o.text("\n");
        }
        o.text("$EndMeshFormat\n");
    }

    fn entities(&self, o: &mut Out, mesh: &Mesh) {
        o.text("$Entities\n");
        let mut counts = [0u64; 4];
        counts[mesh.dim] = 1;
        counts[mesh.dim - 1] = mesh.groups.len() as u64;
        counts[0] = self.counts[0].of(0);
        for c in counts {
            o.size(c);
        }
        o.eol();
        for (d, &c) in counts.iter().enumerate().take(4) {
            for e in 0..c.min(mesh.groups.len() as u64 + 1) {
                let (tag, phys) = match d == mesh.dim {
                    true => (1, vec![]),
                    false => (e as i32 + 2, self.physicals(e as usize)),
                };
                o.int(tag);
                for _ in 0..if d == 0 { 3 } else { 6 } {
                    o.float(0.0);
                }
                o.size(phys.len() as u64);
                phys.iter().for_each(|&p| o.int(p));
                if d > 0 {
                    o.size(0);
                }
                o.eol();
            }
        }
        o.text("$EndEntities\n");
    }

    fn nodes(&self, o: &mut Out, mesh: &Mesh) {
        let n = mesh.node_count();
        o.text("$Nodes\n");
        let xyz = |i: usize| {
            let p = mesh.point(i);
            [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
        };
        if self.v41 {
            for v in [
                1,
                self.counts[1].of(n),
                self.node_tag(0),
                self.node_tag(n - 1),
            ] {
                o.size(v);
            }
            o.eol();
            o.int(mesh.dim as i32);
            o.int(1);
            o.int(0);
            o.size(self.counts[2].of(n));
            o.eol();
            (0..n).for_each(|i| {
                o.size(self.node_tag(i));
                o.eol();
            });
            (0..n).for_each(|i| {
                xyz(i).into_iter().for_each(|x| o.float(x));
                o.eol();
            });
        } else {
            o.text(&format!("{}\n", self.counts[1].text(n)));
            for i in 0..n {
                o.int(self.node_tag(i) as i32);
                xyz(i).into_iter().for_each(|x| o.float(x));
                o.eol();
            }
        }
        o.text("\n$EndNodes\n");
    }

    fn elements_section(&self, o: &mut Out, mesh: &Mesh) {
        let all = self.elements(mesh);
        o.text("$Elements\n");
        if self.v41 {
            for v in [
                all.len() as u64,
                self.counts[3].of(all.len()),
                1,
                all.len() as u64,
            ] {
                o.size(v);
            }
            o.eol();
            for (e, (d, entity, _, kind, nodes)) in all.iter().enumerate() {
                o.int(*d);
                o.int(*entity);
                o.int(gmsh_type(*kind));
                o.size(1);
                o.eol();
                o.size(e as u64 + 1);
                nodes.iter().for_each(|&t| o.size(t));
                o.eol();
            }
        } else {
            o.text(&format!("{}\n", self.counts[3].text(all.len())));
            for (e, (_, entity, phys, kind, nodes)) in all.iter().enumerate() {
                let ntags = phys.len() + 1;
                if o.binary {
                    [gmsh_type(*kind), 1, ntags as i32]
                        .into_iter()
                        .for_each(|v| o.int(v));
                }
                o.int(e as i32 + 1);
                if !o.binary {
                    o.int(gmsh_type(*kind));
                    o.int(ntags as i32);
                }
                phys.iter().for_each(|&p| o.int(p));
                o.int(*entity);
                nodes.iter().for_each(|&t| o.int(t as i32));
                o.eol();
            }
        }
        o.text("\n$EndElements\n");
    }

    /// The file's bytes (empty when the grid cannot be made).
    pub fn bytes(&self) -> Vec<u8> {
        let Some(mesh) = self.base.mesh() else {
            return Vec::new();
        };
        let mut o = Out {
            bytes: Vec::new(),
            binary: false,
        };
        let default = [
            Section::Names,
            Section::Entities,
            Section::Nodes,
            Section::Elements,
        ];
        let sections = if self.sections.is_empty() {
            &default[..]
        } else {
            &self.sections
        };
        self.format(&mut o);
        for s in sections {
            o.binary = self.binary;
            match s {
                Section::Format => self.format(&mut o),
                Section::Names => {
                    o.binary = false;
                    o.text(&format!("$PhysicalNames\n{}\n", self.names.len()));
                    for (d, tag, name) in &self.names {
                        o.text(&format!("{} {tag} \"{}\"\n", d % 5, name.text()));
                    }
                    o.text("$EndPhysicalNames\n");
                }
                Section::Entities if self.v41 => self.entities(&mut o, &mesh),
                Section::Entities => {}
                Section::Nodes => self.nodes(&mut o, &mesh),
                Section::Elements => self.elements_section(&mut o, &mesh),
                Section::Unknown(name) => {
                    let name = name.text().replace(char::is_whitespace, "");
                    o.text(&format!("${name}\n1 2 3\n$End{name}\n"));
                }
            }
        }
        let mut bytes = o.bytes;
        if self.cut > 0 {
            bytes.truncate(usize::from(self.cut));
        }
        bytes
    }
}
