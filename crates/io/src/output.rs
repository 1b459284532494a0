//! Writing results: the human-readable summary, the JSON document of `interfaces.md` and CSV
//! tables. Everything here formats; nothing solves.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::{json, Value};
use unilateral_contact::{ContactSolution, Outcome};
use unilateral_lcp::{LcpSolution, Residual, Tableau};

/// The JSON value of a residual.
pub fn residual_json(r: Option<&Residual>) -> Value {
    match r {
        Some(r) => json!({
            "equation": r.equation,
            "complementarity": r.complementarity,
            "feasibility": r.feasibility,
        }),
        None => Value::Null,
    }
}

/// The result document of a contact solve (`interfaces.md`, "Result JSON").
pub fn contact_json(sol: &ContactSolution) -> Value {
    let p_limit = match &sol.outcome {
        Outcome::Mechanism { p_limit, .. } => json!(p_limit),
        _ => Value::Null,
    };
    let mechanism = match &sol.outcome {
        Outcome::Mechanism { mode, .. } => Value::Array(
            mode.iter()
                .enumerate()
                .map(|(i, (dn, dt))| json!({ "pair": i + 1, "dz_n": dn, "dz_t": dt }))
                .collect(),
        ),
        _ => Value::Null,
    };
    let steps: Vec<Value> = sol
        .steps
        .iter()
        .map(|s| {
            json!({
                "step": s.index,
                "p": s.p,
                "entering": s.entering,
                "leaving": s.leaving,
                "events": s.events.iter().map(|e| e.to_string()).collect::<Vec<_>>(),
                "turning": s.turning,
                "beyond_target": s.index > sol.steps_before_target,
            })
        })
        .collect();
    let pairs: Vec<Value> = sol
        .pairs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            json!({
                "pair": i + 1,
                "name": p.name,
                "x_n": p.x_n,
                "x_t": p.x_t,
                "z_n": p.z_n,
                "z_t": p.z_t,
                "state": p.state.as_str(),
            })
        })
        .collect();
    json!({
        "status": sol.outcome.status(),
        "reading": sol.outcome.reading(sol.settings.target),
        "p": sol.p,
        "p_limit": p_limit,
        "target": sol.settings.target,
        "trace": match sol.settings.trace {
            unilateral_contact::Trace::Target => "target",
            unilateral_contact::Trace::End => "end",
        },
        "tightening": sol.tightening,
        "tightening_pivots": sol.tightening_pivots,
        "pivots": sol.steps.len(),
        "steps": steps,
        "pairs": pairs,
        "mechanism": mechanism,
        "residual": residual_json(sol.residual.as_ref()),
        "notes": sol.notes,
    })
}

fn fmt_num(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.abs() >= 1e-4 && v.abs() < 1e7 {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".into()
        } else {
            s.to_string()
        }
    } else {
        format!("{v:.4e}")
    }
}

/// The human-readable summary of a contact solve.
pub fn contact_summary(sol: &ContactSolution, title: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{title}");
    let _ = writeln!(
        s,
        "status: {} — {}",
        sol.outcome.status(),
        sol.outcome.reading(sol.settings.target)
    );
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
            let _ = writeln!(s, "no solution to report");
        }
    }
    let _ = writeln!(s);
    if sol.steps.is_empty() {
        let _ = writeln!(s, "load path: no change of the working scheme");
    } else {
        let _ = writeln!(
            s,
            "load path ({} step{}{}):",
            sol.steps.len(),
            if sol.steps.len() == 1 { "" } else { "s" },
            if sol.tightening > 0.0 {
                format!(", traced with tightening c = {}", fmt_num(sol.tightening))
            } else {
                String::new()
            }
        );
        let _ = writeln!(
            s,
            "  {:>5}  {:>14}  {:<9} {:<9} events",
            "step", "p", "entering", "leaving"
        );
        for st in &sol.steps {
            let mut ev: Vec<String> = st.events.iter().map(|e| e.to_string()).collect();
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
        let _ = writeln!(
            s,
            "\nmechanism at p_lim = {}; rates per pair (dz_n, dz_t):",
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
    if !sol.pairs.is_empty() {
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
    s
}

/// Writes `pairs.csv` and `steps.csv` into `dir` (created if needed).
pub fn write_contact_csv(
    sol: &ContactSolution,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut pairs = String::from("pair,name,x_n,x_t,z_n,z_t,state\n");
    for (i, p) in sol.pairs.iter().enumerate() {
        let _ = writeln!(
            pairs,
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
    let mut steps = String::from("step,p,entering,leaving,events,turning,beyond_target\n");
    for st in &sol.steps {
        let ev: Vec<String> = st.events.iter().map(|e| e.to_string()).collect();
        let _ = writeln!(
            steps,
            "{},{:e},{},{},{},{},{}",
            st.index,
            st.p,
            st.entering,
            st.leaving,
            csv_field(&ev.join("; ")),
            st.turning,
            st.index > sol.steps_before_target
        );
    }
    let a = dir.join("pairs.csv");
    let b = dir.join("steps.csv");
    std::fs::write(&a, pairs)?;
    std::fs::write(&b, steps)?;
    Ok(vec![a, b])
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The result document of a plain LCP solve.
pub fn lcp_json(sol: &LcpSolution) -> Value {
    let (z, w, r) = match &sol.point {
        Some(p) => (json!(p.z), json!(p.w), residual_json(Some(&p.residual))),
        None => (Value::Null, Value::Null, Value::Null),
    };
    json!({
        "status": sol.status.as_str(),
        "z": z,
        "w": w,
        "pivots": sol.pivots,
        "residual": r,
        "strategy": format!("{:?}", sol.strategy),
        "attempts": sol.attempts,
    })
}

/// The human-readable summary of a plain LCP solve.
pub fn lcp_summary(sol: &LcpSolution, title: &str) -> String {
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
    s
}

/// A tableau in the paper's layout, with labels from `label`.
pub fn tableau_text(t: &Tableau, label: &dyn Fn(unilateral_lcp::Var) -> String) -> String {
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
    s
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

/// The tableaux as JSON (entries by row).
pub fn tableaux_json(ts: &[Tableau], label: &dyn Fn(unilateral_lcp::Var) -> String) -> Value {
    Value::Array(
        ts.iter()
            .map(|t| {
                json!({
                    "title": t.title,
                    "after_steps": t.after_steps,
                    "basis": t.basis.iter().map(|v| label(*v)).collect::<Vec<_>>(),
                    "columns": t.columns.iter().map(|v| label(*v)).collect::<Vec<_>>(),
                    "entries": t.entries,
                    "rhs": t.rhs,
                    "ratios": t.ratios,
                    "entering": t.entering.map(label),
                    "leaving_row": t.leaving_row,
                })
            })
            .collect(),
    )
}
