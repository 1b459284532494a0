//! The integration tests of `unilateral-output`, as modules of one test binary: one build and
//! one link for all of them.

mod charts;
mod examples;
mod history;
mod json_stream;
mod structure_picture;
mod units;
mod vtk;
mod vtk_binary;
