//! Reading typed values out of a [`Node`] tree with errors that name the file, the line and
//! column, and the key path.

use std::path::{Path, PathBuf};

use faer::Mat;

use crate::error::{InputError, InputErrorKind, Location, Pos};
use crate::mtx::{entry_place, read_matrix_market};
use crate::text::read_text;
use crate::tree::{did_you_mean, short, Entry, Node, Value};

/// The format of a problem file, from its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Format {
    Toml,
    Json,
    Dat,
}

pub(crate) fn format_of(path: &Path) -> Option<Format> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "toml" => Some(Format::Toml),
        "json" => Some(Format::Json),
        "dat" => Some(Format::Dat),
        _ => None,
    }
}

/// A parsed TOML or JSON document.
pub(crate) struct Doc<'a> {
    pub path: &'a Path,
    pub json: bool,
}

impl<'a> Doc<'a> {
    /// Reads and parses a `.toml` or `.json` file.
    pub fn load(path: &'a Path, what: &str) -> Result<(Doc<'a>, Node), InputError> {
        let json = match format_of(path) {
            Some(Format::Toml) => false,
            Some(Format::Json) => true,
            _ => {
                let ext = path
                    .extension()
                    .map(|e| format!("`.{}`", e.to_string_lossy()))
                    .unwrap_or_else(|| "no extension".to_string());
                return Err(InputError::at(
                    path,
                    None,
                    InputErrorKind::Unsupported,
                    format!("{what} must be a .toml or .json file, but this file has {ext}"),
                ));
            }
        };
        let text = read_text(path)?;
        let root = if json {
            crate::json::parse(path, &text)?
        } else {
            crate::toml_tree::parse(path, &text)?
        };
        Ok((Doc { path, json }, root))
    }

    pub fn err(
        &self,
        pos: Option<Pos>,
        key: &str,
        kind: InputErrorKind,
        msg: impl Into<String>,
    ) -> InputError {
        let e = InputError::at(self.path, pos, kind, msg);
        if key.is_empty() {
            e
        } else {
            e.with_key(key)
        }
    }

    /// "a table" in TOML is "an object" in JSON.
    pub fn describe(&self, node: &Node) -> String {
        let d = node.describe();
        if self.json {
            d.replace("a table", "an object")
        } else {
            d
        }
    }

    /// "a table" in TOML, "an object" in JSON.
    pub fn a_table(&self) -> &'static str {
        if self.json {
            "an object"
        } else {
            "a table"
        }
    }

    pub fn table_word(&self) -> &'static str {
        if self.json {
            "object"
        } else {
            "table"
        }
    }

    fn wrong_type(&self, node: &Node, key: &str, expected: &str) -> InputError {
        self.err(
            node.pos,
            key,
            InputErrorKind::WrongType,
            format!("expected {expected}, found {}", self.describe(node)),
        )
    }

    /// A table of the document with its key path (`""` for the top level).
    pub fn table<'n>(&'n self, node: &'n Node, key: &str) -> Result<Table<'n>, InputError> {
        match &node.value {
            Value::Table(entries) => Ok(Table {
                doc: self,
                entries,
                key: key.to_string(),
                pos: node.pos,
            }),
            _ => Err(self.wrong_type(node, key, self.a_table())),
        }
    }

    /// A finite number.
    pub fn number(&self, node: &Node, key: &str) -> Result<f64, InputError> {
        let Some(x) = node.as_number() else {
            return Err(self.wrong_type(node, key, "a number"));
        };
        if !x.is_finite() {
            return Err(self.err(
                node.pos,
                key,
                InputErrorKind::Value,
                format!("{x} is not a finite number"),
            ));
        }
        Ok(x)
    }

    pub fn string<'n>(&self, node: &'n Node, key: &str) -> Result<&'n str, InputError> {
        match &node.value {
            Value::String(s) => Ok(s),
            _ => Err(self.wrong_type(node, key, "a string")),
        }
    }

    /// A whole number `≥ 1` (an integral float such as `100.0` is accepted).
    pub fn positive_integer(&self, node: &Node, key: &str) -> Result<usize, InputError> {
        let v = match node.value {
            Value::Integer(i) => Some(i),
            Value::Float(x) if x.fract() == 0.0 && x.abs() < 9.0e15 => Some(x as i64),
            _ => None,
        };
        let Some(v) = v else {
            return Err(self.wrong_type(node, key, "a whole number ≥ 1"));
        };
        usize::try_from(v).ok().filter(|&v| v >= 1).ok_or_else(|| {
            self.err(
                node.pos,
                key,
                InputErrorKind::Value,
                format!("must be a whole number ≥ 1, got {v}"),
            )
        })
    }

    /// A vector of finite numbers, with the position of each entry.
    pub fn vector(
        &self,
        node: &Node,
        key: &str,
    ) -> Result<(Vec<f64>, Vec<Option<Pos>>), InputError> {
        let Value::Array(items) = &node.value else {
            return Err(self.wrong_type(node, key, "an array of numbers"));
        };
        let mut values = Vec::with_capacity(items.len());
        let mut pos = Vec::with_capacity(items.len());
        for (i, item) in items.iter().enumerate() {
            values.push(self.number(item, &format!("{key}[{}]", i + 1))?);
            pos.push(item.pos);
        }
        Ok((values, pos))
    }

    /// A matrix: an inline array of rows, or the name of a Matrix Market file relative to the
    /// problem file. Rows must have equal lengths; entries must be finite.
    pub fn matrix(&self, node: &Node, key: &str) -> Result<MatrixInput, InputError> {
        match &node.value {
            Value::String(name) => self.matrix_file(node, name, key),
            Value::Array(rows) => {
                let ncols = match rows.first().map(|r| &r.value) {
                    Some(Value::Array(first)) => first.len(),
                    _ => 0,
                };
                let mut mat = Mat::<f64>::zeros(rows.len(), ncols);
                let mut pos = Vec::with_capacity(rows.len());
                for (i, row) in rows.iter().enumerate() {
                    let Value::Array(entries) = &row.value else {
                        let hint = if row.as_number().is_some() {
                            " (a matrix is an array of rows: [[1, 2], [3, 4]]; for one pair write [[x]])"
                        } else {
                            ""
                        };
                        return Err(self.err(
                            row.pos,
                            key,
                            InputErrorKind::WrongType,
                            format!(
                                "row {} is {}, expected an array of numbers{hint}",
                                i + 1,
                                self.describe(row)
                            ),
                        ));
                    };
                    if entries.len() != ncols {
                        return Err(self.err(
                            row.pos,
                            key,
                            InputErrorKind::Size,
                            format!(
                                "row {} has {} entries, expected {ncols} (as row 1)",
                                i + 1,
                                entries.len()
                            ),
                        ));
                    }
                    let mut row_pos = Vec::with_capacity(ncols);
                    for (j, e) in entries.iter().enumerate() {
                        mat[(i, j)] = self.number(e, &format!("{key}[{}][{}]", i + 1, j + 1))?;
                        row_pos.push(e.pos);
                    }
                    pos.push(row_pos);
                }
                Ok(MatrixInput {
                    mat,
                    key: key.to_string(),
                    pos: node.pos,
                    source: MatrixSource::Inline(pos),
                })
            }
            _ => Err(self.wrong_type(
                node,
                key,
                "a matrix (an array of rows such as [[1, 2], [3, 4]]) or the name of a Matrix Market file",
            )),
        }
    }

    fn matrix_file(&self, node: &Node, name: &str, key: &str) -> Result<MatrixInput, InputError> {
        if name.trim().is_empty() {
            return Err(self.err(
                node.pos,
                key,
                InputErrorKind::Value,
                "the Matrix Market file name is empty",
            ));
        }
        let dir = self.path.parent().unwrap_or(Path::new(""));
        let file = dir.join(name);
        let from = Location::at(self.path, node.pos);
        let read = read_matrix_market(&file).map_err(|mut e| {
            if e.kind == InputErrorKind::Io {
                // The file named is not there: the error belongs to the problem file.
                self.err(
                    node.pos,
                    key,
                    InputErrorKind::Io,
                    format!(
                        "cannot read the Matrix Market file \"{name}\" (looked for {}): {}",
                        file.display(),
                        e.message.trim_start_matches("cannot read the file: ")
                    ),
                )
            } else {
                e.key = Some(key.to_string());
                e.referenced_from = Some(Box::new(from.clone()));
                e
            }
        })?;
        Ok(MatrixInput {
            mat: read,
            key: key.to_string(),
            pos: node.pos,
            source: MatrixSource::File { file, from },
        })
    }
}

/// Where the entries of a matrix were written.
pub(crate) enum MatrixSource {
    /// Inline: the position of entry `[i][j]`.
    Inline(Vec<Vec<Option<Pos>>>),
    /// A Matrix Market file, named at `from`; the place of an entry is looked up in the file
    /// when an error needs it.
    File { file: PathBuf, from: Location },
}

/// A matrix read from a problem file, with where it came from.
pub(crate) struct MatrixInput {
    pub mat: Mat<f64>,
    /// The key path (`contact_zone.Rnn`).
    pub key: String,
    /// Where the value of the key starts.
    pub pos: Option<Pos>,
    pub source: MatrixSource,
}

impl MatrixInput {
    /// An error about the whole matrix, at its key.
    pub fn err(&self, doc: &Doc, kind: InputErrorKind, msg: impl Into<String>) -> InputError {
        doc.err(self.pos, &self.key, kind, msg)
    }

    /// An error about entry `(i, j)` (0-based), placed where that entry is written.
    pub fn entry_err(
        &self,
        doc: &Doc,
        i: usize,
        j: usize,
        kind: InputErrorKind,
        msg: impl Into<String>,
    ) -> InputError {
        let key = format!("{}[{}][{}]", self.key, i + 1, j + 1);
        match &self.source {
            MatrixSource::Inline(pos) => {
                let p = pos.get(i).and_then(|r| r.get(j)).copied().flatten();
                doc.err(p.or(self.pos), &key, kind, msg)
            }
            MatrixSource::File { file, from } => {
                let mut e = InputError::at(file, entry_place(file, i, j), kind, msg).with_key(key);
                e.referenced_from = Some(Box::new(from.clone()));
                e
            }
        }
    }
}

/// A table of the document.
pub(crate) struct Table<'n> {
    pub doc: &'n Doc<'n>,
    pub entries: &'n [Entry],
    /// Key path of the table (`""` at the top level).
    pub key: String,
    pub pos: Option<Pos>,
}

impl<'n> Table<'n> {
    /// The key path of a child.
    pub fn child(&self, k: &str) -> String {
        if self.key.is_empty() {
            k.to_string()
        } else {
            format!("{}.{k}", self.key)
        }
    }

    /// How to name this table in messages.
    pub fn name(&self) -> String {
        if self.key.is_empty() {
            "the top level".to_string()
        } else if self.doc.json {
            format!("the object \"{}\"", self.key)
        } else {
            format!("[{}]", self.key)
        }
    }

    pub fn get(&self, k: &str) -> Option<&'n Node> {
        self.entries.iter().find(|e| e.key == k).map(|e| &e.node)
    }

    /// Every key must be one of `known`.
    pub fn check_keys(&self, known: &[&str]) -> Result<(), InputError> {
        for e in self.entries {
            if !known.contains(&e.key.as_str()) {
                let hint = match did_you_mean(&e.key, known) {
                    Some(k) => format!(" (did you mean `{k}`?)"),
                    None => String::new(),
                };
                let name = short(&e.key);
                return Err(self.doc.err(
                    e.key_pos.or(e.node.pos),
                    &self.child(&name),
                    InputErrorKind::UnknownKey,
                    format!(
                        "unknown key `{name}` in {}{hint}; the keys here are: {}",
                        self.name(),
                        known.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A required key.
    pub fn require(&self, k: &str, what: &str) -> Result<&'n Node, InputError> {
        self.get(k).ok_or_else(|| {
            self.doc.err(
                self.pos,
                &self.child(k),
                InputErrorKind::MissingKey,
                format!("missing key `{k}` in {}: {what}", self.name()),
            )
        })
    }

    /// A sub-table, if present.
    pub fn table(&self, k: &str) -> Result<Option<Table<'n>>, InputError> {
        match self.get(k) {
            None => Ok(None),
            Some(node) => self.doc.table(node, &self.child(k)).map(Some),
        }
    }
}
