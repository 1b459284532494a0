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

/// Dense column-major data of one tableau: `M`, the driver direction `g` and the right-hand side `h`.
#[derive(Debug, Clone)]
pub(crate) struct Columns {
    pub n: usize,
    /// `M` column-major: column `j` is `m[j*n..(j+1)*n]`.
    pub m: std::sync::Arc<Vec<f64>>,
    pub g: Vec<f64>,
    pub h: Vec<f64>,
    /// Exponent of the scale of `h` (see the module documentation).
    pub eh: i32,
    /// Exponent of the scale of `g`.
    pub eg: i32,
}

impl Columns {
    /// Builds the columns from equilibrated `h` and `g`, each divided by its power-of-two scale.
    pub fn new(n: usize, m: std::sync::Arc<Vec<f64>>, h: Vec<f64>, g: Vec<f64>) -> Self {
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
        Self { n, m, g, h, eh, eg }
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

    pub fn m_col(&self, j: usize) -> &[f64] {
        &self.m[j * self.n..(j + 1) * self.n]
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
            -self.m[(col - n) * n + i]
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
            let c = self.m_col(col - n);
            for (o, v) in out.iter_mut().zip(c) {
                *o -= s * v;
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
