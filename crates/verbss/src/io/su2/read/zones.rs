//! Multi-zone files: the `NZONE=` and `IZONE=` lines that split a file into
//! zones, each read by its own [`Parser`].

use std::path::Path;

use super::{Line, Parser};
use crate::error::{Error, Result};
use crate::io::su2::{Anchor, Skipped};
use crate::mesh::Mesh;

/// The most zones a file may announce: real files have a few (fluid and
/// solid), and each costs a little however small the file that announces it.
const MAX_ZONES: usize = 1 << 16;

/// The keywords of a zone's own sections: none may come before `IZONE= 1`
/// in a file with several zones.
const ZONE_KEYWORDS: [&str; 6] = [
    "NDIME",
    "NELEM",
    "NPOIN",
    "NMARK",
    "MARKERTAG",
    "MARKERELEMS",
];

/// A zone's place in the file.
struct Span {
    /// Byte offset just past its `IZONE=` line.
    start: usize,
    /// Byte offset of the next zone's `IZONE=` line, or the file's length.
    end: usize,
    /// The line number of its `IZONE=` line.
    line: usize,
}

/// How a file is split into zones: `NZONE=` with its line, and the zones
/// (none for a file without `IZONE=` lines, which is one zone).
struct Layout {
    nzone: Option<(usize, usize)>,
    zones: Vec<Span>,
}

impl Layout {
    /// Finds the `NZONE=` and `IZONE=` lines, checking that `NZONE=` comes
    /// first and the zones are numbered 1, 2, … up to its count.
    fn scan(bytes: &[u8], path: &Path) -> Result<Layout> {
        let mut p = Parser::new(bytes, path);
        let mut layout = Layout {
            nzone: None,
            zones: Vec::new(),
        };
        let mut first_section: Option<(&str, usize)> = None;
        while let Some(line) = p.next_line()? {
            let Line::Keyword { raw, key, value } = line else {
                continue;
            };
            match key.as_str() {
                "NZONE" => {
                    if let Some((_, first)) = layout.nzone {
                        let message = format!("NZONE= given twice (first at line {first})");
                        return Err(p.err(p.line, message));
                    }
                    if let Some((keyword, line)) = first_section {
                        let message = format!(
                            "NZONE= after {keyword}= at line {line} (expected NZONE= first)"
                        );
                        return Err(p.err(p.line, message));
                    }
                    let n = p.count(value, "NZONE=")?;
                    if n == 0 || n > MAX_ZONES {
                        let message = format!("NZONE= {n} (expected 1 to {MAX_ZONES} zones)");
                        return Err(p.err(p.line, message));
                    }
                    layout.nzone = Some((n, p.line));
                }
                "IZONE" => layout.zone(&p, value, first_section)?,
                // A file's own NDIME= before its zones (before or after
                // NZONE=, as SU2's fluid–structure meshes have it): SU2 reads
                // each zone's from after its IZONE= line, and so does verbss.
                "NDIME" if layout.zones.is_empty() && first_section.is_none() => {}
                k if layout.zones.is_empty() && ZONE_KEYWORDS.contains(&k) => {
                    if let Some((n, line)) = layout.nzone.filter(|z| z.0 > 1) {
                        let message = format!(
                            "{raw}= before IZONE= 1 (NZONE= {n} at line {line}: expected \
                             IZONE= 1 before the first zone's sections)"
                        );
                        return Err(p.err(p.line, message));
                    }
                    first_section.get_or_insert((raw, p.line));
                }
                _ => {}
            }
        }
        if let Some((n, line)) = layout.nzone {
            if !layout.zones.is_empty() && layout.zones.len() < n {
                let message = format!(
                    "file ends after {} of the {n} zones announced by NZONE= at line {line}",
                    layout.zones.len()
                );
                return Err(p.err(p.line.max(1), message));
            }
        }
        Ok(layout)
    }

    /// An `IZONE=` line: the next zone starts after it.
    fn zone(
        &mut self,
        p: &Parser,
        value: &str,
        first_section: Option<(&str, usize)>,
    ) -> Result<()> {
        let Some((n, nzone_line)) = self.nzone else {
            return Err(p.err(
                p.line,
                "IZONE= without NZONE= (a multi-zone file starts with NZONE= N)".into(),
            ));
        };
        if let (Some((keyword, line)), true) = (first_section, self.zones.is_empty()) {
            let message = format!(
                "IZONE= after {keyword}= at line {line} (expected IZONE= 1 before the \
                 first zone's sections)"
            );
            return Err(p.err(p.line, message));
        }
        let k = p.count(value, "IZONE=")?;
        let expected = self.zones.len() + 1;
        if k != expected {
            let message = format!("IZONE= {k} out of order (expected IZONE= {expected})");
            return Err(p.err(p.line, message));
        }
        if k > n {
            let message = format!(
                "IZONE= {k} is one more zone than the {n} announced by NZONE= at line {nzone_line}"
            );
            return Err(p.err(p.line, message));
        }
        if let Some(last) = self.zones.last_mut() {
            last.end = p.line_start;
        }
        let len = p.bytes.len();
        self.zones.push(Span {
            start: p.pos.min(len),
            end: len,
            line: p.line,
        });
        Ok(())
    }

    /// Reads zone `span`: its mesh and where what it read ends.
    fn read(bytes: &[u8], path: &Path, span: &Span) -> Result<(Mesh, usize)> {
        Parser::within(bytes, path, span.start, span.end, span.line + 1).run()
    }
}

/// Reads zone `zone` (1-based) and the number of zones; see [`crate::io::su2::parse_zone`].
pub(in crate::io::su2) fn parse_zone(
    bytes: &[u8],
    path: &Path,
    zone: usize,
) -> Result<(Mesh, usize)> {
    let layout = Layout::scan(bytes, path)?;
    if layout.zones.is_empty() {
        if zone != 1 {
            return Err(Error::InvalidSetting(format!(
                "{}: zone {zone} asked for, but the file has one zone (no IZONE= lines)",
                path.display()
            )));
        }
        return Ok((Parser::new(bytes, path).run()?.0, 1));
    }
    let count = layout.zones.len();
    if zone == 0 || zone > count {
        let (_, line) = layout.nzone.expect("zones come after NZONE=");
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line,
            message: format!("zone {zone} asked for, but NZONE= {count} (zones 1 to {count})"),
        });
    }
    let mut chosen = None;
    for (k, span) in layout.zones.iter().enumerate() {
        let (mesh, end) = Layout::read(bytes, path, span)?;
        if k + 1 == zone {
            chosen = Some((mesh, end, span.start));
        }
    }
    let (mut mesh, end, start) = chosen.expect("zone is in range");
    let text = |range: std::ops::Range<usize>| String::from_utf8_lossy(&bytes[range]).into_owned();
    mesh.origin.su2_skipped.insert(
        0,
        Skipped {
            after: Anchor::ZonesBefore,
            text: text(0..start),
        },
    );
    if end < bytes.len() {
        mesh.origin.su2_skipped.push(Skipped {
            after: Anchor::ZonesAfter,
            text: text(end..bytes.len()),
        });
    }
    Ok((mesh, count))
}

/// Reads every zone; see [`crate::io::su2::parse_zones`].
pub(in crate::io::su2) fn parse_zones(bytes: &[u8], path: &Path) -> Result<Vec<Mesh>> {
    let layout = Layout::scan(bytes, path)?;
    if layout.zones.is_empty() {
        return Ok(vec![Parser::new(bytes, path).run()?.0]);
    }
    layout
        .zones
        .iter()
        .map(|span| Layout::read(bytes, path, span).map(|(mesh, _)| mesh))
        .collect()
}
