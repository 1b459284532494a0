//! The integration tests of `unilateral-contact`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod at_many;
mod beam_zone;
mod common;
mod generated_beams;
mod history;
mod known_answers;
mod scale_invariance;
mod solution_engine;
mod ten_pair_beam;
mod units_and_hostile;
