//! The VTU reader on structure-aware files (`verbss_fuzz::gen::vtu`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::vtu;
use verbss_fuzz::gen::vtu::VtuFile;
use verbss_fuzz::{check_read, path};

fuzz_target!(|file: VtuFile| {
    let bytes = file.bytes();
    let p = path("fuzz.vtu");
    if let Ok(read) = vtu::parse(&bytes, p) {
        check_read(
            &read.mesh,
            |w, m| vtu::write_to(w, m, &vtu::Fields::default()),
            |b| vtu::parse(b, p).map(|v| v.mesh),
        );
    }
});
