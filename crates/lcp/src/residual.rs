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
        Self::of_terms(&|i, j| m[(i, j)], (m.nrows(), m.ncols()), q, &size, w, z)
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
        Self::of_parametric_with(&|i, j| m[(i, j)], (m.nrows(), m.ncols()), q0, d, p, x, z)
    }

    /// [`Residual::of_parametric`] with `M` given entry by entry (`shape` = rows, columns).
    pub(crate) fn of_parametric_with(
        m: &impl Fn(usize, usize) -> f64,
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
    fn of_terms(
        m: &impl Fn(usize, usize) -> f64,
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
