//! The integration tests of `unilateral-analysis`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod bad_models;
mod beam_bearings;
mod block_sweep;
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

/// The structural model of a beam on bearings of the oracle's fixture, read from its model
/// file's text as a user's file is read.
pub(crate) fn bearings_model(
    b: &unilateral_oracle::fixtures::bearings::Bearings,
) -> unilateral_fem::Model {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("beam.toml");
    std::fs::write(
        &path,
        unilateral_oracle::fixtures::bearings::beam_model_with(b),
    )
    .unwrap();
    match unilateral_io::read_problem(&path).unwrap() {
        unilateral_io::Problem::Structural(p) => p.model,
        unilateral_io::Problem::ContactZone(_) => panic!("a structural model"),
    }
}
