//! The JSON documents of `interfaces.md`: of a contact solution, a plain LCP, the tableaux and a
//! structural analysis. Every number is checked finite first ([`NonFiniteOutput`] otherwise):
//! no `null`, `NaN` or `inf` is ever written.

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

/// The name of a restrained DOF in result files: `ux`, `uy`, `rz` or `along(nx, ny)`.
pub(crate) fn dof_name(d: &unilateral_fem::SupportDof) -> String {
    match (d.label(), d) {
        (Some(l), _) => l.as_str().into(),
        (None, unilateral_fem::SupportDof::Along(v)) => format!("along({}, {})", v[0], v[1]),
        (None, _) => String::new(),
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
    let obj = doc.as_object_mut().expect("an object");
    obj.extend(crate::history_structure::results_json(a.names(), r));
    Ok(doc)
}

/// The `timings` object of a result document: the seconds of each part of the run that
/// happened (`read`, `condense`, `solve`, `recover`, `write`, in that order of the run; the
/// keys of the parts that did not happen are absent). Durations are finite and non-negative by
/// construction, so no finite-number check is needed.
pub fn timings_json(t: &unilateral_analysis::Timings) -> Value {
    Value::Object(
        t.present()
            .map(|(name, d)| (name.to_string(), Value::from(d.as_secs_f64())))
            .collect(),
    )
}

/// The result document with its `timings` added.
pub fn with_timings(mut doc: Value, t: &unilateral_analysis::Timings) -> Value {
    if let Some(obj) = doc.as_object_mut() {
        obj.insert("timings".into(), timings_json(t));
    }
    doc
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use crate::{timings_json, timings_summary, with_timings};
    use unilateral_analysis::Timings;

    /// Hand-made timings: only the parts given appear, in the order of a run, in seconds.
    #[test]
    fn timings_are_written_in_seconds_for_the_parts_that_happened() {
        let t = Timings {
            read: Some(Duration::from_millis(12)),
            solve: Some(Duration::from_millis(1500)),
            write: Some(Duration::from_micros(250)),
            ..Timings::default()
        };
        assert_eq!(
            timings_json(&t),
            serde_json::json!({ "read": 0.012, "solve": 1.5, "write": 0.00025 })
        );
        assert_eq!(
            timings_summary(&t),
            "\ntime: read 0.01 s, solve 1.50 s, write 0.00 s\n"
        );
        let doc = with_timings(serde_json::json!({ "status": "solved" }), &t);
        assert_eq!(doc["status"], "solved");
        assert_eq!(doc["timings"]["solve"], 1.5);
        assert!(doc["timings"].get("condense").is_none());
    }
}
