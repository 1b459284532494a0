//! The answer of a contact solve in the language of the structure: pair states, events, load
//! steps, the outcome, and the solution that answers for any load on its path.

use std::fmt;
use std::sync::{Arc, OnceLock};

use unilateral_lcp::{
    Breakpoint, LoadPath, PathOptions, PathPoint, PathSolver, PathStatus, Residual, Tableau, Var,
};

use crate::lcp::ContactLcp;
use crate::units::Units;
use crate::{ContactError, ContactZone, SolveSettings};

/// The state of a contact pair in a solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairState {
    /// No compression: the points separate (or just touch without force).
    Open,
    /// Closed, `|x_t| ≤ f·x_n`, no slip.
    Stick,
    /// Closed and slipping with `z_t > 0` (`x_t = −f·x_n`).
    SlipPlus,
    /// Closed and slipping with `z_t < 0` (`x_t = +f·x_n`).
    SlipMinus,
}

impl PairState {
    /// `"open"`, `"stick"`, `"slip+"`, `"slip-"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            PairState::Open => "open",
            PairState::Stick => "stick",
            PairState::SlipPlus => "slip+",
            PairState::SlipMinus => "slip-",
        }
    }
}

impl fmt::Display for PairState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What happens to a pair at an event of the load path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    /// Its normal force reached zero: the pair opens.
    Opens,
    /// Its opening reached zero: the pair closes.
    Closes,
    /// Friction reached its limit with slip in the `+` direction.
    StartsSlippingPlus,
    /// Friction reached its limit with slip in the `−` direction.
    StartsSlippingMinus,
    /// The slip stopped: the pair sticks again.
    Sticks,
}

/// A change of the working scheme at one pair.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Event {
    /// 0-based pair index.
    pub pair: usize,
    /// The pair's name.
    pub name: String,
    /// What happens.
    pub kind: EventKind,
    /// A friction event of a pair that is open at the time: it only uses up the sideways
    /// capacity that the artificial tightening gives an open pair (no force is transmitted).
    pub while_open: bool,
}

impl fmt::Display for Event {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.kind {
            EventKind::Opens => "opens",
            EventKind::Closes => "closes",
            EventKind::StartsSlippingPlus => "starts to slip in the + direction",
            EventKind::StartsSlippingMinus => "starts to slip in the − direction",
            EventKind::Sticks => "sticks again",
        };
        write!(f, "pair {} {what}", self.name)?;
        if self.while_open {
            f.write_str(" (while open: within the tightening only)")?;
        }
        Ok(())
    }
}

/// One step of the load path: the load at which the working scheme changed.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadStep {
    /// 1-based step number.
    pub index: usize,
    /// The load parameter (with the tightening, as traced).
    pub p: f64,
    /// Label of the entering variable (`z_n1`, `p`, …).
    pub entering: String,
    /// Label of the leaving variable.
    pub leaving: String,
    /// The events the step stands for.
    pub events: Vec<Event>,
    /// `p` decreased at this step (a turning point: solutions may be non-unique).
    pub turning: bool,
    /// The pivot only settles the working scheme at the start (`p = 0`): not a change of the
    /// scheme as the load grows, not an event.
    pub settling: bool,
}

/// Forces, mutual displacements and state of one pair.
#[derive(Debug, Clone, PartialEq)]
pub struct PairResult {
    /// The pair's name.
    pub name: String,
    /// Normal force, compression positive.
    pub x_n: f64,
    /// Tangential force.
    pub x_t: f64,
    /// Normal mutual displacement, opening positive.
    pub z_n: f64,
    /// Tangential mutual displacement (slip).
    pub z_t: f64,
    /// The state.
    pub state: PairState,
}

/// How the load path ended, in the language of the structure.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// The target load was reached (Criterion 1).
    TargetReached,
    /// The working scheme no longer changes for `p ≥ p_from` (Criterion 2a).
    Ray {
        /// The load of the last event.
        p_from: f64,
    },
    /// The structure becomes a mechanism at `p_limit` (Criterion 2b).
    Mechanism {
        /// The limit load.
        p_limit: f64,
        /// Rates of `(z_n, z_t)` per pair in the mechanism, normalised to a largest rate of 1.
        mode: Vec<(f64, f64)>,
    },
    /// The path came back to `p = 0`.
    ReturnedToZero,
    /// The pivot cap was reached.
    IterationLimit,
    /// No solution at `p = 0` was found.
    NoSolutionAtStart,
    /// A numerically singular basis stopped the path: an internal failure of the solver.
    NumericalFailure,
}

impl Outcome {
    /// The engine's status of this ending.
    pub fn path_status(&self) -> PathStatus {
        match self {
            Outcome::TargetReached => PathStatus::TargetReached,
            Outcome::Ray { .. } => PathStatus::Ray,
            Outcome::Mechanism { .. } => PathStatus::Mechanism,
            Outcome::ReturnedToZero => PathStatus::ReturnedToZero,
            Outcome::IterationLimit => PathStatus::IterationLimit,
            Outcome::NoSolutionAtStart => PathStatus::NoSolutionAtStart,
            Outcome::NumericalFailure => PathStatus::NumericalFailure,
        }
    }

    /// The `status` key of result files (the engine's [`PathStatus::as_str`]).
    pub fn status(&self) -> &'static str {
        self.path_status().as_str()
    }

    /// A sentence for engineers.
    pub fn reading(&self, target: f64) -> String {
        self.reading_traced_with(target, 0.0)
    }

    /// [`Outcome::reading`] of a path traced with the tightening `c` (the paper's procedure):
    /// a ray's start and a mechanism's load depend on `c` there, so they are said to be the
    /// traced path's, not the structure's (an independent tester's beam read "the structure
    /// becomes a mechanism at p_lim = 198.9" with c = 921.6, where its own limit, traced with
    /// `c = 0`, is 62.87).
    pub fn reading_traced_with(&self, target: f64, c: f64) -> String {
        if c > 0.0 {
            match self {
                Outcome::Ray { p_from } if *p_from > 0.0 => {
                    return format!(
                        "the working scheme of the path traced with the tightening c = {} no \
                         longer changes for p ≥ {} (Criterion 2a: ray; this load depends on c \
                         — for the structure's own path see the physical path)",
                        number_text(c),
                        load_text(*p_from)
                    )
                }
                Outcome::Mechanism { p_limit, .. } => {
                    return format!(
                        "the path traced with the tightening c = {} becomes a mechanism at p = {} \
                         (Criterion 2b; this load depends on c — for \
                         the structure's own limit see the physical path)",
                        number_text(c),
                        load_text(*p_limit)
                    )
                }
                _ => {}
            }
        }
        match self {
            Outcome::TargetReached => {
                format!(
                    "the load reached the target p* = {} (Criterion 1)",
                    number_text(target)
                )
            }
            Outcome::Ray { p_from } if *p_from == 0.0 => {
                "the working scheme is the same for every p > 0 (Criterion 2a: ray from the start)"
                    .to_string()
            }
            Outcome::Ray { p_from } => format!(
                "the working scheme no longer changes for p ≥ {} (Criterion 2a: ray)",
                load_text(*p_from)
            ),
            Outcome::Mechanism { p_limit, .. } => format!(
                "the structure becomes a mechanism at p_lim = {} (Criterion 2b)",
                load_text(*p_limit)
            ),
            Outcome::ReturnedToZero => "the load path turned back to p = 0".into(),
            Outcome::IterationLimit => "the pivot cap was reached before the path ended".into(),
            Outcome::NoSolutionAtStart => {
                "the problem has no solution at p = 0 (the constant load alone)".into()
            }
            Outcome::NumericalFailure => {
                "the solver failed: a basis became numerically singular and the path stopped \
                 (an internal failure of the program, not a fault of the model)"
                    .into()
            }
        }
    }
}

/// How the note begins that says why a mechanism at `p = 0` reports no state
/// ([`ContactSolution::no_state_at_start`]).
pub const NO_STATE_AT_START: &str = "no state is reported at p = 0";

/// The answer of [`crate::solve`].
#[derive(Debug, Clone)]
pub struct ContactSolution {
    /// How the path ended.
    pub outcome: Outcome,
    /// The load of the reported solution (`None` when there is none).
    pub p: Option<f64>,
    /// The tightening `c` used.
    pub tightening: f64,
    /// The settings used.
    pub settings: SolveSettings,
    /// Every step of the load path with its events.
    pub steps: Vec<LoadStep>,
    /// Number of steps made before the target was reached (the rest lie beyond `p*`).
    pub steps_before_target: usize,
    /// Per pair, at the reported load (empty when there is no solution).
    pub pairs: Vec<PairResult>,
    /// Verified residuals of the reported solution.
    pub residual: Option<Residual>,
    /// Remarks for the reader (dependence on `c`, turning points, fallbacks).
    pub notes: Vec<String>,
    /// Pivots spent removing the tightening from the reported solution.
    pub tightening_pivots: usize,
    /// The path was traced by the engine on the structure's sparse blocks
    /// ([`crate::solve_sparse`]); the reported point is formed and verified from the zone all
    /// the same.
    pub traced_on_sparse_blocks: bool,
    /// The zone that was solved, in the user's units (shared with the caller by
    /// [`crate::solve_shared`]).
    pub(crate) zone: Arc<ContactZone>,
    /// The `3m` LCP in the user's units, formed on first use ([`ContactSolution::lcp`]).
    pub(crate) lcp: OnceLock<ContactLcp>,
    /// The largest entry of that `M` and of the terms `f·R` its friction rows are formed
    /// from, found on first use (`O(m²)`; [`ContactSolution::traced_on_segments`] asks for it
    /// at every block of breakpoints).
    pub(crate) m_big: OnceLock<f64>,
    /// The engine's load path (breakpoints and mechanism rates in the user's units).
    pub path: LoadPath,
    /// The prepared normalised problem that was solved, shared by the clones of the solution:
    /// it answers for other loads without preparing anything again.
    pub(crate) engine: Arc<Engine>,
}

/// What a solution keeps of its solve to answer for other loads: the engine prepared on the
/// normalised problem (module `units`), the scales back to the user's units, the pair names.
#[derive(Debug)]
pub(crate) struct Engine {
    /// The solver of the normalised `3m` LCP, validated and equilibrated once.
    pub solver: PathSolver,
    /// The scales of the normalisation.
    pub units: Units,
    /// The pair names.
    pub names: Vec<String>,
    /// The force scales of the data without the tightening, normalised (the displacement
    /// scale is relative to the normalised one by the same factor): what round-off of a
    /// reported (tightening-free) point at `p` is judged against — the loads it carries, so
    /// that neither `c` nor a small target changes a state.
    pub data_force: crate::units::DataForce,
}

impl Engine {
    /// Reads the normalised point `sol` as pair results in the user's units.
    pub fn read_point(&self, sol: &PathPoint) -> Result<Vec<PairResult>, ContactError> {
        // A reported point is free of the tightening: its round-off is judged against the
        // data's forces and displacements without `c` (the displacement scale is force over
        // stiffness, and the stiffness does not depend on `c`: the same ratio).
        let mut pairs = pair_results_scaled(
            &sol.x,
            &sol.z,
            &self.names,
            &self.data_force.forces_at(sol.p),
            self.data_force.at(sol.p),
            &self.data_force.component,
            &self.data_force.friction,
        );
        for r in &mut pairs {
            r.x_n = self.units.user_force(r.x_n);
            r.x_t = self.units.user_force(r.x_t);
            r.z_n = self.units.user_displacement(r.z_n);
            r.z_t = self.units.user_displacement(r.z_t);
            if ![r.x_n, r.x_t, r.z_n, r.z_t].iter().all(|v| v.is_finite()) {
                return Err(ContactError::OutOfRange(format!(
                    "the forces and displacements of pair {} at p = {} exceed the \
                     floating-point range (about 1.8e308): express the model in other units",
                    r.name, sol.p
                )));
            }
        }
        Ok(pairs)
    }
}

impl ContactSolution {
    /// The zone that was solved, in the user's units.
    pub fn zone(&self) -> &ContactZone {
        &self.zone
    }

    /// The number of contact pairs `m`.
    pub fn pairs(&self) -> usize {
        self.zone.pairs()
    }

    /// Whether the problem without the tightening is homogeneous: no constant load and no
    /// initial gap, so that a state at a load `p > 0`, scaled by `s > 0`, is the state at
    /// `s·p` (`w = M z + p·q` with `q0 = 0`): the working scheme is the same for every `p > 0`.
    pub fn homogeneous(&self) -> bool {
        self.zone.is_homogeneous()
    }

    /// The reported solution comes from a fresh solve at its load, not from the path's own
    /// basis (the note says it may belong to another branch).
    fn solved_afresh(&self) -> bool {
        self.path.artificial_mechanism.is_none()
            && self.path.solution.as_ref().is_some_and(|s| s.fallback)
    }

    /// What the structure itself does, said before the path traced with the paper's
    /// tightening `c > 0` (whose events are at loads that depend on `c`); `None` when the
    /// path was traced without it (it is then the structure's own).
    ///
    /// Without a constant load the problem is homogeneous ([`ContactSolution::homogeneous`]):
    /// the reported solution, free of the tightening and verified, scaled by `p / p_rep` is a
    /// solution at every `p > 0` — on that branch the structure's path has no event, however
    /// many the traced one has, and no limit (where the path turned or the solution came from
    /// a fresh solve, the text says it may not be unique; at a limit of the traced path only
    /// the values are claimed, its states being named by that limit). Without a reported
    /// state nothing is claimed but the scaling. With a constant load (where the tightening
    /// is never needed) the structure's own path is another trace, with tightening 0; it is
    /// named, not traced.
    pub fn physical_reading(&self) -> Option<String> {
        if self.tightening <= 0.0 {
            return None;
        }
        let state = self
            .p
            .filter(|&p| p > 0.0 && self.residual.is_some() && !self.pairs.is_empty());
        let at_limit = matches!(self.outcome, Outcome::Mechanism { .. });
        Some(match (self.homogeneous(), state) {
            // The states at a limit of the traced path are named by its mechanism, which
            // depends on c: only the values are the structure's.
            (true, Some(p)) if at_limit => format!(
                "no constant load: the forces and displacements of the solution at p = {} \
                 below, scaled by p, solve the problem at every p > 0 — the structure itself \
                 has no limit; the states there are named after the limit of the path traced \
                 with the tightening c = {}, which depends on c",
                number_text(p),
                number_text(self.tightening)
            ),
            (true, Some(p)) => format!(
                "no constant load: the solution at p = {} below, every force and displacement \
                 scaled by p, is a solution at every p > 0 — one working scheme at every load, \
                 with no event and no limit on it; the path traced with the tightening c = {} \
                 is the paper's procedure{}",
                number_text(p),
                number_text(self.tightening),
                if self.steps.iter().any(|s| s.turning) || self.solved_afresh() {
                    " (the solution may not be unique: see the notes)"
                } else {
                    ""
                }
            ),
            (true, None) => format!(
                "no constant load: a state the structure has at one load p > 0, scaled by p, \
                 it has at every load; the path traced with the tightening c = {} reported \
                 none free of c — the structure's own path is the one traced with tightening 0 \
                 (not traced here)",
                number_text(self.tightening)
            ),
            (false, _) => format!(
                "the structure's own path is the one traced with tightening 0 (not traced \
                 here); the events below are the paper's procedure with the tightening \
                 c = {}, at loads that depend on c",
                number_text(self.tightening)
            ),
        })
    }

    /// The paper's label of a variable of the `3m` LCP: `x_n1`, `x_t1+`, `z_t1-`, …, `p`.
    pub fn label(&self, var: Var) -> String {
        crate::lcp::label(self.pairs(), var)
    }

    /// The `3m` LCP that was solved, in the user's units ([`ContactLcp::build`] of
    /// [`ContactSolution::zone`]). Its `M` is a dense `3m × 3m` matrix, formed on the first
    /// call and kept: nothing the solve reports needs it (the engine holds the normalised
    /// problem, and the traced path's forces are formed from the zone's blocks), so a large
    /// solution holds it only if asked.
    pub fn lcp(&self) -> &ContactLcp {
        self.lcp.get_or_init(|| ContactLcp::build(&self.zone))
    }

    /// The load of step `k` (1-based, as [`LoadStep::index`]) computed afresh from the data,
    /// an independent check of the traced `steps[k − 1].p`
    /// ([`unilateral_lcp::PathSolver::event_load`]: the basis before the step factorised anew
    /// and refined; `O(m³)` a step). `None` for a step the path does not have or whose basis is
    /// numerically singular.
    pub fn event_load(&self, k: usize) -> Option<f64> {
        self.engine.solver.event_load(&self.path, k).ok().flatten()
    }

    /// Why no solution is reported although the ending has a load to report it at, for the
    /// reader (the same sentence is among [`ContactSolution::notes`]); `None` when a solution is
    /// reported or the ending has no such load.
    pub fn unreported(&self) -> Option<String> {
        self.path
            .unreported
            .as_ref()
            .filter(|_| self.p.is_none())
            .map(|why| crate::solve::unreported_note(why, self.pairs(), &self.engine.names))
    }

    /// No state is reported at `p = 0` where the structure becomes a mechanism, and a note
    /// (beginning [`NO_STATE_AT_START`]) says why: it carries no force, or the structure's
    /// check refused it.
    pub fn no_state_at_start(&self) -> bool {
        self.p.is_none() && self.notes.iter().any(|n| n.starts_with(NO_STATE_AT_START))
    }

    /// Whether the missing solution ([`ContactSolution::unreported`]) is the program's failure
    /// rather than an answer: the path's own working scheme should have been the solution there
    /// (no tightening to remove), or the fresh solve at that load failed numerically. Only a
    /// tightened path whose real problem Lemke's method ends without a solution is an answer.
    pub fn unreported_is_failure(&self) -> bool {
        self.p.is_none()
            && self
                .path
                .unreported
                .as_ref()
                .is_some_and(|why| crate::solve::unreported_is_failure(why, self.tightening))
    }

    /// Where the path stopped without an answer — at a numerically singular basis
    /// ([`Outcome::NumericalFailure`]), or without the solution it should report
    /// ([`ContactSolution::unreported_is_failure`]) — at a state the data cannot resolve in
    /// double precision: the sentence that says so, with the sizes and the advice; `None`
    /// elsewhere, and for a path traced with the tightening (its states carry `c`). The state is
    /// the path's where it stopped (its last breakpoint), or at the load of the missing
    /// solution; it is beyond double precision where the round-off of the forces its slips and
    /// gaps make term by term (64 ε of their sums) exceeds 1e-8 of the largest load on a pair
    /// there ([`crate::history::VERIFIED`], as a load history's stage judges it): no state
    /// there could be verified, whatever the engine did — the data's conditioning (a steel block
    /// on a 1 N/m spring pushed past its sliding load slides kilometres), not the program's
    /// fault.
    pub fn beyond_double_precision(&self) -> Option<String> {
        if self.tightening != 0.0 {
            return None;
        }
        let last = |what: &str| self.last_breakpoint_state(what);
        let (what, p, pairs) = if self.outcome == Outcome::NumericalFailure {
            last("where it stopped without an answer")?
        } else if self.unreported_is_failure() {
            let at = self.path.unreported.as_ref()?.p;
            let said = format!(
                "the load p = {} where no solution could be verified",
                number_text(at)
            );
            match self.traced_at_many(&[at]).ok()?.pop()? {
                Some(pairs) => (format!("the state of the path at {said},"), at, pairs),
                // Beyond the last breakpoint (on a ray): the scheme there is the last
                // breakpoint's, whose state the load reaches first.
                None => last(&format!("its last change of scheme before {said}"))?,
            }
        } else {
            return None;
        };
        self.unresolvable_at(&what, p, &pairs)
    }

    /// Where the path ended as a ray or a return to zero at a state (its last change of
    /// scheme) the data cannot resolve in double precision, as
    /// [`ContactSolution::beyond_double_precision`] judges one: the sentence that says so. That
    /// ending is read from values whose round-off may change their signs: a block on an 11.4
    /// N/m spring that had slid kilometres when its middle pair opened ended there as a ray in
    /// N·m and turned back to zero in kN·mm, where by statics it is a mechanism (a helper's
    /// sweep of models in both units, round 45). The states reported are verified apart: only
    /// the ending is in doubt, and the reading says so ([`ContactSolution::reading`]).
    pub fn ending_beyond_double_precision(&self) -> Option<String> {
        if self.tightening != 0.0
            || !matches!(self.outcome, Outcome::Ray { .. } | Outcome::ReturnedToZero)
        {
            return None;
        }
        let ending = if self.outcome == Outcome::ReturnedToZero {
            "where it turned back"
        } else {
            "from where it runs on as a ray"
        };
        let (what, p, pairs) = self.last_breakpoint_state(ending)?;
        self.unresolvable_at(&what, p, &pairs)
    }

    /// The state of the path at its last change of scheme, `what` naming that place: the
    /// phrase ("the state of the path at p = …, `what`,"), the load and the pairs.
    fn last_breakpoint_state(&self, what: &str) -> Option<(String, f64, Vec<PairResult>)> {
        let k = self.path.breakpoints.len().checked_sub(1)?;
        let (p, pairs) = self.traced_on_segments_unnamed(&[(k, 0.0)]).ok()?.pop()??;
        Some((
            format!("the state of the path at p = {}, {what},", number_text(p)),
            p,
            pairs,
        ))
    }

    /// The sentence for `pairs`, the state `what` at `p`, where the data cannot resolve it in
    /// double precision ([`ContactSolution::beyond_double_precision`]).
    fn unresolvable_at(&self, what: &str, p: f64, pairs: &[PairResult]) -> Option<String> {
        let zone = &*self.zone;
        // The largest load term on a pair (constant or variable, as a history's stage takes
        // each case's: a net load where the two cancel would inflate the ratio).
        let loads = (0..zone.pairs()).fold(0.0f64, |a, i| {
            a.max(zone.constant.normal[i].abs())
                .max(zone.constant.tangential[i].abs())
                .max((p * zone.variable.normal[i]).abs())
                .max((p * zone.variable.tangential[i]).abs())
        });
        let u = crate::history::unresolvable_state(zone, pairs, loads)?;
        Some(u.sentence(what))
    }

    /// The sentence for engineers of how the path ended
    /// ([`Outcome::reading_traced_with`]), except where it stopped at a state beyond double
    /// precision ([`ContactSolution::beyond_double_precision`]): that sentence, not "an
    /// internal failure of the program". A ray or a return to zero read from such a state
    /// carries the doubt ([`ContactSolution::ending_beyond_double_precision`]).
    pub fn reading(&self) -> String {
        let said = || {
            self.outcome
                .reading_traced_with(self.settings.target, self.tightening)
        };
        match (&self.outcome, self.beyond_double_precision()) {
            (Outcome::NumericalFailure, Some(why)) => {
                format!("the solver stopped at a numerically singular basis: {why}")
            }
            (_, Some(why)) => format!("{}, but {why}", said()),
            _ => match self.ending_beyond_double_precision() {
                Some(why) => format!("{}; this ending is in doubt: {why}", said()),
                None => said(),
            },
        }
    }

    /// Reads the normalised point `sol` as the reported solution.
    pub(crate) fn set_point(&mut self, sol: &PathPoint) -> Result<(), ContactError> {
        self.pairs = self.engine.read_point(sol)?;
        if let Outcome::Mechanism { p_limit, mode } = &self.outcome {
            // the reported load is p_lim to round-off (a target equal to f·W/H by hand)
            if (sol.p - p_limit).abs() <= 1e-12 * sol.p.abs().max(p_limit.abs()) {
                let part = &self.engine.data_force.component;
                sliding_at_the_limit(&mut self.pairs, &self.zone.friction, mode, part);
            }
        }
        self.p = Some(sol.p);
        self.residual = Some(sol.residual);
        self.tightening_pivots = sol.tightening_pivots;
        Ok(())
    }

    /// The solution without tightening at another load `p` on the traced path, in the user's
    /// units; `Ok(None)` when `p` is not on it. Nothing is prepared again: the engine kept from
    /// the solve evaluates the path's basis at `p`. An error when the answer leaves the
    /// floating-point range ([`ContactError::OutOfRange`]) or the engine refuses the path
    /// ([`ContactError::Engine`], a fault of the program).
    pub fn at(&self, p: f64) -> Result<Option<(Vec<PairResult>, Residual)>, ContactError> {
        let Some(pt) = self.engine.solver.solution_at(&self.path, p)? else {
            return Ok(None);
        };
        Ok(Some((self.engine.read_point(&pt)?, pt.residual)))
    }

    /// [`ContactSolution::at`] with the point formed on the structure's own equations
    /// ([`unilateral_lcp::PathSolver::structure_solution_at`]; a structural model's solve
    /// without a tightening keeps them): for a caller whose check of the structure finds the
    /// point formed on the condensed data out of balance beyond the data's round-off. `None`
    /// where there are no such equations or their point does not verify.
    pub fn at_on_structure(
        &self,
        p: f64,
    ) -> Result<Option<(Vec<PairResult>, Residual)>, ContactError> {
        let Some(pt) = self.engine.solver.structure_solution_at(&self.path, p)? else {
            return Ok(None);
        };
        Ok(Some((self.engine.read_point(&pt)?, pt.residual)))
    }

    /// [`ContactSolution::at`] at many loads, one answer per load in the order given, in one
    /// walk along the path ([`PathSolver::points_at`]): the cost of about one more trace of the
    /// path instead of a fresh factorisation per load. The errors are those of
    /// [`ContactSolution::at`].
    #[allow(clippy::type_complexity)]
    pub fn at_many(
        &self,
        loads: &[f64],
    ) -> Result<Vec<Option<(Vec<PairResult>, Residual)>>, ContactError> {
        self.engine
            .solver
            .points_at(&self.path, loads)?
            .into_iter()
            .map(|pt| {
                pt.map(|pt| Ok((self.engine.read_point(&pt)?, pt.residual)))
                    .transpose()
            })
            .collect()
    }

    /// The traced path itself — with the tightening `c` of the solve still in it, as the
    /// paper's procedure follows it — at the given points, in the user's units. A point is
    /// `(k, s)`: the fraction `s ∈ [0, 1]` of the way from breakpoint `k` of
    /// [`LoadPath::breakpoints`] to breakpoint `k + 1` (`s = 0` is breakpoint `k` itself; the
    /// last breakpoint is `(last, 0)`). Between breakpoints the path is linear, so
    /// `z = (1 − s)·z_k + s·z_{k+1}`, `p = (1 − s)·p_k + s·p_{k+1}` and
    /// `x = q_c + c·t + p·d + M z`, with `t` the tightening direction
    /// ([`ContactLcp::tightening_direction`]). With `c > 0` these values and their states
    /// depend on `c`; with `c = 0` they are the solution of the problem. Points off the path
    /// (an index beyond the breakpoints) are `None`. All `x` are found in one matrix product,
    /// and `x_i` is zero exactly where `z_i ≠ 0` (complementary on the segment's basis).
    /// An error when a value leaves the floating-point range ([`ContactError::OutOfRange`]).
    #[allow(clippy::type_complexity)]
    pub fn traced_on_segments(
        &self,
        at: &[(usize, f64)],
    ) -> Result<Vec<Option<(f64, Vec<PairResult>)>>, ContactError> {
        self.traced_points(at, &self.engine.names)
    }

    /// [`ContactSolution::traced_on_segments`] with every pair's `name` left empty: for a
    /// caller that knows the pairs by their place (pair `i` is `zone().pair_names[i]`) and asks
    /// for many points (a name is an allocation a pair a point: at the 300-bearing beam's 622
    /// breakpoints, a tenth of its tables' CPU).
    #[allow(clippy::type_complexity)]
    pub fn traced_on_segments_unnamed(
        &self,
        at: &[(usize, f64)],
    ) -> Result<Vec<Option<(f64, Vec<PairResult>)>>, ContactError> {
        self.traced_points(at, &[])
    }

    /// The traced points with the pairs named by `names` (empty: unnamed).
    #[allow(clippy::type_complexity)]
    fn traced_points(
        &self,
        at: &[(usize, f64)],
        names: &[String],
    ) -> Result<Vec<Option<(f64, Vec<PairResult>)>>, ContactError> {
        let bps = &self.path.breakpoints;
        let n = 3 * self.pairs();
        let mut loads = Vec::new();
        let mut cols: Vec<usize> = Vec::new();
        let mut zs: Vec<Vec<f64>> = Vec::new();
        for &(k, s) in at {
            let Some(a) = bps.get(k) else {
                cols.push(usize::MAX);
                continue;
            };
            let b = if s > 0.0 { bps.get(k + 1) } else { None };
            if s > 0.0 && b.is_none() {
                cols.push(usize::MAX);
                continue;
            }
            let s = if b.is_some() { s.clamp(0.0, 1.0) } else { 0.0 };
            let mut z = vec![0.0; n];
            for &(i, v) in &a.z {
                z[i] += (1.0 - s) * v;
            }
            let mut p = a.p;
            if let Some(b) = b {
                for &(i, v) in &b.z {
                    z[i] += s * v;
                }
                p = (1.0 - s) * a.p + s * b.p;
            }
            cols.push(zs.len());
            loads.push(p);
            zs.push(z);
        }
        // `M`, `q_c`, `d` and `t` are those of `ContactLcp::build`, but `M` is never formed:
        // its rows are the zone's blocks, `x_n = R_nn z_n + R_nt w + …` with
        // `w = (z_t+ − z_t-)/2` and `x_t± = f·(x_n's product) ± (R_tn z_n + R_tt w) + …`, four
        // `m × m` products instead of one `3m × 3m` one.
        let zone = &*self.zone;
        let m = zone.pairs();
        let f = &zone.friction;
        let (q0, d) = crate::lcp::load_vectors(zone);
        let t = crate::lcp::tightening_direction(f);
        let c = self.tightening;
        // The rows `x_t± = f·x_n ± x_t` of a pair with a huge friction coefficient can leave
        // the floating-point range (or their partial sums can) although the pair's forces do
        // not. Everything is then formed times an exact power of two `2^-e` small enough for
        // every sum, and `x_t` is taken from the scaled rows before scaling back: the values
        // are the same, and an overflow left is one of the forces themselves.
        let p_big = loads.iter().fold(0.0f64, |a, p| a.max(p.abs()));
        // The largest entry of `M` and of the terms `f·R` its friction rows are formed from.
        let m_big = *self.m_big.get_or_init(|| {
            let mut m_big = 0.0f64;
            for j in 0..m {
                for (i, &fi) in f.iter().enumerate() {
                    let (nn, nt, tn, tt) = (
                        zone.rnn[(i, j)],
                        zone.rnt[(i, j)],
                        zone.rtn[(i, j)],
                        zone.rtt[(i, j)],
                    );
                    for v in [
                        nn,
                        nt / 2.0,
                        fi * nn,
                        fi * nt / 2.0,
                        fi * nn + tn,
                        fi * nn - tn,
                        (fi * nt + tt) / 2.0,
                        (fi * nt - tt) / 2.0,
                    ] {
                        m_big = m_big.max(v.abs());
                    }
                }
            }
            m_big
        });
        let z_big = zs
            .iter()
            .flat_map(|z| z.iter())
            .fold(0.0f64, |a, v| a.max(v.abs()));
        // log2 of a bound of every term and partial sum (each factor finite, as read).
        let log2 = |v: f64| if v > 0.0 { v.log2() } else { f64::NEG_INFINITY };
        let terms = (0..n).fold(f64::NEG_INFINITY, |a, i| {
            a.max(log2(q0[i].abs() / 4.0 + c / 4.0 * t[i].abs() + p_big / 4.0 * d[i].abs()) + 2.0)
        });
        let bound = terms.max(log2(m_big) + log2(z_big) + 2.0) + log2(n as f64).max(0.0);
        // At most 2^-1000, a normal number: a bound beyond that is an overflow of the forces.
        let e = if bound <= 1000.0 {
            0
        } else {
            (bound - 1000.0).ceil().min(1000.0) as i32
        };
        let down = 2f64.powi(-e);
        let k = zs.len();
        let zn = faer::Mat::from_fn(m, k, |i, j| zs[j][i] * down);
        let w = faer::Mat::from_fn(m, k, |i, j| {
            (zs[j][m + i] * down - zs[j][2 * m + i] * down) / 2.0
        });
        let (normal, tangential) = zone_products(zone, &zn, &w, &active_columns(bps, m));
        // The traced values carry the tightening (`c·t` in `x`): their round-off is judged
        // against the scales that include it.
        let unit = self.engine.units.user_force(1.0);
        let (fs, ds) = (
            vec![(unit, unit); m],
            self.engine.units.user_displacement(1.0),
        );
        let parts = &self.engine.data_force.component;
        // With the tightening in them the friction rows carry `max(1, f)·c` beside `f·x_n`: a
        // pair without friction may carry a traced tangential force (`ContactLcp::build`).
        let friction: &[f64] = if c == 0.0 {
            &self.engine.data_force.friction
        } else {
            &[]
        };
        let mut out = Vec::with_capacity(at.len());
        for &j in &cols {
            if j == usize::MAX {
                out.push(None);
                continue;
            }
            let p = loads[j];
            let mz = |i: usize| {
                let r = i % m;
                match i / m {
                    0 => normal[(r, j)],
                    1 => f[r] * normal[(r, j)] + tangential[(r, j)],
                    _ => f[r] * normal[(r, j)] - tangential[(r, j)],
                }
            };
            let mut x: Vec<f64> = (0..n)
                .map(|i| q0[i] * down + c * down * t[i] + p * down * d[i] + mz(i))
                .collect();
            // Complementary to a non-zero `z_i`, `x_i` is not basic on the segment: it is
            // zero exactly (the product leaves the round-off of its terms there: an open pair
            // would carry a force of the size of its displacement's terms times 1e-16).
            for (xi, &zi) in x.iter_mut().zip(&zs[j]) {
                if zi != 0.0 {
                    *xi = 0.0;
                }
            }
            if e > 0 {
                for i in 0..m {
                    let x_t = (x[m + i] - x[2 * m + i]) / 2.0 / down;
                    x[i] /= down;
                    x[m + i] = x_t;
                    x[2 * m + i] = -x_t;
                }
            }
            let pairs = pair_results_scaled(&x, &zs[j], names, &fs, ds, parts, friction);
            if let Some(i) = pairs
                .iter()
                .position(|r| ![r.x_n, r.x_t, r.z_n, r.z_t].iter().all(|v| v.is_finite()))
            {
                return Err(ContactError::OutOfRange(format!(
                    "the forces and displacements of pair {} on the traced path at p = {} \
                     exceed the floating-point range (about 1.8e308): express the model in \
                     other units",
                    self.engine.names.get(i).map_or("?", String::as_str),
                    number_text(p)
                )));
            }
            out.push(Some((p, pairs)));
        }
        Ok(out)
    }

    /// The traced path (with the tightening, see [`ContactSolution::traced_on_segments`]) at
    /// many loads: at each load, on the first segment between consecutive breakpoints whose
    /// loads bracket it (as [`LoadPath::traced_z_at`]); `None` for a load outside the
    /// breakpoints (beyond the last one, on a ray or before the target).
    pub fn traced_at_many(
        &self,
        loads: &[f64],
    ) -> Result<Vec<Option<Vec<PairResult>>>, ContactError> {
        let bps = &self.path.breakpoints;
        let at: Vec<(usize, f64)> = loads
            .iter()
            .map(|&p| {
                bps.windows(2)
                    .enumerate()
                    .find_map(|(k, w)| {
                        let (a, b) = (w[0].p, w[1].p);
                        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
                        (p >= lo && p <= hi && hi > lo).then(|| (k, (p - a) / (b - a)))
                    })
                    .or_else(|| {
                        // a path of one point answers at its own load
                        (bps.len() == 1 && bps[0].p == p).then_some((0, 0.0))
                    })
                    .unwrap_or((usize::MAX, 0.0))
            })
            .collect();
        Ok(self
            .traced_on_segments(&at)?
            .into_iter()
            .map(|v| v.map(|(_, pairs)| pairs))
            .collect())
    }

    /// The tableaux of the path in the paper's layout and the user's units (at most
    /// `max_steps` steps). They are computed from [`ContactSolution::lcp`], the problem in the
    /// user's units, which is checked on the way ([`ContactError::Engine`] if the engine
    /// refuses it).
    pub fn tableaux(&self, max_steps: Option<usize>) -> Result<Vec<Tableau>, ContactError> {
        // Formed here and dropped after (not kept as [`ContactSolution::lcp`]): the solver
        // takes its `M`.
        let lcp = ContactLcp::build(&self.zone);
        let options = PathOptions {
            target: self.settings.target,
            follow: self.settings.follow,
            tightening: lcp.tightening(self.settings.tightening),
        };
        let solver = PathSolver::new(lcp.problem, options, self.engine.solver.settings().clone())?;
        Ok(solver.tableaux(&self.path, max_steps)?)
    }
}

/// At the load where the structure becomes a mechanism, a pair that has not slipped yet but
/// stands at its friction limit (`|x_t| = f·x_n` to round-off) and slides in the mechanism's
/// mode (its `dz_t` not round-off of the mode's largest rate, in the direction its friction
/// force opposes) slips: it read "stick" (its accumulated slip is zero at that load) while the
/// mode slid it with the others. "To round-off" is 1e-8 of the largest force: the condensed
/// data's accuracy at such a limit (the pair whose start of slip completes a 450-bearing
/// beam's sliding mechanism stood 1.2e-9 of the largest force off its limit, and read "stick"
/// at 1e-9). The largest force is that of the pair's part of the zone (`part`,
/// [`crate::units::components`]), as its state's margins are; the rates are the one mode's.
fn sliding_at_the_limit(
    pairs: &mut [PairResult],
    friction: &[f64],
    mode: &[(f64, f64)],
    part: &[usize],
) {
    let top = mode
        .iter()
        .fold(0.0f64, |a, &(n, t)| a.max(n.abs()).max(t.abs()));
    let force =
        crate::units::largest_by_part(part, 0.0, |i| pairs[i].x_n.abs().max(pairs[i].x_t.abs()));
    for (((r, &f), &(_, dz_t)), &c) in pairs.iter_mut().zip(friction).zip(mode).zip(part) {
        if r.state != PairState::Stick || dz_t.abs() <= 1e-9 * top {
            continue;
        }
        // the friction force opposes the slip: slip + with x_t = −f·x_n
        let limit = -dz_t.signum() * f * r.x_n;
        if (r.x_t - limit).abs() <= 1e-8 * force[c] {
            r.state = if dz_t > 0.0 {
                PairState::SlipPlus
            } else {
                PairState::SlipMinus
            };
        }
    }
}

/// Pair results from the LCP's `x` and `z` (both `3m` long, `[n; t+; t-]` blocks): `m` pairs,
/// pair `i` named `names[i]` (`names` has one name a pair; a pair without one is left
/// unnamed).
///
/// Round-off is judged relative to the largest force and displacement of the solution itself;
/// [`crate::solve`] judges it relative to the scale of the data as well.
pub fn pair_results(x: &[f64], z: &[f64], names: &[String]) -> Vec<PairResult> {
    let m = x.len() / 3;
    pair_results_scaled(x, z, names, &vec![(0.0, 0.0); m], 0.0, &vec![0; m], &[])
}

/// Pair results with round-off judged relative to `max(‖x‖∞, force_scale[i])` for the forces of
/// pair `i` (`force_scale` one a pair: the scales of its normal and its tangential force, the
/// loads of its own rows) and `max(‖z‖∞, displacement_scale)` for its displacements, the
/// norms over the pairs of its part of the zone (`part`, [`crate::units::components`]): a
/// normal force of `4e-16` in a zone whose loads are of order one is round-off of zero, and the
/// pair is open (touching), not stuck; a force of 400 N is none beside another structure's
/// 1e12 N. Where `friction` is given (one a pair), a pair whose `f·x_n` is zero carries no
/// tangential force. The pairs are named by `names` (left unnamed where it has no name: empty for all).
fn pair_results_scaled(
    x: &[f64],
    z: &[f64],
    names: &[String],
    force_scale: &[(f64, f64)],
    displacement_scale: f64,
    part: &[usize],
    friction: &[f64],
) -> Vec<PairResult> {
    let m = x.len() / 3;
    // The forces of the pairs, not the friction rows `f·x_n ± x_t` (a friction coefficient of
    // 1e10 would make every normal force round-off of those), and their displacements, the
    // largest of each part.
    let forces = crate::units::largest_by_part(part, 0.0, |i| {
        x[i].abs().max(((x[m + i] - x[2 * m + i]) / 2.0).abs())
    });
    let zmax = crate::units::largest_by_part(part, displacement_scale, |i| {
        z[i].abs().max(z[m + i].abs()).max(z[2 * m + i].abs())
    });
    (0..m)
        .map(|i| {
            let (forces, tz) = (forces[part[i]], 1e-9 * zmax[part[i]]);
            // A pair's forces are judged against its part's forces and its own loads, not
            // another pair's: a load that no pair carries as a force (a push that only slides
            // a frictionless pair) is no scale of their round-off.
            let (xn_max, xt_max) = (forces.max(force_scale[i].0), forces.max(force_scale[i].1));
            let (tx, txt) = (1e-9 * xn_max, 1e-9 * xt_max);
            // A normal force or opening below zero by round-off is zero (`x_n, z_n ≥ 0`).
            let x_n = if x[i] < 0.0 && -x[i] <= tx { 0.0 } else { x[i] };
            let x_t = (x[m + i] - x[2 * m + i]) / 2.0;
            let z_n = if z[i] < 0.0 && -z[i] <= tz { 0.0 } else { z[i] };
            let z_t = (z[m + i] - z[2 * m + i]) / 2.0;
            let state = if z_n > tz || x_n <= tx {
                PairState::Open
            } else if z[m + i] > tz && z[m + i] > z[2 * m + i] {
                PairState::SlipPlus
            } else if z[2 * m + i] > tz {
                PairState::SlipMinus
            } else {
                PairState::Stick
            };
            // Round-off of the friction rows of an open pair is not a force. Its normal force
            // is kept (a stopper carrying 3 N beside gap forces of 1e11 reads open by the
            // states' margin, but its force is real and the structure's balance needs it),
            // unless it is round-off of the data itself (64 ε of the scale).
            let x_t = if state == PairState::Open && x_t.abs() <= txt {
                0.0
            } else {
                x_t
            };
            let x_n = if state == PairState::Open && x_n <= 64.0 * f64::EPSILON * xn_max {
                0.0
            } else {
                x_n
            };
            // Where `f·x_n` is zero (a frictionless pair, or one that carries no normal force)
            // the friction law allows no tangential force: what the solve left there is
            // round-off of the terms that formed it (of metres of another pair's slip times
            // its stiffness: 7e-4 N on an open pair beside a slide of 8e9 m, in one unit and
            // not the other).
            let x_t = if friction.get(i).is_some_and(|&f| f * x_n == 0.0) {
                0.0
            } else {
                x_t
            };
            PairResult {
                name: names.get(i).cloned().unwrap_or_default(),
                x_n,
                x_t,
                z_n,
                z_t,
                state,
            }
        })
        .collect()
}

/// Columns of the traced values formed by one task ([`zone_products`]): a fixed number, so
/// that the tasks, and the bits, do not depend on the number of threads.
const PRODUCT_COLUMNS: usize = 32;

/// The pairs whose `z_n` (first) and whose `z_t` (second) are not zero at some breakpoint of
/// the path: the only columns of the zone's blocks the traced values need. On the 1000-bearing
/// beam of the benchmark 607 and 627 of 1000 (a pair's `z` is zero while it sticks closed, for
/// most of a path): the products with the blocks, the frames' largest cost, shrink by as
/// much. Found from the whole path, not from the breakpoints asked for, so that the sums (and
/// their last bits) of a breakpoint's values do not depend on which others are asked with it.
fn active_columns(bps: &[Breakpoint], m: usize) -> [Vec<usize>; 2] {
    let (mut on_n, mut on_t) = (vec![false; m], vec![false; m]);
    for b in bps {
        for &(i, v) in &b.z {
            if v != 0.0 {
                match i / m {
                    0 => on_n[i] = true,
                    _ => on_t[i % m] = true,
                }
            }
        }
    }
    let list = |on: Vec<bool>| {
        on.iter()
            .enumerate()
            .filter(|(_, &a)| a)
            .map(|(j, _)| j)
            .collect()
    };
    [list(on_n), list(on_t)]
}

/// `(R_nn·Z_n + R_nt·W, R_tn·Z_n + R_tt·W)` with the blocks' columns and the rows of `Z_n` and
/// `W` restricted to `active` ([`active_columns`]: the rows left out are zero in every column),
/// a task of [`PRODUCT_COLUMNS`] columns at a time on the thread pool (the last task takes the
/// remainder, never a lone column after others: faer forms the product with one column by
/// another kernel, whose sums may differ in their last bits). A column's sums are those of the
/// product with its task's columns.
fn zone_products(
    zone: &ContactZone,
    zn: &faer::Mat<f64>,
    w: &faer::Mat<f64>,
    active: &[Vec<usize>; 2],
) -> (faer::Mat<f64>, faer::Mat<f64>) {
    use rayon::prelude::*;
    use std::borrow::Cow;
    let (m, k) = (zn.nrows(), zn.ncols());
    // Where at most three quarters of the pairs are active, the blocks' active columns and the
    // active rows of `Z_n` and `W` are gathered once a call (copies of the blocks' size
    // against products `PRODUCT_COLUMNS` times it), one pair of blocks at a time (the normal
    // rows, then the tangential ones: half the blocks held twice at once).
    let gathered = |on: &[usize]| 4 * on.len() <= 3 * m;
    let rows = |a: &'_ faer::Mat<f64>, on: &[usize]| -> faer::Mat<f64> {
        faer::Mat::from_fn(on.len(), a.ncols(), |i, j| a[(on[i], j)])
    };
    let cols = |a: &faer::Mat<f64>, on: &[usize]| -> faer::Mat<f64> {
        faer::Mat::from_fn(a.nrows(), on.len(), |i, j| a[(i, on[j])])
    };
    let [an, at] = active;
    let (zn, w): (Cow<faer::Mat<f64>>, Cow<faer::Mat<f64>>) = (
        if gathered(an) {
            Cow::Owned(rows(zn, an))
        } else {
            Cow::Borrowed(zn)
        },
        if gathered(at) {
            Cow::Owned(rows(w, at))
        } else {
            Cow::Borrowed(w)
        },
    );
    let (zn, w): (&faer::Mat<f64>, &faer::Mat<f64>) = (&zn, &w);
    let mut starts: Vec<usize> = (0..k).step_by(PRODUCT_COLUMNS).collect();
    if starts.len() > 1 && k - starts[starts.len() - 1] == 1 {
        starts.pop();
    }
    // `R_zn·Z_n + R_zt·W` for one pair of blocks.
    let side = |r_n: &faer::Mat<f64>, r_t: &faer::Mat<f64>| -> faer::Mat<f64> {
        let r_n: Cow<faer::Mat<f64>> = if gathered(an) {
            Cow::Owned(cols(r_n, an))
        } else {
            Cow::Borrowed(r_n)
        };
        let r_t: Cow<faer::Mat<f64>> = if gathered(at) {
            Cow::Owned(cols(r_t, at))
        } else {
            Cow::Borrowed(r_t)
        };
        let (r_n, r_t): (&faer::Mat<f64>, &faer::Mat<f64>) = (&r_n, &r_t);
        let parts: Vec<(usize, faer::Mat<f64>)> = starts
            .par_iter()
            .enumerate()
            .map(|(i, &a)| {
                let b = starts.get(i + 1).copied().unwrap_or(k);
                let (zc, wc) = (zn.as_ref().subcols(a, b - a), w.as_ref().subcols(a, b - a));
                (a, product(r_n.as_ref(), zc) + product(r_t.as_ref(), wc))
            })
            .collect();
        let mut out = faer::Mat::zeros(m, k);
        for (a, c) in parts {
            out.as_mut().subcols_mut(a, c.ncols()).copy_from(&c);
        }
        out
    };
    let normal = side(&zone.rnn, &zone.rnt);
    let tangential = side(&zone.rtn, &zone.rtt);
    (normal, tangential)
}

/// `a·b` on one thread, whatever faer's global parallelism: faer's parallel product of a matrix
/// and one column splits the sums by thread, so its last bits would depend on the number of
/// threads (a block of breakpoints with one step, m ≥ 256).
fn product(a: faer::MatRef<'_, f64>, b: faer::MatRef<'_, f64>) -> faer::Mat<f64> {
    let mut out = faer::Mat::zeros(a.nrows(), b.ncols());
    faer::linalg::matmul::matmul(
        out.as_mut(),
        faer::Accum::Replace,
        a,
        b,
        1.0,
        faer::Par::Seq,
    );
    out
}

/// A load for a sentence: six decimals in `[1e-3, 1e7)` (`10.666667`, `2.000000`, `0.001235`:
/// four significant digits at the least), else seven in exponent form (`1.066667e-299`,
/// `1.066667e13`): never `0.000000` for a load that is not zero.
pub(crate) fn load_text(p: f64) -> String {
    if p == 0.0 || (1e-3..1e7).contains(&p.abs()) {
        format!("{p:.6}")
    } else {
        format!("{p:.6e}")
    }
}

/// A number given as data or found on the path, for a sentence: its shortest text, in
/// exponent form outside `[1e-4, 1e7)` (`1e12`, not `1000000000000`; `6.857228015352759e-9`,
/// not `0.000000006857228015352759`; `1000` as it is).
pub fn number_text(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e7).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-written texts: ordinary loads keep six decimals, tiny and huge ones their digits.
    #[test]
    fn loads_in_sentences_keep_their_digits() {
        assert_eq!(load_text(32.0 / 3.0), "10.666667");
        assert_eq!(load_text(2.0), "2.000000");
        assert_eq!(load_text(0.0), "0.000000");
        assert_eq!(load_text(32.0 / 3.0 * 1e-300), "1.066667e-299");
        assert_eq!(load_text(1.0666666666666666e13), "1.066667e13");
        assert_eq!(load_text(6.857228015352759e-9), "6.857228e-9");
        assert_eq!(number_text(1e12), "1e12");
        assert_eq!(number_text(1000.0), "1000");
        assert_eq!(number_text(0.5), "0.5");
        assert_eq!(number_text(6.857228015352759e-9), "6.857228015352759e-9");
    }

    // Reference: the definition of the states (formulation: open ⇔ no compression). A normal
    // force of 4e-16 in a zone whose forces are of order one is round-off of zero: the pair
    // touches without force (open/grazing), it does not stick.
    #[test]
    fn round_off_compression_is_open_not_stick() {
        let names = vec!["1".to_string()];
        let x = [4e-16, 0.0, 0.0];
        let z = [0.0; 3];
        assert_eq!(
            pair_results_scaled(&x, &z, &names, &[(1.0, 1.0)], 1.0, &[0], &[])[0].state,
            PairState::Open
        );
        // A normal force below zero by round-off reads as zero, not as a tension.
        let x = [-8.67e-19, 0.0, 0.0];
        let r = &pair_results_scaled(&x, &z, &names, &[(1.0, 1.0)], 1.0, &[0], &[])[0];
        assert_eq!(
            (r.state, r.x_n.to_bits()),
            (PairState::Open, 0.0f64.to_bits())
        );
        // A real compression of the zone's scale sticks.
        let x = [0.5, 0.2, 0.2];
        assert_eq!(
            pair_results_scaled(&x, &z, &names, &[(1.0, 1.0)], 1.0, &[0], &[])[0].state,
            PairState::Stick
        );
    }

    #[test]
    fn traced_values_of_a_pair_with_a_huge_friction_coefficient_stay_finite() {
        // Example 1 with f = 1.797e308 at pair 3 (the corpus's mutant), c = 1: before its one
        // event (p = 32/3, pair 1 opens) every pair is closed and sticks with z = 0, so by
        // hand x_n = c + p·d_n = (0, 25/3, 16/3) there and x_t = 0, although the LCP's rows
        // x_t± = f·x_n ± x_t of pair 3 are beyond the floating-point range.
        use crate::{solve, Follow};
        let zone = example1_zone(vec![0.6, 0.6, f64::MAX]);
        let settings = SolveSettings {
            tightening: 1.0,
            follow: Follow::ToEnd,
            ..Default::default()
        };
        let sol = solve(&zone, &settings).unwrap();
        assert_eq!(sol.path.breakpoints[1].p, 32.0 / 3.0);
        let got = sol.traced_on_segments(&[(1, 0.0)]).unwrap();
        let (_, pairs) = got[0].as_ref().unwrap();
        for (r, want) in pairs.iter().zip([0.0, 25.0 / 3.0, 16.0 / 3.0]) {
            assert!((r.x_n - want).abs() <= 1e-12 * 25.0 / 3.0, "{r:?}");
            assert_eq!(r.x_t, 0.0, "{r:?}");
            assert_eq!((r.z_n, r.z_t), (0.0, 0.0), "{r:?}");
        }
    }

    /// The paper's Example 1 as a contact zone (its `Rnn`, `Rtt` and variable normal load), with
    /// the given friction coefficients.
    fn example1_zone(friction: Vec<f64>) -> crate::ContactZone {
        let mut zone = crate::ContactZone::new(
            faer::mat![
                [0.1875, -0.375, 0.1875],
                [-0.375, 0.75, -0.375],
                [0.1875, -0.375, 0.1875]
            ],
            faer::mat![[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]],
        );
        zone.friction = friction;
        zone.variable.normal = vec![-0.09375, 0.6875, 0.40625];
        zone
    }

    // Reference: brute-force enumeration (unilateral-oracle) of the tightened LCP
    // x = (q_c + c·t) + p·d + M z of the paper's Example 1 (the doc example of `solve`), at the
    // middle of every segment of the traced path and at every breakpoint: the traced values
    // must be one of its solutions (the traced path is a path of solutions of that LCP), and
    // with c = 1 they differ from the problem's own solution (pair 1 is pressed by c).
    #[test]
    fn traced_values_solve_the_tightened_lcp() {
        use crate::{solve, Follow};
        let zone = example1_zone(vec![0.6; 3]);
        let c = 1.0;
        let settings = SolveSettings {
            tightening: c,
            follow: Follow::ToEnd,
            ..Default::default()
        };
        let sol = solve(&zone, &settings).unwrap();
        let lcp = &sol.lcp().problem;
        let n = lcp.q0.len();
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| lcp.m[(i, j)]).collect())
            .collect();
        let q0c: Vec<f64> = (0..n)
            .map(|i| lcp.q0[i] + c * sol.lcp().tightening_direction[i])
            .collect();
        let k = sol.path.breakpoints.len();
        assert!(k >= 2, "the example has events");
        let mut at: Vec<(usize, f64)> = (0..k).map(|j| (j, 0.0)).collect();
        at.extend((0..k - 1).map(|j| (j, 0.5)));
        let got = sol.traced_on_segments(&at).unwrap();
        for ((kk, s), v) in at.iter().zip(&got) {
            let (p, pairs) = v.as_ref().expect("on the path");
            let sols = unilateral_oracle::enumerate_parametric(&m, &q0c, &lcp.d, *p);
            assert!(!sols.is_empty());
            let scale = 1.0;
            let hit = sols.iter().any(|e| {
                let (w, z) = (e.w_f64(), e.z_f64());
                let want = pair_results(&w, &z, &sol.engine.names);
                want.iter().zip(pairs).all(|(a, b)| {
                    [a.x_n - b.x_n, a.x_t - b.x_t, a.z_n - b.z_n, a.z_t - b.z_t]
                        .iter()
                        .all(|d| d.abs() <= 1e-9 * scale)
                })
            });
            assert!(
                hit,
                "segment {kk} at {s}: p = {p}: {pairs:?} is no solution of the tightened LCP"
            );
        }
        // The tightened start presses every pair with c: x_n = c at p = 0.
        let (_, start) = got[0].as_ref().unwrap();
        assert!(start.iter().all(|r| (r.x_n - c).abs() <= 1e-12));
        // Loads: a load inside the first segment answers, one beyond the path does not.
        let p1 = sol.path.breakpoints[1].p;
        let many = sol.traced_at_many(&[0.5 * p1, 1e9 * p1.max(1.0)]).unwrap();
        assert!(many[0].is_some() && many[1].is_none());
        assert_eq!(many[0].as_ref().unwrap(), &got[k].as_ref().unwrap().1);
    }
}
