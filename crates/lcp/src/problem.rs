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
    /// The values of every variable (`x`, then `z`, then `p`; zero where non-basic) on the basis
    /// whose basic variables are marked in `basic` (length `2n + 1`, `n` of them), from a dense
    /// LU with full pivoting of its equations `x_B − M[:, z_B] z_B − d·p = q0`: an independent
    /// check of a breakpoint (`O(n³)`). `None` when `basic` does not mark `n` variables.
    pub fn basis_solution(&self, basic: &[bool]) -> Option<Vec<f64>> {
        use faer::linalg::solvers::Solve;
        let n = self.q0.len();
        let vars: Vec<usize> = (0..=2 * n).filter(|&v| basic[v]).collect();
        if vars.len() != n || basic.len() != 2 * n + 1 {
            return None;
        }
        let a = Mat::<f64>::from_fn(n, n, |i, c| {
            let v = vars[c];
            if v < n {
                f64::from(v == i)
            } else if v < 2 * n {
                -self.m[(i, v - n)]
            } else {
                -self.d[i]
            }
        });
        let rhs = Mat::<f64>::from_fn(n, 1, |i, _| self.q0[i]);
        let sol = a.full_piv_lu().solve(&rhs);
        let mut out = vec![0.0; 2 * n + 1];
        for (c, &v) in vars.iter().enumerate() {
            out[v] = sol[(c, 0)];
        }
        Some(out)
    }

    /// The right-hand side `q0 + p·d` at load `p`.
    pub fn q_at(&self, p: f64) -> Vec<f64> {
        self.q0
            .iter()
            .zip(&self.d)
            .map(|(q, d)| q + p * d)
            .collect()
    }
}
