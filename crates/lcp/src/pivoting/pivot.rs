//! Complementary pivoting with one driving variable, shared by the standard and the
//! parametric Lemke methods.

use crate::pivoting::basis::{Basis, SingularBasis};
use crate::pivoting::columns::Columns;
use crate::pivoting::relations::Relations;
use crate::pivoting::simd::axpy;

/// Numerical thresholds, all relative to the (equilibrated) data.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tolerances {
    /// An entry of the entering column is positive if it exceeds `pivot · ‖α‖∞`.
    pub pivot: f64,
    /// Basic values within `value · scale` of zero are zero.
    pub value: f64,
}

/// The structure's own equations with the equilibration that maps their variables to the
/// tableau's ([`Pivoter::judge`]).
#[derive(Debug, Clone)]
pub(crate) struct Judging {
    pub judge: std::sync::Arc<crate::StructureJudge>,
    /// The rows' and columns' scales of the equilibration (`x̂ = E x`, `z = D ẑ`).
    pub row: Vec<f64>,
    pub col: Vec<f64>,
    /// Row relations that decide the ties of a judged step where the pivoter has none of its
    /// own ([`Pivoter::relations`]: a load history's stages).
    pub relations: Option<std::sync::Arc<Relations>>,
}

/// A segment judged on the structure's equations ([`Pivoter::judged_step`]).
#[derive(Debug, Clone)]
pub(crate) struct JudgedStep {
    /// The direction in the tableau's units (`β` moves by `−θ α`).
    pub alpha: Vec<f64>,
    /// The ratio test's step on it (`None`: nothing blocks within double precision).
    pub step: Option<Choice>,
    /// The load has a rate beyond the round-off of the structure's equations (in `alpha`);
    /// else it is held (its rate zero).
    pub genuine: bool,
}

impl JudgedStep {
    /// The load's rate on the judged direction (the driver's in slot `ds`, the negated rate of
    /// its value): `alpha`'s where it is genuine, zero where the load is held.
    pub fn load_rate(&self, ds: Option<usize>) -> f64 {
        match (self.genuine, ds) {
            (true, Some(ds)) => -self.alpha[ds],
            _ => 0.0,
        }
    }
}

/// One pivot as recorded on the path.
#[derive(Debug, Clone)]
pub(crate) struct PivotRecord {
    pub entering: usize,
    pub leaving: usize,
    /// Value of the driver after the pivot (0 when it left).
    pub driver: f64,
    /// Basic `z` variables after the pivot, as `(index, value)` in the scaled space.
    pub z: Vec<(usize, f64)>,
}

/// How a run of complementary pivots ended.
#[derive(Debug, Clone)]
pub(crate) enum Ending {
    /// The driver left the basis (its value is zero).
    DriverLeft,
    /// The driver reaches the target on the segment of the current entering column; no pivot
    /// was made.
    TargetReached,
    /// The entering column has no positive entry: the entering variable grows without bound.
    Ray { alpha: Vec<f64> },
    /// The pivot cap was hit.
    IterationLimit,
    /// The basis could not be factorised (numerically singular).
    Singular,
}

/// The ratio test's choice: the leaving slot and the step length.
pub(crate) type Choice = (usize, f64);

/// Relative size of a tie in the ratio test.
const TIE: f64 = 1e-9;

/// Entries of an entering column within this fraction of its largest are round-off of the
/// column, however small their own terms (used where a ray's direction is verified).
const ROUNDOFF: f64 = 1e-14;

/// Candidates within this fraction of the minimum ratio are re-judged on refreshed basic values.
const NEAR_TIE: f64 = 1e-7;

/// Candidates within this fraction of the minimum ratio are re-judged on a column refined from
/// the data: an entry `10⁻⁶` of the column's largest with a relative error of `10⁻¹²` of that
/// largest is accurate only to `10⁻⁶` of itself.
const UNSURE_TIE: f64 = 1e-4;

/// A rate of an `x` below the column's pivot tolerance that may still be a rate: above this
/// fraction of the column's largest `x` rate (see [`Pivoter::suspects`]), to be judged against
/// its own terms. The starts of slip the column's tolerance hid had 1.5e-5 of it.
const X_RATE: f64 = 1e-9;

/// A row of `x` the ratio test passed over as round-off of its terms ([`Pivoter::suspects`]) is
/// judged on the structure's equations on the load path where its rate is at least this
/// fraction of the column's largest `x` rate: a force falling at the rate of the others, which
/// the condensed data cannot resolve beside slips 1e9 times the strains (a steel block's toe
/// pair on a 300–500 N/m spring: 0.25 and 0.86). The 819 suspects refused on the 1000-bearing
/// beam's path reached 7e-6 of it; judging them all made its solve three times longer.
const HIDDEN_X_RATE: f64 = 1e-4;

/// A step whose load rate is below the column's tolerance is judged on the structure's
/// equations ([`Pivoter::judge`]) only where it would move the basic variables by more than this
/// many times their largest value: a runaway step, as a mechanism's round-off rates make it
/// (the sliding beams of the tests: 1.7e4 to 1e10; a steel block tipping about its toe on a
/// 1000 N/m spring: 8.9, which the path took at 100 and carried the load from 2 to 4; the
/// reviewers' long paths whose load rates are small but genuine: at most 0.02, and judging all
/// of them cost 907 sparse factorisations, four times the path's time).
const RUNAWAY: f64 = 1.0;

/// A direction on which the load's rate and every basic force's rate are below this fraction
/// of the column's largest rate (a displacement's) moves the structure without loading it: a
/// mechanism, or nearly one, whose load rate may be the condensation's round-off although it
/// passes the column's tolerance. Where the load decreases on it and the step carries the load
/// a real way, or where its step runs away ([`RUNAWAY`]) whatever load it carries (round 45), it
/// is judged on the structure's equations whatever its rate ([`Pivoter::near_mechanism`]): a
/// steel block on a spring of 300 N/m tipping about its toe at p = 2 (load rate −1.7e-8 of the
/// column, the forces' rates 3e-8) stepped back to p = 0, a "return to zero"; on 50 N/m
/// (runaway 1e5) it stepped on into a singular basis. In a reviewer's 832 runs of blocks and beams, 2151 such directions were
/// genuine on the structure's equations and none of them took the load back; 52 took the load
/// back, and each was a mechanism there. Judging them all made a 300-bearing beam five times
/// slower (`docs/engine.md`, "Near-mechanisms").
const NEAR_MECHANISM: f64 = 1e-6;

/// A near-mechanism direction ([`NEAR_MECHANISM`]) whose load rate is below this fraction of
/// its forces' rates is judged too: where forces and load change by round-off alone, their
/// ratio is arbitrary, where a spring or a support is loaded it follows the statics. In the
/// reviewer's runs of [`NEAR_MECHANISM`] the genuine directions had forces' rates at most 159
/// times the load's; a beam at its sliding limit (`p* = 2`) 3200 times, where the path went on
/// to a false mechanism at p = 412.7, and a block tipping on a 178 N/m spring 711 times.
const LOAD_BELOW_FORCES: f64 = 300.0;

/// The share of the load reached that a step of [`LOAD_BELOW_FORCES`] must carry the load by to
/// be judged: the beam's step past its limit carried it by 1.9e-3, the tipping block's by
/// 1.2e-2. On a reviewer's block of 960 elements on an inclined spring, 120 such directions
/// moved the load by 1e-7 to 2e-6 of itself; judging each (a sparse factorisation of the
/// structure) made the run six times slower, and changed nothing of its answer.
const LOAD_STEP: f64 = 1e-3;

/// A pivot whose blocking row falls, and whose load moves, at rates below this fraction of the
/// column's largest rate is a candidate for the structure's equations, taken where they find a
/// mechanism there ([`Pivoter::tiny_pivot_mechanism`]). The blocks on soft heel springs that
/// failed had such pivots at 3e-8 to 1.3e-6 of their columns; a 300-bearing beam's path meets
/// 272 pivots below 1e-4, none of them a mechanism.
const TINY_PIVOT: f64 = 1e-4;

/// A [`TINY_PIVOT`] whose load rate passes the column's tolerance is judged only where its step
/// would carry the load by more than this share of the load reached (the blocks' steps: 0.37
/// and 1.0; the 300-bearing beam's: 1e-3 to 0.9, nine above 0.1) ...
const TINY_PIVOT_STEP: f64 = 0.1;

/// ... and where its blocking row's value is below this share of the largest basic value (the
/// blocks' toe forces: 1e-10 and 2e-11 of their slips, round-off of the slips' terms; the
/// beam's nine: 4.5e-9 and more). Both bounds only spare the judge's sparse factorisations
/// (judged at every tiny pivot, the 300-bearing beam ran 3.5 times slower, answering the same).
const TINY_VALUE: f64 = 1e-9;

/// A step that would carry the load by more than this many times the load reached is put to
/// the structure's equations whatever its rates ([`Pivoter::tiny_pivot_mechanism`]): after
/// their tipping, blocks on heel springs of 0.1–10 N/m met steps of `θ` = 1e13 to 1e16 on a
/// slip reversing (the load carried 7e6 to 2.5e11 times beyond itself) and the pivot left a
/// singular basis. None of the benchmark's beams and zones meets one.
const FAR_STEP: f64 = 1e6;

/// A step on the structure's direction that moves the basic variables by more than this many
/// times their largest value of the same kind ([`Pivoter::runaway_by_kind`]) is beyond double
/// precision (the bound of the callers' resolvability check of the links' dislocations against
/// the forces): the mechanism it approaches is the answer. (The direction's decreases within
/// the data's round-off are already zero, `schur/judge.rs`; this bounds what remains.)
const UNRESOLVED: f64 = 1e10;

/// Relative kernel residual above which the basis is refactorised at once.
const DRIFT: f64 = 1e-9;

/// The state of a complementary pivoting run.
pub(crate) struct Pivoter<'a> {
    /// The tableau's columns; owned once the right-hand side moves ([`Pivoter::rebase`]).
    pub cols: std::borrow::Cow<'a, Columns>,
    pub basis: Basis,
    /// Basic values by slot.
    pub beta: Vec<f64>,
    pub tol: Tolerances,
    /// Lexicographic priority of the start basis' slots.
    pub priority: Vec<usize>,
    /// Rank of each row in the priority given at the start (row `i` ↔ variable `x_i`).
    row_rank: Vec<usize>,
    /// The start basis (slot → column) against which lexicographic rows are measured.
    start: Vec<usize>,
    /// The largest entry of the start's structural columns (1 for the slack start).
    start_scale: f64,
    pub refactor_interval: usize,
    since_refactor: usize,
    pub pivots: usize,
    pub refactorizations: usize,
    value_scale: f64,
    /// Kernel residual seen on the last entering column.
    drift: f64,
    /// Pivots since the basic values were last recomputed from the data.
    since_values: usize,
    /// The last ray's direction, checked against the data ([`Pivoter::check_ray`]).
    pub ray_check: Option<RayCheck>,
    /// The structure's own equations, judging doubtful load rates (the load path without a
    /// tightening sets it: [`crate::PathSolver::judged_on`]).
    pub judge: Option<Judging>,
    /// The run ended in a ray because the judge found the segment's direction a mechanism.
    pub judged_mechanism: bool,
    /// The segments (by the number of pivots before them) taken on the structure's direction
    /// where it gives the load a genuine rate the dense data could not tell from round-off (a
    /// block held by a spring 10⁻⁹ of its own stiffness); a point on such a segment is formed
    /// from the structure's equations ([`crate::StructureJudge::point`]).
    pub judged_load_segments: Vec<usize>,
    /// Bumped after every recorded pivot (inert unless a caller sets one: the load path does).
    pub progress: crate::Progress,
    /// Rows the formulation ties exactly (none unless a caller sets them: the load path does).
    pub relations: std::sync::Arc<Relations>,
    /// Whether the relations' `κ = λᵀh` are taken as zero, the data's, rather than read from
    /// a right-hand side that carries round-off (a history's stage, whose right-hand side
    /// absorbed its slips: [`Pivoter::related_candidates_by`]).
    pub zero_kappa: bool,
    /// The column entering at the ratio test under way.
    entering: usize,
    /// For each column of the start basis, its slot's rank in the priority (`usize::MAX`: not
    /// in the start).
    lex_rank: Vec<usize>,
    /// The kernel solve of the next entering column, formed by the last pivot's update
    /// ([`Basis::pivot_solving`]): `(basis version, column, y_S)`.
    next_solve: Option<(u64, usize, Vec<f64>)>,
    /// `K⁻¹ h_R` formed by the last pivot's update for the values of the next entering
    /// column's pass: `(basis version, y_S)`.
    next_values: Option<(u64, Vec<f64>)>,
    /// How often, lately, a tiny pivot made the basic values be recomputed from the data (a
    /// moving average over about sixteen entering columns with drifted values): when it is
    /// high, the values are formed beforehand in the entering column's pass
    /// ([`Pivoter::choose`]).
    refresh_rate: f64,
}

/// A ray's direction checked against the data: the entering variable at rate 1, every basic
/// variable at rate `−α_s`, each row of `x − M z − g·t = h` measured against the terms that form
/// it, and each rate against the terms whose sums formed it (`|K⁻¹| |u|` for the kernel's): the
/// round-off of a row or a rate is that of its own terms, not of the other rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RayCheck {
    /// `max_i |A_e − A_B α|_i` over the size of the terms that form row `i`.
    pub equation: f64,
    /// The largest decrease of a basic variable that the ratio test counted as zero, relative
    /// to the terms that formed its rate.
    pub decrease: f64,
    /// The driver's rate relative to the terms that formed it.
    pub driver_rate: f64,
}

impl RayCheck {
    /// The direction satisfies the equations and keeps every variable non-negative, within
    /// round-off of the data ([`crate::ACCEPT_RESIDUAL`]).
    pub fn verified(&self) -> bool {
        self.equation <= crate::ACCEPT_RESIDUAL && self.decrease <= crate::ACCEPT_RESIDUAL
    }

    /// The driver does not move along the direction, within round-off of the data (2b).
    pub fn driver_fixed(&self) -> bool {
        self.driver_rate <= crate::ACCEPT_RESIDUAL
    }
}

impl<'a> Pivoter<'a> {
    pub fn new(
        cols: &'a Columns,
        basis: Basis,
        tol: Tolerances,
        priority: Vec<usize>,
        refactor_interval: usize,
    ) -> Self {
        let beta = basis.solve(cols, &cols.h);
        let start = basis.slot_var.clone();
        let n = cols.n;
        let mut col = vec![0.0; n];
        let start_scale = start
            .iter()
            .filter(|&&c| c >= n)
            .map(|&c| {
                cols.col_into(c, &mut col);
                max_abs(&col)
            })
            .fold(1.0f64, f64::max);
        let value_scale = max_abs(&cols.h).max(max_abs(&beta)).max(f64::MIN_POSITIVE);
        Self {
            cols: std::borrow::Cow::Borrowed(cols),
            basis,
            beta,
            tol,
            row_rank: {
                let mut r = vec![0; priority.len()];
                for (k, &i) in priority.iter().enumerate() {
                    if i < r.len() {
                        r[i] = k;
                    }
                }
                r
            },
            priority,
            start,
            start_scale,
            refactor_interval: refactor_interval.max(1),
            since_refactor: 0,
            pivots: 0,
            refactorizations: 0,
            value_scale,
            drift: 0.0,
            since_values: 0,
            ray_check: None,
            judge: None,
            judged_mechanism: false,
            judged_load_segments: Vec::new(),
            progress: crate::Progress::default(),
            relations: Default::default(),
            zero_kappa: false,
            entering: usize::MAX,
            lex_rank: Vec::new(),
            next_solve: None,
            next_values: None,
            refresh_rate: 0.0,
        }
        .with_lex_rank()
    }

    /// [`Pivoter::lex_rank`] of the current start and priority.
    fn with_lex_rank(mut self) -> Self {
        self.set_lex_rank();
        self
    }

    fn set_lex_rank(&mut self) {
        let mut rank = vec![usize::MAX; 2 * self.cols.n + 1];
        for (k, &slot) in self.priority.iter().enumerate() {
            if let Some(&c) = self.start.get(slot) {
                rank[c] = k;
            }
        }
        self.lex_rank = rank;
    }

    /// The sign of the first non-zero entry of `λᵀB_start` in the priority order: `λ_i` for a
    /// start slot holding `x_i`, zero for a column of `M` (`λᵀM = 0`), `driver` for the
    /// driver's column.
    fn relation_lex_sign(&self, terms: &[(usize, f64)], driver: i8) -> i8 {
        let d = self.cols.driver();
        let mut best = (usize::MAX, 0i8);
        for &(i, l) in terms {
            let r = self.lex_rank[i];
            if r < best.0 {
                best = (r, if l > 0.0 { 1 } else { -1 });
            }
        }
        if driver != 0 && self.lex_rank[d] < best.0 {
            best = (self.lex_rank[d], driver);
        }
        best.1
    }

    /// The candidates that the row relations `relations` do not exclude
    /// ([`Relations::filter`]); with `h_exact` false the relations' `κ = λᵀh` are taken as
    /// zero (the data's), not read from a right-hand side that carries round-off.
    fn related_candidates_by(
        &self,
        relations: &Relations,
        cand: Vec<usize>,
        h_exact: bool,
    ) -> Vec<usize> {
        if relations.is_empty() {
            return cand;
        }
        let b = &self.basis;
        let n = self.cols.n;
        let driver = self.cols.driver();
        relations.filter(
            cand,
            |s| b.slot_var[s],
            |i| (i < n && b.is_basic(i)).then(|| b.var_slot[i]),
            self.entering,
            driver,
            b.is_basic(driver),
            h_exact.then_some(&self.cols.h[..]),
            &self.cols.g,
            |terms, drv| self.relation_lex_sign(terms, drv),
        )
    }

    fn zero_value(&self) -> f64 {
        self.tol.value * self.value_scale
    }

    pub fn driver_slot(&self) -> Option<usize> {
        let d = self.cols.driver();
        self.basis.is_basic(d).then(|| self.basis.var_slot[d])
    }

    /// Value of the driver now in the columns' units (zero when non-basic).
    pub fn driver_value_scaled(&self) -> f64 {
        self.driver_slot().map_or(0.0, |s| self.beta[s])
    }

    /// Value of the driver now in the caller's units (zero when non-basic).
    pub fn driver_value(&self) -> f64 {
        self.cols.driver_real(self.driver_value_scaled())
    }

    /// Slots whose entry in `alpha` counts as positive.
    fn positive_slots(&self, alpha: &[f64]) -> Vec<usize> {
        let amax = max_abs(alpha);
        let thr = self.tol.pivot * amax;
        (0..alpha.len()).filter(|&i| alpha[i] > thr).collect()
    }

    /// Among tied candidate slots, the lexicographically smallest (or largest) row of
    /// `B⁻¹ B_start / α` in the start's priority order.
    ///
    /// The rows are never formed: the entries are computed one priority column at a time, for
    /// the candidates still tied, so a tie usually costs a few entries. The column of
    /// `B⁻¹ B_start` for a start column `c` is a unit vector while `c` is basic, an entry of
    /// `B⁻¹` (`O(k)` each) when `c` is a slack, and one solve `B⁻¹ A[:, c]` shared by all
    /// candidates when `c` is a structural column that has left the basis. From the slack start
    /// (the tableau of the paper) only the second case occurs.
    fn lex_pick(&self, ties: &[usize], alpha: &[f64], largest: bool) -> usize {
        if ties.len() == 1 {
            return ties[0];
        }
        let n = self.cols.n;
        let mut alive: Vec<(usize, Vec<f64>)> = ties
            .iter()
            .map(|&s| (s, self.basis.inverse_row_data(&self.cols, s)))
            .collect();
        // Entries are equal when they differ by round-off of the terms they are formed from
        // (times the size of the start's structural columns they are applied to). A bound of
        // a whole row (`max |K⁻¹|` times the row's data) would be far coarser: on a long path it
        // merged entries that differ by half their size, and the friction part of a
        // slipping pair left before its normal row (a false mechanism of the 1000-support beam).
        // For a structural start column (solved whole) the bound of the rows stays.
        let coarse = TIE
            * self.start_scale
            * alive
                .iter()
                .map(|(s, data)| self.basis.inverse_row_scale(*s, data) / alpha[*s].abs())
                .fold(0.0f64, f64::max);
        for &r in &self.priority {
            let c = self.start[r];
            // (value, the size of its round-off) for each candidate still tied.
            let vals: Vec<(f64, f64)> = if self.basis.is_basic(c) {
                // A unit column: exact.
                let t = self.basis.var_slot[c];
                alive
                    .iter()
                    .map(|(s, _)| (if *s == t { 1.0 / alpha[*s] } else { 0.0 }, 0.0))
                    .collect()
            } else if c < n {
                let entries = |refined: Option<&[f64]>| -> Vec<(f64, f64)> {
                    alive
                        .iter()
                        .map(|(s, data)| {
                            let (v, t) = match refined {
                                Some(y) if self.basis.slot_var[*s] < n => {
                                    self.basis.slack_entry_terms(*s, c, data, y)
                                }
                                _ => self.basis.inverse_entry_terms(*s, c, data),
                            };
                            let a = alpha[*s];
                            (v / a, TIE * self.start_scale * t / a.abs())
                        })
                        .collect()
                };
                let vals = entries(None);
                // Entries that differ by more than round-off of their terms but less than
                // the bound of the rows may differ only by the drift of the updated inverse:
                // judged again on its column refined from the data.
                let (lo, hi) = vals
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                        (l.min(v.0), h.max(v.0))
                    });
                let fine = vals.iter().fold(0.0f64, |m, v| m.max(v.1));
                let unsure = hi - lo > fine && hi - lo <= coarse;
                match unsure.then(|| self.basis.kernel_column_refined(&self.cols, c)) {
                    Some(Some(y)) => entries(Some(&y)),
                    _ => vals,
                }
            } else {
                let col = self.basis.ftran(&self.cols, c);
                alive
                    .iter()
                    .map(|(s, _)| (col[*s] / alpha[*s], coarse))
                    .collect()
            };
            if vals.iter().all(|&(v, t)| v.abs() <= t) {
                continue;
            }
            let (best, tb) = vals.iter().copied().fold(
                (
                    if largest {
                        f64::NEG_INFINITY
                    } else {
                        f64::INFINITY
                    },
                    0.0,
                ),
                |acc, (v, t)| {
                    if (largest && v > acc.0) || (!largest && v < acc.0) {
                        (v, t)
                    } else {
                        acc
                    }
                },
            );
            let keep: Vec<bool> = vals
                .iter()
                .map(|&(v, t)| (v - best).abs() <= t.max(tb))
                .collect();
            let mut k = keep.iter();
            alive.retain(|_| *k.next().unwrap_or(&false));
            if alive.len() == 1 {
                break;
            }
        }
        alive[0].0
    }

    /// Minimum-ratio test over the positive entries of `alpha`, ties broken lexicographically
    /// (the driver's row wins a tie). Returns the leaving slot and the step length.
    pub fn ratio_test(&self, alpha: &[f64]) -> Option<(usize, f64)> {
        self.ratio_test_over(alpha, self.positive_slots(alpha))
    }

    /// [`Pivoter::ratio_test`] over the given candidate slots (positive entries of `alpha`).
    fn ratio_test_over(&self, alpha: &[f64], cand: Vec<usize>) -> Option<(usize, f64)> {
        self.ratio_test_over_by(&self.relations, alpha, cand, !self.zero_kappa)
    }

    /// [`Pivoter::ratio_test_over`] with the ties of related rows decided by `relations`
    /// (`h_exact`: [`Pivoter::related_candidates_by`]).
    fn ratio_test_over_by(
        &self,
        relations: &Relations,
        alpha: &[f64],
        cand: Vec<usize>,
        h_exact: bool,
    ) -> Option<(usize, f64)> {
        let cand = self.related_candidates_by(relations, cand, h_exact);
        if cand.is_empty() {
            return None;
        }
        let zero = self.zero_value();
        let val = |i: usize| self.beta[i].max(0.0);
        let (mut imin, mut rmin) = (cand[0], f64::INFINITY);
        for &i in &cand {
            let r = val(i) / alpha[i];
            if r < rmin {
                rmin = r;
                imin = i;
            }
        }
        // A tie: stepping by the minimum ratio leaves the row at zero up to round-off, measured
        // relative to the size of the quantities that cancel.
        let ties: Vec<usize> = cand
            .iter()
            .copied()
            .filter(|&i| val(i) - rmin * alpha[i] <= TIE * (val(i) + rmin * alpha[i]) + zero)
            .collect();
        if ties.len() <= 1 {
            return Some((imin, rmin));
        }
        if let Some(d) = self.driver_slot() {
            if ties.contains(&d) {
                return Some((d, rmin));
            }
        }
        let pick = self.lex_pick(&ties, alpha, false);
        Some((pick, val(pick) / alpha[pick]))
    }

    /// The candidates within `window` (relative) of the minimum ratio at `slot`, `slot`
    /// included, when there is more than one: a tie that drift of the updated basic values
    /// ([`NEAR_TIE`]) or round-off of the column ([`UNSURE_TIE`]) could misjudge.
    fn near_ties(&self, alpha: &[f64], slot: usize, window: f64) -> Vec<usize> {
        let val = |i: usize| self.beta[i].max(0.0);
        let rmin = val(slot) / alpha[slot];
        let thr = self.tol.pivot * max_abs(alpha);
        let zero = self.zero_value();
        let close: Vec<usize> = (0..alpha.len())
            .filter(|&i| {
                alpha[i] > thr
                    && val(i) - rmin * alpha[i] <= window * (val(i) + rmin * alpha[i]) + zero
            })
            .collect();
        if close.len() > 1 {
            close
        } else {
            Vec::new()
        }
    }

    /// Lemke's first step: the driver enters at the row that makes the basis feasible, the
    /// lexicographically largest `β_i/α_i` over `α_i < 0`. Returns the slot, or `None` when the
    /// basis is already feasible.
    pub fn lemke_first_slot(&self, alpha: &[f64]) -> Option<usize> {
        let zero = self.zero_value();
        let cand: Vec<usize> = (0..alpha.len())
            .filter(|&i| alpha[i] < 0.0 && self.beta[i] < -zero)
            .collect();
        if cand.is_empty() {
            return None;
        }
        let mut rmax = f64::NEG_INFINITY;
        for &i in &cand {
            rmax = rmax.max(self.beta[i] / alpha[i]);
        }
        let ties: Vec<usize> = cand
            .iter()
            .copied()
            .filter(|&i| (self.beta[i] - rmax * alpha[i]).abs() <= zero)
            .collect();
        let ties = if ties.is_empty() {
            vec![cand
                .iter()
                .copied()
                .max_by(|&a, &b| (self.beta[a] / alpha[a]).total_cmp(&(self.beta[b] / alpha[b])))
                .unwrap_or(cand[0])]
        } else {
            ties
        };
        Some(self.lex_pick(&ties, alpha, true))
    }

    /// Pivots `entering` into `slot` with step length `theta`.
    pub fn pivot(
        &mut self,
        entering: usize,
        slot: usize,
        theta: f64,
        alpha: &[f64],
    ) -> Result<usize, SingularBasis> {
        self.pivot_updating(entering, slot, theta, alpha, alpha)
    }

    /// [`Pivoter::pivot`] on a step judged on the structure's own equations: the values move
    /// along the judged direction `alpha` to the step's end, the basis's inverse is updated
    /// with the entering column as the data it represents give it (`own`, the direction the
    /// pivoting formed), and the values are then formed afresh from the data, as a
    /// refactorisation would form them: `O(n·k + k²)` against its `O(k³)` in the kernel's
    /// order `k` (the 2000-bearing beam's path has 133 judged steps; refactorising after each
    /// made its solve 108 s instead of 53 s). Where `own` has no pivot at `slot` above the
    /// column's tolerance, the basis is refactorised instead.
    pub fn pivot_judged(
        &mut self,
        entering: usize,
        slot: usize,
        theta: f64,
        alpha: &[f64],
        own: &[f64],
    ) -> Result<usize, SingularBasis> {
        if own.len() != alpha.len() || own[slot].abs() <= self.tol.pivot * max_abs(own) {
            self.force_refactor();
            return self.pivot(entering, slot, theta, alpha);
        }
        let leaving = self.pivot_updating(entering, slot, theta, alpha, own)?;
        if self.since_refactor != 0 {
            self.refresh_values();
        }
        Ok(leaving)
    }

    /// [`Pivoter::pivot`], the values moved along `alpha` and the inverse updated with
    /// `update` (the same but on a judged step, [`Pivoter::pivot_judged`]).
    fn pivot_updating(
        &mut self,
        entering: usize,
        slot: usize,
        theta: f64,
        alpha: &[f64],
        update: &[f64],
    ) -> Result<usize, SingularBasis> {
        let leaving = self.basis.slot_var[slot];
        for (b, a) in self.beta.iter_mut().zip(alpha) {
            *b -= theta * a;
        }
        self.beta[slot] = theta;
        // Solves for the next entering column formed in the update's pass: after a slack
        // leaves its complement enters next, and the values' kernel solve is formed when the
        // next column will want them (the rule of `choose`, on the kernel after this pivot).
        // Neither when a refactorisation follows (below) or the driver leaves: nothing would
        // use them.
        let k_after = match (entering < self.cols.n, leaving < self.cols.n) {
            (false, true) => self.basis.kernel_size() + 1,
            (true, false) => self.basis.kernel_size().saturating_sub(1),
            _ => self.basis.kernel_size(),
        };
        let refactor_next = self.since_refactor + 1 >= self.refactor_interval.max(k_after / 4)
            || self.drift > DRIFT;
        let wanted = !refactor_next && leaving != self.cols.driver();
        let next = self
            .cols
            .complement(leaving)
            .filter(|&c| wanted && c >= self.cols.n);
        let values = wanted && self.wants_values(k_after);
        let (solved, solved_h) = self
            .basis
            .pivot_solving(&self.cols, entering, slot, update, next, values);
        let version = self.basis.version();
        self.next_solve = next.zip(solved).map(|(c, y)| (version, c, y));
        self.next_values = solved_h.map(|y| (version, y));
        self.pivots += 1;
        self.since_refactor += 1;
        self.since_values += 1;
        // Refactorising costs O(k³); doing it every ~k/4 pivots keeps its share per pivot at
        // O(k²), the order of an update, and bounds the drift of the updated inverse. Lost
        // accuracy on an entering column triggers it earlier (`drift`).
        let interval = self.refactor_interval.max(self.basis.kernel_size() / 4);
        if self.since_refactor >= interval || self.drift > DRIFT {
            debug_assert!(refactor_next, "the solves above were skipped for this");
            self.refactor()?;
        }
        Ok(leaving)
    }

    /// Basic values recomputed from the data with the current kernel inverse (`O(n·k + k²)`),
    /// free of the drift that the updates `β −= θ·α` accumulate.
    pub fn refresh_values(&mut self) {
        self.beta = self.basis.solve(&self.cols, &self.cols.h);
        self.since_values = 0;
    }

    /// The basic values of some slots recomputed from the data (`O(k²)` plus `O(k)` a slot).
    fn refresh_slots(&mut self, slots: &[usize]) {
        let fresh = self.basis.values_at(&self.cols, &self.cols.h, slots);
        for (&s, v) in slots.iter().zip(fresh) {
            self.beta[s] = v;
        }
    }

    /// Fresh factorisation of the kernel and recomputation of the basic values from the data.
    pub fn refactor(&mut self) -> Result<(), SingularBasis> {
        self.basis.refactor(&self.cols)?;
        self.beta = self.basis.solve(&self.cols, &self.cols.h);
        self.since_refactor = 0;
        self.since_values = 0;
        self.drift = 0.0;
        self.refactorizations += 1;
        Ok(())
    }

    fn record(&self, entering: usize, leaving: usize) -> PivotRecord {
        let n = self.cols.n;
        let is_z = |v: usize| v >= n && v < 2 * n;
        // Allocated to its exact length: a path keeps one of these a step (a `collect` of the
        // filter grows by doubling and held 1.5× the entries on the 2000-bearing beam).
        let mut z = Vec::with_capacity(self.basis.slot_var.iter().filter(|&&v| is_z(v)).count());
        z.extend(
            self.basis
                .slot_var
                .iter()
                .enumerate()
                .filter(|&(_, &v)| is_z(v))
                .map(|(s, &v)| {
                    (
                        v - n,
                        crate::binary::ldexp(self.beta[s].max(0.0), self.cols.eh),
                    )
                }),
        );
        PivotRecord {
            entering,
            leaving,
            driver: self.driver_value(),
            z,
        }
    }

    /// Whether the basic values are to be formed in the entering column's pass, for a kernel of
    /// order `k`: worth their kernel solve (`O(k²)`) when tiny pivots have lately needed them
    /// for more than `k/2n` of the entering columns, as the pass they save is `O(n·k)`
    /// (measured: the 1000-bearing beam 5.5 → 5.1 s with this rule, 5.3 s with `2k/n`; the
    /// zone, whose tiny pivots are rare, 0.2 s slower when the values are always formed). A
    /// rule of the path alone, and the values are the same bits either way, so the path does
    /// not depend on it.
    fn wants_values(&self, k: usize) -> bool {
        2.0 * self.refresh_rate * self.cols.n as f64 > k as f64
    }

    /// The entering column `α = B⁻¹ A[:, entering]` and the ratio test's choice on it, the
    /// judgement made on accurate numbers: a ray on a fresh factorisation, a tiny pivot on basic
    /// values recomputed from the data.
    pub fn choose(&mut self, entering: usize) -> Result<(Vec<f64>, Option<Choice>), SingularBasis> {
        self.entering = entering;
        let version = self.basis.version();
        let solved = self
            .next_solve
            .take()
            .filter(|&(v, c, _)| v == version && c == entering)
            .map(|(_, _, y)| y);
        // The values a tiny pivot would recompute from the data, formed in the entering
        // column's pass over `M` (the same bits as `refresh_values`), their kernel solve from
        // the last update's pass where it was formed there.
        let values =
            (self.since_values > 0 && self.wants_values(self.basis.kernel_size())).then(|| {
                self.next_values
                    .take()
                    .filter(|(v, _)| *v == version)
                    .map(|(_, y)| y)
            });
        let (mut alpha, drift, mut fresh) = self
            .basis
            .ftran_and_values(&self.cols, entering, solved, values);
        self.drift = drift;
        let mut step = self.ratio_test(&alpha);
        // A ray is judged on a fresh factorisation, never on updates. A tiny pivot is judged
        // on basic values recomputed from the data (the updated ones drift, and near-zero
        // values decide ties); the column itself is accurate while the kernel's residual is.
        if (step.is_none() || drift > DRIFT) && self.since_refactor > 0 {
            self.refactor()?;
            alpha = self.basis.ftran(&self.cols, entering);
            step = self.ratio_test(&alpha);
        }
        if step.is_none() {
            step = self.verify_ray(entering, &mut alpha);
        } else if let Some((slot, _)) = step {
            if self.since_values > 0 {
                let tiny = alpha[slot] < 1e-6 * max_abs(&alpha);
                self.refresh_rate += (if tiny { 1.0 } else { 0.0 } - self.refresh_rate) / 16.0;
                if tiny {
                    match fresh.take() {
                        // Formed on this basis (not one refactorised since).
                        Some(beta) if self.basis.version() == version => {
                            self.beta = beta;
                            self.since_values = 0;
                        }
                        _ => self.refresh_values(),
                    }
                    step = self.ratio_test(&alpha);
                } else {
                    let close = self.near_ties(&alpha, slot, NEAR_TIE);
                    if !close.is_empty() {
                        self.refresh_slots(&close);
                        step = self.ratio_test(&alpha);
                    }
                }
            }
        }
        // A tie is judged on values and a column that satisfy the equations to round-off of
        // their terms. Solved with the explicit `K⁻¹`, they satisfy them only to `cond(K)·ε`
        // of `|K| |y|`, and rows that the data tie exactly (for a slipping pair
        // `x_t∓ = 2f·x_n − x_t±`, the last a non-basic row) then differ by that residual, which
        // far exceeds the tie's tolerance on small values: the wrong row leaves, the opposite
        // friction part enters and the basis turns singular some pivots later (the 1000-support
        // beam). Refined once from the data, the residual shrinks to its square.
        // Only a doubtful judgement is refined: candidates close to the minimum that the tie
        // test did not count as tied (an exact tie found, or a clear minimum, stays as it is).
        if let Some((slot, _)) = step {
            let close = self.near_ties(&alpha, slot, UNSURE_TIE);
            if close.len() > self.near_ties(&alpha, slot, TIE).len().max(1) {
                self.refine(entering, &mut alpha);
                self.refine_values();
                step = self.ratio_test(&alpha);
            }
        }
        // Rows of `x` whose rate is below the column's pivot tolerance but not below that of
        // the `x` rates, and that would block before the chosen row: rates of `z` can exceed
        // those of `x` by many orders, and against the whole column a pair's start of slip
        // read as round-off (the path passed it and carried a friction force 22 337 N beyond
        // its limit for a while on a 600-bearing beam, `docs/performance.md` round 27). Each is
        // taken where its rate exceeds round-off of the terms that formed it, as a ray's rows
        // are judged ([`Pivoter::check_ray`]); a block on a soft spring has `x` rates of
        // round-off above 1e-7 of its largest.
        if let Some((_, theta)) = step {
            let suspects = self.suspects(&alpha, theta);
            if !suspects.is_empty() {
                let real = self.beyond_round_off(entering, &alpha, suspects);
                if !real.is_empty() {
                    let mut cand = self.positive_slots(&alpha);
                    cand.extend(real);
                    step = self.ratio_test_over(&alpha, cand);
                }
            }
        }
        // The driver leaving (the path back at p = 0) is believed only on a rate beyond
        // round-off of the terms that formed it, as a ray's rows are judged
        // ([`Pivoter::check_ray`]); the other candidates are then those that decrease beyond
        // round-off of theirs. A frictionless beam pushed sideways by 1e-4 N beside a
        // frictional one under 1000 N: once both its pairs slip the direction is a rigid
        // slide whose load rate (1.5e-3) is round-off of terms of 5e12, and every other rate
        // in the column was formed from it; the path "returned to zero" at p = 0 where the
        // structure is a mechanism. Not where the driver is below zero: the path left the
        // problem's loads there, and leaving is its return to them (a ray there would be read
        // as a mechanism at a negative load).
        if let (Some((slot, _)), Some(d)) = (step, self.driver_slot()) {
            if slot == d && self.beta[d] >= 0.0 {
                let (check, decreasing) = self.check_ray(entering, &alpha);
                if check.equation <= crate::ACCEPT_RESIDUAL && !decreasing.contains(&d) {
                    step = self.ratio_test_over(&alpha, decreasing);
                    self.ray_check = step.is_none().then_some(check);
                }
            }
        }
        Ok((alpha, step))
    }

    /// [`Basis::kernel_terms`] of the entering column by slot (zero for a slack slot): the
    /// size of the sums that formed each basic variable's rate.
    fn slot_kernel_terms(&self, entering: usize) -> Vec<f64> {
        let kt = self.basis.kernel_terms(&self.cols, entering);
        self.basis
            .slot_var
            .iter()
            .map(|&c| self.basis.kernel_pos(c).map_or(0.0, |a| kt[a]))
            .collect()
    }

    /// The slots (of `x`) among `slots` whose rate in `alpha` exceeds round-off of the terms
    /// that formed it by [`crate::ACCEPT_RESIDUAL`]: [`Pivoter::check_ray`]'s judgement, for
    /// these rows only (`O(k²)` for the kernel's terms, `O(n)` a row).
    fn beyond_round_off(&self, entering: usize, alpha: &[f64], slots: Vec<usize>) -> Vec<usize> {
        let n = self.cols.n;
        let size: Vec<f64> = self
            .slot_kernel_terms(entering)
            .iter()
            .zip(alpha)
            .map(|(tau, a)| a.abs() + tau)
            .collect();
        let floor = ROUNDOFF * max_abs(alpha);
        slots
            .into_iter()
            .filter(|&slot| {
                let c = self.basis.slot_var[slot];
                let a = alpha[slot];
                if c >= n || a.abs() <= floor {
                    return false;
                }
                let mut t = self.cols.entry(c, entering).abs();
                for (s, &col) in self.basis.slot_var.iter().enumerate() {
                    if size[s] == 0.0 {
                        continue;
                    }
                    if col < n {
                        if col == c {
                            t += size[s];
                        }
                    } else {
                        t += self.cols.entry(c, col).abs() * size[s];
                    }
                }
                t > 0.0 && a / t > crate::ACCEPT_RESIDUAL
            })
            .collect()
    }

    /// Slots of `x` that decrease at a rate below the column's pivot tolerance but above
    /// [`X_RATE`] of the column's largest `x` rate, and reach zero before `theta` from a value
    /// above round-off (a row at zero with a rate that small is a degenerate row's round-off:
    /// an open pair's friction row, which its relation pins).
    fn suspects(&self, alpha: &[f64], theta: f64) -> Vec<usize> {
        let n = self.cols.n;
        let zero = self.zero_value();
        let thr = self.tol.pivot * max_abs(alpha);
        let x_max = (0..alpha.len())
            .filter(|&i| self.basis.slot_var[i] < n)
            .fold(0.0f64, |a, i| a.max(alpha[i].abs()));
        let x_thr = X_RATE * x_max;
        (0..alpha.len())
            .filter(|&i| {
                self.basis.slot_var[i] < n
                    && alpha[i] > x_thr
                    && alpha[i] <= thr
                    && self.beta[i] > zero
                    && self.beta[i] / alpha[i] < theta
            })
            .collect()
    }

    /// `α += B⁻¹(A_e − B α)`: one step of refinement from the data (`O(n·k)`).
    fn refine(&self, entering: usize, alpha: &mut [f64]) {
        let zero = vec![0.0; alpha.len()];
        let r = self.direction_residual(entering, alpha, &zero).0;
        let corr = self.basis.solve(&self.cols, &r);
        alpha.iter_mut().zip(&corr).for_each(|(a, c)| *a += c);
    }

    /// [`Pivoter::refine_values`] where the values miss some row of the data by more than
    /// [`ROUNDOFF`] of the terms that form it, kept only where the refined values miss it by
    /// less: values that meet the data to round-off are left as they are, bit for bit, and so
    /// are those a refinement would not improve.
    fn refine_values_beyond_round_off(&mut self) {
        let (r, t) = self.values_residual(true);
        let before = largest_miss(&r, &t);
        if before <= ROUNDOFF {
            return;
        }
        let (kept, since) = (self.beta.clone(), self.since_values);
        self.correct_values(&r);
        let (r, t) = self.values_residual(true);
        if largest_miss(&r, &t) >= before {
            (self.beta, self.since_values) = (kept, since);
        }
    }

    /// `β += B⁻¹(h − B β)`: the basic values refined once from the data (`O(n·k)`).
    fn refine_values(&mut self) {
        let (r, _) = self.values_residual(false);
        self.correct_values(&r);
    }

    /// `h − B β` by row (`O(n·k)`) and, with `terms`, the size of the terms that form each
    /// row, `|h| + Σ |B β|` (empty without).
    fn values_residual(&self, terms: bool) -> (Vec<f64>, Vec<f64>) {
        let mut r = self.cols.h.clone();
        let mut t: Vec<f64> = if terms {
            r.iter().map(|v| v.abs()).collect()
        } else {
            Vec::new()
        };
        let parts: Vec<(usize, f64)> = self
            .basis
            .slot_var
            .iter()
            .zip(&self.beta)
            .filter(|&(_, &b)| b != 0.0)
            .map(|(&c, &b)| (c, -b))
            .collect();
        let n = self.cols.n;
        let cols = &*self.cols;
        // `Columns::axpy_col` of each term in turn, row by row (`o − s·v` is `o + (−s)·v`
        // exactly: an `axpy`).
        by_row_blocks(&mut r, &mut t, |a, r, t| {
            let rows = a..a + r.len();
            for &(c, s) in &parts {
                let (col, w) = if c < n {
                    if rows.contains(&c) {
                        r[c - a] += s;
                        if !t.is_empty() {
                            t[c - a] += s.abs();
                        }
                    }
                    continue;
                } else if c < 2 * n {
                    let (col, neg) = cols.m_col(c - n);
                    (col, if neg { s } else { -s })
                } else {
                    (&cols.g[..], -s)
                };
                let col = &col[rows.clone()];
                axpy(r, w, col);
                for (ti, v) in t.iter_mut().zip(col) {
                    *ti += (w * v).abs();
                }
            }
        });
        (r, t)
    }

    /// `β += B⁻¹ r` for the values' residual `r` ([`Pivoter::values_residual`]).
    fn correct_values(&mut self, r: &[f64]) {
        let corr = self.basis.solve(&self.cols, r);
        self.beta.iter_mut().zip(&corr).for_each(|(b, c)| *b += c);
        self.since_values = 0;
    }

    /// A ray (no positive entry in `alpha`, on a fresh factorisation) is believed only if its
    /// direction is verified from the data ([`Pivoter::check_ray`]). If the equations are not
    /// met, `alpha` is refined once from the data (`α += B⁻¹(A_e − B α)`) and the ratio test
    /// redone; if some basic variable decreases by more than round-off of the terms that formed
    /// its rate (an entry below the pivot tolerance of the column but not round-off of its own
    /// sums), the ratio test is redone with those entries as candidates. The check of the last ray is left
    /// in [`Pivoter::ray_check`] for the caller to judge (an unverified ray or mechanism is a
    /// numerical failure).
    fn verify_ray(&mut self, entering: usize, alpha: &mut [f64]) -> Option<Choice> {
        let (mut check, mut decreasing) = self.check_ray(entering, alpha);
        if check.equation > crate::ACCEPT_RESIDUAL {
            // Refined once from the data: the round-off of the inverse (up to cond(K)·ε of the
            // sums) shrinks to its square.
            self.refine(entering, alpha);
            if let Some(step) = self.ratio_test(alpha) {
                self.ray_check = None;
                return Some(step);
            }
            (check, decreasing) = self.check_ray(entering, alpha);
        }
        self.ray_check = Some(check);
        if check.equation <= crate::ACCEPT_RESIDUAL && !decreasing.is_empty() {
            let step = self.ratio_test_over(alpha, decreasing);
            if step.is_some() {
                self.ray_check = None;
            }
            return step;
        }
        None
    }

    /// `A_e − Σ_s A[:, B_s] α_s` by row and the size of the terms that form it,
    /// `|A_e| + Σ_s |A[:, B_s]| (|α_s| + τ_s)`, from the data (`O(n·k)`); `τ` is
    /// [`Basis::kernel_terms`] by slot (zero for slack slots), the size of the sums that formed
    /// each `α_s`, so a row is measured against the round-off its rates carry.
    fn direction_residual(
        &self,
        entering: usize,
        alpha: &[f64],
        tau: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let mut terms = vec![(entering, 1.0, 1.0)];
        for (slot, &c) in self.basis.slot_var.iter().enumerate() {
            let size = alpha[slot].abs() + tau[slot];
            if size != 0.0 {
                terms.push((c, -alpha[slot], size));
            }
        }
        let n = self.cols.n;
        let (mut r, mut t) = (vec![0.0; n], vec![0.0; n]);
        let cols = &*self.cols;
        by_row_blocks(&mut r, &mut t, |a, r, t| {
            let rows = a..a + r.len();
            for &(c, s, size) in &terms {
                if c < n {
                    if rows.contains(&c) {
                        r[c - a] += s;
                        t[c - a] += size;
                    }
                    continue;
                }
                // A[:, c] as `Columns::col_into` writes it: 0 + v for a negated stored column
                // of `M`, 0 − v for another, 0 − g for the driver's.
                let (col, plus) = if c < 2 * n {
                    let (col, neg) = cols.m_col(c - n);
                    (&col[rows.clone()], neg)
                } else {
                    (&cols.g[rows.clone()], false)
                };
                crate::pivoting::simd::residual_terms(r, t, col, s, size, plus);
            }
        });
        (r, t)
    }

    /// The direction of a ray checked against the data (see [`RayCheck`]), and the slots whose
    /// variable decreases by more than round-off of the terms that formed its rate.
    fn check_ray(&self, entering: usize, alpha: &[f64]) -> (RayCheck, Vec<usize>) {
        let n = self.cols.n;
        let tau = self.slot_kernel_terms(entering);
        let (r, t) = self.direction_residual(entering, alpha, &tau);
        let rel = |v: f64, s: f64| {
            if v == 0.0 {
                0.0
            } else if s > 0.0 {
                v / s
            } else {
                f64::INFINITY
            }
        };
        let equation = r
            .iter()
            .zip(&t)
            .fold(0.0f64, |a, (&ri, &ti)| a.max(rel(ri.abs(), ti)));
        // A rate against the terms that formed it: for a slack `x_i` its own row, for a basic
        // column of `M` or the driver the kernel's sums `τ`.
        let size = |slot: usize, c: usize| if c < n { t[c] } else { tau[slot] };
        let driver = self.cols.driver();
        let mut decrease = 0.0f64;
        let mut decreasing = Vec::new();
        let mut driver_rate = 0.0;
        // Entries within ROUNDOFF of the column's largest are round-off of the column whatever
        // their own terms (a slack row with no other terms would make any of them significant).
        let floor = ROUNDOFF * max_abs(alpha);
        for (slot, &c) in self.basis.slot_var.iter().enumerate() {
            let a = alpha[slot];
            if a.abs() <= floor {
                continue;
            }
            if c == driver {
                driver_rate = rel(a.abs(), size(slot, c));
            }
            if a > 0.0 {
                let e = rel(a, size(slot, c));
                decrease = decrease.max(e);
                if e > crate::ACCEPT_RESIDUAL {
                    decreasing.push(slot);
                }
            }
        }
        let check = RayCheck {
            equation,
            decrease,
            driver_rate,
        };
        (check, decreasing)
    }

    /// Moves the right-hand side so that the basic `z` columns marked in `reset` read zero:
    /// `ĥ += β_j·M̂_j` for each, `β_j ← 0`, and `acc[j] += β_j` (columns' units). The point does
    /// not move; the lexicographic order restarts from the current basis, which is the start
    /// of a new problem (its perturbation `B ε` is lexicographically positive there). The
    /// values moved are formed afresh from the data and, where they miss it beyond round-off,
    /// refined once from it ([`Pivoter::refine_values_beyond_round_off`]): the moved values
    /// become the right-hand side of the rest of the stage, so an error of the updated inverse
    /// there stays in every later point. On a steel block on a 1e5 N/m spring pushed to 1.7
    /// after its weight (three toe pairs opening in turn), the values formed with the updated
    /// inverse alone broke the friction relations `x_t+ + x_t− = 2f·x_n` by 1e-4 of the forces
    /// after the third opening: an open pair ended the stage carrying a friction force of
    /// 0.06 N and the state failed its check; refined, they hold them to 1e-10.
    pub fn rebase(&mut self, reset: &[bool], acc: &mut [f64]) {
        let n = self.cols.n;
        // Solves formed for the right-hand side before the move are not the new one's.
        self.next_values = None;
        self.next_solve = None;
        self.refresh_values();
        self.refine_values_beyond_round_off();
        let moves: Vec<(usize, usize, f64)> = self
            .basis
            .slot_var
            .iter()
            .enumerate()
            .filter(|&(s, &v)| v >= n && v < 2 * n && reset[v - n] && self.beta[s] != 0.0)
            .map(|(s, &v)| (s, v - n, self.beta[s]))
            .collect();
        if !moves.is_empty() {
            let cols = self.cols.to_mut();
            let m = cols.m.clone();
            for &(s, j, b) in &moves {
                // h + b·(−c) is h − b·c exactly (a negated stored column).
                let (c, neg) = m.col(j);
                for (h, mj) in cols.h.iter_mut().zip(c) {
                    if neg {
                        *h -= b * mj;
                    } else {
                        *h += b * mj;
                    }
                }
                acc[j] += b;
                self.beta[s] = 0.0;
            }
        }
        self.restart_lex();
        self.value_scale = max_abs(&self.cols.h)
            .max(max_abs(&self.beta))
            .max(f64::MIN_POSITIVE);
    }

    /// The basic values refined from the data with the driver non-basic at `t` (the columns'
    /// units): the right-hand side becomes `h + t·g` (the driver's column is `−g`), and the
    /// values are refined once where they miss it beyond round-off
    /// ([`Pivoter::refine_values_beyond_round_off`]). For the end of a stage, whose values
    /// were moved there by hand along the last column and whose driver then left the basis.
    /// The right-hand side then holds the driver's value: the tableau is for reading values
    /// only (a further pivot would count the load twice).
    pub fn refine_with_driver_at(&mut self, t: f64) {
        debug_assert!(self.driver_slot().is_none(), "the driver is non-basic");
        let cols = self.cols.to_mut();
        for (h, g) in cols.h.iter_mut().zip(&cols.g) {
            *h += t * g;
        }
        self.next_values = None;
        self.next_solve = None;
        self.refine_values_beyond_round_off();
    }

    /// Restarts the lexicographic rule from the current basis: the perturbation becomes `B ε`,
    /// each basic variable perturbed by its own power of `ε` — the `x`'s in the order of the
    /// rows' priority, then the `z`'s in the same order, the driver last — which is
    /// lexicographically positive at once (`B⁻¹ B = I`). Ranking by variable, not by slot, keeps
    /// what the row priority guarantees from the slack start: combinations of the `x`'s that the
    /// data fix (for friction `x_t+ + x_t- − 2f·x_n = 0`) keep the sign of the perturbation of
    /// the variables they hold.
    pub fn restart_lex(&mut self) {
        let n = self.cols.n;
        self.start = self.basis.slot_var.clone();
        let key = |v: usize| -> usize {
            if v < n {
                self.row_rank[v]
            } else if v < 2 * n {
                n + self.row_rank[v - n]
            } else {
                2 * n
            }
        };
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&s| key(self.start[s]));
        self.priority = order;
        self.set_lex_rank();
        let mut col = vec![0.0; n];
        self.start_scale = self
            .start
            .iter()
            .filter(|&&c| c >= n)
            .map(|&c| {
                self.cols.col_into(c, &mut col);
                max_abs(&col)
            })
            .fold(1.0f64, f64::max);
    }

    /// How far a step moves the basic variables against their current values:
    /// `θ·‖α‖∞ / ‖β‖∞`, infinite without a step (a ray).
    fn runaway(&self, step: Option<Choice>, amax: f64) -> f64 {
        step.map_or(f64::INFINITY, |(_, theta)| {
            theta * amax / max_abs(&self.beta).max(f64::MIN_POSITIVE)
        })
    }

    /// [`Pivoter::runaway`] of each kind against its own values — the forces `x` against the
    /// largest basic force, the displacements `z` (the entering one among them, at rate one)
    /// against the largest basic displacement — the larger of the two.
    fn runaway_by_kind(&self, step: Option<Choice>, alpha: &[f64]) -> f64 {
        let Some((_, theta)) = step else {
            return f64::INFINITY;
        };
        let n = self.cols.n;
        let (mut rate, mut value) = ([0.0f64; 2], [0.0f64; 2]);
        for (slot, &v) in self.basis.slot_var.iter().enumerate() {
            if v < 2 * n {
                let k = usize::from(v >= n);
                rate[k] = rate[k].max(alpha[slot].abs());
                value[k] = value[k].max(self.beta[slot].abs());
            }
        }
        if self.entering < 2 * n {
            let k = usize::from(self.entering >= n);
            rate[k] = rate[k].max(1.0);
        }
        (0..2)
            .filter(|&k| rate[k] > 0.0)
            .map(|k| theta * rate[k] / value[k].max(f64::MIN_POSITIVE))
            .fold(0.0f64, f64::max)
    }

    /// The next pivot refactorises the kernel's inverse and recomputes the values from the
    /// data: for a pivot on a direction the inverse did not form ([`Pivoter::judged_direction`]).
    pub fn force_refactor(&mut self) {
        self.drift = f64::INFINITY;
    }

    /// The segment on which `entering` grows, on the structure's own equations
    /// ([`Pivoter::judge`]), where the load's `rate` there is below the column's tolerance: if
    /// the step would carry the load a real way (1e-6 of the load `now` reached, not of the
    /// target: judged against a far target, a beam's step at its sliding limit was left to the
    /// dense data, which took the path down from the limit) or without end, and is a runaway
    /// step, the structure's direction and its ratio test's step — `None` for no block, or
    /// only beyond double precision. Where the load holds on those equations the driver is
    /// held (its rate zero: without a block, a mechanism); where they give it a rate beyond
    /// their round-off (`genuine`), the driver moves at that rate. `None` where nothing is
    /// judged.
    pub fn judged_step(
        &self,
        entering: usize,
        step: Option<Choice>,
        rate: f64,
        now: f64,
        amax: f64,
    ) -> Option<JudgedStep> {
        self.judged_step_if(entering, step, rate, now, |p| {
            p.runaway(step, amax) > RUNAWAY
        })
    }

    /// [`Pivoter::judged_step`] where `doubtful` (a runaway step there) says whether a step
    /// that carries the load a real way is to be judged.
    pub fn judged_step_if(
        &self,
        entering: usize,
        step: Option<Choice>,
        rate: f64,
        now: f64,
        doubtful: impl FnOnce(&Self) -> bool,
    ) -> Option<JudgedStep> {
        if self.judge.is_none() || rate == 0.0 || entering == self.cols.driver() {
            return None;
        }
        let carries = step.is_none_or(|(_, th)| (th * rate).abs() > 1e-6 * now.abs());
        if !carries || !doubtful(self) {
            return None;
        }
        self.judged_on_structure(entering)
    }

    /// The direction of `entering` and its step judged on the structure's equations, where
    /// they are at hand, whatever the condensed data's step ([`Pivoter::judged_step`] judges
    /// only steps whose load rate the data cannot tell from round-off).
    pub fn judged_on_structure(&self, entering: usize) -> Option<JudgedStep> {
        if self.judge.is_none() || entering == self.cols.driver() {
            return None;
        }
        let (alpha, genuine) = self.judged_direction(entering)?;
        // With the load held, a block beyond double precision's reach of the values is none
        // (a mechanism). With the load moving, the step is as far as the load goes to it (a
        // block held by a soft spring slides metres from rest), and every decrease the judge
        // left is the structure's own (it set those within the data's round-off to zero),
        // however small beside the slips: a heel's normal force falling at 1e-10 of them,
        // below the column's tolerance.
        let step = if genuine {
            self.moving_ratio_test(&alpha)
        } else {
            self.ratio_test(&alpha)
                .filter(|&at| self.runaway_by_kind(Some(at), &alpha) <= UNRESOLVED)
        };
        Some(JudgedStep {
            alpha,
            step,
            genuine,
        })
    }

    /// The ratio test on a direction the structure's equations gave with the load moving:
    /// every decrease they left is a candidate ([`Pivoter::judged_step`]).
    fn moving_ratio_test(&self, alpha: &[f64]) -> Option<Choice> {
        let cand = (0..alpha.len()).filter(|&i| alpha[i] > 0.0).collect();
        // A sliding pair's normal force and its friction part reach zero together where it
        // opens: its relation says which row leaves (a history's stage, which has no
        // relations of its own, takes the judge's; without them the friction part left and
        // the basis turned singular). A stage's right-hand side carries the round-off of the
        // slips it absorbed (terms of 1e12 N against forces of 1e3 N), so there the
        // relation's `κ = λᵀh`, zero by the data (the loads and `M` satisfy it), is taken as
        // zero: read from `h`, its round-off let the friction part leave in kN·mm.
        match self.judge.as_ref().and_then(|j| j.relations.as_ref()) {
            Some(r) if self.relations.is_empty() => self.ratio_test_over_by(r, alpha, cand, false),
            _ => self.ratio_test_over_by(&self.relations, alpha, cand, !self.zero_kappa),
        }
    }

    /// The structure's mechanism at a tiny pivot: where the blocking row of `step` falls, and
    /// the load moves (`rate`, the load `now` reached), at rates below [`TINY_PIVOT`] of the
    /// column's largest rate `amax` — the load's rate below the column's tolerance, or the
    /// step carrying the load by more than [`TINY_PIVOT_STEP`] of itself (or of no length)
    /// with the blocking value below [`TINY_VALUE`] of the largest —, or whose step would
    /// carry the load by more than [`FAR_STEP`] times itself, the structure's equations'
    /// direction where it holds the load and nothing blocks it. `None` elsewhere: the
    /// condensed data's pivot stands (judged and taken at every tiny pivot, three bearing-beam
    /// paths went other ways: a late sliding limit missed, a ray read as a mechanism).
    ///
    /// A steel block on a heel spring of 1 N/m (5e-12 of its stiffness), its pairs slipping
    /// by hundreds of metres, tips about its toe at `W·B/(2H)`: the direction in which its
    /// heel lifts holds the load and the toe's force, but the condensed data gave the load a
    /// rate of 8e-8 and the toe's normal force a fall of 5.5e-7 of the column — the soft
    /// spring's condition times ε, though 4e-6 of the terms that formed them
    /// ([`Pivoter::check_ray`]'s measure) — and the pivot on that fall left a singular basis:
    /// exit 1 for most blocks on springs of 0.1–10 N/m, on the load path and in a history.
    pub fn tiny_pivot_mechanism(
        &self,
        entering: usize,
        alpha: &[f64],
        step: Option<Choice>,
        rate: f64,
        now: f64,
        amax: f64,
    ) -> Option<JudgedStep> {
        let (slot, th) = step?;
        if self.judge.is_none() || entering == self.cols.driver() {
            return None;
        }
        let sure = rate.abs() > self.tol.pivot * amax;
        let tiny = rate.abs() < TINY_PIVOT * amax
            && alpha[slot].abs() < TINY_PIVOT * amax
            && (!sure
                || ((th == 0.0
                    || (now != 0.0 && (th * rate).abs() > TINY_PIVOT_STEP * now.abs()))
                    && self.beta[slot].abs() < TINY_VALUE * max_abs(&self.beta)));
        // So is a step that would carry the load by more than [`FAR_STEP`] times itself,
        // whatever its rates (at a load reached: from zero every step is "far").
        let far = now != 0.0 && (th * rate).abs() > FAR_STEP * now.abs();
        if !tiny && !far {
            return None;
        }
        self.judged_on_structure(entering)
            .filter(|j| j.step.is_none() && j.load_rate(self.driver_slot()) <= 0.0)
    }

    /// Whether the direction `alpha` of the column of `entering` moves only displacements
    /// ([`Pivoter::near_mechanism`]) and takes the load back (`rate < 0`), where the
    /// structure's equations are at hand to judge it: the first of the load path's reasons to
    /// judge a near-mechanism (a history's stage judges on this one alone: the others — forces
    /// moving faster than the load, a runaway step — made 7 of a reviewer's 220 histories of
    /// blocks worse, one a false mechanism, where they made 14 better).
    pub fn near_mechanism_taking_load_back(
        &self,
        entering: usize,
        alpha: &[f64],
        rate: f64,
        amax: f64,
    ) -> bool {
        self.judge.is_some()
            && rate < 0.0
            && self.near_mechanism(entering, alpha, rate, amax).is_some()
    }

    /// Whether the direction `alpha` of the column of `entering` (a displacement), the load's
    /// rate `rate` in it, moves only displacements: the load's rate and every basic force's
    /// rate below [`NEAR_MECHANISM`] of the column's largest rate `amax`. The largest basic
    /// force's rate where it does.
    fn near_mechanism(&self, entering: usize, alpha: &[f64], rate: f64, amax: f64) -> Option<f64> {
        let n = self.cols.n;
        let bound = NEAR_MECHANISM * amax;
        if rate.abs() >= bound || entering < n {
            return None;
        }
        let mut forces = 0.0f64;
        for (&v, a) in self.basis.slot_var.iter().zip(alpha) {
            if v < n {
                if a.abs() >= bound {
                    return None;
                }
                forces = forces.max(a.abs());
            }
        }
        Some(forces)
    }

    /// Whether the direction `alpha` of the column of `entering`, the load's rate `rate` in it,
    /// moves only displacements ([`Pivoter::near_mechanism`]), where the structure's equations
    /// are at hand to judge it.
    pub fn near_mechanism_at(&self, entering: usize, alpha: &[f64], rate: f64, amax: f64) -> bool {
        self.judge.is_some() && self.near_mechanism(entering, alpha, rate, amax).is_some()
    }

    /// Whether the ratio test's `step` is blocked by one of the `z` that `incremental` marks (a
    /// slip increment: the values the stage accumulates, not a gap).
    pub fn blocked_by_increment(&self, step: Option<Choice>, incremental: &[bool]) -> bool {
        let n = self.cols.n;
        step.is_some_and(|(slot, _)| {
            let v = self.basis.slot_var[slot];
            (n..2 * n).contains(&v) && incremental[v - n]
        })
    }

    /// Whether rows of `x` that the ratio test passed over as round-off (rates below the
    /// column's pivot tolerance, [`Pivoter::suspects`]) would reach zero within `theta` at a
    /// rate of at least [`HIDDEN_X_RATE`] of the column's largest `x` rate, where the
    /// structure's equations are at hand to judge them.
    fn hides_force_blocks(&self, alpha: &[f64], theta: f64) -> bool {
        if self.judge.is_none() {
            return false;
        }
        let n = self.cols.n;
        let x_max = (0..alpha.len())
            .filter(|&i| self.basis.slot_var[i] < n)
            .fold(0.0f64, |a, i| a.max(alpha[i].abs()));
        self.suspects(alpha, theta)
            .iter()
            .any(|&i| alpha[i] >= HIDDEN_X_RATE * x_max)
    }

    /// Whether rows of `x` that the ratio test passed over (rates below the column's pivot
    /// tolerance, [`Pivoter::suspects`]) would reach zero within `theta_end` of the segment,
    /// where the structure's equations are at hand to judge them.
    pub fn hides_blocks(&self, alpha: &[f64], theta_end: f64) -> bool {
        self.judge.is_some() && !self.suspects(alpha, theta_end).is_empty()
    }

    /// The segment on which `entering` (the driver too) grows, on the structure's equations,
    /// where the load moves on it: their direction and the ratio test over every decrease
    /// they leave. `None` where they hold the load, or give nothing.
    pub fn judged_moving(&self, entering: usize) -> Option<JudgedStep> {
        let (alpha, genuine) = self.judged_direction(entering)?;
        if !genuine && entering != self.cols.driver() {
            return None;
        }
        let step = self.moving_ratio_test(&alpha);
        Some(JudgedStep {
            alpha,
            step,
            genuine: true,
        })
    }

    /// The direction of the segment on which `entering` grows, as the structure's equations
    /// ([`Pivoter::judge`]) give it, in the tableau's units; with the driver held where they
    /// give the load no rate beyond round-off of their sums, else with the load's rate they
    /// give (`true`: a genuine rate).
    fn judged_direction(&self, entering: usize) -> Option<(Vec<f64>, bool)> {
        use crate::binary::ldexp;
        let judging = self.judge.as_ref()?;
        let n = self.cols.n;
        let mut basic = vec![false; 2 * n + 1];
        for &v in &self.basis.slot_var {
            basic[v] = true;
        }
        let (rates, verdict) = judging.judge.direction(&basic, entering)?;
        let holds = verdict.load_holds();
        // A variable's value in the tableau's units per unit of its own: `x̂ = E x`, `ẑ = z/D`,
        // all over `2^eh`; the driver `t = p·2^(eg − eh)`.
        let (eh, eg) = (self.cols.eh, self.cols.eg);
        let unit = |v: usize| {
            if v < n {
                ldexp(judging.row[v], -eh)
            } else if v < 2 * n {
                ldexp(1.0 / judging.col[v - n], -eh)
            } else {
                ldexp(1.0, eg - eh)
            }
        };
        let per_entering = unit(entering);
        let driver = self.cols.driver();
        // `β` moves by `−θ α`: `α` is minus the rate.
        let alpha: Vec<f64> = self
            .basis
            .slot_var
            .iter()
            .map(|&v| {
                if v == driver && holds {
                    0.0
                } else {
                    -rates[v] * unit(v) / per_entering
                }
            })
            .collect();
        alpha
            .iter()
            .all(|a| a.is_finite())
            .then_some((alpha, !holds))
    }

    /// Complementary pivoting from `entering` until the driver leaves, a ray, the target, or
    /// the pivot cap. `target = Some((t, stop))` (in the caller's units): when the driver would
    /// pass `t`, stop there if `stop`, otherwise note the segment index in `crossed` and go on.
    pub fn run(
        &mut self,
        mut entering: usize,
        target: Option<(f64, bool)>,
        max_pivots: usize,
        records: &mut Vec<PivotRecord>,
        crossed: &mut Option<usize>,
    ) -> (Ending, usize) {
        let driver = self.cols.driver();
        let target = target.map(|(t, stop)| (self.cols.driver_scaled(t), stop));
        loop {
            let Ok((mut alpha, mut step)) = self.choose(entering) else {
                return (Ending::Singular, entering);
            };
            let amax = max_abs(&alpha);
            // How far the driver moves along this segment: its rate as computed, and whether
            // that rate is above the pivot tolerance of the column. A rate below it can still
            // carry the driver over the target within the step (a soft structure sliding: the
            // slips' rates are 1e6 times the load's, and the load went from 0.998 to 1.56 on
            // one segment without the target 1 being seen); on a ray (no step) only a rate
            // above the tolerance reaches it.
            let (t_now, mut t_rate, t_sure) = if entering == driver {
                (0.0, 1.0, true)
            } else if let Some(ds) = self.driver_slot() {
                let a = alpha[ds];
                (self.beta[ds], -a, a.abs() > self.tol.pivot * amax)
            } else {
                (0.0, 0.0, false)
            };
            // A load rate below the column's tolerance, judged on the structure's own equations
            // where they are at hand (`Pivoter::judged_step`): a mechanism there ends the path
            // at the load reached; a genuine rate there (a soft spring's) is the load's rate on
            // this segment.
            // The direction the pivoting formed, where a judged one replaces it (the basis's
            // inverse is updated with it: [`Pivoter::pivot_judged`]).
            let mut judged: Option<Vec<f64>> = None;
            let mut t_sure = t_sure;
            // A direction that moves only displacements is judged too where it takes the load
            // back, where its forces move hundreds of times faster than the load over a real
            // step, or where its step runs away — even with a load rate above the column's
            // tolerance: that rate may be the condensation's round-off of a mechanism
            // ([`NEAR_MECHANISM`], [`LOAD_BELOW_FORCES`], [`LOAD_STEP`]).
            let runaway = self.runaway(step, amax);
            let near = self.judge.is_some()
                && self
                    .near_mechanism(entering, &alpha, t_rate, amax)
                    .is_some_and(|forces| {
                        t_rate < 0.0
                            || (forces > LOAD_BELOW_FORCES * t_rate.abs()
                                && step.is_none_or(|(_, th)| {
                                    (th * t_rate).abs() > LOAD_STEP * t_now.abs()
                                }))
                            || runaway > RUNAWAY
                    });
            // A near-mechanism's step that runs away is judged even where it hardly moves the
            // load: a block on a 30 N/m spring (kN·mm), its heel opened at the tipping load,
            // had the load's rate at −2.7e-15 of the column and a block 1e9 away (the load
            // moved by 3.5e-7 of itself); the pivot on it rotated the block about its toe a
            // billion times its slip, and the path went on from round-off to a false
            // mechanism at 1.4 times the tipping load.
            let j = if near && runaway > RUNAWAY {
                self.judged_on_structure(entering)
            } else if near {
                self.judged_step_if(entering, step, t_rate, t_now, |_| true)
            } else if !t_sure {
                self.judged_step(entering, step, t_rate, t_now, amax)
            } else {
                None
            };
            // A tiny pivot whose load barely moves, where no rule above judged it, is taken from
            // the structure's equations where they find a mechanism there
            // ([`Pivoter::tiny_pivot_mechanism`]).
            let j = match j {
                None if !near => {
                    self.tiny_pivot_mechanism(entering, &alpha, step, t_rate, t_now, amax)
                }
                j => j,
            };
            if let Some(j) = j {
                let rate = j.load_rate(self.driver_slot());
                judged = Some(std::mem::replace(&mut alpha, j.alpha));
                (step, t_rate) = (j.step, rate);
                if rate > 0.0 {
                    t_sure = true;
                    self.judged_load_segments.push(records.len());
                } else if step.is_none() {
                    self.judged_mechanism = true;
                    return (Ending::Ray { alpha }, entering);
                }
            }
            // Rows of `x` that would block before the step at rates of the forces' own size
            // but that the ratio test passed over as round-off of their terms (rates of `z`
            // 1e9 times theirs: `Pivoter::hides_force_blocks`), judged on the structure's
            // equations where the load moves. A steel block on a 300 or 500 N/m spring (slips
            // 1e9 times its strains) had a toe pair's normal force falling at a quarter of the
            // largest force rate; the path passed that pair's opening at p = 1.55098 and
            // opened it together with the next one at 1.56403 (on 178 N/m and on stiff
            // springs: 1.55098 and then 1.56148, as the statics require whatever the spring).
            let hidden = judged.is_none()
                && t_rate > 0.0
                && step.is_some_and(|(_, th)| self.hides_force_blocks(&alpha, th));
            if hidden {
                if let Some(j) = self.judged_moving(entering) {
                    let rate = match self.driver_slot() {
                        Some(ds) if entering != driver => -j.alpha[ds],
                        _ => 1.0,
                    };
                    if rate > 0.0 {
                        // The structure's direction decides which row leaves; a point on the
                        // segment is formed from the condensed data as before (formed on the
                        // structure's equations, four blocks' targets on such segments were
                        // out of balance by 1.03e-6 to 1.21e-6 of their forces, against the
                        // 1e-6 allowed, where the condensed data's points pass).
                        judged = Some(std::mem::replace(&mut alpha, j.alpha));
                        (step, t_rate, t_sure) = (j.step, rate, true);
                    }
                }
            }
            if let Some((t_target, stop)) = target {
                if crossed.is_none() && t_rate > 0.0 && t_now <= t_target {
                    let theta_t = (t_target - t_now) / t_rate;
                    // Reaching the target together with a basic variable counts as reaching
                    // the target: the solution there is the same, and no pivot is needed.
                    // A rate below the tolerance counts only where the step carries the driver
                    // a real way (1e-6 of the target): a block sliding at constant load to a
                    // far stopper moves the load by round-off over a huge step, and stopping
                    // there read the state on another branch.
                    // On a ray, a rate of the basic load that the ray's check found round-off
                    // of its sums does not carry the load anywhere: the direction is a
                    // mechanism's (`parametric::follow`), and its target is not reached. (The
                    // load entering moves at rate 1: the check has no rate of it; a rate the
                    // structure's equations judged genuine on this segment is a ray's.)
                    let fixed = entering != driver
                        && self.judged_load_segments.last() != Some(&records.len())
                        && self.ray_check.is_some_and(|c| c.driver_fixed());
                    let hit = match step {
                        None => t_sure && !fixed,
                        Some((_, th)) => {
                            theta_t <= th + TIE * th.abs().max(theta_t.abs())
                                && (t_sure || th * t_rate > 1e-6 * t_target.abs())
                        }
                    };
                    if hit {
                        *crossed = Some(records.len());
                        if stop {
                            return (Ending::TargetReached, entering);
                        }
                    }
                }
            }
            let Some((slot, theta)) = step else {
                return (Ending::Ray { alpha }, entering);
            };
            if self.pivots >= max_pivots {
                return (Ending::IterationLimit, entering);
            }
            let pivoted = match &judged {
                Some(own) => self.pivot_judged(entering, slot, theta, &alpha, own),
                None => self.pivot(entering, slot, theta, &alpha),
            };
            let leaving = match pivoted {
                Ok(l) => l,
                Err(SingularBasis) => return (Ending::Singular, entering),
            };
            records.push(self.record(entering, leaving));
            self.progress.step(self.driver_value());
            if leaving == driver {
                return (Ending::DriverLeft, entering);
            }
            entering = self
                .cols
                .complement(leaving)
                .expect("only the driver has no complement");
        }
    }
}

/// Runs `f(first row, r block, t block)` over blocks of the rows of `r` and of `t` (of the
/// same length, or empty: then every `t` block is empty), on the thread pool when they are
/// long: one block per thread of at least 512 rows. A row's result depends on that row alone,
/// so it is the same whatever the blocks.
fn by_row_blocks(r: &mut [f64], t: &mut [f64], f: impl Fn(usize, &mut [f64], &mut [f64]) + Sync) {
    use rayon::prelude::*;
    let n = r.len();
    debug_assert!(t.is_empty() || t.len() == n);
    let threads = rayon::current_num_threads();
    if threads <= 1 || n < 1024 {
        f(0, r, t);
        return;
    }
    let rows = n.div_ceil(threads).max(512);
    if t.is_empty() {
        r.par_chunks_mut(rows)
            .enumerate()
            .for_each(|(i, r)| f(i * rows, r, &mut []));
    } else {
        r.par_chunks_mut(rows)
            .zip(t.par_chunks_mut(rows))
            .enumerate()
            .for_each(|(i, (r, t))| f(i * rows, r, t));
    }
}

/// The largest `|r_i|` relative to its terms `t_i` (rows without terms count zero).
fn largest_miss(r: &[f64], t: &[f64]) -> f64 {
    r.iter()
        .zip(t)
        .map(|(ri, ti)| if *ti > 0.0 { ri.abs() / ti } else { 0.0 })
        .fold(0.0f64, f64::max)
}

pub(crate) fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}
