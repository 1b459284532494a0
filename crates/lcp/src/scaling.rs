//! Equilibration of the LCP by powers of two, so that scaling loses no digit.
//!
//! `x̂ = E x`, `z = D ẑ` keep complementarity (positive diagonal scalings) and turn
//! `x = q + M z` into `x̂ = E q + (E M D) ẑ`. Ruiz's iteration balances the largest entry of every
//! row and column of `E M D` to about one, so that relative tolerances mean the same thing in
//! every row whatever the units (forces and displacements of a steel structure differ by 10¹¹).

use faer::Mat;

/// Diagonal scalings `E` (rows) and `D` (columns), powers of two.
#[derive(Debug, Clone)]
pub(crate) struct Scaling {
    pub row: Vec<f64>,
    pub col: Vec<f64>,
}

impl Scaling {
    pub fn equilibrate(m: &Mat<f64>) -> Self {
        let n = m.nrows();
        let mut row = vec![1.0f64; n];
        let mut col = vec![1.0f64; n];
        for _ in 0..6 {
            let mut rmax = vec![0.0f64; n];
            for j in 0..n {
                for i in 0..n {
                    let v = (m[(i, j)] * row[i] * col[j]).abs();
                    rmax[i] = rmax[i].max(v);
                }
            }
            for i in 0..n {
                if rmax[i] > 0.0 {
                    row[i] /= rmax[i].sqrt();
                }
            }
            for j in 0..n {
                let mut cmax = 0.0f64;
                for i in 0..n {
                    cmax = cmax.max((m[(i, j)] * row[i] * col[j]).abs());
                }
                if cmax > 0.0 {
                    col[j] /= cmax.sqrt();
                }
            }
        }
        let pow2 = |v: f64| 2f64.powi(v.log2().round() as i32);
        Self {
            row: row.into_iter().map(pow2).collect(),
            col: col.into_iter().map(pow2).collect(),
        }
    }

    /// `E M D` in column-major order.
    pub fn scale_matrix(&self, m: &Mat<f64>) -> Vec<f64> {
        let n = m.nrows();
        let mut out = vec![0.0; n * n];
        for j in 0..n {
            let c = self.col[j];
            for i in 0..n {
                out[j * n + i] = m[(i, j)] * self.row[i] * c;
            }
        }
        out
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
