#![no_main]
//! `read_problem` on a `.toml` file.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    unilateral_fuzz::check(data, "toml", unilateral_io::read_problem);
});
