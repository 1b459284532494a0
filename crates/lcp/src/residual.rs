//! Verification of a solution from the original data.

use faer::Mat;

use crate::binary::{exponent, ldexp};

/// Verified residuals of a solution of `w = q + M z`, each row and each unknown measured against
/// its own data.
///
/// With `s_i = max(|q_i|, Σ_j |M_ij z_j|, |w_i|)` the scale of row `i`:
///
/// * `equation` = `max_i |w_i − q_i − (Mz)_i| / s_i`,
/// * `feasibility` = the largest of `max(0, −w_i) / s_i` and, for `z_j < 0`, of the relative
///   change `max_i |M_ij z_j| / s_i` that setting `z_j` to zero would make in the rows,
/// * `complementarity` = `max_i min(|w_i| / s_i, max_k |M_ki z_i| / s_k)`: how far, relative to
///   the rows it meets, the point is from one with `w_i = 0` or `z_i = 0`.
///
/// Every measure is a relative change of the data, row by row, that would make the point exact,
/// so none depends on the units of any row or unknown (it is unchanged when `M`, `q`, `w` are
/// multiplied by positive diagonal scalings `E` on the left and `z` by `D⁻¹`), and a row with tiny
/// data is judged on its own: its violation is never hidden by the size of other rows. A
/// non-zero `z_j` whose column of `M` is zero has no row to be measured against and counts as a
/// full violation (it cannot be verified).
///
/// The sums are formed row by row on data rescaled by powers of two (exact), so they neither
/// overflow nor underflow whatever the magnitudes (`M` of `1e300` times `z` of `1e10` is no
/// infinity). A non-finite number in `w` or `z` makes every residual infinite: such a point is
/// never accepted.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Residual {
    /// Relative residual of the equation.
    pub equation: f64,
    /// Relative violation of the sign conditions.
    pub feasibility: f64,
    /// Relative violation of complementarity.
    pub complementarity: f64,
}

impl Residual {
    /// The largest of the three (infinite when any is not a number).
    pub fn max(&self) -> f64 {
        let r = [self.equation, self.feasibility, self.complementarity];
        if r.iter().any(|v| v.is_nan()) {
            return f64::INFINITY;
        }
        r.iter().fold(0.0f64, |a, &b| a.max(b))
    }

    /// Infinite residuals: the point cannot be verified.
    pub fn unverifiable() -> Self {
        Self {
            equation: f64::INFINITY,
            feasibility: f64::INFINITY,
            complementarity: f64::INFINITY,
        }
    }

    /// Residuals of `(w, z)` for `w = q + M z` (`M` is `q.len() × z.len()`).
    pub fn of(m: &Mat<f64>, q: &[f64], w: &[f64], z: &[f64]) -> Self {
        let size: Vec<f64> = q.iter().map(|v| v.abs()).collect();
        Self::of_terms(&MatColumns(m), (m.nrows(), m.ncols()), q, &size, w, z)
    }

    /// Residuals of `(x, z)` for the parametric `x = q0 + p·d + M z` at load `p`. Each row is
    /// measured against the terms `|q0_i| + |p·d_i|` that form its right-hand side as well as
    /// its `M z` terms: where `q0_i + p·d_i` cancels (at the load of an event, where it is
    /// zero in exact arithmetic) its round-off is that of the terms, not of the difference.
    pub fn of_parametric(
        m: &Mat<f64>,
        q0: &[f64],
        d: &[f64],
        p: f64,
        x: &[f64],
        z: &[f64],
    ) -> Self {
        Self::of_parametric_with(&MatColumns(m), (m.nrows(), m.ncols()), q0, d, p, x, z)
    }

    /// [`Residual::of_parametric`] with `M` given by its columns (`shape` = rows, columns).
    pub(crate) fn of_parametric_with(
        m: &impl ColumnSource,
        shape: (usize, usize),
        q0: &[f64],
        d: &[f64],
        p: f64,
        x: &[f64],
        z: &[f64],
    ) -> Self {
        if q0.len() != d.len() {
            return Self::unverifiable();
        }
        let q: Vec<f64> = q0.iter().zip(d).map(|(a, b)| a + p * b).collect();
        let size: Vec<f64> = q0
            .iter()
            .zip(d)
            .map(|(a, b)| a.abs() + (p * b).abs())
            .collect();
        Self::of_terms(m, shape, &q, &size, x, z)
    }

    /// [`Residual::of`] with `size[i] ≥ |q_i|` the magnitude of the terms that formed `q_i`.
    ///
    /// Where every number met (the data, the terms `M_ij z_j` and the row sums) lies well inside
    /// the normal range, the sums are formed in plain arithmetic ([`Residual::plain`]): the
    /// rescaling by powers of two commutes with every rounding there, so the residuals are the
    /// same bits as those of the rescaled sums, at a fraction of the cost (a column is read
    /// twice, in contiguous slices, instead of entry by entry four times). Elsewhere the
    /// rescaled sums are formed ([`Residual::rescaled`]).
    fn of_terms(
        m: &impl ColumnSource,
        shape: (usize, usize),
        q: &[f64],
        size: &[f64],
        w: &[f64],
        z: &[f64],
    ) -> Self {
        let (rows, cols) = (q.len(), z.len());
        if w.iter()
            .chain(z)
            .chain(q)
            .chain(size)
            .any(|v| !v.is_finite())
            || size.len() != rows
            || shape.0 != rows
            || shape.1 != cols
            || w.len() != rows
        {
            return Self::unverifiable();
        }
        match Self::plain(m, q, size, w, z) {
            Plain::Done(r) => r,
            Plain::NotFinite => Self::unverifiable(),
            Plain::OutOfRange => Self::rescaled(&|i, j| m.entry(i, j), shape, q, size, w, z),
        }
    }

    /// The residuals in plain arithmetic, or why they cannot be formed so: a non-finite entry
    /// in a column of non-zero `z` ([`Plain::NotFinite`]), or a number near the ends of the
    /// floating-point range ([`Plain::OutOfRange`]), where the rescaled sums are exact and the
    /// plain ones are not. Row blocks are summed on the thread pool when the work is large;
    /// each row's sum runs over the columns in the same order whatever the number of threads.
    fn plain(m: &impl ColumnSource, q: &[f64], size: &[f64], w: &[f64], z: &[f64]) -> Plain {
        use rayon::prelude::*;
        let rows = q.len();
        let nz: Vec<usize> = (0..z.len()).filter(|&j| z[j] != 0.0).collect();
        // Normal numbers at least 2^±960 away from the ends: no term, sum or ratio below
        // under- or overflows, and a term of a row is never more than 2^1000 below the row's
        // largest one, so that the rescaled sums keep every bit of it too.
        let (lo, hi) = (2f64.powi(-480), 2f64.powi(480));
        let fits = |v: f64| v == 0.0 || (v.abs() >= lo && v.abs() <= hi);
        if !q
            .iter()
            .chain(size)
            .chain(w)
            .chain(nz.iter().map(|&j| &z[j]))
            .all(|&v| fits(v))
        {
            return Plain::OutOfRange;
        }
        const ROWS: usize = 512;
        let blocks: Vec<(usize, usize)> = (0..rows)
            .step_by(ROWS)
            .map(|a| (a, (a + ROWS).min(rows)))
            .collect();
        let parallel = rows * nz.len() >= 1 << 18;
        // (r, mag) per row block, or the reason to give up
        let sums = |&(a, b): &(usize, usize)| -> Result<RowSums, Plain> {
            let mut r = q[a..b].to_vec();
            let mut mag = size[a..b].to_vec();
            let mut col = vec![0.0; b - a];
            for &j in &nz {
                m.column_into(j, a..b, &mut col);
                let zj = z[j];
                // no branch in the loop: one flag for the whole column (NaN fails every
                // comparison)
                let mut ok = true;
                for ((ri, gi), &mij) in r.iter_mut().zip(mag.iter_mut()).zip(&col) {
                    let t = mij * zj;
                    let (a, b) = (mij.abs(), t.abs());
                    ok &=
                        (a <= hi) & ((a >= lo) | (a == 0.0)) & (b <= hi) & ((b >= lo) | (b == 0.0));
                    *ri += t;
                    *gi += b;
                }
                if !ok {
                    return Err(if col.iter().all(|v| v.is_finite()) {
                        Plain::OutOfRange
                    } else {
                        Plain::NotFinite
                    });
                }
            }
            if !r.iter().chain(&mag).all(|&v| fits(v)) {
                return Err(Plain::OutOfRange);
            }
            Ok((r, mag))
        };
        let parts: Vec<Result<RowSums, Plain>> = if parallel {
            blocks.par_iter().map(sums).collect()
        } else {
            blocks.iter().map(sums).collect()
        };
        let mut r = Vec::with_capacity(rows);
        let mut mag = Vec::with_capacity(rows);
        let mut worst = None;
        for part in parts {
            match part {
                Ok((a, b)) => {
                    r.extend(a);
                    mag.extend(b);
                }
                // a non-finite entry decides before a range
                Err(Plain::NotFinite) => worst = Some(Plain::NotFinite),
                Err(e) => {
                    if worst.is_none() {
                        worst = Some(e);
                    }
                }
            }
        }
        if let Some(e) = worst {
            return e;
        }
        let s: Vec<f64> = mag.iter().zip(w).map(|(a, b)| a.max(b.abs())).collect();
        let rel = |v: f64, si: f64| if v == 0.0 { 0.0 } else { v / si };
        let mut equation = 0.0f64;
        let mut wneg = 0.0f64;
        for i in 0..rows {
            equation = equation.max(rel((w[i] - r[i]).abs(), s[i]));
            wneg = wneg.max(rel((-w[i]).max(0.0), s[i]));
        }
        // The effect of each z_j on the rows it meets, relative to their scales.
        // One column buffer per thread (or one for the whole pass), not one per column.
        let effect_of = |col: &mut Vec<f64>, &j: &usize| -> f64 {
            m.column_into(j, 0..rows, col);
            let mut met = false;
            let mut best = 0.0f64;
            for (&mij, &si) in col.iter().zip(&s) {
                if mij != 0.0 {
                    met = true;
                    best = best.max(rel((mij * z[j]).abs(), si));
                }
            }
            if met {
                best
            } else {
                1.0
            }
        };
        let effects: Vec<f64> = if parallel {
            nz.par_iter()
                .map_init(|| vec![0.0; rows], effect_of)
                .collect()
        } else {
            let mut col = vec![0.0; rows];
            nz.iter().map(|j| effect_of(&mut col, j)).collect()
        };
        let mut effect = vec![0.0; z.len()];
        for (&j, e) in nz.iter().zip(effects) {
            effect[j] = e;
        }
        let zneg = (0..z.len())
            .filter(|&j| z[j] < 0.0)
            .fold(0.0f64, |a, j| a.max(effect[j]));
        let complementarity =
            (0..rows.min(z.len())).fold(0.0f64, |a, i| a.max(rel(w[i].abs(), s[i]).min(effect[i])));
        Plain::Done(Self {
            equation,
            feasibility: wneg.max(zneg),
            complementarity,
        })
    }

    /// The residuals from sums rescaled row by row by powers of two (exact whatever the
    /// magnitudes), `M` read entry by entry; the data as [`Residual::of_terms`] checked them.
    fn rescaled(
        m: &impl Fn(usize, usize) -> f64,
        shape: (usize, usize),
        q: &[f64],
        size: &[f64],
        w: &[f64],
        z: &[f64],
    ) -> Self {
        let (rows, cols) = (q.len(), z.len());
        debug_assert_eq!(shape, (rows, cols));
        // Only the columns of non-zero `z` form terms of the residual: a pass over those alone
        // (the residual of a point on a long path is then `O(n·k)` to check, not `O(n²)`).
        if (0..cols).any(|j| z[j] != 0.0 && (0..rows).any(|i| !m(i, j).is_finite())) {
            return Self::unverifiable();
        }
        // Row i is formed times 2^(−e[i]), with e[i] above the exponent of every term of the row.
        let mut e: Vec<i32> = (0..rows)
            .map(|i| {
                let t = [size[i], w[i]].into_iter().filter_map(exponent).max();
                t.unwrap_or(i32::MIN)
            })
            .collect();
        let ez: Vec<Option<i32>> = z.iter().map(|&v| exponent(v)).collect();
        for (j, &ezj) in ez.iter().enumerate() {
            let Some(ezj) = ezj else { continue };
            for (i, ei) in e.iter_mut().enumerate() {
                if let Some(emij) = exponent(m(i, j)) {
                    *ei = (*ei).max(emij + ezj + 1);
                }
            }
        }
        let e: Vec<i32> = e
            .into_iter()
            .map(|v| if v == i32::MIN { 0 } else { v })
            .collect();
        // The term M_ij z_j times 2^(−e[i]): the mantissas multiplied, then one exact shift.
        let zmant: Vec<f64> = z
            .iter()
            .zip(&ez)
            .map(|(&v, &x)| x.map_or(0.0, |x| ldexp(v, -x)))
            .collect();
        let term = |i: usize, j: usize| -> f64 {
            let (Some(ezj), Some(emij)) = (ez[j], exponent(m(i, j))) else {
                return 0.0;
            };
            ldexp(ldexp(m(i, j), -emij) * zmant[j], emij + ezj - e[i])
        };
        let ws: Vec<f64> = w.iter().zip(&e).map(|(&v, &k)| ldexp(v, -k)).collect();
        let mut r: Vec<f64> = q.iter().zip(&e).map(|(&v, &k)| ldexp(v, -k)).collect();
        let mut mag: Vec<f64> = size.iter().zip(&e).map(|(&v, &k)| ldexp(v, -k)).collect();
        for (j, ezj) in ez.iter().enumerate() {
            if ezj.is_none() {
                continue;
            }
            for i in 0..rows {
                let t = term(i, j);
                r[i] += t;
                mag[i] += t.abs();
            }
        }
        let s: Vec<f64> = mag.iter().zip(&ws).map(|(a, b)| a.max(b.abs())).collect();
        let rel = |v: f64, si: f64| if v == 0.0 { 0.0 } else { v / si };
        let mut equation = 0.0f64;
        let mut wneg = 0.0f64;
        for i in 0..rows {
            equation = equation.max(rel((ws[i] - r[i]).abs(), s[i]));
            wneg = wneg.max(rel((-ws[i]).max(0.0), s[i]));
        }
        // The effect of each z_j on the rows it meets, relative to their scales.
        let effect: Vec<f64> = (0..cols)
            .map(|j| {
                if ez[j].is_none() {
                    return 0.0;
                }
                let mut met = false;
                let mut best = 0.0f64;
                for (i, &si) in s.iter().enumerate() {
                    if m(i, j) != 0.0 {
                        met = true;
                        best = best.max(rel(term(i, j).abs(), si));
                    }
                }
                if met {
                    best
                } else {
                    1.0
                }
            })
            .collect();
        let zneg = (0..cols)
            .filter(|&j| z[j] < 0.0)
            .fold(0.0f64, |a, j| a.max(effect[j]));
        let complementarity =
            (0..rows.min(cols)).fold(0.0f64, |a, i| a.max(rel(ws[i].abs(), s[i]).min(effect[i])));
        Self {
            equation,
            feasibility: wneg.max(zneg),
            complementarity,
        }
    }

    /// The point is finite and its residuals are within [`crate::ACCEPT_RESIDUAL`].
    pub(crate) fn accepts(&self, w: &[f64], z: &[f64]) -> bool {
        self.max() <= crate::ACCEPT_RESIDUAL && w.iter().chain(z).all(|v| v.is_finite())
    }
}

/// The sums `q + M z` and their magnitudes over a block of rows.
type RowSums = (Vec<f64>, Vec<f64>);

/// What [`Residual::plain`] found.
enum Plain {
    Done(Residual),
    NotFinite,
    OutOfRange,
}

/// `M` as the residuals read it: rows of a column at a time, or an entry.
pub(crate) trait ColumnSource: Sync {
    /// Entry `(i, j)`.
    fn entry(&self, i: usize, j: usize) -> f64;
    /// Rows `rows` of column `j` into `out` (of the length of `rows`).
    fn column_into(&self, j: usize, rows: std::ops::Range<usize>, out: &mut [f64]);
}

struct MatColumns<'a>(&'a Mat<f64>);

impl ColumnSource for MatColumns<'_> {
    fn entry(&self, i: usize, j: usize) -> f64 {
        self.0[(i, j)]
    }
    fn column_into(&self, j: usize, rows: std::ops::Range<usize>, out: &mut [f64]) {
        out.copy_from_slice(&self.0.col_as_slice(j)[rows]);
    }
}

#[cfg(test)]
mod tests {
    use super::{MatColumns, Residual};
    use faer::Mat;
    use proptest::prelude::*;

    /// The plain sums give the same bits as the rescaled sums they replace where both apply
    /// (the reference is the rescaled evaluation, entry by entry, kept for the ends of the
    /// range): random data over forty orders of magnitude, with zeros in `z` and in `M`,
    /// negative entries and a `w` near `q + M z`.
    fn both(m: &Mat<f64>, q: &[f64], w: &[f64], z: &[f64]) -> (Residual, Residual) {
        let size: Vec<f64> = q.iter().map(|v| v.abs()).collect();
        let shape = (m.nrows(), m.ncols());
        let fast = Residual::of_terms(&MatColumns(m), shape, q, &size, w, z);
        let refr = Residual::rescaled(&|i, j| m[(i, j)], shape, q, &size, w, z);
        (fast, refr)
    }

    fn value() -> impl Strategy<Value = f64> {
        prop_oneof![
            1 => Just(0.0),
            6 => (-1.0f64..1.0, -20i32..20).prop_map(|(a, e)| a * 10f64.powi(e)),
        ]
    }

    proptest! {
        #[test]
        fn plain_sums_equal_the_rescaled_ones(
            n in 1usize..12,
            data in proptest::collection::vec(value(), 12 * 12 + 3 * 12),
            noise in -1e-9f64..1e-9,
        ) {
            let m = Mat::from_fn(n, n, |i, j| data[i * 12 + j]);
            let q: Vec<f64> = (0..n).map(|i| data[144 + i]).collect();
            let z: Vec<f64> = (0..n).map(|i| data[156 + i].abs()).collect();
            let w: Vec<f64> = (0..n)
                .map(|i| {
                    let mz: f64 = (0..n).map(|j| m[(i, j)] * z[j]).sum();
                    (q[i] + mz) * (1.0 + noise) + data[168 + i] * 1e-3
                })
                .collect();
            let (fast, refr) = both(&m, &q, &w, &z);
            let size: Vec<f64> = q.iter().map(|v| v.abs()).collect();
            let plain = Residual::plain(&MatColumns(&m), &q, &size, &w, &z);
            prop_assert!(matches!(plain, super::Plain::Done(_)), "the plain sums are taken");
            prop_assert_eq!(fast.equation.to_bits(), refr.equation.to_bits());
            prop_assert_eq!(fast.feasibility.to_bits(), refr.feasibility.to_bits());
            prop_assert_eq!(fast.complementarity.to_bits(), refr.complementarity.to_bits());
        }
    }

    /// Near the ends of the floating-point range the rescaled sums are taken: a term of
    /// 2^1010 and one of 2^-980 neither overflow nor lose their row (hand values: `w = q + M z`
    /// rounded once per row, so every residual is within one rounding of the row's terms).
    #[test]
    fn the_ends_of_the_range_fall_back_to_the_rescaled_sums() {
        let big = 2f64.powi(1000);
        let tiny = 2f64.powi(-1000);
        let m = Mat::from_fn(2, 2, |i, j| [[big, 0.0], [0.0, tiny]][i][j]);
        let q = [-1.0, 1.0];
        let z = [2f64.powi(10), 2f64.powi(20)];
        let w = [big * z[0] + q[0], tiny * z[1] + q[1]];
        let size: Vec<f64> = q.iter().map(|v| v.abs()).collect();
        let r = Residual::of_terms(&MatColumns(&m), (2, 2), &q, &size, &w, &z);
        let refr = Residual::rescaled(&|i, j| m[(i, j)], (2, 2), &q, &size, &w, &z);
        assert_eq!(r, refr);
        let plain = Residual::plain(&MatColumns(&m), &q, &size, &w, &z);
        assert!(matches!(plain, super::Plain::OutOfRange));
        assert!(r.equation <= f64::EPSILON, "{r:?}");
        assert_eq!(r.feasibility, 0.0);
    }
}
