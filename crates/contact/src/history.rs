//! Load histories with incremental (path-dependent) Coulomb friction (`history.md`).
//!
//! A history is an ordered list of stages; within a stage every load factor moves linearly with
//! the stage parameter `s ∈ [0, 1]` from the factors the previous stage ended with to the
//! stage's own. The evolution is exact: piecewise linear in `s`, every change of the working
//! scheme located by one pivot of the engine's incremental evolution
//! (`unilateral_lcp`), the accumulated slip carried from segment to segment like a
//! tangential dislocation.

use unilateral_lcp::{
    EvolutionProblem, EvolutionSolver, EvolutionState, StageEnding, StageRun, Var,
};

use crate::lcp::ContactLcp;
use crate::solution::{Event, EventKind, PairResult, PairState};
use crate::solve::events_of;
use crate::units::Units;
use crate::{ContactError, ContactLoad, ContactZone, SparseZone};

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
    /// The state reached (where the trace failed, or whose check failed) is beyond what
    /// double precision resolves: the forces its slips and gaps make term by term are so much
    /// larger than the loads that their round-off alone exceeds the check's tolerance
    /// ([`VERIFIED`]) — a block held by a spring a billionth of its stiffness, sliding
    /// kilometres. The data's conditioning, not the program's fault: the reason gives the
    /// sizes.
    Unresolved,
}

impl StageStatus {
    /// `"completed"`, `"mechanism"`, `"indeterminate"`, `"iteration_limit"`,
    /// `"numerical_failure"`, `"unresolved"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            StageStatus::Completed => "completed",
            StageStatus::Mechanism => "mechanism",
            StageStatus::Indeterminate => "indeterminate",
            StageStatus::IterationLimit => "iteration_limit",
            StageStatus::NumericalFailure => "numerical_failure",
            StageStatus::Unresolved => "unresolved",
        }
    }

    /// Whether the stage's states — its end and the changes inside it — are states of the
    /// structure: every status but a failure of the engine (`numerical_failure`) or a state
    /// beyond double precision (`unresolved`), whose end is where the trace stopped, for
    /// diagnosis, not an answer.
    pub fn has_states(&self) -> bool {
        !matches!(
            self,
            StageStatus::NumericalFailure | StageStatus::Unresolved
        )
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
    /// What the reader of the answer should know about it (for instance pairs whose friction
    /// and normal–tangential coupling can make the evolution non-unique).
    pub notes: Vec<String>,
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

/// The largest relative residual of a stage's final state that counts as verified.
pub const VERIFIED: f64 = 1e-8;

/// The round-off a force carries of the terms that form it (64 ε, as the structure's balance
/// allows for the links' dislocations).
const ROUNDOFF_TERMS: f64 = 64.0 * f64::EPSILON;

/// Follows a load history on a contact zone with incremental Coulomb friction (`history.md`).
///
/// The zone's matrices, friction and gaps are used; its `constant`/`variable` loads are not
/// (the loads are the history's cases). The structure starts unloaded, every pair at its gap
/// with zero slip. Each stage is followed by parametric pivoting from the state where the
/// previous one ended ([`unilateral_lcp::EvolutionSolver`]); the history stops at the first stage
/// that cannot be completed. Every stage's final state is verified from the original data
/// ([`HistoryResidual`]).
///
/// ```
/// use faer::mat;
/// use unilateral_contact::{
///     follow_history, ContactLoad, ContactZone, History, LoadCase, PairState, Stage,
/// };
///
/// // One pair on rigid ground: normal stiffness 10, tangential 2, friction 0.5; a constant
/// // compression N = 1 and a tangential force T that goes to 1 (beyond f·N = 0.5) and back to 0.
/// let mut zone = ContactZone::new(mat![[10.0]], mat![[2.0]]);
/// zone.friction = vec![0.5];
/// let case = |n: f64, t: f64, name: &str| LoadCase {
///     name: name.into(),
///     load: ContactLoad { normal: vec![n], tangential: vec![t] },
/// };
/// let history = History {
///     cases: vec![case(1.0, 0.0, "dead"), case(0.0, 1.0, "push")],
///     stages: vec![
///         Stage { name: "dead".into(), factors: vec![Some(1.0), None] },
///         Stage { name: "push".into(), factors: vec![None, Some(1.0)] },
///         Stage { name: "release".into(), factors: vec![None, Some(0.0)] },
///     ],
/// };
/// let h = follow_history(&zone, &history, &Default::default()).unwrap();
/// // By hand: pushed to T = 1 the pair slides (x_t = +f·N = 0.5, z_t = −(T − f·N)/k_t = −0.25);
/// let push = &h.stages[1].pairs[0];
/// assert_eq!(push.state, PairState::SlipMinus);
/// assert!((push.x_t - 0.5).abs() < 1e-12 && (push.z_t + 0.25).abs() < 1e-12);
/// // released, it sticks with its slip kept: x_t = k_t·z_t = −0.5, still within f·N.
/// let released = &h.stages[2].pairs[0];
/// assert_eq!(released.state, PairState::Stick);
/// assert!((released.z_t + 0.25).abs() < 1e-12 && (released.x_t + 0.5).abs() < 1e-12);
/// ```
pub fn follow_history(
    zone: &ContactZone,
    history: &History,
    settings: &unilateral_lcp::Settings,
) -> Result<HistorySolution, ContactError> {
    follow_history_judged(zone, history, None, settings)
}

/// [`follow_history`] with the structure's sparse blocks at hand (`sparse`: the same zone as
/// the bonded structure's blocks, its [`SparseZone::cases`] indexed like the history's): each
/// stage's load rates that the condensed data cannot tell from round-off are judged on the
/// structure's own equations with the stage's load increment
/// ([`unilateral_lcp::EvolutionSolver::stage_judged`]) — a beam sliding on its bearings at
/// constant load is a mechanism there.
pub fn follow_history_judged(
    zone: &ContactZone,
    history: &History,
    sparse: Option<&SparseZone>,
    settings: &unilateral_lcp::Settings,
) -> Result<HistorySolution, ContactError> {
    zone.validate()?;
    let m = zone.pairs();
    for case in &history.cases {
        for (what, v) in [
            ("normal", &case.load.normal),
            ("tangential", &case.load.tangential),
        ] {
            if v.len() != m {
                return Err(ContactError::VectorSize {
                    name: format!("load.{}.{what}", case.name),
                    len: v.len(),
                    pairs: m,
                });
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(ContactError::NotFinite {
                    name: format!("load.{}.{what}", case.name),
                    index: format!("[{}]", i + 1),
                });
            }
        }
    }
    let table = history.factor_table();
    // Units from the loads the history applies: a zone whose variable load holds, pair by
    // pair, the largest load of any stage's end (the loads are linear in the factors along a
    // stage). Not from the cases at factor 1: a case that no stage uses, or one given in
    // other units with small factors, would set a force scale that the loads met never reach,
    // and the states would be read against it (a pressed pair read "open").
    let mut probe = zone.clone();
    probe.constant = ContactLoad::zeros(m);
    probe.variable = ContactLoad::zeros(m);
    for (k, (start, end)) in table.iter().enumerate() {
        for phi in [start, end] {
            for i in 0..m {
                let (mut n, mut t) = (0.0, 0.0);
                for (case, &f) in history.cases.iter().zip(phi) {
                    if f != 0.0 {
                        n += f * case.load.normal[i];
                        t += f * case.load.tangential[i];
                    }
                }
                if !(n.is_finite() && t.is_finite()) {
                    let (number, name) = (format!("stage {}", k + 1), &history.stages[k].name);
                    let stage = if *name == number {
                        number
                    } else {
                        format!("{number} (`{name}`)")
                    };
                    return Err(ContactError::OutOfRange(format!(
                        "{stage}: its factors times the loads of the cases exceed the \
                         floating-point range at pair `{}`; choose other units or factors",
                        zone.pair_names.get(i).map_or("?", |s| s.as_str())
                    )));
                }
                if n.abs() > probe.variable.normal[i].abs() {
                    probe.variable.normal[i] = n;
                }
                if t.abs() > probe.variable.tangential[i].abs() {
                    probe.variable.tangential[i] = t;
                }
            }
        }
    }
    let units = Units::of(&probe, 0.0);
    let mut normalised = units.normalise(&probe);
    normalised.variable = ContactLoad::zeros(m);
    let lcp = ContactLcp::build(&normalised);
    let f = &zone.friction;
    let stack = |l: &ContactLoad| -> Vec<f64> {
        let rn: Vec<f64> = l
            .normal
            .iter()
            .map(|&v| units.normalised_force(v))
            .collect();
        let rt: Vec<f64> = l
            .tangential
            .iter()
            .map(|&v| units.normalised_force(v))
            .collect();
        let mut v = rn.clone();
        v.extend((0..m).map(|i| f[i] * rn[i] + rt[i]));
        v.extend((0..m).map(|i| f[i] * rn[i] - rt[i]));
        v
    };
    let case_d: Vec<Vec<f64>> = history.cases.iter().map(|c| stack(&c.load)).collect();
    let n = 3 * m;
    if lcp
        .problem
        .m
        .col_iter()
        .any(|c| c.iter().any(|v| !v.is_finite()))
        || case_d.iter().flatten().any(|v| !v.is_finite())
    {
        return Err(ContactError::OutOfRange(
            "friction times the contact stiffness or the loads exceeds the floating-point range"
                .into(),
        ));
    }
    let engine = unilateral_lcp::Settings {
        lexicographic_order: Some(lcp.lexicographic_order.clone()),
        covering: Some(lcp.tightening_direction.clone()),
        row_relations: lcp.row_relations(),
        ..settings.clone()
    };
    let solver = EvolutionSolver::new(
        EvolutionProblem {
            m: lcp.problem.m.clone(),
            q0: lcp.problem.q0.clone(),
            incremental: (0..n).map(|i| i >= m).collect(),
            guard: (0..n).map(|i| (i >= m).then_some(i % m)).collect(),
            start_direction: lcp.tightening_direction.clone(),
        },
        engine,
    )?;
    let names = zone.pair_names.clone();
    let mut out = HistorySolution {
        cases: history.cases.iter().map(|c| c.name.clone()).collect(),
        names: names.clone(),
        stages: Vec::new(),
        notes: coupling_notes(zone),
    };
    // The unloaded structure: every pair at its gap, no slip, no force (`history.md`).
    let rest: Vec<f64> = (0..n)
        .map(|i| if i < m { normalised.gap[i] } else { 0.0 })
        .collect();
    let Some(mut state) = solver.start_at_rest(&rest) else {
        return Err(ContactError::OutOfRange(
            "the unloaded structure has no state with every pair at its gap (the gaps are \
             inconsistent with the contact stiffness)"
                .into(),
        ));
    };
    // The structure's blocks in the solver's units, where they match the zone and the cases.
    // Its LCP is formed once; each stage's judge takes it with the stage's increment as the
    // load (the directions do not depend on the constant load).
    let sparse = sparse
        .filter(|sp| sp.pairs() == m && sp.cases.len() == history.cases.len())
        .map(|sp| {
            let sp = units.normalise_sparse(sp);
            let lcp = sp.lcp();
            (sp, lcp)
        });
    let scales = crate::units::load_scales(&probe);
    let reader = Reader {
        zone,
        units,
        names: &names,
        floors: pair_floors(&scales),
        part: scales.component,
    };
    for (k, (stage, (start, end))) in history.stages.iter().zip(&table).enumerate() {
        let mut d = vec![0.0; n];
        for (c, dc) in case_d.iter().enumerate() {
            let df = end[c] - start[c];
            if df != 0.0 {
                for (di, v) in d.iter_mut().zip(dc) {
                    *di += df * v;
                }
            }
        }
        // The judge of the stage: the structure with the stage's increment as its load.
        let judge = sparse.as_ref().map(|(sp, base)| {
            let mut inc = [vec![0.0; sp.kii.nrows()], vec![0.0; 2 * m]];
            for (c, loads) in sp.cases.iter().enumerate() {
                let df = end[c] - start[c];
                if df != 0.0 {
                    for (part, load) in inc.iter_mut().zip(loads) {
                        for (a, b) in part.iter_mut().zip(load) {
                            *a += df * b;
                        }
                    }
                }
            }
            let mut lcp = base.clone();
            (lcp.d0, lcp.da) = sp.load_direction(&inc);
            std::sync::Arc::new(unilateral_lcp::StructureJudge::new(lcp))
        });
        let run = solver.stage_judged(&state, &d, judge.clone());
        let factors_at = |s: f64| -> Vec<f64> {
            start
                .iter()
                .zip(end)
                .map(|(a, b)| a + s * (b - a))
                .collect()
        };
        // The pairs at a trace's end and the check of that state: a pair's state by its slip
        // over the stage's last segment, or, where the stage ends in a mechanism (whose last
        // breakpoint has no segment after it), by its rate in the mechanism's mode — the
        // bearings that slide as the structure moves.
        let assess = |run: &StageRun, relaxed: bool| -> (Vec<PairResult>, HistoryResidual) {
            let inc = &run.last_increment;
            let pairs = match &run.ending {
                StageEnding::Mechanism(mode) => {
                    let dz = &mode.dz;
                    let top = dz[m..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
                    let zmax = run.end.z.iter().fold(1.0f64, |a, b| a.max(b.abs()));
                    let rate = |v: f64| if top > 0.0 { v / top * zmax } else { 0.0 };
                    reader.pairs(&run.end.x, &run.end.z, |i| {
                        (rate(dz[m + i]), rate(dz[2 * m + i]))
                    })
                }
                _ => reader.pairs(&run.end.x, &run.end.z, |i| (inc[m + i], inc[2 * m + i])),
            };
            // Each pair's largest slip over the stage's states (user units, `z_t` as the pairs
            // report it), for the relaxed check only.
            let chain = stage_chain(&state, run);
            let mut excursion = vec![0.0f64; m];
            if relaxed {
                for (_, z) in &chain {
                    for (j, e) in excursion.iter_mut().enumerate() {
                        let slip = (z[m + j] - z[2 * m + j]) / 2.0;
                        *e = e.max(reader.units.user_displacement(slip).abs());
                    }
                }
            }
            let mut residual =
                reader.residual(&pairs, &factors_at(run.s_end), history, inc, &excursion);
            residual.dissipation = reader.dissipation(&chain);
            (pairs, residual)
        };
        let failed = |run: &StageRun, r: &HistoryResidual| {
            run.ending == StageEnding::Singular || r.max() > VERIFIED
        };
        // A completed stage whose end fails its check, whatever trace is kept: checked again
        // with its end refined once from the data (its values were moved there by hand along
        // the last column), kept where it passes. Only as a last resort: a retrace that
        // passes is kept first (a refined end that passed the check instead left six blocks
        // on soft springs of a sweep out of balance on the structure's equations).
        let settle = |mut run: StageRun,
                      pairs: Vec<PairResult>,
                      residual: HistoryResidual,
                      relaxed: bool| {
            if !(run.ending == StageEnding::Completed && failed(&run, &residual)) {
                return (run, pairs, residual);
            }
            let Some(refined) = run.refined.take() else {
                return (run, pairs, residual);
            };
            let kept = (
                std::mem::replace(&mut run.end.x, refined.x),
                std::mem::replace(&mut run.end.z, refined.z),
                std::mem::replace(&mut run.last_increment, refined.last_increment),
            );
            let (p2, r2) = assess(&run, relaxed);
            if failed(&run, &r2) {
                (run.end.x, run.end.z, run.last_increment) = kept;
                return (run, pairs, residual);
            }
            (run, p2, r2)
        };
        let select = |relaxed: bool, first: StageRun| {
            let mut run = first;
            let (mut pairs, mut residual) = assess(&run, relaxed);
            // A stage whose trace failed (a singular basis, or an end that fails its check) or
            // ended in a mechanism is traced again with the friction relations deciding every tie
            // (`EvolutionSolver::stage_related`): where a sliding pair opens, its normal force and
            // its friction part reach zero together, and the stage's own rule, on values that
            // carry the round-off of the slips it absorbed, can let the friction part leave first
            // (then the basis turns singular, or the trace reads a false mechanism, or its end
            // leaves friction on an open pair). After a failure the second trace is kept where it
            // passes the check, whatever its ending; after a mechanism only where it completes
            // the stage and passes the check: a genuine mechanism, which the second trace meets
            // too, stays as the first found it.
            // A mechanism in which nothing moves is the formulation's, not the structure's (an
            // open pair's two friction parts growing together): the trace failed.
            let null_at = moves_nothing(&run.ending, m).then_some(run.s_end);
            let first_failed = failed(&run, &residual) || null_at.is_some();
            // Where the first trace went wrong: a null mode's load, or the load of a singular
            // basis (met after a pair's opening tie was decided for its friction part).
            let wrong_at = null_at.or((run.ending == StageEnding::Singular).then_some(run.s_end));
            // What the traces after the first did, where none was kept (for the failure's reason).
            let mut retraced = Vec::new();
            if first_failed || matches!(run.ending, StageEnding::Mechanism(_)) {
                let again = solver.stage_related(&state, &d, judge.clone());
                let (p2, r2) = assess(&again, relaxed);
                let completed = again.ending == StageEnding::Completed;
                if !failed(&again, &r2)
                    && !moves_nothing(&again.ending, m)
                    && (first_failed || completed)
                {
                    (run, pairs, residual) = (again, p2, r2);
                } else if let Some(s_wrong) = wrong_at {
                    retraced.push(retrace_note(
                        "with the relations deciding every tie",
                        &again,
                        &r2,
                    ));
                    // The relations decide the ties up to where the first trace went wrong (its
                    // null mode, or its singular basis), the stage's own rule the rest (where a
                    // block tips about its toe, the second trace ran past the tipping or turned
                    // back out of balance).
                    let third =
                        solver.stage_related_until(&state, &d, judge.clone(), s_wrong + PAST_NULL);
                    let (p3, r3) = assess(&third, relaxed);
                    if !failed(&third, &r3) && !moves_nothing(&third.ending, m) {
                        (run, pairs, residual) = (third, p3, r3);
                    } else {
                        retraced.push(retrace_note("with them only up to that load", &third, &r3));
                    }
                }
            }
            let (run, pairs, residual) = settle(run, pairs, residual, relaxed);
            (run, pairs, residual, retraced)
        };
        // Where no trace passes the check, the check once more with each pair's largest slip
        // over the stage standing for round-off its forces carry (a block slid far and back:
        // its forces keep the round-off of the slide, its final slips do not). Only as a last
        // resort: the strict check decides which trace is kept wherever one passes it (the
        // relaxed one let a trace that left friction on an opening pair pass, and its later
        // stages fail).
        let (run, pairs, residual, retraced) = {
            let passes = |r: &(StageRun, Vec<PairResult>, HistoryResidual, Vec<String>)| {
                !failed(&r.0, &r.2) && !moves_nothing(&r.0.ending, m)
            };
            let strict = select(false, run.clone());
            if passes(&strict) {
                strict
            } else {
                let relaxed = select(true, run);
                if passes(&relaxed) {
                    relaxed
                } else {
                    strict
                }
            }
        };
        let chain = stage_chain(&state, &run);
        let mut open = (0..m)
            .map(|i| reader.is_open(state.x[i], state.z[i]))
            .collect::<Vec<_>>();
        let mut steps = Vec::with_capacity(run.points.len());
        for (j, p) in run.points.iter().enumerate() {
            let next = chain[j + 2].1;
            let pairs = reader.pairs(&p.x, &p.z, |i| {
                (next[m + i] - p.z[m + i], next[2 * m + i] - p.z[2 * m + i])
            });
            let mut events = events_of(p.leaving, m, &names);
            for e in &mut events {
                match e.kind {
                    EventKind::Opens => open[e.pair] = true,
                    EventKind::Closes => open[e.pair] = false,
                    _ => e.while_open = open[e.pair],
                }
            }
            events.retain(|e| !e.while_open);
            steps.push(HistoryStep {
                step: j + 1,
                s: p.s,
                factors: factors_at(p.s),
                entering: p.entering,
                leaving: p.leaving,
                entering_label: label(&lcp, p.entering),
                leaving_label: label(&lcp, p.leaving),
                events,
                pairs,
            });
        }
        let (status, reason, mechanism) = match &run.ending {
            StageEnding::Completed => (StageStatus::Completed, None, None),
            StageEnding::Mechanism(mode) => {
                let dz = &mode.dz;
                let v: Vec<(f64, f64)> = (0..m)
                    .map(|i| (dz[i], (dz[m + i] - dz[2 * m + i]) / 2.0))
                    .collect();
                let top = v
                    .iter()
                    .fold(0.0f64, |a, &(x, y)| a.max(x.abs()).max(y.abs()));
                let v = if top > 0.0 {
                    v.into_iter().map(|(x, y)| (x / top, y / top)).collect()
                } else {
                    v
                };
                (
                    StageStatus::Mechanism,
                    Some(format!(
                        "the structure becomes a mechanism at s = {} of stage {} (`{}`): the \
                         load cannot be increased further",
                        run.s_end,
                        k + 1,
                        stage.name
                    )),
                    Some(v),
                )
            }
            StageEnding::TurnsBack => (
                StageStatus::Indeterminate,
                Some(format!(
                    "at s = {} of stage {} (`{}`) the path can only go on with the load \
                     decreasing: the rate problem has no solution or several there (possible \
                     in 2D only with large friction); the evolution is not continued",
                    run.s_end,
                    k + 1,
                    stage.name
                )),
                None,
            ),
            StageEnding::IterationLimit => (
                StageStatus::IterationLimit,
                Some(format!(
                    "the pivot cap was reached at s = {} of stage {} (`{}`)",
                    run.s_end,
                    k + 1,
                    stage.name
                )),
                None,
            ),
            StageEnding::Singular => (
                StageStatus::NumericalFailure,
                Some(format!(
                    "a basis was numerically singular at s = {} of stage {} (`{}`) (the \
                     program's fault, not the model's)",
                    run.s_end,
                    k + 1,
                    stage.name
                )),
                None,
            ),
        };
        // A state that fails its own check is not an answer: the program's fault; nor is a
        // mechanism in which nothing moves.
        let (status, reason, mechanism) = if moves_nothing(&run.ending, m) {
            (
                StageStatus::NumericalFailure,
                Some(format!(
                    "at s = {} of stage {} (`{}`) the trace read a mechanism in which no pair \
                     moves (an open pair's two friction parts growing together): not an \
                     answer{}; the program's fault, not the model's",
                    run.s_end,
                    k + 1,
                    stage.name,
                    if retraced.is_empty() {
                        String::new()
                    } else {
                        format!(" (traced again {})", retraced.join("; "))
                    }
                )),
                None,
            )
        } else if residual.max() > VERIFIED && status != StageStatus::NumericalFailure {
            (
                StageStatus::NumericalFailure,
                Some(format!(
                    "the state reached at s = {} of stage {} (`{}`) fails its check (largest \
                     relative residual {:.1e} > {VERIFIED:e}): the program's fault, not the model's",
                    run.s_end,
                    k + 1,
                    stage.name,
                    residual.max()
                )),
                None,
            )
        } else {
            (status, reason, mechanism)
        };
        // A failed stage whose state the data cannot resolve: no state of it could pass the
        // check, whatever the program did — the data's conditioning, said as such. (Judged
        // for a failed stage only: `O(m²)`.)
        let beyond = (status == StageStatus::NumericalFailure)
            .then(|| unresolvable(zone, history, &pairs, &factors_at(run.s_end)))
            .flatten();
        let (status, reason) = match beyond {
            Some(u) => {
                let trace = if run.ending == StageEnding::Singular {
                    " (the trace met a numerically singular basis there)".to_string()
                } else if moves_nothing(&run.ending, m) {
                    " (the trace read a mechanism in which no pair moves there)".to_string()
                } else {
                    format!(
                        " (the state's check: largest relative residual {:.1e})",
                        residual.max()
                    )
                };
                let what = format!(
                    "the state reached at s = {} of stage {} (`{}`)",
                    run.s_end,
                    k + 1,
                    stage.name
                );
                (
                    StageStatus::Unresolved,
                    Some(format!("{}{trace}", u.sentence(&what))),
                )
            }
            None => (status, reason),
        };
        out.stages.push(StageSolution {
            stage: k + 1,
            name: stage.name.clone(),
            factors_start: start.clone(),
            factors_end: end.clone(),
            status,
            s_end: run.s_end,
            steps,
            pairs,
            residual,
            mechanism,
            reason,
        });
        state = run.end;
        if out.stages.last().map(|s| &s.status) != Some(&StageStatus::Completed) {
            break;
        }
    }
    Ok(out)
}

/// The sizes that put a state beyond double precision ([`unresolvable`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Unresolvable {
    /// The largest mutual displacement (`|z_n|`, `|z_t|`, a gap) of the state.
    pub displacement: f64,
    /// The largest sum of the terms `|R_ij·z_j|` (and `|R_nn,ij·η_j|`) forming a pair's force.
    pub terms: f64,
    /// The largest load term of a pair's force at the state's load.
    pub loads: f64,
    /// [`ROUNDOFF_TERMS`] times `terms` over `loads`.
    pub ratio: f64,
    /// Whether the zone has gaps.
    pub gaps: bool,
}

impl Unresolvable {
    /// "… cannot be resolved in double precision: its slips (largest …) make forces of …
    /// term by term, … times the loads (…), whose round-off alone is … of them …; give
    /// supports that keep the slips short …", after `what` (the state named).
    pub(crate) fn sentence(&self, what: &str) -> String {
        format!(
            "{what} cannot be resolved in double precision: its {} (largest {:.3e}) make forces \
             of {:.3e} term by term, {:.1e} times the loads ({:.3e}), whose round-off alone is \
             {:.1e} of them (a state is verified within {VERIFIED:e}); give {}supports that keep \
             the slips short (a spring a billionth of the structure's stiffness lets it slide \
             metres)",
            if self.gaps { "gaps and slips" } else { "slips" },
            self.displacement,
            self.terms,
            self.terms / self.loads,
            self.loads,
            self.ratio,
            if self.gaps {
                "larger loads against the gaps, smaller gaps, or "
            } else {
                ""
            },
        )
    }
}

/// Where the round-off of the terms that form the state's forces (64 ε of their sums: the
/// slips and gaps times the links' stiffness) exceeds [`VERIFIED`] of `loads`, the largest
/// load term on a pair, no state there can be verified: the sizes, else `None` (and `None`
/// where the loads are all zero, which nothing scales).
pub(crate) fn unresolvable_state(
    zone: &ContactZone,
    pairs: &[PairResult],
    loads: f64,
) -> Option<Unresolvable> {
    let m = pairs.len();
    if m != zone.pairs() {
        return None;
    }
    let mut terms = 0.0f64;
    for i in 0..m {
        for (a, b) in [(&zone.rnn, &zone.rnt), (&zone.rtn, &zone.rtt)] {
            let sum: f64 = (0..m)
                .map(|j| {
                    (a[(i, j)] * pairs[j].z_n).abs()
                        + (a[(i, j)] * zone.gap[j]).abs()
                        + (b[(i, j)] * pairs[j].z_t).abs()
                })
                .sum();
            terms = terms.max(sum);
        }
    }
    let displacement = pairs.iter().zip(&zone.gap).fold(0.0f64, |a, (p, g)| {
        a.max(p.z_n.abs()).max(p.z_t.abs()).max(g.abs())
    });
    let ratio = ROUNDOFF_TERMS * terms / loads;
    (loads > 0.0 && ratio.is_finite() && ratio > VERIFIED).then_some(Unresolvable {
        displacement,
        terms,
        loads,
        ratio,
        gaps: zone.gap.iter().any(|&g| g != 0.0),
    })
}

/// [`unresolvable_state`] of a history's state at the factors `phi` of its cases.
fn unresolvable(
    zone: &ContactZone,
    history: &History,
    pairs: &[PairResult],
    phi: &[f64],
) -> Option<Unresolvable> {
    let mut loads = 0.0f64;
    for (c, case) in history.cases.iter().enumerate() {
        let f = phi.get(c).copied().unwrap_or(0.0);
        for v in case.load.normal.iter().chain(&case.load.tangential) {
            loads = loads.max((f * v).abs());
        }
    }
    unresolvable_state(zone, pairs, loads)
}

/// Whether a stage's ending is a mechanism whose mode moves no pair: every normal rate `dz_n`
/// and every net slip rate `dz_t+ − dz_t−` below [`NULL_MODE`] of the mode's largest rate.
/// The structure's motion is a linear function of those rates, so such a mode moves nothing:
/// it is the split of an open pair's friction into two parts, which can grow together
/// without any force or motion changing (both `x_t±` are zero where `x_n` is), not a
/// mechanism of the structure.
fn moves_nothing(ending: &StageEnding, m: usize) -> bool {
    let StageEnding::Mechanism(mode) = ending else {
        return false;
    };
    let dz = &mode.dz;
    if dz.len() != 3 * m {
        return false;
    }
    let top = dz.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let moved = (0..m).fold(0.0f64, |a, i| {
        a.max(dz[i].abs()).max((dz[m + i] - dz[2 * m + i]).abs())
    });
    moved <= NULL_MODE * top
}

/// How far past the load of a first trace's null mode (in the stage's `s`) the third trace
/// keeps the relations deciding its ties: past the round-off of the load where the traces
/// meet the same tie (1e-9 of the stage seen), short of what follows it.
const PAST_NULL: f64 = 1e-6;

/// What a trace after a stage's first did, for the reason of a stage none of them answered.
fn retrace_note(how: &str, run: &StageRun, r: &HistoryResidual) -> String {
    let ending = match run.ending {
        StageEnding::Completed => "completed the stage",
        StageEnding::Mechanism(_) => "ended in a mechanism",
        StageEnding::TurnsBack => "turned back",
        StageEnding::IterationLimit => "reached the pivot cap",
        StageEnding::Singular => "met a singular basis",
    };
    format!(
        "{how}: {ending} at s = {}, largest relative residual {:.1e}",
        run.s_end,
        r.max()
    )
}

/// The share of a mechanism mode's largest rate below which its pairs' motion is taken as
/// none ([`moves_nothing`]): far above the round-off of a mode normalised to 1 (1e-9 seen where
/// only the friction split grows), far below the motion of a genuine mechanism (of order 1).
const NULL_MODE: f64 = 1e-6;

/// Pairs whose own friction times normal–tangential coupling reaches their tangential
/// stiffness, `f·max(|R_nt|, |R_tn|) ≥ R_tt` on the diagonal. For one pair that is where a
/// slipping branch softens (`x_t ∓ f·x_n` falls as the slip grows), and sticking, slipping and
/// opening can all follow the same load increment (Klarbring's non-uniqueness of 2D friction).
/// The path then follows one of them without being able to tell: the note says so. The check
/// is per pair; it does not prove uniqueness for the others.
fn coupling_notes(zone: &ContactZone) -> Vec<String> {
    let m = zone.pairs();
    let risky: Vec<&str> = (0..m)
        .filter(|&i| {
            let c = zone.rnt[(i, i)].abs().max(zone.rtn[(i, i)].abs());
            zone.friction[i] * c >= zone.rtt[(i, i)] && c > 0.0
        })
        .map(|i| zone.pair_names[i].as_str())
        .collect();
    if risky.is_empty() {
        return Vec::new();
    }
    let shown: Vec<&str> = risky.iter().take(8).copied().collect();
    vec![format!(
        "the evolution may not be unique at pair{} {}{}: friction times the normal–tangential \
         coupling reaches the tangential stiffness (f·|R_nt| ≥ R_tt), where sticking, slipping \
         and opening can all follow one load increment; the path followed one of them — check \
         with a smaller friction",
        if risky.len() == 1 { "" } else { "s" },
        shown.join(", "),
        if risky.len() > shown.len() {
            ", …"
        } else {
            ""
        }
    )]
}

/// Reads normalised states as pair results in the user's units and checks them.
struct Reader<'a> {
    zone: &'a ContactZone,
    units: Units,
    names: &'a [String],
    /// The part of the zone each pair belongs to ([`crate::units::components`]).
    part: Vec<usize>,
    /// The floors of each pair's force scales ([`pair_floors`]).
    floors: Vec<(f64, f64)>,
}

/// The floors of each pair's force scales in [`Reader::pairs`], `(normal, tangential)`: the
/// load path's scales of a pair's forces ([`crate::units::DataForce::forces_at`]) for the loads
/// the stages apply (the variable load of the zone the units are made from, at `p = 1`), over
/// the zone's largest load (the normalised units make that about 1). Another pair's loads are
/// no scale of its forces: a frictionless pair pushed sideways by 1e12 slides, and the 400 N
/// that press it are no round-off of that.
fn pair_floors(scales: &crate::units::DataForce) -> Vec<(f64, f64)> {
    let all = scales.at(1.0);
    if !(all > 0.0 && all.is_finite()) {
        return vec![(1.0, 1.0); scales.pairs.len()];
    }
    scales
        .forces_at(1.0)
        .iter()
        .map(|&(n, t)| (n / all, t / all))
        .collect()
}

impl Reader<'_> {
    fn is_open(&self, x_n: f64, z_n: f64) -> bool {
        z_n > 1e-9 || x_n <= 1e-12
    }

    /// Pair results from normalised `x`, `z`; `rate(i)` is the increment `(Δz_t+, Δz_t-)` of
    /// pair `i` on the segment that follows (which decides slip against stick).
    fn pairs(&self, x: &[f64], z: &[f64], rate: impl Fn(usize) -> (f64, f64)) -> Vec<PairResult> {
        let m = self.names.len();
        // The largest force and displacement of each part of the zone; a pair's forces are
        // judged against its part's and its own loads ([`pair_floors`]), its displacements
        // against its part's and the zone's floor (as the load path's states, `solution.rs`).
        let rows = |v: &[f64], i: usize| v[i].abs().max(v[m + i].abs()).max(v[2 * m + i].abs());
        let xmax = crate::units::largest_by_part(&self.part, 0.0, |i| rows(x, i));
        let zmax = crate::units::largest_by_part(&self.part, 1.0, |i| rows(z, i));
        let u = &self.units;
        (0..m)
            .map(|i| {
                let (c, (fn_, ft)) = (self.part[i], self.floors[i]);
                let (tx, txt) = (1e-9 * xmax[c].max(fn_), 1e-9 * xmax[c].max(ft));
                let tz = 1e-9 * zmax[c];
                let x_n = x[i];
                let x_t = (x[m + i] - x[2 * m + i]) / 2.0;
                let (dp, dm) = rate(i);
                let state = if z[i] > tz || x_n <= tx {
                    PairState::Open
                } else if dp > tz && dp > dm {
                    PairState::SlipPlus
                } else if dm > tz {
                    PairState::SlipMinus
                } else {
                    PairState::Stick
                };
                // Round-off of an open pair's friction rows is no force, nor a tangential force
                // where `f·x_n` is zero: the friction law allows none there
                // (`pair_results_scaled` in `solution.rs`).
                let zero = self.zone.friction[i] * x_n == 0.0;
                let x_t = if zero || (state == PairState::Open && x_t.abs() <= txt) {
                    0.0
                } else {
                    x_t
                };
                PairResult {
                    name: self.names[i].clone(),
                    x_n: u.user_force(x_n),
                    x_t: u.user_force(x_t),
                    z_n: u.user_displacement(z[i]),
                    z_t: u.user_displacement((z[m + i] - z[2 * m + i]) / 2.0),
                    state,
                }
            })
            .collect()
    }

    /// Equation, complementarity and feasibility of a final state, from the original data in
    /// the user's units; `inc` the normalised slip increments of the last segment; `excursion`
    /// each pair's largest slip over the stage (user units), whose round-off the forces carry
    /// (zeros for the strict check).
    fn residual(
        &self,
        pairs: &[PairResult],
        phi: &[f64],
        history: &History,
        inc: &[f64],
        excursion: &[f64],
    ) -> HistoryResidual {
        let zone = self.zone;
        let m = pairs.len();
        let xs: f64 = pairs.iter().fold(f64::MIN_POSITIVE, |a, p| {
            a.max(p.x_n.abs()).max(p.x_t.abs())
        });
        // The mutual displacements' scale: the state's, or the last segment's slips where
        // those are larger (a block slid back to where it started: its state's slips are the
        // round-off of the centimetres it slid, the scale of their errors).
        let zi = &self.units;
        let zs: f64 = pairs.iter().fold(f64::MIN_POSITIVE, |a, p| {
            a.max(p.z_n.abs()).max(p.z_t.abs())
        });
        let zs = inc
            .iter()
            .skip(m)
            .fold(zs, |a, &d| a.max(zi.user_displacement(d).abs()));
        let mut equation = 0.0f64;
        // The sums of the terms that form each pair's normal and tangential force: a sign
        // condition is judged against their round-off too (below): an open pair's tangential
        // force is the round-off of metres of slip times the links' stiffness (5.8e-5 N from
        // terms of 7e11 N on a block sliding on a soft spring), no violation.
        let mut terms = vec![[0.0f64; 2]; m];
        for i in 0..m {
            for (normal, x) in [(true, pairs[i].x_n), (false, pairs[i].x_t)] {
                let (a, b) = if normal {
                    (&zone.rnn, &zone.rnt)
                } else {
                    (&zone.rtn, &zone.rtt)
                };
                let mut size = x.abs();
                let mut sum = x.abs();
                let mut r = x;
                for (c, case) in history.cases.iter().enumerate() {
                    let v = phi[c]
                        * if normal {
                            case.load.normal[i]
                        } else {
                            case.load.tangential[i]
                        };
                    r -= v;
                    size = size.max(v.abs());
                    sum += v.abs();
                }
                for j in 0..m {
                    let t1 = a[(i, j)] * (pairs[j].z_n - zone.gap[j]);
                    let t2 = b[(i, j)] * pairs[j].z_t;
                    r -= t1 + t2;
                    let (tn, tg) = (
                        (a[(i, j)] * pairs[j].z_n).abs(),
                        (a[(i, j)] * zone.gap[j]).abs(),
                    );
                    size = size.max(tn).max(tg).max(t2.abs());
                    sum += tn + tg + t2.abs();
                }
                // The round-off the slips met over the stage left in the force (its terms at
                // their largest), none where `excursion` is zero.
                let slid: f64 = (0..m).map(|j| (b[(i, j)] * excursion[j]).abs()).sum();
                sum += slid;
                terms[i][usize::from(!normal)] = sum;
                // The tangential force is formed from the friction parts `x_t± = f·x_n ± x_t`
                // (`(x_t+ − x_t-)/2`), which carry f times the normal row's terms: its
                // round-off is theirs too (64 ε, as the signs are judged below). An open pair
                // on a stiff mount keeps its gap's term `R_nn·η` (1e7 N for 1 mm on 1e10 N/m)
                // in both parts; with its tangential load back at zero nothing else is in its
                // row, and the residual of 4.5e-10 N read 1.0 against itself.
                let parts = if normal {
                    0.0
                } else {
                    zone.friction[i] * terms[i][0] + sum
                };
                let scale = size
                    .max(xs)
                    .max(ROUNDOFF_TERMS * slid / VERIFIED)
                    .max(ROUNDOFF_TERMS * parts / VERIFIED);
                equation = equation.max(r.abs() / scale);
            }
        }
        let mut complementarity = 0.0f64;
        let mut feasibility = 0.0f64;
        for (i, p) in pairs.iter().enumerate() {
            let f = zone.friction[i];
            // Each force against the largest force, or where the terms that form it (`terms`,
            // above) are larger, against their round-off (64 ε of them, as the structure's
            // balance is judged): the check's tolerance is then met by what those terms leave.
            // An open pair's tangential force of 6e-5 N from terms of 7e11 N passes; a heel
            // pulling 3.5 N from terms of 1e12 N (a missed opening) does not.
            let [tn, tt] = terms[i];
            let scale = |t: f64| xs.max(ROUNDOFF_TERMS * t / VERIFIED);
            let (t_n, t_parts) = (scale(tn), scale(f * tn + tt));
            complementarity = complementarity.max((p.x_n * p.z_n).abs() / (t_n * zs));
            let (xp, xm) = (f * p.x_n + p.x_t, f * p.x_n - p.x_t);
            let (dp, dm) = (
                zi.user_displacement(inc[m + i]),
                zi.user_displacement(inc[2 * m + i]),
            );
            complementarity = complementarity
                .max((xp * dp).abs() / (t_parts * zs))
                .max((xm * dm).abs() / (t_parts * zs));
            feasibility = feasibility
                .max(-p.x_n / t_n)
                .max(-p.z_n / zs)
                .max(-xp / t_parts)
                .max(-xm / t_parts);
        }
        HistoryResidual {
            equation,
            complementarity,
            feasibility: feasibility.max(0.0),
            dissipation: 0.0,
        }
    }

    /// The largest violation of `x_t·Δz_t ≤ 0` over consecutive normalised states, relative to
    /// the largest force times the largest mutual displacement of the stage (the scale of the
    /// work the data can do: a round-off increment of a large slip is no violation).
    fn dissipation(&self, chain: &[(&[f64], &[f64])]) -> f64 {
        let m = self.names.len();
        let xs = chain
            .iter()
            .flat_map(|(x, _)| x.iter())
            .fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
        let zs = chain
            .iter()
            .flat_map(|(_, z)| z.iter())
            .fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
        let mut worst = 0.0f64;
        let mut products = Vec::new();
        for w in chain.windows(2) {
            let ((xa, za), (xb, zb)) = (w[0], w[1]);
            for i in 0..m {
                let dz = ((zb[m + i] - zb[2 * m + i]) - (za[m + i] - za[2 * m + i])) / 2.0;
                let xt_a = (xa[m + i] - xa[2 * m + i]) / 2.0;
                let xt_b = (xb[m + i] - xb[2 * m + i]) / 2.0;
                products.push((xt_a * dz).max(xt_b * dz));
            }
        }
        for p in products {
            worst = worst.max(p / (xs * zs));
        }
        worst.max(0.0)
    }
}

/// The states along a stage's trace from `start`: the start, every pivot, the end (normalised
/// `x`, `z`).
fn stage_chain<'a>(start: &'a EvolutionState, run: &'a StageRun) -> Vec<(&'a [f64], &'a [f64])> {
    let mut chain: Vec<(&[f64], &[f64])> = vec![(&start.x, &start.z)];
    chain.extend(run.points.iter().map(|p| (p.x.as_slice(), p.z.as_slice())));
    chain.push((&run.end.x, &run.end.z));
    chain
}

/// The label of an engine variable in a history: the paper's names, `s` for the stage parameter.
fn label(lcp: &ContactLcp, v: Var) -> String {
    match v {
        Var::Driver => "s".into(),
        _ => lcp.label(v),
    }
}
