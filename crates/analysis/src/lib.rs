//! # unilateral-analysis — structural contact analysis from model to results
//!
//! [`analyze`] takes a finite-element [`Model`] with contact pairs and the solve settings and
//! runs the whole chain:
//!
//! 1. validate the model and condense it to the contact zone (`unilateral-fem`): the contact
//!    stiffness matrix `R` and the contact load vectors `R_c`, `R_v` of `formulation.md` §2;
//! 2. follow the load path of the parametric LCP (`unilateral-contact`): events, pair states,
//!    the solution at the target load (or at the end of the path);
//! 3. recover displacements, reactions, internal forces and stresses at the reported load
//!    and check the equilibrium of the whole structure.
//!
//! Results at other loads of the path (for instance at every event, for pictures) come from
//! [`Analysis::results_at`]. The wall-clock time of each of the three steps is kept in
//! [`Analysis::timings`].
//!
//! Errors and extremes name nodes and elements by the model's names (as a model file gives
//! them, [`Model::names`]).

#![warn(missing_docs)]

mod history;

pub use history::{analyze_history, HistoryAnalysis};

use std::sync::Arc;
use std::time::{Duration, Instant};

use unilateral_contact::{
    ContactError, ContactLoad, ContactZone, LoadCase, PairResult, SolveSettings,
};
use unilateral_fem::{
    Condensed, DofLabel, ElementId, FemError, LinkValues, Model, NodeId, Results, Subject,
};

pub use unilateral_contact::{Outcome, PairState};
/// The names of nodes and elements used in messages and in [`Extremes`] (the model's own,
/// [`Model::names`]).
pub use unilateral_fem::Names;

/// Largest relative out-of-balance force accepted in the recovered results (the recovery
/// refines its displacements when it is exceeded, [`unilateral_fem::EQUILIBRIUM_ACCEPT`]).
pub const EQUILIBRIUM_TOLERANCE: f64 = unilateral_fem::EQUILIBRIUM_ACCEPT;

/// What can go wrong in an analysis.
#[derive(Debug, Clone, thiserror::Error)]
pub enum AnalysisError {
    /// The model is inconsistent (bad ids, zero-length element, non-positive property, …).
    #[error("the model is invalid: {message}")]
    Model {
        /// The problem, with node and element names.
        message: String,
        /// The finite-element error.
        #[source]
        source: FemError,
    },
    /// The bonded structure (every contact pair a rigid link) is a mechanism.
    #[error(
        "the structure is unstable even with every contact pair closed and stuck: it can move \
         freely at {}; add supports or contact pairs, or connect the parts",
        list(.free)
    )]
    Unstable {
        /// The DOFs that move in the mechanism: (node name, DOF), largest amplitudes first.
        free: Vec<(String, DofLabel)>,
    },
    /// The contact zone or the settings were refused by the contact solver.
    #[error("contact problem: {0}")]
    Contact(#[from] ContactError),
    /// Recovering the results at `p` failed: an internal failure, but for sums of forces too
    /// large for the model's units ([`FemError::Overflow`]), the model's.
    #[error(
        "{}recovering the results at {at}: {source}",
        if matches!(source, FemError::Overflow { .. }) { "" } else { "internal failure (the program's fault, not the model's): " }
    )]
    Recovery {
        /// The point of the path or history.
        at: Place,
        /// The finite-element error.
        #[source]
        source: FemError,
    },
    /// The recovered results are not in equilibrium (an internal failure).
    #[error(
        "internal failure (the program's fault, not the model's): the results at {at} are \
         out of balance (relative residual {relative:.3e}, accepted {EQUILIBRIUM_TOLERANCE:e})"
    )]
    Equilibrium {
        /// The point of the path or history.
        at: Place,
        /// The relative out-of-balance force.
        relative: f64,
    },
    /// The recovered results are out of balance where the round-off of the gaps' and slips'
    /// dislocations alone can leave them so: the forces those make term by term
    /// (`dislocation`) exceed the forces of the state (`forces`) by more than double precision
    /// resolves within the check's tolerance (a 1 mm gap closed by a rigid motion of a steel
    /// block, and loads of a hundredth of a newton; the same block held by a 10 N/m spring,
    /// sliding 200 m). No state there can be verified, whatever its residual: the data's
    /// conditioning, not the program's fault.
    #[error(
        "the results at {at} cannot be resolved in double precision: the links' \
         dislocations ({}) and the motion they carry make forces of {dislocation:.3e} term by \
         term, {:.1e} times the forces of this state ({forces:.3e}), whose round-off alone can \
         leave them out of balance by {:.1e} of those, above what a state is accepted at \
         ({EQUILIBRIUM_TOLERANCE:e}): no state can be verified with such data (this one is out \
         of balance by {relative:.3e}); give {}supports that keep the slips short (a spring a \
         billionth of the structure's stiffness lets it slide metres)",
        if *gaps { "gaps and slips" } else { "slips" },
        dislocation / forces,
        ROUNDOFF_DISLOCATIONS * dislocation / forces,
        if *gaps { "a larger load (target) against the gaps, smaller gaps, or " } else { "" }
    )]
    Unresolved {
        /// The point of the path or history.
        at: Place,
        /// Whether the model has gaps (the advice names them only then).
        gaps: bool,
        /// The relative out-of-balance force.
        relative: f64,
        /// The size of the dislocations' forces ([`unilateral_fem::Equilibrium::dislocation_force`]),
        /// or of the forces the displacements that follow them make term by term in the
        /// elements and springs where larger ([`Condensed::displacement_terms`]).
        dislocation: f64,
        /// The force scale of the state ([`unilateral_fem::Equilibrium::scale`]).
        forces: f64,
    },
    /// Another failure of the program itself: data it computed from a valid model was wrong
    /// (for instance a condensed contact stiffness the contact solver refused) or a numerical
    /// method failed.
    #[error("internal failure (the program's fault, not the model's): {what}: {message}")]
    Internal {
        /// What failed.
        what: String,
        /// How.
        message: String,
    },
    /// The constant load alone pulls the structure off its contact pairs, and nothing else
    /// holds it: there is no equilibrium at `p = 0`. Usually a normal typed the wrong way
    /// round, or a constant load with the wrong sign.
    #[error(
        "there is no equilibrium under the constant load alone (p = 0): it pulls {} apart \
         (normal {} as rigid {}: {}, tension), and once {} nothing holds the structure; check \
         that each normal points from `from` into `to` (pressing the bodies together is \
         compression) and the signs of the constant loads (their resultant: Fx = {}, Fy = {})",
        plural_pairs(.pairs),
        if .pairs.len() == 1 { "force" } else { "forces" },
        if .pairs.len() == 1 { "link" } else { "links" },
        .forces.iter().map(|f| format!("{f}")).collect::<Vec<_>>().join(", "),
        if .pairs.len() == 1 { "it opens" } else { "they open" },
        .resultant[0],
        .resultant[1]
    )]
    PulledApart {
        /// The pairs the constant load opens (names).
        pairs: Vec<String>,
        /// Their normal link forces in the bonded structure under the constant load (negative:
        /// tension).
        forces: Vec<f64>,
        /// Resultant `[Fx, Fy]` of the constant load.
        resultant: [f64; 2],
    },
    /// The requested load is not on the traced load path.
    #[error("p = {} is not on the traced load path (it ends at {end})", unilateral_contact::number_text(*p))]
    NotOnPath {
        /// The requested load.
        p: f64,
        /// The last load of the path.
        end: String,
    },
}

fn plural_pairs(pairs: &[String]) -> String {
    let names: Vec<String> = pairs.iter().take(12).map(|p| format!("`{p}`")).collect();
    let more = if pairs.len() > 12 {
        format!(" … ({} pairs in all)", pairs.len())
    } else {
        String::new()
    };
    if pairs.len() == 1 {
        format!("pair {}", names[0])
    } else {
        format!("pairs {}{more}", names.join(", "))
    }
}

impl AnalysisError {
    /// `true` for failures that are the program's fault, not the model's: the recovery of the
    /// results, the equilibrium check of the recovered results, a numerical failure of the
    /// linear algebra or of the load path, contact data the program computed and the contact
    /// solver refused ([`AnalysisError::Internal`]). `false` for everything the user can act
    /// on in the model or the settings: an invalid or too large model, a mechanism, contact
    /// settings out of range, no equilibrium under the constant load, a load off the path.
    ///
    /// A command-line front end exits with 1 for internal failures and 2 for bad input.
    pub fn is_internal(&self) -> bool {
        match self {
            // Forces too large for the model's units to sum is the model's.
            AnalysisError::Recovery {
                source: FemError::Overflow { .. },
                ..
            } => false,
            AnalysisError::Recovery { .. }
            | AnalysisError::Equilibrium { .. }
            | AnalysisError::Internal { .. } => true,
            AnalysisError::Model { source, .. } => source.is_internal(),
            AnalysisError::Unstable { .. }
            | AnalysisError::Unresolved { .. }
            | AnalysisError::Contact(_)
            | AnalysisError::PulledApart { .. }
            | AnalysisError::NotOnPath { .. } => false,
        }
    }
}

fn list(free: &[(String, DofLabel)]) -> String {
    let mut s: Vec<String> = free
        .iter()
        .take(12)
        .map(|(n, d)| format!("node `{n}` {d}"))
        .collect();
    if free.len() > 12 {
        s.push(format!("… ({} DOFs in all)", free.len()));
    }
    s.join(", ")
}

/// A value at a node.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeValue {
    /// The node.
    pub node: NodeId,
    /// Its name.
    pub name: String,
    /// The value.
    pub value: f64,
}

/// A value in an element.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementValue {
    /// The element.
    pub element: ElementId,
    /// Its name.
    pub name: String,
    /// The value, with its sign.
    pub value: f64,
    /// Where: the distance from the start node (frames, bars), or the Gauss point (plane).
    pub at: [f64; 2],
}

/// The largest results of a solution.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Extremes {
    /// Largest translation `√(ux² + uy²)`.
    pub displacement: Option<NodeValue>,
    /// Largest `|M|` in frames (value signed, `at[0]` = distance from the start node).
    pub moment: Option<ElementValue>,
    /// Largest `|N|` in frames and bars (tension positive).
    pub axial: Option<ElementValue>,
    /// Largest `|Q|` in frames.
    pub shear: Option<ElementValue>,
    /// Largest von Mises stress in plane elements (`at` = Gauss point coordinates).
    pub von_mises: Option<ElementValue>,
    /// Most compressive principal stress in plane elements.
    pub min_principal: Option<ElementValue>,
}

/// The wall-clock time of the parts of a run, each `None` where that part did not happen.
///
/// [`analyze`] fills `condense`, `solve` and `recover` (`recover` only when the path reports a
/// solution to recover); a front end adds the time it spends reading the input (`read`) and
/// writing the outputs (`write`). The parts never overlap, so their sum is at most the
/// wall-clock time of the whole run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Timings {
    /// Reading the input file and building the problem from it.
    pub read: Option<Duration>,
    /// Checking the model and condensing it to the contact zone handed to the solver.
    pub condense: Option<Duration>,
    /// Following the load path (or solving the plain LCP).
    pub solve: Option<Duration>,
    /// Recovering the structural results at the reported load and checking their equilibrium.
    pub recover: Option<Duration>,
    /// Writing outputs (what exactly is the front end's to say).
    pub write: Option<Duration>,
}

impl Timings {
    /// The parts in the order of a run, with their names (`read`, `condense`, `solve`,
    /// `recover`, `write`): the one list that writers of the timings go through.
    pub fn parts(&self) -> [(&'static str, Option<Duration>); 5] {
        [
            ("read", self.read),
            ("condense", self.condense),
            ("solve", self.solve),
            ("recover", self.recover),
            ("write", self.write),
        ]
    }

    /// The parts that happened, in the order of [`Timings::parts`].
    pub fn present(&self) -> impl Iterator<Item = (&'static str, Duration)> {
        self.parts()
            .into_iter()
            .filter_map(|(name, d)| d.map(|d| (name, d)))
    }
}

/// A finished analysis: the condensed model, the contact solution along the load path, and
/// the full results at the reported load.
///
/// ```
/// use unilateral_analysis::{analyze, Outcome, PairState};
/// use unilateral_contact::{Follow, SolveSettings};
/// use unilateral_fem::{ContactPairSpec, FrameSection, Load, LoadGroup, Model};
///
/// // The paper's Example 1: a two-span beam (spans 2, EI = 1, EA = 2) on three unilateral
/// // supports with friction 0.6, a unit load in the middle of the right span.
/// let mut model = Model::new();
/// let n: Vec<_> = [0.0, 2.0, 3.0, 4.0].iter().map(|&x| model.add_node(x, 0.0)).collect();
/// for w in n.windows(2) {
///     model.add_frame(w[0], w[1], FrameSection::new(1.0, 2.0, 1.0));
/// }
/// for &i in &[n[0], n[1], n[3]] {
///     model.add_contact_pair(ContactPairSpec::to_ground(i, [0.0, 1.0]).friction(0.6));
/// }
/// model.add_load(LoadGroup::Variable, Load::Nodal { node: n[2], fx: 0.0, fy: -1.0, m: 0.0 });
///
/// let settings = SolveSettings { tightening: 1.0, follow: Follow::ToEnd, ..Default::default() };
/// let a = analyze(&model, &settings)?;
/// assert!(matches!(a.solution.outcome, Outcome::Ray { .. }));
/// assert_eq!(a.solution.pairs[0].state, PairState::Open);
/// let r = a.results.as_ref().unwrap();
/// assert!((r.displacements[0][1] - 0.5).abs() < 1e-9); // uplift P·L³/(16·EI)
/// let ext = a.extremes().unwrap();
/// assert_eq!(ext.displacement.unwrap().node, n[0]);
/// # Ok::<(), unilateral_analysis::AnalysisError>(())
/// ```
#[derive(Debug)]
pub struct Analysis {
    /// The condensation of the model (`R_c`, `R_v`) and the means of recovery. Its blocks
    /// `Rnn`, `Rnt`, `Rtn`, `Rtt` were moved into [`Analysis::zone`] (here they are `0 × 0`,
    /// [`Condensed::take_blocks`]): a large zone is held once.
    pub condensed: Condensed,
    /// The contact zone as handed to the contact solver, with the contact stiffness blocks;
    /// shared with [`Analysis::solution`].
    pub zone: Arc<ContactZone>,
    /// The load path, its events and the pair results at the reported load.
    pub solution: unilateral_contact::ContactSolution,
    /// Full results at the reported load (`None` when the path reports no solution).
    pub results: Option<Results>,
    /// The wall-clock time of the condensation, the solve and the recovery (`read` and
    /// `write` are `None`: the analysis neither reads nor writes files).
    pub timings: Timings,
}

/// The number of contact pairs from which [`analyze`] traces the path with the engine on the
/// structure's sparse blocks ([`unilateral_contact::solve_sparse`]): a pivot there costs a few
/// sparse solves, on the condensed zone a pass over `n·k` entries of the dense matrix. Measured
/// on the whole-process benchmark's beams (`docs/performance.md`, round 38): 2.6 s against
/// 4.5 s at 1000 pairs, 13–15 s against 52 s at 2000; slower below about 700 pairs (0.37 s
/// against 0.16 s at 500, round 28). Where the sparse path is not taken (it fails, or ends
/// otherwise than at the target or in a ray that verifies: a sliding mechanism before the
/// target), or where the structure refuses its state, the dense engine traces it (the run
/// pays both).
pub const SPARSE_ENGINE_PAIRS: usize = 1000;

/// Runs the analysis of a model; messages and extremes name nodes and elements by the model's
/// names ([`Model::names`], the 0-based indices where it has none).
pub fn analyze(model: &Model, settings: &SolveSettings) -> Result<Analysis, AnalysisError> {
    settings.validate()?;
    let progress = &settings.engine.progress;
    progress.phase(unilateral_lcp::Phase::Condensing);
    let (condensed, zone, condense) = condensed_zone(model)?;
    let started = Instant::now();
    // Shared with the solution, which keeps it: the zone is held once.
    let zone = Arc::new(zone);
    // The structure's own blocks judge the load rates the condensed data cannot tell from
    // round-off (a path without a tightening only).
    let sparse = (settings.tightening == 0.0)
        .then(|| sparse_zone_of(model).ok())
        .flatten();
    // From SPARSE_ENGINE_PAIRS pairs on, the path is traced on the structure's sparse blocks
    // (the dense engine where that path is not taken).
    let trace = |sparse_engine: bool| {
        if sparse_engine {
            unilateral_contact::solve_sparse(Arc::clone(&zone), sparse.as_ref(), settings)
        } else {
            unilateral_contact::solve_judged(Arc::clone(&zone), sparse.as_ref(), settings)
        }
        .map_err(contact_error)
    };
    let solution = trace(zone.pairs() >= SPARSE_ENGINE_PAIRS)?;
    let solve = started.elapsed();
    if solution.outcome == Outcome::NoSolutionAtStart {
        if let Some(e) = pulled_apart(&condensed, &zone) {
            return Err(e);
        }
    }
    let mut a = Analysis {
        condensed,
        zone: Arc::clone(&zone),
        solution,
        results: None,
        timings: Timings {
            condense: Some(condense),
            solve: Some(solve),
            ..Timings::default()
        },
    };
    let refused = Instant::now();
    match recover_reported(&mut a) {
        // A state of the sparse engine's path that the structure's check refuses or finds out
        // of balance: the dense engine's path instead. The sparse engine can pass a sliding
        // mechanism whose load rate is round-off of its data (a reviewer's beams on 1000-1300
        // bearings: slips of 1e20 at the target, refused as unresolvable), which the dense
        // engine ends at its limit load on the structure's own equations.
        Err(AnalysisError::Equilibrium { .. } | AnalysisError::Unresolved { .. })
            if a.solution.traced_on_sparse_blocks =>
        {
            progress.restart_path();
            a.solution = trace(false)?;
            a.results = None;
            // The refused state's recovery was part of choosing the path: in the solve's time.
            a.timings.solve = Some(solve + refused.elapsed());
            recover_reported(&mut a)?;
        }
        r => r?,
    }
    drop(sparse);
    Ok(a)
}

/// The structure's results at the reported load of `a`'s path (none where it reports none),
/// recovered and checked; the time it took in `a.timings.recover`.
fn recover_reported(a: &mut Analysis) -> Result<(), AnalysisError> {
    let Some(p) = a.solution.p else {
        return Ok(());
    };
    a.solution
        .settings
        .engine
        .progress
        .phase(unilateral_lcp::Phase::Recovering);
    let started = Instant::now();
    a.results = match a.recover_pairs(p, &a.solution.pairs) {
        Err(e @ (AnalysisError::Equilibrium { .. } | AnalysisError::Unresolved { .. })) => {
            match structure_point_recovered(a, p) {
                Some(r) => Some(r),
                None if mechanism_at_rest(&a.solution) => {
                    unreported_rest(&mut a.solution, &e);
                    None
                }
                None => return Err(e),
            }
        }
        r => Some(r?),
    };
    a.timings.recover = Some(started.elapsed());
    Ok(())
}

/// A mechanism as soon as the variable load is applied (`p_lim = 0`), its state at `p = 0`
/// reported.
fn mechanism_at_rest(s: &unilateral_contact::ContactSolution) -> bool {
    matches!(s.outcome, Outcome::Mechanism { p_limit, .. } if p_limit == 0.0) && s.p == Some(0.0)
}

/// The state of a mechanism at `p = 0` whose structure the check refused (a beam under 1e-3 N
/// of weight over a 0.1 m gap: forces 6e11 times below its gap's terms) or found out of
/// balance (200 bearings under 2e-4 N over gaps of 1e-5 m: by 1.9e-6) taken back: the limit
/// stands, the state is not reported, and a note gives the check's verdict — as before the
/// path reported such states (reviewers: the runs answered `p_lim = 0` and were then refused,
/// exit 2, or failed, exit 1).
fn unreported_rest(s: &mut unilateral_contact::ContactSolution, why: &AnalysisError) {
    s.p = None;
    s.pairs.clear();
    s.residual = None;
    s.notes.push(format!(
        "{}, where the structure becomes a mechanism: {why}",
        unilateral_contact::NO_STATE_AT_START
    ));
}

/// The reported solution at `p` formed again on the structure's own equations, where the one
/// formed on the condensed data left the recovered structure out of balance: the condensed
/// `M` carries its condensation's round-off, which a state of soft springs or long slips
/// amplifies (a block lifting its heel on an inclined spring, out of balance by 7e-6 of its
/// forces at its mechanism). Taken, with its results, only where the structure it gives is
/// in balance; `None` otherwise (the first error stands).
fn structure_point_recovered(a: &mut Analysis, p: f64) -> Option<Results> {
    let (pairs, residual) = a.solution.at_on_structure(p).ok()??;
    let r = a.recover_pairs(p, &pairs).ok()?;
    a.solution.pairs = pairs;
    a.solution.residual = Some(residual);
    Some(r)
}

/// The model checked against the memory it needs, condensed, and its contact zone checked; with
/// the time that took. Shared by the paper's path and the load histories.
pub(crate) fn condensed_zone(
    model: &Model,
) -> Result<(Condensed, ContactZone, Duration), AnalysisError> {
    let started = Instant::now();
    let names = model.names();
    let m = model.pairs().len();
    unilateral_fem::check_memory(&format!("{m} contact pairs"), analysis_bytes(m))
        .map_err(|e| fem_error(e, names))?;
    let mut condensed = model.condense().map_err(|e| fem_error(e, names))?;
    // The blocks move into the zone: at m = 2000 they are 128 MB, held once.
    let zone = zone_from(&mut condensed);
    // The zone is computed by the program from a valid model: if the contact solver refuses
    // it, the program is at fault, and the user never wrote the matrix it would name.
    zone.validate().map_err(|e| AnalysisError::Internal {
        what: "the contact zone condensed from the model was refused".into(),
        message: e.to_string(),
    })?;
    Ok((condensed, zone, started.elapsed()))
}

/// A model's contact zone: the model checked and condensed, the zone (`R`, every load case,
/// friction, gaps, pair names) checked — for exporting it (`unilateral zone`) or printing the
/// tableaux of its path, without following the path. The blocks `Rnn`, `Rnt`, `Rtn`, `Rtt` are
/// in the zone only (moved there: the condensation's are `0 × 0`, [`Condensed::take_blocks`]).
pub fn contact_zone_of(model: &Model) -> Result<(Condensed, ContactZone), AnalysisError> {
    condensed_zone(model).map(|(c, z, _)| (c, z))
}

/// A contact error on a zone the program condensed: a setting is the user's, anything else
/// the program's fault.
pub(crate) fn contact_error(e: ContactError) -> AnalysisError {
    match e {
        ContactError::Settings(_) => AnalysisError::Contact(e),
        other => AnalysisError::Internal {
            what: "the contact solver refused the condensed contact zone".into(),
            message: other.to_string(),
        },
    }
}

/// Bytes of the dense matrices an analysis of `m` contact pairs holds at most (an estimate
/// made before anything is allocated): the condensation's (2m)² stiffness and its four m×m
/// blocks, a contact zone (4 m²) and a 3m×3m LCP matrix with about three more of its size for
/// the basis and its factors. A conservative bound: the blocks are moved into the zone, not
/// copied, and the LCP is formed once, in the solver's units. `None` on overflow.
pub fn analysis_bytes(m: usize) -> Option<u64> {
    let fem = unilateral_fem::dense_condensation_bytes(m, 0)?;
    let m = m as u64;
    let solver = m.checked_mul(m)?.checked_mul(4 + 4 * 9)?.checked_mul(8)?;
    fem.checked_add(solver)
}

/// The pairs the constant load alone pulls apart, when the path has no solution at `p = 0`:
/// their normal force as rigid links under the constant load (`R_c − Rnn·η`) is a tension.
fn pulled_apart(c: &Condensed, zone: &ContactZone) -> Option<AnalysisError> {
    let m = c.pairs();
    let mut pairs = Vec::new();
    let mut forces = Vec::new();
    for i in 0..m {
        let x = c.constant.normal[i] - (0..m).map(|j| zone.rnn[(i, j)] * c.gap[j]).sum::<f64>();
        if x < 0.0 {
            pairs.push(c.pair_names[i].clone());
            forces.push(x);
        }
    }
    if pairs.is_empty() {
        return None;
    }
    let resultant = c.load_resultant(unilateral_fem::LoadGroup::Constant);
    Some(AnalysisError::PulledApart {
        pairs,
        forces,
        resultant,
    })
}

/// The link values of pair results, labelled `p`.
fn link_values(p: f64, pairs: &[PairResult]) -> LinkValues {
    LinkValues {
        p,
        x_n: pairs.iter().map(|r| r.x_n).collect(),
        x_t: pairs.iter().map(|r| r.x_t).collect(),
        z_n: pairs.iter().map(|r| r.z_n).collect(),
        z_t: pairs.iter().map(|r| r.z_t).collect(),
    }
}

/// The error of a recovery at `p`, an element it names by the model's name for it.
fn recovery_error(at: Place, source: FemError, names: &Names) -> AnalysisError {
    let source = match source {
        FemError::Overflow {
            element: Some(e),
            what,
        } => FemError::Overflow {
            element: None,
            what: format!("{what} of element `{}`", names.element(e)),
        },
        other => other,
    };
    AnalysisError::Recovery { at, source }
}

/// The round-off of the forces the links' dislocations make term by term, relative to those
/// forces, that a recovered state can carry ([`AnalysisError::Unresolved`]).
const ROUNDOFF_DISLOCATIONS: f64 = 64.0 * f64::EPSILON;

/// Recovered results that are finite and in equilibrium, or the error that says which not.
fn checked(r: Results, at: Place, c: &Condensed) -> Result<Results, AnalysisError> {
    let model = c.model();
    if !r.all_finite() {
        return Err(AnalysisError::Internal {
            what: format!("recovering the results at {at}"),
            message: "a recovered displacement, force or stress is not a finite number".into(),
        });
    }
    let relative = r.equilibrium.relative();
    if relative.is_nan() || relative > EQUILIBRIUM_TOLERANCE {
        // Where what the dislocations' round-off (ε of their forces, times the amplification
        // of a structure's solve: 2.5 to 6 measured, 64 allowed) can make against the state's
        // forces exceeds the tolerance, no state can be verified: the data's conditioning,
        // whatever the residual (the state itself comes from data of that conditioning: a
        // block held by a 10 N/m spring, sliding 490 m in a history, left out of balance by
        // 7e-3 where the round-off bound is 7e-5). Elsewhere an out-of-balance state is the
        // program's failure. The terms are the links' (their dislocations times their
        // couplings) or the elements' and springs' where larger: a steel block sliding 346 m
        // on a soft foundation moved its own nodes with it, terms 130 times the links' (whose
        // couplings are the foundation's), and its state out of balance by 2.1e-6 was said to
        // be the program's fault (a helper's sweep, kN·mm; answered in N·m).
        let forces = r.equilibrium.scale;
        let dislocation = r
            .equilibrium
            .dislocation_force
            .max(c.displacement_terms(&r));
        let roundoff = ROUNDOFF_DISLOCATIONS * dislocation / forces;
        if relative.is_finite() && roundoff > EQUILIBRIUM_TOLERANCE {
            return Err(AnalysisError::Unresolved {
                at,
                gaps: model.pairs().iter().any(|p| p.gap != 0.0),
                relative,
                dislocation,
                forces,
            });
        }
        return Err(AnalysisError::Equilibrium { at, relative });
    }
    Ok(r)
}

/// The full structural results (displacements, reactions, element forces, stresses) for the
/// pair results `pairs` under the load `Σ factors[c]·(case c)`, the factors indexed like the
/// model's load cases ([`Condensed::case_names`]): any point of a load history. `at` is the
/// point the errors name; its [`Place::label`] is [`Results::p`]. The results are checked as
/// those of [`analyze`] are: finite, and in equilibrium within [`EQUILIBRIUM_TOLERANCE`].
pub fn recover_at(
    c: &Condensed,
    factors: &[f64],
    at: Place,
    pairs: &[PairResult],
) -> Result<Results, AnalysisError> {
    let r = c
        .recover_at(factors, &link_values(at.label(), pairs))
        .map_err(|source| recovery_error(at, source, c.model().names()))?;
    checked(r, at, c)
}

/// A point of a load path or of a load history, as errors name it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Place {
    /// The load parameter `p` of a load path ("p = 2.5").
    Load(f64),
    /// Stage `stage` (from 1) of a load history at its parameter `s` in `[0, 1]` ("s = 0.25 of
    /// stage 3").
    Stage {
        /// The stage, from 1.
        stage: usize,
        /// The stage's parameter.
        s: f64,
    },
}

impl Place {
    /// The point as one number: `p`, or a history's pseudo-time `stage − 1 + s` (what
    /// [`Results::p`] holds).
    pub fn label(self) -> f64 {
        match self {
            Place::Load(p) => p,
            Place::Stage { stage, s } => stage.saturating_sub(1) as f64 + s,
        }
    }
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Place::Load(p) => write!(f, "p = {}", unilateral_contact::number_text(p)),
            Place::Stage { stage, s } => {
                write!(
                    f,
                    "s = {} of stage {stage}",
                    unilateral_contact::number_text(s)
                )
            }
        }
    }
}

/// The contact zone of a condensed model, with every load case of the model
/// ([`ContactZone::cases`], in the model's order). `c` must still hold its blocks: the
/// condensation an [`Analysis`] keeps has given them to its zone ([`Condensed::take_blocks`];
/// that zone is [`Analysis::zone`]).
pub fn zone_of(c: &Condensed) -> ContactZone {
    zone_with_blocks(
        c,
        [c.rnn.clone(), c.rnt.clone(), c.rtn.clone(), c.rtt.clone()],
    )
}

/// The contact zone of a model as the bonded structure's sparse blocks
/// ([`unilateral_contact::SparseZone`]): what the engine on sparse data
/// ([`unilateral_lcp::SchurLcp`]) works on instead of the condensed matrix.
pub fn sparse_zone_of(model: &Model) -> Result<unilateral_contact::SparseZone, FemError> {
    let b = model.bonded_blocks()?;
    let pairs = model.pairs();
    Ok(unilateral_contact::SparseZone {
        kii: b.kii,
        kiz: b.kiz,
        kzz: b.kzz,
        constant: b.constant,
        variable: b.variable,
        cases: b.cases,
        friction: pairs.iter().map(|p| p.friction).collect(),
        gap: pairs.iter().map(|p| p.gap).collect(),
    })
}

/// [`zone_of`], the blocks moved out of `c` instead of copied ([`Condensed::take_blocks`]).
fn zone_from(c: &mut Condensed) -> ContactZone {
    let blocks = c.take_blocks();
    zone_with_blocks(c, blocks)
}

/// The zone of `c` with the given blocks `[Rnn, Rnt, Rtn, Rtt]`.
fn zone_with_blocks(c: &Condensed, [rnn, rnt, rtn, rtt]: [faer::Mat<f64>; 4]) -> ContactZone {
    ContactZone {
        rnn,
        rnt,
        rtn,
        rtt,
        friction: c.friction.clone(),
        gap: c.gap.clone(),
        constant: ContactLoad {
            normal: c.constant.normal.clone(),
            tangential: c.constant.tangential.clone(),
        },
        variable: ContactLoad {
            normal: c.variable.normal.clone(),
            tangential: c.variable.tangential.clone(),
        },
        cases: c
            .case_names
            .iter()
            .zip(&c.cases)
            .map(|(name, v)| LoadCase {
                name: name.clone(),
                load: ContactLoad {
                    normal: v.normal.clone(),
                    tangential: v.tangential.clone(),
                },
            })
            .collect(),
        pair_names: c.pair_names.clone(),
    }
}

fn fem_error(e: FemError, names: &Names) -> AnalysisError {
    match &e {
        FemError::Unstable { free, .. } => AnalysisError::Unstable {
            free: free.iter().map(|f| (names.node(f.node), f.dof)).collect(),
        },
        FemError::LinearAlgebra(message) => AnalysisError::Internal {
            what: "the sparse linear algebra of the bonded structure failed".into(),
            message: message.clone(),
        },
        FemError::IllConditioned { .. } => AnalysisError::Internal {
            what: "condensing the model to its contact zone".into(),
            message: e.to_string(),
        },
        _ => {
            let message = match (&e, e.subject(), e.detail()) {
                (FemError::ZeroLength { element, a, b }, ..) => format!(
                    "element `{}` has zero length (nodes `{}` and `{}` coincide)",
                    names.element(*element),
                    names.node(*a),
                    names.node(*b)
                ),
                (
                    FemError::NonPositiveProperty { .. }
                    | FemError::Overflow { .. }
                    | FemError::Underflow { .. },
                    Some(Subject::Element(element)),
                    Some(detail),
                ) => format!("element `{}`: {detail}", names.element(element)),
                (FemError::BadSupport { .. }, Some(Subject::Node(node)), Some(detail)) => {
                    format!("node `{}`: {detail}", names.node(node))
                }
                _ => e.to_string(),
            };
            AnalysisError::Model { message, source: e }
        }
    }
}

impl Analysis {
    /// The names of the model's nodes, elements and pairs (the model's own, [`Model::names`]).
    pub fn names(&self) -> &Names {
        self.condensed.model().names()
    }

    /// The load of the reported solution.
    pub fn p(&self) -> Option<f64> {
        self.solution.p
    }

    /// The full structural results for pair results `pairs` at load `p` (for instance those of
    /// [`unilateral_contact::ContactSolution::at_many`] at many loads in one walk along the
    /// path): one solve with the bonded structure's factor, checked finite.
    pub fn recover_pairs(&self, p: f64, pairs: &[PairResult]) -> Result<Results, AnalysisError> {
        let r = self
            .condensed
            .recover(&link_values(p, pairs))
            .map_err(|source| {
                recovery_error(Place::Load(p), source, self.condensed.model().names())
            })?;
        checked(r, Place::Load(p), &self.condensed)
    }

    /// The pair results (without tightening) and full structural results at another load `p`
    /// of the traced path. A contact error at `p` (forces beyond the floating-point range, or
    /// the engine's own failure) is [`AnalysisError::Contact`].
    pub fn results_at(&self, p: f64) -> Result<(Vec<PairResult>, Results), AnalysisError> {
        let Some((pairs, _)) = self.solution.at(p)? else {
            let end = match &self.solution.outcome {
                Outcome::Ray { .. } => "infinity (ray)".to_string(),
                _ => self.solution.steps.last().map_or("p = 0".to_string(), |s| {
                    format!("p = {}", unilateral_contact::number_text(s.p))
                }),
            };
            return Err(AnalysisError::NotOnPath { p, end });
        };
        let r = self.recover_pairs(p, &pairs)?;
        Ok((pairs, r))
    }

    /// The loads of the events along the path (one per step), in order.
    pub fn event_loads(&self) -> Vec<f64> {
        self.solution.steps.iter().map(|s| s.p).collect()
    }

    /// Extremes of the results at the reported load.
    pub fn extremes(&self) -> Option<Extremes> {
        self.results.as_ref().map(|r| extremes(r, self.names()))
    }
}

/// The largest displacement, internal forces and stresses of a set of results.
pub fn extremes(r: &Results, names: &Names) -> Extremes {
    let mut ex = Extremes::default();
    for (i, d) in r.displacements.iter().enumerate() {
        let v = d[0].hypot(d[1]);
        if ex.displacement.as_ref().is_none_or(|b| v > b.value) {
            ex.displacement = Some(NodeValue {
                node: NodeId(i),
                name: names.node(NodeId(i)),
                value: v,
            });
        }
    }
    let better =
        |cur: &Option<ElementValue>, v: f64| cur.as_ref().is_none_or(|b| v.abs() > b.value.abs());
    for line in &r.lines {
        for pt in &line.diagram {
            let mk = |value: f64| ElementValue {
                element: line.element,
                name: names.element(line.element),
                value,
                at: [pt.s, 0.0],
            };
            if better(&ex.axial, pt.n) {
                ex.axial = Some(mk(pt.n));
            }
            if better(&ex.moment, pt.m) && (pt.m != 0.0 || ex.moment.is_none()) {
                ex.moment = Some(mk(pt.m));
            }
            if better(&ex.shear, pt.q) && (pt.q != 0.0 || ex.shear.is_none()) {
                ex.shear = Some(mk(pt.q));
            }
        }
    }
    for pl in &r.planes {
        for (g, s) in pl.stress.iter().enumerate() {
            let vm = unilateral_fem::von_mises(*s);
            let (_, s2) = unilateral_fem::principal(*s);
            let mk = |value: f64| ElementValue {
                element: pl.element,
                name: names.element(pl.element),
                value,
                at: pl.gauss_points[g],
            };
            if ex.von_mises.as_ref().is_none_or(|b| vm > b.value) {
                ex.von_mises = Some(mk(vm));
            }
            if ex.min_principal.as_ref().is_none_or(|b| s2 < b.value) {
                ex.min_principal = Some(mk(s2));
            }
        }
    }
    ex
}
