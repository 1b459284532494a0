#![no_main]
//! `read_lcp` on a `.toml` or a `.json` file (the first byte chooses).

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (ext, rest) = match data.split_first() {
        Some((b, rest)) if b % 2 == 0 => ("json", rest),
        Some((_, rest)) => ("toml", rest),
        None => ("toml", data),
    };
    unilateral_fuzz::check(rest, ext, unilateral_io::read_lcp);
});
