//! The CGNS reader on structure-aware files (`verbss_fuzz::gen::cgns`):
//! real HDF5 files, written node by node. No file may crash the process
//! (inside the CGNS and HDF5 libraries included); a mesh read passes
//! `Mesh::validate`, and its CGNS copy with new coordinates reads back.
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::cgns::nodes;
use verbss::io::{read, write, WriteOptions};
use verbss_fuzz::gen::cgns::CgnsFile;

fuzz_target!(|file: CgnsFile| {
    let dir = std::env::temp_dir().join(format!("verbss-fuzz-cgns-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("fuzz.cgns");
    let _ = std::fs::remove_file(&path);
    if nodes::write(&path, &file.nodes()).is_err() {
        return;
    }
    if let Ok(mesh) = read(&path) {
        mesh.validate()
            .expect("a mesh the reader accepted passes validate");
        let copy = dir.join("copy.cgns");
        if write(&copy, &mesh, &WriteOptions::default()).is_ok() {
            if let Err(e) = read(&copy) {
                panic!("a written mesh does not read back: {e}");
            }
        }
    }
});
