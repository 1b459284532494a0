//! A basis of the tableau `[E | −M | −g]` kept in revised form.
//!
//! Basic slack columns are unit vectors, so the basis matrix `B` is block triangular: with `S`
//! the basic non-slack columns (`z`'s and the driver) and `R` the rows whose slack is *not*
//! basic (`|S| = |R| = k`), only the kernel `K = A[R, S]` (`k × k`) needs an inverse. Solving
//! with `B` costs `O(k²)` for the kernel plus `O(n·k)` for the slack rows, and each pivot
//! updates `K⁻¹` by a rank-one formula in `O(k²)`. `K⁻¹` is recomputed from the data by a
//! fresh LU factorisation (`faer`) every few pivots and whenever its accuracy degrades.

use rayon::prelude::*;

use crate::pivoting::columns::Columns;
use crate::pivoting::kernel::{KernelInverse, RefactorWork};
use crate::pivoting::simd::{self, dot};

/// Revised representation of a complementary basis.
#[derive(Debug, Clone)]
pub(crate) struct Basis {
    n: usize,
    /// Column held by each slot (tableau row).
    pub slot_var: Vec<usize>,
    /// Slot of each column (`usize::MAX` when non-basic); length `2n + 1`.
    pub var_slot: Vec<usize>,
    /// Basic non-slack columns.
    s_cols: Vec<usize>,
    /// Rows whose slack is non-basic.
    r_rows: Vec<usize>,
    /// Position of a row in `r_rows` (`usize::MAX` when its slack is basic).
    r_pos: Vec<usize>,
    /// Position of a column in `s_cols` (`usize::MAX` otherwise).
    s_pos: Vec<usize>,
    /// `K⁻¹`: rows follow `s_cols`, columns follow `r_rows`.
    kinv: KernelInverse,
    /// Changes so far ([`Basis::version`]).
    version: u64,
    /// The refactorisations' memory.
    work: RefactorWork,
}

/// The kernel matrix was numerically singular.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SingularBasis;

const NONE: usize = usize::MAX;

impl Basis {
    /// The slack basis `B = E`.
    pub fn slack(n: usize) -> Self {
        let mut var_slot = vec![NONE; 2 * n + 1];
        for (i, v) in var_slot.iter_mut().take(n).enumerate() {
            *v = i;
        }
        Self {
            n,
            slot_var: (0..n).collect(),
            var_slot,
            s_cols: Vec::new(),
            r_rows: Vec::new(),
            r_pos: vec![NONE; n],
            s_pos: vec![NONE; 2 * n + 1],
            kinv: KernelInverse::default(),
            version: 0,
            work: RefactorWork::default(),
        }
    }

    /// A basis holding the given column in every slot; the kernel is factorised from `cols`.
    pub fn from_slots(cols: &Columns, slot_var: Vec<usize>) -> Result<Self, SingularBasis> {
        let n = cols.n;
        let mut b = Self::slack(n);
        b.slot_var = slot_var;
        b.var_slot = vec![NONE; 2 * n + 1];
        for (s, &v) in b.slot_var.iter().enumerate() {
            b.var_slot[v] = s;
        }
        for (i, &slot) in b.var_slot.iter().take(n).enumerate() {
            if slot == NONE {
                b.r_pos[i] = b.r_rows.len();
                b.r_rows.push(i);
            }
        }
        for &v in &b.slot_var {
            if v >= n {
                b.s_pos[v] = b.s_cols.len();
                b.s_cols.push(v);
            }
        }
        b.refactor(cols)?;
        Ok(b)
    }

    pub fn kernel_size(&self) -> usize {
        self.s_cols.len()
    }

    pub fn is_basic(&self, col: usize) -> bool {
        self.var_slot[col] != NONE
    }

    /// Recomputes `K⁻¹` from the data by an LU factorisation of `K = A[R, S]`.
    pub fn refactor(&mut self, cols: &Columns) -> Result<(), SingularBasis> {
        self.new_version();
        let k = self.s_cols.len();
        if k == 0 {
            self.kinv.clear();
            return Ok(());
        }
        // Factorised in place by faer's LU with partial pivoting; the inverse is formed from
        // the factors straight into the kernel inverse's buffer. At the refactorisation's peak
        // `K`'s factors, the old inverse's buffer and faer's scratch: three `k × k` matrices
        // instead of the five of `partial_piv_lu` and `inverse`.
        // The kernel's copy and faer's scratch are kept from one refactorisation to the next.
        let (r_rows, s_cols) = (&self.r_rows, &self.s_cols);
        let (fwd, bwd) = self
            .work
            .lu_in_place(k, |a, b| cols.entry(r_rows[a], s_cols[b]));
        let (lu, scratch) = self.work.factors(k);
        let perm = faer::perm::PermRef::new_checked(&fwd, &bwd, k);
        let umax = (0..k).map(|i| lu[(i, i)].abs()).fold(0.0f64, f64::max);
        let umin = (0..k)
            .map(|i| lu[(i, i)].abs())
            .fold(f64::INFINITY, f64::min);
        if umin.is_nan() || umin <= umax * 1e-14 || !umin.is_finite() {
            return Err(SingularBasis);
        }
        // K⁻¹ has rows indexed like the columns of K (S) and columns like its rows (R).
        self.kinv.assign_lu_inverse(lu, perm, scratch);
        Ok(())
    }

    /// `y = B⁻¹ v`, indexed by slot.
    pub fn solve(&self, cols: &Columns, v: &[f64]) -> Vec<f64> {
        let vr: Vec<f64> = self.r_rows.iter().map(|&r| v[r]).collect();
        let ys = self.kernel_solve(&vr);
        self.with_slack_rows(cols, v, &ys)
    }

    /// `B⁻¹ v` by slot from its kernel part `y_S`: the slack rows `v − A[:, S] y_S`.
    fn with_slack_rows(&self, cols: &Columns, v: &[f64], ys: &[f64]) -> Vec<f64> {
        let mut tmp = v.to_vec();
        self.subtract_kernel_columns(cols, ys, &mut tmp);
        self.scatter(ys, &tmp, self.n)
    }

    /// `v_R − K y_S` from the data (`O(k²)`).
    fn kernel_residual(&self, cols: &Columns, vr: &[f64], ys: &[f64]) -> Vec<f64> {
        let mut r = vr.to_vec();
        for (&c, &y) in self.s_cols.iter().zip(ys) {
            if y != 0.0 {
                for (ra, &row) in r.iter_mut().zip(&self.r_rows) {
                    *ra -= cols.entry(row, c) * y;
                }
            }
        }
        r
    }

    /// `y = B⁻¹ v` with the kernel part refined from the data: up to two steps of
    /// `y_S += K⁻¹ (v_R − K y_S)` in working precision (`O(k²)` each, `K`'s entries read from
    /// the columns), each kept only if it leaves a smaller residual. A product with the explicit
    /// inverse is not backward stable: on a large, badly conditioned kernel (the 700-bearing
    /// beam far along its path) the rows of `K y = v` it leaves are off by `10⁻¹⁰` of their
    /// terms, and a reported solution measured row by row can then fail its verification;
    /// refined, they are off by round-off (`10⁻¹⁵`). For the values a fresh basis is formed to
    /// report; the path's own solves are not refined.
    pub fn solve_refined(&self, cols: &Columns, v: &[f64]) -> Vec<f64> {
        let vr: Vec<f64> = self.r_rows.iter().map(|&r| v[r]).collect();
        let residual = |ys: &[f64]| self.kernel_residual(cols, &vr, ys);
        let largest = |r: &[f64]| r.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let mut ys = self.kernel_solve(&vr);
        let mut r = residual(&ys);
        // Each step is kept only if it leaves a smaller residual (a kernel too badly
        // conditioned for the inverse's corrections would otherwise wander).
        for _ in 0..2 {
            let before = largest(&r);
            if before == 0.0 || !r.iter().all(|v| v.is_finite()) {
                break;
            }
            let next: Vec<f64> = ys
                .iter()
                .zip(self.kernel_solve(&r))
                .map(|(y, d)| y + d)
                .collect();
            let r_next = residual(&next);
            if !r_next.iter().all(|v| v.is_finite()) || largest(&r_next) >= before {
                break;
            }
            (ys, r) = (next, r_next);
        }
        self.with_slack_rows(cols, v, &ys)
    }

    /// `(B⁻¹ v)` at the given slots only: the kernel solve `O(k²)`, then `O(k)` per slack row.
    pub fn values_at(&self, cols: &Columns, v: &[f64], slots: &[usize]) -> Vec<f64> {
        let vr: Vec<f64> = self.r_rows.iter().map(|&r| v[r]).collect();
        let ys = self.kernel_solve(&vr);
        slots
            .iter()
            .map(|&slot| {
                let var = self.slot_var[slot];
                if var < self.n {
                    let mut x = v[var];
                    for (&c, &y) in self.s_cols.iter().zip(&ys) {
                        x -= cols.entry(var, c) * y;
                    }
                    x
                } else {
                    ys[self.s_pos[var]]
                }
            })
            .collect()
    }

    /// `α = B⁻¹ A[:, col]`, indexed by slot.
    pub fn ftran(&self, cols: &Columns, col: usize) -> Vec<f64> {
        self.ftran_checked(cols, col).0
    }

    /// `α = B⁻¹ A[:, col]` and the relative residual of the kernel solve, which the slack-row
    /// pass yields for free: on the rows of `R`, `A[:, col] − A[:, S] y_S` is `u_R − K y_S`.
    pub fn ftran_checked(&self, cols: &Columns, col: usize) -> (Vec<f64>, f64) {
        self.ftran_checked_with(cols, col, None)
    }

    /// [`Basis::ftran_checked`] with the kernel solve of a structural `col` given (from
    /// [`Basis::pivot_solving`] in this version of the basis).
    pub fn ftran_checked_with(
        &self,
        cols: &Columns,
        col: usize,
        solved: Option<Vec<f64>>,
    ) -> (Vec<f64>, f64) {
        let (alpha, rel, _) = self.ftran_and_values(cols, col, solved, None);
        (alpha, rel)
    }

    /// [`Basis::ftran_checked_with`], and with `values = Some(…)` also the basic values `B⁻¹h`
    /// from the data (`h` the columns' right-hand side), their slack rows formed in the same
    /// pass over the kernel's columns of `M` as the entering column's: the same bits as
    /// [`Basis::solve`]`(cols, &cols.h)` (each sum formed as alone, [`simd::add_columns2`]), at
    /// the cost of a kernel solve and not of another pass. `values = Some(Some(y))` gives that
    /// kernel solve `K⁻¹ h_R` (from [`Basis::pivot_solving`] in this version of the basis).
    pub fn ftran_and_values(
        &self,
        cols: &Columns,
        col: usize,
        solved: Option<Vec<f64>>,
        values: Option<Option<Vec<f64>>>,
    ) -> (Vec<f64>, f64, Option<Vec<f64>>) {
        let n = self.n;
        let mut tmp = vec![0.0; n];
        let (ys, uscale) = if col < n {
            let b = self.r_pos[col];
            debug_assert!(b != NONE, "entering slack must be non-basic");
            tmp[col] = 1.0;
            (self.kinv.col(b).to_vec(), 1.0)
        } else {
            cols.axpy_col(&mut tmp, 1.0, col);
            let ur: Vec<f64> = self.r_rows.iter().map(|&r| tmp[r]).collect();
            let s = ur.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            match solved {
                Some(ys) => {
                    debug_assert_eq!(ys.len(), ur.len());
                    (ys, s)
                }
                None => (self.kernel_solve(&ur), s),
            }
        };
        let fresh = if let Some(solved_h) = values {
            let yh = solved_h.unwrap_or_else(|| {
                let hr: Vec<f64> = self.r_rows.iter().map(|&r| cols.h[r]).collect();
                self.kernel_solve(&hr)
            });
            let mut th = cols.h.clone();
            self.subtract_kernel_columns2(cols, &ys, &mut tmp, &yh, &mut th);
            Some(self.scatter(&yh, &th, n))
        } else {
            self.subtract_kernel_columns(cols, &ys, &mut tmp);
            None
        };
        let resid = self.r_rows.iter().fold(0.0f64, |a, &r| a.max(tmp[r].abs()));
        let yscale = ys.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let scale = uscale + yscale;
        let rel = if scale > 0.0 { resid / scale } else { 0.0 };
        (self.scatter(&ys, &tmp, n), rel, fresh)
    }

    /// `|K⁻¹| |A[R, col]|` by position in `S`: the size of the terms whose sums form the kernel
    /// part of `B⁻¹ A[:, col]`, against which its entries are round-off or not (`O(k²)`).
    pub fn kernel_terms(&self, cols: &Columns, col: usize) -> Vec<f64> {
        let k = self.s_cols.len();
        let mut out = vec![0.0; k];
        for (b, &r) in self.r_rows.iter().enumerate() {
            let u = cols.entry(r, col).abs();
            if u != 0.0 {
                for (o, g) in out.iter_mut().zip(self.kinv.col(b)) {
                    *o += u * g.abs();
                }
            }
        }
        out
    }

    /// Position of a basic non-slack column in `S` (`None` for a slack or a non-basic column).
    pub fn kernel_pos(&self, col: usize) -> Option<usize> {
        let a = self.s_pos[col];
        (a != NONE).then_some(a)
    }

    fn kernel_solve(&self, vr: &[f64]) -> Vec<f64> {
        self.kinv.solve(vr)
    }

    /// `tmp −= A[:, S] y_S`, four columns per pass over `tmp`.
    fn subtract_kernel_columns(&self, cols: &Columns, ys: &[f64], tmp: &mut [f64]) {
        let zcols = self.kernel_columns(cols, ys, tmp);
        // A[:, z_j] = −M[:, j], so tmp −= A y means tmp += M[:, j]·y; the rows that row
        // relations tie are formed from them after the pass
        // (`relations::DerivedRows`).
        let derived = cols.derived.as_deref();
        let before = derived.map(|d| d.before(tmp));
        add_columns_pooled(cols, &zcols, &mut tmp[..derived.map_or(self.n, |d| d.read)]);
        if let (Some(d), Some(b)) = (derived, before) {
            d.derive(tmp, &b);
        }
    }

    /// The stored columns of `M` and their weights for `tmp −= A[:, S] y_S`, in the order of
    /// `S` without the zero weights; the driver's column, if basic, is subtracted from `tmp`
    /// here.
    fn kernel_columns(&self, cols: &Columns, ys: &[f64], tmp: &mut [f64]) -> Vec<(usize, f64)> {
        let n = self.n;
        let mut zcols: Vec<(usize, f64)> = Vec::with_capacity(ys.len());
        for (&c, &y) in self.s_cols.iter().zip(ys) {
            if y == 0.0 {
                continue;
            }
            if c >= n && c < 2 * n {
                // A negated stored column: (−y)·b is y·(−b) exactly.
                let (s, neg) = cols.m.col_index(c - n);
                zcols.push((s, if neg { -y } else { y }));
            } else {
                cols.axpy_col(tmp, -y, c);
            }
        }
        zcols
    }

    /// [`Basis::subtract_kernel_columns`] for two vectors, in one pass over the columns when
    /// both have the same columns (no zero weight in one and not in the other); each result is
    /// the same bits as alone.
    fn subtract_kernel_columns2(
        &self,
        cols: &Columns,
        y1: &[f64],
        tmp1: &mut [f64],
        y2: &[f64],
        tmp2: &mut [f64],
    ) {
        let z1 = self.kernel_columns(cols, y1, tmp1);
        let z2 = self.kernel_columns(cols, y2, tmp2);
        let derived = cols.derived.as_deref();
        let n = derived.map_or(self.n, |d| d.read);
        let before = derived.map(|d| (d.before(tmp1), d.before(tmp2)));
        if z1.len() == z2.len() && z1.iter().zip(&z2).all(|(a, b)| a.0 == b.0) {
            add_columns_pooled2(cols, &z1, &z2, &mut tmp1[..n], &mut tmp2[..n]);
        } else {
            add_columns_pooled(cols, &z1, &mut tmp1[..n]);
            add_columns_pooled(cols, &z2, &mut tmp2[..n]);
        }
        if let (Some(d), Some((b1, b2))) = (derived, before) {
            d.derive(tmp1, &b1);
            d.derive(tmp2, &b2);
        }
    }

    fn scatter(&self, ys: &[f64], tmp: &[f64], n: usize) -> Vec<f64> {
        let mut out = vec![0.0; n];
        for (i, &t) in tmp.iter().enumerate() {
            let slot = self.var_slot[i];
            if slot != NONE {
                out[slot] = t;
            }
        }
        for (&c, &y) in self.s_cols.iter().zip(ys) {
            out[self.var_slot[c]] = y;
        }
        out
    }

    /// What [`Basis::inverse_entry_terms`] needs of a slot: for a slack row, `A[i, S]`.
    pub fn inverse_row_data(&self, cols: &Columns, slot: usize) -> Vec<f64> {
        let var = self.slot_var[slot];
        if var < self.n {
            self.s_cols.iter().map(|&c| cols.entry(var, c)).collect()
        } else {
            Vec::new()
        }
    }

    /// A bound-like scale of the entries of the row of `B⁻¹` at `slot` (for tolerances).
    pub fn inverse_row_scale(&self, slot: usize, data: &[f64]) -> f64 {
        let g = self.kinv.max_entry();
        if self.slot_var[slot] < self.n {
            1.0 + g * data.iter().map(|v| v.abs()).sum::<f64>()
        } else {
            g
        }
    }

    /// Column `r` of `K⁻¹` (a row whose slack is non-basic) refined once from the data,
    /// `y += K⁻¹(e_r − K y)` (`O(k²)`): the updated inverse satisfies `K y = e_r` only to its
    /// drift, and entries of `B⁻¹` that the data make equal then differ by that residual.
    pub fn kernel_column_refined(&self, cols: &Columns, r: usize) -> Option<Vec<f64>> {
        let b = self.r_pos[r];
        if b == NONE {
            return None;
        }
        let y = self.kinv.col(b).to_vec();
        let mut unit = vec![0.0; y.len()];
        unit[b] = 1.0;
        let res = self.kernel_residual(cols, &unit, &y);
        let corr = self.kernel_solve(&res);
        Some(y.iter().zip(&corr).map(|(a, c)| a + c).collect())
    }

    /// [`Basis::inverse_entry_terms`] of a slack row with `y` the column of `K⁻¹` for row `r`
    /// ([`Basis::kernel_column_refined`]).
    pub fn slack_entry_terms(&self, slot: usize, r: usize, data: &[f64], y: &[f64]) -> (f64, f64) {
        let var = self.slot_var[slot];
        let unit = if r == var { 1.0 } else { 0.0 };
        (unit - dot(data, y), unit + column_terms(data, y))
    }

    /// Entry `(slot, r)` of `B⁻¹` in `O(k)` and the size of the terms it is formed from (its
    /// round-off is relative to those), with `data` from [`Basis::inverse_row_data`]. For a
    /// slack row the terms are `|δ| + Σ_s |A[i, s]| |K⁻¹[s, b]|`; an entry of `K⁻¹` itself is
    /// measured against the inverse's largest entry.
    pub fn inverse_entry_terms(&self, slot: usize, r: usize, data: &[f64]) -> (f64, f64) {
        let var = self.slot_var[slot];
        let b = self.r_pos[r];
        if var < self.n {
            let unit = if r == var { 1.0 } else { 0.0 };
            if b == NONE {
                (unit, unit)
            } else {
                let col = self.kinv.col(b);
                (unit - dot(data, col), unit + column_terms(data, col))
            }
        } else if b == NONE {
            (0.0, 0.0)
        } else {
            (self.kinv.get(self.s_pos[var], b), self.kinv.max_entry())
        }
    }

    /// Replaces the column at `slot` by `entering`, given `alpha = B⁻¹ A[:, entering]`.
    pub fn pivot(&mut self, cols: &Columns, entering: usize, slot: usize, alpha: &[f64]) {
        self.pivot_solving(cols, entering, slot, alpha, None, false);
    }

    /// [`Basis::pivot`], and kernel solves of the new basis formed in the pass that updates
    /// `K⁻¹` (the same bits as [`KernelInverse::solve`] after it), which a solve right after
    /// the update would read `K⁻¹` once more for:
    /// * for a structural column `next`, the kernel part of `B⁻¹ A[:, next]`, when the leaving
    ///   variable is a slack (bordering or replacing a row: the next entering column is then
    ///   that slack's structural complement), for [`Basis::ftran_checked_with`];
    /// * with `values`, `K⁻¹ h_R` (`h` the columns' right-hand side), the kernel part of the
    ///   basic values from the data, for [`Basis::ftran_and_values`] (not when a column and a
    ///   row are removed: that update moves them).
    ///
    /// Either is `None` where it is not formed; use them while [`Basis::version`] is unchanged.
    pub fn pivot_solving(
        &mut self,
        cols: &Columns,
        entering: usize,
        slot: usize,
        alpha: &[f64],
        next: Option<usize>,
        values: bool,
    ) -> (Option<Vec<f64>>, Option<Vec<f64>>) {
        let n = self.n;
        let leaving = self.slot_var[slot];
        let enter_slack = entering < n;
        let leave_slack = leaving < n;
        self.new_version();
        let next = next.filter(|&c| c >= n);
        // The right-hand sides on the new kernel's rows `rows`: the next column's (where the
        // leaving variable is a slack) and the values'; and what the update returns for them.
        let rhs = |rows: &[usize], with_next: bool| -> Vec<Vec<f64>> {
            let mut out = Vec::new();
            if let Some(e) = next.filter(|_| with_next) {
                out.push(rows.iter().map(|&i| cols.entry(i, e)).collect());
            }
            if values {
                out.push(rows.iter().map(|&i| cols.h[i]).collect());
            }
            out
        };
        let split = |solved: Vec<Vec<f64>>, with_next: bool| {
            let mut it = solved.into_iter();
            let y_next = if next.is_some() && with_next {
                it.next()
            } else {
                None
            };
            let y_values = if values { it.next() } else { None };
            (y_next, y_values)
        };
        let mut solved = (None, None);
        match (enter_slack, leave_slack) {
            (false, true) => {
                // Border K with the new column `entering` and the new row `leaving`.
                let r = leaving;
                let ut: Vec<f64> = self
                    .s_cols
                    .iter()
                    .map(|&c| alpha[self.var_slot[c]])
                    .collect();
                let sigma = alpha[slot];
                let v: Vec<f64> = self.s_cols.iter().map(|&c| cols.entry(r, c)).collect();
                // On the bordered rows `R + [r]`.
                let mut rows = self.r_rows.clone();
                rows.push(r);
                let u = rhs(&rows, true);
                let u: Vec<&[f64]> = u.iter().map(|x| &x[..]).collect();
                solved = split(self.kinv.border_solving(&ut, &v, sigma, &u), true);
                self.s_pos[entering] = self.s_cols.len();
                self.s_cols.push(entering);
                self.r_pos[r] = self.r_rows.len();
                self.r_rows.push(r);
            }
            (true, false) => {
                // Remove column `leaving` (position a) and row `entering` (position b).
                let a = self.s_pos[leaving];
                let b = self.r_pos[entering];
                self.kinv.remove(a, b);
                self.s_cols.swap_remove(a);
                if a < self.s_cols.len() {
                    self.s_pos[self.s_cols[a]] = a;
                }
                self.s_pos[leaving] = NONE;
                self.r_rows.swap_remove(b);
                if b < self.r_rows.len() {
                    self.r_pos[self.r_rows[b]] = b;
                }
                self.r_pos[entering] = NONE;
            }
            (false, false) => {
                // Replace column at position a by `entering`.
                let a = self.s_pos[leaving];
                let ut: Vec<f64> = self
                    .s_cols
                    .iter()
                    .map(|&c| alpha[self.var_slot[c]])
                    .collect();
                // The rows do not change; the leaving `z`'s complement (a slack) enters next.
                let u = rhs(&self.r_rows, false);
                let u: Vec<&[f64]> = u.iter().map(|x| &x[..]).collect();
                solved = split(self.kinv.replace_column_solving(a, &ut, &u), false);
                self.s_cols[a] = entering;
                self.s_pos[leaving] = NONE;
                self.s_pos[entering] = a;
            }
            (true, true) => {
                // Row `entering` (position b) of K is replaced by row `leaving`.
                let b = self.r_pos[entering];
                let r = leaving;
                let w: Vec<f64> = self.kinv.col(b).to_vec();
                let v: Vec<f64> = self.s_cols.iter().map(|&c| cols.entry(r, c)).collect();
                // On the rows after the replacement.
                let mut rows = self.r_rows.clone();
                rows[b] = r;
                let u = rhs(&rows, true);
                let u: Vec<&[f64]> = u.iter().map(|x| &x[..]).collect();
                solved = split(self.kinv.replace_row_solving(b, &w, &v, &u), true);
                self.r_rows[b] = r;
                self.r_pos[r] = b;
                self.r_pos[entering] = NONE;
            }
        }
        self.slot_var[slot] = entering;
        self.var_slot[entering] = slot;
        self.var_slot[leaving] = NONE;
        solved
    }

    /// The version of this basis: a number no other basis state of the process has (taken anew
    /// at every pivot and refactorisation, and by a clone's first change), so a kernel solve
    /// from [`Basis::pivot_solving`] belongs to the version it returned at and to no other.
    pub fn version(&self) -> u64 {
        self.version
    }

    fn new_version(&mut self) {
        use std::sync::atomic::{AtomicU64, Ordering};
        static NEXT: AtomicU64 = AtomicU64::new(1);
        self.version = NEXT.fetch_add(1, Ordering::Relaxed);
    }
}

/// The size of the round-off of `data · col` for a column `col` of `K⁻¹`: `Σ |data| · max |col|`.
/// An entry of the inverse carries round-off relative to the column's scale, not to itself (an
/// entry that is zero by the data comes out as noise of that scale).
fn column_terms(data: &[f64], col: &[f64]) -> f64 {
    let g = col.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    g * data.iter().map(|v| v.abs()).sum::<f64>()
}

/// `out += Σ y_s S[.., s]` ([`add_columns`]) over all rows. This pass streams the `k` kernel
/// columns of `M` and dominates a pivot. It is memory-bound, and what the memory delivers
/// depends on how long each column is read without a jump: one long run of rows per thread of
/// the pool (not many short blocks; at least `MIN_RUN` rows on a pool with many threads),
/// eight columns per pass over it. Each row's sum is the same whatever the number of threads.
fn add_columns_pooled(cols: &Columns, zcols: &[(usize, f64)], out: &mut [f64]) {
    const MIN_RUN: usize = 512;
    let n = out.len();
    let threads = rayon::current_num_threads();
    if threads > 1 && n * zcols.len() >= 1 << 18 && n >= 64 {
        let rows = n.div_ceil(threads).max(MIN_RUN).next_multiple_of(8);
        out.par_chunks_mut(rows)
            .enumerate()
            .for_each(|(i, part)| add_columns(cols, zcols, part, i * rows));
    } else {
        add_columns(cols, zcols, out, 0);
    }
}

/// [`add_columns_pooled`] for two weight vectors over the same stored columns (`z1` and `z2`
/// name the same columns in the same order), in one pass: each row's two sums are those of
/// [`add_columns`] alone.
fn add_columns_pooled2(
    cols: &Columns,
    z1: &[(usize, f64)],
    z2: &[(usize, f64)],
    out1: &mut [f64],
    out2: &mut [f64],
) {
    const MIN_RUN: usize = 512;
    let n = out1.len();
    let threads = rayon::current_num_threads();
    let run = |part1: &mut [f64], part2: &mut [f64], offset: usize| {
        let len = part1.len();
        let parts: Vec<&[f64]> = z1
            .iter()
            .map(|&(s, _)| &cols.m.stored(s)[offset..offset + len])
            .collect();
        let y1: Vec<f64> = z1.iter().map(|&(_, y)| y).collect();
        let y2: Vec<f64> = z2.iter().map(|&(_, y)| y).collect();
        simd::add_columns2(&parts, &y1, &y2, part1, part2);
    };
    if threads > 1 && n * z1.len() >= 1 << 18 && n >= 64 {
        let rows = n.div_ceil(threads).max(MIN_RUN).next_multiple_of(8);
        out1.par_chunks_mut(rows)
            .zip(out2.par_chunks_mut(rows))
            .enumerate()
            .for_each(|(i, (p1, p2))| run(p1, p2, i * rows));
    } else {
        run(out1, out2, 0);
    }
}

/// `out += Σ y_s S[offset.., s]` over `(s, y_s)` with `S` the stored columns of `M`, in the
/// order of `zcols`, four columns to a partial sum ([`simd::add_columns`], compiled for the
/// machine's widest vectors with the same bits).
fn add_columns(cols: &Columns, zcols: &[(usize, f64)], out: &mut [f64], offset: usize) {
    let len = out.len();
    let parts: Vec<&[f64]> = zcols
        .iter()
        .map(|&(s, _)| &cols.m.stored(s)[offset..offset + len])
        .collect();
    let y: Vec<f64> = zcols.iter().map(|&(_, y)| y).collect();
    simd::add_columns(&parts, &y, out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;
    use std::sync::Arc;

    use crate::pivoting::columns::ColumnStore;

    /// A dense `n × n` test matrix by columns: entries of both signs and several sizes, the
    /// diagonal dominant (every principal submatrix regular).
    fn test_matrix(n: usize) -> Vec<f64> {
        let entry = |i: usize, j: usize| {
            let k = ((i * 7919 + j * 104_729) as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
            (k as f64 / (1u64 << 24) as f64 - 0.5) * (1.0 + (i % 5) as f64)
                + if i == j { n as f64 } else { 0.0 }
        };
        (0..n * n).map(|x| entry(x % n, x / n)).collect()
    }

    /// A right-hand side `h` and a driver direction `g` for [`test_matrix`].
    fn test_sides(n: usize) -> (Vec<f64>, Vec<f64>) {
        let h = (0..n).map(|i| ((i * 31) as f64).sin()).collect();
        let g = (0..n)
            .map(|i| 1.0 + ((i * 17) as f64).cos().abs())
            .collect();
        (h, g)
    }

    /// Bit-for-bit equality of two vectors.
    fn same(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// The basic values formed in the entering column's pass are the values of a solve of
    /// their own, bit for bit, and the entering column is the same: a basis holding slacks,
    /// columns of `M` (some stored negated) and the driver, entering a structural column and a
    /// slack, on pools of 1, 2 and 3 threads (large enough for the pass to be split), and with a
    /// zero in the right-hand side's kernel part (different columns for the two sums: two
    /// passes).
    #[test]
    fn values_formed_in_the_entering_columns_pass_are_a_solves() {
        // k = 401 kernel columns of 1200 rows: the pass and the kernel solve are split.
        let n = 1200;
        let mut data = test_matrix(n);
        // Column 3 the negation of column 2: stored once, read negated.
        for i in 0..n {
            data[3 * n + i] = -data[2 * n + i];
        }
        let store = Arc::new(ColumnStore::new(n, data));
        let (h, g) = test_sides(n);
        // Every third slot holds its z, slot 5 the driver, the others their slacks.
        let mut slots: Vec<usize> = (0..n).collect();
        for s in (0..n).step_by(3) {
            slots[s] = n + s;
        }
        slots[5] = 2 * n;
        for zero_in_h in [false, true] {
            let mut h = h.clone();
            if zero_in_h {
                // Zero on the kernel's rows (those whose slack is not basic): y_h = 0, no
                // column in the values' sum, every column in the entering column's.
                for (i, v) in h.iter_mut().enumerate() {
                    if i % 3 == 0 || i == 5 {
                        *v = 0.0;
                    }
                }
            }
            let cols = Columns::new(n, store.clone(), h, g.clone());
            let basis = Basis::from_slots(&cols, slots.clone()).expect("a regular basis");
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("a pool");
                // z_1 (its slack is basic) and x_3 (its z is basic).
                for entering in [n + 1, 3] {
                    let (alpha, drift, values) =
                        pool.install(|| basis.ftran_and_values(&cols, entering, None, Some(None)));
                    let (want_alpha, want_drift) =
                        pool.install(|| basis.ftran_checked(&cols, entering));
                    let want_values = pool.install(|| basis.solve(&cols, &cols.h));
                    let values = values.expect("asked for");
                    assert!(
                        same(&alpha, &want_alpha),
                        "α: {threads} threads, {entering}"
                    );
                    assert_eq!(drift.to_bits(), want_drift.to_bits());
                    assert!(
                        same(&values, &want_values),
                        "β: {threads} threads, {zero_in_h}"
                    );
                }
            }
        }
    }

    /// The solves a pivot forms in its update's pass are those of the new basis, bit for bit:
    /// the next column's kernel part (through `ftran_checked_with`) and the values' (through
    /// `ftran_and_values`), for each kind of pivot (bordering, replacing a row, replacing a
    /// column; a removal forms none), on pools of 1, 2 and 3 threads, with a kernel above the
    /// order from which the passes are split.
    #[test]
    fn a_pivots_solves_are_the_new_bases() {
        let n = 1200;
        let store = Arc::new(ColumnStore::new(n, test_matrix(n)));
        let (h, g) = test_sides(n);
        let cols = Columns::new(n, store, h, g);
        // Every third slot holds its z (k = 400), the others their slacks.
        let slots: Vec<usize> = (0..n).map(|s| if s % 3 == 0 { n + s } else { s }).collect();
        let basis = Basis::from_slots(&cols, slots).expect("a regular basis");
        // (entering, slot): z_1 for slack x_2 (bordering), x_3 for slack x_4 (replacing a
        // row), z_7 for z_6 (replacing a column), x_9 for z_9 (removal).
        for (entering, slot, forms) in [
            (n + 1, 2, true),
            (3, 4, true),
            (n + 7, 6, true),
            (9, 9, false),
        ] {
            let alpha = basis.ftran(&cols, entering);
            assert!(alpha[slot].abs() > 1e-9, "a pivot on {entering} at {slot}");
            // The next column: the leaving slack's complement, or some structural column.
            let leaving = basis.slot_var[slot];
            let next = if leaving < n { n + leaving } else { n + 10 };
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("a pool");
                pool.install(|| {
                    let mut fused = basis.clone();
                    let (y_next, y_values) =
                        fused.pivot_solving(&cols, entering, slot, &alpha, Some(next), true);
                    let mut plain = basis.clone();
                    plain.pivot(&cols, entering, slot, &alpha);
                    assert_ne!(fused.version(), basis.version());
                    assert_ne!(fused.version(), plain.version());
                    assert_eq!(y_values.is_some(), forms, "{entering}");
                    assert_eq!(y_next.is_some(), forms && leaving < n, "{entering}");
                    let (a1, d1) = fused.ftran_checked_with(&cols, next, y_next);
                    let (a2, d2) = plain.ftran_checked(&cols, next);
                    assert!(same(&a1, &a2) && d1 == d2, "{entering}, {threads} threads");
                    let (_, _, v1) = fused.ftran_and_values(&cols, next, None, Some(y_values));
                    let v2 = plain.solve(&cols, &cols.h);
                    assert!(same(&v1.expect("asked for"), &v2), "{entering}, {threads}");
                });
            }
        }
    }

    /// The slack-row pass forms every row's sum as the plain loop below does (four columns to
    /// a partial sum, in the order given, then the left-over columns one by one: the reference,
    /// written independently of the eight-column blocking), bit for bit, on pools of 1, 2 and 3
    /// threads (blocks of rows of different lengths).
    #[test]
    fn the_slack_row_pass_is_the_same_sum_whatever_the_threads() {
        let n = 1100;
        // Entries of different signs and magnitudes, so that a different association of the
        // sums would change their last bits.
        let data: Vec<f64> = (0..n * n)
            .map(|i| {
                let k = (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
                (k as f64 / (1u64 << 24) as f64 - 0.5) * (1.0 + (i % 7) as f64 * 1e3)
            })
            .collect();
        let cols = Columns::new(
            n,
            Arc::new(ColumnStore::new(n, data)),
            vec![1.0; n],
            vec![1.0; n],
        );
        // 8·31 + 4 + 3 columns: the eight-column passes, one left-over four, three singles.
        let zcols: Vec<(usize, f64)> = (0..255)
            .map(|j| ((j * 37) % n, (j as f64 - 125.3) / 17.0))
            .collect();
        let start: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut reference = start.clone();
        for (i, t) in reference.iter_mut().enumerate() {
            let v = |c: &(usize, f64)| c.1 * cols.m.stored(c.0)[i];
            let mut fours = zcols.chunks_exact(4);
            for f in &mut fours {
                *t += v(&f[0]) + v(&f[1]) + v(&f[2]) + v(&f[3]);
            }
            for c in fours.remainder() {
                *t += v(c);
            }
        }
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool");
            let mut out = start.clone();
            pool.install(|| add_columns_pooled(&cols, &zcols, &mut out));
            let same = out
                .iter()
                .zip(&reference)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{threads} threads");
        }
    }

    /// The rows that row relations tie are formed, not read: with `M`'s rows `2m..3m` equal
    /// to `2f` times rows `0..m` less rows `m..2m` (the contact LCP's friction rows), the slack
    /// rows of a solve and of an entering column are the same bits whether the kernel columns'
    /// entries in those rows are the data or NaN, and they agree with the rows summed over the
    /// columns (no rows derived) to round-off of the terms.
    #[test]
    fn rows_tied_by_relations_are_formed_not_read() {
        use crate::pivoting::prepare::Prepared;
        use crate::pivoting::relations::Relations;
        use crate::RowRelation;
        let m = 400;
        let n = 3 * m;
        let base = test_matrix(n);
        let f = |i: usize| 0.2 + 0.1 * (i % 7) as f64;
        let mat = Mat::from_fn(n, n, |i, j| {
            let e = |r: usize| base[j * n + r];
            if i < 2 * m {
                e(i)
            } else {
                2.0 * f(i - 2 * m) * e(i - 2 * m) - e(i - m)
            }
        });
        let given: Vec<RowRelation> = (0..m)
            .map(|i| RowRelation {
                terms: vec![(m + i, 1.0), (2 * m + i, 1.0), (i, -2.0 * f(i))],
            })
            .collect();
        let mut prep = Prepared::new(&mat);
        let relations = Relations::new(&prep, &given);
        assert_eq!(relations.list().len(), m, "every relation holds");
        prep.derive_rows(&relations);
        assert_eq!(prep.derived.as_ref().map(|d| d.read), Some(2 * m));
        let (h, g) = test_sides(n);
        let cols = prep.columns(&h, &g);
        assert!(cols.derived.is_some());
        let mut summed = cols.clone();
        summed.derived = None;
        // z_s basic for every third slot below 2m (the kernel's rows are all read), slacks
        // elsewhere.
        let in_kernel = |s: usize| s < 2 * m && s.is_multiple_of(3);
        let slots: Vec<usize> = (0..n)
            .map(|s| if in_kernel(s) { n + s } else { s })
            .collect();
        // The kernel's columns of the equilibrated M with NaN in the derived rows.
        let scaled = prep.matrix();
        let poisoned: Vec<f64> = (0..n * n)
            .map(|x| {
                let (i, j) = (x % n, x / n);
                if in_kernel(j) && i >= 2 * m {
                    f64::NAN
                } else {
                    scaled[(i, j)]
                }
            })
            .collect();
        let mut blind = cols.clone();
        blind.m = Arc::new(ColumnStore::new(n, poisoned));
        let basis = Basis::from_slots(&cols, slots.clone()).expect("a regular basis");
        let basis_blind = Basis::from_slots(&blind, slots.clone()).expect("a regular basis");
        let basis_summed = Basis::from_slots(&summed, slots).expect("a regular basis");
        let close = |a: &[f64], b: &[f64], what: &str| {
            let scale = b.iter().fold(0.0f64, |x, y| x.max(y.abs()));
            for (k, (x, y)) in a.iter().zip(b).enumerate() {
                assert!(
                    (x - y).abs() <= 1e-12 * scale,
                    "{what}, slot {k}: {x} against {y}"
                );
            }
        };
        // Entering: a z of a read row, a z of a derived row, the driver, a non-basic slack.
        for entering in [n + 1, n + 2 * m + 1, 2 * n, 3] {
            let alpha = basis.ftran(&cols, entering);
            assert!(
                same(&alpha, &basis_blind.ftran(&blind, entering)),
                "{entering}"
            );
            close(&alpha, &basis_summed.ftran(&summed, entering), "α");
        }
        let values = basis.solve(&cols, &cols.h);
        assert!(same(&values, &basis_blind.solve(&blind, &blind.h)));
        close(&values, &basis_summed.solve(&summed, &summed.h), "β");
        // In one pass with the values, the same bits as each alone.
        let (alpha, _, fresh) = basis.ftran_and_values(&cols, n + 4, None, Some(None));
        assert!(same(&alpha, &basis.ftran(&cols, n + 4)));
        assert!(same(&fresh.expect("asked for"), &values));
    }
}
