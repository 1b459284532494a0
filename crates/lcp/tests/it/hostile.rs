//! Extreme magnitudes: every reported solution is finite and verified from the data, or the
//! engine says it failed; residuals themselves neither overflow nor underflow.

use faer::mat;
use unilateral_lcp::{solve_lcp, Lcp, LcpStatus, Residual, Settings};

fn solve(m: f64, q: f64) -> unilateral_lcp::LcpSolution {
    solve_lcp(
        &Lcp {
            m: mat![[m]],
            q: vec![q],
        },
        &Settings::default(),
    )
    .unwrap()
}

#[test]
fn a_solution_beyond_the_range_is_a_numerical_failure_not_solved() {
    // Reference: 1×1 by hand, w = 1e-308·z − 10 = 0 ⇒ z = 1e309, beyond the largest f64.
    let s = solve(1e-308, -10.0);
    assert_eq!(s.status, LcpStatus::NumericalFailure, "{s:?}");
    assert!(s.point.is_none());
    // Reference: 1×1 by hand, 1e300·z = 1e-300 ⇒ z = 1e-600, below the smallest f64 (4.9e-324):
    // z = 0 leaves all of the row's data, |q| = 1e-300, unbalanced — no representable point
    // solves this row, and measured against its own data (not against other rows) none is
    // passed off as verified.
    let s = solve(1e300, -1e-300);
    assert_eq!(s.status, LcpStatus::NumericalFailure, "{s:?}");
    assert!(s.point.is_none());
}

#[test]
fn tiny_and_huge_entries_give_verified_finite_solutions() {
    // References: 1×1 by hand, z = −q/m, w = 0.
    for (m, q) in [
        (1e-308, -1.0),
        (1.0, -1e-308),
        (1e-308, -1e-308),
        (1e300, -1e-8),
        (1e150, -1e-150),
        (3e-200, -6e100),
    ] {
        let s = solve(m, q);
        assert_eq!(s.status, LcpStatus::Solved, "m = {m}, q = {q}: {s:?}");
        let p = s.point.unwrap();
        let z = -q / m;
        assert!(
            (p.z[0] - z).abs() <= 1e-12 * z,
            "m = {m}, q = {q}: {:?}",
            p.z
        );
        assert!(p.w[0].is_finite() && p.w[0].abs() <= 1e-12 * q.abs());
        let r = p.residual;
        for v in [r.equation, r.feasibility, r.complementarity] {
            assert!(v.is_finite() && v <= 1e-12, "m = {m}, q = {q}: {r:?}");
        }
    }
}

#[test]
fn residuals_of_non_finite_points_are_infinite() {
    // A NaN is never "verified": f64::max would silently drop it.
    let m = mat![[1.0]];
    let r = Residual::of(&m, &[-1.0], &[f64::NAN], &[1.0]);
    assert_eq!(r.max(), f64::INFINITY);
    let r = Residual::of(&m, &[-1.0], &[0.0], &[f64::INFINITY]);
    assert_eq!(r.max(), f64::INFINITY);
    // Large but finite data: the sums |M||z| would overflow, the relative residual does not.
    // Reference: w = 1e308·1 + 1e308·1 − 1.5e308 = 0.5e308 exactly representable.
    let m = faer::Mat::from_fn(1, 2, |_, _| 1e308);
    let r = Residual::of(&m, &[-1.5e308], &[0.5e308], &[1.0, 1.0]);
    assert!(r.equation <= 1e-15 && r.feasibility == 0.0, "{r:?}");
    // (not a complementary point: w·z ≠ 0 is reported as such, finitely)
    assert!(
        r.complementarity.is_finite() && r.complementarity > 0.1,
        "{r:?}"
    );
    // Tiny: complementarity of z = 1e-308 is no 0/0.
    let m = mat![[1.0]];
    let r = Residual::of(&m, &[-1e-308], &[0.0], &[1e-308]);
    assert!(r.max() == 0.0, "{r:?}");
}

fn solve2(m: [[f64; 2]; 2], q: [f64; 2]) -> unilateral_lcp::LcpSolution {
    solve_lcp(
        &Lcp {
            m: faer::Mat::from_fn(2, 2, |i, j| m[i][j]),
            q: q.to_vec(),
        },
        &Settings::default(),
    )
    .unwrap()
}

#[test]
fn a_decoupled_row_with_a_tiny_stiffness_is_solved_exactly() {
    // Reference, by hand: M = diag(1e-308, 1), q = (−1, −1) decouples into 1e-308·z1 = 1 and
    // z2 = 1, so z = (1e308, 1), w = 0 — 1e308 is a finite double. Equilibration by powers of
    // two turns the problem into the identity, so the answer is exact to round-off.
    let s = solve2([[1e-308, 0.0], [0.0, 1.0]], [-1.0, -1.0]);
    assert_eq!(s.status, LcpStatus::Solved, "{s:?}");
    let p = s.point.unwrap();
    assert!((p.z[0] - 1e308).abs() <= 1e-14 * 1e308, "{:?}", p.z);
    assert!((p.z[1] - 1.0).abs() <= 1e-14, "{:?}", p.z);
    assert!(p.w.iter().all(|&v| v == 0.0), "{:?}", p.w);
    assert!(p.residual.max() <= 1e-15, "{:?}", p.residual);
}

#[test]
fn a_decoupled_row_with_tiny_data_is_not_hidden_by_the_others() {
    // Reference, by hand: M = diag(1e-308, 1), q = (−1e-300, −1) decouples into
    // 1e-308·z1 = 1e-300 and z2 = 1, so z = (1e8, 1), w = 0. The old verification measured row 1
    // against max|q| = 1 and called z1 = 0, w1 = −1e-300 "verified".
    let s = solve2([[1e-308, 0.0], [0.0, 1.0]], [-1e-300, -1.0]);
    assert_eq!(s.status, LcpStatus::Solved, "{s:?}");
    let p = s.point.unwrap();
    assert!((p.z[0] - 1e8).abs() <= 1e-14 * 1e8, "{:?}", p.z);
    assert!((p.z[1] - 1.0).abs() <= 1e-14, "{:?}", p.z);
    assert!(p.w.iter().all(|&v| v == 0.0), "{:?}", p.w);
    assert!(p.residual.max() <= 1e-15, "{:?}", p.residual);
}

#[test]
fn a_subnormal_stiffness_solves_when_its_answer_is_a_double() {
    // Reference, by hand: M = diag(1e-310, 1) (1e-310 is subnormal), q = (−1e-300, −1):
    // z = (1e10, 1), w = 0, every number a double; the subnormal carries ~3 fewer digits of
    // its own, so the agreement asked is 1e-12.
    let s = solve2([[1e-310, 0.0], [0.0, 1.0]], [-1e-300, -1.0]);
    assert_eq!(s.status, LcpStatus::Solved, "{s:?}");
    let p = s.point.unwrap();
    assert!((p.z[0] - 1e10).abs() <= 1e-12 * 1e10, "{:?}", p.z);
    assert!((p.z[1] - 1.0).abs() <= 1e-14, "{:?}", p.z);
    // With q1 = −1 the answer z1 = 1e310 is beyond the largest double (1.8e308): no finite
    // point solves row 1, and the engine says it failed instead of answering.
    let s = solve2([[1e-310, 0.0], [0.0, 1.0]], [-1.0, -1.0]);
    assert_eq!(s.status, LcpStatus::NumericalFailure, "{s:?}");
    assert!(s.point.is_none());
}

#[test]
fn the_residual_judges_each_row_against_its_own_data() {
    // Reference: the wrong point of the previous test, z = (0, 1), w = (−1e-300, 0), violates
    // w1 ≥ 0 by all of row 1's data (|q1| = 1e-300): a relative violation of exactly 1.
    let m = mat![[1e-308, 0.0], [0.0, 1.0]];
    let r = Residual::of(&m, &[-1e-300, -1.0], &[-1e-300, 0.0], &[0.0, 1.0]);
    assert_eq!(r.feasibility, 1.0, "{r:?}");
    assert_eq!(r.equation, 0.0, "{r:?}");
    // A negative z2 of round-off size relative to the rows it meets is no violation, whatever
    // the size of z1 (reference: setting z2 to zero changes row 2 by 1e-17 of its data).
    let r = Residual::of(&m, &[-1e-300, 1.0], &[0.0, 1.0 - 1e-17], &[1e8, -1e-17]);
    assert!(r.feasibility <= 2e-17 && r.equation <= 1e-16, "{r:?}");
    // Units: the residuals of a point do not change when rows and unknowns are rescaled
    // (reference: the definition, x̂ = E x, ẑ = D⁻¹ z, M̂ = E M D).
    let (m, q, w, z) = (
        mat![[2.0, 1.0], [1.0, 3.0]],
        [-1.0, 0.5],
        [0.0, 1.0 + 1e-10],
        [0.5 + 1e-12, 0.0],
    );
    let r0 = Residual::of(&m, &q, &w, &z);
    let (e, d) = ([1e-200, 1e150], [1e250, 1e-100]);
    let ms = faer::Mat::from_fn(2, 2, |i, j| e[i] * m[(i, j)] * d[j]);
    let qs: Vec<f64> = (0..2).map(|i| e[i] * q[i]).collect();
    let ws: Vec<f64> = (0..2).map(|i| e[i] * w[i]).collect();
    let zs: Vec<f64> = (0..2).map(|j| z[j] / d[j]).collect();
    let r1 = Residual::of(&ms, &qs, &ws, &zs);
    for (a, b) in [
        (r0.equation, r1.equation),
        (r0.feasibility, r1.feasibility),
        (r0.complementarity, r1.complementarity),
    ] {
        assert!((a - b).abs() <= 1e-6 * a.max(b) + 1e-30, "{r0:?} vs {r1:?}");
    }
    assert!(r0.equation > 1e-13, "{r0:?}");
}

mod rescaled {
    use proptest::prelude::*;
    use unilateral_lcp::{solve_lcp, Lcp, LcpStatus, Settings, Strategy as How};
    use unilateral_oracle as oracle;

    /// A strictly diagonally dominant integer matrix with a positive diagonal (a P-matrix, so the
    /// LCP has exactly one solution) and an integer `q`. Every off-diagonal entry is non-zero
    /// (±1 to ±3): the matrix is irreducible, which is what makes its equilibration independent
    /// of the scaling (a block-triangular coupling can be made any size by a scaling, and no
    /// equilibration can tell which size was meant).
    fn dominant(max_n: usize) -> impl Strategy<Value = (Vec<Vec<f64>>, Vec<f64>)> {
        let entry = prop_oneof![-3i32..=-1, 1i32..=3];
        (1..=max_n).prop_flat_map(move |n| {
            (
                prop::collection::vec(prop::collection::vec(entry.clone(), n), n),
                prop::collection::vec(1i32..=3, n),
                prop::collection::vec(-8i32..=8, n),
            )
                .prop_map(move |(off, extra, q)| {
                    let m = (0..n)
                        .map(|i| {
                            let sum: i32 =
                                (0..n).filter(|&j| j != i).map(|j| off[i][j].abs()).sum();
                            (0..n)
                                .map(|j| {
                                    if i == j {
                                        (sum + extra[i]) as f64
                                    } else {
                                        off[i][j] as f64
                                    }
                                })
                                .collect()
                        })
                        .collect();
                    (m, q.into_iter().map(f64::from).collect())
                })
        })
    }

    /// `10^k` correctly rounded.
    fn ten(k: i32) -> f64 {
        format!("1e{k}").parse().unwrap()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

        /// Rows and columns rescaled by `10^k`, `k` in [−150, 150]: `M' = D_r M D_c`,
        /// `q' = D_r q`. Reference: the oracle's exact solution `(z, w)` of the unscaled problem
        /// (exact rational enumeration) mapped by the exact relation `z' = D_c⁻¹ z`,
        /// `w' = D_r w`; agreement to 1e-9 of the unscaled data's size, and the same support.
        #[test]
        fn rescaled_rows_and_columns_give_the_mapped_solution(
            (m, q, kr, kc) in dominant(6).prop_flat_map(|(m, q)| {
                let n = q.len();
                (
                    Just(m),
                    Just(q),
                    prop::collection::vec(-150i32..=150, n),
                    prop::collection::vec(-150i32..=150, n),
                )
            })
        ) {
            let n = q.len();
            let sols = oracle::enumerate(&m, &q);
            prop_assert_eq!(sols.len(), 1, "a P-matrix LCP has exactly one solution");
            let (zo, wo) = (sols[0].z_f64(), sols[0].w_f64());
            let (dr, dc): (Vec<f64>, Vec<f64>) =
                (kr.iter().map(|&k| ten(k)).collect(), kc.iter().map(|&k| ten(k)).collect());
            let lcp = Lcp {
                m: faer::Mat::from_fn(n, n, |i, j| dr[i] * m[i][j] * dc[j]),
                q: (0..n).map(|i| dr[i] * q[i]).collect(),
            };
            let sol = solve_lcp(&lcp, &Settings::default()).unwrap();
            prop_assert_eq!(sol.status, LcpStatus::Solved, "attempts: {:?}", sol.attempts);
            // By the pivoting itself, not by the last-resort enumeration.
            prop_assert!(
                matches!(sol.strategy, How::Lemke { .. } | How::Trivial),
                "attempts: {:?}",
                sol.attempts
            );
            let pt = sol.point.unwrap();
            prop_assert!(pt.residual.max() <= 1e-12, "{:?}", pt.residual);
            let zscale = 1.0 + zo.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            let wscale = 1.0 + q.iter().chain(&wo).fold(0.0f64, |a, b| a.max(b.abs()));
            for j in 0..n {
                let z = pt.z[j] * dc[j];
                prop_assert!((z - zo[j]).abs() <= 1e-9 * zscale, "z[{}]: {} vs {}", j, z, zo[j]);
                let w = pt.w[j] / dr[j];
                prop_assert!((w - wo[j]).abs() <= 1e-9 * wscale, "w[{}]: {} vs {}", j, w, wo[j]);
                // The support: an unknown that is zero in the exact solution (and whose
                // complement is not) is exactly zero, whatever the scaling.
                if zo[j] == 0.0 && wo[j] > 0.0 {
                    prop_assert_eq!(pt.z[j], 0.0);
                }
                if wo[j] == 0.0 && zo[j] > 0.0 {
                    prop_assert_eq!(pt.w[j], 0.0);
                }
            }
        }
    }
}

/// At the load of an event the right-hand side `q0_i + p·d_i` of the row that changes is zero
/// in exact arithmetic and round-off in floating point (here `2 − 2.0000000000000004`): the
/// row is measured against the terms that formed it, so the exact point `x = 0` verifies.
/// Measured against the difference alone (the standard form), the same point would not.
/// (Found by `p_matrix_path_matches_enumeration`: `solution_at` at the path's last breakpoint
/// returned nothing.)
#[test]
fn a_cancelling_right_hand_side_is_judged_by_its_terms() {
    let m = faer::Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { 0.0 });
    let p = 2.0000000000000004;
    let (q0, d) = ([2.0, 1.0], [-1.0, 0.0]);
    let r = Residual::of_parametric(&m, &q0, &d, p, &[0.0, 1.0], &[0.0, 0.0]);
    assert!(r.max() <= 1e-15, "{r:?}");
    let q: Vec<f64> = q0.iter().zip(&d).map(|(a, b)| a + p * b).collect();
    assert!(q[0] < 0.0);
    let r = Residual::of(&m, &q, &[0.0, 1.0], &[0.0, 0.0]);
    assert!(r.max() >= 0.5, "{r:?}");
}
