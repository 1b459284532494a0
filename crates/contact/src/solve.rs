//! Solving a contact zone along the load path: the normalised `3m` LCP handed to the engine,
//! and the engine's path read as pair states and events ([`ContactSolution`]).

use std::sync::{Arc, OnceLock};

use unilateral_lcp::{
    BasisVerdict, LcpStatus, PathOptions, PathSolver, PathStatus, Settings, Unreported, Var,
};

use crate::lcp::{label, load_vectors, ContactLcp};
use crate::solution::Engine;
use crate::units::Units;
use crate::{
    ContactError, ContactSolution, ContactZone, Event, EventKind, LoadStep, Outcome, SolveSettings,
};

/// The engine's settings of a solve: the user's (pivot tolerance, pivot cap, …) with the
/// formulation's lexicographic order and covering direction.
fn engine_settings(lcp: &ContactLcp, s: &SolveSettings) -> Settings {
    Settings {
        lexicographic_order: Some(lcp.lexicographic_order.clone()),
        // The start at p = 0 follows a tightening down; without one given, in the direction
        // that keeps friction consistent (`max(1, f)` on the tangential rows).
        covering: Some(lcp.tightening_direction.clone()),
        row_relations: lcp.row_relations(),
        ..s.engine.clone()
    }
}

/// Follows the load path of a contact zone and reads the answer as pair states and events.
///
/// ```
/// use faer::mat;
/// use unilateral_contact::{solve, ContactZone, Follow, Outcome, PairState, SolveSettings};
///
/// // The paper's Example 1: a beam on three supports, load in the right span.
/// let mut zone = ContactZone::new(
///     mat![[0.1875, -0.375, 0.1875], [-0.375, 0.75, -0.375], [0.1875, -0.375, 0.1875]],
///     mat![[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]],
/// );
/// zone.friction = vec![0.6; 3];
/// zone.variable.normal = vec![-0.09375, 0.6875, 0.40625];
/// let settings = SolveSettings { tightening: 1.0, follow: Follow::ToEnd, ..Default::default() };
/// let sol = solve(&zone, &settings).unwrap();
/// assert!(matches!(sol.outcome, Outcome::Ray { .. }));
/// assert_eq!(sol.steps[0].events[0].to_string(), "pair 1 opens");
/// assert_eq!(sol.pairs[0].state, PairState::Open);
/// assert!((sol.pairs[0].z_n - 0.5).abs() < 1e-12);
/// assert!((sol.pairs[1].x_n - 0.5).abs() < 1e-12);
/// ```
///
/// The solution keeps a copy of the zone ([`ContactSolution::zone`]); [`solve_shared`] shares
/// the caller's instead.
pub fn solve(
    zone: &ContactZone,
    settings: &SolveSettings,
) -> Result<ContactSolution, ContactError> {
    solve_shared(Arc::new(zone.clone()), settings)
}

/// [`solve`] on a zone the solution shares with the caller: the solution keeps the zone (its
/// blocks are what the traced path's forces are formed from) and no copy of it is made, so a
/// large zone is held once.
pub fn solve_shared(
    zone: Arc<ContactZone>,
    settings: &SolveSettings,
) -> Result<ContactSolution, ContactError> {
    solve_sparse(zone, None, settings)
}

/// [`solve_shared`], the path traced by the engine on sparse data
/// ([`unilateral_lcp::follow_schur_path`]) on `sparse` — the same zone as the bonded
/// structure's blocks — where it applies: no tightening and a start at the bonded state
/// (`q(0) ≥ 0`). The dense solver judges the rates the sparse data cannot tell from
/// round-off and takes that path as its own ([`PathSolver::follow_sparse`]): it forms and
/// verifies the reported solution, and a ray's basis far along it, and answers every later
/// question on it. Where the sparse engine does not apply, fails, or ends otherwise than at
/// the target or in a verified ray, the dense engine traces the path.
pub fn solve_sparse(
    zone: Arc<ContactZone>,
    sparse: Option<&crate::SparseZone>,
    settings: &SolveSettings,
) -> Result<ContactSolution, ContactError> {
    solve_with(zone, sparse, true, settings)
}

/// [`solve_shared`] with the structure's sparse blocks at hand (`sparse`: the same zone as the
/// bonded structure's blocks): the dense engine traces the path and, without a tightening,
/// judges on those blocks the load rates the condensed data cannot tell from round-off
/// ([`unilateral_lcp::PathSolver::judged_on`]) — a beam sliding on its bearings at constant
/// load is a mechanism there, where the condensed data give the load a rate of their
/// round-off.
pub fn solve_judged(
    zone: Arc<ContactZone>,
    sparse: Option<&crate::SparseZone>,
    settings: &SolveSettings,
) -> Result<ContactSolution, ContactError> {
    solve_with(zone, sparse, false, settings)
}

/// [`solve_sparse`] (`trace_sparse`) or [`solve_judged`].
fn solve_with(
    zone: Arc<ContactZone>,
    sparse: Option<&crate::SparseZone>,
    trace_sparse: bool,
    settings: &SolveSettings,
) -> Result<ContactSolution, ContactError> {
    zone.validate()?;
    settings.validate()?;
    // The LCP that is solved: normalised by powers of two (module `units`), so that neither the
    // states nor the events depend on the units of the data.
    let units = Units::of(&zone, settings.tightening);
    let normalised_zone = units.normalise(&zone);
    // The data's own force scales, without `c`, normalised: the constant load with the gap
    // forces, and the variable load at p = 1 (a reported point at p is judged against the
    // loads it carries, the constant ones and p times the variable ones).
    let data_force = crate::units::load_scales(&normalised_zone);
    let normalised = ContactLcp::build(&normalised_zone);
    // Its four m × m blocks are not needed after the LCP is built: not held along the path
    // (0.44·n² doubles of the peak at m = 2000, n = 3m).
    drop(normalised_zone);
    let nm = &normalised.problem;
    for j in 0..nm.m.ncols() {
        for i in 0..nm.m.nrows() {
            if !nm.m[(i, j)].is_finite() {
                let pair = i % zone.pairs();
                return Err(ContactError::OutOfRange(format!(
                    "friction of pair {} ({}) times the contact stiffness exceeds the \
                     floating-point range",
                    zone.pair_names[pair], zone.friction[pair]
                )));
            }
        }
    }
    if let Some(i) = nm.q0.iter().chain(&nm.d).position(|v| !v.is_finite()) {
        let pair = i % zone.pairs();
        return Err(ContactError::OutOfRange(format!(
            "friction of pair {} ({}) times its loads exceeds the floating-point range",
            zone.pair_names[pair], zone.friction[pair]
        )));
    }
    let normalised_options = PathOptions {
        target: settings.target,
        follow: settings.follow,
        tightening: normalised.tightening(units.normalised_force(settings.tightening)),
    };
    let engine = engine_settings(&normalised, settings);
    // The structure's blocks in the solver's units, where they apply (no tightening).
    let sparse_lcp = sparse
        .filter(|sparse| settings.tightening == 0.0 && sparse.pairs() == zone.pairs())
        .map(|sparse| units.normalise_sparse(sparse).lcp());
    let judge = sparse_lcp
        .as_ref()
        .map(|lcp| Arc::new(unilateral_lcp::StructureJudge::new(lcp.clone())));
    let progress = engine.progress.clone();
    let traced_sparse = sparse_lcp.as_ref().filter(|_| trace_sparse);
    let (solver, traced) = match traced_sparse {
        Some(lcp) => {
            // The sparse engine's options: the solver's order, relations and progress.
            let schur_options = unilateral_lcp::SchurOptions {
                target: settings.target,
                follow: settings.follow,
                // A long path takes about 2n pivots; beyond 6n the sparse engine is more
                // likely wandering in ill-conditioned ties than tracing, and the dense engine
                // takes over.
                max_pivots: engine.max_pivots.unwrap_or(6 * 3 * zone.pairs() + 100),
                // Refactorised when the border passes 28 changes: a border's columns are
                // passed over by every solve, a refactorisation costs about ten of them (the
                // 2000-bearing beam's path 13.3 s at 28, 14.0 s at 40, 13.7 s at 24).
                max_border: 28,
                order: engine.lexicographic_order.clone(),
                relations: engine.row_relations.clone(),
                progress: engine.progress.clone(),
            };
            // Taken where it reaches the target, or ends in a ray that verifies far along
            // it, its doubtful rates judged on the dense data (`PathSolver::follow_sparse`);
            // the dense solver is built on a second thread while the path is traced.
            PathSolver::new_following_sparse(
                normalised.problem,
                normalised_options,
                engine,
                judge,
                lcp,
                &schur_options,
            )?
        }
        None => {
            // The solver takes the normalised LCP and holds its `M` once (equilibrated); the
            // LCP in the user's units, shown in tableaux and labels, is built only after the
            // path, so that the pivoting's kernel matrices never meet a second `n × n` matrix.
            let mut solver = PathSolver::new(normalised.problem, normalised_options, engine)?;
            // The structure's own equations judge the rates the condensed data cannot tell
            // from round-off.
            if let Some(judge) = judge {
                solver.judged_on(judge);
            }
            (solver, None)
        }
    };
    let traced_on_sparse_blocks = traced.is_some();
    let mut path = traced.unwrap_or_else(|| {
        if traced_sparse.is_some() {
            // The sparse engine's path was not taken: the counts start again with the dense
            // engine's.
            progress.restart_path();
        }
        solver.follow()
    });
    let m = zone.pairs();
    let names = zone.pair_names.clone();
    // Which pairs are open, followed along the path, to read friction events of open pairs.
    let mut open = vec![false; m];
    if let Some(start) = path.breakpoints.first() {
        let zmax = start.z.iter().fold(1.0f64, |a, &(_, v)| a.max(v.abs()));
        for &(i, v) in &start.z {
            if i < m && v > 1e-9 * zmax {
                open[i] = true;
            }
        }
    }
    let tightened = settings.tightening > 0.0;
    // The pivots that settle the scheme at p = 0: the steps at p = 0 to round-off of the
    // loads — of the user's load (p = 1) or of those the path reaches where it goes further;
    // not of the target, which may lie far beyond them (with a target of 1e14 the first event,
    // at p = 10.7, read as settling), and never less than p = 1's (a small target would make
    // the round-off pivots of the start events).
    let p_reached = path.steps.iter().fold(1.0f64, |a, s| a.max(s.p.abs()));
    // A path that comes back to p = 0 (returned to zero, the load leaving the basis) does so
    // by an event, not a settling pivot; pivots at loads of round-off after the path has
    // wandered by round-off (the cylinder's, up to 7e-9 and back) still settle it.
    let at_start = |s: &unilateral_lcp::Step| {
        s.p.abs() <= 1e-12 * p_reached && s.leaving != unilateral_lcp::Var::Driver
    };
    let steps: Vec<LoadStep> = path
        .steps
        .iter()
        .map(|s| {
            let mut events = events_of(s.leaving, m, &names);
            for e in &mut events {
                match e.kind {
                    EventKind::Opens => open[e.pair] = true,
                    EventKind::Closes => open[e.pair] = false,
                    _ => e.while_open = open[e.pair],
                }
            }
            // A friction part of an open pair changing is no physical event: no force is
            // transmitted. With a tightening it spends the sideways capacity that the
            // tightening lends an open pair, and is listed as such; without one it is only the
            // pivoting's bookkeeping, and is not listed at all.
            if !tightened {
                events.retain(|e| !e.while_open);
            }
            LoadStep {
                index: s.index,
                settling: at_start(s),
                p: s.p,
                entering: label(m, s.entering),
                leaving: label(m, s.leaving),
                events,
                turning: s.turning,
            }
        })
        .collect();
    // Back to the user's units: the traced z, the mechanism's force rates; the solution is
    // read below from the normalised point.
    let normalised_solution = path.solution.clone();
    for b in &mut path.breakpoints {
        for (_, v) in &mut b.z {
            *v = units.user_displacement(*v);
        }
    }
    if let Some(mm) = &mut path.mechanism {
        for v in &mut mm.dx {
            *v = units.user_stiffness(*v);
        }
    }
    if let Some(BasisVerdict::Negative {
        var,
        value,
        largest,
    }) = path.unreported.as_mut().map(|u| &mut u.path_basis)
    {
        let user = |v: f64| match var {
            Var::X(_) => units.user_force(v),
            _ => units.user_displacement(v),
        };
        (*value, *largest) = (user(*value), user(*largest));
    }
    if let Some(sol) = &mut path.solution {
        sol.x.iter_mut().for_each(|v| *v = units.user_force(*v));
        sol.z
            .iter_mut()
            .for_each(|v| *v = units.user_displacement(*v));
    }
    let outcome = match path.status {
        PathStatus::TargetReached => Outcome::TargetReached,
        PathStatus::Ray => Outcome::Ray {
            p_from: path.steps.last().map_or(0.0, |s| s.p),
        },
        PathStatus::Mechanism => Outcome::Mechanism {
            p_limit: path.p_limit.unwrap_or(0.0),
            mode: path
                .mechanism
                .as_ref()
                .map(|mm| {
                    (0..m)
                        .map(|i| (mm.dz[i], (mm.dz[m + i] - mm.dz[2 * m + i]) / 2.0))
                        .collect()
                })
                .unwrap_or_default(),
        },
        PathStatus::ReturnedToZero => Outcome::ReturnedToZero,
        PathStatus::IterationLimit => Outcome::IterationLimit,
        PathStatus::NoSolutionAtStart => Outcome::NoSolutionAtStart,
        PathStatus::NumericalFailure => Outcome::NumericalFailure,
    };
    let mut notes = Vec::new();
    if outcome == Outcome::NoSolutionAtStart {
        notes.extend(start_diagnosis(&zone));
    }
    let no_constant = zone.is_homogeneous();
    if settings.tightening > 0.0 && no_constant {
        notes.push(format!(
            "the tightening c = {} is artificial and there is no constant load: the loads of the \
             intermediate events depend on c, the final working scheme does not",
            crate::solution::number_text(settings.tightening)
        ));
    } else if settings.tightening > 0.0 {
        notes.push(format!(
            "the tightening c = {} is artificial: the loads of the events depend on it; the \
             reported solution does not contain it",
            crate::solution::number_text(settings.tightening)
        ));
    }
    if settings.tightening == 0.0 && no_constant {
        notes.push(
            "the problem is homogeneous (no constant load, no gaps, no tightening): the working \
             scheme is the same for every p > 0 — the one settled at p = 0 — and every force and \
             displacement is proportional to p; the pivots at p = 0 are not events"
                .into(),
        );
    }
    if steps.iter().any(|s| s.turning) {
        notes.push(
            "the load decreased at a step (a turning point of the load path): the solution at a \
             given load may not be unique"
                .into(),
        );
    }
    if let Some((from, to, pair)) =
        first_slip_decrease(&path, &zone.friction, settings.tightening == 0.0)
    {
        notes.push(format!(
            "between p = {} and p = {} the slip of pair {} decreases along the path: from there \
             the paper's friction law (total slip tied to total force) is not a real one — a \
             slip that reverses or is given back dissipates no energy in it; a [[history]] \
             gives the path-dependent answer",
            crate::solution::number_text(from),
            crate::solution::number_text(to),
            names[pair]
        ));
    }
    if let Some(why) = &path.unreported {
        notes.push(unreported_note(why, m, &names));
    }
    if path.unloaded_at_start {
        notes.push(format!(
            "{}: the structure is a mechanism as soon as the variable load is applied, and at \
             p = 0 no pair carries a force beyond the round-off of the forces its gaps make term \
             by term (no constant load reaches the pairs, or one too small to resolve against \
             the gaps), so nothing fixes the structure's position there",
            crate::solution::NO_STATE_AT_START
        ));
    }
    let solution = normalised_solution;
    if let Some(p_art) = path.artificial_mechanism {
        notes.push(format!(
            "the path traced with the artificial tightening c = {} ended in a mechanism at \
             p = {p_art:.6}; that limit belongs to the tightening, not to the structure: the real \
             problem has a verified solution at the target, found by a fresh solve there (the \
             events between p = {p_art:.6} and the target are not traced)",
            settings.tightening
        ));
    } else if let Some(sol) = &solution {
        if sol.fallback {
            notes.push(format!(
                "{}; the reported solution comes from a fresh solve at this load and may \
                 belong to another branch",
                if settings.tightening > 0.0 {
                    "the tightening could not be removed along the path"
                } else {
                    "the path's working scheme gave no verified point at this load"
                }
            ));
        }
    }
    let steps_before_target = path.target_segment.unwrap_or(steps.len());
    let mut out = ContactSolution {
        outcome,
        p: None,
        tightening: settings.tightening,
        settings: settings.clone(),
        steps,
        steps_before_target,
        pairs: Vec::new(),
        residual: None,
        notes,
        tightening_pivots: 0,
        traced_on_sparse_blocks,
        zone,
        lcp: OnceLock::new(),
        m_big: OnceLock::new(),
        path,
        engine: Arc::new(Engine {
            solver,
            units,
            names,
            data_force,
        }),
    };
    if let Some(sol) = solution {
        out.set_point(&sol)?;
    }
    Ok(out)
}

/// Why no solution is reported at `why.p`, for the reader: what the traced working scheme gave
/// there and how the fresh solve ended (values in the model's units).
pub(crate) fn unreported_note(why: &Unreported, m: usize, names: &[String]) -> String {
    let basis = match &why.path_basis {
        BasisVerdict::Singular => {
            "the working scheme traced there is numerically singular on the data".to_string()
        }
        BasisVerdict::Negative {
            var,
            value,
            largest,
        } => {
            let (pair, what) = match *var {
                Var::X(i) => (i % m, "forces"),
                Var::Z(i) => (i % m, "displacements"),
                Var::Driver => (0, "values"),
            };
            format!(
                "the working scheme traced there is not a solution of the data: {} of pair {} is \
                 {value:.6e}, negative beyond round-off ({what} there up to {largest:.3e}) — the \
                 traced path passed an event that the data put before this load (its updated \
                 values lost that much precision this far along it)",
                label(m, *var),
                names.get(pair).map_or("?", |s| s.as_str()),
            )
        }
        BasisVerdict::TighteningNotRemoved { pivots } => format!(
            "the tightening could not be removed from the working scheme traced there (the drive \
             stopped after {pivots} pivot{})",
            if *pivots == 1 { "" } else { "s" }
        ),
        BasisVerdict::Unverified { residual } => format!(
            "the point of the working scheme traced there fails verification (residuals: \
             equation {:.3e}, sign {:.3e}, complementarity {:.3e}; accepted up to {:.0e})",
            residual.equation,
            residual.feasibility,
            residual.complementarity,
            unilateral_lcp::ACCEPT_RESIDUAL
        ),
    };
    let fresh = match why.fresh {
        Some(LcpStatus::Ray) => "found no solution (Lemke's method ended on a ray with every \
                                 covering vector)"
            .to_string(),
        Some(LcpStatus::IterationLimit) => "reached its pivot cap".to_string(),
        Some(LcpStatus::NumericalFailure) | Some(LcpStatus::Solved) => {
            "could not produce a verified point (numerical_failure)".to_string()
        }
        None => "refused the data".to_string(),
    };
    format!(
        "no solution is reported at p = {}: {basis}; a fresh solve at that load {fresh}",
        crate::solution::number_text(why.p)
    )
}

/// Whether the missing solution of `why` is the program's failure rather than an answer: the
/// path's own working scheme (without a tightening to remove) should be the solution there, or
/// the fresh solve failed numerically. Only a tightened path whose real problem Lemke's method
/// finds without a solution is an answer.
pub(crate) fn unreported_is_failure(why: &Unreported, tightening: f64) -> bool {
    tightening <= 0.0 || !matches!(why.fresh, Some(LcpStatus::Ray | LcpStatus::IterationLimit))
}

/// The first segment (from, to, pair) between breakpoints over which a slip part `z_t±` of a
/// frictional pair (`f > 0`: without friction a slip is free motion, no friction law's) in
/// contact at both ends (`z_n = 0`: an open pair's tangential motion is free too) is smaller at the end than at the start (relative to the largest slip of
/// the two), while the load grows by more than its round-off (`1e-12` of the path's largest
/// load: the pivots at one load where a mechanism sets in are no growth). With `untightened`
/// (the traced path is the real one, c = 0) also the reported solution against the last
/// breakpoint before it (a slip given back on the last segment, where no breakpoint follows: a
/// single pair slipping at p = 0 and pressed harder as p grows).
fn first_slip_decrease(
    path: &unilateral_lcp::LoadPath,
    friction: &[f64],
    untightened: bool,
) -> Option<(f64, f64, usize)> {
    let m = friction.len();
    // The slip parts `[z_t+; z_t-]` of a point and whether each pair is open.
    let slips = |z: &mut dyn Iterator<Item = (usize, f64)>| -> (Vec<f64>, Vec<bool>) {
        let (mut v, mut open) = (vec![0.0; 2 * m], vec![false; m]);
        for (i, z) in z {
            if i < m {
                open[i] = z > 0.0;
            } else if i < 3 * m {
                v[i - m] = z;
            }
        }
        (v, open)
    };
    let decrease = |(prev, o1): &(Vec<f64>, Vec<bool>), (now, o2): &(Vec<f64>, Vec<bool>)| {
        let top = prev.iter().chain(now).fold(0.0f64, |a, v| a.max(v.abs()));
        (0..2 * m)
            .find(|&k| {
                friction[k % m] > 0.0 && !o1[k % m] && !o2[k % m] && prev[k] - now[k] > 1e-9 * top
            })
            .map(|k| k % m)
    };
    let of = |b: &unilateral_lcp::Breakpoint| slips(&mut b.z.iter().copied());
    let sol = path
        .solution
        .as_ref()
        .filter(|s| untightened && !s.fallback);
    let grows = {
        let top = path
            .breakpoints
            .iter()
            .map(|b| b.p.abs())
            .chain(sol.map(|s| s.p.abs()))
            .fold(0.0f64, f64::max);
        move |from: f64, to: f64| to - from > 1e-12 * top
    };
    let first = path.breakpoints.first()?;
    let mut prev = of(first);
    let mut p_prev = first.p;
    for b in path.breakpoints.iter().skip(1) {
        let now = of(b);
        if grows(p_prev, b.p) {
            if let Some(pair) = decrease(&prev, &now) {
                return Some((p_prev, b.p, pair));
            }
        }
        prev = now;
        p_prev = b.p;
    }
    // The reported solution against the breakpoint it follows (the last before the first one
    // beyond it).
    let sol = sol?;
    let beyond = path
        .breakpoints
        .iter()
        .position(|b| b.p > sol.p)
        .unwrap_or(path.breakpoints.len());
    let last = &path.breakpoints[beyond.checked_sub(1)?];
    if grows(last.p, sol.p) {
        let now = slips(&mut sol.z.iter().copied().enumerate());
        return decrease(&of(last), &now).map(|pair| (last.p, sol.p, pair));
    }
    None
}

/// Why p = 0 may have no solution: the pairs whose normal link the constant load (with the
/// gaps) puts in tension in the bonded structure, with those forces.
fn start_diagnosis(zone: &ContactZone) -> Option<String> {
    let m = zone.pairs();
    let (q0, _) = load_vectors(zone);
    let pulled: Vec<String> = (0..m)
        .filter(|&i| q0[i] < 0.0)
        .map(|i| format!("pair {} ({:.6e})", i + 1, q0[i]))
        .collect();
    if pulled.is_empty() {
        return None;
    }
    let all = if pulled.len() == m {
        "every pair: "
    } else {
        ""
    };
    Some(format!(
        "at p = 0 the constant load (with the gaps) pulls {all}{} apart — these are the normal \
         link forces of the bonded structure, compression positive — and no position of the \
         structure balances it with the pairs that stay: check the sign of the constant normal \
         loads and that the structure is held against them",
        pulled.join(", ")
    ))
}

pub(crate) fn events_of(leaving: Var, m: usize, names: &[String]) -> Vec<Event> {
    let ev = |i: usize, kind| {
        vec![Event {
            pair: i % m,
            name: names[i % m].clone(),
            kind,
            while_open: false,
        }]
    };
    match leaving {
        Var::X(i) if i < m => ev(i, EventKind::Opens),
        Var::X(i) if i < 2 * m => ev(i, EventKind::StartsSlippingPlus),
        Var::X(i) => ev(i, EventKind::StartsSlippingMinus),
        Var::Z(i) if i < m => ev(i, EventKind::Closes),
        Var::Z(i) => ev(i, EventKind::Sticks),
        Var::Driver => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    // Reference: the source of the note, whose continuation lines must not leave runs of
    // spaces mid-sentence.
    #[test]
    fn notes_have_no_runs_of_spaces() {
        let src = include_str!("solve.rs");
        let start = src.find("ended in a mechanism at").unwrap();
        let note = &src[start..start + 400];
        assert!(
            note.contains("at \\\n"),
            "continuation backslash lost: {note}"
        );
    }

    use super::{unreported_is_failure, unreported_note};
    use unilateral_lcp::{BasisVerdict, LcpStatus, Residual, Unreported, Var};

    fn why(path_basis: BasisVerdict, fresh: Option<LcpStatus>) -> Unreported {
        Unreported {
            p: 1500.0,
            path_basis,
            fresh,
        }
    }

    /// Each reason for a missing solution reads as one sentence (no runs of spaces from
    /// continuation lines) that names the load, the variable with its pair's name, the values
    /// and how the fresh solve ended.
    #[test]
    fn a_missing_solution_says_why() {
        let names: Vec<String> = ["left", "middle", "right"].map(String::from).to_vec();
        let negative = BasisVerdict::Negative {
            var: Var::Z(3 + 2),
            value: -1.25e-3,
            largest: 3.0e8,
        };
        let note = unreported_note(
            &why(negative.clone(), Some(LcpStatus::NumericalFailure)),
            3,
            &names,
        );
        for part in [
            "no solution is reported at p = 1500",
            "z_t3+ of pair right is -1.250000e-3",
            "displacements there up to 3.000e8",
            "could not produce a verified point (numerical_failure)",
        ] {
            assert!(note.contains(part), "{part:?} not in {note}");
        }
        let residual = Residual {
            equation: 2.5e-7,
            feasibility: 0.0,
            complementarity: 1e-12,
        };
        let notes = [
            unreported_note(&why(negative, None), 3, &names),
            unreported_note(
                &why(BasisVerdict::Singular, Some(LcpStatus::Ray)),
                3,
                &names,
            ),
            unreported_note(
                &why(
                    BasisVerdict::TighteningNotRemoved { pivots: 7 },
                    Some(LcpStatus::IterationLimit),
                ),
                3,
                &names,
            ),
            unreported_note(&why(BasisVerdict::Unverified { residual }, None), 3, &names),
        ];
        assert!(notes[1].contains("numerically singular") && notes[1].contains("ray"));
        assert!(notes[2].contains("after 7 pivots") && notes[2].contains("pivot cap"));
        assert!(notes[3].contains("equation 2.500e-7"), "{}", notes[3]);
        for n in notes.iter().chain([&note]) {
            assert!(!n.contains("  "), "a run of spaces: {n}");
        }
    }

    /// Without a tightening the traced working scheme is the solution at its load: failing to
    /// verify it is the program's failure whatever the fresh solve says. With one, the fresh
    /// solve's ray (no solution found for the real problem) is an answer; its numerical failure
    /// is not.
    #[test]
    fn a_missing_solution_is_a_failure_unless_the_real_problem_has_none() {
        let singular = |fresh| why(BasisVerdict::Singular, fresh);
        assert!(unreported_is_failure(&singular(Some(LcpStatus::Ray)), 0.0));
        assert!(!unreported_is_failure(&singular(Some(LcpStatus::Ray)), 1.0));
        assert!(!unreported_is_failure(
            &singular(Some(LcpStatus::IterationLimit)),
            1.0
        ));
        assert!(unreported_is_failure(
            &singular(Some(LcpStatus::NumericalFailure)),
            1.0
        ));
        assert!(unreported_is_failure(&singular(None), 1.0));
    }
}
