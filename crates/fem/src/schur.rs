//! The condensation of the factorized bonded structure to its contact zone: the Schur
//! complement `R = K_zz − K_zI K_II⁻¹ K_Iz` and the contact load vectors
//! `R_F = K_zI K_II⁻¹ b_I − b_z` (formulation.md §2), with the round-off of exact zeros set
//! to zero.

use crate::assemble::Assembled;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::solvers::SolveCore;
use faer::reborrow::ReborrowMut;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMat;
use faer::{Accum, Conj, Mat, MatMut, Par, Side};

/// The condensed contact-zone data.
pub(crate) struct Condensation {
    pub r: Mat<f64>,
    pub rf: [Vec<f64>; 2],
    pub asymmetry: f64,
    /// Entries of `R` and `R_F` set to zero as round-off (see [`ROUND_OFF`]).
    pub zeroed: usize,
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
/// genuine entries.
pub(crate) const ROUND_OFF: f64 = 8.0 * f64::EPSILON / 2.0;

/// The solves `K_II X = K_Iz` of the condensation. The right-hand sides are sparse (a link
/// DOF touches the few free DOFs of its node), so with the supernodal factor at hand the
/// forward substitution skips every supernode whose block of the (permuted) right-hand
/// sides is still zero: the skipped work is exactly zero (`0 − L·0`), so the result is the
/// same bit for bit as a full supernodal solve, at a fraction of the forward half's cost.
/// The factor is always supernodal (where [`Llt`] may have chosen a simplicial one, so the
/// round-off can differ from its solve); [`Solver::Plain`], [`Llt`]'s own solve, is the
/// fallback when that factorization cannot be made, and the tests' reference.
enum Solver<'a> {
    Supernodal {
        symbolic: Box<SymbolicCholesky<usize>>,
        values: Vec<f64>,
    },
    Plain(&'a Llt<usize, f64>),
}

impl<'a> Solver<'a> {
    /// Refactorizes `K_II` (same ordering and algorithm as [`Llt`]: AMD, default thresholds)
    /// to reach its supernodes, which [`Llt`] does not expose; falls back to `llt` when the
    /// factor is simplicial or the factorization fails.
    fn new(kii: Option<&SparseColMat<usize, f64>>, llt: &'a Llt<usize, f64>) -> Self {
        let plain = Solver::Plain(llt);
        let Some(kii) = kii else { return plain };
        let Ok(symbolic) = factorize_symbolic_cholesky(
            kii.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        ) else {
            return plain;
        };
        if !matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)) {
            return plain;
        }
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let Ok(mut buf) = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        ) else {
            return plain;
        };
        let ok = symbolic
            .factorize_numeric_llt::<f64>(
                &mut values,
                kii.as_ref(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .is_ok();
        if ok {
            Solver::Supernodal {
                symbolic: Box::new(symbolic),
                values,
            }
        } else {
            plain
        }
    }

    /// The position of each free DOF in the rows [`Solver::solve_sparse`] returns: the fill-
    /// reducing permutation of the supernodal factor (so that no chunk is permuted back), the
    /// identity for [`Llt`]'s solve.
    fn row_of(&self, n_i: usize) -> Vec<usize> {
        match self {
            Solver::Supernodal { symbolic, .. } => match symbolic.perm() {
                Some(p) => p.arrays().1.to_vec(),
                None => (0..n_i).collect(),
            },
            Solver::Plain(_) => (0..n_i).collect(),
        }
    }

    /// Solves `K_II X = B` for the columns `cols` of `K_Iz`, returning `X` (`n_i × cols.len()`)
    /// with its rows in the order of [`Solver::row_of`].
    fn solve_sparse(&self, n_i: usize, cols: &[crate::dofs::Row]) -> Mat<f64> {
        let w = cols.len();
        match self {
            Solver::Plain(llt) => {
                let mut x = Mat::<f64>::zeros(n_i, w);
                for (j, col) in cols.iter().enumerate() {
                    for &(i, v) in col {
                        x[(i, j)] = v;
                    }
                }
                llt.solve_in_place_with_conj(Conj::No, x.as_mut());
                x
            }
            Solver::Supernodal { symbolic, values } => {
                let SymbolicCholeskyRaw::Supernodal(sym) = symbolic.raw() else {
                    unreachable!("checked in Solver::new")
                };
                let inv: Vec<usize> = match symbolic.perm() {
                    Some(p) => p.arrays().1.to_vec(),
                    None => (0..n_i).collect(),
                };
                // permuted right-hand sides: row inv[i] holds entry i
                let mut xp = Mat::<f64>::zeros(n_i, w);
                for (j, col) in cols.iter().enumerate() {
                    for &(i, v) in col {
                        xp[(inv[i], j)] = v;
                    }
                }
                let l = SupernodalLltRef::<'_, usize, f64>::new(sym, values);
                forward_sparse(l, &mut xp);
                let par = Par::Seq;
                let mut buf = MemBuffer::new(sym.solve_in_place_scratch::<f64>(w, par));
                l.l_transpose_solve_with_conj(Conj::No, xp.as_mut(), par, MemStack::new(&mut buf));
                xp
            }
        }
    }
}

/// `L Y = B` in place for the supernodal `L`, skipping the supernodes whose rows of `B` are
/// still all zero (their update of the later rows is zero).
fn forward_sparse(l: SupernodalLltRef<'_, usize, f64>, x: &mut Mat<f64>) {
    let k = x.ncols();
    let mut tmp: Vec<f64> = Vec::new();
    for s in 0..l.symbolic().n_supernodes() {
        let sn = l.supernode(s);
        let ls = sn.val();
        let size = ls.ncols();
        let start = sn.start();
        let zero = (0..k).all(|j| {
            x.col_as_slice(j)[start..start + size]
                .iter()
                .all(|v| *v == 0.0)
        });
        if zero {
            continue;
        }
        let (ls_top, ls_bot) = ls.split_at_row(size);
        let pattern = sn.pattern();
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(
            ls_top,
            x.as_mut().subrows_mut(start, size),
            Par::Seq,
        );
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
            x.as_ref().subrows(start, size),
            1.0,
            Par::Seq,
        );
        for j in 0..k {
            let xj = x.col_as_slice_mut(j);
            let tj = &tmp[j * pattern.len()..(j + 1) * pattern.len()];
            for (&i, &v) in pattern.iter().zip(tj) {
                xj[i] -= v;
            }
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

pub(crate) fn condense(
    asm: &Assembled,
    kii: Option<&SparseColMat<usize, f64>>,
    kzz: Mat<f64>,
    llt: Option<&Llt<usize, f64>>,
) -> Condensation {
    condense_with(asm, kii, kzz, llt, Method::Fast)
}

/// How the solves and the round-off bound are computed.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Method {
    /// Sparse forward substitution on the supernodal factor and the weighted bound
    /// ([`abs_form_weights`]).
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
    method: Method,
) -> Condensation {
    let n_i = asm.map.n_i;
    let nz = 2 * asm.map.m;
    let mut r = kzz;
    // magnitude of the terms of each diagonal entry of R, and of each entry of R_F
    let mut mag: Vec<f64> = (0..nz).map(|k| r[(k, k)].abs()).collect();
    let mut rf = [vec![0.0; nz], vec![0.0; nz]];
    let mut rf_mag = [vec![0.0; nz], vec![0.0; nz]];
    for g in 0..2 {
        for k in 0..nz {
            rf[g][k] = -asm.b_z[g][k];
            rf_mag[g][k] = asm.b_z[g][k].abs();
        }
    }
    if let Some(llt) = llt {
        // the load columns first: their |K_II|·|x| enter the magnitudes of R_F below
        let mut xb = Mat::<f64>::from_fn(n_i, 2, |i, g| asm.b_i[g][i]);
        llt.solve_in_place_with_conj(Conj::No, xb.as_mut());
        let kxb: Vec<Vec<f64>> = (0..2)
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
        let solver = match method {
            Method::Fast => Solver::new(kii, llt),
            #[cfg(test)]
            Method::Reference => Solver::Plain(llt),
        };
        // everything the chunks meet, in the row order of the solutions
        let row_of = solver.row_of(n_i);
        let permute = |v: Vec<f64>| {
            let mut p = vec![0.0; v.len()];
            for (a, x) in v.into_iter().enumerate() {
                p[row_of[a]] = x;
            }
            p
        };
        let weights = permute(kii.map_or_else(Vec::new, abs_form_weights));
        let kxb: Vec<Vec<f64>> = kxb
            .into_iter()
            .map(|v| if v.is_empty() { v } else { permute(v) })
            .collect();
        let kiz: Vec<crate::dofs::Row> = asm
            .kiz
            .iter()
            .map(|c| c.iter().map(|&(i, v)| (row_of[i], v)).collect())
            .collect();
        let mut c0 = 0;
        while c0 < nz {
            let w = CHUNK.min(nz - c0);
            let x = solver.solve_sparse(n_i, &asm.kiz[c0..c0 + w]);
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
                let exact = (method == Method::Reference).then(|| abs_quadratic_forms(_k, &x));
                for j in 0..w {
                    let xj = x.col_as_slice(j);
                    #[cfg(test)]
                    if let Some(e) = &exact {
                        mag[c0 + j] += e[j];
                    }
                    if method == Method::Fast {
                        mag[c0 + j] += xj.iter().zip(&weights).map(|(x, w)| w * x * x).sum::<f64>();
                    }
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
    // symmetrize, recording the round-off asymmetry
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
    // round-off to zero: for a symmetric positive semidefinite K the terms of R_ij are
    // bounded by √(mag_i·mag_j) (Cauchy–Schwarz in the energy product)
    let tau = ROUND_OFF;
    let mut zeroed = 0;
    for j in 0..nz {
        for i in 0..nz {
            let v = r[(i, j)];
            if v != 0.0 && v.abs() <= tau * (mag[i] * mag[j]).sqrt() {
                r[(i, j)] = 0.0;
                zeroed += 1;
            }
        }
    }
    for g in 0..2 {
        for k in 0..nz {
            let v = rf[g][k];
            if v != 0.0 && v.abs() <= tau * rf_mag[g][k] {
                rf[g][k] = 0.0;
                zeroed += 1;
            }
        }
    }
    Condensation {
        r,
        rf,
        asymmetry: if maxr > 0.0 { maxd / maxr } else { 0.0 },
        zeroed,
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
    /// of the cancellation of much larger terms, and its round-off is relative to them), and
    /// requires the same entries zeroed.
    fn compare(model: &Model) -> (super::Condensation, super::Condensation) {
        let mut asm = assemble(model).unwrap();
        let (llt, _) = factorize(model, &asm).unwrap();
        let kzz = asm.kzz.clone();
        let kii = asm.kii.take();
        let fast = condense_with(&asm, kii.as_ref(), kzz.clone(), llt.as_ref(), Method::Fast);
        let refr = condense_with(&asm, kii.as_ref(), kzz, llt.as_ref(), Method::Reference);
        let n = fast.r.nrows();
        let kzz = &asm.kzz;
        for i in 0..n {
            for j in 0..n {
                let (a, b) = (fast.r[(i, j)], refr.r[(i, j)]);
                let scale = (kzz[(i, i)] * kzz[(j, j)]).abs().sqrt();
                assert!((a - b).abs() <= 1e-12 * scale, "R[{i},{j}]: {a} vs {b}");
                assert_eq!(a == 0.0, b == 0.0, "zero pattern at R[{i},{j}]: {a} vs {b}");
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
}
