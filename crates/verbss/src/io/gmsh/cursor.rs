//! A byte cursor over a Gmsh file: ASCII tokens with line numbers, binary
//! records with byte offsets, and errors that say where.

use std::path::Path;

use crate::error::{Error, Result};

/// An error of file `path` at `at`: its byte offset in a binary file, its
/// line in an ASCII one.
pub(super) fn located(path: &Path, binary: bool, at: Mark, message: String) -> Error {
    let path = path.to_path_buf();
    if binary {
        Error::Binary {
            path,
            offset: at.offset as u64,
            message,
        }
    } else {
        Error::Parse {
            path,
            line: at.line,
            message,
        }
    }
}

/// A place in the file: 0-based byte offset and 1-based line.
#[derive(Debug, Clone, Copy)]
pub(super) struct Mark {
    pub offset: usize,
    pub line: usize,
}

/// Reads tokens and binary records from a file's bytes.
///
/// Errors name the line in ASCII files and the byte offset in binary files
/// (where line numbers stop meaning anything after the first binary block).
pub(super) struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    mark: Mark,
    binary: bool,
    path: &'a Path,
    /// Offset of `bytes` in the file (a window of it, [`Cursor::window`]).
    base: usize,
}

/// At most this many bytes of an unexpected token are quoted in a message.
const SHOW: usize = 24;

/// Quotes bytes for an error message, escaped and shortened.
pub(super) fn show(bytes: &[u8]) -> String {
    let cut = &bytes[..bytes.len().min(SHOW)];
    let more = if bytes.len() > SHOW { "..." } else { "" };
    format!("'{}{more}'", cut.escape_ascii())
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `bytes` (after a byte-order mark), in ASCII mode.
    pub fn new(bytes: &'a [u8], path: &'a Path) -> Self {
        Cursor {
            bytes,
            pos: crate::io::bom(bytes),
            line: 1,
            mark: Mark { offset: 0, line: 1 },
            binary: false,
            path,
            base: 0,
        }
    }

    /// A cursor over `bytes`, a window of the file that starts at `start`:
    /// errors name the file's lines and offsets.
    pub fn window(bytes: &'a [u8], path: &'a Path, start: Mark, binary: bool) -> Self {
        Cursor {
            bytes,
            pos: 0,
            line: start.line,
            mark: Mark {
                offset: 0,
                line: start.line,
            },
            binary,
            path,
            base: start.offset,
        }
    }

    /// From now on, errors name byte offsets instead of lines.
    pub fn set_binary(&mut self) {
        self.binary = true;
    }

    /// Whether the file is binary.
    pub fn binary(&self) -> bool {
        self.binary
    }

    /// The place of the last token or record read.
    pub fn mark(&self) -> Mark {
        self.mark
    }

    /// The current place.
    pub fn here(&self) -> Mark {
        Mark {
            offset: self.pos,
            line: self.line,
        }
    }

    /// Bytes left after the current position.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// An error at the last token or record read.
    pub fn error(&self, message: impl Into<String>) -> Error {
        self.error_at(self.mark, message)
    }

    /// An error at `mark`.
    pub fn error_at(&self, mark: Mark, message: impl Into<String>) -> Error {
        let at = Mark {
            offset: self.base + mark.offset,
            line: mark.line,
        };
        located(self.path, self.binary, at, message.into())
    }

    /// An error at byte `offset` of a binary block.
    pub fn error_at_offset(&self, offset: usize, message: impl Into<String>) -> Error {
        self.error_at(
            Mark {
                offset,
                line: self.line,
            },
            message,
        )
    }

    fn skip_ws(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            match b {
                b'\n' => self.line += 1,
                b' ' | b'\t' | b'\r' | b'\x0c' | b'\x0b' => {}
                _ => break,
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited token, or `None` at the end of the file.
    pub fn next_token(&mut self) -> Option<&'a [u8]> {
        self.skip_ws();
        self.mark = self.here();
        if self.pos == self.bytes.len() {
            return None;
        }
        let start = self.pos;
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        Some(&self.bytes[start..self.pos])
    }

    /// The next token, which must exist; `what` names it in the error.
    pub fn token(&mut self, what: &str) -> Result<&'a [u8]> {
        self.next_token()
            .ok_or_else(|| self.error(format!("unexpected end of file: expected {what}")))
    }

    /// Whether the next token starts with `$` (a section ends), without consuming it.
    pub fn at_section_mark(&mut self) -> bool {
        self.skip_ws();
        self.bytes.get(self.pos) == Some(&b'$')
    }

    /// Reads `keyword`, or fails saying what was found instead.
    pub fn keyword(&mut self, keyword: &str) -> Result<()> {
        let tok = self.token(keyword)?;
        if tok == keyword.as_bytes() {
            Ok(())
        } else {
            Err(self.error(format!("expected {keyword}, found {}", show(tok))))
        }
    }

    /// A non-negative decimal integer.
    pub fn uint(&mut self, what: &str) -> Result<u64> {
        let tok = self.token(what)?;
        parse_uint(tok).ok_or_else(|| self.error(format!("expected {what}, found {}", show(tok))))
    }

    /// A non-negative integer that is used as a count or an index.
    pub fn count(&mut self, what: &str) -> Result<usize> {
        let v = self.uint(what)?;
        usize::try_from(v).map_err(|_| self.error(format!("{what} {v} is too large")))
    }

    /// A signed decimal integer that fits an `i32`.
    pub fn int(&mut self, what: &str) -> Result<i32> {
        let tok = self.token(what)?;
        let (neg, digits) = match tok.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, tok),
        };
        parse_uint(digits)
            .and_then(|v| i64::try_from(v).ok())
            .map(|v| if neg { -v } else { v })
            .and_then(|v| i32::try_from(v).ok())
            .ok_or_else(|| self.error(format!("expected {what}, found {}", show(tok))))
    }

    /// A floating-point number (it may be NaN or infinite: callers check).
    pub fn float(&mut self, what: &str) -> Result<f64> {
        let tok = self.token(what)?;
        std::str::from_utf8(tok)
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| self.error(format!("expected {what}, found {}", show(tok))))
    }

    /// The rest of the current line, without the line break.
    pub fn rest_of_line(&mut self) -> &'a [u8] {
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(|&b| b != b'\n') {
            self.pos += 1;
        }
        let end = if self.pos > start && self.bytes[self.pos - 1] == b'\r' {
            self.pos - 1
        } else {
            self.pos
        };
        &self.bytes[start..end]
    }

    /// Consumes the line break (after optional blanks) that ends an ASCII
    /// line before binary data, and nothing after it.
    pub fn newline(&mut self) -> Result<()> {
        self.mark = self.here();
        while matches!(self.bytes.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
            self.pos += 1;
        }
        match self.bytes.get(self.pos) {
            Some(b'\n') => {
                self.pos += 1;
                self.line += 1;
                Ok(())
            }
            Some(_) => Err(self.error(format!(
                "expected the end of the line, found {}",
                show(&self.bytes[self.pos..])
            ))),
            None => Err(self.error("unexpected end of file: expected the end of the line")),
        }
    }

    /// The next `n` bytes of binary data; `what` names them in the error.
    pub fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        self.mark = self.here();
        if n > self.remaining() {
            return Err(self.error(format!(
                "unexpected end of file: {what} needs {n} bytes, only {} remain",
                self.remaining()
            )));
        }
        let start = self.pos;
        self.pos += n;
        Ok(&self.bytes[start..self.pos])
    }

    /// `count` records of `size` bytes each (see [`Cursor::take`]).
    pub fn take_n(&mut self, count: usize, size: usize, what: &str) -> Result<&'a [u8]> {
        match count.checked_mul(size) {
            Some(n) => self.take(n, what),
            None => {
                self.mark = self.here();
                Err(self.error(format!(
                    "unexpected end of file: {what} needs {count} records of {size} bytes, only {} bytes remain",
                    self.remaining()
                )))
            }
        }
    }

    /// A little-endian `u64` (Gmsh's `size_t`).
    pub fn u64_le(&mut self, what: &str) -> Result<u64> {
        Ok(u64_at(self.take(8, what)?, 0))
    }

    /// A little-endian `i32` (Gmsh's `int`).
    pub fn i32_le(&mut self, what: &str) -> Result<i32> {
        Ok(i32_at(self.take(4, what)?, 0))
    }

    /// A little-endian `u64` used as a count.
    pub fn count_le(&mut self, what: &str) -> Result<usize> {
        let v = self.u64_le(what)?;
        usize::try_from(v).map_err(|_| self.error(format!("{what} {v} is too large")))
    }

    /// Skips everything up to and including `end` (an unknown section's closing
    /// keyword); fails at the end of the file.
    pub fn skip_past(&mut self, end: &str) -> Result<()> {
        let rest = &self.bytes[self.pos..];
        // A linear search: a window-by-window one is quadratic in `end`.
        let found = memchr::memmem::find(rest, end.as_bytes())
            .ok_or_else(|| self.error(format!("unexpected end of file: no {end} closes it")))?;
        let skipped = &rest[..found + end.len()];
        self.line += skipped.iter().filter(|&&b| b == b'\n').count();
        self.pos += skipped.len();
        Ok(())
    }
}

/// Parses an unsigned decimal integer, `None` on anything else or overflow.
fn parse_uint(tok: &[u8]) -> Option<u64> {
    if tok.is_empty() {
        return None;
    }
    tok.iter().try_fold(0u64, |acc, &b| {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        acc.checked_mul(10)?.checked_add(u64::from(d))
    })
}

/// The little-endian `u64` at byte `at` of `b`.
#[inline]
pub(super) fn u64_at(b: &[u8], at: usize) -> u64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[at..at + 8]);
    u64::from_le_bytes(a)
}

/// The little-endian `i32` at byte `at` of `b`.
#[inline]
pub(super) fn i32_at(b: &[u8], at: usize) -> i32 {
    let mut a = [0u8; 4];
    a.copy_from_slice(&b[at..at + 4]);
    i32::from_le_bytes(a)
}

/// The little-endian `f64` at byte `at` of `b`.
#[inline]
pub(super) fn f64_at(b: &[u8], at: usize) -> f64 {
    f64::from_bits(u64_at(b, at))
}
