//! Problem data: the standard LCP and the parametric LCP.

use faer::Mat;

/// A standard linear complementarity problem: find `z` with
/// `w = M z + q ≥ 0`, `z ≥ 0`, `wᵀz = 0`.
#[derive(Debug, Clone)]
pub struct Lcp {
    /// The `n × n` matrix `M`.
    pub m: Mat<f64>,
    /// The vector `q` (length `n`).
    pub q: Vec<f64>,
}

/// A parametric linear complementarity problem: for a load parameter `p ≥ 0`, find `z` with
/// `x = q0 + p·d + M z ≥ 0`, `z ≥ 0`, `xᵀz = 0`.
#[derive(Debug, Clone)]
pub struct ParametricLcp {
    /// The `n × n` matrix `M`.
    pub m: Mat<f64>,
    /// The constant part `q0` (length `n`).
    pub q0: Vec<f64>,
    /// The direction `d` multiplied by the parameter (length `n`).
    pub d: Vec<f64>,
}

impl ParametricLcp {
    /// The right-hand side `q0 + p·d` at load `p`.
    pub fn q_at(&self, p: f64) -> Vec<f64> {
        self.q0
            .iter()
            .zip(&self.d)
            .map(|(q, d)| q + p * d)
            .collect()
    }
}
