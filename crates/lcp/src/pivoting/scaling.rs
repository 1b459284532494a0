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

/// The parts of a problem are raised to the largest part's loads only from within `2^-42`
/// (about `2.3e-13`) of them ([`Scaling::raise_parts`]): a few hundred times the round-off
/// of sums of the largest loads, so that no part whose loads could be that round-off is taken
/// for a load.
pub(crate) const RAISE_FLOOR: i32 = 42;

/// The set of each row `i` (index `i`) and column `j` (index `n + j`) of `m`: rows and columns
/// joined by the non-zeros of `m`, and the rows of each of `tied` with each other, each set
/// named by one of its members.
pub(crate) fn coupled_sets(m: &Mat<f64>, tied: &[Vec<usize>]) -> Vec<usize> {
    let n = m.nrows();
    let mut parent: Vec<usize> = (0..2 * n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for j in 0..n {
        for (i, &v) in m.col_as_slice(j).iter().enumerate() {
            if v != 0.0 {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, n + j));
                if ri != rj {
                    parent[ri] = rj;
                }
            }
        }
    }
    for rows in tied {
        for w in rows.windows(2) {
            let (ra, rb) = (find(&mut parent, w[0]), find(&mut parent, w[1]));
            if ra != rb {
                parent[ra] = rb;
            }
        }
    }
    (0..2 * n).map(|x| find(&mut parent, x)).collect()
}

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
            let set = coupled_sets(m, &[]);
            let mut top = vec![f64::NEG_INFINITY; 2 * n];
            for i in 0..n {
                if let Some(l) = log2_of(q[i]) {
                    top[set[i]] = top[set[i]].max(l + a[i]);
                }
            }
            for i in 0..n {
                let t = top[set[i]];
                if t.is_finite() {
                    a[i] -= t;
                }
            }
            for j in 0..n {
                let t = top[set[n + j]];
                if t.is_finite() {
                    b[j] += t;
                }
            }
        }
        Self::from_exponents(&a, &b)
    }

    /// Raises each part of the problem that no entry of `M` and no row relation joins to the
    /// others (a set of rows and columns that `M` couples, with the rows each of `tied` ties:
    /// a structure beside another in one contact zone, or the friction rows of a body that
    /// slides on frictionless pairs, which no relation ties to its normal rows) by a power of
    /// two `2^s`: as far as each kind of its loads (each of `loads`, the right-hand sides the
    /// scaled rows carry: the constant load, the load's direction) reaches the largest of that
    /// kind over all parts, and no further (the smallest of the kinds' gaps). `E M D` does not
    /// change (the part's rows times `2^s`, its columns over `2^s`), only the size of the
    /// part's values: a part whose loads are a billionth of another's is no longer below the
    /// pivot tolerance of the columns both share (the load's). A part is raised by at most
    /// `2^RAISE_FLOOR` ([`RAISE_FLOOR`]): farther, its loads could be round-off of the others'
    /// terms, and it is left as it is. No kind
    /// of its loads passes the largest of that kind: a part's constant load raised past the
    /// others' (its load's direction far below theirs) would make their values at the start
    /// round-off of its own. Returns `s` a row (zero where nothing was raised).
    pub fn raise_parts(&mut self, m: &Mat<f64>, loads: &[&[f64]], tied: &[Vec<usize>]) -> Vec<i32> {
        self.raise_sets(&coupled_sets(m, tied), loads)
    }

    /// [`Scaling::raise_parts`] on the sets [`coupled_sets`] gave.
    pub fn raise_sets(&mut self, set: &[usize], loads: &[&[f64]]) -> Vec<i32> {
        let n = set.len() / 2;
        // The largest binary exponent of each kind of load in each set, and over all sets.
        let mut top = vec![vec![i32::MIN; 2 * n]; loads.len()];
        for (k, v) in loads.iter().enumerate() {
            for i in 0..n {
                if let Some(e) = exponent(v[i]) {
                    top[k][set[i]] = top[k][set[i]].max(e + self.row_exp[i]);
                }
            }
        }
        let largest: Vec<i32> = top
            .iter()
            .map(|t| t.iter().copied().max().unwrap_or(i32::MIN))
            .collect();
        let mut shift = vec![0i32; 2 * n];
        for (x, s) in shift.iter_mut().enumerate() {
            if set[x] != x {
                continue;
            }
            // The smallest gap over the kinds of load this set carries.
            let gap = (0..loads.len())
                .filter(|&k| top[k][x] != i32::MIN)
                .map(|k| largest[k] - top[k][x])
                .min();
            if let Some(g) = gap.filter(|g| (1..=RAISE_FLOOR).contains(g)) {
                *s = g;
            }
        }
        // A set whose scales would leave the range of the exponents is left as it is.
        for i in 0..n {
            let r = set[i];
            if shift[r] != 0 && self.row_exp[i] + shift[r] > MAX_EXP {
                shift[r] = 0;
            }
            let c = set[n + i];
            if shift[c] != 0 && self.col_exp[i] - shift[c] < -MAX_EXP {
                shift[c] = 0;
            }
        }
        let mut shifts = vec![0; n];
        for (i, s) in shifts.iter_mut().enumerate() {
            *s = shift[set[i]];
            self.row_exp[i] += *s;
            self.row[i] = ldexp(1.0, self.row_exp[i]);
        }
        for j in 0..n {
            self.col_exp[j] -= shift[set[n + j]];
            self.col[j] = ldexp(1.0, self.col_exp[j]);
        }
        shifts
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Parts that `M` does not couple — rows and columns {0, 1}, {2}, {3}, {4}, {5} and {6} —
    /// whose constant loads are 2^0, 2^-30, 2^-50, none, 2^-10 and 2^0 and whose loads'
    /// directions are 2^-1 (the largest), none, none, none, none and 2^-31, after the
    /// equilibration: by hand the second is raised by 2^30 (its row scale times 2^30, its
    /// column scale over 2^30, so that `E M D` keeps every bit) and the fifth by 2^10, the
    /// third is left (below `2^-RAISE_FLOOR`), the fourth has nothing to raise, and the sixth
    /// is left: its direction is 2^30 below the largest, but its constant load is as large as
    /// the largest already.
    #[test]
    fn raise_parts_brings_each_part_to_the_largest_parts_loads() {
        let m = Mat::from_fn(7, 7, |i, j| match (i, j) {
            (0, 0) | (1, 1) => 2.0,
            (0, 1) | (1, 0) => 1.0,
            (2, 2) | (3, 3) | (4, 4) | (5, 5) | (6, 6) => 4.0,
            _ => 0.0,
        });
        let mut s = Scaling::equilibrate(&m, &[]);
        let before = s.clone();
        let (scaled, _) = s.scale_matrix(&m);
        let q0 = [
            -ldexp(1.0, -before.row_exp[0]),
            0.0,
            -ldexp(1.0, -30 - before.row_exp[2]),
            ldexp(1.0, -50 - before.row_exp[3]),
            0.0,
            ldexp(1.0, -10 - before.row_exp[5]),
            ldexp(1.0, -before.row_exp[6]),
        ];
        let mut d = [0.0; 7];
        d[1] = ldexp(0.5, -before.row_exp[1]);
        d[6] = ldexp(1.0, -31 - before.row_exp[6]);
        let shifts = s.raise_parts(&m, &[&q0, &d], &[]);
        assert_eq!(shifts, vec![0, 0, 30, 0, 0, 10, 0]);
        for (i, &shift) in shifts.iter().enumerate() {
            assert_eq!(s.row_exp[i], before.row_exp[i] + shift);
            assert_eq!(s.col_exp[i], before.col_exp[i] - shift);
            assert_eq!(s.row[i], ldexp(1.0, s.row_exp[i]));
            assert_eq!(s.col[i], ldexp(1.0, s.col_exp[i]));
        }
        assert_eq!(s.scale_matrix(&m).0, scaled, "E M D keeps every bit");
        // The raised parts' loads are now as large as the first part's.
        let q_hat = s.scale_rows(&q0);
        assert_eq!(q_hat[2], q_hat[0]);
        assert_eq!(q_hat[5], -q_hat[0]);
    }
}
