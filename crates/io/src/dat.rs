//! Siconos numerics `.dat` files: dense LCPs and 2D frictional-contact problems.

use std::path::Path;

use faer::Mat;
use unilateral_lcp::Lcp;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::scan::{Scanner, Source};

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

/// A bound on the values still to be read, set when a header has fixed how many must follow:
/// if the file ends early, the error says so at the header, with the count it holds.
struct Needed {
    /// Where the size was written.
    at: Pos,
    /// Values the header asks for.
    count: usize,
    /// What they are (`M and the vectors`).
    name: String,
    /// Values read since.
    read: usize,
}

/// A cursor over the words of a `.dat` file, read as a stream (the file is never held whole).
struct Cursor<'a> {
    path: &'a Path,
    words: Scanner<'a>,
    needed: Option<Needed>,
    /// The problem size of the matrix block (for the messages of the size guard).
    n: usize,
}

impl<'a> Cursor<'a> {
    fn new(path: &'a Path, source: Source<'a>) -> Result<Self, InputError> {
        Ok(Self {
            path,
            words: source.scanner(path)?,
            needed: None,
            n: 0,
        })
    }

    fn end_err(&self, what: &str) -> InputError {
        let msg = if self.words.last().is_none() {
            format!("the file is empty: expected {what}")
        } else {
            format!("the file ends before {what} (truncated file?)")
        };
        InputError::at(self.path, self.words.last(), InputErrorKind::Syntax, msg)
    }

    /// The error of a header that asks for more values than the file holds (`remaining`).
    fn short_err(
        &self,
        at: Pos,
        needed: Option<usize>,
        name: &str,
        remaining: usize,
    ) -> InputError {
        InputError::at(
            self.path,
            Some(at),
            InputErrorKind::Size,
            format!(
                "the header says n = {}, so {name} and the vectors need {} numbers, but the file holds only {remaining} more values (wrong header or truncated file?)",
                self.n,
                needed.map_or_else(|| "more than 2^64".to_string(), |k| k.to_string()),
            ),
        )
    }

    /// A whole number of the header.
    fn header(&mut self, what: &str) -> Result<(usize, Pos), InputError> {
        let path = self.path;
        let Some(w) = self.words.next_word()? else {
            return Err(self.end_err(what));
        };
        let pos = w.pos;
        let v = w.text.parse::<usize>().map_err(|_| {
            let big = w.text.bytes().all(|b| b.is_ascii_digit());
            InputError::at(
                path,
                Some(pos),
                InputErrorKind::Syntax,
                if big {
                    format!("{what}: `{}` is too large", w.text)
                } else {
                    format!("expected {what} (a whole number ≥ 0), found `{}`", w.text)
                },
            )
        })?;
        Ok((v, pos))
    }

    /// A finite number of the data and its place; `key` names it in errors (e.g. `M[2][3]`).
    #[inline]
    fn number(
        &mut self,
        key: impl Fn() -> String,
        what: impl Fn() -> String,
    ) -> Result<(f64, Pos), InputError> {
        let path = self.path;
        let Some(w) = self.words.next_word()? else {
            return Err(self.no_number(&key, &what));
        };
        let pos = w.pos;
        match w.text.parse::<f64>() {
            Ok(v) if v.is_finite() => {
                if let Some(n) = &mut self.needed {
                    n.read += 1;
                }
                Ok((v, pos))
            }
            parsed => Err(bad_number(path, w.text, pos, parsed.is_ok(), &key)),
        }
    }

    /// The error of a file that ends where a number was expected.
    #[cold]
    #[inline(never)]
    fn no_number(&self, key: &dyn Fn() -> String, what: &dyn Fn() -> String) -> InputError {
        if let Some(n) = &self.needed {
            return self.short_err(n.at, Some(n.count), &n.name, n.read);
        }
        self.end_err(&what()).with_key(key())
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
        // Guard against absurd headers before allocating: every value takes at least two
        // bytes (a digit and a separator) but the last, so the rest of the file bounds their
        // number; beyond that bound the file is counted to say how many it holds.
        self.n = n;
        let needed = n.checked_mul(n).and_then(|nn| nn.checked_add(extra));
        let most = self.words.remaining_bytes().div_ceil(2);
        match needed {
            Some(k) if k as u64 <= most => {}
            _ => {
                let (_, remaining) = self.words.finish()?;
                if needed.is_none_or(|k| k > remaining) {
                    return Err(self.short_err(n_pos, needed, name, remaining));
                }
            }
        }
        self.needed = needed.map(|count| Needed {
            at: n_pos,
            count,
            name: name.to_string(),
            read: 0,
        });
        let mut m = Mat::<f64>::zeros(n, n);
        for j in 0..n {
            for i in 0..n {
                m[(i, j)] = self
                    .number(
                        || format!("{name}[{}][{}]", i + 1, j + 1),
                        || format!("entry ({}, {}) of {name}", i + 1, j + 1),
                    )?
                    .0;
            }
        }
        Ok(m)
    }

    /// `n` values and where each is written.
    fn vector(&mut self, n: usize, name: &str) -> Result<(Vec<f64>, Vec<Pos>), InputError> {
        let mut values = Vec::with_capacity(n);
        let mut places = Vec::with_capacity(n);
        for i in 0..n {
            let (v, p) = self.number(
                || format!("{name}[{}]", i + 1),
                || format!("entry {} of {name} (it has {n} entries)", i + 1),
            )?;
            values.push(v);
            places.push(p);
        }
        Ok((values, places))
    }
}

/// Reads a dense LCP in Siconos `.dat` format: `n`, storage type `0`, `n`, `n`, `n n`, the
/// `n²` entries of `M` column by column, then `q`. Anything after `q` is a comment.
pub fn read_siconos_lcp(path: &Path) -> Result<Lcp, InputError> {
    parse_lcp_dat(path, Source::File(path))
}

pub(crate) fn parse_lcp_dat(path: &Path, source: Source<'_>) -> Result<Lcp, InputError> {
    let mut c = Cursor::new(path, source)?;
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
    let (q, _) = c.vector(n, "q")?;
    Ok(Lcp { m, q })
}

/// Reads a 2D frictional contact problem in Siconos `.dat` "local" format: dimension `2`,
/// number of contacts `nc`, storage type `0`, `n`, `n`, `n n` (with `n = 2·nc`), the `n²`
/// entries of `W` column by column, then `q` (`n` values) and `mu` (`nc` values).
pub fn read_fc2d(path: &Path) -> Result<Fc2dProblem, InputError> {
    parse_fc2d(path, Source::File(path))
}

pub(crate) fn parse_fc2d(path: &Path, source: Source<'_>) -> Result<Fc2dProblem, InputError> {
    let mut c = Cursor::new(path, source)?;
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
    let (q, _) = c.vector(n, "q")?;
    let (mu, places) = c.vector(nc, "mu")?;
    if let Some(i) = mu.iter().position(|&f| f < 0.0) {
        return Err(InputError::at(
            path,
            Some(places[i]),
            InputErrorKind::Value,
            format!("friction must be ≥ 0, but contact {} has {}", i + 1, mu[i]),
        )
        .with_key(format!("mu[{}]", i + 1)));
    }
    Ok(Fc2dProblem { w, q, mu })
}

/// The error of a word that is not a finite number (`parsed`: it is a number, but not finite).
#[cold]
#[inline(never)]
fn bad_number(
    path: &Path,
    text: &str,
    pos: Pos,
    parsed: bool,
    key: &dyn Fn() -> String,
) -> InputError {
    if parsed {
        InputError::at(
            path,
            Some(pos),
            InputErrorKind::Value,
            format!("`{text}` is not a finite number"),
        )
    } else {
        InputError::at(
            path,
            Some(pos),
            InputErrorKind::Syntax,
            format!("expected a number, found `{text}`"),
        )
    }
    .with_key(key())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lcp(s: &str) -> Result<Lcp, InputError> {
        parse_lcp_dat(Path::new("x.dat"), Source::Text(s))
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
            Source::Text("2\n1\n0\n2\n2\n2 2\n1 2\n3 4\n-1 0\n0.3\n"),
        )
        .unwrap();
        assert_eq!(p.w[(1, 0)], 2.0);
        assert_eq!(p.q, vec![-1.0, 0.0]);
        assert_eq!(p.mu, vec![0.3]);
        let e = parse_fc2d(Path::new("f.dat"), Source::Text("3\n1\n")).unwrap_err();
        assert!(e.message.contains("dimension 3"));
        let e = parse_fc2d(
            Path::new("f.dat"),
            Source::Text("2\n1\n0\n2\n2\n2 2\n1 2\n3 4\n-1 0\n-0.3\n"),
        )
        .unwrap_err();
        assert_eq!(e.key.as_deref(), Some("mu[1]"));
        assert_eq!(e.location.line, Some(10));
    }
}
