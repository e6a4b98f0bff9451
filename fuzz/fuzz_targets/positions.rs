//! The prescribed-positions reader (SU2 surface file or CSV). The first byte
//! picks the dimension.
#![no_main]

use libfuzzer_sys::fuzz_target;
use verbss::io::positions;
use verbss_fuzz::path;

fuzz_target!(|data: &[u8]| {
    let Some((first, rest)) = data.split_first() else {
        return;
    };
    let dim = 2 + usize::from(first % 2);
    let p = path("fuzz.dat");
    if let Ok(table) = positions::parse(rest, p, dim) {
        assert_eq!(table.coords.len(), dim * table.len());
        assert!(table.coords.iter().all(|x| x.is_finite()));
        let _ = table.check_against(usize::from(*first), p);
    }
});
