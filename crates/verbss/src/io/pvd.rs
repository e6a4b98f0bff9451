//! ParaView collections (`.pvd`): a list of `(time, file)` entries that
//! ParaView opens as one time series.
//!
//! ```xml
//! <VTKFile type="Collection" version="0.1" byte_order="LittleEndian">
//!   <Collection>
//!     <DataSet timestep="0.5" group="" part="0" file="step_0001.vtu"/>
//!   </Collection>
//! </VTKFile>
//! ```

use std::io::Write;
use std::path::Path;

use quick_xml::events::Event;
use quick_xml::Reader;

use crate::error::{Error, Result};

/// Writes a collection of `(timestep, file)` entries to `path` atomically
/// (see [`crate::io::write_atomic`]); file names are stored as given, so they
/// should be relative to the `.pvd` file's folder.
///
/// Timesteps are written in Rust's shortest round-trip form, so [`read`]
/// gives back the same `f64`s; a non-finite timestep is an
/// [`Error::InvalidSetting`].
pub fn write(path: &Path, entries: &[(f64, String)]) -> Result<()> {
    if let Some((t, file)) = entries.iter().find(|(t, _)| !t.is_finite()) {
        return Err(Error::InvalidSetting(format!(
            "timestep {t} of '{file}' in {} is not finite",
            path.display()
        )));
    }
    crate::io::write_atomic(path, |w| write_to(w, entries))
}

/// Writes the collection's XML.
fn write_to(w: &mut dyn Write, entries: &[(f64, String)]) -> std::io::Result<()> {
    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">"#
    )?;
    writeln!(w, "  <Collection>")?;
    for (t, file) in entries {
        writeln!(
            w,
            r#"    <DataSet timestep="{t:?}" group="" part="0" file="{}"/>"#,
            quick_xml::escape::escape(file.as_str())
        )?;
    }
    writeln!(w, "  </Collection>")?;
    writeln!(w, "</VTKFile>")
}

/// Reads the `(timestep, file)` entries of a collection, in file order.
pub fn read(path: &Path) -> Result<Vec<(f64, String)>> {
    parse(&crate::io::read_bytes(path)?, path)
}

/// Parses a collection's bytes; `path` is only used in error messages.
pub fn parse(bytes: &[u8], path: &Path) -> Result<Vec<(f64, String)>> {
    let err = |pos: u64, message: String| Error::Parse {
        path: path.to_path_buf(),
        line: 1 + bytes[..(pos as usize).min(bytes.len())]
            .iter()
            .filter(|&&b| b == b'\n')
            .count(),
        message,
    };
    let mut reader = Reader::from_reader(bytes);
    let mut entries = Vec::new();
    let mut collection = false;
    loop {
        let pos = reader.buffer_position();
        match reader.read_event() {
            Err(e) => return Err(err(reader.error_position(), format!("malformed XML: {e}"))),
            Ok(Event::Eof) => break,
            Ok(Event::Start(e) | Event::Empty(e)) => match e.name().as_ref() {
                b"VTKFile" => {
                    let kind = e.try_get_attribute("type").ok().flatten();
                    if kind.as_ref().map(|a| a.value.as_ref()) != Some(b"Collection") {
                        return Err(err(pos, r#"expected <VTKFile type="Collection">"#.into()));
                    }
                    collection = true;
                }
                b"DataSet" => {
                    let attr = |key: &str| -> Result<String> {
                        match e.try_get_attribute(key) {
                            Ok(Some(a)) => a
                                .unescape_value()
                                .map(|v| v.into_owned())
                                .map_err(|x| err(pos, format!("malformed XML: {x}"))),
                            _ => Err(err(pos, format!("DataSet without a {key} attribute"))),
                        }
                    };
                    let t = attr("timestep")?;
                    let t = t.trim().parse().map_err(|_| {
                        err(pos, format!("DataSet timestep \"{t}\" is not a number"))
                    })?;
                    entries.push((t, attr("file")?));
                }
                _ => {}
            },
            Ok(_) => {}
        }
    }
    if !collection {
        return Err(err(0, r#"expected <VTKFile type="Collection">"#.into()));
    }
    Ok(entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_keeps_times_and_names() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.pvd");
        let entries = vec![
            (0.0, "run_0000.vtu".to_string()),
            (0.1, "run_0001.vtu".to_string()),
            (1e-7, "a&b <c>.vtu".to_string()),
            (2.5e300, "d\"e'.vtu".to_string()),
        ];
        write(&path, &entries).unwrap();
        assert_eq!(read(&path).unwrap(), entries);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains(r#"<DataSet timestep="0.1" group="" part="0" file="run_0001.vtu"/>"#));
    }

    #[test]
    fn rejects_non_finite_timestep() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.pvd");
        let e = write(&path, &[(f64::NAN, "a.vtu".into())]).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "invalid setting: timestep NaN of 'a.vtu' in {} is not finite",
                path.display()
            )
        );
        assert!(!path.exists());
    }

    #[test]
    fn reader_errors_name_the_line() {
        let p = Path::new("c.pvd");
        let e = |text: &str| parse(text.as_bytes(), p).unwrap_err().to_string();
        assert_eq!(
            e("<VTKFile type=\"UnstructuredGrid\">\n</VTKFile>"),
            "c.pvd:1: expected <VTKFile type=\"Collection\">"
        );
        assert_eq!(
            e("hello"),
            "c.pvd:1: expected <VTKFile type=\"Collection\">"
        );
        assert_eq!(
            e("<VTKFile type=\"Collection\">\n<Collection>\n<DataSet timestep=\"x\" file=\"a.vtu\"/>"),
            "c.pvd:3: DataSet timestep \"x\" is not a number"
        );
        assert_eq!(
            e("<VTKFile type=\"Collection\">\n<DataSet timestep=\"1\"/>"),
            "c.pvd:2: DataSet without a file attribute"
        );
        assert_eq!(
            e("<VTKFile type=\"Collection\">\n<Collection>\n</VTKFile>"),
            "c.pvd:3: malformed XML: ill-formed document: expected `</Collection>`, but `</VTKFile>` was found"
        );
    }
}
