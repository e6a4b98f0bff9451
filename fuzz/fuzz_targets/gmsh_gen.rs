//! The Gmsh reader on structure-aware files (`verbss_fuzz::gen::msh`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::{gmsh, MshVersion};
use verbss_fuzz::gen::msh::MshFile;
use verbss_fuzz::{check_read, path};

fuzz_target!(|file: MshFile| {
    let bytes = file.bytes();
    let p = path("fuzz.msh");
    if let Ok(mesh) = gmsh::parse(&bytes, p) {
        for (version, binary) in [(MshVersion::V22, false), (MshVersion::V41, true)] {
            check_read(
                &mesh,
                |w, m| gmsh::write_to(w, m, version, binary),
                |b| gmsh::parse(b, p),
            );
        }
    }
});
