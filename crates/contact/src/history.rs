//! Load histories with incremental (path-dependent) Coulomb friction (`history.md`).
//!
//! A history is an ordered list of stages; within a stage every load factor moves linearly with
//! the stage parameter `s ∈ [0, 1]` from the factors the previous stage ended with to the
//! stage's own. The evolution is exact: piecewise linear in `s`, every change of the working
//! scheme located by one pivot of the engine's incremental evolution
//! (`unilateral_lcp`), the accumulated slip carried from segment to segment like a
//! tangential dislocation.

use unilateral_lcp::Var;

use crate::solution::{Event, PairResult};
use crate::ContactLoad;

/// A load case by name: the link forces of the bonded structure under the case at factor 1
/// (`R_case`, `formulation.md` §2).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadCase {
    /// The case's name (`constant`, `variable`, `dead`, `push`, …).
    pub name: String,
    /// Normal and tangential link forces at factor 1.
    pub load: ContactLoad,
}

/// One stage of a history as given: its name and the factors at its end.
#[derive(Debug, Clone, PartialEq)]
pub struct Stage {
    /// The stage's name (`"stage K"` when the file gives none).
    pub name: String,
    /// The factor of every case at the end of the stage, indexed like the cases; `None` keeps
    /// the factor the case had at the start of the stage.
    pub factors: Vec<Option<f64>>,
}

/// A load history: the cases and the stages.
#[derive(Debug, Clone, PartialEq)]
pub struct History {
    /// The load cases, in the order of the file.
    pub cases: Vec<LoadCase>,
    /// The stages, in order.
    pub stages: Vec<Stage>,
}

impl History {
    /// The factors of every case at the start and the end of every stage (every case starts
    /// at 0; a case a stage does not name keeps its factor).
    pub fn factor_table(&self) -> Vec<(Vec<f64>, Vec<f64>)> {
        let mut now = vec![0.0; self.cases.len()];
        self.stages
            .iter()
            .map(|stage| {
                let start = now.clone();
                for (v, f) in now.iter_mut().zip(&stage.factors) {
                    if let Some(f) = f {
                        *v = *f;
                    }
                }
                (start, now.clone())
            })
            .collect()
    }
}

/// How a stage ended.
#[derive(Debug, Clone, PartialEq)]
pub enum StageStatus {
    /// The stage was followed to `s = 1`.
    Completed,
    /// The structure became a mechanism at `s_end < 1`: the load cannot be carried further.
    Mechanism,
    /// The rate problem has no solution or several (the path turned back, or a degenerate
    /// vertex could not be left): the reason says where and why.
    Indeterminate,
    /// The pivot cap was hit.
    IterationLimit,
    /// The engine could not continue (a numerically singular basis).
    NumericalFailure,
}

impl StageStatus {
    /// `"completed"`, `"mechanism"`, `"indeterminate"`, `"iteration_limit"`,
    /// `"numerical_failure"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            StageStatus::Completed => "completed",
            StageStatus::Mechanism => "mechanism",
            StageStatus::Indeterminate => "indeterminate",
            StageStatus::IterationLimit => "iteration_limit",
            StageStatus::NumericalFailure => "numerical_failure",
        }
    }
}

/// One change of the working scheme inside a stage.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryStep {
    /// 1-based step number within the stage.
    pub step: usize,
    /// The stage parameter at the change, `0 ≤ s ≤ 1`.
    pub s: f64,
    /// The factor of every case there.
    pub factors: Vec<f64>,
    /// The engine's entering variable (`Var::Driver` is the stage parameter).
    pub entering: Var,
    /// The engine's leaving variable.
    pub leaving: Var,
    /// Label of the entering variable (`z_n1`, `x_t2+`, `s`, …).
    pub entering_label: String,
    /// Label of the leaving variable.
    pub leaving_label: String,
    /// What changed at which pair.
    pub events: Vec<Event>,
    /// Every pair's forces, mutual displacements (`z_t` the accumulated slip) and state at the
    /// change (the state is the one of the segment that starts here).
    pub pairs: Vec<PairResult>,
}

/// Residuals of a stage's final state, each relative to the data's scale.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HistoryResidual {
    /// `‖x − q(φ) − R z‖∞` over the normal and tangential link forces, from the original data.
    pub equation: f64,
    /// Largest `|x_n·z_n|` and `|x_t±·(slip rate)|` of the final state.
    pub complementarity: f64,
    /// Largest violation of `x_n ≥ 0`, `z_n ≥ 0`, `|x_t| ≤ f·x_n`.
    pub feasibility: f64,
    /// Largest violation of `x_t·Δz_t ≤ 0` over the stage's segments.
    pub dissipation: f64,
}

impl HistoryResidual {
    /// The largest of the four.
    pub fn max(&self) -> f64 {
        self.equation
            .max(self.complementarity)
            .max(self.feasibility)
            .max(self.dissipation)
    }
}

/// The answer of one stage.
#[derive(Debug, Clone, PartialEq)]
pub struct StageSolution {
    /// 1-based stage number.
    pub stage: usize,
    /// The stage's name.
    pub name: String,
    /// The factors at the start of the stage.
    pub factors_start: Vec<f64>,
    /// The factors at its end as given.
    pub factors_end: Vec<f64>,
    /// How it ended.
    pub status: StageStatus,
    /// The stage parameter reached (1 when completed).
    pub s_end: f64,
    /// Every change of the working scheme inside the stage.
    pub steps: Vec<HistoryStep>,
    /// The pairs at `s_end`.
    pub pairs: Vec<PairResult>,
    /// Verified residuals of the state at `s_end` and the dissipation over the stage.
    pub residual: HistoryResidual,
    /// For a mechanism: the direction of the mutual displacements (`z_n`, `z_t` per pair,
    /// largest entry 1).
    pub mechanism: Option<Vec<(f64, f64)>>,
    /// For `indeterminate` (and failures): where and why.
    pub reason: Option<String>,
}

/// The answer of a whole history.
#[derive(Debug, Clone, PartialEq)]
pub struct HistorySolution {
    /// The names of the load cases.
    pub cases: Vec<String>,
    /// The pair names.
    pub names: Vec<String>,
    /// The stages run (the history stops at the first stage that is not completed).
    pub stages: Vec<StageSolution>,
}

impl HistorySolution {
    /// The status of the last stage run.
    pub fn status(&self) -> &StageStatus {
        self.stages
            .last()
            .map_or(&StageStatus::Completed, |s| &s.status)
    }

    /// The final state: the pairs at the end of the last stage run.
    pub fn final_pairs(&self) -> &[PairResult] {
        self.stages.last().map_or(&[], |s| &s.pairs)
    }

    /// The factors of every case at the final state.
    pub fn final_factors(&self) -> Vec<f64> {
        match self.stages.last() {
            Some(s) => s
                .factors_start
                .iter()
                .zip(&s.factors_end)
                .map(|(a, b)| a + s.s_end * (b - a))
                .collect(),
            None => vec![0.0; self.cases.len()],
        }
    }
}
