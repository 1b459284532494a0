//! The integration tests of `unilateral-lcp`, as modules of one test binary: one build and one
//! link for all of them (a binary per file costs minutes on a two-core machine).

mod against_oracle;
mod common;
mod contact_path;
mod degenerate;
mod hostile;
mod paper_example1;
mod ray_verification;
mod related_rows;
mod schur;
mod schur_beam;
mod solver;
mod sweep;
mod units;
