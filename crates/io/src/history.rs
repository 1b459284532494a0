//! `[[history]]`: the stages of a load history (`history.md`), read the same way in structural
//! models and contact-zone problems.
//!
//! ```toml
//! [[history]]
//! name = "self-weight"          # optional; default "stage K"
//! factors = { dead = 1.0 }      # the factors at the END of the stage
//!
//! [[history]]
//! factors = { push = 1.0 }      # cases not named keep the factor they had
//! ```
//!
//! Every case starts at factor 0. A stage must change at least one factor; with a history the
//! `[solve]` keys of the paper's single load path (`tightening`, `target`, `trace`) do not
//! apply and are refused.

use unilateral_contact::Stage;

use crate::error::{InputError, InputErrorKind};
use crate::reader::Table;
use crate::tree::{did_you_mean, short, Value};

const STAGE_KEYS: &[&str] = &["name", "factors"];

/// The `[solve]` keys that belong to the paper's single load path, with why they do not
/// apply to a history.
const PATH_KEYS: &[(&str, &str)] = &[
    (
        "tightening",
        "a load history is followed without the tightening: each stage starts from the state the previous one ended in",
    ),
    (
        "target",
        "with a load history the stages' factors say where the load goes, not a target load p*",
    ),
    (
        "trace",
        "with a load history every stage is followed to its end (s = 1), or to where it cannot go on",
    ),
];

/// The names of the load cases as `a`, `b`, `c` for messages.
fn listed(cases: &[String]) -> String {
    cases
        .iter()
        .map(|c| format!("`{}`", short(c)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads the top-level `history` (`[[history]]` in TOML, `"history": [...]` in JSON), the
/// factors indexed like `cases`; `None` when the file has none. `loads` names the tables of
/// the cases in messages (`loads` in a structural model, `load` in a contact-zone file).
pub(crate) fn read_history(
    top: &Table,
    cases: &[String],
    loads: &str,
) -> Result<Option<Vec<Stage>>, InputError> {
    let doc = top.doc;
    let Some(node) = top.get("history") else {
        return Ok(None);
    };
    let Value::Array(items) = &node.value else {
        return Err(doc.err(
            node.pos,
            "history",
            InputErrorKind::WrongType,
            format!(
                "expected an array of {}s, one per stage (write [[history]] for each stage), found {}",
                doc.table_word(),
                doc.describe(node)
            ),
        ));
    };
    if items.is_empty() {
        return Err(doc.err(
            node.pos,
            "history",
            InputErrorKind::Size,
            "the history is empty: give at least one stage ([[history]] with `factors = { case = factor }`), or leave `history` out for the paper's single load path",
        ));
    }
    let mut now = vec![0.0; cases.len()];
    let mut stages = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let key = format!("history[{}]", k + 1);
        let t = doc.table(item, &key)?;
        t.check_keys(STAGE_KEYS)?;
        let name = match t.get("name") {
            Some(n) => {
                let s = doc.string(n, &t.child("name"))?.trim();
                if s.is_empty() {
                    return Err(doc.err(
                        n.pos,
                        &t.child("name"),
                        InputErrorKind::Value,
                        "a stage name must not be empty (leave `name` out for \"stage K\")",
                    ));
                }
                s.to_string()
            }
            None => format!("stage {}", k + 1),
        };
        let which = match t.get("name") {
            Some(_) => format!("stage {} (\"{}\")", k + 1, short(&name)),
            None => format!("stage {}", k + 1),
        };
        let fnode = t.require(
            "factors",
            "the load factors at the end of the stage, `factors = { case = factor, … }`",
        )?;
        let Value::Table(entries) = &fnode.value else {
            return Err(doc.err(
                fnode.pos,
                &t.child("factors"),
                InputErrorKind::WrongType,
                format!(
                    "expected a {} of load factors, case name → number (`factors = {{ {} = 1.0 }}`), found {}",
                    doc.table_word(),
                    cases.first().map_or("dead", |c| c.as_str()),
                    doc.describe(fnode)
                ),
            ));
        };
        let mut factors: Vec<Option<f64>> = vec![None; cases.len()];
        for e in entries {
            let fkey = format!("{}.{}", t.child("factors"), short(&e.key));
            let Some(c) = cases.iter().position(|c| *c == e.key) else {
                let names: Vec<&str> = cases.iter().map(String::as_str).collect();
                let hint = match did_you_mean(&e.key, &names) {
                    Some(n) => format!(" (did you mean `{n}`?)"),
                    None => String::new(),
                };
                let known = if cases.is_empty() {
                    format!("the file has no load cases ([{loads}.NAME])")
                } else {
                    format!("the load cases are {}", listed(cases))
                };
                return Err(doc.err(
                    e.key_pos.or(e.node.pos),
                    &fkey,
                    InputErrorKind::UnknownKey,
                    format!(
                        "unknown load case `{}` in the factors of {which}{hint}; {known}",
                        short(&e.key)
                    ),
                ));
            };
            factors[c] = Some(doc.number(&e.node, &fkey)?);
        }
        let changes = factors
            .iter()
            .zip(&now)
            .any(|(f, v)| f.is_some_and(|f| f != *v));
        if !changes {
            let detail = if entries.is_empty() {
                "it names no load case".to_string()
            } else {
                let at: Vec<String> = factors
                    .iter()
                    .zip(cases)
                    .filter_map(|(f, c)| f.map(|f| format!("{} = {f}", short(c))))
                    .collect();
                format!(
                    "every factor it gives is the one the stage starts with ({})",
                    at.join(", ")
                )
            };
            return Err(doc.err(
                item.pos,
                &key,
                InputErrorKind::Invalid,
                format!("{which} changes no load factor: {detail}; a stage must change at least one factor (every case starts at 0)"),
            ));
        }
        for (v, f) in now.iter_mut().zip(&factors) {
            if let Some(f) = f {
                *v = *f;
            }
        }
        stages.push(Stage { name, factors });
    }
    Ok(Some(stages))
}

/// With a history, refuses the `[solve]` keys of the paper's single load path.
pub(crate) fn refuse_path_keys(top: &Table) -> Result<(), InputError> {
    if top.get("history").is_none() {
        return Ok(());
    }
    let Some(solve) = top.table("solve")? else {
        return Ok(());
    };
    for (k, why) in PATH_KEYS {
        if let Some(e) = solve.entries.iter().find(|e| e.key == *k) {
            return Err(top.doc.err(
                e.key_pos.or(e.node.pos),
                &solve.child(k),
                InputErrorKind::Invalid,
                format!("`{k}` does not apply to a file with a [[history]]: {why}; remove it"),
            ));
        }
    }
    Ok(())
}

/// Without a history, a load case other than `constant` and `variable` is refused: only the
/// stages of a history give it a factor. `None` when `name` is one of the two.
pub(crate) fn case_without_history(table: &Table, name: &str) -> Option<InputError> {
    const GROUPS: &[&str] = &["constant", "variable"];
    if GROUPS.contains(&name) {
        return None;
    }
    let e = table.entries.iter().find(|e| e.key == name)?;
    let hint = match did_you_mean(name, GROUPS) {
        Some(n) => format!(" (did you mean `{n}`?)"),
        None => String::new(),
    };
    Some(table.doc.err(
        e.key_pos.or(e.node.pos),
        &table.child(&short(name)),
        InputErrorKind::UnknownKey,
        format!(
            "load case `{}`{hint} is used only by a load history: without [[history]] stages the file has the paper's two cases, `constant` and `variable` (R_c + p·R_v); add [[history]] stages that give `{}` its factors, or rename it",
            short(name),
            short(name)
        ),
    ))
}
