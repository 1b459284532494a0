//! The integration tests of `unilateral-fem`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod condensation;
mod errors;
mod example1;
mod fine_mesh;
mod frames;
mod load_cases;
mod plane;
mod segment;
mod triangle;
