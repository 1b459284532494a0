#![no_main]
//! The two Siconos `.dat` readers, `read_siconos_lcp` and `read_fc2d`, on the same bytes.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    unilateral_fuzz::check(data, "dat", unilateral_io::read_siconos_lcp);
    unilateral_fuzz::check(data, "dat", unilateral_io::read_fc2d);
});
