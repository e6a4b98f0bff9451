//! The SU2 reader on structure-aware files (`verbss_fuzz::gen::su2`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::su2;
use verbss_fuzz::gen::su2::Su2File;
use verbss_fuzz::{check_read, path};

fuzz_target!(|file: Su2File| {
    let bytes = file.bytes();
    let p = path("fuzz.su2");
    if let Ok(mesh) = su2::parse(&bytes, p) {
        check_read(&mesh, |w, m| su2::write_to(w, m), |b| su2::parse(b, p));
    }
});
