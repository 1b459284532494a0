//! Equilibration of the LCP by powers of two, so that scaling loses no digit.
//!
//! `x̂ = E x`, `z = D ẑ` keep complementarity (positive diagonal scalings) and turn
//! `x = q + M z` into `x̂ = E q + (E M D) ẑ`. Ruiz's iteration balances the largest entry of every
//! row and column of `E M D` to about one, so that relative tolerances mean the same thing in
//! every row whatever the units (forces and displacements of a steel structure differ by 10¹¹).
//!
//! The iteration works on binary exponents, not on the numbers: a scale is an integer power of
//! two, so a change of units by `2^k` shifts every exponent by `k` and changes no bit of the
//! equilibrated problem, and no scale overflows however small or large the data (an entry of
//! `1e-308` needs a scale of `1e308`, a product of `1e-308` and `1e308` loses nothing).
//!
//! Right-hand sides may take part (each with a column scale of its own, which is not kept): a
//! row whose `M` entries and `q` entry are both tiny is then scaled up to the size of the other
//! rows, instead of looking like round-off of them.

use faer::Mat;
use rayon::prelude::*;

use crate::binary::{exponent, ldexp};

/// Exponents of the scales stay within this bound, so that every scale is a normal number.
const MAX_EXP: i32 = 1000;

/// Ruiz sweeps at most; the iteration stops as soon as every row and column is balanced to
/// within a factor of two, which usually takes a handful.
const MAX_SWEEPS: usize = 64;

/// Diagonal scalings `E` (rows) and `D` (columns), powers of two.
#[derive(Debug, Clone)]
pub(crate) struct Scaling {
    pub row: Vec<f64>,
    pub col: Vec<f64>,
    /// `row[i] = 2^row_exp[i]`.
    pub row_exp: Vec<i32>,
    /// `col[j] = 2^col_exp[j]`.
    pub col_exp: Vec<i32>,
}

/// `log2 |v|` to within one half (`None` for zero).
fn log2_of(v: f64) -> Option<f64> {
    exponent(v).map(|e| e as f64 + 0.5)
}

impl Scaling {
    /// Balances `[M | r_1 | r_2 | …]`: the rows of `M` with the right-hand sides `rhs`, each of
    /// which has a column scale of its own.
    pub fn equilibrate(m: &Mat<f64>, rhs: &[&[f64]]) -> Self {
        let n = m.nrows();
        let (a, b) = Self::ruiz(m, rhs, vec![0.0; n], vec![0.0; n]);
        Self::from_exponents(&a, &b)
    }

    /// The equilibration of an LCP `w = q + M z` that does not depend on the units of its rows
    /// and unknowns (`D_r M D_c`, `D_r q` give the same equilibrated problem, up to a factor of
    /// two per row and column).
    ///
    /// 1. When every diagonal entry is non-zero, each row is divided by its diagonal entry,
    ///    which leaves `D_c⁻¹ N D_c` (`N` with a unit diagonal), and the similarity `D_c` is
    ///    undone by max-balancing (each unknown's largest coupling in its row made equal to its
    ///    largest in its column; the max-balanced matrix is unique; a coupling one way only is
    ///    made as large as the diagonal). Ruiz's iteration alone,
    ///    started from the data, can settle on a balance where a few huge columns make every
    ///    other entry of their rows negligible.
    /// 2. Ruiz's iteration on `M` from there.
    /// 3. The scalings that leave `E M D` unchanged — rows times `t`, columns over `t`, on each
    ///    set of rows and columns that `M` couples — bring the largest `|q̂_i|` of each set to
    ///    about one: a block whose data are all tiny (`M = diag(1e-308, 1)`, `q = (−1e-300, −1)`)
    ///    is then as large as the others, not round-off next to them.
    pub fn equilibrate_lcp(m: &Mat<f64>, q: Option<&[f64]>) -> Self {
        let n = m.nrows();
        let diag: Option<Vec<f64>> = (0..n).map(|i| log2_of(m[(i, i)])).collect();
        let (a0, b0) = match diag {
            Some(diag) => {
                let a: Vec<f64> = diag.iter().map(|d| -d).collect();
                let mut b = vec![0.0f64; n];
                for _ in 0..MAX_SWEEPS {
                    let mut moved = 0.0f64;
                    for i in 0..n {
                        let mut rmax = f64::NEG_INFINITY;
                        let mut cmax = f64::NEG_INFINITY;
                        for j in (0..n).filter(|&j| j != i) {
                            if let Some(l) = log2_of(m[(i, j)]) {
                                rmax = rmax.max(l + a[i] + b[j]);
                            }
                            if let Some(l) = log2_of(m[(j, i)]) {
                                cmax = cmax.max(l + a[j] - b[j]);
                            }
                        }
                        // Balanced where the unknown is coupled both ways; where only one
                        // way (a block-triangular coupling, which a similarity can make as
                        // large or small as it likes), that coupling is made as large as the
                        // diagonal.
                        let new = match (rmax.is_finite(), cmax.is_finite()) {
                            (true, true) => (rmax - cmax) / 2.0,
                            (true, false) => rmax,
                            (false, true) => -cmax,
                            (false, false) => continue,
                        };
                        moved = moved.max((new - b[i]).abs());
                        b[i] = new;
                    }
                    if moved <= 0.5 {
                        break;
                    }
                }
                ((0..n).map(|i| a[i] - b[i]).collect(), b)
            }
            None => (vec![0.0; n], vec![0.0; n]),
        };
        let (mut a, mut b) = Self::ruiz(m, &[], a0, b0);
        if let Some(q) = q {
            // Union-find over rows 0..n and columns n..2n joined by the non-zeros of M.
            let mut parent: Vec<usize> = (0..2 * n).collect();
            fn find(p: &mut [usize], mut x: usize) -> usize {
                while p[x] != x {
                    p[x] = p[p[x]];
                    x = p[x];
                }
                x
            }
            for j in 0..n {
                for i in 0..n {
                    if m[(i, j)] != 0.0 {
                        let (ri, rj) = (find(&mut parent, i), find(&mut parent, n + j));
                        if ri != rj {
                            parent[ri] = rj;
                        }
                    }
                }
            }
            let mut top = vec![f64::NEG_INFINITY; 2 * n];
            for i in 0..n {
                if let Some(l) = log2_of(q[i]) {
                    let r = find(&mut parent, i);
                    top[r] = top[r].max(l + a[i]);
                }
            }
            for i in 0..n {
                let t = top[find(&mut parent, i)];
                if t.is_finite() {
                    a[i] -= t;
                }
            }
            for j in 0..n {
                let t = top[find(&mut parent, n + j)];
                if t.is_finite() {
                    b[j] += t;
                }
            }
        }
        Self::from_exponents(&a, &b)
    }

    fn from_exponents(a: &[f64], b: &[f64]) -> Self {
        let to_exp = |v: &f64| (v.round() as i32).clamp(-MAX_EXP, MAX_EXP);
        let row_exp: Vec<i32> = a.iter().map(to_exp).collect();
        let col_exp: Vec<i32> = b.iter().map(to_exp).collect();
        Self {
            row: row_exp.iter().map(|&e| ldexp(1.0, e)).collect(),
            col: col_exp.iter().map(|&e| ldexp(1.0, e)).collect(),
            row_exp,
            col_exp,
        }
    }

    /// Ruiz's iteration from row and column exponents `a`, `b`.
    fn ruiz(
        m: &Mat<f64>,
        rhs: &[&[f64]],
        mut a: Vec<f64>,
        mut b: Vec<f64>,
    ) -> (Vec<f64>, Vec<f64>) {
        let n = m.nrows();
        let mut c = vec![0.0f64; rhs.len()];
        // Each sweep reads `M` twice, by columns; the row maxima are formed over blocks of rows
        // and the column maxima column by column on the thread pool (a maximum is exact: the
        // same exponents whatever the threads).
        const ROWS: usize = 256;
        for _ in 0..MAX_SWEEPS {
            let mut rmax = vec![f64::NEG_INFINITY; n];
            rmax.par_chunks_mut(ROWS)
                .enumerate()
                .for_each(|(blk, part)| {
                    let i0 = blk * ROWS;
                    for (j, &bj) in b.iter().enumerate() {
                        let col = &m.col_as_slice(j)[i0..i0 + part.len()];
                        for (r, (&v, &ai)) in part.iter_mut().zip(col.iter().zip(&a[i0..])) {
                            if let Some(l) = log2_of(v) {
                                *r = r.max(l + ai + bj);
                            }
                        }
                    }
                });
            for (k, r) in rhs.iter().enumerate() {
                for i in 0..n {
                    if let Some(l) = log2_of(r[i]) {
                        rmax[i] = rmax[i].max(l + a[i] + c[k]);
                    }
                }
            }
            let mut balanced = true;
            for i in 0..n {
                if rmax[i].is_finite() {
                    balanced &= rmax[i].abs() <= 1.0;
                    a[i] -= rmax[i] / 2.0;
                }
            }
            let columns_balanced = b
                .par_iter_mut()
                .enumerate()
                .map(|(j, bj)| {
                    let mut cmax = f64::NEG_INFINITY;
                    for (&v, &ai) in m.col_as_slice(j).iter().zip(&a) {
                        if let Some(l) = log2_of(v) {
                            cmax = cmax.max(l + ai + *bj);
                        }
                    }
                    if cmax.is_finite() {
                        *bj -= cmax / 2.0;
                        cmax.abs() <= 1.0
                    } else {
                        true
                    }
                })
                .reduce(|| true, |x, y| x && y);
            balanced &= columns_balanced;
            for (k, r) in rhs.iter().enumerate() {
                let mut cmax = f64::NEG_INFINITY;
                for i in 0..n {
                    if let Some(l) = log2_of(r[i]) {
                        cmax = cmax.max(l + a[i] + c[k]);
                    }
                }
                if cmax.is_finite() {
                    // The column scale of a right-hand side is free: set it at once.
                    c[k] -= cmax;
                }
            }
            if balanced {
                break;
            }
        }
        (a, b)
    }

    /// `E M D` in column-major order, and whether every entry of `M` is recovered from it
    /// exactly by [`Scaling::original_entry`] (no scaled entry underflowed or overflowed).
    pub fn scale_matrix(&self, m: &Mat<f64>) -> (Vec<f64>, bool) {
        let n = m.nrows();
        let mut out = vec![0.0; n * n];
        if n == 0 {
            return (out, true);
        }
        // Column by column on the pool (each entry depends on itself alone).
        let exact = out
            .par_chunks_mut(n)
            .enumerate()
            .map(|(j, out)| {
                let c = self.col_exp[j];
                let mut exact = true;
                for ((o, &v), &r) in out.iter_mut().zip(m.col_as_slice(j)).zip(&self.row_exp) {
                    let e = r + c;
                    let s = ldexp(v, e);
                    exact &= ldexp(s, -e) == v;
                    *o = s;
                }
                exact
            })
            .reduce(|| true, |a, b| a && b);
        (out, exact)
    }

    /// `M_ij` from the scaled entry `(E M D)_ij` (exact when [`Scaling::scale_matrix`] said so).
    #[inline]
    pub fn original_entry(&self, scaled: f64, i: usize, j: usize) -> f64 {
        ldexp(scaled, -(self.row_exp[i] + self.col_exp[j]))
    }

    pub fn scale_rows(&self, v: &[f64]) -> Vec<f64> {
        v.iter().zip(&self.row).map(|(a, e)| a * e).collect()
    }

    /// `x = E⁻¹ x̂`.
    pub fn unscale_x(&self, x: &[f64]) -> Vec<f64> {
        x.iter().zip(&self.row).map(|(a, e)| a / e).collect()
    }

    /// `z = D ẑ`.
    pub fn unscale_z(&self, z: &[f64]) -> Vec<f64> {
        z.iter().zip(&self.col).map(|(a, d)| a * d).collect()
    }
}
