//! The columns of the pivoting tableau `[E | −M | −g]` over a column-major copy of `M`.
//!
//! Tableau equation: `x − M z − g·t = h`, i.e. `x = h + g·t + M z`, where `t` is the driving
//! variable (the load parameter `p`, Lemke's artificial `z0`, or the tightening being removed).
//! Column indices: `0..n` are `x_i`, `n..2n` are `z_i`, `2n` is the driver.
//!
//! `h` and `g` are kept on their own scales: with `σ_h = 2^eh` and `σ_g = 2^eg` powers of two near
//! their largest entries, the columns hold `h/σ_h` and `g/σ_g`, the unknowns are `x/σ_h`, `z/σ_h`
//! and the driver `t·σ_g/σ_h`. Then `h`, `g` and the (equilibrated) `M` all have entries of
//! order one, and every relative tolerance of the pivoting compares like with like: a `q0` of
//! `1e-150` against a stiffness of `1e9`, or a load direction a million times larger than the
//! constant load, no longer makes some entries of a column look like round-off of others. The
//! scalings are exact; values leave through [`Columns::values`] and [`Columns::driver_real`].

/// The columns of an `n × n` matrix, column-major, each distinct column stored once: a column
/// that is bit for bit another one or its exact negation (the `z_t-` columns of the contact
/// LCP are the negated `z_t+` columns) points to it. A product with a negated column is formed
/// as the product with the stored one, negated — exact in floating point — so every result is
/// the same to the bit as with the full matrix, while the memory held and streamed by the
/// slack-row pass shrinks (by a third for the contact LCP).
#[derive(Debug, Clone)]
pub(crate) struct ColumnStore {
    n: usize,
    /// Distinct columns: stored column `s` is `data[s*n..(s+1)*n]`.
    data: Vec<f64>,
    /// For each column of the matrix: its stored column and whether it is that one negated.
    map: Vec<(usize, bool)>,
}

impl ColumnStore {
    /// Takes the column-major `n × n` data and keeps each distinct column once (in place).
    pub fn new(n: usize, mut data: Vec<f64>) -> Self {
        use std::collections::HashMap;
        debug_assert_eq!(data.len(), n * n);
        // A column's key: its bits with the sign of its first non-zero entry made positive.
        let key = |c: &[f64]| -> (bool, u64) {
            let neg = c.iter().find(|v| **v != 0.0).is_some_and(|v| *v < 0.0);
            let mut h: u64 = 0xcbf2_9ce4_8422_2325;
            for v in c {
                let b = if neg { (-v).to_bits() } else { v.to_bits() };
                h = (h ^ b).wrapping_mul(0x0100_0000_01b3);
            }
            (neg, h)
        };
        let same = |a: &[f64], b: &[f64], negated: bool| {
            a.iter().zip(b).all(|(x, y)| {
                let y = if negated { -y } else { *y };
                x.to_bits() == y.to_bits()
            })
        };
        let mut seen: HashMap<u64, Vec<(usize, bool)>> = HashMap::new();
        let mut map = Vec::with_capacity(n);
        let mut stored = 0usize;
        for j in 0..n {
            let (neg, h) = key(&data[j * n..(j + 1) * n]);
            let found = seen.get(&h).and_then(|cands| {
                cands.iter().find_map(|&(s, sneg)| {
                    let (a, b) = (&data[j * n..(j + 1) * n], &data[s * n..(s + 1) * n]);
                    same(a, b, neg != sneg).then_some((s, neg != sneg))
                })
            });
            match found {
                Some(entry) => map.push(entry),
                None => {
                    if stored != j {
                        data.copy_within(j * n..(j + 1) * n, stored * n);
                    }
                    seen.entry(h).or_default().push((stored, neg));
                    map.push((stored, false));
                    stored += 1;
                }
            }
        }
        data.truncate(stored * n);
        data.shrink_to_fit();
        Self { n, data, map }
    }

    /// Column `j`: the stored column and whether column `j` is its negation.
    #[inline]
    pub fn col(&self, j: usize) -> (&[f64], bool) {
        let (s, neg) = self.map[j];
        (&self.data[s * self.n..(s + 1) * self.n], neg)
    }

    /// The stored column of column `j` and whether column `j` is its negation.
    #[inline]
    pub fn col_index(&self, j: usize) -> (usize, bool) {
        self.map[j]
    }

    /// Stored column `s`.
    #[inline]
    pub fn stored(&self, s: usize) -> &[f64] {
        &self.data[s * self.n..(s + 1) * self.n]
    }

    /// Entry `(i, j)`.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (s, neg) = self.map[j];
        let v = self.data[s * self.n + i];
        if neg {
            -v
        } else {
            v
        }
    }
}

/// Dense column-major data of one tableau: `M`, the driver direction `g` and the right-hand side `h`.
#[derive(Debug, Clone)]
pub(crate) struct Columns {
    pub n: usize,
    /// `M` by columns (see [`ColumnStore`]).
    pub m: std::sync::Arc<ColumnStore>,
    pub g: Vec<f64>,
    pub h: Vec<f64>,
    /// Exponent of the scale of `h` (see the module documentation).
    pub eh: i32,
    /// Exponent of the scale of `g`.
    pub eg: i32,
    /// Rows of `M` that the slack-row pass forms from row relations instead of reading them.
    pub derived: Option<std::sync::Arc<crate::pivoting::relations::DerivedRows>>,
}

impl Columns {
    /// Builds the columns from equilibrated `h` and `g`, each divided by its power-of-two scale.
    pub fn new(n: usize, m: std::sync::Arc<ColumnStore>, h: Vec<f64>, g: Vec<f64>) -> Self {
        use crate::binary::{exponent, ldexp};
        let top = |v: &[f64]| exponent(v.iter().fold(0.0f64, |a, b| a.max(b.abs())));
        let (eh, eg) = match (top(&h), top(&g)) {
            (Some(a), Some(b)) => (a, b),
            (Some(a), None) => (a, a),
            (None, Some(b)) => (b, b),
            (None, None) => (0, 0),
        };
        let h = h.into_iter().map(|v| ldexp(v, -eh)).collect();
        let g = g.into_iter().map(|v| ldexp(v, -eg)).collect();
        Self {
            n,
            m,
            g,
            h,
            eh,
            eg,
            derived: None,
        }
    }

    /// Basic values (`x`, `z` by slot) in the equilibrated units of the caller.
    pub fn values(&self, beta: &[f64]) -> Vec<f64> {
        beta.iter()
            .map(|&b| crate::binary::ldexp(b, self.eh))
            .collect()
    }

    /// The driver's value in the caller's units from its value in the columns' units.
    pub fn driver_real(&self, t: f64) -> f64 {
        crate::binary::ldexp(t, self.eh - self.eg)
    }

    /// The driver's value in the columns' units from the caller's.
    pub fn driver_scaled(&self, t: f64) -> f64 {
        crate::binary::ldexp(t, self.eg - self.eh)
    }

    pub fn driver(&self) -> usize {
        2 * self.n
    }

    /// Column `j` of `M` as stored, and whether `M[:, j]` is its negation.
    #[inline]
    pub fn m_col(&self, j: usize) -> (&[f64], bool) {
        self.m.col(j)
    }

    /// Entry `A[i, col]` of the tableau matrix `[E | −M | −g]`.
    #[inline]
    pub fn entry(&self, i: usize, col: usize) -> f64 {
        let n = self.n;
        if col < n {
            if i == col {
                1.0
            } else {
                0.0
            }
        } else if col < 2 * n {
            -self.m.get(i, col - n)
        } else {
            -self.g[i]
        }
    }

    /// `out += s · A[:, col]` for a non-slack column.
    #[inline]
    pub fn axpy_col(&self, out: &mut [f64], s: f64, col: usize) {
        let n = self.n;
        if col < n {
            out[col] += s;
        } else if col < 2 * n {
            // o − s·(−v) is o + s·v exactly: the negated column needs no copy.
            let (c, neg) = self.m_col(col - n);
            if neg {
                for (o, v) in out.iter_mut().zip(c) {
                    *o += s * v;
                }
            } else {
                for (o, v) in out.iter_mut().zip(c) {
                    *o -= s * v;
                }
            }
        } else {
            for (o, v) in out.iter_mut().zip(&self.g) {
                *o -= s * v;
            }
        }
    }

    /// Writes `A[:, col]` into `out`.
    pub fn col_into(&self, col: usize, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        self.axpy_col(out, 1.0, col);
    }

    /// The complement of a column: `x_i ↔ z_i`. The driver has none.
    pub fn complement(&self, col: usize) -> Option<usize> {
        let n = self.n;
        if col < n {
            Some(col + n)
        } else if col < 2 * n {
            Some(col - n)
        } else {
            None
        }
    }
}
