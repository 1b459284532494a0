//! The condensation of the factorized bonded structure to its contact zone: the Schur
//! complement `R = K_zz − K_zI K_II⁻¹ K_Iz` and the contact load vectors
//! `R_F = K_zI K_II⁻¹ b_I − b_z` (formulation.md §2), with the round-off of exact zeros set
//! to zero.

use crate::assemble::Assembled;
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::SparseColMat;
use faer::{Conj, Mat};

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
pub(crate) const ROUND_OFF: f64 = 8.0 * f64::EPSILON / 2.0;

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

/// `|x_j|ᵀ|K||x_j|` for every column `x_j` of `x`, `K` symmetric and stored as its lower
/// triangle, in one pass over `K` for the whole block (the block is copied row-major so the
/// inner loop runs over contiguous columns): one sparse pass per block of right-hand sides
/// instead of one per column.
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
        let mut c0 = 0;
        while c0 < nz {
            let w = CHUNK.min(nz - c0);
            let mut x = Mat::<f64>::zeros(n_i, w);
            for j in 0..w {
                for &(i, v) in &asm.kiz[c0 + j] {
                    x[(i, j)] = v;
                }
            }
            llt.solve_in_place_with_conj(Conj::No, x.as_mut());
            for row in 0..nz {
                let col = &asm.kiz[row];
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
            // (K_zI K_II⁻¹ = x_iᵀ): bounded by |x_i|ᵀ|K_II||x_j|. This grows with the number
            // of elements the static mode x_j spans, where the terms of K_zz and K_zI x_j
            // alone do not.
            if let Some(k) = kii {
                let forms = abs_quadratic_forms(k, &x);
                for j in 0..w {
                    let xj = x.col_as_slice(j);
                    mag[c0 + j] += forms[j];
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
