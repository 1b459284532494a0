//! # unilateral-contact — frictional unilateral contact as a parametric LCP
//!
//! Data flow: a [`ContactZone`] (the contact stiffness matrix and load vectors of a structure,
//! `formulation.md` §2) → the `3m` LCP of §3 ([`ContactLcp`]) → the load path of the parametric
//! Lemke method (`unilateral-lcp`) → pair states and events ([`solve`] → [`ContactSolution`]).
//!
//! Files: `zone.rs` (the data), `lcp.rs` (the `3m` LCP), `units.rs` (the normalisation),
//! `settings.rs` (the solve's settings, embedding the engine's), `solve.rs` (the algorithm),
//! `solution.rs` (the answer: states, events, outcome, and the solution that keeps the prepared
//! engine to answer for any load on its path), `error.rs` (the engine's errors nested by type).
//!
//! The zone is solved in normalised units: forces divided by a power of two near the data's
//! largest force, stiffness by one near its largest stiffness, displacements by their ratio
//! (the `units` module). States, events and (scaled) numbers are therefore the same in N and m,
//! kN and mm or MN and m; results are handed back in the user's units, checked finite.
//!
//! Signs (`formulation.md` §1): `x_n` compression positive, `z_n` opening positive; friction is
//! split as `x_t± = f·x_n ± x_t`, `z_t = (z_t+ − z_t-)/2`.

#![warn(missing_docs)]

mod error;
mod history;
mod lcp;
mod settings;
mod solution;
mod solve;
mod sparse_zone;
mod units;
mod zone;

pub use error::ContactError;
pub use history::{
    follow_history, follow_history_judged, History, HistoryResidual, HistorySolution, HistoryStep,
    LoadCase, Stage, StageSolution, StageStatus,
};
pub use lcp::ContactLcp;
pub use settings::SolveSettings;
pub use solution::{
    number_text, pair_results, ContactSolution, Event, EventKind, LoadStep, Outcome, PairResult,
    PairState, NO_STATE_AT_START,
};
pub use solve::{solve, solve_judged, solve_shared, solve_sparse};
pub use sparse_zone::SparseZone;
pub use unilateral_lcp::Follow;
pub use zone::{ContactLoad, ContactZone};
