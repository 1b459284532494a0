//! Small typed readers for model files: ids, references, points, flags and `[solve]`.

use crate::error::{InputError, InputErrorKind, Pos};
use crate::reader::{Doc, Table};
use crate::tree::{did_you_mean, Node, Value};

/// A name or number that identifies something, with where it is written.
#[derive(Debug, Clone)]
pub(crate) struct Ref {
    pub name: String,
    pub pos: Option<Pos>,
    /// The key path where it is written.
    pub key: String,
}

/// An id: a non-empty string, or a whole number (which names the same thing as its decimal
/// string: `3` and `"3"` are one id).
pub(crate) fn id(doc: &Doc, node: &Node, key: &str) -> Result<Ref, InputError> {
    let name = match &node.value {
        Value::String(s) => {
            let s = s.trim();
            if s.is_empty() {
                return Err(doc.err(
                    node.pos,
                    key,
                    InputErrorKind::Value,
                    "an id must not be empty",
                ));
            }
            s.to_string()
        }
        Value::Integer(i) => i.to_string(),
        _ => {
            return Err(doc.err(
                node.pos,
                key,
                InputErrorKind::WrongType,
                format!(
                    "expected an id (a name in quotes or a whole number), found {}",
                    doc.describe(node)
                ),
            ))
        }
    };
    Ok(Ref {
        name,
        pos: node.pos,
        key: key.to_string(),
    })
}

/// One id or an array of ids.
pub(crate) fn refs(doc: &Doc, node: &Node, key: &str) -> Result<Vec<Ref>, InputError> {
    match &node.value {
        Value::Array(items) => {
            if items.is_empty() {
                return Err(doc.err(
                    node.pos,
                    key,
                    InputErrorKind::Size,
                    "the list is empty: name at least one node, set or element",
                ));
            }
            items
                .iter()
                .enumerate()
                .map(|(i, n)| id(doc, n, &format!("{key}[{}]", i + 1)))
                .collect()
        }
        _ => Ok(vec![id(doc, node, key)?]),
    }
}

/// A table's required number.
pub(crate) fn number(t: &Table, k: &str, what: &str) -> Result<f64, InputError> {
    let node = t.require(k, what)?;
    t.doc.number(node, &t.child(k))
}

/// A table's optional number.
pub(crate) fn opt_number(t: &Table, k: &str) -> Result<Option<f64>, InputError> {
    t.get(k).map(|n| t.doc.number(n, &t.child(k))).transpose()
}

/// A number that must be `> 0`.
pub(crate) fn positive(t: &Table, k: &str, what: &str) -> Result<f64, InputError> {
    let x = number(t, k, what)?;
    if x <= 0.0 {
        return Err(t.doc.err(
            t.get(k).and_then(|n| n.pos),
            &t.child(k),
            InputErrorKind::Value,
            format!("{what} must be > 0, got {x}"),
        ));
    }
    Ok(x)
}

/// A point or vector `[x, y]`.
pub(crate) fn vec2(doc: &Doc, node: &Node, key: &str) -> Result<[f64; 2], InputError> {
    let Value::Array(items) = &node.value else {
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::WrongType,
            format!("expected two numbers [x, y], found {}", doc.describe(node)),
        ));
    };
    if items.len() != 2 {
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::Size,
            format!("expected two numbers [x, y], found {} entries", items.len()),
        ));
    }
    Ok([
        doc.number(&items[0], &format!("{key}[1]"))?,
        doc.number(&items[1], &format!("{key}[2]"))?,
    ])
}

/// A non-zero direction `[x, y]`.
pub(crate) fn direction(doc: &Doc, node: &Node, key: &str) -> Result<[f64; 2], InputError> {
    let v = vec2(doc, node, key)?;
    if v[0] == 0.0 && v[1] == 0.0 {
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::Value,
            "a direction must not be [0, 0]",
        ));
    }
    Ok(v)
}

pub(crate) fn opt_bool(t: &Table, k: &str) -> Result<bool, InputError> {
    match t.get(k) {
        None => Ok(false),
        Some(node) => match node.value {
            Value::Bool(b) => Ok(b),
            _ => Err(t.doc.err(
                node.pos,
                &t.child(k),
                InputErrorKind::WrongType,
                format!("expected true or false, found {}", t.doc.describe(node)),
            )),
        },
    }
}

/// One of a few words.
pub(crate) fn choice<'a>(
    t: &Table,
    k: &str,
    options: &[&'a str],
    default: Option<&'a str>,
    what: &str,
) -> Result<&'a str, InputError> {
    let Some(node) = t.get(k) else {
        return match default {
            Some(d) => Ok(d),
            None => Err(t.doc.err(
                t.pos,
                &t.child(k),
                InputErrorKind::MissingKey,
                format!(
                    "missing key `{k}` in {}: {what} (one of {})",
                    t.name(),
                    quoted(options)
                ),
            )),
        };
    };
    let s = t.doc.string(node, &t.child(k))?;
    if let Some(o) = options.iter().find(|o| o.eq_ignore_ascii_case(s)) {
        return Ok(o);
    }
    let hint = match did_you_mean(s, options) {
        Some(o) => format!(" (did you mean \"{o}\"?)"),
        None => String::new(),
    };
    Err(t.doc.err(
        node.pos,
        &t.child(k),
        InputErrorKind::Value,
        format!(
            "unknown {what} \"{}\"{hint}: use one of {}",
            crate::tree::short(s),
            quoted(options)
        ),
    ))
}

pub(crate) fn quoted(options: &[&str]) -> String {
    options
        .iter()
        .map(|o| format!("\"{o}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every entry of an array of tables, with its key path (`elements[3]`).
pub(crate) fn table_array<'n>(t: &Table<'n>, k: &str) -> Result<Vec<Table<'n>>, InputError> {
    let Some(node) = t.get(k) else {
        return Ok(Vec::new());
    };
    let Value::Array(items) = &node.value else {
        return Err(t.doc.err(
            node.pos,
            &t.child(k),
            InputErrorKind::WrongType,
            format!(
                "expected an array of {}s (write [[{}]] for each entry), found {}",
                t.doc.table_word(),
                t.child(k),
                t.doc.describe(node)
            ),
        ));
    };
    items
        .iter()
        .enumerate()
        .map(|(i, item)| t.doc.table(item, &format!("{}[{}]", t.child(k), i + 1)))
        .collect()
}

/// The `[solve]` table: the same keys and checks as in contact-zone problems.
pub(crate) use crate::zone::solve_settings;
