//! The full rational tableau shared by Lemke's method and the parametric method.
//!
//! Columns: `x_0..x_{n−1}` (or `w`), `z_0..z_{n−1}`, one extra variable (`p` or `z0`), then the
//! right-hand side. Row `i` initially reads `x_i − Σ_j M_ij z_j − a_i·extra = rhs_i`, basis `x`.
//! The tableau is always kept in the form `B⁻¹ [E | −M | −a | rhs]`, so the value of the basic
//! variable of a row is its right-hand side, and the columns of the initial basis (`x`) hold
//! `B⁻¹`.

use crate::{linalg, Rat, Var};
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

pub(crate) struct Tableau {
    pub n: usize,
    pub t: Vec<Vec<Rat>>,
    /// Column of the basic variable of each row.
    pub basis: Vec<usize>,
    /// The columns of `B⁻¹` (the initial basis) in lexicographic priority order.
    lex: Vec<usize>,
    /// What the extra column stands for (`Var::P` or `Var::Z0`).
    extra: Var,
}

impl Tableau {
    /// `[E | −M | −a | rhs]` with basis `x`. `priority` (a permutation of `0..n`) orders the
    /// columns of `B⁻¹` for the lexicographic tie-break; default identity.
    ///
    /// # Panics
    /// If the sizes are inconsistent or `priority` is not a permutation of `0..n`.
    pub fn new(
        m: &[Vec<Rat>],
        a: &[Rat],
        rhs: &[Rat],
        extra: Var,
        priority: Option<&[usize]>,
    ) -> Self {
        let n = rhs.len();
        crate::check_square(m, n);
        assert_eq!(a.len(), n, "the extra column must have length {n}");
        let lex: Vec<usize> = match priority {
            None => (0..n).collect(),
            Some(p) => {
                let mut seen = vec![false; n];
                assert_eq!(p.len(), n, "priority must be a permutation of 0..{n}");
                for &i in p {
                    assert!(
                        i < n && !seen[i],
                        "priority must be a permutation of 0..{n}"
                    );
                    seen[i] = true;
                }
                p.to_vec()
            }
        };
        let t = (0..n)
            .map(|i| {
                let mut row = Vec::with_capacity(2 * n + 2);
                row.extend((0..n).map(|j| if i == j { Rat::one() } else { Rat::zero() }));
                row.extend(m[i].iter().map(|v| -v));
                row.push(-&a[i]);
                row.push(rhs[i].clone());
                row
            })
            .collect();
        Tableau {
            n,
            t,
            basis: (0..n).collect(),
            lex,
            extra,
        }
    }

    pub fn rhs_col(&self) -> usize {
        2 * self.n + 1
    }

    pub fn extra_col(&self) -> usize {
        2 * self.n
    }

    pub fn var(&self, col: usize) -> Var {
        let n = self.n;
        match col {
            c if c < n => Var::X(c),
            c if c < 2 * n => Var::Z(c - n),
            c if c == 2 * n => self.extra,
            _ => panic!("column {col} is not a variable"),
        }
    }

    pub fn col(&self, v: Var) -> usize {
        match v {
            Var::X(i) => i,
            Var::Z(i) => self.n + i,
            _ => {
                assert_eq!(v, self.extra, "{v} is not a variable of this tableau");
                2 * self.n
            }
        }
    }

    /// The row whose basic variable is in column `col`, if it is basic.
    pub fn row_of(&self, col: usize) -> Option<usize> {
        self.basis.iter().position(|&b| b == col)
    }

    /// Pivots on `(r, c)`; returns the column that left the basis.
    pub fn pivot(&mut self, r: usize, c: usize) -> usize {
        linalg::pivot(&mut self.t, r, c);
        std::mem::replace(&mut self.basis[r], c)
    }

    /// Compares row `i` divided by `di > 0` with row `k` divided by `dk > 0`, lexicographically
    /// over `[rhs | B⁻¹ columns in priority order]`.
    fn lex_cmp(&self, i: usize, di: &Rat, k: usize, dk: &Rat) -> Ordering {
        let rc = self.rhs_col();
        std::iter::once(rc)
            .chain(self.lex.iter().copied())
            .map(|c| (&self.t[i][c] * dk).cmp(&(&self.t[k][c] * di)))
            .find(|o| o.is_ne())
            .unwrap_or(Ordering::Equal)
    }

    /// The lexicographically smallest of the rows `rows`, each divided by its (positive)
    /// `divisor`. `None` if `rows` is empty.
    pub fn lex_min(
        &self,
        rows: impl IntoIterator<Item = usize>,
        divisor: impl Fn(usize) -> Rat,
    ) -> Option<usize> {
        let mut best: Option<(usize, Rat)> = None;
        for i in rows {
            let di = divisor(i);
            debug_assert!(di.is_positive());
            let better = match &best {
                None => true,
                Some((k, dk)) => self.lex_cmp(i, &di, *k, dk) == Ordering::Less,
            };
            if better {
                best = Some((i, di));
            }
        }
        best.map(|(i, _)| i)
    }

    /// The rows with a positive entry in column `c`.
    pub fn positive_rows(&self, c: usize) -> Vec<usize> {
        (0..self.n)
            .filter(|&i| self.t[i][c].is_positive())
            .collect()
    }

    /// The lexicographic minimum-ratio row for entering column `c` (over positive entries).
    pub fn ratio_test(&self, c: usize) -> Option<usize> {
        self.lex_min(self.positive_rows(c), |i| self.t[i][c].clone())
    }

    /// Current values: `(x, z, extra)`; non-basic variables are zero.
    pub fn values(&self) -> (Vec<Rat>, Vec<Rat>, Rat) {
        let mut all = vec![Rat::zero(); 2 * self.n + 1];
        let rc = self.rhs_col();
        for (i, &b) in self.basis.iter().enumerate() {
            all[b] = self.t[i][rc].clone();
        }
        let extra = all.pop().expect("non-empty");
        let z = all.split_off(self.n);
        (all, z, extra)
    }

    /// The change of `(x, z, extra)` per unit increase of the non-basic variable of column `c`.
    pub fn direction(&self, c: usize) -> (Vec<Rat>, Vec<Rat>, Rat) {
        let mut all = vec![Rat::zero(); 2 * self.n + 1];
        all[c] = Rat::one();
        for (i, &b) in self.basis.iter().enumerate() {
            all[b] = -&self.t[i][c];
        }
        let extra = all.pop().expect("non-empty");
        let z = all.split_off(self.n);
        (all, z, extra)
    }
}
