//! `include/verbss.h` is what cbindgen generates from `src/lib.rs` and its modules with
//! `cbindgen.toml`: the committed header never drifts from the code.
//!
//! After changing the API, rewrite the header with
//! `VERBSS_WRITE_HEADER=1 cargo test -p verbss-capi --test header`.

use std::path::Path;

const CRATE: &str = env!("CARGO_MANIFEST_DIR");

#[test]
fn committed_header_is_the_generated_one() {
    let config = cbindgen::Config::from_file(Path::new(CRATE).join("cbindgen.toml")).unwrap();
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(Path::new(CRATE).join("src/lib.rs"))
        .generate()
        .unwrap()
        .write(&mut generated);
    let generated = String::from_utf8(generated).unwrap();
    let path = Path::new(CRATE).join("../../include/verbss.h");
    if std::env::var_os("VERBSS_WRITE_HEADER").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "include/verbss.h differs from the generated header; rewrite it with \
         VERBSS_WRITE_HEADER=1 cargo test -p verbss-capi --test header"
    );
}
