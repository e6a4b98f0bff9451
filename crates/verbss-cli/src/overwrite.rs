//! The input mesh is never an output unless the user says so.

use std::path::Path;

use anyhow::bail;

/// Fails when `output` is the file `input` (same canonical path), unless
/// `overwrite` (`--overwrite`).
pub fn refuse_input_as_output(input: &Path, output: &Path, overwrite: bool) -> anyhow::Result<()> {
    let same = match (input.canonicalize(), output.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same && !overwrite {
        bail!(
            "{}: the output is the input mesh {} (give --overwrite to replace it)",
            output.display(),
            input.display()
        );
    }
    Ok(())
}
