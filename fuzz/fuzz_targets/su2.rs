//! The SU2 reader.
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::su2;
use verbss_fuzz::{check_read, path};

fuzz_target!(|data: &[u8]| {
    let p = path("fuzz.su2");
    if let Ok(mesh) = su2::parse(data, p) {
        check_read(&mesh, |w, m| su2::write_to(w, m), |b| su2::parse(b, p));
    }
});
