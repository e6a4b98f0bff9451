//! The OpenFOAM reader on structure-aware cases (`verbss_fuzz::gen::foam`):
//! the five polyMesh files, ASCII or binary, written into a case folder. A
//! mesh read passes `Mesh::validate`, and the whole case written from it
//! into another folder reads back.
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::{read, write, WriteOptions};
use verbss_fuzz::gen::foam::FoamCase;

fuzz_target!(|case: FoamCase| {
    let Some(files) = case.files() else {
        return;
    };
    let root = std::env::temp_dir().join(format!("verbss-fuzz-foam-{}", std::process::id()));
    let (dir, out) = (root.join("case"), root.join("out"));
    let _ = std::fs::remove_dir_all(&root);
    let poly = dir.join("constant/polyMesh");
    std::fs::create_dir_all(&poly).unwrap();
    for (name, bytes) in &files {
        std::fs::write(poly.join(name), bytes).unwrap();
    }
    if let Ok(mesh) = read(&dir) {
        mesh.validate()
            .expect("a mesh the reader accepted passes validate");
        std::fs::create_dir_all(&out).unwrap();
        if write(&out, &mesh, &WriteOptions::default()).is_ok() {
            if let Err(e) = read(&out) {
                panic!("a written case does not read back: {e}");
            }
        }
    }
});
