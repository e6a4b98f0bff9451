//! File patterns of per-step positions: `{step}` and `{step:0W}` fields.

use std::path::PathBuf;

/// The widest `{step:0W}` a pattern may ask for (a step number has at
/// most 20 digits).
const MAX_STEP_WIDTH: usize = 20;

/// The `{step}` and `{step:0W}` fields of a file pattern: where each is and
/// its width (0 for `{step}`); the message for any other `{step…` or a
/// width above [`MAX_STEP_WIDTH`].
pub(super) fn step_fields(
    s: &str,
) -> std::result::Result<Vec<(std::ops::Range<usize>, usize)>, String> {
    // The pattern as quoted in messages: at most 60 characters.
    let quoted = match s.char_indices().nth(60) {
        Some((cut, _)) => format!("{}…", &s[..cut]),
        None => s.to_string(),
    };
    let mut fields = Vec::new();
    let mut from = 0;
    while let Some(k) = s[from..].find("{step") {
        let start = from + k;
        let rest = &s[start + 5..];
        let (width, len) = if rest.starts_with('}') {
            (0, 6)
        } else {
            let digits = rest
                .strip_prefix(":0")
                .map(|d| &d[..d.bytes().take_while(u8::is_ascii_digit).count()])
                .filter(|d| rest[2 + d.len()..].starts_with('}'));
            let Some(digits) = digits else {
                let field: String = s[start..].chars().take(12).collect();
                return Err(format!(
                    "the file pattern \"{quoted}\" has \"{field}…\" (expected {{step}} or {{step:0W}}, \
                     W the number of digits)"
                ));
            };
            match digits.parse::<usize>() {
                _ if digits.is_empty() => (0, 8),
                Ok(w) if w <= MAX_STEP_WIDTH => (w, 8 + digits.len()),
                _ => {
                    return Err(format!(
                    "the file pattern \"{quoted}\" asks for {} digits (at most {MAX_STEP_WIDTH})",
                    digits.trim_start_matches('0')
                ))
                }
            }
        };
        fields.push((start..start + len, width));
        from = start + len;
    }
    Ok(fields)
}

/// The file of step `step` for a pattern with `{step}` or `{step:0W}`
/// fields (checked by [`Motion::validate`](crate::motion::Motion::validate); a pattern with a bad field is
/// returned as it is).
pub fn step_path(pattern: &std::path::Path, step: usize) -> PathBuf {
    let s = pattern.to_string_lossy();
    let Ok(fields) = step_fields(&s) else {
        return pattern.to_path_buf();
    };
    let mut out = String::new();
    let mut from = 0;
    for (range, width) in fields {
        out += &s[from..range.start];
        out += &format!("{step:0width$}");
        from = range.end;
    }
    out += &s[from..];
    PathBuf::from(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::{Motion, PositionSource};

    #[test]
    fn step_file_patterns() {
        let p = std::path::Path::new("d/pos_{step:04}.csv");
        assert_eq!(step_path(p, 7), PathBuf::from("d/pos_0007.csv"));
        let p = std::path::Path::new("pos_{step}.dat");
        assert_eq!(step_path(p, 12), PathBuf::from("pos_12.dat"));
        let p = std::path::Path::new("{step}/é_{step:03}.dat");
        assert_eq!(step_path(p, 5), PathBuf::from("5/é_005.dat"));
        let bad = |p: &str| {
            Motion::Positions(PositionSource::PerStep(PathBuf::from(p)))
                .validate(2)
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            bad("p_{step:099999999999999999999999}.dat"),
            "invalid setting: the file pattern \"p_{step:099999999999999999999999}.dat\" asks for \
             99999999999999999999999 digits (at most 20)"
        );
        assert_eq!(
            bad("p_{step:0-5}.dat"),
            "invalid setting: the file pattern \"p_{step:0-5}.dat\" has \"{step:0-5}.d…\" \
             (expected {step} or {step:0W}, W the number of digits)"
        );
        assert!(bad(&"{step".repeat(100_000)).contains("has \"{step{step{s…\""));
    }
}
