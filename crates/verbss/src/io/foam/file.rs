//! The parts of an OpenFOAM file: the `FoamFile { … }` header and the
//! lists `N ( item … )`, `( item … )` and `N { item }` (N copies of one
//! item), or in a binary file `N ( raw little-endian numbers )`.

use super::lex::{Lexer, Token};
use crate::error::Result;
use crate::io::shown;

/// What the `FoamFile { … }` header says of the data after it.
#[derive(Default)]
pub(super) struct Header {
    /// `class`, when given.
    pub class: Option<String>,
    /// `format binary`: the lists hold raw little-endian numbers.
    pub binary: Option<Arch>,
}

/// The sizes of a binary file's numbers (`arch "LSB;label=32;scalar=64"`).
#[derive(Clone, Copy)]
pub(super) struct Arch {
    /// Bytes of a label (4 or 8).
    pub label: usize,
    /// Bytes of a scalar (4 or 8).
    pub scalar: usize,
}

/// The bytes of `label=32`-style sizes: 4 or 8.
fn arch_bytes(lx: &Lexer, line: usize, entry: &str) -> Result<usize> {
    let bits = entry.split('=').nth(1).unwrap_or("").trim_end_matches('"');
    match bits {
        "32" => Ok(4),
        "64" => Ok(8),
        _ => Err(lx.err(
            line,
            format!(
                "arch entry '{}' (expected label=32 or 64, scalar=32 or 64)",
                shown(entry)
            ),
        )),
    }
}

/// Reads the optional `FoamFile { … }` header: the `class`, and for
/// `format binary` the sizes `arch` gives (labels of 32 bits and scalars of
/// 64 when it gives none, as OpenFOAM writes them by default).
pub(super) fn header(lx: &mut Lexer) -> Result<Header> {
    if lx.peek()?.is_none_or(|t| t.text != "FoamFile") {
        return Ok(Header::default());
    }
    lx.next()?;
    lx.expect("{", "after FoamFile")?;
    let mut header = Header::default();
    let mut binary = false;
    let mut arch = Arch {
        label: 4,
        scalar: 8,
    };
    loop {
        let key = lx.expect_any("a header entry or '}'")?;
        if key.text == "}" {
            header.binary = binary.then_some(arch);
            return Ok(header);
        }
        let Some(value) = lx.peek()? else {
            return Err(lx.err(key.line, "file ends inside the FoamFile header".into()));
        };
        // `arch "LSB;label=32;scalar=64";` comes as the tokens `arch`
        // `"LSB` `;` `label=32` `;` `scalar=64"` `;`.
        match (key.text, value.text) {
            ("format", "ascii") => {}
            ("format", "binary") => binary = true,
            ("format", other) => {
                return Err(lx.err(
                    value.line,
                    format!(
                        "unknown format '{}' (expected ascii or binary)",
                        shown(other)
                    ),
                ))
            }
            ("arch", v) if v.contains("MSB") => {
                return Err(lx.err(
                    value.line,
                    "big-endian (MSB) binary files are not supported (expected LSB)".into(),
                ))
            }
            (k, _) if k.starts_with("label=") => arch.label = arch_bytes(lx, key.line, k)?,
            (k, _) if k.trim_start_matches('"').starts_with("scalar=") => {
                arch.scalar = arch_bytes(lx, key.line, k)?
            }
            ("class", c) => header.class = Some(c.to_string()),
            _ => {}
        }
        lx.skip_value(key.text, key.line)?;
    }
}

/// Reads a binary list `N ( raw bytes )` of `what`, each item `item_bytes`
/// long; gives its raw bytes and the line it starts on.
pub(super) fn raw_list<'a>(
    lx: &mut Lexer<'a>,
    what: &str,
    item_bytes: usize,
) -> Result<(&'a [u8], usize)> {
    let (count, line) = lx.label(&format!("the count of a binary list of {what}"))?;
    lx.expect("(", &format!("after the count {count} of a binary list"))?;
    let data = count
        .checked_mul(item_bytes)
        .and_then(|n| lx.raw(n))
        .ok_or_else(|| {
            lx.err(
                line,
                format!("the file ends inside the binary list of {count} {what}"),
            )
        })?;
    lx.expect(")", &format!("after the {count} {what} of a binary list"))?;
    Ok((data, line))
}

/// The little-endian numbers of `size` bytes (4 or 8) in `data`, as labels
/// below `bound`.
pub(super) fn raw_labels(
    lx: &Lexer,
    line: usize,
    data: &[u8],
    size: usize,
    what: &str,
    bound: usize,
) -> Result<Vec<usize>> {
    data.chunks_exact(size)
        .map(|b| {
            let v = if size == 4 {
                i64::from(i32::from_le_bytes(b.try_into().expect("4 bytes")))
            } else {
                i64::from_le_bytes(b.try_into().expect("8 bytes"))
            };
            usize::try_from(v)
                .ok()
                .filter(|&n| n < bound)
                .ok_or_else(|| {
                    lx.err(
                        line,
                        format!(
                            "{what} {v} in the binary list out of range (expected 0 to {})",
                            bound as i64 - 1
                        ),
                    )
                })
        })
        .collect()
}

/// The little-endian finite numbers of `size` bytes (4 or 8) in `data`.
pub(super) fn raw_scalars(lx: &Lexer, line: usize, data: &[u8], size: usize) -> Result<Vec<f64>> {
    data.chunks_exact(size)
        .map(|b| {
            let v = if size == 4 {
                f64::from(f32::from_le_bytes(b.try_into().expect("4 bytes")))
            } else {
                f64::from_le_bytes(b.try_into().expect("8 bytes"))
            };
            if v.is_finite() {
                Ok(v)
            } else {
                Err(lx.err(
                    line,
                    format!("a coordinate {v} in the binary list (expected finite numbers)"),
                ))
            }
        })
        .collect()
}

/// How a list is written.
pub(super) enum Shape {
    /// `N ( … )` or `( … )`: the items follow, then `)`.
    Items(Option<usize>),
    /// `N { item }`: one item, repeated N times, then `}`.
    Uniform(usize),
}

/// Reads the start of a list of `what`; `N { item }` is refused with more
/// than `max_uniform` items (its size is not bounded by the file's).
pub(super) fn list_start(lx: &mut Lexer, what: &str, max_uniform: usize) -> Result<Shape> {
    let first = lx.expect_any(&format!("a list of {what}"))?;
    if first.text == "(" {
        return Ok(Shape::Items(None));
    }
    let Ok(count) = first.text.parse::<usize>() else {
        return Err(lx.err(
            first.line,
            format!(
                "expected a list of {what} (N ( … )), found '{}'",
                shown(first.text)
            ),
        ));
    };
    let open = lx.expect_any(&format!("'(' or '{{' after the count {count}"))?;
    match open.text {
        "(" => Ok(Shape::Items(Some(count))),
        "{" if count <= max_uniform => Ok(Shape::Uniform(count)),
        "{" => Err(lx.err(
            open.line,
            format!("{count}{{…}} is more {what} than the {max_uniform} this mesh can have"),
        )),
        other => Err(lx.err(
            open.line,
            format!(
                "expected '(' or '{{' after the count {count}, found '{}'",
                shown(other)
            ),
        )),
    }
}

/// Reads a whole list of `what`, each item read by `item` (given its first
/// token); `per_item` is the fewest bytes an item takes in the file, which
/// bounds the room reserved for a count. Returns the items and the line of
/// each.
pub(super) fn list<'a, T: Clone>(
    lx: &mut Lexer<'a>,
    what: &str,
    max_uniform: usize,
    per_item: usize,
    mut item: impl FnMut(&mut Lexer<'a>, Token<'a>) -> Result<T>,
) -> Result<(Vec<T>, Vec<u32>)> {
    let start = lx.next_line()?;
    let shape = list_start(lx, what, max_uniform)?;
    let mut items = Vec::new();
    let mut lines = Vec::new();
    match shape {
        Shape::Uniform(count) => {
            let t = lx.expect_any(what)?;
            let line = t.line;
            let value = item(lx, t)?;
            lx.expect("}", &format!("after the one item of {count}{{…}}"))?;
            items = vec![value; count];
            lines = vec![line as u32; count];
        }
        Shape::Items(count) => {
            let room = count.unwrap_or(0).min(lx.remaining() / per_item.max(1));
            items.reserve(room);
            lines.reserve(room);
            loop {
                let t = lx.expect_any(&format!("{what} or ')'"))?;
                if t.text == ")" {
                    break;
                }
                if count.is_some_and(|n| items.len() == n) {
                    return Err(lx.err(
                        t.line,
                        format!(
                            "more {what} than the {} announced at line {start} \
                             (expected ')')",
                            items.len()
                        ),
                    ));
                }
                lines.push(t.line as u32);
                items.push(item(lx, t)?);
            }
            if let Some(n) = count.filter(|&n| n != items.len()) {
                return Err(lx.err(
                    lx.line(),
                    format!(
                        "the list holds {} {what}, not the {n} announced at line {start}",
                        items.len()
                    ),
                ));
            }
        }
    }
    Ok((items, lines))
}

/// Fails unless only comments are left.
pub(super) fn end(lx: &mut Lexer) -> Result<()> {
    match lx.next()? {
        None => Ok(()),
        Some(t) => Err(lx.err(
            t.line,
            format!(
                "unexpected '{}' after the list (expected the end of the file)",
                shown(t.text)
            ),
        )),
    }
}

/// The label in token `t`, below `bound` (`what` names it in messages).
pub(super) fn label_below(lx: &Lexer, t: Token, what: &str, bound: usize) -> Result<usize> {
    match t.text.parse::<usize>() {
        Ok(n) if n < bound => Ok(n),
        Ok(n) => Err(lx.err(
            t.line,
            format!(
                "{what} {n} out of range (expected 0 to {})",
                bound as i64 - 1
            ),
        )),
        Err(_) => Err(lx.err(
            t.line,
            format!("expected {what} (a label), found '{}'", shown(t.text)),
        )),
    }
}
