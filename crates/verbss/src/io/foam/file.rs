//! The parts of an OpenFOAM ASCII file: the `FoamFile { … }` header and the
//! lists `N ( item … )`, `( item … )` and `N { item }` (N copies of one item).

use super::lex::{Lexer, Token};
use crate::error::Result;
use crate::io::shown;

/// Reads the optional `FoamFile { … }` header and returns its `class`.
/// Fails for `format binary;`.
pub(super) fn header(lx: &mut Lexer) -> Result<Option<String>> {
    if lx.peek()?.is_none_or(|t| t.text != "FoamFile") {
        return Ok(None);
    }
    lx.next()?;
    lx.expect("{", "after FoamFile")?;
    let mut class = None;
    loop {
        let key = lx.expect_any("a header entry or '}'")?;
        if key.text == "}" {
            return Ok(class);
        }
        let Some(value) = lx.peek()? else {
            return Err(lx.err(key.line, "file ends inside the FoamFile header".into()));
        };
        match (key.text, value.text) {
            ("format", "ascii") => {}
            ("format", "binary") => {
                return Err(lx.err(
                    value.line,
                    "format binary is not supported (expected format ascii: run \
                     `foamFormatConvert` with `writeFormat ascii;` in system/controlDict)"
                        .into(),
                ))
            }
            ("format", other) => {
                return Err(lx.err(
                    value.line,
                    format!("unknown format '{}' (expected ascii)", shown(other)),
                ))
            }
            ("class", c) => class = Some(c.to_string()),
            _ => {}
        }
        lx.skip_value(key.text, key.line)?;
    }
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
