//! The columns of the pivoting tableau `[E | −M | −g]` over a column-major copy of `M`.
//!
//! Tableau equation: `x − M z − g·t = h`, i.e. `x = h + g·t + M z`, where `t` is the driving
//! variable (the load parameter `p`, Lemke's artificial `z0`, or the tightening being removed).
//! Column indices: `0..n` are `x_i`, `n..2n` are `z_i`, `2n` is the driver.

/// Dense column-major data of one tableau: `M`, the driver direction `g` and the right-hand side `h`.
#[derive(Debug, Clone)]
pub(crate) struct Columns {
    pub n: usize,
    /// `M` column-major: column `j` is `m[j*n..(j+1)*n]`.
    pub m: std::sync::Arc<Vec<f64>>,
    pub g: Vec<f64>,
    pub h: Vec<f64>,
}

impl Columns {
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
