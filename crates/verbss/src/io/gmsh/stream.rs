//! A Gmsh file read piece by piece: lines, token runs and byte runs from a
//! buffered file, each with the place where it starts, so that what is kept
//! is parsed by a [`Cursor::window`](super::cursor::Cursor::window) and what
//! is skipped is never stored.

use std::fs::File;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

use super::cursor::{show, Mark};
use crate::error::{Error, Result};

/// A file open for reading from its start.
pub(super) struct Stream<'p> {
    reader: BufReader<File>,
    path: &'p Path,
    /// The place of the next byte.
    at: Mark,
    /// The file's size in bytes.
    len: usize,
    /// Whether errors name byte offsets (binary files) rather than lines.
    binary: bool,
}

impl<'p> Stream<'p> {
    /// Opens `path`.
    pub fn open(path: &'p Path) -> Result<Stream<'p>> {
        let io = |source| Error::Io {
            path: path.to_path_buf(),
            source,
        };
        let file = crate::io::open_input(path)?;
        let len = file.metadata().map_err(io)?.len() as usize;
        Ok(Stream {
            reader: BufReader::with_capacity(1 << 16, file),
            path,
            at: Mark { offset: 0, line: 1 },
            len,
            binary: false,
        })
    }

    /// From now on, errors name byte offsets.
    pub fn set_binary(&mut self) {
        self.binary = true;
    }

    /// The place of the next byte.
    pub fn here(&self) -> Mark {
        self.at
    }

    /// The file's path.
    pub fn path(&self) -> &'p Path {
        self.path
    }

    /// An error at `mark`: its line in an ASCII file, its offset in a binary one.
    pub fn error_at(&self, mark: Mark, message: impl Into<String>) -> Error {
        super::cursor::located(self.path, self.binary, mark, message.into())
    }

    fn io(&self, source: std::io::Error) -> Error {
        Error::Io {
            path: self.path.to_path_buf(),
            source,
        }
    }

    /// Appends the next line, with its line break, to `into`; `false` at
    /// the end of the file.
    pub fn line(&mut self, into: &mut Vec<u8>) -> Result<bool> {
        let start = into.len();
        let n = self
            .reader
            .read_until(b'\n', into)
            .map_err(|e| self.io(e))?;
        self.at.offset += n;
        if into[start..].ends_with(b"\n") {
            self.at.line += 1;
        }
        Ok(n > 0)
    }

    /// Reads the lines up to and including the one that is `end` (blanks
    /// around it allowed), appending them to `into` when given (else
    /// dropping them); `opened` names the section's start for the error at
    /// the end of the file.
    pub fn section(
        &mut self,
        end: &str,
        opened: Mark,
        mut into: Option<&mut Vec<u8>>,
    ) -> Result<()> {
        let mut line = Vec::new();
        loop {
            line.clear();
            if !self.line(&mut line)? {
                return Err(self.error_at(
                    opened,
                    format!("unexpected end of file: no {end} closes the section"),
                ));
            }
            if let Some(into) = into.as_deref_mut() {
                into.extend_from_slice(&line);
            }
            if line.trim_ascii() == end.as_bytes() {
                return Ok(());
            }
        }
    }

    /// Reads the next `count` whitespace-separated tokens, whole lines at a
    /// time, appending them to `into` when given (else dropping them):
    /// `what` names them in the errors. The last line must end with the
    /// last token.
    pub fn tokens(
        &mut self,
        count: usize,
        mut into: Option<&mut Vec<u8>>,
        what: &str,
    ) -> Result<()> {
        let mut seen = 0;
        let mut line = Vec::new();
        while seen < count {
            let at = self.here();
            line.clear();
            if !self.line(&mut line)? {
                return Err(self.error_at(
                    at,
                    format!("unexpected end of file: {what} holds {seen} of its {count} numbers"),
                ));
            }
            if line.trim_ascii_start().starts_with(b"$") {
                return Err(self.error_at(
                    at,
                    format!("{what} ends after {seen} of its {count} numbers"),
                ));
            }
            // Stepped over, not parsed: what is not a number is said here,
            // in the one pass that counts the tokens.
            let number = |t: &[u8]| t.iter().all(|b| b.is_ascii_digit() || b"+-.eE".contains(b));
            for t in line
                .split(u8::is_ascii_whitespace)
                .filter(|t| !t.is_empty())
            {
                if into.is_none() && !number(t) {
                    return Err(
                        self.error_at(at, format!("{what}: expected a number, found {}", show(t)))
                    );
                }
                seen += 1;
            }
            if seen > count {
                return Err(self.error_at(
                    at,
                    format!("{what} should end after {count} numbers, and this line holds more"),
                ));
            }
            if let Some(into) = into.as_deref_mut() {
                into.extend_from_slice(&line);
            }
        }
        Ok(())
    }

    /// Appends the next `n` bytes to `into`; `what` names them in the error.
    pub fn bytes(&mut self, n: usize, into: &mut Vec<u8>, what: &str) -> Result<()> {
        self.check_left(n, what)?;
        let start = into.len();
        into.resize(start + n, 0);
        self.reader
            .read_exact(&mut into[start..])
            .map_err(|e| self.io(e))?;
        self.at.offset += n;
        Ok(())
    }

    /// Skips the next `n` bytes without reading them.
    pub fn skip(&mut self, n: usize, what: &str) -> Result<()> {
        self.check_left(n, what)?;
        let step =
            i64::try_from(n).map_err(|_| self.error_at(self.at, format!("{what} is too large")))?;
        self.reader.seek_relative(step).map_err(|e| self.io(e))?;
        self.at.offset += n;
        Ok(())
    }

    /// Fails when fewer than `n` bytes are left.
    fn check_left(&self, n: usize, what: &str) -> Result<()> {
        let left = self.len.saturating_sub(self.at.offset);
        if n > left {
            return Err(self.error_at(
                self.at,
                format!("unexpected end of file: {what} needs {n} bytes, only {left} remain"),
            ));
        }
        Ok(())
    }
}
