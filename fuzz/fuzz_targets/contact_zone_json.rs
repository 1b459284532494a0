#![no_main]
//! `read_contact_zone` on a `.json` file.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    unilateral_fuzz::check(data, "json", unilateral_io::read_contact_zone);
});
