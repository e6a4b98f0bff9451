//! The VTU reader (ASCII, binary, appended, zlib).
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::vtu;
use verbss_fuzz::{check_read, path};

fuzz_target!(|data: &[u8]| {
    let p = path("fuzz.vtu");
    if let Ok(read) = vtu::parse(data, p) {
        check_read(
            &read.mesh,
            |w, m| vtu::write_to(w, m, &vtu::Fields::default()),
            |b| vtu::parse(b, p).map(|v| v.mesh),
        );
    }
});
