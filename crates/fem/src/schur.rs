//! The condensation of the factorized bonded structure to its contact zone: the Schur
//! complement `R = K_zz − K_zI K_II⁻¹ K_Iz` and the contact load vectors
//! `R_F = K_zI K_II⁻¹ b_I − b_z` (formulation.md §2), with the round-off of exact zeros set
//! to zero.
//!
//! `R` is formed by forward substitution only, `R = K_zz − YᵀY` with `Y = L⁻¹ P K_Iz` on a
//! factor ordered by nested dissection (`dissection`), blockwise per supernode; the full
//! static modes `x_j = K_II⁻¹ K_Iz,j` (backward solves) are computed only for the columns whose
//! round-off decision depends on them (see [`condense`] for the rule and its proof).

mod dissection;

use crate::assemble::Assembled;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::SolveCore;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, SparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, MatRef, Par, Side};

/// The condensed contact-zone data.
pub(crate) struct Condensation {
    pub r: Mat<f64>,
    pub rf: [Vec<f64>; 2],
    pub asymmetry: f64,
    /// Entries of `R` and `R_F` set to zero as round-off (see [`ROUND_OFF`]).
    pub zeroed: usize,
    /// Columns whose round-off decision needed their full static mode (backward solve).
    #[cfg_attr(not(test), allow(dead_code))]
    pub exact_columns: usize,
}

/// Number of right-hand sides solved together.
pub(crate) const CHUNK: usize = 64;

/// An entry of `R = K_zz − K_zI K_II⁻¹ K_Iz` (or of `R_F`) is round-off when it is smaller
/// than this fraction of the magnitude of what formed it: `|K_zz|`, the sum of the absolute
/// values of the products in `K_zI·x_j` (`x_j = K_II⁻¹ K_Iz,j`), and the bound
/// `|x_i|ᵀ|K_II||x_j|` of how far the round-off of the solves (a residual of order
/// `u·|K_II||x_j|`) reaches the entry. The last term grows with the number of elements the
/// static modes span, as the round-off does; the first two do not, so a threshold on them
/// alone either lets the round-off of a fine mesh through or zeroes real stiffness.
///
/// The threshold is 8 unit round-offs. Measured over the test models (any mesh from 1 to
/// 2000 elements, any units), an exact zero (for instance the normal stiffness of a bearing
/// on which a beam turns freely about a pin) comes out below 4e-17 of this magnitude, and
/// the smallest genuine entries at 1.7e-14 (the tip stiffness of a cantilever of 2000
/// elements, `1/(8N³)` of its terms; finer members are refused as ill-conditioned by
/// `factorize` before this point) and 3.3e-14 (a spring behind a bar 10¹³ times stiffer).
/// Those figures are for the exact form; the condensation uses the upper bound of
/// [`abs_form_weights`], which only makes exact zeros smaller against it, and the same test
/// models (`tests/it/fine_mesh.rs`, the analysis crate's determinate supports) keep their
/// genuine entries. Since issue 11 the magnitude with the static modes decides the diagonal
/// of `R` and `R_F` only; see [`condense`].
pub(crate) const ROUND_OFF: f64 = 8.0 * f64::EPSILON / 2.0;

/// The unit round-off of double precision.
const UNIT_ROUND_OFF: f64 = f64::EPSILON / 2.0;

/// A supernodal Cholesky factor of `K_II` made here (faer's [`Llt`] hides its factor and may
/// choose a simplicial one), with its ordering.
struct Factor {
    symbolic: Box<SymbolicCholesky<usize>>,
    values: Vec<f64>,
}

impl Factor {
    /// The supernodal factor of `kii` in the nested-dissection order of its graph; `None`
    /// when it cannot be made (the caller then falls back to [`Llt`]'s own solves).
    fn dissected(kii: &SparseColMat<usize, f64>) -> Option<Self> {
        let n = kii.nrows();
        let s = kii.symbolic();
        let mut rows = Vec::with_capacity(s.row_idx().len());
        let mut ptr = Vec::with_capacity(n + 1);
        ptr.push(0);
        for c in 0..n {
            rows.extend_from_slice(s.row_idx_of_col_raw(c));
            ptr.push(rows.len());
        }
        let fwd = dissection::nested_dissection(&dissection::Graph::from_triangle(n, &ptr, &rows));
        let mut inv = vec![0usize; n];
        for (k, &v) in fwd.iter().enumerate() {
            inv[v] = k;
        }
        let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
        Self::new(kii, SymmetricOrdering::Custom(perm))
    }

    fn new(kii: &SparseColMat<usize, f64>, ordering: SymmetricOrdering<'_, usize>) -> Option<Self> {
        let symbolic = factorize_symbolic_cholesky(
            kii.symbolic(),
            Side::Lower,
            ordering,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .ok()?;
        if !matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)) {
            return None;
        }
        let f = Factor {
            symbolic: Box::new(symbolic),
            values: Vec::new(),
        };
        let values = f.numeric(kii.as_ref())?;
        Some(Factor { values, ..f })
    }

    /// The numeric factor of a matrix of `kii`'s pattern with this factor's ordering; `None`
    /// when the factorization fails (not positive definite) or memory is lacking.
    fn numeric(&self, a: SparseColMatRef<'_, usize, f64>) -> Option<Vec<f64>> {
        let mut values = Vec::new();
        values.try_reserve_exact(self.symbolic.len_val()).ok()?;
        values.resize(self.symbolic.len_val(), 0.0);
        let par = Par::Seq;
        let mut buf = MemBuffer::try_new(
            self.symbolic
                .factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .ok()?;
        self.symbolic
            .factorize_numeric_llt::<f64>(
                &mut values,
                a,
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .ok()?;
        Some(values)
    }

    fn l(&self) -> SupernodalLltRef<'_, usize, f64> {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("checked in Factor::new")
        };
        SupernodalLltRef::<'_, usize, f64>::new(sym, &self.values)
    }

    /// The position of each free DOF in the factor's rows.
    fn row_of(&self, n_i: usize) -> Vec<usize> {
        match self.symbolic.perm() {
            Some(p) => p.arrays().1.to_vec(),
            None => (0..n_i).collect(),
        }
    }

    /// The largest number of entries of a row of `L`: every inner product of the
    /// factorization (`l_ij = (a_ij − Σ_k l_ik l_jk)/l_jj`, `k < j`, both non-zero) has at
    /// most that many terms.
    fn max_row_count(&self) -> usize {
        let l = self.l();
        let mut count = vec![0usize; l.symbolic().nrows()];
        for s in 0..l.symbolic().n_supernodes() {
            let sn = l.supernode(s);
            let (start, size) = (sn.start(), sn.val().ncols());
            for (i, c) in count[start..start + size].iter_mut().enumerate() {
                *c += i + 1;
            }
            for &r in sn.pattern() {
                count[r] += size;
            }
        }
        count.into_iter().max().unwrap_or(0)
    }
}

/// The solves `K_II X = K_Iz` of the full condensation (the fallback and the tests'
/// reference): [`Llt`]'s own solve, or the supernodal factor's (forward substitution
/// skipping the supernodes a chunk does not reach, then the backward half).
enum Solver<'a> {
    Supernodal(&'a Factor),
    Plain(&'a Llt<usize, f64>),
}

impl Solver<'_> {
    /// The position of each free DOF in the rows [`Solver::solve_sparse`] returns.
    fn row_of(&self, n_i: usize) -> Vec<usize> {
        match self {
            Solver::Supernodal(f) => f.row_of(n_i),
            Solver::Plain(_) => (0..n_i).collect(),
        }
    }

    /// Solves `K_II X = B` for the columns `cols` of `K_Iz` (their rows already in the order
    /// of [`Solver::row_of`]), returning `X` (`n_i × cols.len()`) in that row order.
    fn solve_sparse(&self, n_i: usize, cols: &[&crate::dofs::Row]) -> Mat<f64> {
        let w = cols.len();
        let mut x = Mat::<f64>::zeros(n_i, w);
        for (j, col) in cols.iter().enumerate() {
            for &(i, v) in col.iter() {
                x[(i, j)] = v;
            }
        }
        match self {
            Solver::Plain(llt) => llt.solve_in_place_with_conj(Conj::No, x.as_mut()),
            Solver::Supernodal(f) => {
                let l = f.l();
                let mut touched = vec![false; l.symbolic().n_supernodes()];
                let sn_of = supernode_of_rows(&l);
                for col in cols {
                    for &(i, _) in col.iter() {
                        touched[sn_of[i]] = true;
                    }
                }
                forward_sparse(l, x.as_mut(), &mut touched, &sn_of, |_, _| {});
                let par = Par::Seq;
                let mut buf = MemBuffer::new(l.symbolic().solve_in_place_scratch::<f64>(w, par));
                l.l_transpose_solve_with_conj(Conj::No, x.as_mut(), par, MemStack::new(&mut buf));
            }
        }
        x
    }
}

/// The supernode holding each row of the factor.
fn supernode_of_rows(l: &SupernodalLltRef<'_, usize, f64>) -> Vec<usize> {
    let sym = l.symbolic();
    let mut of = vec![0; sym.nrows()];
    for s in 0..sym.n_supernodes() {
        let sn = l.supernode(s);
        let start = sn.start();
        of[start..start + sn.val().ncols()].fill(s);
    }
    of
}

/// `L Y = B` in place for the supernodal `L`, processing only the supernodes marked in
/// `touched` (on entry: those holding a non-zero of `B`; each processed supernode marks the
/// supernodes of its pattern, which it updates). A supernode never marked has all its rows
/// of `B` zero and stays so: its update of the later rows is exactly zero, so the result is
/// the same bit for bit as a full supernodal forward solve. `done(s, rows)` receives each
/// processed supernode with its final rows of `Y` (`size × k`).
fn forward_sparse(
    l: SupernodalLltRef<'_, usize, f64>,
    mut x: MatMut<'_, f64>,
    touched: &mut [bool],
    sn_of: &[usize],
    mut done: impl FnMut(usize, MatRef<'_, f64>),
) {
    let k = x.ncols();
    let mut tmp: Vec<f64> = Vec::new();
    for s in 0..l.symbolic().n_supernodes() {
        if !touched[s] {
            continue;
        }
        let sn = l.supernode(s);
        let ls = sn.val();
        let size = ls.ncols();
        let start = sn.start();
        let (ls_top, ls_bot) = ls.split_at_row(size);
        let pattern = sn.pattern();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            ls_top,
            x.rb_mut().subrows_mut(start, size),
            Par::Seq,
        );
        done(s, x.rb().subrows(start, size));
        if pattern.is_empty() {
            continue;
        }
        tmp.clear();
        tmp.resize(pattern.len() * k, 0.0);
        let mut t = MatMut::from_column_major_slice_mut(&mut tmp, pattern.len(), k);
        faer::linalg::matmul::matmul(
            t.rb_mut(),
            Accum::Replace,
            ls_bot,
            x.rb().subrows(start, size),
            1.0,
            Par::Seq,
        );
        for j in 0..k {
            let xj = x
                .rb_mut()
                .col_mut(j)
                .try_as_col_major_mut()
                .expect("contiguous")
                .as_slice_mut();
            let tj = &tmp[j * pattern.len()..(j + 1) * pattern.len()];
            for (&i, &v) in pattern.iter().zip(tj) {
                xj[i] -= v;
            }
        }
        for &i in pattern {
            touched[sn_of[i]] = true;
        }
    }
}

/// `|K|·|x|` for a symmetric `K` stored as its lower triangle.
fn abs_product(k: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let k = k.as_ref();
    let mut y = vec![0.0; x.len()];
    for j in 0..x.len() {
        let rows = k.symbolic().row_idx_of_col_raw(j);
        let vals = k.val_of_col(j);
        for (&i, &v) in rows.iter().zip(vals) {
            y[i] += v.abs() * x[j].abs();
            if i != j {
                y[j] += v.abs() * x[i].abs();
            }
        }
    }
    y
}

/// Weights `w` with `|x|ᵀ|K||x| ≤ Σ_a w_a x_a²` for every `x`, `K` symmetric positive
/// definite and stored as its lower triangle: `w_a = Σ_b |K_ab| √(K_aa/K_bb)`.
///
/// In the Jacobi-scaled variables `x̂_a = √K_aa·x_a`, `K̂_ab = K_ab/√(K_aa K_bb)`, each term
/// `|K_ab||x_a||x_b| = |K̂_ab||x̂_a||x̂_b| ≤ |K̂_ab|(x̂_a² + x̂_b²)/2`; summing over all `a, b`
/// (K symmetric) gives `Σ_a x̂_a² Σ_b |K̂_ab|`. The bound is as independent of units as the
/// form itself (the scaling makes it so), it is close to the form where neighbouring
/// scaled values are alike (the smooth static modes of a mesh), and it costs one pass over
/// `K` for all columns and then `O(n)` per column instead of one sparse pass per column.
fn abs_form_weights(k: &SparseColMat<usize, f64>) -> Vec<f64> {
    let k = k.as_ref();
    let n = k.ncols();
    let mut d = vec![0.0; n];
    for (c, dc) in d.iter_mut().enumerate() {
        let rows = k.symbolic().row_idx_of_col_raw(c);
        for (&i, &v) in rows.iter().zip(k.val_of_col(c)) {
            if i == c {
                *dc += v;
            }
        }
    }
    let mut w = vec![0.0; n];
    for c in 0..n {
        let rows = k.symbolic().row_idx_of_col_raw(c);
        for (&i, &v) in rows.iter().zip(k.val_of_col(c)) {
            if i == c {
                w[c] += v.abs();
            } else if d[i] > 0.0 && d[c] > 0.0 {
                // K_ic and K_ci: the terms of rows i and c
                w[i] += v.abs() * (d[i] / d[c]).sqrt();
                w[c] += v.abs() * (d[c] / d[i]).sqrt();
            } else {
                // a DOF without stiffness does not reach the factorization
                w[i] = f64::INFINITY;
                w[c] = f64::INFINITY;
            }
        }
    }
    w
}

/// `|x_j|ᵀ|K||x_j|` for every column `x_j` of `x`, `K` symmetric and stored as its lower
/// triangle, in one pass over `K` for the whole block (the block is copied row-major so the
/// inner loop runs over contiguous columns): one sparse pass per block of right-hand sides
/// instead of one per column.
#[cfg(test)]
fn abs_quadratic_forms(k: &SparseColMat<usize, f64>, x: &Mat<f64>) -> Vec<f64> {
    let (n, w) = (x.nrows(), x.ncols());
    let mut a = vec![0.0; n * w];
    for j in 0..w {
        for (i, v) in x.col_as_slice(j).iter().enumerate() {
            a[i * w + j] = v.abs();
        }
    }
    let k = k.as_ref();
    let mut e = vec![0.0; w];
    for c in 0..n {
        let rows = k.symbolic().row_idx_of_col_raw(c);
        let vals = k.val_of_col(c);
        let ac = &a[c * w..(c + 1) * w];
        for (&i, &v) in rows.iter().zip(vals) {
            let f = if i == c { v.abs() } else { 2.0 * v.abs() };
            let ai = &a[i * w..(i + 1) * w];
            for ((ej, &x_i), &x_c) in e.iter_mut().zip(ai).zip(ac) {
                *ej += f * x_i * x_c;
            }
        }
    }
    e
}

/// The condensation of the factorized bonded structure (`lambda`: the stability check's
/// estimate of the smallest eigenvalue of the Jacobi-scaled `K_II`).
///
/// **How `R` is formed.** `K_II = Pᵀ L Lᵀ P` (a supernodal factor in nested-dissection order),
/// so `K_zI K_II⁻¹ K_Iz = YᵀY` with `Y = L⁻¹ P K_Iz`: forward substitution only, chunk by chunk
/// of 64 link columns, each chunk reaching only the supernodes on the elimination-tree paths
/// from its links' DOFs to the root. `YᵀY` is summed per supernode `s` over the chunks that
/// reached it (one dense product per pair of chunks), into the upper block triangle of `R`.
///
/// **The round-off rule.** With `τ` = [`ROUND_OFF`], `u` the unit round-off:
///
/// * *Diagonal* `R_jj`: zero exactly when `|R_jj| ≤ τ·mag_j`, `mag_j = K_zz,jj + Σ_a
///   |K_zI,ja x_ja| + Σ_a w_a x_ja²` — the rule of the previous condensation (the weighted
///   bound of [`abs_form_weights`]), with the static mode `x_j`.
///   `mag_j` is bracketed without `x_j`: below by `m0_j = K_zz,jj + ‖y_j‖²` (in exact
///   arithmetic `‖y_j‖² = K_zI,j x_j ≤ Σ_a |K_zI,ja x_ja|`), above by
///   `M̄_j = K_zz,jj + ‖k̂_j‖·ξ_j + ŵ·ξ_j²` with `ξ_j² = 2‖y_j‖²/λ̲`: in Jacobi-scaled variables
///   (`x̂ = D^½ x`, `k̂ = D^-½ k`, `K̂ = D^-½ K D^-½`, `D = diag K_II`) `‖y_j‖² = x̂ᵀK̂x̂ ≥
///   λ_min(K̂)‖x̂_j‖²`, so `‖x̂_j‖ ≤ ξ_j` (the factor 2 covers the round-off of the computed
///   `y_j`, `x_j`: relative `≲ u/λ ≤ 1e-3` for a structure the stability check accepts);
///   `Σ|K_zI,ja x_ja| = Σ|k̂_ja||x̂_ja| ≤ ‖k̂_j‖‖x̂_j‖` (Cauchy–Schwarz) and `Σ w_a x_ja² =
///   Σ ŵ_a x̂_ja² ≤ max_a ŵ_a ‖x̂_j‖²` (`ŵ_a = w_a/K_aa`, the row sums of `|K̂|`). `λ̲` is a
///   verified lower bound of `λ_min(K̂)` ([`verified_lower_eigenvalue`]; `0`, so `M̄ = ∞`,
///   when none is found). So `|R_jj| > τ·M̄_j` is kept and `|R_jj| ≤ τ·m0_j` is zeroed by the
///   old rule too; only a column between the two gets its backward solve and `mag_j`
///   itself: every diagonal decision is the old rule's.
/// * *Rows and columns of a zeroed diagonal* are zero: the exact `R` is positive semidefinite
///   (a Schur complement of the positive semidefinite stiffness), and a positive
///   semidefinite matrix with `R_jj = 0` has `R_ij = 0` for every `i` (`R_ij² ≤ R_ii R_jj`).
///   This is what keeps a determinate support's row exactly zero.
/// * *Other off-diagonal entries* are kept as computed. Until round 28 those below
///   `τ·√(m0_i m0_j)` were zeroed as round-off; they are the genuine far-field coupling of
///   two links (or its round-off), and late on a long path the bases are ill-conditioned
///   enough to need them: on a 600-bearing beam the zeroed `R` put the load after step 1404
///   at 136.54 where the structure's own equations, solved in double-double arithmetic,
///   give 136.688 (136.684 with them kept; the analysis crate's `sparse_zone.rs`).
/// * *`R_F`* (`R_F,j = K_zI,j x_b − b_z,j`, `x_b` solved in full): zero when `|R_F,j| ≤
///   τ·mag_F,j`, `mag_F,j = |b_z,j| + Σ_a |K_zI,ja x_b,a| + |x_j|ᵀ|K_II||x_b|` as before;
///   the last term lies in `[0, √(ŵ ξ_j² · Σ_a w_a x_b,a²)]` (the weighted bound of
///   [`abs_form_weights`] applied as Cauchy–Schwarz: `|K_ab||x_ja||x_b,b| ≤ |K̂_ab|(t x̂_ja² +
///   x̂_b,b²/t)/2` summed and minimised over `t`), so again only an entry inside the window
///   needs `x_j`. This holds in every row whose diagonal is not certainly kept (zeroed, or
///   decided by its mode): there the sign of `R_F,j` decides the pair, as for a determinate
///   support. In a row whose diagonal is certainly genuine stiffness `R_F,j` is zeroed on
///   the forward-only magnitude `|b_z,j| + Σ_a |K_zI,ja x_b,a|` (a subset of the old zeros):
///   the bound of the mode's term is global where the term is local (on a long strip `R_F`
///   of a load decays through every order of magnitude along the base, and most columns
///   would fall inside the window), and a round-off `R_F,j` kept there moves that row's
///   answer by round-off over its stiffness.
pub(crate) fn condense(
    asm: &Assembled,
    kii: Option<&SparseColMat<usize, f64>>,
    kzz: Mat<f64>,
    llt: Option<&Llt<usize, f64>>,
    lambda: f64,
) -> Condensation {
    condense_with(asm, kii, kzz, llt, lambda, Method::Fast)
}

/// How the solves and the round-off bound are computed.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Method {
    /// Forward substitution on the nested-dissection factor, full modes only where a
    /// decision needs them ([`condense`]).
    Fast,
    /// The formula before issue 11, kept as the tests' reference: full solves with [`Llt`]
    /// and the exact forms `|x_j|ᵀ|K_II||x_j|`.
    #[cfg(test)]
    Reference,
}

fn condense_with(
    asm: &Assembled,
    kii: Option<&SparseColMat<usize, f64>>,
    kzz: Mat<f64>,
    llt: Option<&Llt<usize, f64>>,
    lambda: f64,
    method: Method,
) -> Condensation {
    let (Some(kii_m), Some(llt_m)) = (kii, llt) else {
        return condense_full(asm, kii, kzz, None, None, false);
    };
    match method {
        Method::Fast => match Factor::dissected(kii_m) {
            Some(f) => condense_forward(asm, kii_m, kzz, llt_m, lambda, &f),
            None => condense_full(asm, kii, kzz, llt, Some(Solver::Plain(llt_m)), false),
        },
        #[cfg(test)]
        Method::Reference => condense_full(asm, kii, kzz, llt, Some(Solver::Plain(llt_m)), true),
    }
}

/// The load columns `x_b = K_II⁻¹ b_I` (full solves), `R_F` from them with the magnitudes of
/// its terms without the static modes (`|b_z| + Σ|K_zI x_b|`), and `|K_II||x_b|`.
struct Loads {
    xb: Mat<f64>,
    rf: [Vec<f64>; 2],
    rf_mag: [Vec<f64>; 2],
    kxb: Vec<Vec<f64>>,
}

fn loads(
    asm: &Assembled,
    kii: Option<&SparseColMat<usize, f64>>,
    llt: Option<&Llt<usize, f64>>,
) -> Loads {
    let n_i = asm.map.n_i;
    let nz = 2 * asm.map.m;
    let mut rf = [vec![0.0; nz], vec![0.0; nz]];
    let mut rf_mag = [vec![0.0; nz], vec![0.0; nz]];
    for g in 0..2 {
        for k in 0..nz {
            rf[g][k] = -asm.b_z[g][k];
            rf_mag[g][k] = asm.b_z[g][k].abs();
        }
    }
    let mut xb = Mat::<f64>::from_fn(n_i, 2, |i, g| asm.b_i[g][i]);
    let mut kxb = vec![Vec::new(), Vec::new()];
    if let Some(llt) = llt {
        llt.solve_in_place_with_conj(Conj::No, xb.as_mut());
        kxb = (0..2)
            .map(|g| kii.map_or_else(Vec::new, |k| abs_product(k, xb.col_as_slice(g))))
            .collect();
        for g in 0..2 {
            let xg = xb.col_as_slice(g);
            for row in 0..nz {
                let col = &asm.kiz[row];
                rf[g][row] += col.iter().map(|&(i, v)| v * xg[i]).sum::<f64>();
                rf_mag[g][row] += col.iter().map(|&(i, v)| (v * xg[i]).abs()).sum::<f64>();
            }
        }
    }
    Loads {
        xb,
        rf,
        rf_mag,
        kxb,
    }
}

/// A vector in the factor's row order (`p[row_of[a]] = v[a]`).
fn permuted(v: &[f64], row_of: &[usize]) -> Vec<f64> {
    let mut p = vec![0.0; v.len()];
    for (a, &x) in v.iter().enumerate() {
        p[row_of[a]] = x;
    }
    p
}

/// Symmetrizes `r` in place; returns the largest `|R_ij − R_ji|` relative to the largest
/// `|R_ij|`.
fn symmetrize(r: &mut Mat<f64>) -> f64 {
    let nz = r.nrows();
    let mut maxr = 0.0f64;
    let mut maxd = 0.0f64;
    for i in 0..nz {
        for j in 0..nz {
            maxr = maxr.max(r[(i, j)].abs());
            if j > i {
                maxd = maxd.max((r[(i, j)] - r[(j, i)]).abs());
                let a = 0.5 * (r[(i, j)] + r[(j, i)]);
                r[(i, j)] = a;
                r[(j, i)] = a;
            }
        }
    }
    if maxr > 0.0 {
        maxd / maxr
    } else {
        0.0
    }
}

/// The condensation with a full static mode per link column (the rule before issue 11 for
/// every entry): the fallback when no supernodal factor can be made, and the tests'
/// reference (`exact`: the exact forms `|x_j|ᵀ|K_II||x_j|` instead of the weighted bound).
fn condense_full(
    asm: &Assembled,
    kii: Option<&SparseColMat<usize, f64>>,
    kzz: Mat<f64>,
    llt: Option<&Llt<usize, f64>>,
    solver: Option<Solver<'_>>,
    exact: bool,
) -> Condensation {
    let n_i = asm.map.n_i;
    let nz = 2 * asm.map.m;
    let mut r = kzz;
    // magnitude of the terms of each diagonal entry of R, and of each entry of R_F
    let mut mag: Vec<f64> = (0..nz).map(|k| r[(k, k)].abs()).collect();
    let has_solver = solver.is_some();
    let Loads {
        mut rf,
        mut rf_mag,
        kxb,
        ..
    } = loads(asm, kii, llt);
    if let Some(solver) = solver {
        // everything the chunks meet, in the row order of the solutions
        let row_of = solver.row_of(n_i);
        let weights = permuted(&kii.map_or_else(Vec::new, abs_form_weights), &row_of);
        let kxb: Vec<Vec<f64>> = kxb
            .into_iter()
            .map(|v| {
                if v.is_empty() {
                    v
                } else {
                    permuted(&v, &row_of)
                }
            })
            .collect();
        let kiz: Vec<crate::dofs::Row> = asm
            .kiz
            .iter()
            .map(|c| c.iter().map(|&(i, v)| (row_of[i], v)).collect())
            .collect();
        let mut c0 = 0;
        while c0 < nz {
            let w = CHUNK.min(nz - c0);
            let cols: Vec<&crate::dofs::Row> = kiz[c0..c0 + w].iter().collect();
            let x = solver.solve_sparse(n_i, &cols);
            for row in 0..nz {
                let col = &kiz[row];
                if col.is_empty() {
                    continue;
                }
                for j in 0..w {
                    let xj = x.col_as_slice(j);
                    let s: f64 = col.iter().map(|&(i, v)| v * xj[i]).sum();
                    r[(row, c0 + j)] -= s;
                    if row == c0 + j {
                        mag[row] += col.iter().map(|&(i, v)| (v * xj[i]).abs()).sum::<f64>();
                    }
                }
            }
            // The round-off of the solves: the computed x_j satisfies K_II x_j = K_Iz,j up
            // to a residual of order u·|K_II|·|x_j|, which reaches R_ij as x_iᵀ·residual
            // (K_zI K_II⁻¹ = x_iᵀ): bounded by |x_i|ᵀ|K_II||x_j| ≤ √(e_i e_j) with
            // e_j = |x_j|ᵀ|K_II||x_j| ≤ Σ_a w_a x_ja² (abs_form_weights: O(n) per column
            // instead of a sparse pass). This grows with the number of elements the static
            // mode x_j spans, where the terms of K_zz and K_zI x_j alone do not.
            if let Some(_k) = kii {
                #[cfg(test)]
                let forms = exact.then(|| abs_quadratic_forms(_k, &x));
                #[cfg(not(test))]
                let forms: Option<Vec<f64>> = {
                    let _ = exact;
                    None
                };
                for j in 0..w {
                    let xj = x.col_as_slice(j);
                    mag[c0 + j] += match &forms {
                        Some(e) => e[j],
                        None => xj.iter().zip(&weights).map(|(x, w)| w * x * x).sum::<f64>(),
                    };
                    for g in 0..2 {
                        if !kxb[g].is_empty() {
                            rf_mag[g][c0 + j] += xj
                                .iter()
                                .zip(&kxb[g])
                                .map(|(a, b)| a.abs() * b)
                                .sum::<f64>();
                        }
                    }
                }
            }
            c0 += w;
        }
    }
    let asymmetry = symmetrize(&mut r);
    // Round-off to zero: a diagonal entry against the magnitude of its terms, and with it its
    // row and column (positive semidefinite). Entries off the diagonal are kept as computed
    // (see `condense`: a far-field coupling of that size is what an ill-conditioned basis
    // late on a long path needs).
    let zero_diag: Vec<bool> = (0..nz)
        .map(|j| r[(j, j)] == 0.0 || r[(j, j)].abs() <= ROUND_OFF * mag[j])
        .collect();
    let mut zeroed = zero_rows_of_zero_diagonals(&mut r, &zero_diag);
    zeroed += zero_load_round_off(&mut rf, &rf_mag);
    Condensation {
        r,
        rf,
        asymmetry,
        zeroed,
        exact_columns: if has_solver { nz } else { 0 },
    }
}

/// Sets the rows and columns of `r` whose diagonal is marked zero to zero; returns how many
/// entries it changed.
fn zero_rows_of_zero_diagonals(r: &mut Mat<f64>, zero_diag: &[bool]) -> usize {
    let nz = r.nrows();
    let mut zeroed = 0;
    for j in 0..nz {
        for i in 0..nz {
            if r[(i, j)] != 0.0 && (zero_diag[i] || zero_diag[j]) {
                r[(i, j)] = 0.0;
                zeroed += 1;
            }
        }
    }
    zeroed
}

/// Sets the entries of `R_F` below [`ROUND_OFF`] of their magnitudes to zero; returns how
/// many.
fn zero_load_round_off(rf: &mut [Vec<f64>; 2], rf_mag: &[Vec<f64>; 2]) -> usize {
    let mut zeroed = 0;
    for g in 0..2 {
        for (v, m) in rf[g].iter_mut().zip(&rf_mag[g]) {
            if *v != 0.0 && v.abs() <= ROUND_OFF * m {
                *v = 0.0;
                zeroed += 1;
            }
        }
    }
    zeroed
}

/// A lower bound of the smallest eigenvalue of the Jacobi-scaled `K̂ = D^-½ K_II D^-½`,
/// verified by a Cholesky factorization of `K̂ − σI` (same ordering as `f`) that succeeds in
/// floating point, with `σ` a fraction of the estimate `lambda`; `0` when none succeeds.
///
/// Proof. The matrix factorized is `A = fl(K̂) − σI` rounded: each scaled entry carries a
/// relative error of at most `3u` (a product, a square root, a quotient) and the diagonal
/// shift one more rounding, so `A = K̂ − σI + E` with `‖E‖₂ ≤ 4u·(max_a ŵ_a + 1)` (`ŵ_a` the
/// row sums of `|K̂|`, which bound `‖|K̂|‖₂`). A Cholesky factorization whose inner products
/// have at most `k` terms (`k` the largest row count of `L`) that runs to completion gives
/// `L̃L̃ᵀ = A + ΔA`, `|ΔA| ≤ γ_{k+1}|L̃||L̃ᵀ|` (Higham, *Accuracy and Stability of Numerical
/// Algorithms*, Thm. 10.5, for any order of the sums), so `‖ΔA‖₂ ≤ γ_{k+1}‖L̃‖_F²` and
/// `‖L̃‖_F² = tr(A + ΔA) ≤ tr A + γ_{k+1}‖L̃‖_F²`: `‖ΔA‖₂ ≤ γ_{k+1}/(1 − γ_{k+1})·tr A`. `A + ΔA`
/// is positive semidefinite, so by Weyl `λ_min(K̂) ≥ σ − ‖E‖₂ − ‖ΔA‖₂`.
fn verified_lower_eigenvalue(
    kii: &SparseColMat<usize, f64>,
    diag: &[f64],
    f: &Factor,
    lambda: f64,
    max_w_hat: f64,
) -> f64 {
    let u = UNIT_ROUND_OFF;
    let n = kii.nrows();
    if !(lambda.is_finite() && lambda > 0.0 && max_w_hat.is_finite()) {
        return 0.0;
    }
    let k = f.max_row_count() as f64 + 1.0;
    if k * u >= 0.1 {
        return 0.0;
    }
    let gamma = k * u / (1.0 - k * u);
    let s = kii.symbolic();
    let sq: Vec<f64> = diag.iter().map(|d| d.sqrt()).collect();
    for sigma in [lambda / 4.0, lambda / 64.0] {
        let mut vals = kii.val().to_vec();
        let mut trace = 0.0;
        for c in 0..n {
            for idx in s.col_range(c) {
                let i = s.row_idx()[idx];
                vals[idx] /= sq[i] * sq[c];
                if i == c {
                    vals[idx] -= sigma;
                    trace += vals[idx].abs();
                }
            }
        }
        let a = SparseColMatRef::new(s, &vals);
        if f.numeric(a).is_some() {
            let bound = sigma - 4.0 * u * (max_w_hat + 1.0) - gamma / (1.0 - gamma) * trace;
            return bound.max(0.0);
        }
    }
    0.0
}

/// Where the round-off decision of a column stands without its static mode.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Decision {
    Keep,
    Zero,
    /// Between the bounds: the full mode decides.
    Exact,
}

/// `|v| ≤ τ·lo` is zero, `|v| > τ·hi` is kept, in between the exact magnitude decides.
fn decide(v: f64, lo: f64, hi: f64) -> Decision {
    if v == 0.0 || v.abs() <= ROUND_OFF * lo {
        Decision::Zero
    } else if v.abs() > ROUND_OFF * hi {
        Decision::Keep
    } else {
        Decision::Exact
    }
}

/// The forward-only condensation of [`condense`].
fn condense_forward(
    asm: &Assembled,
    kii: &SparseColMat<usize, f64>,
    kzz: Mat<f64>,
    llt: &Llt<usize, f64>,
    lambda: f64,
    f: &Factor,
) -> Condensation {
    let n_i = asm.map.n_i;
    let nz = 2 * asm.map.m;
    let mut r = kzz;
    let kzz_diag: Vec<f64> = (0..nz).map(|k| r[(k, k)]).collect();
    let Loads {
        xb,
        mut rf,
        rf_mag: rf_lo,
        kxb,
    } = loads(asm, Some(kii), Some(llt));
    let weights = abs_form_weights(kii);
    let diag = &asm.diag;
    let max_w_hat = weights
        .iter()
        .zip(diag)
        .fold(0.0f64, |m, (w, d)| m.max(w / d));
    // Σ_a w_a x_b,a²: the weighted bound of |x_b|ᵀ|K||x_b| for the two load columns
    let e_b: Vec<f64> = (0..2)
        .map(|g| {
            xb.col_as_slice(g)
                .iter()
                .zip(&weights)
                .map(|(x, w)| w * x * x)
                .sum()
        })
        .collect();
    // ‖k̂_j‖² = Σ_a K_zI,ja²/K_aa
    let khat2: Vec<f64> = asm
        .kiz
        .iter()
        .map(|c| c.iter().map(|&(i, v)| v * v / diag[i]).sum())
        .collect();
    let row_of = f.row_of(n_i);
    let kiz: Vec<crate::dofs::Row> = asm
        .kiz
        .iter()
        .map(|c| c.iter().map(|&(i, v)| (row_of[i], v)).collect())
        .collect();

    // Y = L⁻¹ P K_Iz, chunk by chunk; each processed supernode's rows kept as a dense block
    let l = f.l();
    let ns = l.symbolic().n_supernodes();
    let sn_of = supernode_of_rows(&l);
    let mut blocks: Vec<Vec<(usize, usize)>> = vec![Vec::new(); ns]; // (chunk, offset)
    let mut data: Vec<f64> = Vec::new();
    let mut ynorm2 = vec![0.0; nz];
    let mut buf = Mat::<f64>::zeros(n_i, CHUNK.min(nz));
    let mut touched = vec![false; ns];
    let chunks: Vec<(usize, usize)> = (0..nz)
        .step_by(CHUNK)
        .map(|c0| (c0, CHUNK.min(nz - c0)))
        .collect();
    for (c, &(c0, w)) in chunks.iter().enumerate() {
        touched.fill(false);
        let mut x = buf.as_mut().subcols_mut(0, w);
        for j in 0..w {
            for &(i, v) in &kiz[c0 + j] {
                x[(i, j)] = v;
                touched[sn_of[i]] = true;
            }
        }
        forward_sparse(l, x.rb_mut(), &mut touched, &sn_of, |s, ys| {
            blocks[s].push((c, data.len()));
            for j in 0..w {
                let col = ys.col(j);
                let mut acc = 0.0;
                for v in col.iter() {
                    data.push(*v);
                    acc += v * v;
                }
                ynorm2[c0 + j] += acc;
            }
        });
        // clear what this chunk wrote: the rows of the processed supernodes
        for (s, t) in touched.iter().enumerate() {
            if *t {
                let sn = l.supernode(s);
                x.rb_mut()
                    .subrows_mut(sn.start(), sn.val().ncols())
                    .fill(0.0);
            }
        }
    }
    drop(buf);

    // R = K_zz − YᵀY: K_zz symmetrized first, then the upper block triangle of YᵀY
    let asym_kzz = symmetrize(&mut r);
    for s in 0..ns {
        let list = &blocks[s];
        if list.is_empty() {
            continue;
        }
        let size = l.supernode(s).val().ncols();
        for (a, &(ca, oa)) in list.iter().enumerate() {
            let (c0a, wa) = chunks[ca];
            let ya = MatRef::from_column_major_slice(&data[oa..oa + size * wa], size, wa);
            for &(cb, ob) in &list[a..] {
                let (c0b, wb) = chunks[cb];
                let yb = MatRef::from_column_major_slice(&data[ob..ob + size * wb], size, wb);
                faer::linalg::matmul::matmul(
                    r.as_mut().submatrix_mut(c0a, c0b, wa, wb),
                    Accum::Add,
                    ya.transpose(),
                    yb,
                    -1.0,
                    Par::Seq,
                );
            }
        }
    }
    drop(data);
    drop(blocks);
    // the lower block triangle from the upper; the diagonal blocks averaged
    let chunk_of = |i: usize| i / CHUNK;
    let mut maxr = 0.0f64;
    let mut maxd = 0.0f64;
    for j in 0..nz {
        for i in 0..j {
            if chunk_of(i) == chunk_of(j) {
                maxd = maxd.max((r[(i, j)] - r[(j, i)]).abs());
                let a = 0.5 * (r[(i, j)] + r[(j, i)]);
                r[(i, j)] = a;
                r[(j, i)] = a;
            } else {
                r[(j, i)] = r[(i, j)];
            }
            maxr = maxr.max(r[(i, j)].abs());
        }
        maxr = maxr.max(r[(j, j)].abs());
    }
    let asymmetry = asym_kzz.max(if maxr > 0.0 { maxd / maxr } else { 0.0 });

    // the decisions without the static modes
    let lam = verified_lower_eigenvalue(kii, diag, f, lambda, max_w_hat);
    let m0: Vec<f64> = (0..nz).map(|j| kzz_diag[j].abs() + ynorm2[j]).collect();
    let xi2: Vec<f64> = (0..nz)
        .map(|j| {
            if lam > 0.0 {
                2.0 * ynorm2[j] / lam
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let mut diag_dec: Vec<Decision> = (0..nz)
        .map(|j| {
            let hi = kzz_diag[j].abs() + (khat2[j] * xi2[j]).sqrt() + max_w_hat * xi2[j];
            decide(r[(j, j)], m0[j], hi)
        })
        .collect();
    // R_F: the old rule where the diagonal is not certainly kept; in a row of certainly
    // genuine stiffness the forward-only magnitude (see `condense`)
    let mut rf_dec: Vec<[Decision; 2]> = (0..nz)
        .map(|j| {
            [0, 1].map(|g| {
                let lo = rf_lo[g][j];
                let hi = if diag_dec[j] == Decision::Keep {
                    lo
                } else {
                    lo + (max_w_hat * xi2[j] * e_b[g]).sqrt()
                };
                decide(rf[g][j], lo, hi)
            })
        })
        .collect();

    // the columns between the bounds: their full modes and the magnitudes with them
    let exact: Vec<usize> = (0..nz)
        .filter(|&j| diag_dec[j] == Decision::Exact || rf_dec[j].contains(&Decision::Exact))
        .collect();
    if !exact.is_empty() {
        let w_perm = permuted(&weights, &row_of);
        let kxb: Vec<Vec<f64>> = kxb.iter().map(|v| permuted(v, &row_of)).collect();
        let solver = Solver::Supernodal(f);
        for group in exact.chunks(CHUNK) {
            let cols: Vec<&crate::dofs::Row> = group.iter().map(|&j| &kiz[j]).collect();
            let x = solver.solve_sparse(n_i, &cols);
            for (k, &j) in group.iter().enumerate() {
                let xj = x.col_as_slice(k);
                if diag_dec[j] == Decision::Exact {
                    let mag = kzz_diag[j].abs()
                        + kiz[j].iter().map(|&(i, v)| (v * xj[i]).abs()).sum::<f64>()
                        + xj.iter().zip(&w_perm).map(|(x, w)| w * x * x).sum::<f64>();
                    diag_dec[j] = decide(r[(j, j)], mag, mag);
                }
                for g in 0..2 {
                    if rf_dec[j][g] == Decision::Exact {
                        let mag = rf_lo[g][j]
                            + xj.iter()
                                .zip(&kxb[g])
                                .map(|(a, b)| a.abs() * b)
                                .sum::<f64>();
                        rf_dec[j][g] = decide(rf[g][j], mag, mag);
                    }
                }
            }
        }
    }

    // apply: zeroed diagonals with their rows and columns
    let zero_diag: Vec<bool> = diag_dec.iter().map(|d| *d == Decision::Zero).collect();
    let mut zeroed = zero_rows_of_zero_diagonals(&mut r, &zero_diag);
    for g in 0..2 {
        for j in 0..nz {
            if rf_dec[j][g] == Decision::Zero && rf[g][j] != 0.0 {
                rf[g][j] = 0.0;
                zeroed += 1;
            }
        }
    }
    Condensation {
        r,
        rf,
        asymmetry,
        zeroed,
        exact_columns: exact.len(),
    }
}

#[cfg(test)]
mod abs_form_tests {
    use super::{abs_product, abs_quadratic_forms};
    use faer::sparse::{SparseColMat, Triplet};
    use faer::Mat;

    /// The block form agrees with `|x|ᵀ(|K||x|)` column by column (a 3×3 symmetric `K` with
    /// negative entries, stored as its lower triangle; hand value of the first column:
    /// |x| = (1, 2, 0.5), |K| = [[4,1,0],[1,3,2],[0,2,5]] → 4 + 2·1·2 + 3·4 + 2·2·2·0.5 + 5·0.25).
    #[test]
    fn block_forms_agree_with_the_products() {
        let lower = [
            (0, 0, 4.0),
            (1, 0, -1.0),
            (1, 1, 3.0),
            (2, 1, 2.0),
            (2, 2, 5.0),
        ];
        let trip: Vec<_> = lower
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let k = SparseColMat::<usize, f64>::try_new_from_triplets(3, 3, &trip).unwrap();
        let x = Mat::from_fn(3, 2, |i, j| [[1.0, -2.0, 0.5], [0.0, 1.0, -3.0]][j][i]);
        let e = abs_quadratic_forms(&k, &x);
        assert_eq!(e[0], 4.0 + 4.0 + 12.0 + 4.0 + 1.25);
        for j in 0..2 {
            let xj = x.col_as_slice(j);
            let y = abs_product(&k, xj);
            let direct: f64 = xj.iter().zip(&y).map(|(a, b)| a.abs() * b).sum();
            assert!(
                (e[j] - direct).abs() <= 1e-15 * direct,
                "{} vs {direct}",
                e[j]
            );
        }
    }
}

#[cfg(test)]
mod reference_tests {
    //! The condensation against the formula it replaced (issue 11): full solves with `Llt`
    //! and the exact round-off forms. Both compute `R = K_zz − K_zI K_II⁻¹ K_Iz` in floating
    //! point from the same factor ordering, so they agree to round-off; the zeroed entries
    //! agree because the weighted bound exceeds the exact form by a small factor only.
    use super::{condense_with, Method};
    use crate::assemble::assemble;
    use crate::model::{ContactPairSpec, FrameSection, Load, LoadGroup, Model};
    use crate::model::{NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial, SupportDof};
    use crate::stability::factorize;

    /// Compares the two ways entry by entry, to round-off of the terms that form each entry
    /// (`K_zz`: a small entry such as the tip stiffness of a fine cantilever is what is left
    /// of the cancellation of much larger terms, and its round-off is relative to them). The
    /// zero patterns: the same diagonal and the same `R_F` (both decided by the old rule, see
    /// `condense`), every zero off the diagonal also a zero of the reference (the new rule
    /// zeroes a subset there), and the rows and columns of a zeroed diagonal zero.
    fn compare(model: &Model) -> (super::Condensation, super::Condensation) {
        let mut asm = assemble(model).unwrap();
        let (llt, lambda) = factorize(model, &asm).unwrap();
        let kzz = asm.kzz.clone();
        let kii = asm.kii.take();
        let run = |method| {
            condense_with(
                &asm,
                kii.as_ref(),
                kzz.clone(),
                llt.as_ref(),
                lambda,
                method,
            )
        };
        let fast = run(Method::Fast);
        let refr = run(Method::Reference);
        let n = fast.r.nrows();
        let kzz = &asm.kzz;
        for i in 0..n {
            for j in 0..n {
                let (a, b) = (fast.r[(i, j)], refr.r[(i, j)]);
                let scale = (kzz[(i, i)] * kzz[(j, j)]).abs().sqrt();
                assert!((a - b).abs() <= 1e-12 * scale, "R[{i},{j}]: {a} vs {b}");
                if i == j {
                    assert_eq!(a == 0.0, b == 0.0, "zero pattern at R[{i},{i}]: {a} vs {b}");
                } else {
                    assert!(
                        a != 0.0 || b == 0.0,
                        "a new zero at R[{i},{j}]: reference {b}"
                    );
                }
                if fast.r[(i, i)] == 0.0 || fast.r[(j, j)] == 0.0 {
                    assert_eq!(a, 0.0, "R[{i},{j}] in the row of a zeroed diagonal");
                }
            }
        }
        for g in 0..2 {
            let s = refr.rf[g].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for k in 0..n {
                let (a, b) = (fast.rf[g][k], refr.rf[g][k]);
                assert!((a - b).abs() <= 1e-12 * s, "R_F{g}[{k}]: {a} vs {b}");
                assert_eq!(a == 0.0, b == 0.0, "zero pattern at R_F{g}[{k}]");
            }
        }
        (fast, refr)
    }

    /// Soil block of 24 × 6 QM6 on 24 frictional base pairs (supernodal factor, many
    /// right-hand sides in several chunks).
    #[test]
    fn soil_block_agrees_with_the_reference() {
        let (nx, ny) = (40, 6);
        let mut m = Model::new();
        let grid = crate::mesh::BlockGrid::new([0.0; 2], 0.5 * nx as f64, 0.4 * ny as f64, nx, ny);
        let id: Vec<NodeId> = grid
            .points()
            .iter()
            .map(|p| m.add_node(p[0], p[1]))
            .collect();
        let node = |i: usize, j: usize| id[grid.index(i, j)];
        for cell in grid.cells() {
            m.add_plane(
                cell.map(|k| id[k]),
                PlaneMaterial::new(3e4, 0.3),
                PlaneAnalysis::PlaneStrain,
                PlaneFormulation::QM6,
            );
        }
        m.pin(node(0, 0));
        for j in 1..=ny {
            m.add_support(node(nx, j), SupportDof::Ux);
        }
        for i in 1..=nx {
            m.add_contact_pair(ContactPairSpec::to_ground(node(i, 0), [0.0, 1.0]).friction(0.3));
        }
        for i in 0..=nx / 3 {
            m.add_load(
                LoadGroup::Variable,
                Load::Nodal {
                    node: node(i, ny),
                    fx: 0.1,
                    fy: -1.0,
                    m: 0.0,
                },
            );
        }
        compare(&m);
    }

    /// A beam on a pin and one bearing, in 1 … 40 elements: the bearing's normal stiffness is
    /// exactly zero (the beam turns about the pin), and both ways zero it.
    #[test]
    fn determinate_support_is_zero_both_ways() {
        for n in [1, 2, 5, 20, 40] {
            let mut m = Model::new();
            let nodes: Vec<NodeId> = (0..=n)
                .map(|i| m.add_node(6.0 * i as f64 / n as f64, 0.0))
                .collect();
            for w in nodes.windows(2) {
                m.add_frame(w[0], w[1], FrameSection::new(2.1e8, 0.01, 1e-4));
            }
            m.pin(nodes[0]);
            m.add_contact_pair(ContactPairSpec::to_ground(nodes[n], [0.0, 1.0]).friction(0.2));
            m.add_load(
                LoadGroup::Variable,
                Load::Nodal {
                    node: nodes[n / 2],
                    fx: 0.0,
                    fy: -1.0,
                    m: 0.0,
                },
            );
            let (fast, refr) = compare(&m);
            assert_eq!(fast.r[(0, 0)], 0.0, "{n} elements");
            assert_eq!(refr.r[(0, 0)], 0.0, "{n} elements");
        }
    }

    /// A cantilever of 400 elements with a tip pair: its small genuine tip stiffness is kept
    /// both ways.
    #[test]
    fn fine_cantilever_keeps_its_tip_stiffness() {
        let n = 400;
        let mut m = Model::new();
        let nodes: Vec<NodeId> = (0..=n)
            .map(|i| m.add_node(3.0 * i as f64 / n as f64, 0.0))
            .collect();
        for w in nodes.windows(2) {
            m.add_frame(w[0], w[1], FrameSection::new(3e7, 0.02, 2e-5));
        }
        m.fix(nodes[0]);
        m.add_contact_pair(ContactPairSpec::to_ground(nodes[n], [0.0, 1.0]));
        m.add_load(
            LoadGroup::Variable,
            Load::Nodal {
                node: nodes[n],
                fx: 0.0,
                fy: -1.0,
                m: 0.0,
            },
        );
        let (fast, _) = compare(&m);
        // hand value: 3EI/L³ = 3·3e7·2e-5/27, what is left of terms of the size of K_zz
        // (12EI/h³ of the last element), to round-off of those terms
        let k = 3.0 * 3e7 * 2e-5 / 27.0;
        let h = 3.0 / n as f64;
        let terms = 12.0 * 3e7 * 2e-5 / (h * h * h);
        assert!(fast.r[(0, 0)] > 0.0);
        assert!(
            (fast.r[(0, 0)] - k).abs() <= 1e-12 * terms,
            "{} vs {k}",
            fast.r[(0, 0)]
        );
    }

    /// Two beams in one model: a continuous beam on 30 frictional bearings (every link a
    /// genuine stiffness) and, apart, a beam of 400 elements on a pin and one bearing (that
    /// bearing's `Rnn` is exactly zero: the beam turns about the pin). The reference is the
    /// old rule (`compare`); the screening must give the determinate bearing's column its
    /// full static mode and spare the others. With 400 elements the round-off of the rigid
    /// turn in `R_nn` exceeds `τ` of the forward-only magnitude `m0` (with 20 or 100 elements
    /// it does not, and the column is certainly zero without its mode), while the verified
    /// `λ̲` still bounds the others (from about 1000 elements `λ` ≈ 4e-12 is below the
    /// margin of its verification, and every undecided column is solved in full).
    #[test]
    fn screening_gives_the_determinate_column_its_exact_mode() {
        let m = two_beams(1.0, 1.0);
        let (fast, _) = compare(&m);
        let nz = fast.r.nrows();
        let bearing = 30; // the last pair: the determinate beam's bearing, normal row
        assert_eq!(fast.r[(bearing, bearing)], 0.0);
        for i in 0..nz {
            assert_eq!(fast.r[(i, bearing)], 0.0, "R[{i},{bearing}]");
        }
        assert!(fast.exact_columns >= 1, "no column needed its mode");
        assert!(
            fast.exact_columns <= 4,
            "{} of {nz} columns solved in full",
            fast.exact_columns
        );
        for j in 0..30 {
            assert!(fast.r[(j, j)] > 0.0, "genuine bearing {j}");
        }
    }

    /// The same two beams in N, m and in kN, mm (`E`·1e-9, `A`·1e6, `I`·1e12, lengths·1e3,
    /// forces·1e-3): `R` (N/m → kN/mm) is the first `R` times 1e-6 and `R_F` (N → kN) times
    /// 1e-3, to round-off of the terms of each entry (the unit factors are not powers of two,
    /// so the products are not exact; the solves of the 400-element beam carry relative
    /// errors up to `u/λ`, as `tests/it/fine_mesh.rs` states, so the tolerance is
    /// `max(1e-12, 4u/λ)`), with the same entries zeroed: the rule is as independent of units
    /// as the data (reference: the change of units itself).
    #[test]
    fn units_scale_r_and_keep_its_zeros() {
        let cond = |m: &Model| {
            let mut asm = assemble(m).unwrap();
            let (llt, lambda) = factorize(m, &asm).unwrap();
            let kzz = asm.kzz.clone();
            let kii = asm.kii.take();
            let c = condense_with(&asm, kii.as_ref(), kzz, llt.as_ref(), lambda, Method::Fast);
            (c, asm.kzz.clone(), lambda)
        };
        let (a, kzz, lambda) = cond(&two_beams(1.0, 1.0));
        let (b, _, _) = cond(&two_beams(1e3, 1e-3));
        let tol = 1e-12f64.max(4.0 * f64::EPSILON / 2.0 / lambda);
        let n = a.r.nrows();
        assert!(a.zeroed > 0);
        assert_eq!(a.zeroed, b.zeroed);
        for i in 0..n {
            for j in 0..n {
                let (x, y) = (a.r[(i, j)] * 1e-6, b.r[(i, j)]);
                let scale = (kzz[(i, i)] * kzz[(j, j)]).abs().sqrt() * 1e-6;
                assert!((x - y).abs() <= tol * scale, "R[{i},{j}]: {x} vs {y}");
                assert_eq!(x == 0.0, y == 0.0, "zero pattern at R[{i},{j}]");
            }
        }
        for g in 0..2 {
            let s = a.rf[g].iter().fold(0.0f64, |m, v| m.max(v.abs())) * 1e-3;
            for k in 0..n {
                let (x, y) = (a.rf[g][k] * 1e-3, b.rf[g][k]);
                assert!((x - y).abs() <= tol * s, "R_F{g}[{k}]: {x} vs {y}");
                assert_eq!(x == 0.0, y == 0.0, "zero pattern at R_F{g}[{k}]");
            }
        }
    }

    /// The model of the two tests above, with lengths times `lf` and forces times `ff`.
    fn two_beams(lf: f64, ff: f64) -> Model {
        let nd = 400;
        let section = FrameSection::new(2.1e11 * ff / (lf * lf), 0.01 * lf * lf, 1e-4 * lf.powi(4));
        let mut m = Model::new();
        // continuous beam of 60 elements on 30 bearings, pinned at its left end
        let n = 60;
        let cont: Vec<NodeId> = (0..=n)
            .map(|i| m.add_node(0.5 * lf * i as f64, 0.0))
            .collect();
        for w in cont.windows(2) {
            m.add_frame(w[0], w[1], section);
        }
        m.pin(cont[0]);
        for k in 1..=30 {
            m.add_contact_pair(ContactPairSpec::to_ground(cont[2 * k], [0.0, 1.0]).friction(0.3));
        }
        // apart: a beam of 20 elements on a pin and one bearing
        let d: Vec<NodeId> = (0..=nd)
            .map(|i| m.add_node(6.0 / nd as f64 * lf * i as f64, 10.0 * lf))
            .collect();
        for w in d.windows(2) {
            m.add_frame(w[0], w[1], section);
        }
        m.pin(d[0]);
        m.add_contact_pair(ContactPairSpec::to_ground(d[nd], [0.0, 1.0]).friction(0.3));
        for node in [cont[15], cont[41], d[nd / 3]] {
            m.add_load(
                LoadGroup::Variable,
                Load::Nodal {
                    node,
                    fx: 100.0 * ff,
                    fy: -1e4 * ff,
                    m: 0.0,
                },
            );
        }
        m
    }
}

#[cfg(test)]
mod eigenvalue_bound_tests {
    use super::{abs_form_weights, verified_lower_eigenvalue, Factor};
    use faer::sparse::{SparseColMat, Triplet};

    /// The 1D Laplacian `tridiag(−1, 2, −1)` of order 300: its Jacobi-scaled form has the
    /// smallest eigenvalue `1 − cos(π/301)` (closed form). The verified bound lies below it
    /// and, from an estimate at that value, within the factor 4 of its first shift.
    #[test]
    fn the_verified_bound_is_below_the_closed_form() {
        let n = 300;
        let mut t = Vec::new();
        for i in 0..n {
            t.push(Triplet::new(i, i, 2.0));
            if i + 1 < n {
                t.push(Triplet::new(i + 1, i, -1.0));
            }
        }
        let k = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &t).unwrap();
        let exact = 1.0 - (std::f64::consts::PI / (n as f64 + 1.0)).cos();
        let f = Factor::dissected(&k).unwrap();
        let diag = vec![2.0; n];
        let w = abs_form_weights(&k);
        let max_w_hat = w.iter().zip(&diag).fold(0.0f64, |m, (w, d)| m.max(w / d));
        assert_eq!(max_w_hat, 2.0);
        let lb = verified_lower_eigenvalue(&k, &diag, &f, exact, max_w_hat);
        assert!(lb <= exact, "{lb} vs {exact}");
        // less the margin of the verification, below 2·γ_{n+1}·tr ≈ 2·(n + 1)·u·n (every row
        // count of L is at most n)
        let margin = 2.0 * (n as f64 + 1.0) * f64::EPSILON / 2.0 * n as f64;
        assert!(lb >= exact / 4.0 - margin, "{lb} vs {exact}");
        // an estimate far too high (the shifted matrix is indefinite) gives no bound or a
        // lower one, never one above the eigenvalue
        let lb = verified_lower_eigenvalue(&k, &diag, &f, 100.0 * exact, max_w_hat);
        assert!(lb <= exact, "{lb} vs {exact}");
    }
}
