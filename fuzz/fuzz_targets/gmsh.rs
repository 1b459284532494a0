#![no_main]
//! `read_gmsh` on a `.msh` file.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    unilateral_fuzz::check(data, "msh", unilateral_io::read_gmsh);
});
