//! The integration tests of `unilateral-oracle`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod example1;
mod fixtures;
mod hand;
mod random;
