//! The outputs of a load history (`history.md`): the JSON document, the CSV tables and the
//! summary of a [`HistorySolution`]. The pictures are in `history_chart.rs`.
//!
//! Every number is checked finite before anything is made ([`NonFiniteOutput`] otherwise),
//! and the checks name the number as the JSON document does (`history[2].steps[3].s`).

use std::fmt::Write as _;

use serde_json::{json, Map, Value};
use unilateral_contact::{
    Event, EventKind, HistorySolution, HistoryStep, PairResult, PairState, StageSolution,
};

use crate::finite::{finite, NonFiniteOutput};
use crate::json::{pairs_json, About};

/// The pseudo-time of a point of a history: `stage − 1 + s` (stage 1-based), so that stage
/// `K` runs from `K − 1` to `K`.
pub fn pseudo_time(stage: usize, s: f64) -> f64 {
    stage.saturating_sub(1) as f64 + s
}

/// The factors at the stage parameter `s` of a stage.
pub(crate) fn factors_at(stage: &StageSolution, s: f64) -> Vec<f64> {
    stage
        .factors_start
        .iter()
        .zip(&stage.factors_end)
        .map(|(a, b)| a + s * (b - a))
        .collect()
}

/// Every number the history writers print, named as in the JSON document (1-based).
pub(crate) fn check(h: &HistorySolution) -> Result<(), NonFiniteOutput> {
    let pairs = |ps: &[PairResult], at: &dyn Fn() -> String| -> Result<(), NonFiniteOutput> {
        for (i, p) in ps.iter().enumerate() {
            for (what, v) in [
                ("x_n", p.x_n),
                ("x_t", p.x_t),
                ("z_n", p.z_n),
                ("z_t", p.z_t),
            ] {
                finite(v, || format!("{}.pairs[{}].{what}", at(), i + 1))?;
            }
        }
        Ok(())
    };
    let factors = |fs: &[f64], key: &str, at: &dyn Fn() -> String| {
        for (c, v) in fs.iter().enumerate() {
            let case = h.cases.get(c).map_or("?", String::as_str);
            finite(*v, || format!("{}.{key}.{case}", at()))?;
        }
        Ok::<(), NonFiniteOutput>(())
    };
    for st in &h.stages {
        let at = || format!("history[{}]", st.stage);
        factors(&st.factors_start, "factors_start", &at)?;
        factors(&st.factors_end, "factors_end", &at)?;
        finite(st.s_end, || format!("{}.s_end", at()))?;
        for step in &st.steps {
            let at_step = || format!("history[{}].steps[{}]", st.stage, step.step);
            finite(step.s, || format!("{}.s", at_step()))?;
            factors(&step.factors, "factors", &at_step)?;
            pairs(&step.pairs, &at_step)?;
        }
        pairs(&st.pairs, &at)?;
        let r = &st.residual;
        for (what, v) in [
            ("equation", r.equation),
            ("complementarity", r.complementarity),
            ("feasibility", r.feasibility),
            ("dissipation", r.dissipation),
        ] {
            finite(v, || format!("{}.residual.{what}", at()))?;
        }
        for (i, (dn, dt)) in st.mechanism.iter().flatten().enumerate() {
            finite(*dn, || format!("{}.mechanism[{}].dz_n", at(), i + 1))?;
            finite(*dt, || format!("{}.mechanism[{}].dz_t", at(), i + 1))?;
        }
    }
    Ok(())
}

/// The object `case → factor`, in the order of the cases.
fn factors_json(cases: &[String], fs: &[f64]) -> Value {
    Value::Object(
        cases
            .iter()
            .zip(fs)
            .map(|(c, v)| (c.clone(), json!(v)))
            .collect::<Map<_, _>>(),
    )
}

/// What an event does, as one word, and its direction (`+`, `-`) for a pair that starts to
/// slip.
pub fn change_word(kind: EventKind) -> (&'static str, Option<&'static str>) {
    match kind {
        EventKind::Opens => ("opens", None),
        EventKind::Closes => ("closes", None),
        EventKind::StartsSlippingPlus => ("slips", Some("+")),
        EventKind::StartsSlippingMinus => ("slips", Some("-")),
        EventKind::Sticks => ("sticks", None),
    }
}

/// The slip a pair keeps when it sticks at `step` (its accumulated `z_t` there).
fn kept_slip(step: &HistoryStep, e: &Event) -> Option<f64> {
    (e.kind == EventKind::Sticks)
        .then(|| step.pairs.get(e.pair).map(|p| p.z_t))
        .flatten()
}

/// The sentence of an event of a history: as on the load path, except that a pair that
/// sticks says which slip it keeps (`pair right.3 sticks (slip 1.2e-4 kept)`).
pub fn history_event_sentence(step: &HistoryStep, e: &Event) -> String {
    match kept_slip(step, e) {
        Some(z) => format!("pair {} sticks (slip {z:e} kept)", e.name),
        None => e.to_string(),
    }
}

fn step_json(cases: &[String], step: &HistoryStep) -> Value {
    let changes: Vec<Value> = step
        .events
        .iter()
        .map(|e| {
            let (what, direction) = change_word(e.kind);
            let mut c = json!({
                "pair": e.pair + 1,
                "name": e.name,
                "what": what,
                "direction": direction,
            });
            if let Some(z) = kept_slip(step, e) {
                c["slip_kept"] = json!(z);
            }
            c
        })
        .collect();
    json!({
        "step": step.step,
        "s": step.s,
        "factors": factors_json(cases, &step.factors),
        "entering": step.entering_label,
        "leaving": step.leaving_label,
        "events": step.events.iter().map(|e| history_event_sentence(step, e)).collect::<Vec<_>>(),
        "changes": changes,
        "pairs": pairs_json(&step.pairs),
    })
}

fn mechanism_json(mode: Option<&Vec<(f64, f64)>>) -> Value {
    match mode {
        Some(mode) => Value::Array(
            mode.iter()
                .enumerate()
                .map(|(i, (dn, dt))| json!({ "pair": i + 1, "dz_n": dn, "dz_t": dt }))
                .collect(),
        ),
        None => Value::Null,
    }
}

fn stage_json(cases: &[String], st: &StageSolution) -> Value {
    let r = &st.residual;
    json!({
        "stage": st.stage,
        "name": st.name,
        "factors_start": factors_json(cases, &st.factors_start),
        "factors_end": factors_json(cases, &st.factors_end),
        "status": st.status.as_str(),
        "s_end": st.s_end,
        "factors_reached": factors_json(cases, &factors_at(st, st.s_end)),
        "steps": st.steps.iter().map(|s| step_json(cases, s)).collect::<Vec<_>>(),
        "pairs": pairs_json(&st.pairs),
        "residual": {
            "equation": r.equation,
            "complementarity": r.complementarity,
            "feasibility": r.feasibility,
            "dissipation": r.dissipation,
        },
        "mechanism": mechanism_json(st.mechanism.as_ref()),
        "reason": st.reason,
    })
}

/// The `history` array of the result document (`history.md`, "Output"): per stage its
/// number, name, factors at start and end (objects `case → factor`), status, `s_end`, the
/// factors reached there (`factors_reached`), every step (`step`, `s`, `factors`, `entering`,
/// `leaving`, `events` as sentences, `changes` as `{pair, name, what, direction}` with
/// `slip_kept` for a pair that sticks, and the pairs at the step), the pairs at the end of
/// the stage, the residuals, the mechanism's direction (`null` unless a mechanism) and the
/// reason (`null` unless given).
pub fn history_json(h: &HistorySolution) -> Result<Value, NonFiniteOutput> {
    check(h)?;
    Ok(Value::Array(
        h.stages.iter().map(|s| stage_json(&h.cases, s)).collect(),
    ))
}

/// A sentence for engineers on how the history ended.
pub fn history_reading(h: &HistorySolution) -> String {
    let Some(last) = h.stages.last() else {
        return "no stage was run".into();
    };
    let at = |st: &StageSolution| {
        let f: Vec<String> = h
            .cases
            .iter()
            .zip(factors_at(st, st.s_end))
            .map(|(c, v)| format!("{c} = {v}"))
            .collect();
        format!(
            "stage {} \"{}\" at s = {} ({})",
            st.stage,
            st.name,
            st.s_end,
            f.join(", ")
        )
    };
    use unilateral_contact::StageStatus as S;
    // ": the stage's reason", where it has one.
    let why = last
        .reason
        .as_deref()
        .map_or(String::new(), |r| format!(": {r}"));
    match last.status {
        S::Completed => format!(
            "every stage was completed ({} stage{})",
            h.stages.len(),
            if h.stages.len() == 1 { "" } else { "s" }
        ),
        S::Mechanism => format!(
            "the structure becomes a mechanism in {}: the load cannot be carried further",
            at(last)
        ),
        S::Indeterminate => format!("the evolution is indeterminate in {}{why}", at(last)),
        S::IterationLimit => format!("the pivot cap was reached in {}", at(last)),
        S::NumericalFailure => format!(
            "the solver failed in {} (an internal failure of the program, not a fault of the \
             model){why}",
            at(last)
        ),
        S::Unresolved => format!(
            "the history cannot be followed in double precision in {}{why}",
            at(last)
        ),
    }
}

/// The result document of a contact-zone history: `status` (of the last stage run),
/// `reading`, `cases`, `factors` (the final ones), `pivots` (steps of all stages), `pairs`
/// (the final state), `mechanism` (of the last stage, else `null`), `residual` (of the last
/// stage) and `history` ([`history_json`]).
pub fn history_document(h: &HistorySolution) -> Result<Value, NonFiniteOutput> {
    let history = history_json(h)?;
    let last = h.stages.last();
    let residual = match last {
        Some(st) => json!({
            "equation": st.residual.equation,
            "complementarity": st.residual.complementarity,
            "feasibility": st.residual.feasibility,
            "dissipation": st.residual.dissipation,
        }),
        None => Value::Null,
    };
    Ok(json!({
        "status": h.status().as_str(),
        "reading": history_reading(h),
        "cases": h.cases,
        "factors": factors_json(&h.cases, &h.final_factors()),
        "pivots": h.stages.iter().map(|s| s.steps.len()).sum::<usize>(),
        "pairs": pairs_json(h.final_pairs()),
        "mechanism": mechanism_json(last.and_then(|s| s.mechanism.as_ref())),
        "residual": residual,
        "notes": h.notes,
        "history": history,
    }))
}

/// Adds the `history` array to a result document made for the final state (for instance a
/// structural document), and sets its `status` to the history's: the document then reads as
/// `history.md` asks.
pub fn with_history(mut doc: Value, h: &HistorySolution) -> Result<Value, NonFiniteOutput> {
    let history = history_json(h)?;
    if let Some(obj) = doc.as_object_mut() {
        obj.insert("status".into(), json!(h.status().as_str()));
        obj.insert("reading".into(), json!(history_reading(h)));
        obj.insert("factors".into(), factors_json(&h.cases, &h.final_factors()));
        obj.insert("notes".into(), json!(h.notes));
        obj.insert("history".into(), history);
    }
    Ok(doc)
}

// ---------------------------------------------------------------------------------------------
// CSV

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The header cells of the factors: `factor_<case>`.
fn factor_header(h: &HistorySolution) -> String {
    h.cases
        .iter()
        .map(|c| csv_field(&format!("factor_{c}")))
        .collect::<Vec<_>>()
        .join(",")
}

fn factor_cells(fs: &[f64]) -> String {
    fs.iter()
        .map(|v| format!("{v:e}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// The name of the table of stage `k` among `n` stages: `history_stage_K.csv`, `K` zero-padded
/// to the width of `n` (at least 2 digits).
pub fn stage_table_name(k: usize, n: usize) -> String {
    let w = n.to_string().len().max(2);
    format!("history_stage_{k:0w$}.csv")
}

/// The file of every event of the history.
pub const HISTORY_EVENTS_CSV: &str = "history_events.csv";
/// The file of every pair at every breakpoint of the history.
pub const HISTORY_BREAKPOINTS_CSV: &str = "history_breakpoints.csv";

/// The CSV tables of a history as `(file name, text)`, made and checked before any is
/// written (the CLI writes them):
///
/// * one table per stage ([`stage_table_name`]): `pair,name,x_n,x_t,z_n,z_t,state` at the end
///   of the stage;
/// * [`HISTORY_EVENTS_CSV`]: one row per change of a pair: `stage,stage_name,step,s,time,`
///   `factor_<case>…,pair,name,event,direction,slip_kept,description` (`time` the pseudo-time
///   `stage − 1 + s`; `event` `opens`/`closes`/`slips`/`sticks`);
/// * [`HISTORY_BREAKPOINTS_CSV`]: every pair at every step and at every stage end, in the
///   order of the history: `stage,stage_name,point,s,time,factor_<case>…,pair,name,x_n,x_t,`
///   `z_n,z_t,state` (`point` the step number, or `end`) — the data of load–displacement
///   curves.
///
/// The column names carry no units ([`About::history_csv`] gives them the file's).
pub fn history_csv(h: &HistorySolution) -> Result<Vec<(String, String)>, NonFiniteOutput> {
    history_tables(h, &About::default())
}

impl About {
    /// The CSV tables of [`history_csv`] with these units in the column names, as the paper's
    /// path has them: `x_n [N]`, `x_t [N]`, `z_n [m]`, `z_t [m]`, `slip_kept [m]` (factors, `s`
    /// and `time` are pure numbers).
    pub fn history_csv(
        &self,
        h: &HistorySolution,
    ) -> Result<Vec<(String, String)>, NonFiniteOutput> {
        history_tables(h, self)
    }
}

fn history_tables(
    h: &HistorySolution,
    about: &About,
) -> Result<Vec<(String, String)>, NonFiniteOutput> {
    check(h)?;
    let n = h.stages.len();
    let mut files = Vec::with_capacity(n + 2);
    let values = about.pair_columns();
    let kept_column = about.column("slip_kept", |_, l| l.into());
    for st in &h.stages {
        let mut t = format!("pair,name,{values},state\n");
        for (i, p) in st.pairs.iter().enumerate() {
            let _ = writeln!(
                t,
                "{},{},{:e},{:e},{:e},{:e},{}",
                i + 1,
                csv_field(&p.name),
                p.x_n,
                p.x_t,
                p.z_n,
                p.z_t,
                p.state
            );
        }
        files.push((stage_table_name(st.stage, n), t));
    }
    let fh = factor_header(h);
    let sep = if fh.is_empty() { "" } else { "," };
    let mut ev = format!(
        "stage,stage_name,step,s,time{sep}{fh},pair,name,event,direction,{kept_column},description\n"
    );
    let mut bp = format!("stage,stage_name,point,s,time{sep}{fh},pair,name,{values},state\n");
    let pair_rows = |bp: &mut String, head: &str, ps: &[PairResult]| {
        for (i, p) in ps.iter().enumerate() {
            let _ = writeln!(
                bp,
                "{head},{},{},{:e},{:e},{:e},{:e},{}",
                i + 1,
                csv_field(&p.name),
                p.x_n,
                p.x_t,
                p.z_n,
                p.z_t,
                p.state
            );
        }
    };
    for st in &h.stages {
        let name = csv_field(&st.name);
        for step in &st.steps {
            let head = format!(
                "{},{name},{},{:e},{:e}{sep}{}",
                st.stage,
                step.step,
                step.s,
                pseudo_time(st.stage, step.s),
                factor_cells(&step.factors)
            );
            for e in &step.events {
                let (what, dir) = change_word(e.kind);
                let kept = kept_slip(step, e).map_or(String::new(), |z| format!("{z:e}"));
                let _ = writeln!(
                    ev,
                    "{head},{},{},{what},{},{kept},{}",
                    e.pair + 1,
                    csv_field(&e.name),
                    dir.unwrap_or(""),
                    csv_field(&history_event_sentence(step, e))
                );
            }
            pair_rows(&mut bp, &head, &step.pairs);
        }
        let head = format!(
            "{},{name},end,{:e},{:e}{sep}{}",
            st.stage,
            st.s_end,
            pseudo_time(st.stage, st.s_end),
            factor_cells(&factors_at(st, st.s_end))
        );
        pair_rows(&mut bp, &head, &st.pairs);
    }
    files.push((HISTORY_EVENTS_CSV.to_string(), ev));
    files.push((HISTORY_BREAKPOINTS_CSV.to_string(), bp));
    Ok(files)
}

// ---------------------------------------------------------------------------------------------
// Summary

/// Up to 6 significant digits, plain between 1e-4 and 1e7, else with an exponent.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    let s = if (1e-4..1e7).contains(&a) {
        let digits = (5 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{v:.5e}")
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// The summary shows the pair table up to this many pairs, and counts of states beyond.
pub const SUMMARY_PAIRS: usize = crate::chart::MANY_PAIRS;

/// The human-readable summary of a history: how it ended, one line per stage (number, name,
/// status, `s_end`, number of changes of pairs, largest residual), the mechanism or the reason
/// of a stage that could not be completed, then the final pairs (a table for up to
/// [`SUMMARY_PAIRS`] pairs, the counts of states beyond).
pub fn history_summary(h: &HistorySolution, title: &str) -> Result<String, NonFiniteOutput> {
    check(h)?;
    let mut s = String::new();
    let _ = writeln!(s, "{title}");
    let _ = writeln!(
        s,
        "status: {} — {}",
        h.status().as_str(),
        history_reading(h)
    );
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "history ({} stage{} run):",
        h.stages.len(),
        if h.stages.len() == 1 { "" } else { "s" }
    );
    let name_w = h
        .stages
        .iter()
        .map(|st| st.name.chars().count())
        .max()
        .unwrap_or(0)
        .clamp(4, 32);
    let _ = writeln!(
        s,
        "  {:>5}  {:<name_w$}  {:<15}  {:>8}  {:>7}  {:>11}",
        "stage", "name", "status", "s_end", "changes", "residual"
    );
    for st in &h.stages {
        let changes: usize = st.steps.iter().map(|p| p.events.len()).sum();
        let _ = writeln!(
            s,
            "  {:>5}  {:<name_w$}  {:<15}  {:>8}  {:>7}  {:>11.3e}",
            st.stage,
            st.name,
            st.status.as_str(),
            short(st.s_end),
            changes,
            st.residual.max()
        );
    }
    for note in &h.notes {
        let _ = writeln!(s, "note: {note}");
    }
    for st in &h.stages {
        if let Some(mode) = &st.mechanism {
            let _ = writeln!(
                s,
                "\nmechanism in stage {} at s = {}; rates per pair (dz_n, dz_t):",
                st.stage,
                short(st.s_end)
            );
            for (i, (dn, dt)) in mode.iter().enumerate() {
                if dn.abs().max(dt.abs()) > 1e-9 {
                    let name = h.names.get(i).map_or("?", String::as_str);
                    let _ = writeln!(s, "  pair {name:<10} {:>12} {:>12}", short(*dn), short(*dt));
                }
            }
        }
        if let Some(r) = &st.reason {
            let _ = writeln!(s, "\nstage {}: {r}", st.stage);
        }
    }
    let pairs = h.final_pairs();
    let _ = writeln!(s);
    if pairs.len() <= SUMMARY_PAIRS {
        // A stage that failed ends in no state of the structure: its pairs are where the
        // engine stopped, shown for diagnosis, not as an answer.
        let failed = h.stages.last().is_some_and(|st| !st.status.has_states());
        let _ = writeln!(
            s,
            "{}",
            if failed {
                "the pairs where the engine stopped (not a solution):"
            } else {
                "final state of the pairs:"
            }
        );
        let w = pairs
            .iter()
            .map(|p| p.name.chars().count())
            .max()
            .unwrap_or(0)
            .clamp(4, 24);
        let _ = writeln!(
            s,
            "  {:<w$}  {:>13}  {:>13}  {:>13}  {:>13}  state",
            "pair", "x_n", "x_t", "z_n", "z_t"
        );
        for p in pairs {
            let _ = writeln!(
                s,
                "  {:<w$}  {:>13}  {:>13}  {:>13}  {:>13}  {}",
                p.name,
                short(p.x_n),
                short(p.x_t),
                short(p.z_n),
                short(p.z_t),
                p.state
            );
        }
    } else {
        let count = |st: PairState| pairs.iter().filter(|p| p.state == st).count();
        let _ = writeln!(
            s,
            "final state of the {} pairs: {} open, {} stick, {} slip+, {} slip-",
            pairs.len(),
            count(PairState::Open),
            count(PairState::Stick),
            count(PairState::SlipPlus),
            count(PairState::SlipMinus)
        );
    }
    Ok(s)
}
