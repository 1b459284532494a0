//! Solving a contact zone along the load path and reading the answer as a structure.

use std::fmt;

use unilateral_lcp::{
    follow_path, solution_at, tableaux, Follow, LoadPath, PathOptions, PathPoint, PathStatus,
    Residual, Settings, Tableau, Var,
};

use crate::lcp::ContactLcp;
use crate::units::Units;
use crate::{ContactError, ContactZone, SolveSettings, Trace};

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
    /// The `status` key of result files.
    pub fn status(&self) -> &'static str {
        match self {
            Outcome::TargetReached => "target_reached",
            Outcome::Ray { .. } => "ray",
            Outcome::Mechanism { .. } => "mechanism",
            Outcome::ReturnedToZero => "returned_to_zero",
            Outcome::IterationLimit => "iteration_limit",
            Outcome::NoSolutionAtStart => "no_solution_at_start",
            Outcome::NumericalFailure => "numerical_failure",
        }
    }

    /// A sentence for engineers.
    pub fn reading(&self, target: f64) -> String {
        match self {
            Outcome::TargetReached => {
                format!("the load reached the target p* = {target} (Criterion 1)")
            }
            Outcome::Ray { p_from } => format!(
                "the working scheme no longer changes for p ≥ {p_from:.6} (Criterion 2a: ray)"
            ),
            Outcome::Mechanism { p_limit, .. } => {
                format!("the structure becomes a mechanism at p_lim = {p_limit:.6} (Criterion 2b)")
            }
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

/// The answer of [`solve`].
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
    /// The LCP that was solved.
    pub lcp: ContactLcp,
    /// The engine's load path.
    pub path: LoadPath,
    /// The path options in the user's units (for the tableaux of `lcp`).
    pub(crate) options: PathOptions,
    pub(crate) engine: Settings,
    pub(crate) names: Vec<String>,
    /// The normalised problem that was solved, its options, and the scales (see `units`).
    pub(crate) normalised: ContactLcp,
    pub(crate) normalised_options: PathOptions,
    pub(crate) units: Units,
}

fn engine_settings(lcp: &ContactLcp, s: &SolveSettings) -> Settings {
    Settings {
        pivot_tolerance: s.pivot_tolerance,
        max_pivots: s.max_pivots,
        lexicographic_order: Some(lcp.lexicographic_order.clone()),
        // The start at p = 0 follows a tightening down; without one given, in the direction
        // that keeps friction consistent (`max(1, f)` on the tangential rows).
        covering: Some(lcp.tightening_direction.clone()),
        ..Settings::default()
    }
}

/// Follows the load path of a contact zone and reads the answer as pair states and events.
///
/// ```
/// use faer::mat;
/// use unilateral_contact::{solve, ContactZone, Outcome, PairState, SolveSettings, Trace};
///
/// // The paper's Example 1: a beam on three supports, load in the right span.
/// let mut zone = ContactZone::new(
///     mat![[0.1875, -0.375, 0.1875], [-0.375, 0.75, -0.375], [0.1875, -0.375, 0.1875]],
///     mat![[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]],
/// );
/// zone.friction = vec![0.6; 3];
/// zone.variable.normal = vec![-0.09375, 0.6875, 0.40625];
/// let settings = SolveSettings { tightening: 1.0, trace: Trace::End, ..Default::default() };
/// let sol = solve(&zone, &settings).unwrap();
/// assert!(matches!(sol.outcome, Outcome::Ray { .. }));
/// assert_eq!(sol.steps[0].events[0].to_string(), "pair 1 opens");
/// assert_eq!(sol.pairs[0].state, PairState::Open);
/// assert!((sol.pairs[0].z_n - 0.5).abs() < 1e-12);
/// assert!((sol.pairs[1].x_n - 0.5).abs() < 1e-12);
/// ```
pub fn solve(
    zone: &ContactZone,
    settings: &SolveSettings,
) -> Result<ContactSolution, ContactError> {
    zone.validate()?;
    settings.validate()?;
    // The LCP in the user's units: shown in tableaux and labels.
    let lcp = ContactLcp::build(zone);
    let follow = match settings.trace {
        Trace::Target => Follow::ToTarget,
        Trace::End => Follow::ToEnd,
    };
    let options = PathOptions {
        target: settings.target,
        follow,
        tightening: lcp.tightening(settings.tightening),
    };
    // The LCP that is solved: normalised by powers of two (module `units`), so that neither the
    // states nor the events depend on the units of the data.
    let units = Units::of(zone, settings.tightening);
    let normalised = ContactLcp::build(&units.normalise(zone));
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
        follow,
        tightening: normalised.tightening(units.normalised_force(settings.tightening)),
    };
    let engine = engine_settings(&normalised, settings);
    let mut path = follow_path(&normalised.problem, &normalised_options, &engine)?;
    let m = lcp.pairs;
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
                p: s.p,
                entering: lcp.label(s.entering),
                leaving: lcp.label(s.leaving),
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
        notes.extend(start_diagnosis(&lcp));
    }
    let no_constant = zone.constant.normal.iter().all(|&v| v == 0.0)
        && zone.constant.tangential.iter().all(|&v| v == 0.0)
        && zone.gap.iter().all(|&g| g == 0.0);
    if settings.tightening > 0.0 && no_constant {
        notes.push(format!(
            "the tightening c = {} is artificial and there is no constant load: the loads of the \
             intermediate events depend on c, the final working scheme does not",
            settings.tightening
        ));
    } else if settings.tightening > 0.0 {
        notes.push(format!(
            "the tightening c = {} is artificial: the loads of the events depend on it; the \
             reported solution does not contain it",
            settings.tightening
        ));
    }
    if steps.iter().any(|s| s.turning) {
        notes.push(
            "the load decreased at a step (a turning point of the load path): the solution at a \
             given load may not be unique"
                .into(),
        );
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
            notes.push(
                "the tightening could not be removed along the path; the reported solution comes \
                 from a fresh solve at this load and may belong to another branch"
                    .into(),
            );
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
        lcp,
        path,
        options,
        engine,
        names,
        normalised,
        normalised_options,
        units,
    };
    if let Some(sol) = solution {
        out.set_point(&sol)?;
    }
    Ok(out)
}

/// Why p = 0 may have no solution: the pairs whose normal link the constant load (with the
/// gaps) puts in tension in the bonded structure, with those forces.
fn start_diagnosis(lcp: &ContactLcp) -> Option<String> {
    let m = lcp.pairs;
    let q0 = &lcp.problem.q0;
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

fn events_of(leaving: Var, m: usize, names: &[String]) -> Vec<Event> {
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

impl ContactSolution {
    /// Reads the normalised point `sol` as pair results in the user's units.
    fn set_point(&mut self, sol: &PathPoint) -> Result<(), ContactError> {
        self.pairs = self.read_point(sol)?;
        self.p = Some(sol.p);
        self.residual = Some(sol.residual);
        self.tightening_pivots = sol.tightening_pivots;
        Ok(())
    }

    fn read_point(&self, sol: &PathPoint) -> Result<Vec<PairResult>, ContactError> {
        let mut pairs = pair_results_scaled(&sol.x, &sol.z, &self.names, 1.0, 1.0);
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

    /// The solution without tightening at another load `p` on the traced path (`None` when `p`
    /// is not on it).
    pub fn at(&self, p: f64) -> Option<(Vec<PairResult>, Residual)> {
        let pt = solution_at(
            &self.normalised.problem,
            &self.normalised_options,
            &self.engine,
            &self.path,
            p,
        )
        .ok()??;
        Some((self.read_point(&pt).ok()?, pt.residual))
    }

    /// The tableaux of the path in the paper's layout (at most `max_steps` steps).
    pub fn tableaux(&self, max_steps: Option<usize>) -> Vec<Tableau> {
        tableaux(&self.lcp.problem, &self.options, &self.path, max_steps).unwrap_or_default()
    }
}

/// Pair results from the LCP's `x` and `z`.
///
/// Round-off is judged relative to the largest force and displacement of the solution itself;
/// [`solve`] judges it relative to the scale of the data as well.
pub fn pair_results(x: &[f64], z: &[f64], names: &[String]) -> Vec<PairResult> {
    pair_results_scaled(x, z, names, 0.0, 0.0)
}

/// Pair results with round-off judged relative to `max(‖x‖∞, force_scale)` for forces and
/// `max(‖z‖∞, displacement_scale)` for displacements: a normal force of `4e-16` in a zone whose
/// loads are of order one is round-off of zero, and the pair is open (touching), not stuck.
fn pair_results_scaled(
    x: &[f64],
    z: &[f64],
    names: &[String],
    force_scale: f64,
    displacement_scale: f64,
) -> Vec<PairResult> {
    let m = names.len();
    let xmax = x.iter().fold(force_scale, |a, b| a.max(b.abs()));
    let zmax = z.iter().fold(displacement_scale, |a, b| a.max(b.abs()));
    let (tx, tz) = (1e-9 * xmax, 1e-9 * zmax);
    (0..m)
        .map(|i| {
            let x_n = x[i];
            let x_t = (x[m + i] - x[2 * m + i]) / 2.0;
            let z_n = z[i];
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
            // Round-off of the friction rows of an open pair is not a force.
            let x_t = if state == PairState::Open && x_t.abs() <= tx {
                0.0
            } else {
                x_t
            };
            PairResult {
                name: names[i].clone(),
                x_n,
                x_t,
                z_n,
                z_t,
                state,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: the definition of the states (formulation: open ⇔ no compression). A normal
    // force of 4e-16 in a zone whose forces are of order one is round-off of zero: the pair
    // touches without force (open/grazing), it does not stick.
    #[test]
    fn round_off_compression_is_open_not_stick() {
        let names = vec!["1".to_string()];
        let x = [4e-16, 0.0, 0.0];
        let z = [0.0; 3];
        assert_eq!(
            pair_results_scaled(&x, &z, &names, 1.0, 1.0)[0].state,
            PairState::Open
        );
        // A real compression of the zone's scale sticks.
        let x = [0.5, 0.2, 0.2];
        assert_eq!(
            pair_results_scaled(&x, &z, &names, 1.0, 1.0)[0].state,
            PairState::Stick
        );
    }

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
}
