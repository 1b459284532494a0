//! Exhaustive enumeration of complementary bases, the last resort for small problems.

use faer::linalg::solvers::Solve;
use faer::Mat;

use crate::binary::ldexp;
use crate::pivoting::scaling::Scaling;
use crate::Residual;

/// All `2^n` complementary bases in order of growing support; the first whose solution verifies
/// is returned as `(z, w, S)` with `S` the basic `z` indices. Bases with a numerically singular
/// `M[S, S]` (after equilibration) are skipped.
pub(crate) fn enumerate_first(m: &Mat<f64>, q: &[f64]) -> Option<(Vec<f64>, Vec<f64>, Vec<usize>)> {
    let n = q.len();
    assert!(n <= 24, "enumeration is for small problems");
    let mut subsets: Vec<u32> = (0..(1u32 << n)).collect();
    subsets.sort_by_key(|s| s.count_ones());
    for s in subsets {
        let idx: Vec<usize> = (0..n).filter(|&i| s >> i & 1 == 1).collect();
        let k = idx.len();
        let mut z = vec![0.0; n];
        if k > 0 {
            let a = Mat::<f64>::from_fn(k, k, |r, c| m[(idx[r], idx[c])]);
            // `M[S, S]` is equilibrated (powers of two, exact) before the singularity test, so
            // that its pivots compare rows and columns brought to one size: a row whose entries
            // are all small is not a near-singularity.
            let sc = Scaling::equilibrate_lcp(&a, None);
            let ahat =
                Mat::<f64>::from_fn(k, k, |r, c| ldexp(a[(r, c)], sc.row_exp[r] + sc.col_exp[c]));
            let lu = ahat.partial_piv_lu();
            let u = lu.U();
            let umax = (0..k).map(|i| u[(i, i)].abs()).fold(0.0f64, f64::max);
            let umin = (0..k)
                .map(|i| u[(i, i)].abs())
                .fold(f64::INFINITY, f64::min);
            if umin.is_nan() || umin <= 1e-12 * umax {
                continue;
            }
            // M[S,S] z_S = −q_S with M̂ = E M D: z_S = D M̂⁻¹ (−E q_S).
            let rhs = Mat::<f64>::from_fn(k, 1, |r, _| ldexp(-q[idx[r]], sc.row_exp[r]));
            let sol = lu.solve(&rhs);
            for (r, &i) in idx.iter().enumerate() {
                z[i] = ldexp(sol[(r, 0)], sc.col_exp[r]);
            }
        }
        if z.iter().any(|v| !v.is_finite()) {
            continue;
        }
        // Negative entries are set to zero, and so are those below the round-off of the solve
        // (a degenerate basic `z_i = 0` comes out as ±1e-19 beside entries of order one, and a
        // row whose only term it is would verify against that round-off alone, relative
        // residual 1); if one mattered, its row no longer balances and the verification below
        // rejects the point.
        let zmax = z.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for v in z.iter_mut() {
            if *v < 0.0 || v.abs() <= 1e-13 * zmax {
                *v = 0.0;
            }
        }
        let mut w = lcp_w(m, q, &z);
        for &i in &idx {
            w[i] = 0.0;
        }
        if Residual::of(m, q, &w, &z).accepts(&w, &z) {
            return Some((z, w, idx));
        }
    }
    None
}

/// `w = q + M z` for a dense `M`.
fn lcp_w(m: &Mat<f64>, q: &[f64], z: &[f64]) -> Vec<f64> {
    let mut w = q.to_vec();
    for (j, &zj) in z.iter().enumerate() {
        if zj != 0.0 {
            for (i, wi) in w.iter_mut().enumerate() {
                *wi += m[(i, j)] * zj;
            }
        }
    }
    w
}
