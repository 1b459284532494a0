//! Quasi-static evolution of an LCP whose complementarity holds, for some components, between
//! `x_i` and the *increment* of `z_i` (incremental friction), followed exactly along a
//! piecewise-linear load program.
//!
//! The problem is `x = q0 + ℓ(s) + M z`, `x ≥ 0`, `z ≥ 0`, with a load `ℓ` that moves linearly
//! within each stage, `ℓ = ℓ_start + s·d`, `s ∈ [0, 1]`. For an ordinary ("total") component
//! `x_i·z_i = 0` at every instant. For an *incremental* component the unknown is the rate:
//! `z_i` only grows, and only while `x_i = 0` (`x_i·ż_i = 0`, `ż_i ≥ 0`); it keeps its value
//! otherwise. Between two breakpoints the basis is constant and everything is linear in `s`, so
//! each segment is one segment of the parametric Lemke path of the LCP in the increments. At
//! every breakpoint that moved the point, the incremental values reached are absorbed into the
//! right-hand side (`ĥ += M̂_j z_j`, [`crate::pivoting`]'s `rebase`) and read zero again: where
//! the next segment would make such a component decrease, the ratio test meets a zero at once
//! and the component leaves the basis (the slip stops, its value kept); the degenerate vertex is
//! left by the lexicographic rule restarted from the current basis, never by luck.
//!
//! The engine knows nothing of mechanics: `unilateral-contact` maps friction onto it.

use faer::Mat;

use crate::parametric::{mechanism_mode, start_basis};
use crate::pivoting::basis::Basis;
use crate::pivoting::pivot::{max_abs, Pivoter, Tolerances};
use crate::pivoting::prepare::{check_matrix, check_vector, Prepared};
use crate::{LcpError, MechanismMode, Settings, Var};

/// Differences of the stage parameter (a pure number in `[0, 1]`) at or below this are
/// round-off: the breakpoint is reported at the previous one's `s` (at the stage's start for
/// the pivots that settle the scheme there). The size of a tie in the ratio test.
const S_ROUNDOFF: f64 = 1e-9;

/// The round-off, relative to a row's terms, within which a caller's state at rest solves the
/// problem at zero load ([`EvolutionSolver::start_at_rest`]): the contact crate's ceiling for
/// gap forces that cancel (`load_vectors`).
const REST_ROUNDOFF: f64 = 1e-9;

/// The data of an evolution: `x = q0 + ℓ + M z` at load `ℓ` (zero at the start).
#[derive(Debug, Clone)]
pub struct EvolutionProblem {
    /// The matrix `M` (`n × n`).
    pub m: Mat<f64>,
    /// The constant part (for contact: the initial gaps).
    pub q0: Vec<f64>,
    /// Which components of `z` are incremental.
    pub incremental: Vec<bool>,
    /// For an incremental component, the index `g` of a `z_g` whose being basic suspends it
    /// (`None`: never suspended): while `z_g` is basic the component is a total. For friction
    /// the opening of the pair: the slip of an open pair is its free
    /// tangential motion, a total measured from where it opened, and only a closed pair's slip
    /// is absorbed at breakpoints. That spares the pivots a free motion's every change of
    /// direction would cost, and is exact: an open pair transmits no force either way.
    pub guard: Vec<Option<usize>>,
    /// A positive direction along which `q0` is made feasible to find the start (as the
    /// tightening direction of the parametric method).
    pub start_direction: Vec<f64>,
}

/// A state of the evolution: the load reached, the values, and the basis to go on from.
#[derive(Debug, Clone)]
pub struct EvolutionState {
    /// The load part `ℓ` of the right-hand side reached (`q0` not included).
    pub load: Vec<f64>,
    /// `x` at the state.
    pub x: Vec<f64>,
    /// `z` at the state: current values of total components, accumulated values of
    /// incremental ones.
    pub z: Vec<f64>,
    /// The complementary basis (none at a state the evolution cannot go on from).
    basis: Option<Basis>,
}

impl EvolutionState {
    /// Whether the evolution can go on from this state.
    pub fn can_continue(&self) -> bool {
        self.basis.is_some()
    }
}

/// One pivot of a stage: a change of the working scheme at stage parameter `s`.
#[derive(Debug, Clone, PartialEq)]
pub struct EvolutionPoint {
    /// The stage parameter.
    pub s: f64,
    /// The entering variable (`Var::Driver` is `s`).
    pub entering: Var,
    /// The leaving variable.
    pub leaving: Var,
    /// `x` just after the pivot.
    pub x: Vec<f64>,
    /// `z` just after the pivot (accumulated values of incremental components).
    pub z: Vec<f64>,
}

/// How a stage ended.
#[derive(Debug, Clone, PartialEq)]
pub enum StageEnding {
    /// `s = 1` was reached.
    Completed,
    /// The entering variable grows without bound at fixed `s`: a mechanism at `s`.
    Mechanism(MechanismMode),
    /// The path would turn back (`s` decreasing) or leave `s = 0`: the rate problem has no
    /// solution or several here.
    TurnsBack,
    /// The pivot cap was hit.
    IterationLimit,
    /// A basis could not be factorised.
    Singular,
}

/// The result of one stage.
#[derive(Debug, Clone)]
pub struct StageRun {
    /// How it ended.
    pub ending: StageEnding,
    /// The stage parameter reached.
    pub s_end: f64,
    /// Every pivot in order.
    pub points: Vec<EvolutionPoint>,
    /// The state at `s_end`.
    pub end: EvolutionState,
    /// The increment of every incremental `z` on the stage's last segment (zero for the
    /// others): which components are still growing at the end.
    pub last_increment: Vec<f64>,
    /// Pivots spent.
    pub pivots: usize,
    /// For a completed stage, its end refined once from the data (a second opinion: the values
    /// at the end are moved there by hand along the last column).
    pub refined: Option<RefinedEnd>,
}

/// The end of a completed stage with its values refined once from the data, the driver
/// non-basic at the stage's end (`Pivoter::refine_with_driver_at`): the fields of a
/// [`StageRun`] that change.
#[derive(Debug, Clone)]
pub struct RefinedEnd {
    /// The `x` at the end.
    pub x: Vec<f64>,
    /// The `z` at the end.
    pub z: Vec<f64>,
    /// The increments of the last segment.
    pub last_increment: Vec<f64>,
}

/// The evolution solver: the problem checked and equilibrated once.
pub struct EvolutionSolver {
    problem: EvolutionProblem,
    settings: Settings,
    n: usize,
    prep: Prepared,
    /// The settings' row relations that the data satisfy, in the equilibrated rows: they
    /// decide the ties of a step judged on the structure's equations.
    relations: std::sync::Arc<crate::pivoting::relations::Relations>,
    /// The parts of the problem that `M` and the row relations couple
    /// ([`crate::pivoting::scaling::coupled_sets`]): each stage raises them to one size.
    sets: Vec<usize>,
}

impl std::fmt::Debug for EvolutionSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EvolutionSolver")
            .field("order", &self.n)
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl EvolutionSolver {
    /// Validates the problem and the settings, and equilibrates `M`.
    pub fn new(problem: EvolutionProblem, settings: Settings) -> Result<Self, LcpError> {
        let n = check_matrix(&problem.m)?;
        check_vector("q0", &problem.q0, n)?;
        check_vector("start direction", &problem.start_direction, n)?;
        if problem.guard.len() != n || problem.guard.iter().flatten().any(|&g| g >= n) {
            return Err(LcpError::Dimension(format!(
                "the guards have {} entries (each < n), M has order {n}",
                problem.guard.len()
            )));
        }
        if problem.incremental.len() != n {
            return Err(LcpError::Dimension(format!(
                "the incremental mask has {} entries, M has order {n}",
                problem.incremental.len()
            )));
        }
        settings.validate(n)?;
        let prep = Prepared::new(&problem.m);
        // For the ties of the judged steps, and of a stage traced again after its own rules
        // met a singular basis (`stage_judged`): the stages' own pivoting keeps its rules
        // (with the relations throughout, stiff-spring histories of reviewers' sweeps met a
        // singular basis or a false mechanism: 8 of 155 worse, 3 better).
        let relations = std::sync::Arc::new(crate::pivoting::relations::Relations::new(
            &prep,
            &settings.row_relations,
        ));
        let sets = crate::pivoting::scaling::coupled_sets(&problem.m, &settings.relation_rows());
        Ok(Self {
            problem,
            settings,
            n,
            prep,
            relations,
            sets,
        })
    }

    /// The order `n`.
    pub fn order(&self) -> usize {
        self.n
    }

    /// The problem as given.
    pub fn problem(&self) -> &EvolutionProblem {
        &self.problem
    }

    /// The problem's parts raised to one size on a stage's right-hand side `h` and direction
    /// `d` (`Scaling::raise_sets`), where any part is raised.
    fn stage_prep(&self, h: &[f64], d: &[f64]) -> Option<Prepared> {
        let mut scaling = self.prep.scaling.clone();
        let raised = scaling
            .raise_sets(&self.sets, &[h, d])
            .iter()
            .any(|&s| s != 0);
        raised.then(|| self.prep.rescaled(scaling))
    }

    fn tolerances(&self) -> Tolerances {
        Tolerances {
            pivot: self.settings.pivot_tol(),
            value: 1e-13,
        }
    }

    /// The state at zero load: the solution of `x = q0 + M z` (every incremental component
    /// starts at its value there, normally zero). `None` when there is none.
    pub fn start(&self) -> Option<EvolutionState> {
        let n = self.n;
        let zero = vec![0.0; n];
        let (basis, ..) = start_basis(
            &self.prep,
            &zero,
            &self.problem.q0,
            &self.problem.start_direction,
            &self.settings,
            None,
        );
        let basis = basis?;
        let cols = self.prep.columns(&self.problem.q0, &zero);
        let beta = basis.solve(&cols, &cols.h);
        let (x, z) = self.prep.unscale(
            &basis.slot_var,
            &cols.values(&crate::parametric::clamp(&beta)),
        );
        Some(EvolutionState {
            load: zero,
            x,
            z,
            basis: Some(basis),
        })
    }

    /// [`EvolutionSolver::start`] where the caller knows the state at zero load: `rest`, a `z`
    /// at which every `x = q0 + M·rest` is zero (for contact, every pair at its gap with no
    /// slip and no force, `history.md`). The state is `rest` with `x = 0`, from the basis that
    /// [`EvolutionSolver::start`] finds. Where the gaps' stiffness is regular that basis's
    /// values are `rest` itself; where a motion that no force resists closes a gap (a beam held
    /// only by its pairs, turning about one of them), `rest` is no basic solution at all (every
    /// basic solution of `q0 = 0` is `z = 0`), and the basis's values are `rest` moved along
    /// that free motion (the gap shut at no force): the state the first load that presses the
    /// pair takes at once (`load_vectors`' rigid motions in the contact crate). The state
    /// reported is `rest` all the same — a stage that ends where nothing moved holds it (a
    /// mechanism at its start) — and the basis stays the one to go on from. `rest` is taken
    /// only where it solves the problem within 1e-9 of each row's terms (`|q0| + |M|·rest`,
    /// the contact crate's round-off of cancelled gap forces) and the basis's own state
    /// carries no more force than that (two states of the same forces); otherwise the state
    /// is [`EvolutionSolver::start`]'s.
    pub fn start_at_rest(&self, rest: &[f64]) -> Option<EvolutionState> {
        let mut state = self.start()?;
        let n = self.n;
        if rest.len() != n || rest.iter().any(|v| !(v.is_finite() && *v >= 0.0)) {
            return Some(state);
        }
        let m = &self.problem.m;
        let q0 = &self.problem.q0;
        let unloaded = (0..n).all(|i| {
            let (mut sum, mut terms) = (q0[i], q0[i].abs());
            for (j, &r) in rest.iter().enumerate() {
                if r != 0.0 {
                    sum += m[(i, j)] * r;
                    terms += (m[(i, j)] * r).abs();
                }
            }
            let tol = REST_ROUNDOFF * terms;
            sum.abs() <= tol && state.x[i].abs() <= tol
        });
        if unloaded {
            state.x = vec![0.0; n];
            state.z = rest.to_vec();
        }
        Some(state)
    }

    /// The right-hand side `q0 + ℓ + M_inc z_inc` of the LCP in the increments at `state`.
    fn rhs_at(&self, state: &EvolutionState) -> Vec<f64> {
        let n = self.n;
        let mut h: Vec<f64> = self
            .problem
            .q0
            .iter()
            .zip(&state.load)
            .map(|(a, b)| a + b)
            .collect();
        for j in 0..n {
            let zj = state.z[j];
            if self.problem.incremental[j] && zj != 0.0 {
                for (i, hi) in h.iter_mut().enumerate() {
                    *hi += self.problem.m[(i, j)] * zj;
                }
            }
        }
        h
    }

    /// Follows one stage from `from`: the load moves by `s·d`, `s` from 0 to 1.
    pub fn stage(&self, from: &EvolutionState, d: &[f64]) -> StageRun {
        self.stage_judged(from, d, None)
    }

    /// [`EvolutionSolver::stage`], the load's rates that the data cannot tell from round-off
    /// judged on `judge`: the same problem on the structure's own sparse equations, with the
    /// stage's load increment `d` as its load (as [`crate::PathSolver::judged_on`] judges a
    /// load path's).
    pub fn stage_judged(
        &self,
        from: &EvolutionState,
        d: &[f64],
        judge: Option<std::sync::Arc<crate::StructureJudge>>,
    ) -> StageRun {
        self.trace_from(from, d, judge, None)
    }

    /// [`EvolutionSolver::stage_judged`] traced with the row relations deciding every tie
    /// (their `κ` taken as zero, the data's), not only those of judged steps: a second opinion
    /// for a caller whose first trace failed or read a mechanism. Where a sliding pair opens,
    /// its normal row and its friction part reach zero together, a tie that a stage's own
    /// rule decides on values carrying the round-off of the slips it absorbed; the relations
    /// in every stage are no cure (in a reviewer's sweep of 155 histories they made 8 worse
    /// and 3 better), so the caller (the contact crate's history) keeps this trace only by
    /// its check of the two.
    pub fn stage_related(
        &self,
        from: &EvolutionState,
        d: &[f64],
        judge: Option<std::sync::Arc<crate::StructureJudge>>,
    ) -> StageRun {
        self.trace_from(from, d, judge, Some(f64::INFINITY))
    }

    /// [`EvolutionSolver::stage_related`] with the relations deciding the ties of the steps
    /// that start at or before `s = until` (the landing of the step that crosses it too), the
    /// stage's own rule after them: a third opinion for a caller whose first
    /// trace went wrong at `until` (a tie there decided against the relations) and whose
    /// second went wrong later (where the stage's own rule, not the relations, finds its way:
    /// a block tipping about its toe).
    pub fn stage_related_until(
        &self,
        from: &EvolutionState,
        d: &[f64],
        judge: Option<std::sync::Arc<crate::StructureJudge>>,
        until: f64,
    ) -> StageRun {
        self.trace_from(from, d, judge, Some(until))
    }

    /// [`EvolutionSolver::trace_stage`] from `from`'s basis, the first trace of a stage
    /// counted as the next stage of the progress; a stage that cannot start (no basis, a load
    /// of another order, or a second trace without relations to decide its ties) is a singular
    /// basis at `s = 0`.
    fn trace_from(
        &self,
        from: &EvolutionState,
        d: &[f64],
        judge: Option<std::sync::Arc<crate::StructureJudge>>,
        related_until: Option<f64>,
    ) -> StageRun {
        let related_ties = related_until.is_some();
        match from.basis.clone() {
            Some(basis) if d.len() == self.n && !(related_ties && self.relations.is_empty()) => {
                if !related_ties {
                    self.settings.progress.next_stage();
                }
                self.trace_stage(from, d, basis, judge, related_until)
            }
            _ => StageRun {
                ending: StageEnding::Singular,
                s_end: 0.0,
                points: vec![],
                end: EvolutionState {
                    basis: None,
                    ..from.clone()
                },
                last_increment: vec![0.0; self.n],
                pivots: 0,
                refined: None,
            },
        }
    }

    /// One trace of a stage from `from`'s basis `basis`. With `related_until`, the row
    /// relations decide the ties of every step up to that `s` ([`Pivoter::relations`], their
    /// `κ` taken as zero: a stage's right-hand side carries the round-off of the slips it
    /// absorbed), not only those of judged steps.
    fn trace_stage(
        &self,
        from: &EvolutionState,
        d: &[f64],
        basis: crate::pivoting::basis::Basis,
        judge: Option<std::sync::Arc<crate::StructureJudge>>,
        related_until: Option<f64>,
    ) -> StageRun {
        let n = self.n;
        let progress = &self.settings.progress;
        let h = self.rhs_at(from);
        // The stage's parts raised to one size, as a path's (`Scaling::raise_parts`, on the
        // stage's right-hand side and direction): the basis it goes on from is the same on
        // both scalings (`E M D` is).
        let raised = self.stage_prep(&h, d);
        let prep = raised.as_ref().unwrap_or(&self.prep);
        let cols = prep.columns(&h, d);
        let tol = self.tolerances();
        let mut piv = Pivoter::new(
            &cols,
            basis,
            tol,
            self.settings.priority(n),
            self.settings.refactor_interval,
        );
        if related_until.is_some() {
            piv.relations = self.relations.clone();
            piv.zero_kappa = true;
        }
        piv.restart_lex();
        piv.judge = judge
            .filter(|j| j.order() == n)
            .map(|judge| crate::pivoting::pivot::Judging {
                judge,
                row: prep.scaling.row.clone(),
                col: prep.scaling.col.clone(),
                relations: Some(self.relations.clone()),
            });
        let reset = &self.problem.incremental;
        let guard = &self.problem.guard;
        let driver = 2 * n;
        let target = cols.driver_scaled(1.0);
        let cap = self.settings.cap(n);
        // Incremental values absorbed into the right-hand side during this stage (columns' units).
        let mut acc = vec![0.0; n];
        let mut points = Vec::new();
        // The last point reached by a step that moved the values (pivots of no step after it
        // hold the same state in exact arithmetic).
        let mut moved: Option<usize> = None;
        let mut entering = driver;
        let point = |piv: &Pivoter, acc: &[f64]| -> (Vec<f64>, Vec<f64>) {
            let mut zc = acc.to_vec();
            let mut xc = vec![0.0; n];
            for (slot, &v) in piv.basis.slot_var.iter().enumerate() {
                if v < n {
                    xc[v] = piv.beta[slot].max(0.0);
                } else if v < 2 * n {
                    zc[v - n] += piv.beta[slot].max(0.0);
                }
            }
            let x = prep.scaling.unscale_x(&piv.cols.values(&xc));
            let dz = prep.scaling.unscale_z(&piv.cols.values(&zc));
            let z = from.z.iter().zip(&dz).enumerate().map(
                |(j, (z0, dzj))| {
                    if reset[j] {
                        z0 + dzj
                    } else {
                        *dzj
                    }
                },
            );
            (x, z.collect())
        };
        let ending = loop {
            let Ok((mut alpha, mut step)) = piv.choose(entering) else {
                break StageEnding::Singular;
            };
            let amax = max_abs(&alpha);
            let ds = piv.driver_slot();
            let (t_now, t_rate) = if entering == driver {
                (0.0, 1.0)
            } else if let Some(ds) = ds {
                let a = alpha[ds];
                let a = if a.abs() <= tol.pivot * amax { 0.0 } else { a };
                (piv.beta[ds], -a)
            } else {
                (0.0, 0.0)
            };
            // A rate of the load below the column's tolerance, read as zero above, that would
            // still move the load a real way (the pivot applies the whole column), judged on
            // the structure's equations where they are at hand: where the load holds there,
            // the segment is taken on their direction at constant load.
            // A rate of `s` read as zero, judged on the structure's equations where they are at
            // hand (`Pivoter::judged_step`; a real way from the `s` reached, as on the load
            // path: against the whole stage, a push to 200 of a beam sliding at 2 was left to
            // the condensed data at the limit).
            let mut judged = false;
            let mut t_rate = t_rate;
            // A step of no length: below round-off of the values and the right-hand side.
            let zero = tol.value * max_abs(&piv.beta).max(max_abs(&piv.cols.h));
            // Rows of `x` that the ratio test passed over (rates below the column's tolerance)
            // and that would reach zero before the segment ends, judged on the structure's
            // equations where they are at hand and `s` moves there: a block sliding on in a
            // later stage on a soft spring, its heel unloading at 3e-10 of the slips' terms,
            // ran past the heel's opening to a state out of balance.
            if piv.judge.is_some() && (t_rate > 0.0 || entering == driver) {
                let to_end = (target - t_now) / t_rate;
                let theta_end = step.map_or(to_end, |(_, th)| th.min(to_end));
                if piv.hides_blocks(&alpha, theta_end) {
                    if let Some(j) = piv.judged_moving(entering) {
                        let rate = match ds {
                            Some(ds) if entering != driver => -j.alpha[ds],
                            _ => 1.0,
                        };
                        if rate > 0.0 {
                            (alpha, step, t_rate, judged) = (j.alpha, j.step, rate, true);
                        }
                    }
                }
            }
            // A direction that moves only displacements and takes the load back, judged on the
            // structure's equations where they are at hand, as the load path judges it: its
            // rate may be the condensation's round-off of a mechanism (blocks tipping in a
            // stage turned back, or went on to a singular basis, at their tipping load).
            if !judged
                && entering != driver
                && piv.near_mechanism_taking_load_back(entering, &alpha, t_rate, amax)
            {
                if let Some(j) = piv.judged_step_if(entering, step, t_rate, t_now, |_| true) {
                    t_rate = j.load_rate(ds);
                    (alpha, step, judged) = (j.alpha, j.step, true);
                }
            }
            if let Some(ds) = ds.filter(|_| !judged && t_rate == 0.0) {
                if let Some(j) = piv.judged_step(entering, step, alpha[ds], t_now, amax) {
                    t_rate = j.load_rate(Some(ds));
                    (alpha, step, judged) = (j.alpha, j.step, true);
                }
            }
            // A total (not incremental) `z` entering at constant load — for contact, a pair's
            // gap opening — blocked at once by a row at zero (an increment the last breakpoint
            // absorbed), judged on the structure's equations where they are at hand: at a
            // block's tipping its last pair but the toe opens, and the toe's slip increment
            // read a rate of round-off in the rotation; the pivot took it and the next basis
            // was singular (a numerical failure at the tipping load). On the structure the
            // rotation is the mechanism. Only for a total variable: judged for any entering
            // one, slip increments entering at constant load read false mechanisms (7 of a
            // reviewer's 220 block histories). The same with the load's rate zero on a
            // direction that moves displacements alone (`Pivoter::near_mechanism_at`), blocked
            // after a real step by a slip increment (`Pivoter::blocked_by_increment`): at the
            // tipping of a block held by a spring of 1e5 N/m, the toe's slip increment fell at
            // 2e-12 of the rotation's rate and stopped it after a step that moved the load by
            // 5e-8 of itself, and the next basis was singular. Judged on the structure, 23 of
            // 2896 generated block histories (18 on springs of 1e4 and 1e5 N/m) tip at the load
            // by hand instead of failing, none worse. Blocked by a force or a gap, such steps
            // are the structure's own: a pair opening as a block slides on a soft spring
            // (judged there too, 13 answered histories failed), a block rotating until its
            // corner meets a wall (judged, two of a reviewer's 1664 histories failed their
            // checks). Judging also a load rate just above the column's tolerance, or a step
            // blocked at once by a force, answered 46 more of the blocks but failed 49 of the
            // reviewer's blocks that tip against a wall and are unloaded.
            let total = entering >= n && entering < driver && !reset[entering - n];
            let at_once = step.is_some_and(|(_, th)| th <= zero);
            if total
                && !judged
                && t_rate == 0.0
                && (at_once
                    || (piv.near_mechanism_at(entering, &alpha, 0.0, amax)
                        && piv.blocked_by_increment(step, reset)))
            {
                if let Some(j) = piv.judged_on_structure(entering) {
                    t_rate = j.load_rate(ds);
                    (alpha, step, judged) = (j.alpha, j.step, true);
                }
            }
            // A tiny pivot whose load barely moves, taken from the structure's equations where
            // they find a mechanism there, as on the load path
            // ([`Pivoter::tiny_pivot_mechanism`]): a block on a heel spring of 10 N/m pushed in
            // a stage past its tipping load stopped there at a singular basis.
            if !judged && entering != driver {
                let raw = ds.map_or(0.0, |ds| -alpha[ds]);
                if let Some(j) = piv.tiny_pivot_mechanism(entering, &alpha, step, raw, t_now, amax)
                {
                    t_rate = 0.0;
                    (alpha, step, judged) = (j.alpha, j.step, true);
                }
            }
            // A rate below the column's tolerance that was not judged still moves `s` by the
            // whole column at the pivot: where the step carries `s` a real way (1e-6 of the
            // stage) it counts, as on the load path (`Pivoter::run`) — read as zero, a sliding
            // beam's last stage (a zone without its structure) ran on past its end to
            // s = 1.53. On a ray it stays zero: a mechanism.
            if let Some(ds) = ds.filter(|_| !judged && entering != driver && t_rate == 0.0) {
                let raw = -alpha[ds];
                if raw != 0.0 && step.is_some_and(|(_, th)| (th * raw).abs() > 1e-6 * target) {
                    t_rate = raw;
                }
            }
            if t_rate > 0.0 {
                let theta_t = (target - t_now) / t_rate;
                let hit = match step {
                    None => true,
                    Some((_, th)) => theta_t <= th + 1e-9 * th.abs().max(theta_t.abs()),
                };
                if hit {
                    // The end of the stage lies on this segment: move there and take `s` out of
                    // the basis, leaving a complementary basis at `s = 1`.
                    // The values are moved by hand and the basis updated without a
                    // refactorisation: recomputed from the data with `s` non-basic they would
                    // be the values at `s = 0`.
                    for (b, a) in piv.beta.iter_mut().zip(&alpha) {
                        *b -= theta_t * a;
                    }
                    if entering != driver {
                        let Some(ds) = ds else {
                            break StageEnding::Singular;
                        };
                        piv.beta[ds] = theta_t;
                        piv.basis.pivot(&piv.cols, entering, ds, &alpha);
                    }
                    break StageEnding::Completed;
                }
            }
            let Some((slot, theta)) = step else {
                if t_rate == 0.0 {
                    break StageEnding::Mechanism(mechanism_mode(prep, &piv, entering, &alpha));
                }
                break StageEnding::TurnsBack;
            };
            if t_rate < 0.0 && theta > zero {
                break StageEnding::TurnsBack;
            }
            if piv.pivots >= cap {
                break StageEnding::IterationLimit;
            }
            if judged {
                piv.force_refactor();
            }
            let Ok(leaving) = piv.pivot(entering, slot, theta, &alpha) else {
                break StageEnding::Singular;
            };
            if leaving == driver {
                break StageEnding::TurnsBack;
            }
            if theta > zero {
                let mask: Vec<bool> = (0..n)
                    .map(|j| reset[j] && guard[j].is_none_or(|g| !piv.basis.is_basic(n + g)))
                    .collect();
                piv.rebase(&mask, &mut acc);
            }
            // `s` is a pure number in [0, 1]: a distance from the stage's start of the order
            // of round-off of one is the start (or the previous breakpoint) itself.
            let s_now = piv.cols.driver_real(piv.driver_value_scaled());
            let s_last = points.last().map_or(0.0, |p: &EvolutionPoint| p.s);
            let s = if (s_now - s_last).abs() <= S_ROUNDOFF {
                s_last
            } else {
                s_now
            };
            progress.step(s);
            if related_until.is_some_and(|until| s > until) && !piv.relations.is_empty() {
                piv.relations = Default::default();
                piv.zero_kappa = false;
            }
            let (x, z) = point(&piv, &acc);
            points.push(EvolutionPoint {
                s,
                entering: Var::from_col(entering, n),
                leaving: Var::from_col(leaving, n),
                x,
                z,
            });
            if theta > zero {
                moved = Some(points.len() - 1);
            }
            entering = piv
                .cols
                .complement(leaving)
                .expect("only the driver has no complement");
        };
        let completed = ending == StageEnding::Completed;
        // The breakpoint whose state a mechanism holds: its last step that moved, unless that
        // step is at the stage's start (`s` read 0, as the pivots that settle the scheme there
        // are): there the load is the one the stage received, and so is the state (below).
        let held = match (&ending, moved) {
            (StageEnding::Mechanism(_), Some(i)) if points[i].s != 0.0 => Some(i),
            _ => None,
        };
        // A mechanism's `s` is that of the state it holds (else the stage's start), as every
        // breakpoint's is: the driver's value there carries the round-off of the pivots of no
        // step after it (a bar that nothing holds sideways, pushed with every pair open: a
        // mechanism read at s = 1.1e-13, its state checked against the load there and
        // refused, 2.1e-8 > 1e-8).
        let raw = piv.cols.driver_real(piv.driver_value_scaled());
        let s_end = match &ending {
            StageEnding::Completed => 1.0,
            StageEnding::Mechanism(_) => {
                let at = held.map_or(0.0, |i| points[i].s);
                if (raw - at).abs() <= S_ROUNDOFF {
                    at
                } else {
                    raw
                }
            }
            _ => raw,
        };
        // The increments of the last segment: the incremental values since the last rebase.
        let increments = |piv: &Pivoter| {
            let mut last = vec![0.0; n];
            for (slot, &v) in piv.basis.slot_var.iter().enumerate() {
                if v >= n && v < 2 * n && reset[v - n] {
                    last[v - n] = piv.beta[slot].max(0.0);
                }
            }
            prep.scaling.unscale_z(&piv.cols.values(&last))
        };
        let last_increment = increments(&piv);
        // A mechanism holds the state of the last step that moved, as that step formed it
        // (after its rebase, refined from the data): judging the ray refactorises the basis and
        // forms the values afresh without the refinement, and pivots of no step may follow
        // whose bases turn singular in the mechanism's mode. A block tipping about its toe in
        // a stage: after its last pair but the toe opened, the toe's slip increment stopped at
        // no step and that basis's values had the block rotated by 8 mm (its check failing at
        // 3.5e-3); in kN·mm, with no such pivot, the fresh values failed it.
        // Where no step moved, or none after the stage's start, that is the stage's start as
        // the stage received it — for the first, the unloaded structure with every pair at its
        // gap (`start_at_rest`), which no basis may hold where a free motion closes a gap. A
        // frame held only by its pairs, pushed at a pair that its gap keeps open, is a
        // mechanism at once: the basis's values had the gap shut by a rigid turn, whose
        // round-off a stiff spring made forces of against a state of no load (out of balance
        // by 1.0, exit 1); a beam that nothing holds sideways held a step at s = 0 that moved
        // by round-off, its forces of 1e-10 N against no load.
        let (x, z) = match (&ending, held) {
            (StageEnding::Mechanism(_), Some(i)) => (points[i].x.clone(), points[i].z.clone()),
            (StageEnding::Mechanism(_), None) => (from.x.clone(), from.z.clone()),
            _ => point(&piv, &acc),
        };
        let load = from
            .load
            .iter()
            .zip(d)
            .map(|(l, di)| l + s_end * di)
            .collect();
        let basis = completed.then(|| piv.basis.clone());
        let refined = completed.then(|| {
            piv.refine_with_driver_at(target);
            let (x, z) = point(&piv, &acc);
            RefinedEnd {
                x,
                z,
                last_increment: increments(&piv),
            }
        });
        StageRun {
            ending,
            s_end,
            points,
            end: EvolutionState { load, x, z, basis },
            last_increment,
            pivots: piv.pivots,
            refined,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solver(m: Mat<f64>, q0: Vec<f64>) -> EvolutionSolver {
        let n = q0.len();
        let problem = EvolutionProblem {
            m,
            q0,
            incremental: vec![false; n],
            guard: vec![None; n],
            start_direction: vec![1.0; n],
        };
        EvolutionSolver::new(problem, Settings::default()).expect("a valid problem")
    }

    /// By hand, `x = q0 + M z` at zero load: `x = −1 + 2z` rests at `z = 1/2`, `x = 0`, which
    /// the start's basis finds too; a rest that does not solve it (`z = 0.3`, `x = −0.4`) is
    /// refused for the start's own state. With `M = 0` and `q0 = 0` (a gap that a free motion
    /// shuts) every basic solution has `z = 0`, and the rest at the gap, `z = 1e-3`, which
    /// solves it as well, is the start.
    #[test]
    fn the_start_at_rest_is_the_callers_state_where_it_solves_the_problem() {
        let s = solver(Mat::from_fn(1, 1, |_, _| 2.0), vec![-1.0]);
        let at_rest = s.start_at_rest(&[0.5]).unwrap();
        assert_eq!((at_rest.z, at_rest.x), (vec![0.5], vec![0.0]));
        assert_eq!(s.start().unwrap().z, vec![0.5]);
        assert_eq!(s.start_at_rest(&[0.3]).unwrap().z, vec![0.5]);
        let free = solver(Mat::zeros(1, 1), vec![0.0]);
        assert_eq!(free.start().unwrap().z, vec![0.0]);
        let at_gap = free.start_at_rest(&[1e-3]).unwrap();
        assert!(at_gap.can_continue());
        assert_eq!((at_gap.z, at_gap.x), (vec![1e-3], vec![0.0]));
        // Not a state at all: refused for the start's.
        assert_eq!(free.start_at_rest(&[-1.0]).unwrap().z, vec![0.0]);
    }
}
