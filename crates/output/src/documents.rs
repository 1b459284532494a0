//! Writing results: the human-readable summary, the JSON document of `interfaces.md` and CSV
//! tables. Everything here formats; nothing solves.
//!
//! No writer emits a non-finite number: each checks every number it would print first and
//! returns a [`NonFiniteOutput`] (an internal failure, not bad input) instead of writing a
//! `null`, `NaN` or `inf`.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::{json, Value};
use unilateral_contact::{ContactSolution, Outcome};
use unilateral_lcp::{LcpSolution, Residual, Tableau};

use crate::finite::{self, NonFiniteOutput};

/// The JSON value of a residual.
pub fn residual_json(r: Option<&Residual>) -> Result<Value, NonFiniteOutput> {
    if let Some(r) = r {
        finite::residual(r, "residual")?;
    }
    Ok(residual_json_unchecked(r))
}

fn residual_json_unchecked(r: Option<&Residual>) -> Value {
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
pub fn contact_json(sol: &ContactSolution) -> Result<Value, NonFiniteOutput> {
    finite::contact_solution(sol)?;
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
    Ok(json!({
        "status": sol.outcome.status(),
        "reading": sol.outcome.reading(sol.settings.target),
        "p": sol.p,
        "p_limit": p_limit,
        "target": sol.settings.target,
        "trace": match sol.settings.follow {
            unilateral_contact::Follow::ToTarget => "target",
            unilateral_contact::Follow::ToEnd => "end",
        },
        "tightening": sol.tightening,
        "tightening_pivots": sol.tightening_pivots,
        "pivots": sol.steps.len(),
        "steps": steps,
        "pairs": pairs,
        "mechanism": mechanism,
        "residual": residual_json_unchecked(sol.residual.as_ref()),
        "notes": sol.notes,
    }))
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
pub fn contact_summary(sol: &ContactSolution, title: &str) -> Result<String, NonFiniteOutput> {
    finite::contact_solution(sol)?;
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
    Ok(s)
}

/// Writes `pairs.csv` and `steps.csv` into `dir` (created if needed).
///
/// A non-finite number in the solution is an error carrying a [`NonFiniteOutput`]
/// ([`NonFiniteOutput::in_io_error`]), and then nothing is written.
pub fn write_contact_csv(
    sol: &ContactSolution,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    finite::contact_solution(sol)?;
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
pub fn lcp_json(sol: &LcpSolution) -> Result<Value, NonFiniteOutput> {
    finite::lcp_solution(sol)?;
    let (z, w, r) = match &sol.point {
        Some(p) => (
            json!(p.z),
            json!(p.w),
            residual_json_unchecked(Some(&p.residual)),
        ),
        None => (Value::Null, Value::Null, Value::Null),
    };
    Ok(json!({
        "status": sol.status.as_str(),
        "z": z,
        "w": w,
        "pivots": sol.pivots,
        "residual": r,
        "strategy": format!("{:?}", sol.strategy),
        "attempts": sol.attempts,
    }))
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

/// The tableaux as JSON (entries by row).
pub fn tableaux_json(
    ts: &[Tableau],
    label: &dyn Fn(unilateral_lcp::Var) -> String,
) -> Result<Value, NonFiniteOutput> {
    finite::tableaux(ts)?;
    Ok(Value::Array(
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
    ))
}

/// The human-readable summary of a structural analysis: the contact summary, then the largest
/// displacement and internal forces and the equilibrium check.
pub fn structural_summary(
    a: &unilateral_analysis::Analysis,
    title: &str,
) -> Result<String, NonFiniteOutput> {
    finite::analysis(a)?;
    let mut s = contact_summary(&a.solution, title)?;
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
        let line = |label: &str, v: &Option<unilateral_analysis::ElementValue>, s: &mut String| {
            if let Some(v) = v {
                let _ = writeln!(
                    s,
                    "  {label:<22} {:>12} in element {} at s = {}",
                    fmt_num(v.value),
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

fn dof_name(d: &unilateral_fem::SupportDof) -> String {
    match d {
        unilateral_fem::SupportDof::Ux => "ux".into(),
        unilateral_fem::SupportDof::Uy => "uy".into(),
        unilateral_fem::SupportDof::Rz => "rz".into(),
        unilateral_fem::SupportDof::Along(v) => format!("along({}, {})", v[0], v[1]),
    }
}

/// The result document of a structural analysis: the contact document plus node
/// displacements, reactions, frame end forces, plane-element stresses and the equilibrium check.
pub fn structural_json(a: &unilateral_analysis::Analysis) -> Result<Value, NonFiniteOutput> {
    finite::analysis(a)?;
    let mut doc = contact_json(&a.solution)?;
    let Some(r) = &a.results else {
        return Ok(doc);
    };
    let names = &a.names;
    let nodes: Vec<Value> = r
        .displacements
        .iter()
        .enumerate()
        .map(|(i, d)| {
            json!({ "node": names.node(unilateral_fem::NodeId(i)), "ux": d[0], "uy": d[1], "rz": d[2] })
        })
        .collect();
    let reactions: Vec<Value> = r
        .reactions
        .iter()
        .map(|x| json!({ "node": names.node(x.node), "dof": dof_name(&x.dof), "value": x.value }))
        .collect();
    let frames: Vec<Value> = r
        .lines
        .iter()
        .map(|l| {
            let f = l.end_forces;
            json!({
                "element": names.element(l.element),
                "end_forces": { "N1": f[0], "V1": f[1], "M1": f[2], "N2": f[3], "V2": f[4], "M2": f[5] },
                "diagram": l.diagram.iter().map(|p| json!({ "s": p.s, "N": p.n, "Q": p.q, "M": p.m })).collect::<Vec<_>>(),
            })
        })
        .collect();
    let planes: Vec<Value> = r
        .planes
        .iter()
        .map(|pl| {
            json!({
                "element": names.element(pl.element),
                "gauss_points": pl.gauss_points,
                "stress": pl.stress.iter().map(|s| json!({ "sxx": s[0], "syy": s[1], "txy": s[2], "szz": s[3] })).collect::<Vec<_>>(),
            })
        })
        .collect();
    let e = &r.equilibrium;
    let obj = doc.as_object_mut().expect("an object");
    obj.insert("nodes".into(), Value::Array(nodes));
    obj.insert("reactions".into(), Value::Array(reactions));
    obj.insert("frames".into(), Value::Array(frames));
    obj.insert("plane_elements".into(), Value::Array(planes));
    obj.insert(
        "equilibrium".into(),
        json!({ "applied": e.applied, "reactions": e.reactions, "contact": e.contact, "springs": e.springs, "resultant": e.resultant, "relative": e.relative() }),
    );
    Ok(doc)
}

/// Writes the contact tables and one table per kind of structural result into `dir`.
pub fn write_structural_csv(
    a: &unilateral_analysis::Analysis,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    finite::analysis(a)?;
    let mut files = write_contact_csv(&a.solution, dir)?;
    let Some(r) = &a.results else {
        return Ok(files);
    };
    let names = &a.names;
    let mut t = String::from("node,ux,uy,rz\n");
    for (i, d) in r.displacements.iter().enumerate() {
        let _ = writeln!(
            t,
            "{},{:e},{:e},{:e}",
            csv_field(&names.node(unilateral_fem::NodeId(i))),
            d[0],
            d[1],
            d[2]
        );
    }
    files.push(write_table(dir, "displacements.csv", t)?);
    let mut t = String::from("node,dof,value\n");
    for x in &r.reactions {
        let _ = writeln!(
            t,
            "{},{},{:e}",
            csv_field(&names.node(x.node)),
            csv_field(&dof_name(&x.dof)),
            x.value
        );
    }
    files.push(write_table(dir, "reactions.csv", t)?);
    let mut t = String::from("element,N1,V1,M1,N2,V2,M2\n");
    for l in &r.lines {
        let f = l.end_forces;
        let _ = writeln!(
            t,
            "{},{:e},{:e},{:e},{:e},{:e},{:e}",
            csv_field(&names.element(l.element)),
            f[0],
            f[1],
            f[2],
            f[3],
            f[4],
            f[5]
        );
    }
    files.push(write_table(dir, "frame_end_forces.csv", t)?);
    let mut t = String::from("element,gauss_point,x,y,sxx,syy,txy,szz\n");
    for pl in &r.planes {
        for (g, (xy, st)) in pl.gauss_points.iter().zip(&pl.stress).enumerate() {
            let _ = writeln!(
                t,
                "{},{},{:e},{:e},{:e},{:e},{:e},{:e}",
                csv_field(&names.element(pl.element)),
                g + 1,
                xy[0],
                xy[1],
                st[0],
                st[1],
                st[2],
                st[3]
            );
        }
    }
    files.push(write_table(dir, "plane_stresses.csv", t)?);
    Ok(files)
}

fn write_table(dir: &Path, name: &str, text: String) -> std::io::Result<std::path::PathBuf> {
    let path = dir.join(name);
    std::fs::write(&path, text)?;
    Ok(path)
}
