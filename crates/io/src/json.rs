//! A small JSON parser (RFC 8259) that keeps the position of every key and value, so that
//! errors about a value can name its line and column.

use std::collections::HashSet;
use std::path::Path;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::text::LineIndex;
use crate::tree::{short, Entry, Node, Value};

/// Deeper nesting than this is refused (no problem file needs more than 4 levels).
const MAX_DEPTH: usize = 64;

pub(crate) fn parse(path: &Path, text: &str) -> Result<Node, InputError> {
    let index = LineIndex::new(text);
    let mut p = Parser {
        path,
        text,
        bytes: text.as_bytes(),
        at: 0,
        index: &index,
    };
    p.skip_ws();
    if p.at >= p.bytes.len() {
        return Err(p.err_here("the file is empty: expected a JSON object"));
    }
    let node = p.value(0)?;
    p.skip_ws();
    if p.at < p.bytes.len() {
        return Err(p.err_here("unexpected text after the end of the JSON value"));
    }
    Ok(node)
}

struct Parser<'a> {
    path: &'a Path,
    text: &'a str,
    bytes: &'a [u8],
    at: usize,
    index: &'a LineIndex<'a>,
}

impl Parser<'_> {
    fn pos(&self, offset: usize) -> Pos {
        self.index.pos(offset)
    }

    fn err_at(&self, offset: usize, msg: impl Into<String>) -> InputError {
        InputError::at(
            self.path,
            Some(self.pos(offset)),
            InputErrorKind::Syntax,
            format!("JSON syntax error: {}", msg.into()),
        )
    }

    fn err_here(&self, msg: impl Into<String>) -> InputError {
        self.err_at(self.at, msg)
    }

    /// What is at the cursor, for messages.
    fn found(&self) -> String {
        match self.text.get(self.at..).and_then(|s| s.chars().next()) {
            None => "the end of the file".to_string(),
            Some(c) if c.is_control() => format!("the control character U+{:04X}", c as u32),
            Some(c) => format!("`{c}`"),
        }
    }

    fn skip_ws(&mut self) {
        while let Some(&b) = self.bytes.get(self.at) {
            if matches!(b, b' ' | b'\t' | b'\n' | b'\r') {
                self.at += 1;
            } else {
                break;
            }
        }
    }

    fn value(&mut self, depth: usize) -> Result<Node, InputError> {
        if depth > MAX_DEPTH {
            return Err(self.err_here(format!("nesting deeper than {MAX_DEPTH} levels")));
        }
        let start = self.at;
        let pos = Some(self.pos(start));
        let value = match self.bytes.get(self.at) {
            Some(b'{') => self.object(depth)?,
            Some(b'[') => self.array(depth)?,
            Some(b'"') => Value::String(self.string()?),
            Some(b'-' | b'0'..=b'9') => self.number()?,
            Some(b't') => self.literal("true", Value::Bool(true))?,
            Some(b'f') => self.literal("false", Value::Bool(false))?,
            Some(b'n') => {
                if self.text[self.at..].starts_with("null") {
                    self.at += 4;
                    Value::Other("null")
                } else if self.bytes[self.at..]
                    .get(..3)
                    .is_some_and(|w| w.eq_ignore_ascii_case(b"nan"))
                {
                    return Err(self.err_here(
                        "`nan` is not a JSON value (JSON has no NaN; every number must be finite)",
                    ));
                } else {
                    return Err(self.err_here(format!("expected a value, found {}", self.found())));
                }
            }
            Some(b'N' | b'I') => {
                return Err(self.err_here(format!(
                    "expected a value, found {} (JSON has no NaN or Infinity; every number must be finite)",
                    self.found()
                )))
            }
            _ => return Err(self.err_here(format!("expected a value, found {}", self.found()))),
        };
        Ok(Node { value, pos })
    }

    fn literal(&mut self, word: &str, v: Value) -> Result<Value, InputError> {
        if self.text[self.at..].starts_with(word) {
            self.at += word.len();
            Ok(v)
        } else {
            Err(self.err_here(format!("expected a value, found {}", self.found())))
        }
    }

    fn object(&mut self, depth: usize) -> Result<Value, InputError> {
        self.at += 1; // '{'
        let mut entries: Vec<Entry> = Vec::new();
        // The keys seen so far: a duplicate is found in constant time, not by a scan of the
        // entries (which made an object of many keys quadratic).
        let mut seen: HashSet<String> = HashSet::new();
        self.skip_ws();
        if self.bytes.get(self.at) == Some(&b'}') {
            self.at += 1;
            return Ok(Value::Table(entries));
        }
        loop {
            self.skip_ws();
            if self.bytes.get(self.at) != Some(&b'"') {
                return Err(self.err_here(format!(
                    "expected a key in double quotes, found {}",
                    self.found()
                )));
            }
            let key_start = self.at;
            let key = self.string()?;
            if !seen.insert(key.clone()) {
                return Err(self.err_at(
                    key_start,
                    format!("the key \"{}\" appears twice", short(&key)),
                ));
            }
            self.skip_ws();
            if self.bytes.get(self.at) != Some(&b':') {
                return Err(self.err_here(format!(
                    "expected `:` after the key \"{key}\", found {}",
                    self.found()
                )));
            }
            self.at += 1;
            self.skip_ws();
            let node = self.value(depth + 1)?;
            entries.push(Entry {
                key,
                key_pos: Some(self.pos(key_start)),
                node,
            });
            self.skip_ws();
            match self.bytes.get(self.at) {
                Some(b',') => {
                    self.at += 1;
                    self.skip_ws();
                    if self.bytes.get(self.at) == Some(&b'}') {
                        return Err(self.err_here("trailing comma before `}`"));
                    }
                }
                Some(b'}') => {
                    self.at += 1;
                    return Ok(Value::Table(entries));
                }
                _ => {
                    return Err(self.err_here(format!(
                        "expected `,` or `}}` after an object entry, found {}",
                        self.found()
                    )))
                }
            }
        }
    }

    fn array(&mut self, depth: usize) -> Result<Value, InputError> {
        self.at += 1; // '['
        let mut items = Vec::new();
        self.skip_ws();
        if self.bytes.get(self.at) == Some(&b']') {
            self.at += 1;
            return Ok(Value::Array(items));
        }
        loop {
            self.skip_ws();
            items.push(self.value(depth + 1)?);
            self.skip_ws();
            match self.bytes.get(self.at) {
                Some(b',') => {
                    self.at += 1;
                    self.skip_ws();
                    if self.bytes.get(self.at) == Some(&b']') {
                        return Err(self.err_here("trailing comma before `]`"));
                    }
                }
                Some(b']') => {
                    self.at += 1;
                    return Ok(Value::Array(items));
                }
                _ => {
                    return Err(self.err_here(format!(
                        "expected `,` or `]` after an array element, found {}",
                        self.found()
                    )))
                }
            }
        }
    }

    fn string(&mut self) -> Result<String, InputError> {
        let start = self.at;
        self.at += 1; // opening quote
        let mut out = String::new();
        loop {
            let Some(c) = self.text.get(self.at..).and_then(|s| s.chars().next()) else {
                return Err(self.err_at(start, "this string is never closed"));
            };
            match c {
                '"' => {
                    self.at += 1;
                    return Ok(out);
                }
                '\\' => {
                    self.at += 1;
                    let esc = self.bytes.get(self.at).copied();
                    self.at += 1;
                    match esc {
                        Some(b'"') => out.push('"'),
                        Some(b'\\') => out.push('\\'),
                        Some(b'/') => out.push('/'),
                        Some(b'b') => out.push('\u{8}'),
                        Some(b'f') => out.push('\u{c}'),
                        Some(b'n') => out.push('\n'),
                        Some(b'r') => out.push('\r'),
                        Some(b't') => out.push('\t'),
                        Some(b'u') => {
                            let hi = self.hex4()?;
                            let ch = if (0xD800..0xDC00).contains(&hi) {
                                // A surrogate pair: a second \uXXXX must follow.
                                if self.text[self.at..].starts_with("\\u") {
                                    self.at += 2;
                                    let lo = self.hex4()?;
                                    if !(0xDC00..0xE000).contains(&lo) {
                                        return Err(self.err_at(
                                            self.at - 6,
                                            "invalid low surrogate in a \\u escape",
                                        ));
                                    }
                                    char::from_u32(0x10000 + ((hi - 0xD800) << 10) + (lo - 0xDC00))
                                } else {
                                    None
                                }
                            } else {
                                char::from_u32(hi)
                            };
                            match ch {
                                Some(ch) => out.push(ch),
                                None => {
                                    return Err(self.err_at(
                                        self.at.saturating_sub(6),
                                        "invalid \\u escape (unpaired surrogate)",
                                    ))
                                }
                            }
                        }
                        _ => {
                            return Err(self.err_at(
                                self.at - 2,
                                "invalid escape in a string (valid: \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)",
                            ))
                        }
                    }
                }
                c if (c as u32) < 0x20 => {
                    return Err(self.err_here(
                        "control character in a string (a string must end on the line it starts)",
                    ))
                }
                c => {
                    out.push(c);
                    self.at += c.len_utf8();
                }
            }
        }
    }

    fn hex4(&mut self) -> Result<u32, InputError> {
        let digits = self.text.get(self.at..self.at + 4);
        match digits.and_then(|d| {
            if d.bytes().all(|b| b.is_ascii_hexdigit()) {
                u32::from_str_radix(d, 16).ok()
            } else {
                None
            }
        }) {
            Some(v) => {
                self.at += 4;
                Ok(v)
            }
            None => Err(self.err_here("expected 4 hexadecimal digits after \\u")),
        }
    }

    fn number(&mut self) -> Result<Value, InputError> {
        let start = self.at;
        let b = self.bytes;
        let mut i = self.at;
        if b.get(i) == Some(&b'-') {
            i += 1;
        }
        match b.get(i) {
            Some(b'0') => i += 1,
            Some(b'1'..=b'9') => {
                while b.get(i).is_some_and(u8::is_ascii_digit) {
                    i += 1;
                }
            }
            _ => {
                self.at = i;
                return Err(self.err_here(format!(
                    "expected a digit in a number, found {}",
                    self.found()
                )));
            }
        }
        let mut integer = true;
        if b.get(i) == Some(&b'.') {
            integer = false;
            i += 1;
            if !b.get(i).is_some_and(u8::is_ascii_digit) {
                self.at = i;
                return Err(self.err_here("expected a digit after the decimal point"));
            }
            while b.get(i).is_some_and(u8::is_ascii_digit) {
                i += 1;
            }
        }
        if matches!(b.get(i), Some(b'e' | b'E')) {
            integer = false;
            i += 1;
            if matches!(b.get(i), Some(b'+' | b'-')) {
                i += 1;
            }
            if !b.get(i).is_some_and(u8::is_ascii_digit) {
                self.at = i;
                return Err(self.err_here("expected a digit in the exponent"));
            }
            while b.get(i).is_some_and(u8::is_ascii_digit) {
                i += 1;
            }
        }
        if b.get(i)
            .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'.')
        {
            self.at = i;
            return Err(self.err_here(format!("unexpected {} in a number", self.found())));
        }
        let s = &self.text[start..i];
        self.at = i;
        if integer {
            if let Ok(v) = s.parse::<i64>() {
                return Ok(Value::Integer(v));
            }
        }
        match s.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Value::Float(x)),
            _ => Err(self.err_at(
                start,
                format!("the number {s} is too large for a 64-bit float"),
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<Node, InputError> {
        parse(Path::new("t.json"), s)
    }

    #[test]
    fn values_and_positions() {
        let n = p("{\n  \"a\": [1, -2.5e1, \"x\\u00e9\"],\n  \"b\": {\"c\": true}\n}").unwrap();
        let Value::Table(t) = n.value else { panic!() };
        assert_eq!(t[0].key, "a");
        assert_eq!(t[0].key_pos, Some(Pos { line: 2, col: 3 }));
        let Value::Array(a) = &t[0].node.value else {
            panic!()
        };
        assert!(matches!(a[0].value, Value::Integer(1)));
        assert!(matches!(a[1].value, Value::Float(x) if x == -25.0));
        assert!(matches!(&a[2].value, Value::String(s) if s == "xé"));
        assert_eq!(a[1].pos, Some(Pos { line: 2, col: 12 }));
    }

    #[test]
    fn errors() {
        for (text, frag, line, col) in [
            ("", "empty", 1, 1),
            ("{\"a\": 1,}", "trailing comma", 1, 9),
            ("{\"a\": 1 \"b\": 2}", "expected `,` or `}`", 1, 9),
            ("[1, 2", "expected `,` or `]`", 1, 6),
            ("{\"a\": NaN}", "NaN", 1, 7),
            ("{\"a\": 1e999}", "too large", 1, 7),
            ("{\"a\": \"x}", "never closed", 1, 7),
            ("{\"a\": 01}", "unexpected", 1, 8),
            ("{\"a\": 1, \"a\": 2}", "twice", 1, 10),
            ("{} x", "after the end", 1, 4),
        ] {
            let e = p(text).unwrap_err();
            assert!(e.message.contains(frag), "{text}: {e}");
            assert_eq!(
                (e.location.line, e.location.column),
                (Some(line), Some(col)),
                "{text}: {e}"
            );
        }
        let deep = "[".repeat(10_000);
        assert!(p(&deep).unwrap_err().message.contains("nesting"));
    }
}
