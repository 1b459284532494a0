//! The solver object of the parametric method: the problem, its options and settings,
//! validated and equilibrated once, answering every question about its load path.

use std::fmt;

use crate::parametric::{follow, point_at, tightening_of, validate};
use crate::pivoting::prepare::Prepared;
use crate::sweep;
use crate::tableau::tableaux_of;
use crate::{LcpError, LoadPath, ParametricLcp, PathOptions, PathPoint, Settings, Tableau};

/// A parametric LCP `x = q0 + p·d + M z` prepared for pivoting: built once from the problem, the
/// path options and the engine settings — which it validates, and whose `M` it equilibrates —
/// and then asked for the load path ([`PathSolver::follow`]), the solution at any load on it
/// ([`PathSolver::solution_at`]) and its tableaux ([`PathSolver::tableaux`]) without preparing
/// anything again.
///
/// **Continuation.** A [`LoadPath`] keeps its final basis (the start basis and every pivot), so
/// a later method — "continue from the end of this path with another direction `d′`", which load
/// histories need — takes `&LoadPath` and the new direction, starts the pivoting from that basis
/// with `q0 + p_end·d` as the constant part, and returns a new `LoadPath`; the equilibrated `M`
/// held here serves it unchanged (the scaling depends on `M` only).
///
/// ```
/// use faer::mat;
/// use unilateral_lcp::{Follow, ParametricLcp, PathOptions, PathSolver, Settings, Tightening};
///
/// // The paper's Example 1 reduced to its normal rows: three supports, c = 1.
/// let problem = ParametricLcp {
///     m: mat![[0.1875, -0.375, 0.1875], [-0.375, 0.75, -0.375], [0.1875, -0.375, 0.1875]],
///     q0: vec![0.0; 3],
///     d: vec![-0.09375, 0.6875, 0.40625],
/// };
/// let options = PathOptions {
///     target: 1.0,
///     follow: Follow::ToEnd,
///     tightening: Some(Tightening { amount: 1.0, direction: vec![1.0; 3] }),
/// };
/// let solver = PathSolver::new(problem, options, Settings::default()).unwrap();
/// let path = solver.follow();
/// // By hand: at p = 1 the left support has lifted by 0.5 and the middle one carries 0.5.
/// let at_one = solver.solution_at(&path, 1.0).unwrap().unwrap();
/// assert!((at_one.z[0] - 0.5).abs() < 1e-12 && (at_one.x[1] - 0.5).abs() < 1e-12);
/// // Without the tightening the problem is homogeneous in p (q0 = 0): half the answer at p = 1/2.
/// let half = solver.solution_at(&path, 0.5).unwrap().unwrap();
/// assert!((half.z[0] - 0.25).abs() < 1e-12 && (half.x[1] - 0.25).abs() < 1e-12);
/// ```
pub struct PathSolver {
    /// `q0` and `d` as given (`M` is held once, equilibrated, in `prep`).
    q0: Vec<f64>,
    d: Vec<f64>,
    options: PathOptions,
    settings: Settings,
    n: usize,
    /// The equilibrated `M` and its scalings; the original `M` is recovered from it exactly.
    pub(crate) prep: Prepared,
    /// The tightening's amount (`0` without one).
    pub(crate) c0: f64,
    /// The tightening's direction (zeros without one).
    pub(crate) cov: Vec<f64>,
    /// `prep` on the scaling before its parts were raised, where any was
    /// ([`Prepared::from_owned_raising`]): the start at `p = 0` is found on it.
    pub(crate) start_prep: Option<Prepared>,
    /// The settings' row relations that the data satisfy, in the equilibrated rows.
    pub(crate) relations: std::sync::Arc<crate::pivoting::relations::Relations>,
    /// The structure's own equations, judging the load rates the data cannot tell from
    /// round-off ([`PathSolver::judged_on`]).
    pub(crate) judge: Option<std::sync::Arc<crate::StructureJudge>>,
}

impl fmt::Debug for PathSolver {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("PathSolver")
            .field("order", &self.n)
            .field("options", &self.options)
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl PathSolver {
    /// Validates the problem, the options and the settings, and equilibrates `M`.
    ///
    /// The solver holds one `n × n` matrix: the equilibrated `M`, from which the original is
    /// recovered bit for bit where verification needs it (the scalings are powers of two); a
    /// copy of the original is kept as well only when some scaled entry left the normal range.
    pub fn new(
        problem: ParametricLcp,
        options: PathOptions,
        settings: Settings,
    ) -> Result<Self, LcpError> {
        let n = validate(&problem, &options, &settings)?;
        let ParametricLcp { m, q0, d } = problem;
        let (c0, cov) = tightening_of(&options, n);
        // Without a tightening each part of the problem that neither `M` nor a row relation
        // couples to the others (a structure beside another) is raised to the size of the
        // largest part's loads, so that its loads are not round-off of the others' in the
        // columns they share along the path. The start at `p = 0` is found on the scaling
        // before the raise: one tightening drives every part there, and its size is set by the
        // largest part's constant load, so that a raised part's would swamp a small negative
        // load of another (a portal's thrust on frictionless feet beside a raised beam). With a
        // tightening the traced path is the tightened problem's, whose direction the caller
        // chose: scaled as given.
        let (mut prep, unraised) = if c0 == 0.0 {
            Prepared::from_owned_raising(m, &[&q0, &d], &settings.relation_rows())
        } else {
            (Prepared::from_owned(m), None)
        };
        let relations = std::sync::Arc::new(crate::pivoting::relations::Relations::new(
            &prep,
            &settings.row_relations,
        ));
        prep.derive_rows(&relations);
        let start_prep = unraised.map(|scaling| prep.rescaled(scaling));
        Ok(Self {
            relations,
            start_prep,
            judge: None,
            q0,
            d,
            options,
            settings,
            n,
            prep,
            c0,
            cov,
        })
    }

    /// Judges the path's doubtful load rates on `judge`, the same problem on the structure's
    /// own sparse equations (in the same units): where a segment would carry the load a real
    /// way at a rate below the pivot tolerance of its column, or a ray's load moves at such a
    /// rate, and the structure's equations give the load no rate beyond round-off of their sums
    /// and no variable a decrease, the segment is the structure's mechanism at the load
    /// reached (`crate::schur::judge`). Only a path without a tightening is judged; a judge of
    /// another order is ignored.
    pub fn judged_on(&mut self, judge: std::sync::Arc<crate::StructureJudge>) {
        if judge.order() == self.n {
            self.judge = Some(judge);
        }
    }

    /// The problem, as given: `M` rebuilt bit for bit from the equilibrated copy the solver
    /// holds (an `O(n²)` copy).
    pub fn problem(&self) -> ParametricLcp {
        ParametricLcp {
            m: self.prep.original_matrix(),
            q0: self.q0.clone(),
            d: self.d.clone(),
        }
    }

    /// The constant part `q0`, as given.
    pub fn q0(&self) -> &[f64] {
        &self.q0
    }

    /// The load direction `d`, as given.
    pub fn d(&self) -> &[f64] {
        &self.d
    }

    /// `q0 + c0·cov`: the constant part with the tightening, as the path is traced.
    pub(crate) fn q_traced(&self) -> Vec<f64> {
        self.q0
            .iter()
            .zip(&self.cov)
            .map(|(q, c)| q + self.c0 * c)
            .collect()
    }

    /// `q0 + p·d`.
    pub(crate) fn q_at(&self, p: f64) -> Vec<f64> {
        self.q0
            .iter()
            .zip(&self.d)
            .map(|(q, d)| q + p * d)
            .collect()
    }

    /// `|q0| + |p·d|`: the sizes of the terms of [`PathSolver::q_at`], a row.
    pub(crate) fn q_terms_at(&self, p: f64) -> Vec<f64> {
        self.q0
            .iter()
            .zip(&self.d)
            .map(|(q, d)| q.abs() + (p * d).abs())
            .collect()
    }

    /// `q0 + p·d + M z` on the original data: the `x` that the equations give `z` at `p`.
    pub(crate) fn x_of(&self, p: f64, z: &[f64]) -> Vec<f64> {
        use crate::residual::ColumnSource as _;
        let n = self.n;
        let cols = OriginalColumns(&self.prep);
        let mut x = self.q_at(p);
        let mut col = vec![0.0; n];
        for (j, &zj) in z.iter().enumerate() {
            if zj != 0.0 {
                cols.column_into(j, 0..n, &mut col);
                x.iter_mut().zip(&col).for_each(|(xi, c)| *xi += c * zj);
            }
        }
        x
    }

    /// `max_i |M_ij|` on the original data.
    pub(crate) fn column_max(&self, j: usize) -> f64 {
        use crate::residual::ColumnSource as _;
        let mut col = vec![0.0; self.n];
        OriginalColumns(&self.prep).column_into(j, 0..self.n, &mut col);
        col.iter().fold(0.0f64, |a, v| a.max(v.abs()))
    }

    /// Residuals of `(x, z)` at load `p` against the original data.
    pub(crate) fn residual(&self, p: f64, x: &[f64], z: &[f64]) -> crate::Residual {
        let n = self.n;
        crate::Residual::of_parametric_with(
            &OriginalColumns(&self.prep),
            (n, n),
            &self.q0,
            &self.d,
            p,
            x,
            z,
        )
    }

    /// The path options, as given.
    pub fn options(&self) -> &PathOptions {
        &self.options
    }

    /// The engine settings, as given.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The order `n` of the problem.
    pub fn order(&self) -> usize {
        self.n
    }

    /// Follows the load path from `p = 0` (`formulation.md` §4).
    ///
    /// The start is the scheme at `p = 0`: the slack basis when `q0 (+ tightening) ≥ 0`,
    /// otherwise the solution of the `p = 0` problem by Lemke's method. Then `p` enters and
    /// every pivot is one change of the working scheme. The reported solution never contains
    /// the tightening: the last basis is evaluated without it, verified, and if needed the
    /// tightening is driven to zero by further pivots at fixed `p`.
    pub fn follow(&self) -> LoadPath {
        follow(self)
    }

    /// A path traced by the engine on sparse data ([`crate::follow_schur_path`]) on the same
    /// problem, taken as this solver's [`LoadPath`]: its pivots from the slack basis, and the
    /// solution reported where [`PathSolver::follow`] would report it, formed and verified from
    /// this solver's data; every method that reads a path then answers on it. `None` when this
    /// solver's start is not the slack basis (a tightening, or `q0` not `≥ 0`), where the
    /// sparse engine does not start.
    pub fn adopt(&self, schur: crate::SchurPath) -> Option<LoadPath> {
        crate::parametric::adopt(self, schur)
    }

    /// The engine on sparse data's path on `lcp` (the same problem as this solver's, of its
    /// order), with the rates it cannot tell from round-off judged on this solver's `M`, as
    /// that engine reports it: not adopted, nothing verified ([`PathSolver::follow_sparse`]
    /// does both).
    pub fn trace_sparse(
        &self,
        lcp: &crate::SchurLcp,
        options: &crate::SchurOptions,
    ) -> crate::SchurPath {
        crate::schur::follow(lcp, options, Some(self))
    }

    /// The path traced by the engine on sparse data on `lcp` — the same problem as this
    /// solver's, kept as the structure's sparse blocks — with the rates it cannot tell from
    /// round-off judged on this solver's `M` (a start of slip whose rate is 10⁻¹⁴ of the
    /// structure's displacements it forms it from, but clear on the condensed matrix), then
    /// adopted ([`PathSolver::adopt`]). Taken only where it reaches the target or ends in a ray
    /// whose reported point verifies and, for a ray, whose basis still solves the problem at
    /// 10⁶ times the larger of its start and the target (a false ray ends there in a negative
    /// variable): on the structure's own equations where this solver is judged on them
    /// ([`PathSolver::judged_on`]; no value below −1e-6 of the largest of its kind), else on
    /// this solver's data. `None` otherwise: the caller traces with [`PathSolver::follow`].
    pub fn follow_sparse(
        &self,
        lcp: &crate::SchurLcp,
        options: &crate::SchurOptions,
    ) -> Option<LoadPath> {
        if lcp.order() != self.n {
            return None;
        }
        self.take_sparse(self.trace_sparse(lcp, options))
    }

    /// A new solver (as [`PathSolver::new`], judged on `judge` where given) and the path of
    /// [`PathSolver::follow_sparse`] on `lcp`, the solver built on a second thread while this
    /// one traces: the engine on sparse data needs the dense data only for the rates it cannot
    /// tell from round-off, and waits for them there (preparing a 6000-row `M` takes about a
    /// second, a fifteenth of the 2000-bearing beam's path). `Ok((solver, None))` where the
    /// path is not taken (the caller traces with [`PathSolver::follow`]).
    pub fn new_following_sparse(
        problem: ParametricLcp,
        options: PathOptions,
        settings: Settings,
        judge: Option<std::sync::Arc<crate::StructureJudge>>,
        lcp: &crate::SchurLcp,
        schur_options: &crate::SchurOptions,
    ) -> Result<(Self, Option<LoadPath>), LcpError> {
        use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
        use std::sync::OnceLock;
        // The solver, or `None` where its construction panicked (the panic is resumed here).
        let built: OnceLock<Option<Result<Self, LcpError>>> = OnceLock::new();
        let order = problem.q0.len();
        let schur = std::thread::scope(|scope| {
            let builder = scope.spawn(|| {
                let made = catch_unwind(AssertUnwindSafe(|| {
                    PathSolver::new(problem, options, settings).map(|mut solver| {
                        if let Some(judge) = judge {
                            solver.judged_on(judge);
                        }
                        solver
                    })
                }));
                let panicked = made.is_err();
                let _ = built.set(made.ok());
                if panicked {
                    resume_unwind(Box::new("the dense solver's construction panicked"));
                }
            });
            let schur = (lcp.order() == order)
                .then(|| crate::schur::follow(lcp, schur_options, Some(&Building(&built))));
            if let Err(panic) = builder.join() {
                resume_unwind(panic);
            }
            schur
        });
        let solver = built
            .into_inner()
            .flatten()
            .expect("the builder sets the solver or panics")?;
        let path = schur.and_then(|schur| solver.take_sparse(schur));
        Ok((solver, path))
    }

    /// A path of the engine on sparse data taken as this solver's (see
    /// [`PathSolver::follow_sparse`]), or `None`.
    fn take_sparse(&self, schur: crate::SchurPath) -> Option<LoadPath> {
        if !matches!(
            schur.status,
            crate::PathStatus::TargetReached | crate::PathStatus::Ray
        ) {
            return None;
        }
        let path = self.adopt(schur)?;
        path.solution.as_ref()?;
        if path.status == crate::PathStatus::Ray {
            let start = path.breakpoints.last().map_or(0.0, |b| b.p);
            let far = 1e6 * start.max(self.options.target).max(f64::MIN_POSITIVE);
            // The ray's own basis (not a fresh solve there, which at 6000 rows takes minutes),
            // on the structure's own equations where this solver has them: far along a long
            // path the condensed data's round-off times the basis's conditioning exceeds the
            // values' (the 2000-bearing beam's ray: a force −5.5e-8 of the largest on them,
            // −2.2e-9 on the structure's equations — a rate of 2.2e-9 of the largest, a basis
            // the dense engine reaches too and calls a ray).
            match crate::parametric::last_basis_on_structure(self, &path, far) {
                Some((x, z)) => {
                    if !ray_values_hold(&x) || !ray_values_hold(&z) {
                        return None;
                    }
                }
                None => {
                    let point = crate::parametric::basis_point_on_segment(
                        self,
                        &path,
                        path.records.len(),
                        far,
                    )
                    .ok()?;
                    if point.tightening_pivots != 0 {
                        return None;
                    }
                }
            }
        }
        Some(path)
    }

    /// The solution without tightening at any `p` on a path this solver followed (for example
    /// a load below the target, or a load on the ray's half-line beyond the last event);
    /// `Ok(None)` when `p` is not on the traced path.
    ///
    /// A path of a problem of another order is refused ([`LcpError::Dimension`]).
    pub fn solution_at(&self, path: &LoadPath, p: f64) -> Result<Option<PathPoint>, LcpError> {
        self.check_path(path)?;
        Ok(point_at(self, path, p))
    }

    /// The solution without tightening at load `p` of a path this solver followed, formed on
    /// the structure's own equations ([`PathSolver::judged_on`]) from the basis of the path's
    /// last segment through `p`, and verified on this solver's data as every point is: for a
    /// caller whose own check on the structure finds the point formed on the condensed data
    /// out of balance beyond the data's round-off. `Ok(None)` without a judge, with a
    /// tightening, off the path, or where that basis is singular on the structure or its
    /// point does not verify.
    ///
    /// A path of a problem of another order is refused ([`LcpError::Dimension`]).
    pub fn structure_solution_at(
        &self,
        path: &LoadPath,
        p: f64,
    ) -> Result<Option<PathPoint>, LcpError> {
        self.check_path(path)?;
        Ok(crate::parametric::structure_point_at(self, path, p))
    }

    /// The load of step `k` (1-based, as [`crate::Step::index`]) of a path this solver followed,
    /// computed afresh from the data: the basis of the segment before the step factorised anew
    /// and its values and rates refined in working precision, where the path itself moves its
    /// basis by updates of an inverse that is refactorised every few pivots. An independent
    /// check of the traced [`crate::Step::p`] (`O(k³)` a step); `Ok(None)` for a step the path does
    /// not have or whose basis is numerically singular.
    ///
    /// A path of a problem of another order is refused ([`LcpError::Dimension`]).
    pub fn event_load(&self, path: &LoadPath, k: usize) -> Result<Option<f64>, LcpError> {
        self.check_path(path)?;
        Ok(crate::parametric::event_load(self, path, k))
    }

    /// The solutions without tightening at many loads of a path this solver followed, one per
    /// load in the order given (`None` for a load off the traced path): the same answers as
    /// [`PathSolver::solution_at`] at each load, in one walk along the path.
    ///
    /// The walk keeps one basis, updated by the path's own pivots (`O(n·k + k²)` a step, as
    /// tracing), instead of rebuilding and factorising the basis of every load's segment
    /// (`O(k³)` a load). At a load whose basis is infeasible without the tightening, the
    /// tightening is removed on a copy for a few pivots at most; a load that needs more, or
    /// whose point does not verify, is computed exactly as [`PathSolver::solution_at`] does.
    /// Loads in increasing order make one walk; any order is accepted.
    ///
    /// A path of a problem of another order is refused ([`LcpError::Dimension`]).
    pub fn points_at(
        &self,
        path: &LoadPath,
        loads: &[f64],
    ) -> Result<Vec<Option<PathPoint>>, LcpError> {
        self.check_path(path)?;
        Ok(sweep::points_at(self, path, loads))
    }

    /// All tableaux of a path this solver followed, in the paper's layout: the initial one, one
    /// after each step (at most `max_steps` steps), and — when the path ended by Criterion 1
    /// or 2a — the final one with `p` pivoted out of the basis.
    ///
    /// A path of a problem of another order is refused ([`LcpError::Dimension`]).
    pub fn tableaux(
        &self,
        path: &LoadPath,
        max_steps: Option<usize>,
    ) -> Result<Vec<Tableau>, LcpError> {
        self.check_path(path)?;
        Ok(tableaux_of(self, path, max_steps))
    }

    fn check_path(&self, path: &LoadPath) -> Result<(), LcpError> {
        if path.order() != self.n {
            return Err(LcpError::Dimension(format!(
                "the load path belongs to a problem of order {}, M has order {}",
                path.order(),
                self.n
            )));
        }
        Ok(())
    }
}

/// Follows the load path of `x = q0 + p·d + M z` from `p = 0`: a one-shot convenience for
/// [`PathSolver::new`] and [`PathSolver::follow`] (it copies the problem; keep a [`PathSolver`]
/// to ask for solutions at other loads or for tableaux).
///
/// ```
/// use faer::mat;
/// use unilateral_lcp::{follow_path, Follow, ParametricLcp, PathOptions, PathStatus, Settings, Tightening};
///
/// // The paper's Example 1 reduced to its normal rows: three supports, c = 1.
/// let problem = ParametricLcp {
///     m: mat![[0.1875, -0.375, 0.1875], [-0.375, 0.75, -0.375], [0.1875, -0.375, 0.1875]],
///     q0: vec![0.0; 3],
///     d: vec![-0.09375, 0.6875, 0.40625],
/// };
/// let options = PathOptions {
///     target: 1.0,
///     follow: Follow::ToEnd,
///     tightening: Some(Tightening { amount: 1.0, direction: vec![1.0; 3] }),
/// };
/// let path = follow_path(&problem, &options, &Settings::default()).unwrap();
/// assert_eq!(path.status, PathStatus::Ray);
/// assert!((path.steps[0].p - 1.0 / 0.09375).abs() < 1e-12);
/// let sol = path.solution.unwrap();
/// assert!((sol.z[0] - 0.5).abs() < 1e-12 && (sol.x[1] - 0.5).abs() < 1e-12);
/// ```
pub fn follow_path(
    problem: &ParametricLcp,
    options: &PathOptions,
    settings: &Settings,
) -> Result<LoadPath, LcpError> {
    Ok(PathSolver::new(problem.clone(), options.clone(), settings.clone())?.follow())
}

/// The solution without tightening at `p` on a traced path: a one-shot convenience for
/// [`PathSolver::solution_at`] (it validates and equilibrates the problem again on every call;
/// keep a [`PathSolver`] to ask for many loads). `Ok(None)` when `p` is not on the path.
pub fn solution_at(
    problem: &ParametricLcp,
    options: &PathOptions,
    settings: &Settings,
    path: &LoadPath,
    p: f64,
) -> Result<Option<PathPoint>, LcpError> {
    PathSolver::new(problem.clone(), options.clone(), settings.clone())?.solution_at(path, p)
}

/// All tableaux of a traced path: a one-shot convenience for [`PathSolver::tableaux`] with the
/// default settings (the tableaux do not depend on them).
pub fn tableaux(
    problem: &ParametricLcp,
    options: &PathOptions,
    path: &LoadPath,
    max_steps: Option<usize>,
) -> Result<Vec<Tableau>, LcpError> {
    PathSolver::new(problem.clone(), options.clone(), Settings::default())?
        .tableaux(path, max_steps)
}

/// The original `M` of a prepared problem, as the residuals read it.
struct OriginalColumns<'a>(&'a crate::pivoting::prepare::Prepared);

impl crate::residual::ColumnSource for OriginalColumns<'_> {
    fn entry(&self, i: usize, j: usize) -> f64 {
        self.0.original_entry(i, j)
    }
    fn column_into(&self, j: usize, rows: std::ops::Range<usize>, out: &mut [f64]) {
        self.0.original_column_into(j, rows, out);
    }
}

/// The dense data of a solver being built on another thread
/// ([`PathSolver::new_following_sparse`]): a question waits for it. Where its construction
/// failed, every rate is called round-off (the path is then discarded with the failure).
struct Building<'a>(&'a std::sync::OnceLock<Option<Result<PathSolver, LcpError>>>);

impl crate::schur::DenseRates for Building<'_> {
    fn row(&self, i: usize, dz: &[f64], dp: f64) -> (f64, f64) {
        match self.0.wait() {
            Some(Ok(solver)) => solver.row(i, dz, dp),
            _ => (0.0, f64::INFINITY),
        }
    }

    fn rows(&self, dz: &[f64], dp: f64) -> (Vec<f64>, Vec<f64>) {
        match self.0.wait() {
            Some(Ok(solver)) => solver.rows(dz, dp),
            _ => (vec![0.0; dz.len()], vec![f64::INFINITY; dz.len()]),
        }
    }
}

impl crate::schur::DenseRates for PathSolver {
    fn row(&self, i: usize, dz: &[f64], dp: f64) -> (f64, f64) {
        let (mut rate, mut terms) = (0.0, 0.0);
        for (j, &r) in dz.iter().enumerate().filter(|(_, r)| **r != 0.0) {
            let t = self.prep.original_entry(i, j) * r;
            rate += t;
            terms += t.abs();
        }
        let t = self.d[i] * dp;
        (rate + t, terms + t.abs())
    }

    fn rows(&self, dz: &[f64], dp: f64) -> (Vec<f64>, Vec<f64>) {
        let n = self.n;
        let mut rate: Vec<f64> = self.d.iter().map(|d| d * dp).collect();
        let mut terms: Vec<f64> = rate.iter().map(|t| t.abs()).collect();
        let mut col = vec![0.0; n];
        for (j, &r) in dz.iter().enumerate().filter(|(_, r)| **r != 0.0) {
            self.prep.original_column_into(j, 0..n, &mut col);
            for ((a, b), &m) in rate.iter_mut().zip(terms.iter_mut()).zip(&col) {
                let t = m * r;
                *a += t;
                *b += t.abs();
            }
        }
        (rate, terms)
    }
}

/// A ray's values of one kind (`x` or `z`) far along it: none below −1e-6 of the largest of
/// the kind. At 10⁶ times the ray's start a value is that many times its rate, so this
/// refuses a variable that decreases at more than 1e-6 of the largest rate. The rays that the
/// engines reach late on long paths, in bases of condition 1e8 to 1e10, have rows whose rates
/// are round-off of that size and which both engines judge round-off of their terms (a
/// reviewer's beams on 1000–1300 bearings: −1.3e-8 to −4.5e-8, the dense engine ending in the
/// same rays; at 1e-8 those sparse paths were refused and traced a second time); a false ray,
/// a variable that genuinely decreases (the dense engine's "ray" of the 1000-bearing beam,
/// −2.9e-3), is far beyond it.
fn ray_values_hold(v: &[f64]) -> bool {
    let top = v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    v.iter().all(|&b| b.is_finite() && b >= -1e-6 * top)
}
