//! Validation and equilibration shared by both methods.

use faer::Mat;

use crate::pivoting::columns::{ColumnStore, Columns};
use crate::pivoting::relations::{DerivedRows, Relations};
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
///
/// The equilibrated copy is the one the pivoting reads. The original `M`, which verification
/// needs, is recovered from it entry by entry ([`Prepared::original_entry`]): the scalings are
/// powers of two, so this is exact unless a scaled entry left the normal range, and only then
/// is a copy of the original kept ([`Prepared::from_owned`]).
pub(crate) struct Prepared {
    pub n: usize,
    pub scaling: Scaling,
    pub m_scaled: std::sync::Arc<ColumnStore>,
    /// Every original entry is recovered exactly from `m_scaled`.
    exact: bool,
    /// The original `M`, kept only when it is not recovered exactly (shared with the
    /// [`Prepared::rescaled`] copies).
    original: Option<std::sync::Arc<Mat<f64>>>,
    /// Rows of `M` that the slack-row pass forms from row relations ([`Prepared::derive_rows`]).
    pub derived: Option<std::sync::Arc<DerivedRows>>,
}

impl Prepared {
    /// The equilibration of `m`, which the caller keeps (nothing of it is held here).
    pub fn new(m: &Mat<f64>) -> Self {
        Self::with_scaling(m, Scaling::equilibrate(m, &[]))
    }

    /// `m` scaled by `scaling`.
    fn with_scaling(m: &Mat<f64>, scaling: Scaling) -> Self {
        let (scaled, exact) = scaling.scale_matrix(m);
        Self {
            n: m.nrows(),
            scaling,
            m_scaled: std::sync::Arc::new(ColumnStore::new(m.nrows(), scaled)),
            exact,
            original: None,
            derived: None,
        }
    }

    /// Lets every tableau of this problem form the rows that `relations` tie instead of
    /// reading them in the slack-row pass ([`DerivedRows`]).
    pub fn derive_rows(&mut self, relations: &Relations) {
        self.derived = DerivedRows::new(self.n, relations).map(std::sync::Arc::new);
    }

    /// The equilibration of `m`, which it takes: one copy of the matrix is held (the
    /// equilibrated one), and the original as well only if it cannot be recovered exactly.
    pub fn from_owned(m: Mat<f64>) -> Self {
        let scaling = Scaling::equilibrate(&m, &[]);
        Self::owning(m, scaling)
    }

    /// `m` scaled by `scaling`, kept only where its entries are not recovered exactly.
    fn owning(m: Mat<f64>, scaling: Scaling) -> Self {
        let mut prep = Self::with_scaling(&m, scaling);
        if !prep.exact {
            prep.original = Some(std::sync::Arc::new(m));
        }
        prep
    }

    /// [`Prepared::from_owned`], each part of the problem that neither `M` nor the rows tied in
    /// `tied` couple to the others raised to the size of the largest part's `loads`
    /// ([`Scaling::raise_parts`]), and the scaling before the raise where it raised any part
    /// (`E M D` is the same on both).
    pub fn from_owned_raising(
        m: Mat<f64>,
        loads: &[&[f64]],
        tied: &[Vec<usize>],
    ) -> (Self, Option<Scaling>) {
        let mut scaling = Scaling::equilibrate(&m, &[]);
        let before = scaling.clone();
        let raised = scaling.raise_parts(&m, loads, tied).iter().any(|&s| s != 0);
        (Self::owning(m, scaling), raised.then_some(before))
    }

    /// The same problem on another `scaling` of the same `E M D` (one of the two
    /// [`Prepared::from_owned_raising`] gives): the scaled matrix, the original where it is
    /// kept and the derived rows are shared (a relation's rows are raised together, so that its derived row is the same).
    pub fn rescaled(&self, scaling: Scaling) -> Self {
        Self {
            n: self.n,
            scaling,
            m_scaled: self.m_scaled.clone(),
            exact: self.exact,
            original: self.original.clone(),
            derived: self.derived.clone(),
        }
    }

    /// Entry `(i, j)` of the original `M`, bit for bit (for a [`Prepared::from_owned`]).
    #[inline]
    pub fn original_entry(&self, i: usize, j: usize) -> f64 {
        match &self.original {
            Some(m) => m[(i, j)],
            None => {
                debug_assert!(self.exact, "the original is recovered exactly");
                self.scaling.original_entry(self.m_scaled.get(i, j), i, j)
            }
        }
    }

    /// Rows `rows` of column `j` of the original `M` into `out`, bit for bit as
    /// [`Prepared::original_entry`] (read from the stored column in one contiguous slice).
    pub fn original_column_into(&self, j: usize, rows: std::ops::Range<usize>, out: &mut [f64]) {
        match &self.original {
            Some(m) => out.copy_from_slice(&m.col_as_slice(j)[rows]),
            None => {
                let (col, neg) = self.m_scaled.col(j);
                let ce = self.scaling.col_exp[j];
                let re = &self.scaling.row_exp[rows.clone()];
                let col = &col[rows];
                let (lo, hi) = re
                    .iter()
                    .fold((i32::MAX, i32::MIN), |(a, b), &r| (a.min(r), b.max(r)));
                if re.is_empty() || (lo + ce >= -1000 && hi + ce <= 1000) {
                    // v·2^−(r + c): one multiplication by an exact power of two, as `ldexp`
                    // makes it in this range (a loop without branches)
                    let sign = if neg { -1.0 } else { 1.0 };
                    for ((o, &v), &r) in out.iter_mut().zip(col).zip(re) {
                        let f = f64::from_bits(((1023 - (r + ce)) as u64) << 52);
                        *o = (sign * v) * f;
                    }
                } else {
                    for ((o, &v), &r) in out.iter_mut().zip(col).zip(re) {
                        let v = if neg { -v } else { v };
                        *o = crate::binary::ldexp(v, -(r + ce));
                    }
                }
            }
        }
    }

    /// The original `M` as a matrix (an `O(n²)` copy; for a [`Prepared::from_owned`]).
    pub fn original_matrix(&self) -> Mat<f64> {
        match &self.original {
            Some(m) => Mat::clone(m),
            None => Mat::from_fn(self.n, self.n, |i, j| self.original_entry(i, j)),
        }
    }

    /// Equilibrated independently of the units of rows and unknowns, each coupled block
    /// brought to the size of its `q` (see [`Scaling::equilibrate_lcp`]).
    pub fn for_lcp(m: &Mat<f64>, q: &[f64]) -> Self {
        let scaling = Scaling::equilibrate_lcp(m, Some(q));
        let (scaled, exact) = scaling.scale_matrix(m);
        Self {
            n: m.nrows(),
            scaling,
            m_scaled: std::sync::Arc::new(ColumnStore::new(m.nrows(), scaled)),
            exact,
            original: None,
            derived: None,
        }
    }

    /// `E M D` as a matrix.
    pub fn matrix(&self) -> Mat<f64> {
        let n = self.n;
        Mat::from_fn(n, n, |i, j| self.m_scaled.get(i, j))
    }

    /// Tableau columns for `x = h + g t + M z` given in original units.
    pub fn columns(&self, h: &[f64], g: &[f64]) -> Columns {
        let mut cols = Columns::new(
            self.n,
            self.m_scaled.clone(),
            self.scaling.scale_rows(h),
            self.scaling.scale_rows(g),
        );
        cols.derived = self.derived.clone();
        cols
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
