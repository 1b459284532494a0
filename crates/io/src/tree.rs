//! A format-neutral document tree with source positions, built from TOML or JSON.

use crate::error::Pos;

/// A value and where it starts in the file.
#[derive(Debug, Clone)]
pub(crate) struct Node {
    pub value: Value,
    pub pos: Option<Pos>,
}

/// A table entry: the key, where the key is written, and the value.
#[derive(Debug, Clone)]
pub(crate) struct Entry {
    pub key: String,
    pub key_pos: Option<Pos>,
    pub node: Node,
}

#[derive(Debug, Clone)]
pub(crate) enum Value {
    Table(Vec<Entry>),
    Array(Vec<Node>),
    Integer(i64),
    Float(f64),
    String(String),
    Bool(bool),
    /// A TOML date-time or anything else no key of ours accepts; the text names the type.
    Other(&'static str),
}

impl Node {
    /// The type, in words, for messages ("a string", "an array", …).
    pub fn type_name(&self) -> &'static str {
        match &self.value {
            Value::Table(_) => "a table",
            Value::Array(_) => "an array",
            Value::Integer(_) | Value::Float(_) => "a number",
            Value::String(_) => "a string",
            Value::Bool(_) => "a boolean",
            Value::Other(t) => t,
        }
    }

    /// The type and a short rendering of the value, for messages: `a string ("abc")`.
    pub fn describe(&self) -> String {
        match &self.value {
            Value::String(s) => {
                let short: String = s.chars().take(40).collect();
                let more = if s.chars().count() > 40 { "…" } else { "" };
                format!("a string (\"{short}{more}\")")
            }
            Value::Bool(b) => format!("a boolean ({b})"),
            Value::Integer(i) => format!("a number ({i})"),
            Value::Float(x) => format!("a number ({x})"),
            _ => self.type_name().to_string(),
        }
    }

    pub fn as_number(&self) -> Option<f64> {
        match self.value {
            Value::Integer(i) => Some(i as f64),
            Value::Float(x) => Some(x),
            _ => None,
        }
    }
}

/// Names longer than this (in characters) get no "did you mean" suggestion: a typo of a name
/// that long is not found by eye anyway, and the comparison must stay cheap whatever the file.
const MAX_SUGGESTED_LEN: usize = 256;

/// The Levenshtein distance of `a` and `b` if it is at most `limit`, else `None`.
///
/// Only the band `|i - j| ≤ limit` of the table is computed (a path outside it costs more
/// than `limit`), so a call costs `O(len · limit)`, not `O(len²)`.
fn distance_within(a: &[char], b: &[char], limit: usize) -> Option<usize> {
    if a.len().abs_diff(b.len()) > limit {
        return None;
    }
    let over = limit + 1;
    // prev[j]: distance of a[..i] and b[..j], capped at `over`.
    let mut prev: Vec<usize> = (0..=b.len()).map(|j| j.min(over)).collect();
    let mut cur = vec![over; b.len() + 1];
    for (i, ca) in a.iter().enumerate() {
        let lo = (i + 1).saturating_sub(limit);
        let hi = (i + 1 + limit).min(b.len());
        cur.fill(over);
        if lo == 0 {
            cur[0] = (i + 1).min(over);
        }
        let mut best = cur[0];
        for j in lo.max(1)..=hi {
            let sub = prev[j - 1] + usize::from(*ca != b[j - 1]);
            let v = sub.min(prev[j] + 1).min(cur[j - 1] + 1).min(over);
            cur[j] = v;
            best = best.min(v);
        }
        if best > limit {
            return None;
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    Some(prev[b.len()]).filter(|&d| d <= limit)
}

fn lower_chars(s: &str) -> Vec<char> {
    s.chars().flat_map(char::to_lowercase).collect()
}

/// The closest known key, if it is close enough to be a likely typo (case is ignored).
pub(crate) fn did_you_mean<'a>(unknown: &str, known: &[&'a str]) -> Option<&'a str> {
    let len = unknown.chars().count();
    if len > MAX_SUGGESTED_LEN {
        return None;
    }
    let limit = match len {
        0..=2 => 1,
        3..=5 => 2,
        _ => 3,
    };
    let a = lower_chars(unknown);
    known
        .iter()
        .filter(|k| k.chars().count().abs_diff(len) <= limit)
        .filter_map(|k| distance_within(&a, &lower_chars(k), limit).map(|d| (d, *k)))
        .min_by_key(|&(d, _)| d)
        .map(|(_, k)| k)
}

/// A name cut to a length fit for a message: `abc…` after 60 characters.
pub(crate) fn short(s: &str) -> String {
    const KEEP: usize = 60;
    match s.char_indices().nth(KEEP) {
        None => s.to_string(),
        Some((cut, _)) => format!("{}… ({} characters)", &s[..cut], s.chars().count()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions() {
        let keys = ["friction", "gap", "Rnn", "Rtt", "Rnt", "Rtn", "names"];
        assert_eq!(did_you_mean("rnn", &keys), Some("Rnn"));
        assert_eq!(did_you_mean("fricton", &keys), Some("friction"));
        assert_eq!(did_you_mean("Rn", &keys), Some("Rnn"));
        assert_eq!(did_you_mean("stiffness", &keys), None);
        assert_eq!(did_you_mean("", &keys), None);
    }

    /// Reference: the full Levenshtein table, written the textbook way.
    fn full_distance(a: &str, b: &str) -> usize {
        let (a, b) = (lower_chars(a), lower_chars(b));
        let mut d = vec![vec![0; b.len() + 1]; a.len() + 1];
        for (i, row) in d.iter_mut().enumerate() {
            row[0] = i;
        }
        d[0] = (0..=b.len()).collect();
        for i in 1..=a.len() {
            for j in 1..=b.len() {
                let sub = d[i - 1][j - 1] + usize::from(a[i - 1] != b[j - 1]);
                d[i][j] = sub.min(d[i - 1][j] + 1).min(d[i][j - 1] + 1);
            }
        }
        d[a.len()][b.len()]
    }

    #[test]
    fn banded_distance_agrees_with_the_full_table() {
        let words = [
            "",
            "a",
            "ab",
            "ba",
            "Rnn",
            "rtt",
            "friction",
            "fricton",
            "frictionn",
            "tightening",
            "tighten",
            "gap",
            "gaps",
            "beam.10",
            "beam.01",
            "xyzzy",
            "名前",
            "名前x",
        ];
        for a in words {
            for b in words {
                let full = full_distance(a, b);
                for limit in 0..5 {
                    let banded = distance_within(&lower_chars(a), &lower_chars(b), limit);
                    let expected = (full <= limit).then_some(full);
                    assert_eq!(banded, expected, "{a:?} {b:?} limit {limit}");
                }
            }
        }
    }

    #[test]
    fn long_names_get_no_suggestion_and_short_messages() {
        let long = "x".repeat(1_000_000);
        assert_eq!(did_you_mean(&long, &[long.as_str()]), None);
        let shown = short(&long);
        assert!(
            shown.len() < 100 && shown.contains("1000000 characters"),
            "{shown}"
        );
        assert_eq!(short("Rnn"), "Rnn");
    }
}
