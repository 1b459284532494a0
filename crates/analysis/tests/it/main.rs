//! The integration tests of `unilateral-analysis`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod bad_models;
mod beam_bearings;
mod example1;
mod example2;
mod example3;
mod fixes;
mod hertz;
mod history;
mod keys;
mod long_path;
mod mindlin;
mod related_rows;
mod scale;
mod sparse_zone;
mod surface;
mod timings;
mod triangle_block;
mod zone_rows;
