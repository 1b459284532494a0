//! A Matrix Market reader (`matrix coordinate|array real|integer general|symmetric`),
//! into a dense matrix, with errors that name the line.
//!
//! The file is read as a stream ([`crate::scan`]): the text of a large matrix is never held,
//! and no entry's place is stored. Where an error about the whole matrix later needs the place
//! of one entry, [`entry_place`] reads the file again (the error path only).

use std::path::Path;

use faer::Mat;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::scan::{Scan, Scanner, Source, Token};

/// Largest dense matrix built from a Matrix Market file (rows × columns).
pub(crate) const MAX_DENSE_ENTRIES: usize = 1 << 26;

/// Reads a dense matrix from a Matrix Market file.
///
/// Supported: `%%MatrixMarket matrix coordinate|array real|integer|double general|symmetric`.
/// Coordinate entries that are not given are zero; an entry given twice is an error.
/// For `symmetric`, give each off-diagonal entry once (either triangle).
pub fn read_matrix_market(path: &Path) -> Result<Mat<f64>, InputError> {
    parse_mtx(path, Source::File(path))
}

#[derive(Clone, Copy, PartialEq)]
enum Format {
    Coordinate,
    Array,
}

/// The banner's choices.
#[derive(Clone, Copy)]
struct Header {
    format: Format,
    integer: bool,
    symmetric: bool,
}

/// The next word of the data, skipping comment lines (a line whose first word starts with
/// `%`) and blank lines.
fn data_word<'s>(s: &'s mut Scanner<'_>) -> Scan<Option<Token<'s>>> {
    loop {
        match s.peek_first_on_line()? {
            None => return Ok(None),
            Some(true) if s.peek_byte() == Some(b'%') => s.skip_line()?,
            Some(_) => break,
        }
    }
    s.next_word()
}

/// A word's text and place, kept only for a message.
struct Kept {
    text: String,
    pos: Pos,
}

impl Kept {
    fn of(t: &Token<'_>) -> Self {
        Self {
            text: t.text.to_string(),
            pos: t.pos,
        }
    }
}

/// The banner line: `%%MatrixMarket matrix <format> <field> <symmetry>`.
fn banner(path: &Path, s: &mut Scanner<'_>) -> Result<Header, InputError> {
    let err =
        |pos: Option<Pos>, kind: InputErrorKind, msg: String| InputError::at(path, pos, kind, msg);
    let syntax = |pos: Pos, msg: String| err(Some(pos), InputErrorKind::Syntax, msg);
    if s.is_empty()? {
        return Err(err(
            None,
            InputErrorKind::Syntax,
            "the file is empty: expected a Matrix Market banner `%%MatrixMarket matrix coordinate real general`".into(),
        ));
    }
    let mut banner = Vec::new();
    while s.peek_line()? == Some(1) {
        if let Some(w) = s.next_word()? {
            if banner.len() <= 5 {
                banner.push(Kept::of(&w));
            } else {
                banner.push(Kept {
                    text: String::new(),
                    pos: w.pos,
                });
            }
        }
    }
    let first_pos = Pos { line: 1, col: 1 };
    if banner
        .first()
        .is_none_or(|w| !w.text.eq_ignore_ascii_case("%%MatrixMarket"))
    {
        return Err(syntax(
            first_pos,
            "not a Matrix Market file: the first line must be a banner like `%%MatrixMarket matrix coordinate real general`".into(),
        ));
    }
    if banner.len() != 5 {
        return Err(syntax(
            first_pos,
            format!(
                "the banner has {} words, expected 5: `%%MatrixMarket matrix <coordinate|array> <real|integer> <general|symmetric>`",
                banner.len()
            ),
        ));
    }
    let lower = |w: &Kept| w.text.to_ascii_lowercase();
    if lower(&banner[1]) != "matrix" {
        return Err(err(
            Some(banner[1].pos),
            InputErrorKind::Unsupported,
            format!(
                "object `{}` is not supported: only `matrix`",
                banner[1].text
            ),
        ));
    }
    let format = match lower(&banner[2]).as_str() {
        "coordinate" => Format::Coordinate,
        "array" => Format::Array,
        _ => {
            return Err(err(
                Some(banner[2].pos),
                InputErrorKind::Unsupported,
                format!(
                    "format `{}` is not supported: use `coordinate` or `array`",
                    banner[2].text
                ),
            ))
        }
    };
    let integer = match lower(&banner[3]).as_str() {
        "real" | "double" => false,
        "integer" => true,
        "complex" | "pattern" => {
            return Err(err(
                Some(banner[3].pos),
                InputErrorKind::Unsupported,
                format!(
                    "field `{}` is not supported: a stiffness matrix needs `real` (or `integer`) values",
                    banner[3].text
                ),
            ))
        }
        _ => {
            return Err(err(
                Some(banner[3].pos),
                InputErrorKind::Unsupported,
                format!(
                    "unknown field `{}`: use `real` or `integer`",
                    banner[3].text
                ),
            ))
        }
    };
    let symmetric = match lower(&banner[4]).as_str() {
        "general" => false,
        "symmetric" => true,
        _ => {
            return Err(err(
                Some(banner[4].pos),
                InputErrorKind::Unsupported,
                format!(
                    "symmetry `{}` is not supported: use `general` or `symmetric`",
                    banner[4].text
                ),
            ))
        }
    };

    Ok(Header {
        format,
        integer,
        symmetric,
    })
}

/// A number of the data: finite, and whole when the banner says `integer`.
fn value(path: &Path, w: &Token<'_>, integer: bool) -> Scan<f64> {
    let syntax = |msg: String| {
        Box::new(InputError::at(
            path,
            Some(w.pos),
            InputErrorKind::Syntax,
            msg,
        ))
    };
    let v: f64 = w
        .text
        .parse()
        .map_err(|_| syntax(format!("expected a number, found `{}`", w.text)))?;
    if !v.is_finite() {
        return Err(Box::new(InputError::at(
            path,
            Some(w.pos),
            InputErrorKind::Value,
            format!("`{}` is not a finite number", w.text),
        )));
    }
    if integer && v.fract() != 0.0 {
        return Err(Box::new(InputError::at(
            path,
            Some(w.pos),
            InputErrorKind::Value,
            format!(
                "the banner says `integer`, but `{}` is not a whole number (declare the file `real`)",
                w.text
            ),
        )));
    }
    Ok(v)
}

/// A 1-based index in `1..=n`, as a 0-based one.
fn index(path: &Path, w: &Token<'_>, n: usize, row: bool) -> Scan<usize> {
    let i = w
        .text
        .parse::<usize>()
        .ok()
        .filter(|&i| (1..=n).contains(&i));
    i.map(|i| i - 1).ok_or_else(|| {
        Box::new(InputError::at(
            path,
            Some(w.pos),
            InputErrorKind::Value,
            format!(
                "{} index `{}` is not a whole number in 1..={n}",
                if row { "row" } else { "column" },
                w.text
            ),
        ))
    })
}

/// Which entries are already given, one bit each (1/64 of the matrix).
struct Given {
    rows: usize,
    bits: Vec<u64>,
}

impl Given {
    fn new(rows: usize, cols: usize) -> Self {
        Self {
            rows,
            bits: vec![0; (rows * cols).div_ceil(64)],
        }
    }

    /// Marks `(i, j)`; returns whether it was marked before.
    fn mark(&mut self, i: usize, j: usize) -> bool {
        let k = j * self.rows + i;
        let (w, b) = (k / 64, 1u64 << (k % 64));
        let was = self.bits[w] & b != 0;
        self.bits[w] |= b;
        was
    }
}

/// Reads a dense matrix from `source` (errors name `path`).
pub(crate) fn parse_mtx(path: &Path, source: Source<'_>) -> Result<Mat<f64>, InputError> {
    let err =
        |pos: Option<Pos>, kind: InputErrorKind, msg: String| InputError::at(path, pos, kind, msg);
    let syntax = |pos: Pos, msg: String| err(Some(pos), InputErrorKind::Syntax, msg);
    let mut s = source.scanner(path)?;
    let Header {
        format,
        integer,
        symmetric,
    } = banner(path, &mut s)?;
    // The place of "the file ends here" messages: its last line.
    let end_pos = |s: &mut Scanner<'_>| -> Result<Option<Pos>, InputError> {
        let (lines, _) = s.finish()?;
        Ok(Some(Pos {
            line: lines.max(1),
            col: 1,
        }))
    };

    // The size line: its words, counted before any is parsed.
    let Some(first) = data_word(&mut s)? else {
        return Err(err(
            end_pos(&mut s)?,
            InputErrorKind::Syntax,
            format!(
                "the file ends before the size line (`rows columns{}`)",
                if format == Format::Coordinate {
                    " entries"
                } else {
                    ""
                }
            ),
        ));
    };
    let size_line = first.pos.line;
    let mut size_words = vec![Kept::of(&first)];
    while let Some(w) = s.next_on_line()? {
        size_words.push(if size_words.len() < 3 {
            Kept::of(&w)
        } else {
            Kept {
                text: String::new(),
                pos: w.pos,
            }
        });
    }
    let expected = if format == Format::Coordinate { 3 } else { 2 };
    let what = if format == Format::Coordinate {
        "`rows columns entries`"
    } else {
        "`rows columns`"
    };
    if size_words.len() != expected {
        return Err(syntax(
            Pos {
                line: size_line,
                col: 1,
            },
            format!(
                "the size line has {} values, expected {expected}: {what}",
                size_words.len()
            ),
        ));
    }
    let mut sizes = [0usize; 3];
    for (k, w) in size_words.iter().enumerate() {
        sizes[k] = w.text.parse::<usize>().map_err(|_| {
            syntax(
                w.pos,
                format!(
                    "expected a whole number ≥ 0 in the size line, found `{}`",
                    w.text
                ),
            )
        })?;
    }
    let (rows, cols, nnz) = (sizes[0], sizes[1], sizes[2]);
    let size_pos = size_words[0].pos;
    if symmetric && rows != cols {
        return Err(err(
            Some(size_pos),
            InputErrorKind::Size,
            format!("a symmetric matrix must be square, but the size line says {rows}×{cols}"),
        ));
    }
    let total = rows.checked_mul(cols).filter(|&t| t <= MAX_DENSE_ENTRIES);
    let Some(total) = total else {
        return Err(err(
            Some(size_pos),
            InputErrorKind::Size,
            format!(
                "the matrix is {rows}×{cols}: too large for a dense contact-zone matrix (at most {MAX_DENSE_ENTRIES} entries)"
            ),
        ));
    };

    let mut mat = Mat::<f64>::zeros(rows, cols);
    match format {
        Format::Coordinate => {
            if nnz > total {
                return Err(err(
                    Some(size_words[2].pos),
                    InputErrorKind::Size,
                    format!("{nnz} entries declared, but a {rows}×{cols} matrix has only {total}"),
                ));
            }
            let mut given = Given::new(rows, cols);
            let mut read = 0;
            while let Some(w) = data_word(&mut s)? {
                let line_no = w.pos.line;
                if read == nnz {
                    return Err(syntax(
                        Pos {
                            line: line_no,
                            col: 1,
                        },
                        format!("more entries than the {nnz} declared on line {size_line}"),
                    ));
                }
                // Each word is parsed as it comes; a word's error waits until the line's
                // words are counted (a wrong count is reported first).
                let first_pos = w.pos;
                let i = index(path, &w, rows, true);
                let mut j = None;
                let mut v = None;
                let mut count = 1;
                while let Some(w) = s.next_on_line()? {
                    count += 1;
                    match count {
                        2 => j = Some(index(path, &w, cols, false)),
                        3 => v = Some(value(path, &w, integer)),
                        _ => {}
                    }
                }
                let (Some(j), Some(v), 3) = (j, v, count) else {
                    return Err(syntax(
                        Pos {
                            line: line_no,
                            col: 1,
                        },
                        format!(
                            "an entry line needs 3 values `row column value`, this one has {count}"
                        ),
                    ));
                };
                let (i, j, v) = (i?, j?, v?);
                let mirror = symmetric && i != j;
                for (a, b) in [(i, j), (j, i)]
                    .into_iter()
                    .take(if mirror { 2 } else { 1 })
                {
                    if given.mark(a, b) {
                        let prev = entry_line(path, source, a, b, symmetric)?;
                        let also = if (a, b) != (i, j) {
                            format!(
                                " (a symmetric file gives ({}, {}) and ({}, {}) once for both)",
                                i + 1,
                                j + 1,
                                j + 1,
                                i + 1
                            )
                        } else {
                            String::new()
                        };
                        return Err(err(
                            Some(first_pos),
                            InputErrorKind::Invalid,
                            format!(
                                "entry ({}, {}) is given twice, here and on line {}{also}",
                                a + 1,
                                b + 1,
                                prev.map_or(0, |p| p.line)
                            ),
                        ));
                    }
                    mat[(a, b)] = v;
                }
                read += 1;
            }
            if read < nnz {
                return Err(err(
                    end_pos(&mut s)?,
                    InputErrorKind::Syntax,
                    format!(
                        "the file ends after {read} of the {nnz} entries declared on line {size_line}"
                    ),
                ));
            }
        }
        Format::Array => {
            let needed = if symmetric {
                rows * (rows + 1) / 2
            } else {
                total
            };
            // Column by column; for `symmetric` the lower triangle.
            let (mut i, mut j) = (0, 0);
            let mut read = 0;
            while let Some(w) = data_word(&mut s)? {
                if read == needed {
                    return Err(syntax(
                        w.pos,
                        format!(
                            "more values than the {needed} that a {rows}×{cols}{} array holds",
                            if symmetric { " symmetric" } else { "" }
                        ),
                    ));
                }
                let v = value(path, &w, integer)?;
                mat[(i, j)] = v;
                if symmetric {
                    mat[(j, i)] = v;
                }
                read += 1;
                i += 1;
                if i == rows {
                    j += 1;
                    i = if symmetric { j } else { 0 };
                }
            }
            if read < needed {
                return Err(err(
                    end_pos(&mut s)?,
                    InputErrorKind::Syntax,
                    format!(
                        "the file ends after {read} of the {needed} values of the {rows}×{cols}{} array (declared on line {size_line})",
                        if symmetric { " symmetric (lower triangle, column by column)" } else { " (column by column)" }
                    ),
                ));
            }
        }
    }
    Ok(mat)
}

/// Where entry `(i, j)` (0-based) is written in a coordinate file: the first entry line that
/// gives it (or, in a symmetric file, its mirror).
fn entry_line(
    path: &Path,
    source: Source<'_>,
    i: usize,
    j: usize,
    symmetric: bool,
) -> Result<Option<Pos>, InputError> {
    let mut s = source.scanner(path)?;
    banner(path, &mut s)?;
    // Skip the size line.
    if data_word(&mut s)?.is_none() {
        return Ok(None);
    }
    while s.next_on_line()?.is_some() {}
    let target =
        |r: usize, c: usize| (r, c) == (i + 1, j + 1) || symmetric && (c, r) == (i + 1, j + 1);
    while let Some(w) = data_word(&mut s)? {
        let pos = w.pos;
        let r = w.text.parse::<usize>().ok();
        let c = s.next_on_line()?.and_then(|w| w.text.parse::<usize>().ok());
        while s.next_on_line()?.is_some() {}
        if let (Some(r), Some(c)) = (r, c) {
            if target(r, c) {
                return Ok(Some(pos));
            }
        }
    }
    Ok(None)
}

/// Where entry `(i, j)` (0-based) of the matrix in the Matrix Market file `path` is written,
/// found by reading the file again (for an error about the matrix as a whole). `None` when
/// the entry is not written (a zero of a coordinate file) or the file cannot be read again.
pub(crate) fn entry_place(path: &Path, i: usize, j: usize) -> Option<Pos> {
    let source = Source::File(path);
    let mut s = source.scanner(path).ok()?;
    let header = banner(path, &mut s).ok()?;
    match header.format {
        Format::Coordinate => entry_line(path, source, i, j, header.symmetric).ok()?,
        Format::Array => {
            let first = data_word(&mut s).ok()??;
            let rows: usize = first.text.parse().ok()?;
            while s.next_on_line().ok()?.is_some() {}
            let (i, j) = if header.symmetric && i < j {
                (j, i)
            } else {
                (i, j)
            };
            let k = if header.symmetric {
                // Columns before j hold rows - c values each (lower triangle).
                (0..j).map(|c| rows - c).sum::<usize>() + (i - j)
            } else {
                j * rows + i
            };
            for _ in 0..k {
                data_word(&mut s).ok()??;
            }
            data_word(&mut s).ok()?.map(|w| w.pos)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<Mat<f64>, InputError> {
        parse_mtx(Path::new("m.mtx"), Source::Text(s))
    }

    #[test]
    fn coordinate_symmetric() {
        let m = p("%%MatrixMarket matrix coordinate real symmetric\n% c\n3 3 4\n1 1 2\n2 1 -1\n3 3 5e-1\n3 2 7\n").unwrap();
        assert_eq!(m[(0, 1)], -1.0);
        assert_eq!(m[(1, 0)], -1.0);
        assert_eq!(m[(2, 2)], 0.5);
        assert_eq!(m[(1, 2)], 7.0);
        assert_eq!(m[(0, 2)], 0.0);
    }

    /// Reference: the places written in the texts below, counted by hand.
    #[test]
    fn entry_places_found_by_reading_again() {
        let dir = tempfile::tempdir().unwrap();
        let coordinate = dir.path().join("c.mtx");
        std::fs::write(
            &coordinate,
            "%%MatrixMarket matrix coordinate real symmetric\n% c\n3 3 3\n1 1 2\n  3 1 -1\n\n2 2 4\n",
        )
        .unwrap();
        assert_eq!(
            entry_place(&coordinate, 2, 0),
            Some(Pos { line: 5, col: 3 })
        );
        // The mirror of a symmetric entry is found at the written one.
        assert_eq!(
            entry_place(&coordinate, 0, 2),
            Some(Pos { line: 5, col: 3 })
        );
        assert_eq!(
            entry_place(&coordinate, 1, 1),
            Some(Pos { line: 7, col: 1 })
        );
        // A zero that is not written has no place.
        assert_eq!(entry_place(&coordinate, 1, 0), None);
        let array = dir.path().join("a.mtx");
        std::fs::write(
            &array,
            "%%MatrixMarket matrix array real symmetric\n3 3\n1 2 3\n% c\n4 5\n 6\n",
        )
        .unwrap();
        // Lower triangle column by column: (1,1) (2,1) (3,1) (2,2) (3,2) (3,3).
        assert_eq!(entry_place(&array, 2, 1), Some(Pos { line: 5, col: 3 }));
        assert_eq!(entry_place(&array, 1, 2), Some(Pos { line: 5, col: 3 }));
        assert_eq!(entry_place(&array, 2, 2), Some(Pos { line: 6, col: 2 }));
        let general = dir.path().join("g.mtx");
        std::fs::write(
            &general,
            "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n",
        )
        .unwrap();
        assert_eq!(entry_place(&general, 0, 1), Some(Pos { line: 5, col: 1 }));
    }

    /// Reference: the line of the first entry line, by hand.
    #[test]
    fn a_repeated_entry_names_the_earlier_line() {
        let e = p("%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n\n1 2 1\n2 1 2\n")
            .unwrap_err();
        assert!(e.message.contains("here and on line 4"), "{e}");
        assert_eq!(e.location.line, Some(5));
    }

    #[test]
    fn array_general_is_column_major() {
        let m = p("%%MatrixMarket matrix array integer general\n2 3\n1\n2\n3\n4\n5\n6\n").unwrap();
        assert_eq!(m.nrows(), 2);
        assert_eq!(m[(1, 0)], 2.0);
        assert_eq!(m[(0, 1)], 3.0);
        assert_eq!(m[(1, 2)], 6.0);
    }

    #[test]
    fn array_symmetric() {
        let m = p("%%MatrixMarket matrix array real symmetric\n2 2\n1\n2\n3\n").unwrap();
        assert_eq!(m[(0, 1)], 2.0);
        assert_eq!(m[(1, 0)], 2.0);
        assert_eq!(m[(1, 1)], 3.0);
    }

    #[test]
    fn errors() {
        for (text, frag, line) in [
            ("", "empty", None),
            ("hello\n", "not a Matrix Market", Some(1)),
            (
                "%%MatrixMarket matrix coordinate complex general\n",
                "complex",
                Some(1),
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 1\n",
                "row index `3`",
                Some(3),
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n",
                "ends after 1 of the 2",
                Some(3),
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1\n2 2 2\n",
                "more entries",
                Some(4),
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n1 1 2\n",
                "twice",
                Some(4),
            ),
            (
                "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 2 1\n2 1 2\n",
                "twice",
                Some(4),
            ),
            (
                "%%MatrixMarket matrix array real general\n2 2\n1\n2\nnan\n4\n",
                "not a finite",
                Some(5),
            ),
            (
                "%%MatrixMarket matrix array integer general\n1 1\n1.5\n",
                "whole number",
                Some(3),
            ),
            (
                "%%MatrixMarket matrix array real general\n1000000000 1000000000\n",
                "too large",
                Some(2),
            ),
            (
                "%%MatrixMarket matrix array real symmetric\n2 3\n",
                "square",
                Some(2),
            ),
            (
                "%%MatrixMarket matrix coordinate real general\n2 2\n",
                "size line has 2",
                Some(2),
            ),
        ] {
            let Err(e) = p(text) else {
                panic!("{text}: no error")
            };
            assert!(e.message.contains(frag), "{text}: {e}");
            assert_eq!(e.location.line, line, "{text}: {e}");
        }
    }
}
