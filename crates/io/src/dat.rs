//! Siconos numerics `.dat` files: dense LCPs and 2D frictional-contact problems.

use std::path::Path;

use faer::Mat;
use unilateral_lcp::Lcp;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::text::{read_text, words as line_words, Word};

/// A 2D frictional contact problem in Siconos' "local" form: find contact forces `r` and
/// relative velocities `u = W r + q` satisfying Coulomb's law per contact with friction `mu`.
/// Each contact `i` owns rows `2i` (normal) and `2i + 1` (tangential) of `W` and `q`.
#[derive(Debug, Clone)]
pub struct Fc2dProblem {
    /// The Delassus matrix `W` (`2·nc × 2·nc`).
    pub w: Mat<f64>,
    /// The free velocity `q` (length `2·nc`).
    pub q: Vec<f64>,
    /// Friction coefficient per contact (length `nc`), each `≥ 0`.
    pub mu: Vec<f64>,
}

impl Fc2dProblem {
    /// Number of contacts `nc`.
    pub fn contacts(&self) -> usize {
        self.mu.len()
    }
}

/// Every word of the file, line by line.
fn words(text: &str) -> Vec<Word<'_>> {
    text.lines()
        .enumerate()
        .flat_map(|(l, line)| line_words(line, l + 1))
        .collect()
}

/// A cursor over the words of a `.dat` file.
struct Cursor<'a> {
    path: &'a Path,
    words: Vec<Word<'a>>,
    at: usize,
    /// Where the last word was, for "the file ends here" messages.
    last: Option<Pos>,
}

impl<'a> Cursor<'a> {
    fn new(path: &'a Path, text: &'a str) -> Self {
        let words = words(text);
        let last = words.last().map(|w| w.pos);
        Self {
            path,
            words,
            at: 0,
            last,
        }
    }

    fn remaining(&self) -> usize {
        self.words.len() - self.at
    }

    fn end_err(&self, what: &str) -> InputError {
        let msg = if self.words.is_empty() {
            format!("the file is empty: expected {what}")
        } else {
            format!("the file ends before {what} (truncated file?)")
        };
        InputError::at(self.path, self.last, InputErrorKind::Syntax, msg)
    }

    /// A whole number of the header.
    fn header(&mut self, what: &str) -> Result<(usize, Pos), InputError> {
        let Some(w) = self.words.get(self.at) else {
            return Err(self.end_err(what));
        };
        let v = w.text.parse::<usize>().map_err(|_| {
            let big = w.text.bytes().all(|b| b.is_ascii_digit());
            InputError::at(
                self.path,
                Some(w.pos),
                InputErrorKind::Syntax,
                if big {
                    format!("{what}: `{}` is too large", w.text)
                } else {
                    format!("expected {what} (a whole number ≥ 0), found `{}`", w.text)
                },
            )
        })?;
        self.at += 1;
        Ok((v, w.pos))
    }

    /// A finite number of the data; `key` names it in errors (e.g. `M[2][3]`).
    fn number(&mut self, key: impl Fn() -> String, what: &str) -> Result<f64, InputError> {
        let Some(w) = self.words.get(self.at) else {
            return Err(self.end_err(what).with_key(key()));
        };
        let v: f64 = w.text.parse().map_err(|_| {
            InputError::at(
                self.path,
                Some(w.pos),
                InputErrorKind::Syntax,
                format!("expected a number, found `{}`", w.text),
            )
            .with_key(key())
        })?;
        if !v.is_finite() {
            return Err(InputError::at(
                self.path,
                Some(w.pos),
                InputErrorKind::Value,
                format!("`{}` is not a finite number", w.text),
            )
            .with_key(key()));
        }
        self.at += 1;
        Ok(v)
    }

    /// Checks the header value `got` against `want`.
    fn expect_eq(
        &self,
        got: usize,
        pos: Pos,
        want: usize,
        what: &str,
        why: &str,
    ) -> Result<(), InputError> {
        if got != want {
            return Err(InputError::at(
                self.path,
                Some(pos),
                InputErrorKind::Size,
                format!("{what} is {got}, but {why} is {want}"),
            ));
        }
        Ok(())
    }

    /// The dense matrix block: storage type, rows, columns, "rows columns" again, then the
    /// entries column by column. `n` is the expected size; `extra` the values that must follow.
    fn dense_block(
        &mut self,
        n: usize,
        n_pos: Pos,
        extra: usize,
        name: &str,
    ) -> Result<Mat<f64>, InputError> {
        let (storage, s_pos) = self.header("the storage type (0 for dense)")?;
        if storage != 0 {
            return Err(InputError::at(
                self.path,
                Some(s_pos),
                InputErrorKind::Unsupported,
                format!(
                    "storage type {storage} is not supported: only 0 (dense, column-major) is read"
                ),
            ));
        }
        for what in [
            "the number of rows",
            "the number of columns",
            "the number of rows (repeated)",
            "the number of columns (repeated)",
        ] {
            let (v, p) = self.header(&format!("{what} of {name}"))?;
            self.expect_eq(v, p, n, &format!("{what} of {name}"), "the problem size")?;
        }
        // Guard against absurd headers before allocating.
        let needed = n.checked_mul(n).and_then(|nn| nn.checked_add(extra));
        match needed {
            Some(k) if k <= self.remaining() => {}
            _ => {
                return Err(InputError::at(
                    self.path,
                    Some(n_pos),
                    InputErrorKind::Size,
                    format!(
                        "the header says n = {n}, so {name} and the vectors need {} numbers, but the file holds only {} more values (wrong header or truncated file?)",
                        needed.map_or_else(|| "more than 2^64".to_string(), |k| k.to_string()),
                        self.remaining()
                    ),
                ));
            }
        }
        let mut m = Mat::<f64>::zeros(n, n);
        for j in 0..n {
            for i in 0..n {
                m[(i, j)] = self.number(
                    || format!("{name}[{}][{}]", i + 1, j + 1),
                    &format!("entry ({}, {}) of {name}", i + 1, j + 1),
                )?;
            }
        }
        Ok(m)
    }

    fn vector(&mut self, n: usize, name: &str) -> Result<Vec<f64>, InputError> {
        (0..n)
            .map(|i| {
                self.number(
                    || format!("{name}[{}]", i + 1),
                    &format!("entry {} of {name} (it has {n} entries)", i + 1),
                )
            })
            .collect()
    }
}

/// Reads a dense LCP in Siconos `.dat` format: `n`, storage type `0`, `n`, `n`, `n n`, the
/// `n²` entries of `M` column by column, then `q`. Anything after `q` is a comment.
pub fn read_siconos_lcp(path: &Path) -> Result<Lcp, InputError> {
    let text = read_text(path)?;
    parse_lcp_dat(path, &text)
}

pub(crate) fn parse_lcp_dat(path: &Path, text: &str) -> Result<Lcp, InputError> {
    let mut c = Cursor::new(path, text);
    let (n, n_pos) = c.header("the problem size n")?;
    if n == 0 {
        return Err(InputError::at(
            path,
            Some(n_pos),
            InputErrorKind::Size,
            "the problem size n is 0: there is nothing to solve",
        ));
    }
    let m = c.dense_block(n, n_pos, n, "M")?;
    let q = c.vector(n, "q")?;
    Ok(Lcp { m, q })
}

/// Reads a 2D frictional contact problem in Siconos `.dat` "local" format: dimension `2`,
/// number of contacts `nc`, storage type `0`, `n`, `n`, `n n` (with `n = 2·nc`), the `n²`
/// entries of `W` column by column, then `q` (`n` values) and `mu` (`nc` values).
pub fn read_fc2d(path: &Path) -> Result<Fc2dProblem, InputError> {
    let text = read_text(path)?;
    parse_fc2d(path, &text)
}

pub(crate) fn parse_fc2d(path: &Path, text: &str) -> Result<Fc2dProblem, InputError> {
    let mut c = Cursor::new(path, text);
    let (dim, d_pos) = c.header("the dimension (2)")?;
    if dim != 2 {
        return Err(InputError::at(
            path,
            Some(d_pos),
            InputErrorKind::Unsupported,
            format!("dimension {dim} is not supported: only 2D frictional contact (dimension 2)"),
        ));
    }
    let (nc, nc_pos) = c.header("the number of contacts")?;
    if nc == 0 {
        return Err(InputError::at(
            path,
            Some(nc_pos),
            InputErrorKind::Size,
            "the number of contacts is 0: there is nothing to solve",
        ));
    }
    let Some(n) = nc.checked_mul(2) else {
        return Err(InputError::at(
            path,
            Some(nc_pos),
            InputErrorKind::Size,
            format!("the number of contacts {nc} is too large"),
        ));
    };
    let w = c.dense_block(n, nc_pos, n + nc, "W")?;
    let q = c.vector(n, "q")?;
    let mu = c.vector(nc, "mu")?;
    if let Some(i) = mu.iter().position(|&f| f < 0.0) {
        // Find where mu[i] was written: the last nc words read.
        let pos = c.words.get(c.at - nc + i).map(|w| w.pos);
        return Err(InputError::at(
            path,
            pos,
            InputErrorKind::Value,
            format!("friction must be ≥ 0, but contact {} has {}", i + 1, mu[i]),
        )
        .with_key(format!("mu[{}]", i + 1)));
    }
    Ok(Fc2dProblem { w, q, mu })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcp(s: &str) -> Result<Lcp, InputError> {
        parse_lcp_dat(Path::new("x.dat"), s)
    }

    #[test]
    fn column_major() {
        let l = lcp("2\n0\n2\n2\n2 2\n1 2\n3 4\n5 6\n# comment\n").unwrap();
        assert_eq!(l.m[(0, 0)], 1.0);
        assert_eq!(l.m[(1, 0)], 2.0);
        assert_eq!(l.m[(0, 1)], 3.0);
        assert_eq!(l.q, vec![5.0, 6.0]);
    }

    #[test]
    fn errors() {
        for (text, frag, line) in [
            ("", "empty", None),
            ("x", "expected the problem size", Some(1)),
            (
                "1000000000\n0\n1000000000\n1000000000\n1000000000 1000000000\n1 2 3\n",
                "only 3 more values",
                Some(1),
            ),
            ("99999999999999999999999\n", "too large", Some(1)),
            ("2\n1\n", "storage type 1", Some(2)),
            ("2\n0\n3\n", "number of rows of M is 3", Some(3)),
            ("2\n0\n2\n2\n2 2\n1 2\n3 x\n5 6\n", "found `x`", Some(7)),
            (
                "2\n0\n2\n2\n2 2\n1 2\n3 inf\n5 6\n",
                "not a finite",
                Some(7),
            ),
            ("2\n0\n2\n2\n2 2\n1 2\n3 4\n5 six\n", "found `six`", Some(8)),
            ("0\n", "is 0", Some(1)),
        ] {
            let Err(e) = lcp(text) else {
                panic!("{text}: no error")
            };
            assert!(e.to_string().contains(frag), "{text}: {e}");
            assert_eq!(e.location.line, line, "{text}: {e}");
        }
    }

    #[test]
    fn fc2d_small() {
        let p = parse_fc2d(
            Path::new("f.dat"),
            "2\n1\n0\n2\n2\n2 2\n1 2\n3 4\n-1 0\n0.3\n",
        )
        .unwrap();
        assert_eq!(p.w[(1, 0)], 2.0);
        assert_eq!(p.q, vec![-1.0, 0.0]);
        assert_eq!(p.mu, vec![0.3]);
        let e = parse_fc2d(Path::new("f.dat"), "3\n1\n").unwrap_err();
        assert!(e.message.contains("dimension 3"));
        let e = parse_fc2d(
            Path::new("f.dat"),
            "2\n1\n0\n2\n2\n2 2\n1 2\n3 4\n-1 0\n-0.3\n",
        )
        .unwrap_err();
        assert_eq!(e.key.as_deref(), Some("mu[1]"));
        assert_eq!(e.location.line, Some(10));
    }
}
