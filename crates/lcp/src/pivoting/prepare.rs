//! Validation and equilibration shared by both methods.

use faer::Mat;

use crate::pivoting::columns::Columns;
use crate::pivoting::scaling::Scaling;
use crate::LcpError;

pub(crate) fn check_matrix(m: &Mat<f64>) -> Result<usize, LcpError> {
    let n = m.nrows();
    if n == 0 {
        return Err(LcpError::Empty);
    }
    if m.ncols() != n {
        return Err(LcpError::Dimension(format!(
            "M is {}×{}, it must be square",
            m.nrows(),
            m.ncols()
        )));
    }
    for j in 0..n {
        for i in 0..n {
            if !m[(i, j)].is_finite() {
                return Err(LcpError::NotFinite {
                    what: "M",
                    index: format!("({}, {})", i + 1, j + 1),
                });
            }
        }
    }
    Ok(n)
}

pub(crate) fn check_vector(what: &'static str, v: &[f64], n: usize) -> Result<(), LcpError> {
    if v.len() != n {
        return Err(LcpError::Dimension(format!(
            "{what} has {} entries, M has order {n}",
            v.len()
        )));
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(LcpError::NotFinite {
            what,
            index: format!("[{}]", i + 1),
        });
    }
    Ok(())
}

/// The equilibrated problem: scaled `M` and the scalings.
pub(crate) struct Prepared {
    pub n: usize,
    pub scaling: Scaling,
    pub m_scaled: std::sync::Arc<Vec<f64>>,
}

impl Prepared {
    pub fn new(m: &Mat<f64>) -> Self {
        let scaling = Scaling::equilibrate(m, &[]);
        let m_scaled = std::sync::Arc::new(scaling.scale_matrix(m));
        Self {
            n: m.nrows(),
            scaling,
            m_scaled,
        }
    }

    /// Equilibrated independently of the units of rows and unknowns, each coupled block
    /// brought to the size of its `q` (see [`Scaling::equilibrate_lcp`]).
    pub fn for_lcp(m: &Mat<f64>, q: &[f64]) -> Self {
        let scaling = Scaling::equilibrate_lcp(m, Some(q));
        let m_scaled = std::sync::Arc::new(scaling.scale_matrix(m));
        Self {
            n: m.nrows(),
            scaling,
            m_scaled,
        }
    }

    /// `E M D` as a matrix.
    pub fn matrix(&self) -> Mat<f64> {
        let n = self.n;
        Mat::from_fn(n, n, |i, j| self.m_scaled[j * n + i])
    }

    /// Tableau columns for `x = h + g t + M z` given in original units.
    pub fn columns(&self, h: &[f64], g: &[f64]) -> Columns {
        Columns::new(
            self.n,
            self.m_scaled.clone(),
            self.scaling.scale_rows(h),
            self.scaling.scale_rows(g),
        )
    }

    /// Unscaled `(x, z)` from basic values by slot.
    pub fn unscale(&self, slot_var: &[usize], beta: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.n;
        let mut x = vec![0.0; n];
        let mut z = vec![0.0; n];
        for (&v, &b) in slot_var.iter().zip(beta) {
            if v < n {
                x[v] = b;
            } else if v < 2 * n {
                z[v - n] = b;
            }
        }
        (self.scaling.unscale_x(&x), self.scaling.unscale_z(&z))
    }
}
