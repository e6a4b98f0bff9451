//! The tokens of an OpenFOAM file: words, numbers and the punctuation
//! `( ) { } ;`, with `//` and `/* */` comments skipped, each with its line;
//! and the raw bytes of a binary list.

use std::path::Path;

use crate::error::{Error, Result};
use crate::io::shown;

/// One token and the line it starts on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Token<'a> {
    /// The token's text: one punctuation character, or a run of other
    /// non-space characters.
    pub text: &'a str,
    /// 1-based line.
    pub line: usize,
}

/// A cursor over the tokens of one file.
pub(super) struct Lexer<'a> {
    bytes: &'a [u8],
    path: &'a Path,
    pos: usize,
    line: usize,
    peeked: Option<Token<'a>>,
}

/// Whether `b` is a one-character token.
fn is_punct(b: u8) -> bool {
    matches!(b, b'(' | b')' | b'{' | b'}' | b';')
}

impl<'a> Lexer<'a> {
    pub(super) fn new(bytes: &'a [u8], path: &'a Path) -> Self {
        Lexer {
            bytes,
            path,
            pos: crate::io::bom(bytes),
            line: 1,
            peeked: None,
        }
    }

    /// A parse error at `line`.
    pub(super) fn err(&self, line: usize, message: String) -> Error {
        Error::Parse {
            path: self.path.to_path_buf(),
            line,
            message,
        }
    }

    /// The bytes not read yet (an upper bound on what the rest can hold).
    pub(super) fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.pos)
    }

    /// The current line (of the next token, once peeked).
    pub(super) fn line(&self) -> usize {
        self.peeked.map_or(self.line, |t| t.line)
    }

    /// The line of the next token (the current line at the end).
    pub(super) fn next_line(&mut self) -> Result<usize> {
        Ok(self.peek()?.map_or(self.line, |t| t.line))
    }

    /// Skips spaces and comments; fails on an unclosed `/*`.
    fn skip_blank(&mut self) -> Result<()> {
        while self.pos < self.bytes.len() {
            let rest = &self.bytes[self.pos..];
            if rest[0] == b'\n' {
                self.line += 1;
                self.pos += 1;
            } else if rest[0].is_ascii_whitespace() {
                self.pos += 1;
            } else if rest.starts_with(b"//") {
                self.pos += rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
            } else if rest.starts_with(b"/*") {
                let start = self.line;
                let Some(end) = rest.windows(2).position(|w| w == b"*/") else {
                    return Err(self.err(start, "unclosed /* comment".into()));
                };
                self.line += rest[..end].iter().filter(|&&b| b == b'\n').count();
                self.pos += end + 2;
            } else {
                break;
            }
        }
        Ok(())
    }

    /// The next token without consuming it, or `None` at the end.
    pub(super) fn peek(&mut self) -> Result<Option<Token<'a>>> {
        if self.peeked.is_none() {
            self.peeked = self.read()?;
        }
        Ok(self.peeked)
    }

    /// The next token, or `None` at the end.
    pub(super) fn next(&mut self) -> Result<Option<Token<'a>>> {
        match self.peeked.take() {
            Some(t) => Ok(Some(t)),
            None => self.read(),
        }
    }

    fn read(&mut self) -> Result<Option<Token<'a>>> {
        self.skip_blank()?;
        let rest = &self.bytes[self.pos.min(self.bytes.len())..];
        let Some(&first) = rest.first() else {
            return Ok(None);
        };
        let len = if is_punct(first) {
            1
        } else {
            rest.iter()
                .position(|&b| b.is_ascii_whitespace() || is_punct(b) || b == b'/')
                .unwrap_or(rest.len())
                .max(1)
        };
        let text = std::str::from_utf8(&rest[..len]).map_err(|_| {
            self.err(
                self.line,
                "non-ASCII bytes (expected OpenFOAM ASCII text; binary data where the \
                 header says `format ascii`?)"
                    .into(),
            )
        })?;
        self.pos += len;
        Ok(Some(Token {
            text,
            line: self.line,
        }))
    }

    /// The `n` bytes right after the last token read (binary list data),
    /// or `None` when fewer are left. Call it with no token peeked.
    pub(super) fn raw(&mut self, n: usize) -> Option<&'a [u8]> {
        debug_assert!(self.peeked.is_none());
        let end = self.pos.checked_add(n).filter(|&e| e <= self.bytes.len())?;
        let data = &self.bytes[self.pos..end];
        self.line += data.iter().filter(|&&b| b == b'\n').count();
        self.pos = end;
        Some(data)
    }

    /// The next token, failing at the end of the file with `expected`.
    pub(super) fn expect_any(&mut self, expected: &str) -> Result<Token<'a>> {
        match self.next()? {
            Some(t) => Ok(t),
            None => Err(self.err(
                self.line,
                format!("file ends where {expected} was expected"),
            )),
        }
    }

    /// Consumes the token `text`, or fails naming what was found.
    pub(super) fn expect(&mut self, text: &str, context: &str) -> Result<usize> {
        let t = self.expect_any(&format!("'{text}' {context}"))?;
        if t.text != text {
            return Err(self.err(
                t.line,
                format!("expected '{text}' {context}, found '{}'", shown(t.text)),
            ));
        }
        Ok(t.line)
    }

    /// The next token as a non-negative integer (a count or a label).
    pub(super) fn label(&mut self, what: &str) -> Result<(usize, usize)> {
        let t = self.expect_any(what)?;
        match t.text.parse::<usize>() {
            Ok(n) => Ok((n, t.line)),
            Err(_) => Err(self.err(
                t.line,
                format!("expected {what}, found '{}'", shown(t.text)),
            )),
        }
    }

    /// The next token as a finite number.
    pub(super) fn scalar(&mut self, what: &str) -> Result<f64> {
        let t = self.expect_any(what)?;
        match t.text.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(
                t.line,
                format!(
                    "expected {what} (a finite number), found '{}'",
                    shown(t.text)
                ),
            )),
        }
    }

    /// Skips one dictionary value up to and including its `;`, nested
    /// `( )` and `{ }` included.
    pub(super) fn skip_value(&mut self, key: &str, line: usize) -> Result<()> {
        let mut depth = 0usize;
        loop {
            let Some(t) = self.next()? else {
                return Err(self.err(line, format!("entry '{}' has no closing ';'", shown(key))));
            };
            match t.text {
                "(" | "{" => depth += 1,
                ")" | "}" if depth == 0 => {
                    return Err(self.err(
                        t.line,
                        format!("unbalanced '{}' in entry '{}'", t.text, shown(key)),
                    ))
                }
                ")" | "}" => {
                    depth -= 1;
                    if depth == 0 && t.text == "}" && self.peek()?.is_none_or(|n| n.text != ";") {
                        return Ok(());
                    }
                }
                ";" if depth == 0 => return Ok(()),
                _ => {}
            }
        }
    }
}
