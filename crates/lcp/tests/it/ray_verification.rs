//! A path ends in a ray or a mechanism only when the direction is verified from the data:
//! `dx = d·dp + M dz` row by row against the terms that form it, every rate non-negative
//! within round-off of the rows it meets. An entry of the entering column below the pivot
//! tolerance of the column, but not round-off of its own row, is a pivot, not a ray.

use crate::common;

use common::*;
use unilateral_lcp::{follow_path, Follow, ParametricLcp, PathOptions, PathStatus, Settings};
use unilateral_oracle as oracle;

fn trace(m: &[Vec<f64>], q0: &[f64], d: &[f64]) -> unilateral_lcp::LoadPath {
    let problem = ParametricLcp {
        m: to_mat(m),
        q0: q0.to_vec(),
        d: d.to_vec(),
    };
    let options = PathOptions {
        target: 1.0,
        follow: Follow::ToEnd,
        tightening: None,
    };
    follow_path(&problem, &options, &Settings::default()).expect("valid input")
}

/// `x1 = 1 − p`, `x2 = 1 + 0.3·z1 + z2`: at `p = 1` (x1 leaves) `z1` enters with no effect on
/// any pinned row, so `z1` grows at fixed `p` — a mechanism exact by construction (by hand:
/// `dz = (1, 0)`, `dx = (0, 0.3)`, `dp = 0`), as the exact oracle finds too.
#[test]
fn an_exact_mechanism_is_verified_and_reported() {
    let m = vec![vec![0.0, 0.0], vec![0.3, 1.0]];
    let (q0, d) = (vec![1.0, 1.0], vec![-1.0, 0.0]);
    let exact = oracle::parametric_path(&m, &q0, &d, None, None);
    assert!(same_status(PathStatus::Mechanism, exact.status));
    let path = trace(&m, &q0, &d);
    assert_eq!(path.status, PathStatus::Mechanism);
    assert_eq!(path.p_limit, Some(1.0));
    let mode = path.mechanism.expect("a mechanism has its mode");
    assert_eq!(mode.dz, vec![1.0, 0.0]);
    assert_close("dx", &mode.dx, &[0.0, 0.3], 1e-15).unwrap();
}

/// A ray exact by construction and the same ray with round-off in the data: `x1 = 1 − 0.3p +
/// 0.1·z1`, `x2 = 3 − 0.7p + (0.7/3)·z1 + z2`. After `x1` leaves at `p = 1/0.3`, `z1` enters
/// with `dp = 1/3` and, by hand, `dx2 = −0.7/3 + 0.7/3 = 0`: in floating point the two terms of
/// `dx2` cancel only to round-off (`0.7/3` and `0.1/0.3` are not exact), which the check must
/// accept as zero — a ray, not a numerical failure nor a pivot on round-off. The exactly
/// representable variant (`0.25`, `0.5`: every rate exact) is the reference.
#[test]
fn a_ray_with_round_off_in_its_rates_is_still_a_ray() {
    // Exact: x1 = 1 − 0.5p + 0.25 z1, x2 = 3 − 0.75p + 0.375 z1 + z2 (dp = 1/2, dx2 = 0).
    let exact_m = vec![vec![0.25, 0.0], vec![0.375, 1.0]];
    let (eq0, ed) = (vec![1.0, 3.0], vec![-0.5, -0.75]);
    let oracle_path = oracle::parametric_path(&exact_m, &eq0, &ed, None, None);
    assert!(same_status(PathStatus::Ray, oracle_path.status));
    let exact = trace(&exact_m, &eq0, &ed);
    assert_eq!(exact.status, PathStatus::Ray);
    assert_eq!(exact.steps.len(), 1);
    assert_eq!(exact.steps[0].p, 2.0);

    let m = vec![vec![0.1, 0.0], vec![0.7 / 3.0, 1.0]];
    let (q0, d) = (vec![1.0, 3.0], vec![-0.3, -0.7]);
    let path = trace(&m, &q0, &d);
    assert_eq!(path.status, PathStatus::Ray, "{:?}", path.steps);
    assert_eq!(path.steps.len(), 1);
    assert!((path.steps[0].p - 1.0 / 0.3).abs() <= 1e-15 * (1.0 / 0.3));
    let sol = path.solution.expect("the ray's point at the target");
    check_path_point(&m, &q0, &d, &sol, 1e-12).unwrap();
}

/// A false mechanism from a rate below the pivot tolerance of its column: `x1 = 1 − p + z2`,
/// `x2 = 1 − δ·z1 + 1000·z2`, `x3 = 1 + 1000·z1 + z3` with `δ = 1e-9`. At `p = 1` (x1 leaves)
/// `z1` enters; its column has `1000` in row 3 and `δ` in row 2, so by the column's pivot
/// tolerance (`1e-9·‖α‖`) nothing decreases and `p` does not move: a mechanism. But `δ·z1` is
/// the only term of row 2's rate, so `x2` does decrease, and leaves at `z1 = 1/δ`; then `z2`
/// enters with `dp = 1`: a ray. The exact oracle (rational arithmetic on the same data) is the
/// reference: two steps, both at `p = 1`, then a ray.
#[test]
fn a_rate_below_the_columns_tolerance_but_not_round_off_of_its_row_is_a_pivot() {
    let delta = 1e-9;
    let m = vec![
        vec![0.0, 1.0, 0.0],
        vec![-delta, 1000.0, 0.0],
        vec![1000.0, 0.0, 1.0],
    ];
    let (q0, d) = (vec![1.0; 3], vec![-1.0, 0.0, 0.0]);
    let exact = oracle::parametric_path(&m, &q0, &d, None, None);
    assert!(
        same_status(PathStatus::Ray, exact.status),
        "{:?}",
        exact.status
    );
    assert_eq!(exact.steps.len(), 2);
    let path = trace(&m, &q0, &d);
    assert_eq!(path.status, PathStatus::Ray, "{:?}", path.steps);
    assert_eq!(path.steps.len(), 2);
    for (s, e) in path.steps.iter().zip(&exact.steps) {
        assert_eq!(oracle_var(s.entering), e.entering);
        assert_eq!(oracle_var(s.leaving), e.leaving);
        assert!((s.p - e.p_f64()).abs() <= 1e-12, "{} vs {}", s.p, e.p_f64());
    }
    let sol = path.solution.expect("the ray's point at the target");
    check_path_point(&m, &q0, &d, &sol, 1e-12).unwrap();
}
