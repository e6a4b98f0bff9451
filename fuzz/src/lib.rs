//! What the fuzz targets share: the checks every successfully read mesh must
//! pass, a byte reader for structured inputs and the structure-aware file
//! generators (the generated meshes are [`verbss::mesh::samples`]).

use std::path::Path;

use verbss::Mesh;

pub mod gen;

/// A mesh that a reader accepted must pass `Mesh::validate`, and what the
/// writer makes of it (when it can store it) must read back.
pub fn check_read(
    mesh: &Mesh,
    write: impl Fn(&mut Vec<u8>, &Mesh) -> std::io::Result<()>,
    parse: impl Fn(&[u8]) -> verbss::Result<Mesh>,
) {
    mesh.validate()
        .expect("a mesh the reader accepted passes validate");
    let mut bytes = Vec::new();
    if write(&mut bytes, mesh).is_ok() {
        if let Err(e) = parse(&bytes) {
            panic!("a written mesh does not read back: {e}");
        }
    }
}

/// Reads numbers from fuzz bytes; past the end, zeros.
pub struct Bytes<'a>(pub &'a [u8]);

impl Bytes<'_> {
    /// The next byte.
    pub fn u8(&mut self) -> u8 {
        match self.0.split_first() {
            Some((b, rest)) => {
                self.0 = rest;
                *b
            }
            None => 0,
        }
    }

    /// The next 8 bytes as an `f64`'s bits (any value: NaN, infinities, huge).
    pub fn f64(&mut self) -> f64 {
        f64::from_bits(u64::from_le_bytes(std::array::from_fn(|_| self.u8())))
    }

    /// The next byte as a number in `[-1, 1]`.
    pub fn unit(&mut self) -> f64 {
        f64::from(self.u8() as i8) / 127.0
    }
}

/// The path named in the targets' error messages.
pub fn path(name: &str) -> &Path {
    Path::new(name)
}
