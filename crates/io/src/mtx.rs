//! A Matrix Market reader (`matrix coordinate|array real|integer general|symmetric`),
//! into a dense matrix, with errors that name the line.

use std::collections::HashMap;
use std::path::Path;

use faer::Mat;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::text::{read_text, words, Word};

/// Largest dense matrix built from a Matrix Market file (rows × columns).
pub(crate) const MAX_DENSE_ENTRIES: usize = 1 << 26;

/// A matrix read from a Matrix Market file, with the place of each entry written in the file.
pub(crate) struct MtxMatrix {
    pub mat: Mat<f64>,
    /// 0-based (row, column) → where the entry is written. Mirrored entries of a symmetric
    /// file point at the written one.
    pub entry_pos: HashMap<(usize, usize), Pos>,
}

/// Reads a dense matrix from a Matrix Market file.
///
/// Supported: `%%MatrixMarket matrix coordinate|array real|integer|double general|symmetric`.
/// Coordinate entries that are not given are zero; an entry given twice is an error.
/// For `symmetric`, give each off-diagonal entry once (either triangle).
pub fn read_matrix_market(path: &Path) -> Result<Mat<f64>, InputError> {
    read_mtx(path).map(|m| m.mat)
}

pub(crate) fn read_mtx(path: &Path) -> Result<MtxMatrix, InputError> {
    let text = read_text(path)?;
    parse_mtx(path, &text)
}

#[derive(Clone, Copy, PartialEq)]
enum Format {
    Coordinate,
    Array,
}

pub(crate) fn parse_mtx(path: &Path, text: &str) -> Result<MtxMatrix, InputError> {
    let err =
        |pos: Option<Pos>, kind: InputErrorKind, msg: String| InputError::at(path, pos, kind, msg);
    let syntax = |pos: Pos, msg: String| err(Some(pos), InputErrorKind::Syntax, msg);
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));

    // Banner.
    let Some((_, first)) = lines.next() else {
        return Err(err(
            None,
            InputErrorKind::Syntax,
            "the file is empty: expected a Matrix Market banner `%%MatrixMarket matrix coordinate real general`".into(),
        ));
    };
    let banner = words(first, 1);
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
    let lower = |w: &Word| w.text.to_ascii_lowercase();
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

    // The data lines: skip comments and blank lines.
    let last_line = text.lines().count().max(1);
    let end_pos = Some(Pos {
        line: last_line,
        col: 1,
    });
    let mut data = lines.filter(|(_, l)| {
        let t = l.trim_start();
        !t.is_empty() && !t.starts_with('%')
    });

    let Some((size_line, size_text)) = data.next() else {
        return Err(err(
            end_pos,
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
    let size_words = words(size_text, size_line);
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

    let parse_value = |w: &Word| -> Result<f64, InputError> {
        let v: f64 = w
            .text
            .parse()
            .map_err(|_| syntax(w.pos, format!("expected a number, found `{}`", w.text)))?;
        if !v.is_finite() {
            return Err(err(
                Some(w.pos),
                InputErrorKind::Value,
                format!("`{}` is not a finite number", w.text),
            ));
        }
        if integer && v.fract() != 0.0 {
            return Err(err(
                Some(w.pos),
                InputErrorKind::Value,
                format!(
                    "the banner says `integer`, but `{}` is not a whole number (declare the file `real`)",
                    w.text
                ),
            ));
        }
        Ok(v)
    };

    let mut mat = Mat::<f64>::zeros(rows, cols);
    let mut entry_pos = HashMap::new();
    match format {
        Format::Coordinate => {
            if nnz > total {
                return Err(err(
                    Some(size_words[2].pos),
                    InputErrorKind::Size,
                    format!("{nnz} entries declared, but a {rows}×{cols} matrix has only {total}"),
                ));
            }
            let mut read = 0;
            for (line_no, line) in data.by_ref() {
                if read == nnz {
                    return Err(syntax(
                        Pos {
                            line: line_no,
                            col: 1,
                        },
                        format!("more entries than the {nnz} declared on line {size_line}"),
                    ));
                }
                let ws = words(line, line_no);
                if ws.len() != 3 {
                    return Err(syntax(
                        Pos {
                            line: line_no,
                            col: 1,
                        },
                        format!(
                            "an entry line needs 3 values `row column value`, this one has {}",
                            ws.len()
                        ),
                    ));
                }
                let mut idx = [0usize; 2];
                for (k, (w, n)) in ws.iter().zip([rows, cols]).enumerate() {
                    let i = w
                        .text
                        .parse::<usize>()
                        .ok()
                        .filter(|&i| (1..=n).contains(&i));
                    idx[k] = i.ok_or_else(|| {
                        err(
                            Some(w.pos),
                            InputErrorKind::Value,
                            format!(
                                "{} index `{}` is not a whole number in 1..={n}",
                                if k == 0 { "row" } else { "column" },
                                w.text
                            ),
                        )
                    })? - 1;
                }
                let v = parse_value(&ws[2])?;
                let (i, j) = (idx[0], idx[1]);
                let mut targets = vec![(i, j)];
                if symmetric && i != j {
                    targets.push((j, i));
                }
                for &(a, b) in &targets {
                    if let Some(prev) = entry_pos.get(&(a, b)) {
                        let prev: &Pos = prev;
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
                            Some(ws[0].pos),
                            InputErrorKind::Invalid,
                            format!(
                                "entry ({}, {}) is given twice, here and on line {}{also}",
                                a + 1,
                                b + 1,
                                prev.line
                            ),
                        ));
                    }
                    entry_pos.insert((a, b), ws[0].pos);
                    mat[(a, b)] = v;
                }
                read += 1;
            }
            if read < nnz {
                return Err(err(
                    end_pos,
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
            let mut values = Vec::new();
            for (line_no, line) in data {
                for w in words(line, line_no) {
                    if values.len() == needed {
                        return Err(syntax(
                            w.pos,
                            format!(
                                "more values than the {needed} that a {rows}×{cols}{} array holds",
                                if symmetric { " symmetric" } else { "" }
                            ),
                        ));
                    }
                    values.push((parse_value(&w)?, w.pos));
                }
            }
            if values.len() < needed {
                return Err(err(
                    end_pos,
                    InputErrorKind::Syntax,
                    format!(
                        "the file ends after {} of the {needed} values of the {rows}×{cols}{} array (declared on line {size_line})",
                        values.len(),
                        if symmetric { " symmetric (lower triangle, column by column)" } else { " (column by column)" }
                    ),
                ));
            }
            let mut it = values.into_iter();
            for j in 0..cols {
                let first_row = if symmetric { j } else { 0 };
                for i in first_row..rows {
                    if let Some((v, pos)) = it.next() {
                        mat[(i, j)] = v;
                        entry_pos.insert((i, j), pos);
                        if symmetric {
                            mat[(j, i)] = v;
                            entry_pos.insert((j, i), pos);
                        }
                    }
                }
            }
        }
    }
    Ok(MtxMatrix { mat, entry_pos })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<MtxMatrix, InputError> {
        parse_mtx(Path::new("m.mtx"), s)
    }

    #[test]
    fn coordinate_symmetric() {
        let m = p("%%MatrixMarket matrix coordinate real symmetric\n% c\n3 3 4\n1 1 2\n2 1 -1\n3 3 5e-1\n3 2 7\n").unwrap();
        assert_eq!(m.mat[(0, 1)], -1.0);
        assert_eq!(m.mat[(1, 0)], -1.0);
        assert_eq!(m.mat[(2, 2)], 0.5);
        assert_eq!(m.mat[(1, 2)], 7.0);
        assert_eq!(m.mat[(0, 2)], 0.0);
        assert_eq!(m.entry_pos[&(1, 2)].line, 7);
    }

    #[test]
    fn array_general_is_column_major() {
        let m = p("%%MatrixMarket matrix array integer general\n2 3\n1\n2\n3\n4\n5\n6\n").unwrap();
        assert_eq!(m.mat.nrows(), 2);
        assert_eq!(m.mat[(1, 0)], 2.0);
        assert_eq!(m.mat[(0, 1)], 3.0);
        assert_eq!(m.mat[(1, 2)], 6.0);
    }

    #[test]
    fn array_symmetric() {
        let m = p("%%MatrixMarket matrix array real symmetric\n2 2\n1\n2\n3\n").unwrap();
        assert_eq!(m.mat[(0, 1)], 2.0);
        assert_eq!(m.mat[(1, 0)], 2.0);
        assert_eq!(m.mat[(1, 1)], 3.0);
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
