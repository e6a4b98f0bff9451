//! SU2 files of a small mesh: sections in any order, repeated or unknown
//! (`FFD_NBOX=`, `NZONE=`/`IZONE=` zones), fuzzed counts (negative, huge,
//! with a domain count), markers with odd or repeated names, odd numbers in
//! place of coordinates and node indices, comments and line ends.

use arbitrary::Arbitrary;

use super::{Base, Count, Name};

/// An SU2 file, described.
#[derive(Arbitrary, Debug)]
pub struct Su2File {
    base: Base,
    sections: Vec<Section>,
    counts: [Count; 4],
    /// Names of markers `k`: `names[k % len]`, or the group's.
    names: Vec<Name>,
    /// Tokens replaced: `(line, token, replacement)` of the data lines.
    edits: Vec<(u8, u8, Token)>,
    crlf: bool,
    comments: bool,
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Section {
    Dimension,
    Elements,
    Points,
    Markers,
    /// `NZONE= 2`, then `IZONE= 1`.
    Zones,
    Unknown(Name),
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Token {
    Nan,
    Inf,
    Big,
    Negative,
    Huge,
    Empty,
    Int(u64),
}

impl Token {
    fn text(self) -> String {
        match self {
            Token::Nan => "nan".into(),
            Token::Inf => "-inf".into(),
            Token::Big => "1e400".into(),
            Token::Negative => "-1".into(),
            Token::Huge => "18446744073709551616".into(),
            Token::Empty => String::new(),
            Token::Int(v) => v.to_string(),
        }
    }
}

impl Su2File {
    /// The file's bytes (empty when the grid cannot be made).
    pub fn bytes(&self) -> Vec<u8> {
        let Some(mesh) = self.base.mesh() else {
            return Vec::new();
        };
        let mut data: Vec<Vec<String>> = Vec::new();
        let mut lines: Vec<String> = Vec::new();
        let n = mesh.node_count();
        let default = [
            Section::Dimension,
            Section::Elements,
            Section::Points,
            Section::Markers,
        ];
        let sections = if self.sections.is_empty() {
            &default[..]
        } else {
            &self.sections
        };
        // Each data line is kept as tokens (edited below) behind a marker.
        let mut push_data = |lines: &mut Vec<String>, tokens: Vec<String>| {
            lines.push(format!("\u{0}{}", data.len()));
            data.push(tokens);
        };
        for s in sections {
            match s {
                Section::Dimension => {
                    lines.push(format!("NDIME= {}", self.counts[0].text(mesh.dim)))
                }
                Section::Zones => lines.extend(["NZONE= 2".to_string(), "IZONE= 1".to_string()]),
                Section::Unknown(name) => {
                    let name = name.text().replace('=', "");
                    lines.extend([format!("{name}= 1"), "1 2 3".into()]);
                }
                Section::Elements => {
                    lines.push(format!("NELEM= {}", self.counts[1].text(mesh.cell_count())));
                    for (c, (kind, nodes)) in mesh.cells.iter().enumerate() {
                        let mut t = vec![kind.vtk_id().to_string()];
                        t.extend((0..nodes.len()).map(|k| nodes[kind.vtk_local(k)].to_string()));
                        t.push(c.to_string());
                        push_data(&mut lines, t);
                    }
                }
                Section::Points => {
                    lines.push(format!("NPOIN= {} {n}", self.counts[2].text(n)));
                    for i in 0..n {
                        let mut t: Vec<String> =
                            mesh.point(i).iter().map(|x| x.to_string()).collect();
                        t.push(i.to_string());
                        push_data(&mut lines, t);
                    }
                }
                Section::Markers => {
                    lines.push(format!("NMARK= {}", self.counts[3].text(mesh.groups.len())));
                    for (k, g) in mesh.groups.iter().enumerate() {
                        let name = match self.names.get(k % self.names.len().max(1)) {
                            Some(name) => name.text(),
                            None => g.name.clone(),
                        };
                        lines.push(format!("MARKER_TAG= {name}"));
                        lines.push(format!("MARKER_ELEMS= {}", g.facets.len()));
                        for (kind, nodes) in g.facets.iter() {
                            let mut t = vec![kind.vtk_id().to_string()];
                            t.extend(nodes.iter().map(|i| i.to_string()));
                            push_data(&mut lines, t);
                        }
                    }
                }
            }
        }
        for &(line, token, with) in &self.edits {
            let len = data.len();
            if let Some(t) = data.get_mut(usize::from(line) % len.max(1)) {
                let k = usize::from(token) % t.len().max(1);
                if let Some(slot) = t.get_mut(k) {
                    *slot = with.text();
                }
            }
        }
        let end = if self.crlf { "\r\n" } else { "\n" };
        let mut out = String::new();
        for line in lines {
            let line = match line.strip_prefix('\u{0}') {
                Some(k) => data[k.parse::<usize>().expect("an index")].join(" "),
                None => line,
            };
            out += &line;
            if self.comments {
                out += " % a comment";
            }
            out += end;
        }
        out.into_bytes()
    }
}
