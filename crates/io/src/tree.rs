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

/// Levenshtein distance on lowercase characters.
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    let mut cur = vec![0; b.len() + 1];
    for (i, ca) in a.iter().enumerate() {
        cur[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    prev[b.len()]
}

/// The closest known key, if it is close enough to be a likely typo.
pub(crate) fn did_you_mean<'a>(unknown: &str, known: &[&'a str]) -> Option<&'a str> {
    let limit = match unknown.chars().count() {
        0..=2 => 1,
        3..=5 => 2,
        _ => 3,
    };
    known
        .iter()
        .map(|k| (distance(unknown, k), *k))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, k)| k)
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
}
