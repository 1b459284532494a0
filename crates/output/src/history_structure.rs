//! The result document of a structural model's load history: the history document
//! ([`crate::history_document`]) plus the structural results of the final state at the top
//! level (`nodes`, `reactions`, `frames`, `plane_elements`, `equilibrium`, with the keys of
//! the structural document of one load) and the same results of every stage end under
//! `history[k].structure`.
//!
//! The result objects are made here because the structural document of `json.rs` is built
//! from a whole `Analysis`; the keys are the same, and the tests hold them to that document.

use serde_json::{json, Value};
use unilateral_analysis::HistoryAnalysis;
use unilateral_fem::{Names, NodeId, Results};

use crate::finite::{finite, NonFiniteOutput};
use crate::json::dof_name;

/// Every number of one state's results that the document prints, named as in it under
/// `at` (`history[2].structure`).
fn check_results(r: &Results, at: &str) -> Result<(), NonFiniteOutput> {
    let all = |vs: &[f64], name: &dyn Fn(usize) -> String| {
        for (k, v) in vs.iter().enumerate() {
            finite(*v, || format!("{at}.{}", name(k)))?;
        }
        Ok::<(), NonFiniteOutput>(())
    };
    for (i, d) in r.displacements.iter().enumerate() {
        all(d, &|k| {
            format!("nodes[{}].{}", i + 1, ["ux", "uy", "rz"][k])
        })?;
    }
    for (i, x) in r.reactions.iter().enumerate() {
        finite(x.value, || format!("{at}.reactions[{}].value", i + 1))?;
        if let unilateral_fem::SupportDof::Along(v) = &x.dof {
            all(v, &|k| format!("reactions[{}].dof[{}]", i + 1, k + 1))?;
        }
    }
    const END: [&str; 6] = ["N1", "V1", "M1", "N2", "V2", "M2"];
    for (i, l) in r.lines.iter().enumerate() {
        all(&l.end_forces, &|k| {
            format!("frames[{}].end_forces.{}", i + 1, END[k])
        })?;
        for (j, p) in l.diagram.iter().enumerate() {
            all(&[p.s, p.n, p.q, p.m], &|k| {
                format!(
                    "frames[{}].diagram[{}].{}",
                    i + 1,
                    j + 1,
                    ["s", "N", "Q", "M"][k]
                )
            })?;
        }
    }
    for (i, pl) in r.planes.iter().enumerate() {
        for (g, (xy, st)) in pl.gauss_points.iter().zip(&pl.stress).enumerate() {
            all(xy, &|k| {
                format!(
                    "plane_elements[{}].gauss_points[{}][{}]",
                    i + 1,
                    g + 1,
                    k + 1
                )
            })?;
            all(st, &|k| {
                format!(
                    "plane_elements[{}].stress[{}].{}",
                    i + 1,
                    g + 1,
                    ["sxx", "syy", "txy", "szz"][k]
                )
            })?;
        }
    }
    let e = &r.equilibrium;
    for (name, v) in [
        ("applied", &e.applied),
        ("reactions", &e.reactions),
        ("contact", &e.contact),
        ("springs", &e.springs),
        ("resultant", &e.resultant),
    ] {
        all(v, &|k| format!("equilibrium.{name}[{}]", k + 1))?;
    }
    finite(e.relative(), || format!("{at}.equilibrium.relative"))
}

/// The structural results of one state: `nodes`, `reactions`, `frames`, `plane_elements`,
/// `equilibrium` (the keys of the structural document) — the one writer of them, for the
/// paper's single path and for every state of a history.
pub(crate) fn results_json(names: &Names, r: &Results) -> serde_json::Map<String, Value> {
    let nodes: Vec<Value> = r
        .displacements
        .iter()
        .enumerate()
        .map(|(i, d)| json!({ "node": names.node(NodeId(i)), "ux": d[0], "uy": d[1], "rz": d[2] }))
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
    let mut m = serde_json::Map::new();
    m.insert("nodes".into(), Value::Array(nodes));
    m.insert("reactions".into(), Value::Array(reactions));
    m.insert("frames".into(), Value::Array(frames));
    m.insert("plane_elements".into(), Value::Array(planes));
    m.insert(
        "equilibrium".into(),
        json!({ "applied": e.applied, "reactions": e.reactions, "contact": e.contact, "springs": e.springs, "resultant": e.resultant, "relative": e.relative() }),
    );
    m
}

/// The result document of a structural history (`history.md`, "Output"): the history
/// document ([`crate::history_document`]: `status`, `pairs` and `factors` of the final state,
/// `history[]`), the final state's `nodes`, `reactions`, `frames`, `plane_elements` and
/// `equilibrium` at the top level, and each stage end's under `history[k].structure`
/// (`null` for a stage without results).
pub fn history_structural_document(a: &HistoryAnalysis) -> Result<Value, NonFiniteOutput> {
    for (k, r) in a.stage_results.iter().enumerate() {
        check_results(r, &format!("history[{}].structure", k + 1))?;
    }
    let mut doc = crate::history::history_document(&a.history)?;
    let names = a.condensed.model().names();
    let n = a.history.stages.len();
    if let Some(list) = doc["history"].as_array_mut() {
        for (k, st) in list.iter_mut().enumerate() {
            st["structure"] = a
                .stage_results
                .get(k)
                .map_or(Value::Null, |r| Value::Object(results_json(names, r)));
        }
    }
    if let (Some(r), Some(obj)) = (
        n.checked_sub(1).and_then(|k| a.stage_results.get(k)),
        doc.as_object_mut(),
    ) {
        obj.extend(results_json(names, r));
    }
    Ok(doc)
}
