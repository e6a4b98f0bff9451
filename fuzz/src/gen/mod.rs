//! Structure-aware inputs for the `*_gen` targets: files written from a
//! small valid mesh with fuzzed counts, headers, encodings, tag lists and
//! extra or repeated sections, so that the fuzzer spends its time past the
//! readers' first checks instead of on the syntax.

pub mod cgns;
pub mod foam;
pub mod msh;
pub mod su2;
pub mod vtu;

use arbitrary::Arbitrary;
use verbss::Mesh;

use verbss::mesh::samples::jittered_grid;

/// A count as a file states it: the true one, off by a little, or any.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Count {
    True,
    Off(i8),
    Any(u64),
    Max,
}

impl Count {
    /// The count stated for a true `n` (an offset below 0 gives 0).
    pub fn of(self, n: usize) -> u64 {
        match self {
            Count::True => n as u64,
            Count::Off(d) => (n as i64).saturating_add(i64::from(d)).max(0) as u64,
            Count::Any(v) => v,
            Count::Max => u64::MAX,
        }
    }

    /// The count as text: an offset below 0 stays negative.
    pub fn text(self, n: usize) -> String {
        match self {
            Count::Off(d) => (n as i64).saturating_add(i64::from(d)).to_string(),
            _ => self.of(n).to_string(),
        }
    }
}

/// The mesh the file is made from: a jittered grid of 2–4 nodes a side.
#[derive(Arbitrary, Debug)]
pub struct Base {
    dim3: bool,
    n: u8,
    kind: u8,
    jitter: Vec<i8>,
}

impl Base {
    /// The mesh (groups `left` and `walls`).
    pub fn mesh(&self) -> Option<Mesh> {
        let dim = if self.dim3 { 3 } else { 2 };
        let mut k = 0;
        jittered_grid(dim, 2 + usize::from(self.n % 3), self.kind, || {
            k += 1;
            self.jitter
                .get(k - 1)
                .map_or(0.0, |&j| 0.3 * f64::from(j) / 127.0)
        })
    }
}

/// A name for a group or an array: plain, empty, with characters the
/// formats treat specially, or long.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Name {
    Plain(u8),
    Empty,
    Special(u8),
    Long(u16),
}

impl Name {
    /// The name's text.
    pub fn text(self) -> String {
        const SPECIAL: [&str; 8] = [
            "a=b",
            "%c",
            "\"q\"",
            "<x>",
            "&amp;",
            "é\u{202e}",
            " s ",
            "$End",
        ];
        match self {
            Name::Plain(k) => format!("g{k}"),
            Name::Empty => String::new(),
            Name::Special(k) => SPECIAL[usize::from(k) % SPECIAL.len()].to_string(),
            Name::Long(n) => "n".repeat(usize::from(n)),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use arbitrary::{Arbitrary, Unstructured};
    use verbss::io::{gmsh, su2, vtu};

    use super::{msh::MshFile, su2::Su2File, vtu::VtuFile};

    /// Zero bytes describe honest files: every generator's reads back, in
    /// 2D and 3D (the first byte of the description picks the dimension).
    #[test]
    fn honest_descriptions_read() {
        for dim3 in [0u8, 1] {
            let mut bytes = vec![0u8; 256];
            bytes[0] = dim3;
            let file = VtuFile::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
            let mesh = vtu::parse(&file.bytes(), Path::new("g.vtu")).unwrap().mesh;
            assert_eq!(mesh.dim, 2 + usize::from(dim3));
            assert_eq!(mesh.groups.len(), 2);
            let file = MshFile::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
            let mesh = gmsh::parse(&file.bytes(), Path::new("g.msh")).unwrap();
            assert_eq!(mesh.dim, 2 + usize::from(dim3));
            let file = Su2File::arbitrary(&mut Unstructured::new(&bytes)).unwrap();
            let mesh = su2::parse(&file.bytes(), Path::new("g.su2")).unwrap();
            assert_eq!(mesh.groups.len(), 2);
        }
    }
}
