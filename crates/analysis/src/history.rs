//! Load histories of structural models: the history followed on the condensed contact zone,
//! and the full structural results at the end of every stage (`history.md`).

use unilateral_contact::{ContactZone, HistorySolution};
use unilateral_fem::{Condensed, Results};

use crate::Timings;

/// A finished history analysis of a structural model.
#[derive(Debug)]
pub struct HistoryAnalysis {
    /// The contact zone of the model and the means of recovery.
    pub condensed: Condensed,
    /// The same data as handed to the contact solver (with every load case).
    pub zone: ContactZone,
    /// The history on the contact zone: every stage, step and pair state.
    pub history: HistorySolution,
    /// Full results (displacements, reactions, element forces, stresses) at the end of every
    /// stage run, in the order of `history.stages`.
    pub stage_results: Vec<Results>,
    /// Wall-clock times of condensation, solve and recovery.
    pub timings: Timings,
}
