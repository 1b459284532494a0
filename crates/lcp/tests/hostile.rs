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
