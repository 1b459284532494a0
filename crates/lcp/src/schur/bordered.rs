//! A basis of a Schur-complement LCP kept as one sparse LU factorisation of a *base* system
//! and a small dense *border* for the changes since.
//!
//! The unknowns of the base system are `v = (y, x, z, p)` (`N + 2n + 1`), its rows the `N`
//! rows of `A y − B z − da·p = …`, the `n` rows of `x − D z + C y − d0·p = …`, one *fix row*
//! per index `i` that holds one of `x_i`, `z_i` at a given value, and one *extra* fix row for
//! the basis's one more non-basic variable (the driver at the start, then the second of the
//! missing pair). A base is a basis of the path, so it is as regular as the path's bases are.
//! Each fix row holds one entry, so a base is as sparse as its equations: it is factorised by
//! faer's simplicial (left-looking, partial pivoting) LU in one column order computed once
//! (COLAMD on the union of the bases' patterns). A basis differs from the base in
//!
//! * *freed* fix rows: the base fixes a variable that is now basic — the row gets a border
//!   column (an unknown that absorbs it);
//! * *newly fixed* variables: non-basic now, but not fixed by the base — a border row `e_vᵀ`.
//!
//! With `W = 𝒜0⁻¹ U` (the border columns solved once when they join) the system
//! `[𝒜0 U; Vᵀ C] [v; μ] = [r; r']` is solved as `S μ = r' − Vᵀ 𝒜0⁻¹ r` with the small
//! `S = C − Vᵀ W`, then `v = 𝒜0⁻¹ (r − U μ)` (the block-LU, or Schur-complement, update of a
//! basis; Bisschop and Meeraus 1977). A pivot costs a few sparse solves and a dense `S` of the
//! border's size; the base is refactorised (numerically only) when the border grows.

use std::cell::RefCell;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::SolveCore;
use faer::perm::PermRef;
use faer::sparse::linalg::colamd;
use faer::sparse::linalg::lu::simplicial::{self, SimplicialLu};
use faer::sparse::linalg::triangular_solve;
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{Conj, Mat, MatMut, Par};

use super::SchurLcp;

/// A variable of the tableau as a column: `x_i` is `i`, `z_i` is `n + i`, the driver `2n`.
pub(crate) type Col = usize;

/// A border column: the base's fix row of index `i` (the extra row as `n`), freed.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Freed(usize);

/// The base system, factorised.
struct Base {
    size: usize,
    /// The entries that never change: the first two blocks of rows (with the driver's column),
    /// as a matrix of the base's size without the fix rows.
    equations: SparseColMat<usize, f64>,
    matrix: SparseColMat<usize, f64>,
    lu: SimplicialLu<usize, f64>,
    row_perm: Vec<usize>,
    row_perm_inv: Vec<usize>,
    col_perm: Vec<usize>,
    col_perm_inv: Vec<usize>,
    /// The permuted right-hand side of a solve.
    work: RefCell<Vec<f64>>,
    /// The column each index's fix row holds (`x_i` as `i`, `z_i` as `n + i`).
    fixed: Vec<Col>,
    /// The column the extra row holds.
    extra: Col,
    /// The entry of a fix row at its variable (`x`, `z`, then `p`): four times the largest
    /// entry of the variable's column, so that partial pivoting takes a fixed variable's pivot
    /// in its fix row and not in the equations it appears in.
    fix_scale: Vec<f64>,
    scratch: RefCell<MemBuffer>,
}

impl Base {
    /// The base of the slack basis (every `z` and the driver fixed), and the column order.
    fn new(lcp: &SchurLcp) -> Result<Self, Singular> {
        let n = lcp.order();
        let big_n = lcp.a.nrows();
        let size = big_n + 2 * n + 1;
        let equations = equations(lcp);
        // The order: COLAMD on the equations and every fix row with both of its variables.
        let mut pattern: Vec<Pair<usize, usize>> =
            equations.iter().map(|t| Pair::new(t.row, t.col)).collect();
        for i in 0..n {
            pattern.push(Pair::new(big_n + n + i, big_n + i));
            pattern.push(Pair::new(big_n + n + i, big_n + n + i));
        }
        pattern.push(Pair::new(big_n + 2 * n, big_n + 2 * n));
        let sym = SymbolicSparseColMat::try_new_from_indices(size, size, &pattern)
            .map_err(|_| Singular)?
            .0;
        let (mut col_perm, mut col_perm_inv) = (vec![0usize; size], vec![0usize; size]);
        let req = colamd::order_scratch::<usize>(size, size, sym.compute_nnz());
        colamd::order(
            &mut col_perm,
            &mut col_perm_inv,
            sym.as_ref(),
            colamd::Control::default(),
            MemStack::new(&mut MemBuffer::new(req)),
        )
        .map_err(|_| Singular)?;
        let scratch = simplicial::factorize_simplicial_numeric_lu_scratch::<usize, f64>(size, size);
        let equations =
            SparseColMat::try_new_from_triplets(size, size, &equations).map_err(|_| Singular)?;
        let mut base = Self {
            size,
            equations,
            matrix: SparseColMat::try_new_from_triplets(0, 0, &[]).map_err(|_| Singular)?,
            lu: SimplicialLu::new(),
            row_perm: vec![0; size],
            row_perm_inv: vec![0; size],
            col_perm,
            col_perm_inv,
            work: RefCell::new(Vec::new()),
            fixed: (n..2 * n).collect(),
            extra: 2 * n,
            fix_scale: fix_scales(lcp),
            scratch: RefCell::new(MemBuffer::new(scratch)),
        };
        base.factor(big_n, n)?;
        Ok(base)
    }

    /// Forms the base matrix of `fixed` and `extra` and factorises it.
    fn factor(&mut self, big_n: usize, n: usize) -> Result<(), Singular> {
        // Each column holds at most one fix row's entry, whose row lies below every equation:
        // appended to the equations' column, it keeps the rows sorted (no sort of triplets, 3 %
        // of a long path's time).
        let mut fix: Vec<Option<(usize, f64)>> = vec![None; self.size];
        for (i, &f) in self.fixed.iter().enumerate() {
            fix[big_n + f] = Some((big_n + n + i, self.fix_scale[f]));
        }
        fix[big_n + self.extra] = Some((big_n + 2 * n, self.fix_scale[self.extra]));
        let eq = &self.equations;
        let nnz = eq.compute_nnz() + n + 1;
        let (mut col_ptr, mut rows, mut values) = (
            Vec::with_capacity(self.size + 1),
            Vec::with_capacity(nnz),
            Vec::with_capacity(nnz),
        );
        col_ptr.push(0);
        for (j, fix) in fix.iter().enumerate() {
            rows.extend_from_slice(eq.row_idx_of_col_raw(j));
            values.extend_from_slice(eq.val_of_col(j));
            if let Some((row, value)) = *fix {
                rows.push(row);
                values.push(value);
            }
            col_ptr.push(rows.len());
        }
        let symbolic = SymbolicSparseColMat::new_checked(self.size, self.size, col_ptr, None, rows);
        self.matrix = SparseColMat::new(symbolic, values);
        let col_perm = PermRef::new_checked(&self.col_perm, &self.col_perm_inv, self.size);
        simplicial::factorize_simplicial_numeric_lu(
            &mut self.row_perm,
            &mut self.row_perm_inv,
            &mut self.lu,
            self.matrix.as_ref(),
            col_perm,
            MemStack::new(&mut self.scratch.borrow_mut()),
        )
        .map_err(|_| Singular)
    }

    /// `r` overwritten by `𝒜0⁻¹ r`: the rows permuted into the factor's order, the two
    /// triangular solves, the unknowns permuted back (one pass each way; the factor's own
    /// solve copies the vector twice more, and checks both permutations, 10 % of a long
    /// path's time).
    fn solve(&self, r: &mut [f64]) {
        self.solve_permuted(r);
        let work = self.work.borrow();
        for (ri, &j) in r.iter_mut().zip(&self.col_perm_inv) {
            *ri = work[j];
        }
    }

    /// `t = 𝒜0⁻¹ r` (`t` resized to the base's size) from the unknown `from` on; the unknowns
    /// before it are zero.
    fn solve_from(&self, r: &[f64], t: &mut Vec<f64>, from: usize) {
        self.solve_permuted(r);
        let work = self.work.borrow();
        t.clear();
        t.resize(from, 0.0);
        t.extend(self.col_perm_inv[from..].iter().map(|&j| work[j]));
    }

    /// `𝒜0⁻¹ r` in the factor's order of the unknowns, left in `work`.
    fn solve_permuted(&self, r: &[f64]) {
        let mut work = self.work.borrow_mut();
        work.clear();
        work.extend(self.row_perm.iter().map(|&i| r[i]));
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        let x = MatMut::from_column_major_slice_mut(&mut work[..], self.size, 1);
        triangular_solve::solve_unit_lower_triangular_in_place(l, Conj::No, x, Par::Seq);
        let x = MatMut::from_column_major_slice_mut(&mut work[..], self.size, 1);
        triangular_solve::solve_upper_triangular_in_place(u, Conj::No, x, Par::Seq);
    }
}

/// The basis: the base and its border.
pub(crate) struct Bordered {
    n: usize,
    big_n: usize,
    base: Base,
    cols: Vec<Freed>,
    /// `𝒜0⁻¹ u` for each border column `u`.
    w: Vec<Vec<f64>>,
    /// Newly fixed variables (border rows).
    rows: Vec<Col>,
    /// `S`, factorised, or `None` when singular.
    s_lu: Option<faer::linalg::solvers::PartialPivLu<f64>>,
    /// `S`'s row and column scalings: the factorised matrix is `diag(rs) S diag(cs)`.
    s_rows: Vec<f64>,
    s_cols: Vec<f64>,
    /// Columns of `W` no longer in the border, their memory reused.
    spare: Vec<Vec<f64>>,
    /// Refactorisations so far.
    pub refactorizations: usize,
    /// A fresh base is judged on its test system's solution after one step of iterative
    /// refinement ([`Bordered::refine_checks`]).
    refined_check: bool,
}

/// The base's solution `t = 𝒜0⁻¹ (entry·e_row)` of a right-hand side with one entry, at a
/// fix row: the entering variable's direction solves it before the pivot that frees that row
/// needs `𝒜0⁻¹ (−e_row) = −t / entry` as its border column.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KnownColumn<'a> {
    pub row: usize,
    pub entry: f64,
    pub t: &'a [f64],
}

/// The base or the border is numerically singular.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Singular;

impl Bordered {
    /// The slack basis: every `z_i` and the driver fixed.
    pub fn slack(lcp: &SchurLcp) -> Result<Self, Singular> {
        let b = Self {
            n: lcp.order(),
            big_n: lcp.a.nrows(),
            base: Base::new(lcp)?,
            cols: Vec::new(),
            w: Vec::new(),
            rows: Vec::new(),
            s_lu: None,
            s_rows: Vec::new(),
            s_cols: Vec::new(),
            spare: Vec::new(),
            refactorizations: 0,
            refined_check: false,
        };
        b.check_base()?;
        Ok(b)
    }

    /// Unknowns of the base system.
    fn size(&self) -> usize {
        self.big_n + 2 * self.n + 1
    }

    /// Index of a variable's column among the base's unknowns.
    pub fn unknown(&self, v: Col) -> usize {
        self.big_n + v
    }

    /// The base's fix row (`i` for index `i`'s, `n` for the extra one) that fixes `v`.
    fn base_row(&self, v: Col) -> Option<usize> {
        let n = self.n;
        if v < 2 * n && self.base.fixed[v % n] == v {
            Some(v % n)
        } else if self.base.extra == v {
            Some(n)
        } else {
            None
        }
    }

    /// The row of the base system that fixes `v` and its entry there, if the base fixes it
    /// and the row is not freed.
    pub fn fix_row(&self, v: Col) -> Option<(usize, f64)> {
        self.base_row(v)
            .filter(|&r| !self.cols.contains(&Freed(r)))
            .map(|r| (self.big_n + self.n + r, self.base.fix_scale[v]))
    }

    /// The entry of `v`'s fix row at `v` (a right-hand side for `v` is multiplied by it).
    pub fn fix_scale(&self, v: Col) -> f64 {
        self.base.fix_scale[v]
    }

    /// The border's size.
    pub fn border(&self) -> usize {
        self.cols.len()
    }

    fn solve_base(&self, r: &mut [f64]) {
        self.base.solve(r);
    }

    /// The base row of a border column's single entry (`−1`).
    fn col_row(&self, c: Freed) -> usize {
        self.big_n + self.n + c.0
    }

    /// Adds the border column of the freed fix row `c`: `W`'s column `𝒜0⁻¹ (−e_row)`, taken
    /// from `known` where that holds the base's solution `𝒜0⁻¹ (entry·e_row)` of the same
    /// row (the direction of the step whose pivot this is solved it already), else solved.
    fn add_col(&mut self, c: Freed, known: Option<KnownColumn>) {
        let row = self.col_row(c);
        let mut w = self.spare.pop().unwrap_or_default();
        w.clear();
        match known.filter(|k| k.row == row && k.t.len() == self.size()) {
            Some(k) => w.extend(k.t.iter().map(|&t| -t / k.entry)),
            None => {
                w.resize(self.size(), 0.0);
                w[row] = -1.0;
                self.solve_base(&mut w);
            }
        }
        self.cols.push(c);
        self.w.push(w);
    }

    /// Forms and factorises `S = C − Vᵀ W`.
    fn refresh_s(&mut self) -> Result<(), Singular> {
        let k = self.cols.len();
        debug_assert_eq!(k, self.rows.len());
        if k == 0 {
            self.s_lu = None;
            return Ok(());
        }
        let mut s = Mat::<f64>::zeros(k, k);
        for (g, &v) in self.rows.iter().enumerate() {
            let at = self.unknown(v);
            for u in 0..k {
                s[(g, u)] = -self.w[u][at];
            }
        }
        // Rows and columns mix the units of forces and displacements: each row, then each
        // column, brought to a largest entry of 1 by a power of two before the factorisation.
        let pow2 = |v: f64| {
            if v > 0.0 && v.is_finite() {
                2f64.powi(-v.log2().round() as i32)
            } else {
                1.0
            }
        };
        let rs: Vec<f64> = (0..k)
            .map(|g| pow2((0..k).fold(0.0f64, |a, u| a.max(s[(g, u)].abs()))))
            .collect();
        for g in 0..k {
            for u in 0..k {
                s[(g, u)] *= rs[g];
            }
        }
        let cs: Vec<f64> = (0..k)
            .map(|u| pow2((0..k).fold(0.0f64, |a, g| a.max(s[(g, u)].abs()))))
            .collect();
        for u in 0..k {
            for g in 0..k {
                s[(g, u)] *= cs[u];
            }
        }
        let lu = s.partial_piv_lu();
        let ok = (0..k).all(|i| {
            let u = lu.U()[(i, i)];
            u.is_finite() && u.abs() > 1e-13
        });
        self.s_rows = rs;
        self.s_cols = cs;
        self.s_lu = ok.then_some(lu);
        if ok {
            Ok(())
        } else {
            Err(Singular)
        }
    }

    /// The entering variable `e` becomes basic and `l` non-basic.
    ///
    /// `known`: the base's solution of the entering variable's fix row where the caller has
    /// it ([`KnownColumn`]): the border column without a solve of its own.
    pub fn pivot_with(
        &mut self,
        e: Col,
        l: Col,
        known: Option<KnownColumn>,
    ) -> Result<(), Singular> {
        if let Some(at) = self.rows.iter().position(|&v| v == e) {
            self.rows.swap_remove(at);
        } else {
            let r = self.base_row(e).expect("a non-basic variable is fixed");
            self.add_col(Freed(r), known);
        }
        let freed = self
            .base_row(l)
            .and_then(|r| self.cols.iter().position(|&c| c == Freed(r)));
        match freed {
            Some(at) => {
                self.cols.swap_remove(at);
                let w = self.w.swap_remove(at);
                self.spare.push(w);
            }
            None => self.rows.push(l),
        }
        self.refresh_s()
    }

    /// A fresh base from the basis's non-basic variables (`nonbasic[v]`, length `2n + 1`):
    /// each index's fix row holds its non-basic variable (the missing pair's `z`), the extra
    /// row the one more (the missing pair's `x`, or the driver).
    pub fn refactor(&mut self, nonbasic: &[bool]) -> Result<(), Singular> {
        let n = self.n;
        let mut extra = 2 * n;
        let fixed: Vec<Col> = (0..n)
            .map(|i| {
                if nonbasic[i] && nonbasic[n + i] {
                    extra = i;
                    n + i
                } else if nonbasic[i] {
                    i
                } else {
                    n + i
                }
            })
            .collect();
        self.refactorizations += 1;
        self.base.fixed = fixed;
        self.base.extra = extra;
        self.base.factor(self.big_n, n)?;
        self.cols.clear();
        self.w.clear();
        self.rows.clear();
        self.refresh_s()?;
        self.check_base()
    }

    /// From now on a fresh base is judged after one step of iterative refinement of its test
    /// system, for a caller that refines every solve it relies on (the path's engine). Late on
    /// a long path partial pivoting in the fixed column order can grow a factor's entries: the
    /// 2000-bearing beam's base after step 9712 solved its test system to a backward error of
    /// 2.1e-8 and was refused as singular (the path ended in a numerical failure), where one
    /// refinement brings it to round-off.
    pub fn refine_checks(&mut self) {
        self.refined_check = true;
    }

    /// The base's factor solves a test system to a backward error of round-off (after one step
    /// of refinement where [`Bordered::refine_checks`] asked for it), else the base is
    /// (numerically) singular.
    fn check_base(&self) -> Result<(), Singular> {
        let size = self.size();
        let b = Mat::<f64>::from_fn(size, 1, |i, _| 1.0 + (i % 7) as f64 / 7.0);
        let mut x = b.clone();
        self.solve_base(x.col_as_slice_mut(0));
        if self.refined_check {
            let mut r = &b - &self.base.matrix * &x;
            self.solve_base(r.col_as_slice_mut(0));
            x += &r;
        }
        let r = &self.base.matrix * &x - &b;
        let (mut worst, mut finite) = (0.0f64, true);
        let a = &self.base.matrix;
        let mut scale = vec![0.0f64; size];
        for j in 0..size {
            for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
                scale[i] += (v * x[(j, 0)]).abs();
            }
        }
        for i in 0..size {
            finite &= x[(i, 0)].is_finite();
            worst = worst.max(r[(i, 0)].abs() / (scale[i] + b[(i, 0)].abs()));
        }
        if finite && worst < 1e-8 {
            Ok(())
        } else {
            Err(Singular)
        }
    }

    /// `𝒜0 v = r` solved in working precision, `r` overwritten by `v`.
    pub fn base_solve(&self, r: &mut [f64]) {
        self.solve_base(r);
    }

    /// The base's matrix (the basis's equations and fix rows after a refactorisation).
    pub fn base_matrix(&self) -> &SparseColMat<usize, f64> {
        &self.base.matrix
    }

    /// The base system `𝒜0 v = r` solved on its factor and refined with residuals in
    /// double-double arithmetic ([`super::refined_in_double_double`]): the solution of the data
    /// as stored, to far below the round-off of a working-precision solve. For a base without
    /// a border (just refactorised).
    pub fn refined_base_solve(&self, r: &[f64]) -> Vec<f64> {
        debug_assert!(self.cols.is_empty());
        let a = &self.base.matrix;
        super::refined_in_double_double(
            r,
            |visit| {
                for j in 0..a.ncols() {
                    for (&i, &aij) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
                        visit(i, j, aij);
                    }
                }
            },
            |v| self.solve_base(v),
        )
    }

    /// Solves the basis system whose right-hand side is `r` on the base's rows (the fix rows
    /// of freed indices are ignored) and `fix(v)` on each newly fixed variable `v`; returns the
    /// base's unknowns (`p` the last).
    pub fn solve(&self, r: &[f64], fix: impl Fn(Col) -> f64) -> Vec<f64> {
        let mut t = Vec::new();
        self.solve_into(r, fix, &mut t, None, 0);
        t
    }

    /// [`Bordered::solve`] into `t` (its memory reused: a solve's vectors are larger than
    /// the allocator keeps at hand, and fresh pages cost a long path 5 % of its time), the
    /// base's own solution `𝒜0⁻¹ r` (before the border's correction) copied into `base` where
    /// it is given.
    ///
    /// Only the unknowns from `from` on are solved for (every unknown with `from = 0`); those
    /// before it are zero: a caller that reads only the tableau's `x`, `z` and `p` (from the
    /// structure's `N` on) streams a third of the border's columns and of the permutation.
    pub fn solve_into(
        &self,
        r: &[f64],
        fix: impl Fn(Col) -> f64,
        t: &mut Vec<f64>,
        base: Option<&mut Vec<f64>>,
        from: usize,
    ) {
        // The border's rows read unknowns from `N` on; a base copy must be whole (it becomes
        // a border column).
        assert!(from <= self.big_n && (base.is_none() || from == 0));
        self.base.solve_from(r, t, from);
        if let Some(base) = base {
            base.clear();
            base.extend_from_slice(t);
        }
        let k = self.cols.len();
        if k == 0 {
            return;
        }
        let mut rhs = Mat::<f64>::zeros(k, 1);
        for (g, &v) in self.rows.iter().enumerate() {
            rhs[(g, 0)] = (fix(v) - t[self.unknown(v)]) * self.s_rows[g];
        }
        let s = self.s_lu.as_ref().expect("a factorised border");
        s.solve_in_place_with_conj(Conj::No, rhs.as_mut());
        // v = 𝒜0⁻¹ r − W μ, a block of rows at a time (the block stays in cache while the
        // border's columns pass over it; each entry's terms in the same order as column by
        // column).
        let mu: Vec<f64> = (0..k).map(|u| rhs[(u, 0)] * self.s_cols[u]).collect();
        const BLOCK: usize = 1024;
        for (b, block) in t[from..].chunks_mut(BLOCK).enumerate() {
            let start = from + b * BLOCK;
            for (w, &mu) in self.w.iter().zip(&mu) {
                for (a, wi) in block.iter_mut().zip(&w[start..]) {
                    *a -= wi * mu;
                }
            }
        }
    }
}

/// The fix rows' entries (see [`Base::fix_scale`]).
fn fix_scales(lcp: &SchurLcp) -> Vec<f64> {
    let n = lcp.order();
    let mut sc = vec![0.0; 2 * n + 1];
    sc[..n].fill(1.0);
    sc[2 * n] = lcp
        .d0
        .iter()
        .chain(&lcp.da)
        .fold(0.0f64, |a, v| a.max(v.abs()));
    for (m, off) in [(&lcp.b, n), (&lcp.d, n)] {
        for j in 0..m.ncols() {
            for v in m.val_of_col(j) {
                sc[off + j] = f64::max(sc[off + j], v.abs());
            }
        }
    }
    sc.iter()
        .map(|&v| if v > 0.0 { 4.0 * v } else { 1.0 })
        .collect()
}

/// The base's equations: `A y − B z − da·p` and `x − D z + C y − d0·p`.
fn equations(lcp: &SchurLcp) -> Vec<Triplet<usize, usize, f64>> {
    let n = lcp.order();
    let big_n = lcp.a.nrows();
    let mut t = Vec::new();
    let mut push_all = |m: &SparseColMat<usize, f64>, r0: usize, c0: usize, sign: f64| {
        for j in 0..m.ncols() {
            let rows = m.row_idx_of_col_raw(j);
            for (&i, &v) in rows.iter().zip(m.val_of_col(j)) {
                t.push(Triplet::new(r0 + i, c0 + j, sign * v));
            }
        }
    };
    push_all(&lcp.a, 0, 0, 1.0);
    push_all(&lcp.b, 0, big_n + n, -1.0);
    push_all(&lcp.c, big_n, 0, 1.0);
    push_all(&lcp.d, big_n, big_n + n, -1.0);
    let pcol = big_n + 2 * n;
    for (i, &v) in lcp.da.iter().enumerate().filter(|(_, v)| **v != 0.0) {
        t.push(Triplet::new(i, pcol, -v));
    }
    for (i, &v) in lcp.d0.iter().enumerate().filter(|(_, v)| **v != 0.0) {
        t.push(Triplet::new(big_n + i, pcol, -v));
    }
    for i in 0..n {
        t.push(Triplet::new(big_n + i, big_n + i, 1.0));
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schur::test_data::small_lcp;

    /// A solve for the unknowns from `N` on gives them bit for bit as the whole solve does
    /// (the same operations in the same order), the unknowns before `N` zero — with a border
    /// of two columns and two rows, so that the border's correction is in play.
    #[test]
    fn a_solve_from_the_tableau_on_is_the_whole_solves_tail_bit_for_bit() {
        let (n, big_n) = (4, 5);
        let lcp = small_lcp();
        let mut basis = Bordered::slack(&lcp).unwrap();
        // z0 enters for x0, then the driver for x1: two freed fix rows (border columns) and
        // two newly fixed variables (border rows).
        basis.pivot_with(n, 0, None).unwrap();
        basis.pivot_with(2 * n, 1, None).unwrap();
        assert_eq!(basis.border(), 2);
        let size = big_n + 2 * n + 1;
        let r: Vec<f64> = (0..size).map(|i| (i as f64 * 0.37).sin()).collect();
        let fix = |v: Col| 0.25 * v as f64 - 0.5;
        let (mut whole, mut tail) = (Vec::new(), Vec::new());
        basis.solve_into(&r, fix, &mut whole, None, 0);
        basis.solve_into(&r, fix, &mut tail, None, big_n);
        assert_eq!(whole.len(), size);
        assert_eq!(tail.len(), size);
        assert!(tail[..big_n].iter().all(|&v| v == 0.0));
        for i in big_n..size {
            assert_eq!(whole[i].to_bits(), tail[i].to_bits(), "unknown {i}");
        }
        assert!(whole[big_n..].iter().any(|&v| v != 0.0));
    }
}
