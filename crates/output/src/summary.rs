//! The human-readable summaries: of a contact solution, a plain LCP, a structural analysis, and
//! the tableaux in the paper's layout. Every number is checked finite before it is printed
//! ([`NonFiniteOutput`] otherwise).

use std::fmt::Write as _;

use unilateral_contact::{ContactSolution, Outcome, PairResult};
use unilateral_lcp::{LcpSolution, Tableau};

use crate::finite::{self, NonFiniteOutput};

use crate::json::About;

/// Numbers for people: 6 significant digits, never `-0`.
fn fmt_num(v: f64) -> String {
    finite::plain(v)
}

/// The human-readable summary of a contact solve.
pub fn contact_summary(sol: &ContactSolution, title: &str) -> Result<String, NonFiniteOutput> {
    contact_summary_with(sol, title, &About::default())
}

/// The header of a summary: the program's `title` line, then the file's title (unless the
/// line already holds it) and units.
fn header(s: &mut String, title: &str, about: &About) {
    let _ = writeln!(s, "{title}");
    if let Some(t) = about.title.as_deref().filter(|t| !title.contains(t)) {
        let _ = writeln!(s, "title: {t}");
    }
    if let Some(u) = &about.units {
        let _ = writeln!(s, "units: {u}");
    }
}

/// How much a summary says: everything (`verbose`), or — for more than [`SUMMARY_PAIRS`](crate::history::SUMMARY_PAIRS)
/// pairs — counts of states, the first and last events, and the pairs with the largest forces
/// and slips.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Detail {
    /// Every step and every pair, whatever their number.
    pub verbose: bool,
}

/// The number of pairs up to which a summary lists every pair and every step.
pub const SUMMARY_LIST_PAIRS: usize = 24;

/// [`contact_summary`] with the file's title and units in its header (everything listed).
pub fn contact_summary_with(
    sol: &ContactSolution,
    title: &str,
    about: &About,
) -> Result<String, NonFiniteOutput> {
    contact_summary_detail(sol, title, about, Detail { verbose: true })
}

/// [`contact_summary_with`] that scales: for many pairs, unless `detail.verbose`, the counts of
/// states, the first and last 10 events, and the 10 pairs with the largest normal forces and
/// slips instead of every step and pair.
pub fn contact_summary_detail(
    sol: &ContactSolution,
    title: &str,
    about: &About,
    detail: Detail,
) -> Result<String, NonFiniteOutput> {
    let brief = !detail.verbose && sol.pairs.len() > SUMMARY_LIST_PAIRS;
    finite::contact_solution(sol)?;
    let mut s = String::new();
    header(&mut s, title, about);
    // The structure's own path first, where the path was traced with the paper's tightening.
    if let Some(physical) = sol.physical_reading() {
        let _ = writeln!(s, "physical path: {physical}");
    }
    let _ = writeln!(s, "status: {} — {}", sol.outcome.status(), sol.reading());
    match sol.p {
        Some(p) => {
            let _ = write!(s, "solution at p = {}", fmt_num(p));
            if sol.tightening > 0.0 {
                let _ = write!(
                    s,
                    " (tightening c = {} removed from it{})",
                    fmt_num(sol.tightening),
                    if sol.tightening_pivots > 0 {
                        let n = sol.tightening_pivots;
                        format!(" by {n} pivot{}", if n == 1 { "" } else { "s" })
                    } else {
                        String::new()
                    }
                );
            }
            let _ = writeln!(s);
        }
        None => {
            let why = if sol.unreported().is_some() || sol.no_state_at_start() {
                " (why: in the notes at the end)"
            } else {
                ""
            };
            let _ = writeln!(s, "no solution to report{why}");
        }
    }
    let _ = writeln!(s);
    // With --verbose every step is listed; by default the pivots that settle the start and
    // those with no event (the friction parts of an open pair trading places), which change
    // nothing a structure shows, are counted, not listed.
    let every = detail.verbose;
    let listed_where = if !every {
        "not listed (they are in --json)"
    } else {
        "listed below"
    };
    let settling = sol.steps.iter().filter(|st| st.settling).count();
    if settling > 0 {
        let _ = writeln!(
            s,
            "the working scheme at the start (p = 0) is settled by {settling} pivot{} — not \
             events ({})",
            if settling == 1 { "" } else { "s" },
            if !every {
                "listed with --json as `settling` steps"
            } else {
                "listed below"
            }
        );
    }
    let quiet = sol
        .steps
        .iter()
        .filter(|st| !st.settling && st.events.is_empty() && !st.turning)
        .count();
    let events: Vec<&unilateral_contact::LoadStep> = sol
        .steps
        .iter()
        .filter(|st| every || (!st.settling && (!st.events.is_empty() || st.turning)))
        .collect();
    if quiet > 0 {
        let _ = writeln!(
            s,
            "{quiet} pivot{} of the path change no pair's state (friction parts of open pairs \
             trading places): {listed_where}",
            if quiet == 1 { "" } else { "s" }
        );
    }
    if events.is_empty() {
        let _ = writeln!(s, "load path: no change of the working scheme");
    } else {
        let _ = writeln!(
            s,
            "load path ({} step{}{}):",
            events.len(),
            if events.len() == 1 { "" } else { "s" },
            if sol.tightening > 0.0 {
                format!(", traced with tightening c = {}", fmt_num(sol.tightening))
            } else {
                String::new()
            }
        );
        if sol.tightening > 0.0 {
            let _ = writeln!(
                s,
                "  these are the events of the paper's procedure: their loads depend on c{}",
                match sol.p {
                    Some(p) => format!(" (the solution at p = {} is free of c)", fmt_num(p)),
                    None => String::new(),
                }
            );
        }
        let _ = writeln!(
            s,
            "  {:>5}  {:>14}  {:<9} {:<9} events",
            "step", "p", "entering", "leaving"
        );
        let shown = events.len();
        for (k, st) in events.into_iter().enumerate() {
            if brief && shown > 20 && (10..shown - 10).contains(&k) {
                if k == 10 {
                    let _ = writeln!(
                        s,
                        "  … {} more steps (all of them with --verbose)",
                        shown - 20
                    );
                }
                continue;
            }
            let mut ev: Vec<String> = st.events.iter().map(|e| e.to_string()).collect();
            if st.settling {
                ev.push("(settles the start at p = 0)".into());
            } else if ev.is_empty() && !st.turning {
                ev.push("(no pair's state changes)".into());
            }
            if st.turning {
                ev.push("(load decreases: turning point)".into());
            }
            if st.index > sol.steps_before_target {
                ev.push("(beyond the target)".into());
            }
            let _ = writeln!(
                s,
                "  {:>5}  {:>14}  {:<9} {:<9} {}",
                st.index,
                fmt_num(st.p),
                st.entering,
                st.leaving,
                ev.join("; ")
            );
        }
    }
    if let Outcome::Mechanism { p_limit, mode } = &sol.outcome {
        // Traced with a tightening, the load is the traced path's (it depends on c).
        let _ = writeln!(
            s,
            "\nmechanism {} {}; rates per pair (dz_n, dz_t):",
            if sol.tightening > 0.0 {
                "of the tightened path at p ="
            } else {
                "at p_lim ="
            },
            fmt_num(*p_limit)
        );
        for (i, (dn, dt)) in mode.iter().enumerate() {
            if dn.abs() + dt.abs() > 1e-9 {
                let _ = writeln!(
                    s,
                    "  pair {:<6} {:>12} {:>12}",
                    i + 1,
                    fmt_num(*dn),
                    fmt_num(*dt)
                );
            }
        }
    }
    for note in &sol.notes {
        let _ = writeln!(s, "note: {note}");
    }
    if brief {
        let count =
            |k: unilateral_contact::PairState| sol.pairs.iter().filter(|p| p.state == k).count();
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "pairs at p = {} ({} pairs): {} open, {} stick, {} slip+, {} slip- (every pair with --verbose)",
            sol.p.map(fmt_num).unwrap_or_default(),
            sol.pairs.len(),
            count(unilateral_contact::PairState::Open),
            count(unilateral_contact::PairState::Stick),
            count(unilateral_contact::PairState::SlipPlus),
            count(unilateral_contact::PairState::SlipMinus)
        );
        let top = |key: &dyn Fn(&unilateral_contact::PairResult) -> f64| {
            let mut v: Vec<&unilateral_contact::PairResult> = sol.pairs.iter().collect();
            v.sort_by(|a, b| key(b).total_cmp(&key(a)));
            v.into_iter().take(10).collect::<Vec<_>>()
        };
        for (label, list) in [
            ("largest normal forces", top(&|p| p.x_n.abs())),
            ("largest slips", top(&|p| p.z_t.abs())),
        ] {
            let _ = writeln!(s, "  {label}:");
            for p in list {
                pair_row(&mut s, p);
            }
        }
    } else if !sol.pairs.is_empty() {
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "pairs at p = {}:",
            sol.p.map(fmt_num).unwrap_or_default()
        );
        let _ = writeln!(
            s,
            "  {:<8} {:>14} {:>14} {:>14} {:>14}  state",
            "pair", "x_n", "x_t", "z_n", "z_t"
        );
        for p in &sol.pairs {
            pair_row(&mut s, p);
        }
    }
    if let Some(r) = &sol.residual {
        let _ = writeln!(
            s,
            "\nresiduals (relative): equation {:.1e}, feasibility {:.1e}, complementarity {:.1e} — {}",
            r.equation,
            r.feasibility,
            r.complementarity,
            if r.max() <= unilateral_lcp::ACCEPT_RESIDUAL {
                "verified"
            } else {
                "NOT verified"
            }
        );
    }
    Ok(s)
}

/// The human-readable summary of a plain LCP solve.
pub fn lcp_summary(sol: &LcpSolution, title: &str) -> Result<String, NonFiniteOutput> {
    finite::lcp_solution(sol)?;
    let mut s = String::new();
    let _ = writeln!(s, "{title}");
    let _ = writeln!(
        s,
        "status: {} after {} pivots",
        sol.status.as_str(),
        sol.pivots
    );
    for a in &sol.attempts {
        let _ = writeln!(s, "  {a}");
    }
    if let Some(p) = &sol.point {
        let _ = writeln!(s, "  {:>6} {:>16} {:>16}", "i", "z", "w");
        for (i, (z, w)) in p.z.iter().zip(&p.w).enumerate() {
            let _ = writeln!(s, "  {:>6} {:>16} {:>16}", i + 1, fmt_num(*z), fmt_num(*w));
        }
        let r = &p.residual;
        let _ = writeln!(
            s,
            "residuals (relative): equation {:.1e}, feasibility {:.1e}, complementarity {:.1e} — verified",
            r.equation, r.feasibility, r.complementarity
        );
    }
    Ok(s)
}

/// A tableau in the paper's layout, with labels from `label`.
pub fn tableau_text(
    t: &Tableau,
    label: &dyn Fn(unilateral_lcp::Var) -> String,
) -> Result<String, NonFiniteOutput> {
    finite::tableaux(std::slice::from_ref(t))?;
    let mut s = String::new();
    let _ = writeln!(s, "tableau {}", t.title);
    let w = 9;
    let _ = write!(s, "{:<8}", "basis");
    for c in &t.columns {
        let mark = if Some(*c) == t.entering { "*" } else { "" };
        let _ = write!(s, " {:>w$}", format!("{}{mark}", label(*c)));
    }
    let _ = writeln!(s, " {:>w$} {:>w$}", "rhs", "min ratio");
    for (i, b) in t.basis.iter().enumerate() {
        let mark = if Some(i) == t.leaving_row { "*" } else { " " };
        let _ = write!(s, "{mark}{:<7}", label(*b));
        for v in &t.entries[i] {
            let _ = write!(s, " {:>w$}", short(*v));
        }
        let ratio = t.ratios[i].map(short).unwrap_or_default();
        let _ = writeln!(s, " {:>w$} {:>w$}", short(t.rhs[i]), ratio);
    }
    if let Some(e) = t.entering {
        let _ = write!(s, "leading column: {}", label(e));
        match t.leaving_row {
            Some(r) => {
                let _ = writeln!(s, "; leading row: {}", label(t.basis[r]));
            }
            None => {
                let _ = writeln!(s, "; no positive entry: ray");
            }
        }
    }
    Ok(s)
}

fn short(v: f64) -> String {
    if v.abs() < 1e-12 {
        "0".into()
    } else if v.abs() >= 1e-3 && v.abs() < 1e5 {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.2e}")
    }
}

/// The human-readable summary of a structural analysis: the contact summary, then the largest
/// displacement and internal forces and the equilibrium check.
pub fn structural_summary(
    a: &unilateral_analysis::Analysis,
    title: &str,
) -> Result<String, NonFiniteOutput> {
    structural_summary_with(a, title, &About::default())
}

/// [`structural_summary`] with the file's title and units in its header (everything listed).
pub fn structural_summary_with(
    a: &unilateral_analysis::Analysis,
    title: &str,
    about: &About,
) -> Result<String, NonFiniteOutput> {
    structural_summary_detail(a, title, about, Detail { verbose: true })
}

/// [`structural_summary_with`] that scales with the number of pairs ([`contact_summary_detail`]).
pub fn structural_summary_detail(
    a: &unilateral_analysis::Analysis,
    title: &str,
    about: &About,
    detail: Detail,
) -> Result<String, NonFiniteOutput> {
    finite::analysis(a)?;
    let mut s = contact_summary_detail(&a.solution, title, about, detail)?;
    if let (Some(r), Some(ex)) = (&a.results, a.extremes()) {
        let _ = writeln!(s, "\nstructure at p = {}:", fmt_num(r.p));
        if let Some(d) = &ex.displacement {
            let [ux, uy, _] = r.displacements[d.node.0];
            let _ = writeln!(
                s,
                "  largest displacement   {:>12} at node {} (ux = {}, uy = {})",
                fmt_num(d.value),
                d.name,
                fmt_num(ux),
                fmt_num(uy)
            );
        }
        // The magnitude under a `|…|` label (its sign is the element's convention, not a size).
        let line = |label: &str, v: &Option<unilateral_analysis::ElementValue>, s: &mut String| {
            if let Some(v) = v {
                let _ = writeln!(
                    s,
                    "  {label:<22} {:>12} in element {} at s = {}",
                    fmt_num(v.value.abs()),
                    v.name,
                    fmt_num(v.at[0])
                );
            }
        };
        line("largest |M|", &ex.moment, &mut s);
        line("largest |N|", &ex.axial, &mut s);
        line("largest |Q|", &ex.shear, &mut s);
        if let Some(v) = &ex.von_mises {
            let _ = writeln!(
                s,
                "  {:<22} {:>12} in element {} at ({}, {})",
                "largest von Mises",
                fmt_num(v.value),
                v.name,
                fmt_num(v.at[0]),
                fmt_num(v.at[1])
            );
        }
        let e = &r.equilibrium;
        let _ = writeln!(
            s,
            "  equilibrium: applied + reactions + contact + springs = ({}, {}, {}), relative {:.1e}",
            fmt_num(e.resultant[0]),
            fmt_num(e.resultant[1]),
            fmt_num(e.resultant[2]),
            e.relative()
        );
    }
    Ok(s)
}

/// The closing paragraph of a summary: a blank line and `time: read 0.01 s, solve 0.20 s`, the
/// parts of the run done by the time the summary is printed.
pub fn timings_summary(t: &unilateral_analysis::Timings) -> String {
    let parts: Vec<String> = t
        .present()
        .map(|(name, d)| format!("{name} {:.2} s", d.as_secs_f64()))
        .collect();
    format!("\ntime: {}\n", parts.join(", "))
}

/// One pair's line of the summary's table of pairs (name, `x_n`, `x_t`, `z_n`, `z_t`, state).
fn pair_row(s: &mut String, p: &PairResult) {
    let _ = writeln!(
        s,
        "  {:<8} {:>14} {:>14} {:>14} {:>14}  {}",
        p.name,
        fmt_num(p.x_n),
        fmt_num(p.x_t),
        fmt_num(p.z_n),
        fmt_num(p.z_t),
        p.state
    );
}
