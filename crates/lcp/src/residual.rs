//! Verification of a solution from the original data.

use faer::Mat;

/// Verified residuals of a solution of `w = q + M z`, all relative to the data's scale.
///
/// * `equation` = `‖w − q − Mz‖∞ / s_w`,
/// * `feasibility` = largest violation of `w ≥ 0` (over `s_w`) or `z ≥ 0` (over `‖z‖∞`),
/// * `complementarity` = `max |w_i z_i| / (s_w ‖z‖∞)`,
///
/// where `s_w = max(‖q‖∞, ‖|M||z|‖∞, ‖w‖∞)`.
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
    /// The largest of the three.
    pub fn max(&self) -> f64 {
        self.equation
            .max(self.feasibility)
            .max(self.complementarity)
    }

    /// Residuals of `(w, z)` for `w = q + M z`.
    pub fn of(m: &Mat<f64>, q: &[f64], w: &[f64], z: &[f64]) -> Self {
        let n = q.len();
        let mut r = q.to_vec();
        let mut mag: Vec<f64> = q.iter().map(|v| v.abs()).collect();
        for (j, &zj) in z.iter().enumerate() {
            if zj == 0.0 {
                continue;
            }
            for i in 0..n {
                let t = m[(i, j)] * zj;
                r[i] += t;
                mag[i] += t.abs();
            }
        }
        let tiny = f64::MIN_POSITIVE;
        let sw = mag
            .iter()
            .chain(w.iter())
            .fold(0.0f64, |a, b| a.max(b.abs()))
            .max(tiny);
        let sz = z.iter().fold(0.0f64, |a, b| a.max(b.abs())).max(tiny);
        let equation = w
            .iter()
            .zip(&r)
            .fold(0.0f64, |a, (wi, ri)| a.max((wi - ri).abs()))
            / sw;
        let wneg = w.iter().fold(0.0f64, |a, &b| a.max(-b)) / sw;
        let zneg = z.iter().fold(0.0f64, |a, &b| a.max(-b)) / sz;
        let complementarity = w
            .iter()
            .zip(z)
            .fold(0.0f64, |a, (wi, zi)| a.max((wi * zi).abs()))
            / (sw * sz);
        Self {
            equation,
            feasibility: wneg.max(zneg),
            complementarity,
        }
    }
}
