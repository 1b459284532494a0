//! The integration tests of `unilateral-io`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod bad_inputs;
mod common;
mod corpus;
mod gmsh;
mod history_input;
mod layouts;
mod meshes;
mod model_bad;
mod model_read;
mod readers;
mod siconos_data;
