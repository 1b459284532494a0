//! The error of every reader: which file, where in it, which key, and what is wrong.

use std::fmt;
use std::path::{Path, PathBuf};

/// A place in a text file: the file, and the 1-based line and column (in characters) when known.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file, as the caller named it (not canonicalized).
    pub file: PathBuf,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// 1-based column in characters, when known.
    pub column: Option<usize>,
}

impl Location {
    /// The whole file, no line known.
    pub fn file(file: impl Into<PathBuf>) -> Self {
        Self {
            file: file.into(),
            line: None,
            column: None,
        }
    }

    /// A file and an optional position.
    pub(crate) fn at(file: &Path, pos: Option<Pos>) -> Self {
        Self {
            file: file.to_path_buf(),
            line: pos.map(|p| p.line),
            column: pos.map(|p| p.col),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(col) = self.column {
                write!(f, ":{col}")?;
            }
        }
        Ok(())
    }
}

/// A 1-based line and column (columns count characters, not bytes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Pos {
    pub line: usize,
    pub col: usize,
}

/// What kind of problem an [`InputError`] reports. Every kind is bad input (the command-line
/// program exits with status 2); the kind only helps programs that want to react differently.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum InputErrorKind {
    /// The file cannot be opened or read.
    Io,
    /// The file is not UTF-8 text.
    Encoding,
    /// TOML, JSON, Matrix Market or `.dat` syntax.
    Syntax,
    /// A required key is missing.
    MissingKey,
    /// A key that the format does not know (often a typo).
    UnknownKey,
    /// A value of the wrong type (a string where a number belongs, …).
    WrongType,
    /// Sizes that disagree (non-square matrix, vector of the wrong length, …).
    Size,
    /// A value out of range: NaN or infinite, negative friction, an unknown `trace`, …
    Value,
    /// A file variant this program does not read (sparse Siconos storage, complex Matrix Market, …).
    Unsupported,
    /// The data is complete and well-typed but inconsistent (e.g. a non-symmetric `Rnn`).
    Invalid,
}

/// Bad input: the file, the place in it (line and column, and/or the key path such as
/// `contact_zone.Rnn[2][3]`), and the problem in plain words.
///
/// Displayed like a compiler message:
///
/// ```text
/// model.toml:12:7: contact_zone.Rnn: row 2 has 2 entries, expected 3 (as row 1)
/// ```
///
/// Indices in key paths and messages are **1-based** (row 1 is the first row), as in the paper
/// and in [`unilateral_contact::ContactError`].
///
/// When the problem lies in a Matrix Market file named by a problem file, [`location`] is the
/// `.mtx` file and [`referenced_from`] the place in the problem file that named it.
///
/// [`location`]: InputError::location
/// [`referenced_from`]: InputError::referenced_from
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct InputError {
    /// Where the problem is.
    pub location: Location,
    /// The key path in the problem file (e.g. `load.variable.normal[2]`), when there is one.
    pub key: Option<String>,
    /// What kind of problem.
    pub kind: InputErrorKind,
    /// The problem in plain words.
    pub message: String,
    /// For a problem inside a file named by another file: where it was named.
    pub referenced_from: Option<Box<Location>>,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.location)?;
        if let Some(key) = &self.key {
            write!(f, "{key}: ")?;
        }
        write!(f, "{}", self.message)?;
        if let Some(from) = &self.referenced_from {
            write!(f, " (this file is named at {from})")?;
        }
        Ok(())
    }
}

impl InputError {
    /// A new error at `location`.
    pub fn new(location: Location, kind: InputErrorKind, message: impl Into<String>) -> Self {
        Self {
            location,
            key: None,
            kind,
            message: message.into(),
            referenced_from: None,
        }
    }

    /// The same error with a key path.
    pub fn with_key(mut self, key: impl Into<String>) -> Self {
        self.key = Some(key.into());
        self
    }

    /// The file the error is about.
    pub fn file(&self) -> &Path {
        &self.location.file
    }

    pub(crate) fn at(
        file: &Path,
        pos: Option<Pos>,
        kind: InputErrorKind,
        message: impl Into<String>,
    ) -> Self {
        Self::new(Location::at(file, pos), kind, message)
    }
}

impl From<Box<InputError>> for InputError {
    fn from(e: Box<InputError>) -> Self {
        *e
    }
}
