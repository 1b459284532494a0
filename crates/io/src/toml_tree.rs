//! TOML → [`Node`] tree, keeping the position of every key and value.

use std::path::Path;

use toml_edit::{Item, TableLike, Value as TValue};

use crate::error::{InputError, InputErrorKind, Pos};
use crate::text::LineIndex;
use crate::tree::{Entry, Node, Value};

pub(crate) fn parse(path: &Path, text: &str) -> Result<Node, InputError> {
    let index = LineIndex::new(text);
    let doc = toml_edit::ImDocument::parse(text).map_err(|e| {
        let pos = e.span().map(|s| index.pos(s.start));
        // toml_edit's message can span lines; keep it on one.
        let msg = e
            .message()
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        InputError::at(
            path,
            pos,
            InputErrorKind::Syntax,
            format!("TOML syntax error: {msg}"),
        )
    })?;
    let conv = Conv { index: &index };
    Ok(Node {
        value: conv.table(doc.as_table()),
        pos: Some(Pos { line: 1, col: 1 }),
    })
}

struct Conv<'a> {
    index: &'a LineIndex<'a>,
}

impl Conv<'_> {
    fn pos(&self, span: Option<std::ops::Range<usize>>) -> Option<Pos> {
        span.map(|s| self.index.pos(s.start))
    }

    fn table(&self, t: &dyn TableLike) -> Value {
        let mut entries = Vec::new();
        for (k, item) in t.iter() {
            let key_pos = t.get_key_value(k).and_then(|(key, _)| self.pos(key.span()));
            let mut node = self.item(item);
            if node.pos.is_none() {
                node.pos = key_pos;
            }
            entries.push(Entry {
                key: k.to_string(),
                key_pos,
                node,
            });
        }
        Value::Table(entries)
    }

    fn item(&self, item: &Item) -> Node {
        match item {
            Item::None => Node {
                value: Value::Other("nothing"),
                pos: None,
            },
            Item::Value(v) => self.value(v),
            Item::Table(t) => Node {
                value: self.table(t),
                pos: self.pos(t.span()),
            },
            Item::ArrayOfTables(a) => Node {
                value: Value::Array(
                    a.iter()
                        .map(|t| Node {
                            value: self.table(t),
                            pos: self.pos(t.span()),
                        })
                        .collect(),
                ),
                pos: self.pos(a.span()),
            },
        }
    }

    fn value(&self, v: &TValue) -> Node {
        let pos = self.pos(v.span());
        let value = match v {
            TValue::String(s) => Value::String(s.value().clone()),
            TValue::Integer(i) => Value::Integer(*i.value()),
            TValue::Float(x) => Value::Float(*x.value()),
            TValue::Boolean(b) => Value::Bool(*b.value()),
            TValue::Datetime(_) => Value::Other("a date-time"),
            TValue::Array(a) => Value::Array(a.iter().map(|x| self.value(x)).collect()),
            TValue::InlineTable(t) => self.table(t),
        };
        Node { value, pos }
    }
}
