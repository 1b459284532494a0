//! The parametric Lemke method: the load parameter `p` is the driving variable
//! (`formulation.md` §4), and the removal of the artificial tightening. The entry points are the
//! methods of [`crate::PathSolver`], which validates and prepares the data once.

use crate::lemke::{lemke_run, solve_lcp, LemkeOutcome};
use crate::pivoting::basis::Basis;
use crate::pivoting::columns::Columns;
use crate::pivoting::enumerate::enumerate_first;
use crate::pivoting::pivot::{max_abs, Ending, PivotRecord, Pivoter, Tolerances};
use crate::pivoting::prepare::{check_matrix, check_vector, Prepared};
use crate::{
    BasisVerdict, Breakpoint, Follow, Lcp, LcpError, LcpStatus, LoadPath, MechanismMode,
    ParametricLcp, PathOptions, PathPoint, PathSolver, PathStatus, Settings, SettingsError, Step,
    Unreported, Var,
};

/// Checks the problem, the settings and the options; returns the order `n`.
pub(crate) fn validate(
    problem: &ParametricLcp,
    options: &PathOptions,
    settings: &Settings,
) -> Result<usize, LcpError> {
    let n = check_matrix(&problem.m)?;
    check_vector("q0", &problem.q0, n)?;
    check_vector("d", &problem.d, n)?;
    settings.validate(n)?;
    PathOptions::check_target(options.target)?;
    if let Some(t) = &options.tightening {
        crate::Tightening::check_amount(t.amount)?;
        check_vector("tightening direction", &t.direction, n)?;
        if let Some(i) = t.direction.iter().position(|&v| v < 0.0) {
            return Err(SettingsError::TighteningDirection(i + 1).into());
        }
    }
    Ok(n)
}

/// The tightening's amount and direction (zero and a zero direction when there is none).
pub(crate) fn tightening_of(options: &PathOptions, n: usize) -> (f64, Vec<f64>) {
    match &options.tightening {
        Some(t) if t.amount > 0.0 => (t.amount, t.direction.clone()),
        _ => (0.0, vec![0.0; n]),
    }
}

/// The load path from `p = 0` (see [`PathSolver::follow`]).
pub(crate) fn follow(solver: &PathSolver) -> LoadPath {
    let (options, settings) = (solver.options(), solver.settings());
    let n = solver.order();
    let prep = &solver.prep;
    let c0 = solver.c0;
    let h = solver.q_traced();
    let cols = prep.columns(&h, solver.d());
    let tol = Tolerances {
        pivot: settings.pivot_tol(),
        value: 1e-13,
    };
    let priority = settings.priority(n);
    let driver = cols.driver();

    // The scheme at p = 0.
    let phase1_dir = match (&options.tightening, &settings.covering) {
        (Some(t), _) => t.direction.clone(),
        (None, Some(c)) => c.clone(),
        (None, None) => vec![1.0; n],
    };
    let progress = &settings.progress;
    progress.phase(crate::Phase::Start);
    // The start on the scaling before any raise ([`PathSolver`]'s `start_prep`); its basis is
    // the same on both (a complementary basis holds no column of `h` or `d`, and `E M D` is
    // the same), its values are formed on this one by the pivoting.
    let start_prep = solver.start_prep.as_ref().unwrap_or(prep);
    let judged_start = |slots: &[usize]| start_on_structure(solver, slots);
    let on_structure: Option<&StartJudge> =
        (c0 == 0.0 && solver.judge.is_some()).then_some(&judged_start);
    let (start_basis, start_pivots) = match start_basis(
        start_prep,
        solver.d(),
        &h,
        &phase1_dir,
        settings,
        on_structure,
    ) {
        (Some(b), pivots, _) => (b, pivots),
        (None, start_pivots, capped) => {
            return LoadPath {
                // The pivot cap ended the search for the start: not a proof that there is
                // none.
                status: if capped {
                    PathStatus::IterationLimit
                } else {
                    PathStatus::NoSolutionAtStart
                },
                steps: vec![],
                breakpoints: vec![],
                p_max: 0.0,
                p_limit: None,
                mechanism: None,
                last_entering: None,
                solution: None,
                start_pivots,
                refactorizations: 0,
                artificial_mechanism: None,
                unreported: None,
                unloaded_at_start: false,
                start_slots: (0..n).collect(),
                records: vec![],
                target_segment: None,
                judged_load_segments: Vec::new(),
            };
        }
    };
    let start_slots = start_basis.slot_var.clone();
    let mut piv = Pivoter::new(
        &cols,
        start_basis,
        tol,
        priority,
        settings.refactor_interval,
    );
    piv.progress = settings.progress.clone();
    piv.relations = solver.relations.clone();
    if c0 == 0.0 {
        piv.judge = solver
            .judge
            .clone()
            .map(|judge| crate::pivoting::pivot::Judging {
                judge,
                row: prep.scaling.row.clone(),
                col: prep.scaling.col.clone(),
                relations: None,
            });
    }
    let start_z = basic_z(prep, &piv.basis.slot_var, &cols.values(&piv.beta));
    let mut records: Vec<PivotRecord> = Vec::new();
    let mut crossed = None;
    let stop = options.follow == Follow::ToTarget;
    progress.pivots(start_pivots);
    progress.phase(crate::Phase::Path);
    let (ending, last_entering) = piv.run(
        driver,
        Some((options.target, stop)),
        settings.cap(n),
        &mut records,
        &mut crossed,
    );

    progress.steps_to(records.len(), records.last().map_or(0.0, |r| r.driver));
    let kseg = records.len();
    let pivots: Vec<(usize, usize)> = records.iter().map(|r| (r.entering, r.leaving)).collect();
    let mut steps = Vec::with_capacity(records.len());
    let mut breakpoints = Vec::with_capacity(records.len() + 1);
    breakpoints.push(Breakpoint { p: 0.0, z: start_z });
    let mut p_prev = 0.0f64;
    let mut p_max = 0.0f64;
    // The records' values move into the breakpoints (`O(k)` a step: not held twice).
    for (k, mut r) in records.into_iter().enumerate() {
        let zero = 1e-9 * p_prev.abs().max(1.0);
        steps.push(Step {
            index: k + 1,
            p: r.driver,
            entering: Var::from_col(r.entering, n),
            leaving: Var::from_col(r.leaving, n),
            turning: r.driver < p_prev - zero,
        });
        r.z.iter_mut().for_each(|(i, v)| *v *= prep.scaling.col[*i]);
        breakpoints.push(Breakpoint {
            p: r.driver,
            z: r.z,
        });
        p_prev = r.driver;
        p_max = p_max.max(r.driver);
    }
    let mut path = LoadPath {
        status: PathStatus::NumericalFailure,
        steps,
        breakpoints,
        p_max,
        p_limit: None,
        mechanism: None,
        last_entering: Some(Var::from_col(last_entering, n)),
        solution: None,
        start_pivots,
        refactorizations: piv.refactorizations,
        artificial_mechanism: None,
        unreported: None,
        unloaded_at_start: false,
        start_slots,
        records: pivots,
        target_segment: crossed,
        judged_load_segments: std::mem::take(&mut piv.judged_load_segments),
    };
    // (segment, p) at which to report the solution.
    let report: Option<(usize, f64)> = match ending {
        Ending::TargetReached => {
            path.status = PathStatus::TargetReached;
            path.p_max = path.p_max.max(options.target);
            Some((kseg, options.target))
        }
        Ending::Ray { alpha } => {
            let ds = piv.driver_slot();
            let amax = max_abs(&alpha);
            let rate = ds.map(|s| alpha[s]).unwrap_or(-1.0);
            // The direction was checked against the data before the ray was believed
            // (`Pivoter::verify_ray`): a mechanism needs the driver fixed within round-off of
            // the rows it meets, not only below the pivot tolerance of the column.
            let check = piv.ray_check;
            // A direction the structure's own equations found a mechanism is judged on them;
            // one on which they gave the load a genuine rate is a ray.
            let judged = piv.judged_mechanism;
            let judged_ray = path.judged_load_segments.last() == Some(&kseg);
            let fixed = judged || (!judged_ray && check.is_none_or(|c| c.driver_fixed()));
            // A load rate above the column's tolerance is a ray's unless the check found it
            // round-off of the terms that formed it: a portal on feet of friction 1e-11 and
            // 8.7e-8 pushed by 1.3e-4 N slid at its limit on a load rate of 9.6e-7 of the
            // column, 1.2e-12 of its terms, in kN·mm (a "ray" of slips of 20 km to p = 10, the
            // push balanced by round-off of the stiffness), and at 1.3e-6 of the column (a
            // load decreasing: a mechanism) in N·m.
            let rising = rate < -tol.pivot * amax && !(fixed && check.is_some());
            if !judged && !judged_ray && check.is_some_and(|c| !c.verified()) {
                path.status = PathStatus::NumericalFailure;
                None
            } else if last_entering == driver || rising || !fixed {
                path.status = PathStatus::Ray;
                match crossed {
                    Some(j) => Some((j, options.target)),
                    None => Some((kseg, options.target.max(piv.driver_value()))),
                }
            } else {
                path.status = PathStatus::Mechanism;
                // The ray was judged on a fresh factorisation: its load is the limit load, and
                // the last breakpoint (where the mechanism forms) and its step carry it too,
                // not the value the updates had reached there (a rounding or more apart).
                let p_lim = piv.driver_value();
                // A limit whose variable load is round-off of the constant one (`|p|·‖d‖` within
                // 1e-12 of `‖q0‖`) is the start: the mechanism forms as soon as the variable load
                // is applied (beams on frictionless bearings pushed sideways, or hanging over
                // their gaps; an independent tester's enumeration finds no state at any p > 0).
                // Read as p = ±1e-15, the point there failed its verification or was refused as
                // unresolvable (exit 1 or 2, in N·m and not in kN·mm), or was reported at a
                // negative load. Both against the constant load and against p = 1 (or the
                // target): a variable load written 1e15 times the constant one has a real limit
                // at p = 1e-13, and a part of the model under a constant load 1e15 times the
                // rest's does not make the rest's limit at p = 0.4 round-off (a reviewer's
                // models).
                let (q0, d) = (max_abs(solver.q0()), max_abs(solver.d()));
                let start = 1e-12 * options.target.abs().max(1.0);
                let p_lim = if p_lim.abs() * d <= 1e-12 * q0 && p_lim.abs() <= start {
                    0.0
                } else {
                    p_lim
                };
                path.p_limit = Some(p_lim);
                if let (Some(b), Some(st)) = (path.breakpoints.last_mut(), path.steps.last_mut()) {
                    b.p = p_lim;
                    st.p = p_lim;
                    path.p_max = path.breakpoints.iter().fold(0.0f64, |a, b| a.max(b.p));
                }
                path.mechanism = Some(mechanism_mode(prep, &piv, last_entering, &alpha));
                match crossed {
                    Some(j) => Some((j, options.target)),
                    None if p_lim == 0.0 => None,
                    None => path.last_segment_containing(p_lim).map(|j| (j, p_lim)),
                }
            }
        }
        Ending::DriverLeft => {
            path.status = PathStatus::ReturnedToZero;
            match crossed {
                Some(j) => Some((j, options.target)),
                None => path.last_segment_containing(0.0).map(|j| (j, 0.0)),
            }
        }
        Ending::IterationLimit => {
            path.status = PathStatus::IterationLimit;
            match crossed {
                Some(j) => Some((j, options.target)),
                None => {
                    let p_end = piv.driver_value();
                    path.last_segment_containing(p_end).map(|j| (j, p_end))
                }
            }
        }
        Ending::Singular => {
            path.status = PathStatus::NumericalFailure;
            None
        }
    };
    if let (PathStatus::Mechanism, Some(p_lim)) = (path.status, path.p_limit) {
        if c0 > 0.0 && p_lim < options.target {
            if let Ok(pt) = fresh_solution(solver, options.target) {
                path.status = PathStatus::TargetReached;
                path.artificial_mechanism = Some(p_lim);
                path.solution = Some(pt);
                return path;
            }
        }
    }
    if let Some((seg, p)) = report {
        // Only verified, finite points are reported (`solution_on_segment`); none at all when
        // the real problem (without tightening) has no solution there.
        progress.phase(crate::Phase::Tightening);
        match solution_on_segment(solver, &path, seg, p) {
            Ok(pt) => path.solution = Some(pt),
            Err(why) => path.unreported = Some(why),
        }
        progress.pivots(path.solution.as_ref().map_or(0, |s| s.tightening_pivots));
    }
    if path.status == PathStatus::Mechanism && c0 == 0.0 {
        mechanism_at_start(solver, &mut path, kseg, options.target);
    }
    path
}

/// Every value `x = q0 + M z` of `point` (at `p = 0`) is round-off of the terms that form it
/// (`|q0| + |M|·|z|`, 1e-10 of the largest): a state without force — the gaps alone, closed
/// or not by a rigid motion of a structure that nothing holds (the tester's beams without a
/// constant load: their positions there are not determined, and the structure's check, its
/// forces being round-off, refused them).
fn carries_no_force(solver: &PathSolver, point: &PathPoint) -> bool {
    use crate::schur::DenseRates;
    let (_, terms) = solver.rows(&point.z, 0.0);
    let largest = terms
        .iter()
        .zip(solver.q0())
        .fold(0.0f64, |a, (t, q)| a.max(t + q.abs()));
    point.x.iter().all(|x| x.abs() <= 1e-10 * largest)
}

/// The state of a structure that becomes a mechanism as soon as the variable load is applied,
/// where the path's own report found none (an independent tester's beams on bearings):
///
/// * the limit read at `p = 0`, but every breakpoint lies there, so no segment of positive
///   length contains it: the state is the point at `p = 0` of the last segment containing it,
///   else of the latest basis at `p = 0` that verifies there (the settling's; the last one,
///   where the mechanism was found, is singular with the load held), else of a fresh solve —
///   unless that state carries no force ([`carries_no_force`], or `q0 = 0`): then nothing
///   fixes the structure's position, no state is reported and
///   [`LoadPath::unloaded_at_start`] says why;
/// * the limit read a round-off above zero (`|p|·‖d‖` within 1e-12 of `‖q0‖`: a frictionless
///   pair's tangential row blocking at its round-off, `p ≈ 2.7e-12` on a beam pushed sideways
///   by a small load) where no state exists — the problem has none for any `p > 0` — while
///   the constant load's state at `p = 0` is verified: the limit is `p = 0`, and the
///   breakpoints in between are there too.
///
/// Only a verified point changes the path; otherwise it stays as it was (no state, or the
/// reason none was reported).
fn mechanism_at_start(solver: &PathSolver, path: &mut LoadPath, kseg: usize, target: f64) {
    let Some(p_lim) = path.p_limit else { return };
    let (q0, d) = (max_abs(solver.q0()), max_abs(solver.d()));
    let at_start = p_lim == 0.0 && path.unreported.is_none() && path.solution.is_none();
    // Within round-off of the start: the variable load at `p_lim` round-off of the constant
    // one, and `p_lim` itself within 1e-9 of `p = 1` (or of the target) — a real limit at
    // `p = 0.83` beside an unrelated part under 1e18 N is not (a reviewer's portal, whose
    // tipping breakpoints a first version moved to 0). Whether or not a state was reported
    // at `p_lim` (a frictionless portal read its limit at `p = −1.1e-12` in N·m, with a state
    // at that negative load, and at `+1.4e-12` in kN·mm).
    let near_start = p_lim.abs() * d <= 1e-12 * q0 && p_lim.abs() <= 1e-9 * target.abs().max(1.0);
    // A limit below zero on a path that never carried a positive load is the start's too: the
    // loads never rise, only round-off takes them below zero (a reviewer's beam beside a
    // frictionless bearing read its limit at p = −3.1e-9 in N·m, a limit at a negative load,
    // and at −2.4e-7 in kN·mm, where no state was verified: exit 1).
    let below = p_lim < 0.0 && path.p_max <= 0.0;
    let round_off = p_lim != 0.0 && (near_start || below);
    if !(at_start || round_off) {
        return;
    }
    if q0 == 0.0 {
        // Nothing loads the pairs at p = 0 (no constant load; gaps that a rigid motion takes
        // up): the state there is zero.
        path.unloaded_at_start = at_start;
        return;
    }
    // The bases from the start to the limit, latest first (the last one is where the
    // mechanism was found: with the load held its entering column makes it singular); those
    // of the settling at p = 0 solve the problem there by construction. Then a fresh solve.
    let first = path.last_segment_containing(0.0);
    let (lo, hi) = (p_lim.min(0.0), p_lim.max(0.0));
    let at_zero = (0..=kseg).rev().filter(|&j| {
        path.breakpoints
            .get(j)
            .is_some_and(|b| (lo..=hi).contains(&b.p))
    });
    let point = first
        .into_iter()
        .chain(at_zero)
        .map(|j| basis_point_on_segment(solver, path, j, 0.0))
        .find_map(Result::ok)
        .or_else(|| fresh_solution(solver, 0.0).ok());
    let Some(point) = point else { return };
    // A state without force is no state (its position is not determined): the limit is the
    // start's all the same (a beam lifted 3.9 cm by a rigid motion, forces of 7e-9 N, read
    // its limit at a round-off of zero and was refused as unresolvable).
    if carries_no_force(solver, &point) {
        path.unloaded_at_start = true;
        path.solution = None;
    } else {
        path.solution = Some(point);
    }
    path.unreported = None;
    path.p_limit = Some(0.0);
    // The breakpoints whose variable load is round-off of the constant one are at p = 0 too
    // (on the tester's beam with its variable load 1e-7 times smaller, two pivots read at
    // p = 2.2e-9 between the start and the limit).
    let round_off_load = |p: f64| p.abs() * d <= 1e-12 * q0 || (p != 0.0 && lo <= p && p <= hi);
    for b in path.breakpoints.iter_mut().filter(|b| round_off_load(b.p)) {
        b.p = 0.0;
    }
    for st in path.steps.iter_mut().filter(|s| round_off_load(s.p)) {
        st.p = 0.0;
    }
    path.p_max = path.breakpoints.iter().fold(0.0f64, |a, b| a.max(b.p));
}

/// A path traced by the engine on sparse data ([`crate::SchurPath`]) as this solver's
/// [`LoadPath`]: the same pivots from the slack basis, the solution reported where
/// [`follow`] reports it, formed and verified from this solver's data. `None` when this
/// solver's start is not the slack basis (a tightening, or `q0` not `≥ 0`: the sparse engine
/// starts only there) or the pivots name variables of another order.
pub(crate) fn adopt(solver: &PathSolver, schur: crate::SchurPath) -> Option<LoadPath> {
    let (options, n) = (solver.options(), solver.order());
    if solver.c0 != 0.0 {
        return None;
    }
    let h = solver.q_traced();
    let hmax = max_abs(&h).max(f64::MIN_POSITIVE);
    if h.iter().any(|&v| v < -1e-13 * hmax) {
        return None;
    }
    let col = |v: Var| match v {
        Var::X(i) => i,
        Var::Z(i) => n + i,
        Var::Driver => 2 * n,
    };
    let in_range = |v: Var| matches!(v, Var::Driver) || col(v) < 2 * n;
    if schur
        .steps
        .iter()
        .any(|s| !in_range(s.entering) || !in_range(s.leaving))
    {
        return None;
    }
    let kseg = schur.steps.len();
    let p_end = schur.breakpoints.last().map_or(0.0, |b| b.p);
    let records = schur
        .steps
        .iter()
        .map(|s| (col(s.entering), col(s.leaving)))
        .collect();
    let p_max = schur.breakpoints.iter().fold(0.0f64, |a, b| a.max(b.p));
    let mut path = LoadPath {
        status: schur.status,
        steps: schur.steps,
        breakpoints: schur.breakpoints,
        p_max,
        p_limit: None,
        mechanism: None,
        last_entering: schur.last_entering.map(|c| Var::from_col(c, n)),
        solution: None,
        start_pivots: 0,
        refactorizations: schur.refactorizations,
        artificial_mechanism: None,
        unreported: None,
        unloaded_at_start: false,
        start_slots: (0..n).collect(),
        records,
        target_segment: schur.target_segment,
        judged_load_segments: Vec::new(),
    };
    let crossed = schur.target_segment;
    let report = match schur.status {
        PathStatus::TargetReached => {
            path.p_max = path.p_max.max(options.target);
            Some((kseg, options.target))
        }
        PathStatus::Ray => match crossed {
            Some(j) => Some((j, options.target)),
            None => Some((kseg, options.target.max(p_end))),
        },
        PathStatus::Mechanism => {
            path.p_limit = Some(p_end);
            if let (Some(e), Some((dx, dz))) = (schur.last_entering, &schur.mechanism_rates) {
                let norm = max_abs(dz).max(f64::MIN_POSITIVE);
                path.mechanism = Some(MechanismMode {
                    entering: Var::from_col(e, n),
                    dz: dz.iter().map(|v| v / norm).collect(),
                    dx: dx.iter().map(|v| v / norm).collect(),
                });
            }
            match crossed {
                Some(j) => Some((j, options.target)),
                None => path.last_segment_containing(p_end).map(|j| (j, p_end)),
            }
        }
        PathStatus::ReturnedToZero => match crossed {
            Some(j) => Some((j, options.target)),
            None => path.last_segment_containing(0.0).map(|j| (j, 0.0)),
        },
        PathStatus::IterationLimit => match crossed {
            Some(j) => Some((j, options.target)),
            None => path.last_segment_containing(p_end).map(|j| (j, p_end)),
        },
        PathStatus::NoSolutionAtStart | PathStatus::NumericalFailure => None,
    };
    if let Some((seg, p)) = report {
        match solution_on_segment(solver, &path, seg, p) {
            Ok(pt) => path.solution = Some(pt),
            Err(why) => path.unreported = Some(why),
        }
    }
    Some(path)
}

/// Whether a start basis (its slots) that the condensed data refuse solves the problem on the
/// structure's own equations ([`start_on_structure`]).
pub(crate) type StartJudge<'a> = dyn Fn(&[usize]) -> bool + 'a;

/// The complementary basis of the problem at `p = 0`, `x = h + M z` (`h = q0 + c·e`), and the
/// pivots spent finding it.
///
/// 1. `h ≥ 0`: the slack basis.
/// 2. Otherwise the tightening is followed down: from `h + t₀·e` with `t₀` twice the least
///    amount that makes it non-negative (a start with every row strictly positive where `h` is
///    not) the tightening is driven back to zero by complementary pivots with the problem's own
///    lexicographic order, exactly as the parametric path itself moves. `e` is the tightening's
///    direction (for friction `max(1, f)` on the tangential rows). Lemke's method with the
///    covering vector `e` would be the same path but starting on the degenerate vertex where
///    the first rows reach zero all at once; with `f > 1` and gaps the rows `x_n`, `x_t±` of
///    an open pair reach zero together there, and its arbitrary first pivot could enter a
///    friction part opposite a basic one — a ray (`M` has the null direction `z_t+ = z_t-`),
///    reported as "no solution at the start" although the pair simply sits open.
/// 3. Then Lemke's method with covering ones and, for `n ≤ 16`, enumeration of all bases.
///
/// A basis is taken only if its values, recomputed from the data, are feasible within their
/// round-off: a basic force not below `−ACCEPT_RESIDUAL` of its row's terms (the residual a
/// reported solution is verified within) or `−1e-12` of the largest value, a displacement not
/// below the latter (the pivoting reads a basic value below zero as zero); else, where
/// `on_structure` is given, as the structure's equations judge it. At a degenerate start the
/// value of a basic row that is zero by the statics comes out as the data's round-off: a steel
/// portal on feet with friction 0.05 spreads under its beam's load until both feet are at
/// their friction's capacity, one of them sticking with `x_t− = f·x_n + x_t = 0`; formed from
/// the condensed data in kN·mm it read −1.4e-12 of the largest, below the −1e-12 once asked
/// of every value, and every basis was refused: "no solution at the start" (in N·m the same
/// row read +1e-13).
pub(crate) fn start_basis(
    prep: &Prepared,
    d: &[f64],
    h: &[f64],
    dir: &[f64],
    settings: &Settings,
    on_structure: Option<&StartJudge>,
) -> (Option<Basis>, usize, bool) {
    let n = prep.n;
    let cols = prep.columns(h, d);
    let hmax = max_abs(&cols.h).max(f64::MIN_POSITIVE);
    if cols.h.iter().all(|&v| v >= -1e-13 * hmax) {
        return (Some(Basis::slack(n)), 0, false);
    }
    let feasible = |slots: Vec<usize>| -> Option<Basis> {
        let b = Basis::from_slots(&cols, slots).ok()?;
        let beta = b.solve(&cols, &cols.h);
        let scale = hmax.max(max_abs(&beta));
        // A basic force within `ACCEPT_RESIDUAL` of the terms of its own row,
        // `|h_i| + Σ_j |M_ij z_j|` (a part loaded a million times less than its neighbour is
        // judged on its own loads: measured against the largest value of the problem, a pair
        // loaded beyond its friction's capacity by 1e-3 of its load passed), or within `1e-12`
        // of the largest value as every value (the solve's round-off spreads across rows: a
        // frictionless portal free to slide starts with friction rows zero by the statics and
        // terms far below that round-off).
        let mut terms: Vec<f64> = cols.h.iter().map(|v| v.abs()).collect();
        let mut col = vec![0.0; n];
        for (&v, &z) in b.slot_var.iter().zip(&beta) {
            if (n..2 * n).contains(&v) && z != 0.0 {
                cols.col_into(v, &mut col);
                for (t, a) in terms.iter_mut().zip(&col) {
                    *t += (a * z).abs();
                }
            }
        }
        let ok = b.slot_var.iter().zip(&beta).all(|(&v, &x)| {
            let allowed = if v < n {
                (crate::ACCEPT_RESIDUAL * terms[v]).max(1e-12 * scale)
            } else {
                1e-12 * scale
            };
            x.is_finite() && x >= -allowed
        });
        // Refused on the condensed data: the structure's own equations, where they are at
        // hand, judge the basis's values ([`start_on_structure`]).
        (ok || on_structure.is_some_and(|judge| judge(&b.slot_var))).then_some(b)
    };
    let mut pivots = 0;
    // 2. Down the tightening.
    let t_min = h
        .iter()
        .zip(dir)
        .filter(|(&hi, _)| hi < 0.0)
        .map(|(&hi, &di)| if di > 0.0 { -hi / di } else { f64::INFINITY })
        .fold(0.0f64, f64::max);
    if t_min.is_finite() && t_min > 0.0 {
        let t0 = 2.0 * t_min;
        let h0: Vec<f64> = h.iter().zip(dir).map(|(a, e)| a + t0 * e).collect();
        let g: Vec<f64> = dir.iter().map(|e| -e).collect();
        let cols_t = prep.columns(&h0, &g);
        let (reached, spent) = drive_to_zero(&cols_t, Basis::slack(n), t0, settings, n);
        pivots += spent;
        if let Some(slots) = reached {
            if let Some(b) = feasible(slots) {
                return (Some(b), pivots, false);
            }
        }
    }
    // 3. Lemke's method, then enumeration.
    let run = lemke_run(prep, h, &vec![1.0; n], settings);
    pivots += run.pivots;
    let capped = matches!(run.outcome, LemkeOutcome::IterationLimit);
    if let LemkeOutcome::Solved(slots, _) = run.outcome {
        if let Some(b) = feasible(slots) {
            return (Some(b), pivots, false);
        }
    }
    if n <= 16 {
        // On the equilibrated problem, whose entries are of order one.
        let hhat = prep.scaling.scale_rows(h);
        if let Some((_, _, idx)) = enumerate_first(&prep.matrix(), &hhat) {
            let mut slots: Vec<usize> = (0..n).collect();
            for i in idx {
                slots[i] = n + i;
            }
            if let Some(b) = feasible(slots) {
                return (Some(b), pivots, false);
            }
        }
    }
    // The enumeration (n ≤ 16) answers for good: no solution is no solution, whatever the cap.
    (None, pivots, capped && n > 16)
}

fn basic_z(prep: &Prepared, slots: &[usize], beta: &[f64]) -> Vec<(usize, f64)> {
    let n = prep.n;
    slots
        .iter()
        .zip(beta)
        .filter(|&(&v, _)| v >= n && v < 2 * n)
        .map(|(&v, &b)| (v - n, b.max(0.0) * prep.scaling.col[v - n]))
        .collect()
}

pub(crate) fn mechanism_mode(
    prep: &Prepared,
    piv: &Pivoter,
    entering: usize,
    alpha: &[f64],
) -> MechanismMode {
    let n = prep.n;
    let mut dxs = vec![0.0; n];
    let mut dzs = vec![0.0; n];
    let mut set = |col: usize, v: f64| {
        if col < n {
            dxs[col] = v;
        } else if col < 2 * n {
            dzs[col - n] = v;
        }
    };
    set(entering, 1.0);
    for (s, &col) in piv.basis.slot_var.iter().enumerate() {
        set(col, -alpha[s]);
    }
    let mut dx = prep.scaling.unscale_x(&dxs);
    let mut dz = prep.scaling.unscale_z(&dzs);
    let norm = max_abs(&dz).max(f64::MIN_POSITIVE);
    dz.iter_mut().for_each(|v| *v /= norm);
    dx.iter_mut().for_each(|v| *v /= norm);
    MechanismMode {
        entering: Var::from_col(entering, n),
        dz,
        dx,
    }
}

/// The solution at `p` on segment `seg` without the tightening, or why there is none: the
/// segment's basis evaluated from the data, then a fresh standard solve at `p`.
pub(crate) fn solution_on_segment(
    solver: &PathSolver,
    path: &LoadPath,
    seg: usize,
    p: f64,
) -> Result<PathPoint, Unreported> {
    let path_basis = match basis_point_on_segment(solver, path, seg, p) {
        Ok(point) => return Ok(point),
        Err(verdict) => verdict,
    };
    // The condensed data refuse the basis by a value below zero beyond their round-off, or a
    // point they do not verify: the structure's own equations (double-double) are asked
    // before the fresh solve — their values judged by the same allowance, `1e-12` of the
    // largest of each kind, so that a basis whose value is really negative (an event before
    // `p`) is refused there too. The condensation's round-off can put a force that the
    // structure's data make zero below that allowance: a portal in kN·mm tipping at its
    // target had its lifting foot's force at −1.3e-11 of the forces on the condensed data,
    // +2e-11 on the structure's, and failed.
    if matches!(
        path_basis,
        BasisVerdict::Negative { .. } | BasisVerdict::Unverified { .. }
    ) && !path.judged_load_segments.contains(&seg)
    {
        if let Some(pt) = structure_point_signed(solver, path, seg, p) {
            return Ok(pt);
        }
    }
    fresh_solution(solver, p).map_err(|fresh| Unreported {
        p,
        path_basis,
        fresh,
    })
}

/// The solution at `p` from segment `seg`'s basis alone (evaluated from the data, the
/// tightening removed, verified), without the fresh standard solve of
/// [`solution_on_segment`]: whether that basis solves the problem there.
pub(crate) fn basis_point_on_segment(
    solver: &PathSolver,
    path: &LoadPath,
    seg: usize,
    p: f64,
) -> Result<PathPoint, BasisVerdict> {
    let (prep, settings) = (&solver.prep, solver.settings());
    let (c0, cov) = (solver.c0, &solver.cov[..]);
    let slots = segment_slots(path, seg, prep.n);
    // A segment whose direction came from the structure's equations: its point too, where it
    // solves the problem on this solver's data.
    if let (Some(slots), true) = (
        &slots,
        c0 == 0.0 && path.judged_load_segments.contains(&seg),
    ) {
        if let Some(pt) = structure_point(solver, slots, p) {
            return Ok(pt);
        }
    }
    let q_real: Vec<f64> = solver.q_at(p);
    let terms = solver.q_terms_at(p);
    let evaluated = match slots {
        Some(slots) => remove_tightening(prep, (&q_real, &terms), slots, c0, cov, settings),
        None => Err(BasisVerdict::Singular),
    };
    match evaluated {
        Ok((x, z, pivots)) => {
            let residual = solver.residual(p, &x, &z);
            let point = |x, z, residual| PathPoint {
                p,
                x,
                z,
                residual,
                tightening_pivots: pivots,
                fallback: false,
            };
            if residual.accepts(&x, &z) {
                return Ok(point(x, z, residual));
            }
            // Refused: the point formed once more from its equations. A basic `z` whose every
            // term `M_ij z_j` is round-off of the point's forces (64 ε of the largest of
            // `|q0| + |p·d|` and `x`) is the zero it is, and the basic `x` are formed again as
            // `q(p) + M z` (the others stay zero). A row that the data leave empty (a
            // frictionless pair's friction row: nothing of `q`, `d` or the basic `z` in it) is
            // met only by an exact zero, and the basis's solve left round-off there: 1.4e-17 N
            // beside a beam's other bearing at its limit in N·m; in kN·mm a slip starting at
            // that load read as 2.6e-17 mm put 1.4e-17 kN into it (the fresh solve failed).
            let forces = terms
                .iter()
                .zip(&x)
                .fold(0.0f64, |a, (t, xi)| a.max(*t).max(xi.abs()));
            let round_off =
                |j: usize, zj: f64| zj.abs() * solver.column_max(j) <= 64.0 * f64::EPSILON * forces;
            let z2: Vec<f64> = z
                .iter()
                .enumerate()
                .map(|(j, &zj)| {
                    if zj != 0.0 && round_off(j, zj) {
                        0.0
                    } else {
                        zj
                    }
                })
                .collect();
            let again = solver.x_of(p, &z2);
            let x2: Vec<f64> = (0..prep.n)
                .map(|i| if x[i] != 0.0 { again[i] } else { 0.0 })
                .collect();
            let residual2 = solver.residual(p, &x2, &z2);
            if residual2.accepts(&x2, &z2) {
                Ok(point(x2, z2, residual2))
            } else {
                Err(BasisVerdict::Unverified { residual })
            }
        }
        Err(verdict) => Err(verdict),
    }
}

/// The basis of segment `seg` of `path` (order `n`): the slots after its pivots, the driver's
/// slot taking the segment's entering column. `None` for a segment without one (the end of the
/// record), which has no basis to evaluate.
fn segment_slots(path: &LoadPath, seg: usize, n: usize) -> Option<Vec<usize>> {
    let mut slots = path.slots_after(seg);
    if let Some(ds) = slots.iter().position(|&v| v == 2 * n) {
        slots[ds] = path.segment_entering(seg, n)?;
    }
    Some(slots)
}

/// [`PathSolver::structure_solution_at`]: the point at `p` of the basis of the path's last
/// segment through `p`, formed on the structure's equations.
pub(crate) fn structure_point_at(
    solver: &PathSolver,
    path: &LoadPath,
    p: f64,
) -> Option<PathPoint> {
    if solver.c0 != 0.0 {
        return None;
    }
    let seg = path.last_segment_containing(p)?;
    structure_point(solver, &segment_slots(path, seg, solver.prep.n)?, p)
}

/// The values of the basis of the path's last segment at load `p`, formed on the structure's
/// own equations (the judge's); `None` without a judge, with a tightening, or where that basis
/// is singular there.
pub(crate) fn last_basis_on_structure(
    solver: &PathSolver,
    path: &LoadPath,
    p: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    if solver.c0 != 0.0 {
        return None;
    }
    structure_values(
        solver,
        &segment_slots(path, path.records.len(), solver.prep.n)?,
        p,
    )
}

/// `(x, z)` of the complementary basis `slots` at load `p` from the structure's equations
/// ([`crate::StructureJudge::point`]), where this solver has them.
fn structure_values(solver: &PathSolver, slots: &[usize], p: f64) -> Option<(Vec<f64>, Vec<f64>)> {
    let judge = solver.judge.as_ref()?;
    let mut basic = vec![false; 2 * solver.prep.n];
    for &v in slots {
        *basic.get_mut(v)? = true;
    }
    judge.point(&basic, p)
}

/// Whether the complementary basis `slots` solves the problem at `p = 0` on the structure's
/// own equations ([`structure_values`]): every value at least `−1e-12` of the largest of its
/// kind and the point, those set to zero, verified on this solver's data. A start that the
/// condensed data refuse by their round-off: a block lying without friction on a foundation,
/// held sideways by a 133 N/m spring (1e-9 of its stiffness), starts with its pairs' friction
/// rows zero by the statics, and the condensed data made them −2.7e-9 of the largest value in
/// N·m ("no solution at the start"; answered in kN·mm).
fn start_on_structure(solver: &PathSolver, slots: &[usize]) -> bool {
    let Some((x, z)) = structure_values(solver, slots, 0.0) else {
        return false;
    };
    match (signed(x), signed(z)) {
        (Some(x), Some(z)) => verified_point(solver, 0.0, x, z).is_some(),
        _ => false,
    }
}

/// The values `v` of one kind (`x` or `z`) with those within `1e-12` of the largest below zero
/// set to zero, where none is below that.
fn signed(v: Vec<f64>) -> Option<Vec<f64>> {
    let top = max_abs(&v).max(f64::MIN_POSITIVE);
    let v = clamp_at(&v, top);
    v.iter().all(|&a| a >= 0.0).then_some(v)
}

/// [`structure_values`] as a point, where it solves this solver's problem (verified on its
/// data, as every reported point is).
fn structure_point(solver: &PathSolver, slots: &[usize], p: f64) -> Option<PathPoint> {
    let (x, z) = structure_values(solver, slots, p)?;
    verified_point(solver, p, x, z)
}

/// `(x, z)` at `p` as a point of the path, where it is verified on this solver's data.
fn verified_point(solver: &PathSolver, p: f64, x: Vec<f64>, z: Vec<f64>) -> Option<PathPoint> {
    let residual = solver.residual(p, &x, &z);
    residual.accepts(&x, &z).then_some(PathPoint {
        p,
        x,
        z,
        residual,
        tightening_pivots: 0,
        fallback: false,
    })
}

/// The point of segment `seg`'s basis at `p` formed on the structure's equations
/// ([`structure_values`]), where every value is at least `−1e-12` of the largest of its kind
/// (`x`, `z`) and it is verified on this solver's data; the values within that allowance
/// below zero set to zero. `None` without a judge, with a tightening, or where the basis is
/// singular, negative or unverified there.
fn structure_point_signed(
    solver: &PathSolver,
    path: &LoadPath,
    seg: usize,
    p: f64,
) -> Option<PathPoint> {
    if solver.c0 != 0.0 {
        return None;
    }
    let (x, z) = structure_values(solver, &segment_slots(path, seg, solver.prep.n)?, p)?;
    verified_point(solver, p, signed(x)?, signed(z)?)
}

/// A solution at load `p` by a fresh standard solve (Lemke with fallbacks), verified; else how
/// that solve ended (`None`: it refused the data).
fn fresh_solution(solver: &PathSolver, p: f64) -> Result<PathPoint, Option<LcpStatus>> {
    let lcp = Lcp {
        m: solver.prep.original_matrix(),
        q: solver.q_at(p),
    };
    let sol = solve_lcp(&lcp, solver.settings()).map_err(|_| None)?;
    let status = sol.status;
    match (status, sol.point) {
        (LcpStatus::Solved, Some(pt)) => Ok(PathPoint {
            p,
            x: pt.w,
            z: pt.z,
            residual: pt.residual,
            tightening_pivots: sol.pivots,
            fallback: true,
        }),
        (LcpStatus::Solved, None) => Err(Some(LcpStatus::NumericalFailure)),
        (other, _) => Err(Some(other)),
    }
}

/// Evaluates the complementary basis `slots` at `x = q + M z` (no tightening). If it is not
/// feasible, drives the tightening `c` from `c0` down to zero by complementary pivots at fixed
/// load. Returns unscaled `(x, z)` and the pivots spent, or what went wrong. `terms` are the
/// sizes of the terms that formed `q` (`|q0| + |p·d|` a row): where they cancel — a beam lifted
/// off both its bearings at once by a load that takes their reactions to zero together — `q`
/// and the values are round-off, judged against the terms, not against themselves.
fn remove_tightening(
    prep: &Prepared,
    (q, terms): (&[f64], &[f64]),
    slots: Vec<usize>,
    c0: f64,
    cov: &[f64],
    settings: &Settings,
) -> Result<(Vec<f64>, Vec<f64>, usize), BasisVerdict> {
    let n = prep.n;
    let zero_g = vec![0.0; n];
    let cols = prep.columns(q, &zero_g);
    let basis = Basis::from_slots(&cols, slots.clone()).map_err(|_| BasisVerdict::Singular)?;
    let beta = basis.solve_refined(&cols, &cols.h);
    // The terms on the scale of `h` (its rows equilibrated, then by the power of two `2^eh`).
    let terms = crate::binary::ldexp(max_abs(&prep.scaling.scale_rows(terms)), -cols.eh);
    let hmax = max_abs(&cols.h)
        .max(max_abs(&beta))
        .max(terms)
        .max(f64::MIN_POSITIVE);
    if beta.iter().all(|&b| b >= -1e-12 * hmax) {
        // Zeroed on the scale the test above accepted them on (the data's and the values'):
        // on the values' alone, a value accepted as round-off of larger data was then
        // reported as negative.
        let (x, z) = prep.unscale(&slots, &cols.values(&clamp_at(&beta, hmax)));
        return nonnegative(x, z, 0);
    }
    if c0 <= 0.0 {
        let (x, z) = prep.unscale(&slots, &cols.values(&beta));
        return Err(most_negative(&x, &z));
    }
    // x = (q + c0·cov) − cov·t + M z with t = c0 − c going from 0 to c0.
    let h: Vec<f64> = q.iter().zip(cov).map(|(a, c)| a + c0 * c).collect();
    let g: Vec<f64> = cov.iter().map(|c| -c).collect();
    let cols_c = prep.columns(&h, &g);
    let basis = Basis::from_slots(&cols_c, slots).map_err(|_| BasisVerdict::Singular)?;
    let (reached, spent) = drive_to_zero(&cols_c, basis, c0, settings, n);
    let final_slots = reached.ok_or(BasisVerdict::TighteningNotRemoved { pivots: spent })?;
    let basis =
        Basis::from_slots(&cols, final_slots.clone()).map_err(|_| BasisVerdict::Singular)?;
    let beta = basis.solve_refined(&cols, &cols.h);
    let (x, z) = prep.unscale(&final_slots, &cols.values(&clamp(&beta)));
    nonnegative(x, z, spent)
}

/// The variable most negative against the largest of its kind (`x` or `z`).
fn most_negative(x: &[f64], z: &[f64]) -> BasisVerdict {
    let (xmax, zmax) = (max_abs(x), max_abs(z));
    let rel = |v: f64, top: f64| if top > 0.0 { v / top } else { v };
    let xs = x.iter().enumerate().map(|(i, &v)| (Var::X(i), v, xmax));
    let zs = z.iter().enumerate().map(|(i, &v)| (Var::Z(i), v, zmax));
    let (var, value, largest) = xs
        .chain(zs)
        .min_by(|a, b| rel(a.1, a.2).total_cmp(&rel(b.1, b.2)))
        .unwrap_or((Var::Driver, 0.0, 0.0));
    BasisVerdict::Negative {
        var,
        value,
        largest,
    }
}

/// Drives the auxiliary variable of `cols` (the driver, index `2n`, whose column is `g`) from
/// `t0` down to zero by complementary pivots from `basis`: the phase that both finds the start
/// at `p = 0` and removes the tightening. Returns the complementary basis reached (the driver
/// replaced by the last entering column), `None` when the drive stops short of zero, and the
/// pivots spent either way.
fn drive_to_zero(
    cols: &Columns,
    basis: Basis,
    t0: f64,
    settings: &Settings,
    n: usize,
) -> (Option<Vec<usize>>, usize) {
    let tol = Tolerances {
        pivot: settings.pivot_tol(),
        value: 1e-13,
    };
    let mut piv = Pivoter::new(
        cols,
        basis,
        tol,
        settings.priority(n),
        settings.refactor_interval,
    );
    let mut records = Vec::new();
    let mut crossed = None;
    let (ending, entering) = piv.run(
        2 * n,
        Some((t0, true)),
        settings.cap(n),
        &mut records,
        &mut crossed,
    );
    let Ending::TargetReached = ending else {
        return (None, piv.pivots);
    };
    let mut slots = piv.basis.slot_var.clone();
    if let Some(ds) = slots.iter().position(|&v| v == 2 * n) {
        slots[ds] = entering;
    }
    (Some(slots), piv.pivots)
}

/// Values within round-off below zero (`1e-12` of their largest) set to zero.
pub(crate) fn clamp(beta: &[f64]) -> Vec<f64> {
    clamp_at(beta, max_abs(beta).max(f64::MIN_POSITIVE))
}

/// Values within `1e-12 · scale` below zero set to zero; the others as they are.
pub(crate) fn clamp_at(beta: &[f64], scale: f64) -> Vec<f64> {
    beta.iter()
        .map(|&b| {
            if b < 0.0 && b >= -1e-12 * scale {
                0.0
            } else {
                b
            }
        })
        .collect()
}

/// The point if it satisfies the sign conditions (the residuals are computed by the caller).
fn nonnegative(
    x: Vec<f64>,
    z: Vec<f64>,
    pivots: usize,
) -> Result<(Vec<f64>, Vec<f64>, usize), BasisVerdict> {
    if x.iter().chain(&z).any(|&v| v < 0.0) {
        return Err(most_negative(&x, &z));
    }
    Ok((x, z, pivots))
}

/// The load at which step `k` (1-based) of `path` happens, computed afresh from the data: the
/// basis of the segment before it factorised anew, its values and the entering column's rates
/// solved with working-precision refinement ([`Basis::solve_refined`]), and the load where the
/// step's leaving variable reaches zero on that segment. `None` when the step or its basis is
/// not there (a singular basis, a step past the record).
pub(crate) fn event_load(solver: &PathSolver, path: &LoadPath, k: usize) -> Option<f64> {
    let prep = &solver.prep;
    let n = prep.n;
    let seg = k.checked_sub(1)?;
    let &(_, leaving) = path.records.get(seg)?;
    let entering = path.segment_entering(seg, n)?;
    let cols = prep.columns(&solver.q_traced(), solver.d());
    let slots = path.slots_after(seg);
    let basis = Basis::from_slots(&cols, slots.clone()).ok()?;
    let beta = basis.solve_refined(&cols, &cols.h);
    let mut column = vec![0.0; n];
    cols.axpy_col(&mut column, 1.0, entering);
    let alpha = basis.solve_refined(&cols, &column);
    let ls = slots.iter().position(|&v| v == leaving)?;
    let theta = beta[ls] / alpha[ls];
    // The driver's value where the leaving variable reaches zero: basic, it moves with the
    // entering column's rate; entering (the first segment), it is the step length itself.
    let t = match slots.iter().position(|&v| v == cols.driver()) {
        Some(ds) => beta[ds] - theta * alpha[ds],
        None if entering == cols.driver() => theta,
        None => return None,
    };
    let p = cols.driver_real(t);
    p.is_finite().then_some(p)
}

/// The solution without tightening at `p` on a traced path (see [`PathSolver::solution_at`]).
pub(crate) fn point_at(solver: &PathSolver, path: &LoadPath, p: f64) -> Option<PathPoint> {
    let seg = match path.last_segment_containing(p) {
        Some(j) if path.records.get(j).is_some() || j + 1 < path.breakpoints.len() => Some(j),
        _ => None,
    };
    let seg = seg.or_else(|| {
        (path.status == PathStatus::Ray && p >= path.breakpoints.last().map_or(0.0, |b| b.p))
            .then_some(path.records.len())
    });
    seg.and_then(|j| solution_on_segment(solver, path, j, p).ok())
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    fn prepared(rows: &[[f64; 3]]) -> Prepared {
        Prepared::new(&Mat::from_fn(3, 3, |i, j| rows[i][j]))
    }

    /// A basis that is not a solution at the load is diagnosed by the variable most negative
    /// against the largest of its kind, in the problem's units. By hand, for
    /// `M = [[2, 1, 0], [1, 3, 0], [0, 0, 1]]`, `q = (−2, 1, 3)` and the basis `{x1, z2, x3}`:
    /// `x2 = 1 + 3·z2 = 0` gives `z2 = −1/3`, then `x1 = −2 + z2 = −7/3` and `x3 = 3`. Against
    /// the largest of their kinds, `x1/3 = −0.78` and `z2/(1/3) = −1`: `z2` is named.
    #[test]
    fn a_basis_that_is_not_a_solution_names_its_most_negative_variable() {
        let prep = prepared(&[[2.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 1.0]]);
        let q = [-2.0, 1.0, 3.0];
        let settings = Settings::default();
        let cov = [0.0; 3];
        let verdict = remove_tightening(&prep, (&q, &q), vec![0, 4, 2], 0.0, &cov, &settings)
            .expect_err("the basis {x1, z2, x3} is infeasible at q");
        let BasisVerdict::Negative {
            var,
            value,
            largest,
        } = verdict
        else {
            panic!("{verdict:?}");
        };
        assert_eq!(var, Var::Z(1));
        assert!((value + 1.0 / 3.0).abs() < 1e-15, "{value}");
        assert!((largest - 1.0 / 3.0).abs() < 1e-15, "{largest}");
        // The solution's basis {z1, x2, x3} (z1 = 1, x2 = 2, x3 = 3) is accepted as it is.
        let (x, z, pivots) =
            remove_tightening(&prep, (&q, &q), vec![3, 1, 2], 0.0, &cov, &settings)
                .expect("the basis {z1, x2, x3} solves the problem at q");
        assert_eq!(pivots, 0);
        assert!((z[0] - 1.0).abs() < 1e-15 && (x[1] - 2.0).abs() < 1e-15 && x[2] == 3.0);
    }

    /// A value accepted as round-off below zero is reported as zero, on the scale it was
    /// accepted on (the data's and the values'), not as a negative one. By hand, for
    /// `M = [[1, 0.75, 0], [0.75, 1, 0], [0, 0, 1]]` (equilibrated as it is), `q = (−1, −1,
    /// 0.8e-12)` and the basis `{z1, z2, z3}`: `z1 = z2 = 1/1.75 = 4/7` and `z3 = −0.8e-12`,
    /// within `1e-12` of the data's largest (1) but not of the values' (4/7).
    #[test]
    fn a_value_accepted_as_round_off_is_reported_as_zero() {
        let prep = prepared(&[[1.0, 0.75, 0.0], [0.75, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        // The basis {z1, z2, z3} at q, without tightening.
        let evaluate = |q: &[f64]| {
            remove_tightening(
                &prep,
                (q, q),
                vec![3, 4, 5],
                0.0,
                &[0.0; 3],
                &Settings::default(),
            )
        };
        let (x, z, pivots) =
            evaluate(&[-1.0, -1.0, 0.8e-12]).expect("z3 = −0.8e-12 is round-off of data of size 1");
        assert_eq!(pivots, 0);
        assert_eq!(z[2], 0.0);
        assert!((z[0] - 4.0 / 7.0).abs() < 1e-15 && (z[1] - 4.0 / 7.0).abs() < 1e-15);
        assert!(x.iter().all(|&v| v == 0.0), "{x:?}");
        // Twice as far below zero it is a negative value, named.
        let verdict = evaluate(&[-1.0, -1.0, 2.5e-12])
            .expect_err("z3 = −2.5e-12 is not round-off of data of size 1");
        assert!(
            matches!(verdict, BasisVerdict::Negative { var: Var::Z(2), .. }),
            "{verdict:?}"
        );
    }

    /// A value below zero by round-off of the terms that formed `q` (`q` itself their
    /// cancellation) is zero: `M = I`, `q = (−2.8e-14, 1e-14, 2e-14)`, its first row formed from
    /// terms of 400 (a reaction of `200 − 500·0.4`), the basis `{x1, x2, x3}`: `x1 = −2.8e-14` is
    /// 7e-17 of the terms, accepted and reported as zero; judged against `q` alone (all its rows
    /// of round-off size) it is named negative.
    #[test]
    fn a_value_below_zero_by_round_off_of_cancelling_terms_is_zero() {
        let prep = prepared(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let q = [-2.8e-14, 1e-14, 2e-14];
        let evaluate = |terms: &[f64]| {
            let settings = Settings::default();
            remove_tightening(&prep, (&q, terms), vec![0, 1, 2], 0.0, &[0.0; 3], &settings)
        };
        let (x, _, _) = evaluate(&[400.0, 1e-14, 2e-14]).expect("round-off of terms of 400");
        assert_eq!(x, vec![0.0, 1e-14, 2e-14]);
        let verdict = evaluate(&q).expect_err("against q alone: negative");
        assert!(
            matches!(verdict, BasisVerdict::Negative { var: Var::X(0), .. }),
            "{verdict:?}"
        );
    }

    /// A basis whose kernel is singular on the data is said to be so: `{z1, z2, x3}` of
    /// `M = [[1, 1, 0], [1, 1, 0], [0, 0, 1]]` has the kernel `[[1, 1], [1, 1]]`.
    #[test]
    fn a_singular_basis_is_said_to_be_singular() {
        let prep = prepared(&[[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let verdict = remove_tightening(
            &prep,
            (&[-1.0, -1.0, 1.0], &[1.0, 1.0, 1.0]),
            vec![3, 4, 2],
            0.0,
            &[0.0; 3],
            &Settings::default(),
        )
        .expect_err("a singular kernel");
        assert_eq!(verdict, BasisVerdict::Singular);
    }
}
