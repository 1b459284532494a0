#![no_main]
//! `read_matrix_market` on a `.mtx` file.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    unilateral_fuzz::check(data, "mtx", unilateral_io::read_matrix_market);
});
