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
}

#[test]
fn tiny_and_huge_entries_give_verified_finite_solutions() {
    // References: 1×1 by hand, z = −q/m, w = 0.
    for (m, q) in [
        (1e-308, -1.0),
        (1.0, -1e-308),
        (1e-308, -1e-308),
        (1e300, -1e-300),
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
