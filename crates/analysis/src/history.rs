//! Load histories of structural models: the history followed on the condensed contact zone,
//! and the full structural results at the end of every stage and at any point of the history
//! (`history.md`).

use std::time::Instant;

use unilateral_contact::{
    follow_history_judged, ContactZone, History, HistorySolution, PairResult, Stage,
};
use unilateral_fem::{Condensed, Model, Results};

use crate::{condensed_zone, contact_error, recover_at, AnalysisError, Place, Timings};

/// A finished history analysis of a structural model.
#[derive(Debug)]
pub struct HistoryAnalysis {
    /// The condensation of the model and the means of recovery; its contact stiffness blocks
    /// are in [`HistoryAnalysis::zone`] (moved there, `0 × 0` here).
    pub condensed: Condensed,
    /// The same data as handed to the contact solver (with every load case).
    pub zone: ContactZone,
    /// The history on the contact zone: every stage, step and pair state.
    pub history: HistorySolution,
    /// Full results (displacements, reactions, element forces, stresses) at the end of every
    /// stage run, in the order of `history.stages`; none for a last stage that ended in a
    /// numerical failure (its end is no state of the structure).
    pub stage_results: Vec<Results>,
    /// Wall-clock times of condensation, solve and recovery.
    pub timings: Timings,
}

/// Condenses the model once and follows the load history `stages` (factors indexed like the
/// model's load cases, [`Model::cases`]) on its contact zone with incremental friction; then
/// recovers the full results at the end of every stage run, each checked for equilibrium.
pub fn analyze_history(
    model: &Model,
    stages: &[Stage],
    settings: &unilateral_lcp::Settings,
) -> Result<HistoryAnalysis, AnalysisError> {
    settings.progress.phase(unilateral_lcp::Phase::Condensing);
    let (condensed, zone, condense) = condensed_zone(model)?;
    let started = Instant::now();
    let history = History {
        cases: zone.cases.clone(),
        stages: stages.to_vec(),
    };
    // The structure's own blocks judge the load rates the condensed data cannot tell from
    // round-off.
    let sparse = crate::sparse_zone_of(model).ok();
    let solution =
        follow_history_judged(&zone, &history, sparse.as_ref(), settings).map_err(contact_error)?;
    drop(sparse);
    let solve = started.elapsed();
    settings.progress.phase(unilateral_lcp::Phase::Recovering);
    let started = Instant::now();
    let mut stage_results = Vec::with_capacity(solution.stages.len());
    for st in &solution.stages {
        // A stage the engine failed in (a singular basis, or an end state that fails its
        // check), or whose state is beyond double precision, has no state to recover: its results are left out (they were recovered and
        // read "out of balance", hiding the stage's own reason) and the history ends there.
        if !st.status.has_states() {
            break;
        }
        let factors: Vec<f64> = st
            .factors_start
            .iter()
            .zip(&st.factors_end)
            .map(|(a, b)| a + st.s_end * (b - a))
            .collect();
        let at = Place::Stage {
            stage: st.stage,
            s: st.s_end,
        };
        stage_results.push(recover_at(&condensed, &factors, at, &st.pairs)?);
    }
    let recover = started.elapsed();
    Ok(HistoryAnalysis {
        condensed,
        zone,
        history: solution,
        stage_results,
        timings: Timings {
            condense: Some(condense),
            solve: Some(solve),
            recover: Some(recover),
            ..Timings::default()
        },
    })
}

impl HistoryAnalysis {
    /// The pair results and full structural results at stage parameter `s` of stage `stage`
    /// (1-based): any point of the history, interpolated linearly between the breakpoints that
    /// enclose it (the evolution is linear between them), then recovered and checked.
    pub fn results_at(
        &self,
        stage: usize,
        s: f64,
    ) -> Result<(Vec<PairResult>, Results), AnalysisError> {
        let not_on = || AnalysisError::NotOnPath {
            p: s,
            end: format!(
                "stage {} at s = {}",
                self.history.stages.len(),
                self.history.stages.last().map_or(0.0, |st| st.s_end)
            ),
        };
        let st = stage
            .checked_sub(1)
            .and_then(|k| self.history.stages.get(k))
            .ok_or_else(not_on)?;
        if !(0.0..=st.s_end).contains(&s) {
            return Err(not_on());
        }
        // Breakpoints of the stage: its start (the end of the previous stage, or unloaded),
        // every step, its end.
        let start: Vec<PairResult> = match stage.checked_sub(2) {
            Some(k) => self.history.stages[k].pairs.clone(),
            None => self
                .zone
                .pair_names
                .iter()
                .zip(&self.zone.gap)
                .map(|(name, &g)| PairResult {
                    name: name.clone(),
                    x_n: 0.0,
                    x_t: 0.0,
                    z_n: g,
                    z_t: 0.0,
                    state: if g > 0.0 {
                        unilateral_contact::PairState::Open
                    } else {
                        unilateral_contact::PairState::Stick
                    },
                })
                .collect(),
        };
        let mut points: Vec<(f64, &[PairResult])> = vec![(0.0, &start)];
        points.extend(st.steps.iter().map(|p| (p.s, p.pairs.as_slice())));
        points.push((st.s_end, &st.pairs));
        let j = points
            .windows(2)
            .position(|w| w[0].0 <= s && s <= w[1].0)
            .ok_or_else(not_on)?;
        let ((s0, a), (s1, b)) = (points[j], points[j + 1]);
        let w = if s1 > s0 { (s - s0) / (s1 - s0) } else { 1.0 };
        let lerp = |u: f64, v: f64| u + w * (v - u);
        let pairs: Vec<PairResult> = a
            .iter()
            .zip(b)
            .map(|(p, q)| PairResult {
                name: p.name.clone(),
                x_n: lerp(p.x_n, q.x_n),
                x_t: lerp(p.x_t, q.x_t),
                z_n: lerp(p.z_n, q.z_n),
                z_t: lerp(p.z_t, q.z_t),
                // The state of the segment (the one that starts at its first breakpoint).
                state: p.state,
            })
            .collect();
        let factors: Vec<f64> = st
            .factors_start
            .iter()
            .zip(&st.factors_end)
            .map(|(a, b)| a + s * (b - a))
            .collect();
        let r = recover_at(&self.condensed, &factors, Place::Stage { stage, s }, &pairs)?;
        Ok((pairs, r))
    }
}
