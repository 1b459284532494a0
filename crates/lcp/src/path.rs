//! The load path of a parametric LCP: how far it is followed, how it ended, its steps and
//! breakpoints, and the solutions read from it.

use crate::{LcpStatus, Residual, SettingsError, Var};

/// How far the path is followed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Follow {
    /// Stop when `p` reaches the target (Criterion 1).
    #[default]
    ToTarget,
    /// Follow the path until a ray, a mechanism, a return to `p = 0` or the pivot cap.
    ToEnd,
}

/// An artificial tightening `c·direction` added to `q0` so that the start is feasible; it is
/// removed from every reported solution.
#[derive(Debug, Clone, PartialEq)]
pub struct Tightening {
    /// The amount `c ≥ 0`.
    pub amount: f64,
    /// The direction (all entries `≥ 0`), e.g. all ones.
    pub direction: Vec<f64>,
}

/// Options of a path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathOptions {
    /// The target load `p* > 0` at which the solution is reported.
    pub target: f64,
    /// How far the path is followed.
    pub follow: Follow,
    /// Optional artificial tightening.
    pub tightening: Option<Tightening>,
}

impl PathOptions {
    /// Checks a target load: a finite number `> 0`.
    pub fn check_target(target: f64) -> Result<(), SettingsError> {
        // A subnormal target (below 2.2e-308) carries fewer digits than a load needs.
        if target.is_finite() && target >= f64::MIN_POSITIVE {
            Ok(())
        } else {
            Err(SettingsError::Target(target))
        }
    }
}

impl Tightening {
    /// Checks a tightening amount: a finite number `≥ 0`.
    pub fn check_amount(amount: f64) -> Result<(), SettingsError> {
        if amount.is_finite() && amount >= 0.0 {
            Ok(())
        } else {
            Err(SettingsError::Tightening(amount))
        }
    }
}

impl Default for PathOptions {
    fn default() -> Self {
        Self {
            target: 1.0,
            follow: Follow::ToTarget,
            tightening: None,
        }
    }
}

/// How the traced path ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathStatus {
    /// `p` reached the target (Criterion 1).
    TargetReached,
    /// The entering column has no positive entry and `p` grows without bound: the basis (the
    /// working scheme) no longer changes for larger `p` (Criterion 2a).
    Ray,
    /// The entering variable grows without bound while `p` stays fixed: a mechanism forms at
    /// `p_limit` (Criterion 2b).
    Mechanism,
    /// `p` left the basis: the path came back to `p = 0`.
    ReturnedToZero,
    /// The pivot cap was reached.
    IterationLimit,
    /// The problem at `p = 0` has no solution that Lemke's method (with fallbacks) finds.
    NoSolutionAtStart,
    /// A basis became numerically singular.
    NumericalFailure,
}

impl PathStatus {
    /// The status as written in result files.
    pub fn as_str(&self) -> &'static str {
        match self {
            PathStatus::TargetReached => "target_reached",
            PathStatus::Ray => "ray",
            PathStatus::Mechanism => "mechanism",
            PathStatus::ReturnedToZero => "returned_to_zero",
            PathStatus::IterationLimit => "iteration_limit",
            PathStatus::NoSolutionAtStart => "no_solution_at_start",
            PathStatus::NumericalFailure => "numerical_failure",
        }
    }
}

/// One pivot of the path: one change of the working scheme.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// 1-based step number.
    pub index: usize,
    /// The load parameter after the step (with the tightening, as traced).
    pub p: f64,
    /// The variable that entered the basis.
    pub entering: Var,
    /// The variable that left the basis.
    pub leaving: Var,
    /// `p` decreased at this step: a turning point of the load path.
    pub turning: bool,
}

/// The basic variables (`x_i` as `i`, `z_i` as `n + i`, the driver `2n`) after the first `k`
/// of `steps`, from the slack basis.
pub fn basic_after(steps: &[Step], k: usize, n: usize) -> Vec<bool> {
    let col = |v: Var| match v {
        Var::X(i) => i,
        Var::Z(i) => n + i,
        Var::Driver => 2 * n,
    };
    let mut basic: Vec<bool> = (0..=2 * n).map(|v| v < n).collect();
    for s in &steps[..k] {
        basic[col(s.entering)] = true;
        basic[col(s.leaving)] = false;
    }
    basic
}

/// The first step (0-based) at which two paths pivot differently, or the shorter one's length
/// where one continues the other; `None` when they take the same pivots.
pub fn first_different_step(a: &[Step], b: &[Step]) -> Option<usize> {
    a.iter()
        .zip(b)
        .position(|(x, y)| (x.entering, x.leaving) != (y.entering, y.leaving))
        .or((a.len() != b.len()).then(|| a.len().min(b.len())))
}

/// A solution on the path, free of any tightening, verified from the original data.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// The load parameter.
    pub p: f64,
    /// `x = q0 + p·d + M z`.
    pub x: Vec<f64>,
    /// `z`.
    pub z: Vec<f64>,
    /// Residuals from the original data.
    pub residual: Residual,
    /// How the tightening was removed: `0` when the path's basis was already feasible without it,
    /// else the number of pivots with the tightening as driving variable.
    pub tightening_pivots: usize,
    /// The solution had to be found by a fresh standard solve at this `p` (the path's basis could
    /// not be freed of the tightening); it may lie on another branch when solutions are not unique.
    pub fallback: bool,
}

/// Why no solution is reported at a load where the path should give one
/// ([`LoadPath::unreported`]): what the path's own basis gave there, evaluated afresh from the
/// data, and how a fresh standard solve at that load ended. Every reported solution is
/// verified; this says what was tried instead of a bare "none".
#[derive(Debug, Clone, PartialEq)]
pub struct Unreported {
    /// The load at which the solution was sought.
    pub p: f64,
    /// The path's basis at `p`, without the tightening.
    pub path_basis: BasisVerdict,
    /// How the fresh standard solve at `p` (Lemke's method with its fallbacks) ended: never
    /// [`LcpStatus::Solved`] here; `None` when it stopped on invalid data.
    pub fresh: Option<LcpStatus>,
}

/// What the path's basis gave at a load where it gives no verified solution.
#[derive(Debug, Clone, PartialEq)]
pub enum BasisVerdict {
    /// The basis matrix formed from the data is numerically singular (or the path records no
    /// complementary basis on that segment).
    Singular,
    /// A basic variable of the basis is negative beyond round-off: the basis is not a solution
    /// at this load (the traced path passed an event that the data put before it, or the
    /// tightening was not removed to a feasible basis).
    Negative {
        /// The variable (`X` a component of `x = q + M z`, `Z` one of `z`).
        var: Var,
        /// Its value, in the units of the problem.
        value: f64,
        /// The largest magnitude among the variables of its kind (`x` or `z`) there.
        largest: f64,
    },
    /// The tightening could not be driven to zero at this load: the drive stopped after this
    /// many pivots (on a ray, the pivot cap or a singular basis).
    TighteningNotRemoved {
        /// Pivots made before the drive stopped.
        pivots: usize,
    },
    /// A point was formed but its residuals exceed the acceptance ([`crate::ACCEPT_RESIDUAL`]).
    Unverified {
        /// The residuals from the data.
        residual: Residual,
    },
}

/// The direction in which a mechanism moves (Criterion 2b), normalised to `max |dz| = 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismMode {
    /// The variable that grows without bound.
    pub entering: Var,
    /// Rate of `z`.
    pub dz: Vec<f64>,
    /// Rate of `x`.
    pub dx: Vec<f64>,
}

/// A breakpoint of the traced path: the load and the non-zero `z` there (with the tightening).
#[derive(Debug, Clone, PartialEq)]
pub struct Breakpoint {
    /// Load parameter.
    pub p: f64,
    /// Non-zero entries of `z`, `(index, value)`.
    pub z: Vec<(usize, f64)>,
}

/// The whole load path of a parametric LCP.
#[derive(Debug, Clone)]
pub struct LoadPath {
    /// How the traced path ended.
    pub status: PathStatus,
    /// Every pivot, in order.
    pub steps: Vec<Step>,
    /// The start (index 0) and the point after every step.
    pub breakpoints: Vec<Breakpoint>,
    /// The largest `p` reached on the traced path.
    pub p_max: f64,
    /// The limit load for [`PathStatus::Mechanism`].
    pub p_limit: Option<f64>,
    /// The mechanism's direction for [`PathStatus::Mechanism`].
    pub mechanism: Option<MechanismMode>,
    /// The variable entering on the last segment (for a ray: the one that grows without bound).
    pub last_entering: Option<Var>,
    /// The reported solution (at the target when it lies on the path, else at the end of the
    /// path), without the tightening.
    pub solution: Option<PathPoint>,
    /// Pivots of the standard Lemke solve at `p = 0` when `q0` was not feasible.
    pub start_pivots: usize,
    /// Fresh factorisations of the basis during the path.
    pub refactorizations: usize,
    /// Set when the path traced with an artificial tightening ended in a mechanism at this load
    /// although the real problem (without tightening) has a solution at the target: the
    /// mechanism belongs to the tightening, not to the structure. The status is then
    /// [`PathStatus::TargetReached`] and the solution comes from a fresh solve at the target
    /// (`fallback` is set on it).
    pub artificial_mechanism: Option<f64>,
    /// Why there is no [`LoadPath::solution`] although the path has a load to report it at
    /// (`None` when there is a solution, or when the ending has no such load: a numerical failure
    /// of the path itself, no solution at the start).
    pub unreported: Option<Unreported>,
    /// A mechanism at `p = 0` whose state there carries no force: every value of the path's
    /// state at `p = 0` is round-off of the terms that form it (no constant load reaches the
    /// pairs, or one too small to resolve against the gaps' terms): the structure's position
    /// is not determined there, and no state is reported.
    pub unloaded_at_start: bool,
    pub(crate) start_slots: Vec<usize>,
    pub(crate) records: Vec<(usize, usize)>,
    /// The segments (by the number of pivots before them) whose direction, and whose points,
    /// come from the structure's equations ([`crate::StructureJudge`]): the load's rate there
    /// is genuine but below what the condensed `M` can tell from round-off.
    pub(crate) judged_load_segments: Vec<usize>,
    /// The number of steps made before the load first reached the target (the target lies on
    /// the segment after that many pivots), if it did.
    pub target_segment: Option<usize>,
}

impl LoadPath {
    /// `z` on the traced path (with the tightening) at load `p`, by linear interpolation between
    /// the first pair of consecutive breakpoints whose loads bracket `p`.
    pub fn traced_z_at(&self, p: f64, n: usize) -> Option<Vec<f64>> {
        for w in self.breakpoints.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let (lo, hi) = if a.p <= b.p { (a.p, b.p) } else { (b.p, a.p) };
            if p >= lo && p <= hi && hi > lo {
                let s = (p - a.p) / (b.p - a.p);
                let mut z = vec![0.0; n];
                for &(i, v) in &a.z {
                    z[i] += (1.0 - s) * v;
                }
                for &(i, v) in &b.z {
                    z[i] += s * v;
                }
                return Some(z);
            }
        }
        None
    }

    /// Total pivots of the path (without the start and the tightening removal).
    pub fn pivots(&self) -> usize {
        self.steps.len()
    }

    /// The basis at the end of the traced path (tableau rows → column: `x_i` is `i`, `z_i` is
    /// `n + i`, the driver `2n`), the start of a continuation (see [`crate::PathSolver`]).
    pub(crate) fn final_slots(&self) -> Vec<usize> {
        self.slots_after(self.records.len())
    }

    /// The last segment whose traced loads contain `p` and along which `p` moves.
    pub(crate) fn last_segment_containing(&self, p: f64) -> Option<usize> {
        let bps = &self.breakpoints;
        (0..bps.len().saturating_sub(1)).rev().find(|&j| {
            let (a, b) = (bps[j].p, bps[j + 1].p);
            let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
            hi > lo && p >= lo - 1e-12 * hi.abs().max(1.0) && p <= hi + 1e-12 * hi.abs().max(1.0)
        })
    }

    /// The order `n` of the problem whose path this is.
    pub(crate) fn order(&self) -> usize {
        self.start_slots.len()
    }

    /// Slots (tableau rows → column) after `k` pivots.
    pub(crate) fn slots_after(&self, k: usize) -> Vec<usize> {
        let mut slots = self.start_slots.clone();
        let mut pos = vec![usize::MAX; 2 * slots.len() + 1];
        for (s, &v) in slots.iter().enumerate() {
            pos[v] = s;
        }
        for &(e, l) in self.records.iter().take(k) {
            let s = pos[l];
            slots[s] = e;
            pos[l] = usize::MAX;
            pos[e] = s;
        }
        slots
    }

    /// Entering column of segment `k` (the segment after `k` pivots), if known.
    pub(crate) fn segment_entering(&self, k: usize, n: usize) -> Option<usize> {
        if k == 0 {
            return Some(2 * n);
        }
        let (_, leaving) = *self.records.get(k - 1)?;
        if leaving == 2 * n {
            return None;
        }
        Some(if leaving < n {
            leaving + n
        } else {
            leaving - n
        })
    }
}
