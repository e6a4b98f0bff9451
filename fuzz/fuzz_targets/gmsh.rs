//! Gmsh MSH 2.2 and 4.1, ASCII and binary (the header picks the reader).
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::{gmsh, MshVersion};
use verbss_fuzz::{check_read, path};

fuzz_target!(|data: &[u8]| {
    let p = path("fuzz.msh");
    if let Ok(mesh) = gmsh::parse(data, p) {
        let binary = data.windows(5).take(40).any(|w| w == b" 1 8\n");
        for version in [MshVersion::V22, MshVersion::V41] {
            check_read(
                &mesh,
                |w, m| gmsh::write_to(w, m, version, binary),
                |b| gmsh::parse(b, p),
            );
        }
    }
});
