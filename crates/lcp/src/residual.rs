//! Verification of a solution from the original data.

use faer::Mat;

/// Verified residuals of a solution of `w = q + M z`, all relative to the data's scale.
///
/// * `equation` = `‖w − q − Mz‖∞ / s_w`,
/// * `feasibility` = largest violation of `w ≥ 0` (over `s_w`) or `z ≥ 0` (over `‖z‖∞`),
/// * `complementarity` = `max |w_i z_i| / (s_w ‖z‖∞)`,
///
/// where `s_w = max(‖q‖∞, ‖|M||z|‖∞, ‖w‖∞)`.
///
/// The sums are formed on data rescaled by powers of two (exact), so they neither overflow nor
/// underflow whatever the magnitudes (`M` of `1e300` times `z` of `1e10` is no infinity). A
/// non-finite number in `w` or `z` makes every residual infinite: such a point is never accepted.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Residual {
    /// Relative residual of the equation.
    pub equation: f64,
    /// Relative violation of the sign conditions.
    pub feasibility: f64,
    /// Relative violation of complementarity.
    pub complementarity: f64,
}

/// The binary exponent `e` of `x` with `2^e ≤ |x| < 2^(e+1)` (`None` for zero or non-finite).
pub(crate) fn exponent(x: f64) -> Option<i32> {
    if x == 0.0 || !x.is_finite() {
        return None;
    }
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    if biased > 0 {
        return Some(biased - 1023);
    }
    // Subnormal: the position of the leading mantissa bit.
    let mant = bits & ((1u64 << 52) - 1);
    Some(-1074 + (63 - mant.leading_zeros() as i32))
}

/// `x · 2^k`, exact unless the result leaves the normal range.
pub(crate) fn ldexp(mut x: f64, mut k: i32) -> f64 {
    let step = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    while k > 1000 {
        x *= step(1000);
        k -= 1000;
    }
    while k < -1000 {
        x *= step(-1000);
        k += 1000;
    }
    x * step(k)
}

fn max_abs(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(0.0f64, |a, b| a.max(b.abs()))
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

    /// Residuals of `(w, z)` for `w = q + M z`.
    pub fn of(m: &Mat<f64>, q: &[f64], w: &[f64], z: &[f64]) -> Self {
        let n = q.len();
        if w.iter().chain(z).chain(q).any(|v| !v.is_finite()) {
            return Self::unverifiable();
        }
        // Powers of two: e_m for M, e_z for z, e_s for the force side (q, w, |M||z|).
        let mmax = (0..m.ncols()).fold(0.0f64, |a, j| {
            a.max(max_abs((0..m.nrows()).map(|i| m[(i, j)])))
        });
        if !mmax.is_finite() {
            return Self::unverifiable();
        }
        let e_m = exponent(mmax).unwrap_or(0);
        let e_z = exponent(max_abs(z.iter().copied())).unwrap_or(0);
        let e_qw = exponent(max_abs(q.iter().chain(w).copied()));
        let e_mz = e_m + e_z + 1;
        let e_s = e_qw.map_or(e_mz, |e| e.max(e_mz));
        // Everything below is the original data times 2^(−e_s) (w, q, Mz) or 2^(−e_z) (z).
        let zs: Vec<f64> = z.iter().map(|&v| ldexp(v, -e_z)).collect();
        let ws: Vec<f64> = w.iter().map(|&v| ldexp(v, -e_s)).collect();
        let mut r: Vec<f64> = q.iter().map(|&v| ldexp(v, -e_s)).collect();
        let mut mag: Vec<f64> = r.iter().map(|v| v.abs()).collect();
        let shift = e_m + e_z - e_s;
        for (j, &zj) in zs.iter().enumerate() {
            if zj == 0.0 {
                continue;
            }
            for i in 0..n {
                let t = ldexp(ldexp(m[(i, j)], -e_m) * zj, shift);
                r[i] += t;
                mag[i] += t.abs();
            }
        }
        let tiny = f64::MIN_POSITIVE;
        let sw = mag
            .iter()
            .chain(ws.iter())
            .fold(0.0f64, |a, b| a.max(b.abs()))
            .max(tiny);
        let sz = max_abs(zs.iter().copied()).max(tiny);
        let equation = ws
            .iter()
            .zip(&r)
            .fold(0.0f64, |a, (wi, ri)| a.max((wi - ri).abs()))
            / sw;
        let wneg = ws.iter().fold(0.0f64, |a, &b| a.max(-b)) / sw;
        let zneg = zs.iter().fold(0.0f64, |a, &b| a.max(-b)) / sz;
        let complementarity = ws
            .iter()
            .zip(&zs)
            .fold(0.0f64, |a, (wi, zi)| a.max((wi * zi).abs()))
            / sw
            / sz;
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
