//! Property tests of the engine against the exact-rational oracle (`unilateral-oracle`) on
//! random problems with n ≤ 8:
//!
//! * P-matrices: `solve_lcp` finds the unique enumerated solution;
//! * positive semidefinite and copositive-plus matrices: no false ray, every solution verifies;
//! * the parametric problem with a P-matrix: the path agrees with enumeration at random loads,
//!   and its events (loads, entering and leaving variables) agree with the oracle's exact
//!   parametric Lemke method on nondegenerate data (also for general matrices).

use crate::common;

use common::*;
use proptest::prelude::*;
use unilateral_lcp::{
    follow_path, solution_at, solve_lcp, Follow, Lcp, LcpStatus, ParametricLcp, PathOptions,
    PathStatus, Settings,
};
use unilateral_oracle as oracle;

/// Agreement required between the engine and the exact answer.
const AGREE: f64 = 1e-9;
/// Residual required of every P-matrix solution.
const RESIDUAL: f64 = 1e-10;

fn square_i(n: usize, lo: i64, hi: i64) -> impl Strategy<Value = Vec<Vec<f64>>> {
    prop::collection::vec(prop::collection::vec(lo..=hi, n), n).prop_map(|m| to_f64_matrix(&m))
}

fn square_f(n: usize, r: f64) -> impl Strategy<Value = Vec<Vec<f64>>> {
    prop::collection::vec(prop::collection::vec(-r..r, n), n)
}

fn vec_i(n: usize, lo: i64, hi: i64) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(lo..=hi, n).prop_map(|v| v.into_iter().map(|x| x as f64).collect())
}

/// An integer P-matrix `AᵀA + I + (B − Bᵀ)` of order 1..=max_n and an integer `q`.
fn p_matrix_int(max_n: usize) -> impl Strategy<Value = (Vec<Vec<f64>>, Vec<f64>)> {
    (1..=max_n).prop_flat_map(|n| {
        (square_i(n, -2, 2), square_i(n, -2, 2), vec_i(n, -8, 8))
            .prop_map(|(a, b, q)| (psd_plus_skew(&a, &b, 1.0), q))
    })
}

/// A P-matrix with arbitrary `f64` entries and an `f64` `q`.
fn p_matrix_float(max_n: usize) -> impl Strategy<Value = (Vec<Vec<f64>>, Vec<f64>)> {
    (1..=max_n).prop_flat_map(|n| {
        (
            square_f(n, 1.0),
            square_f(n, 1.0),
            0.05f64..1.0,
            prop::collection::vec(-3.0f64..3.0, n),
        )
            .prop_map(|(a, b, s, q)| (psd_plus_skew(&a, &b, s), q))
    })
}

fn solve(m: &[Vec<f64>], q: &[f64]) -> unilateral_lcp::LcpSolution {
    let lcp = Lcp {
        m: to_mat(m),
        q: q.to_vec(),
    };
    solve_lcp(&lcp, &Settings::default()).expect("valid input")
}

fn p_matrix_agrees(m: &[Vec<f64>], q: &[f64]) -> Result<(), TestCaseError> {
    let sols = oracle::enumerate(m, q);
    prop_assert_eq!(sols.len(), 1, "a P-matrix LCP has exactly one solution");
    let (zo, wo) = (sols[0].z_f64(), sols[0].w_f64());
    let sol = solve(m, q);
    prop_assert_eq!(
        sol.status,
        LcpStatus::Solved,
        "attempts: {:?}",
        sol.attempts
    );
    let pt = sol.point.as_ref().expect("a solved LCP has a point");
    prop_assert!(
        pt.residual.max() <= RESIDUAL,
        "residual {:?} (strategy {:?})",
        pt.residual,
        sol.strategy
    );
    assert_close("z", &pt.z, &zo, AGREE).map_err(TestCaseError::fail)?;
    assert_close("w", &pt.w, &wo, AGREE).map_err(TestCaseError::fail)?;
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// Integer P-matrices: the unique solution, to 1e-9, with a residual ≤ 1e-10.
    #[test]
    fn p_matrix_int_solve_matches_enumeration((m, q) in p_matrix_int(8)) {
        p_matrix_agrees(&m, &q)?;
    }

    /// P-matrices with arbitrary `f64` entries (converted exactly by the oracle).
    #[test]
    fn p_matrix_float_solve_matches_enumeration((m, q) in p_matrix_float(8)) {
        p_matrix_agrees(&m, &q)?;
    }

    /// Positive semidefinite `AᵀA + (B − Bᵀ)` with `A` of rank ≤ k (often singular): the engine
    /// reports a ray exactly when enumeration finds no solution, and a reported solution
    /// verifies.
    #[test]
    fn psd_no_false_ray(
        (a, b, q) in (1usize..=8).prop_flat_map(|n| (
            (1usize..=n).prop_flat_map(move |k| prop::collection::vec(
                prop::collection::vec(-2i64..=2, n), k)).prop_map(|a| to_f64_matrix(&a)),
            square_i(n, -1, 1),
            vec_i(n, -6, 6),
        ))
    ) {
        let m = psd_plus_skew(&a, &b, 0.0);
        let exists = oracle::has_solution(&m, &q);
        let sol = solve(&m, &q);
        if exists {
            prop_assert_eq!(sol.status, LcpStatus::Solved,
                "false {:?}: enumeration finds a solution; attempts {:?}", sol.status, sol.attempts);
        } else {
            prop_assert_eq!(sol.status, LcpStatus::Ray,
                "no solution exists; attempts {:?}", sol.attempts);
        }
        if let Some(pt) = &sol.point {
            check_point(&m, &q, pt, 1e-9).map_err(TestCaseError::fail)?;
        }
    }

    /// Copositive-plus matrices that are not positive semidefinite: a nonnegative matrix with a
    /// positive diagonal (strictly copositive) plus a positive semidefinite part. Such an LCP
    /// always has a solution; the engine must find and verify one.
    #[test]
    fn copositive_plus_always_solved(
        (nn, diag, a, b, q) in (1usize..=8).prop_flat_map(|n| (
            square_i(n, 0, 3),
            vec_i(n, 1, 3),
            square_i(n, -1, 1),
            square_i(n, -1, 1),
            vec_i(n, -6, 6),
        ))
    ) {
        let n = q.len();
        let psd = psd_plus_skew(&a, &b, 0.0);
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| psd[i][j] + if i == j { diag[i] } else { nn[i][j] }).collect())
            .collect();
        prop_assert!(oracle::has_solution(&m, &q), "strictly copositive: solvable");
        let sol = solve(&m, &q);
        prop_assert_eq!(sol.status, LcpStatus::Solved, "attempts {:?}", sol.attempts);
        check_point(&m, &q, sol.point.as_ref().unwrap(), 1e-9).map_err(TestCaseError::fail)?;
        // When the solution set is finite and known exactly, the engine's point is on it.
        let sols = oracle::enumerate(&m, &q);
        if sols.iter().all(|s| s.singular_sets.is_empty()) {
            let pt = sol.point.as_ref().unwrap();
            prop_assert!(
                sols.iter().any(|s| assert_close("z", &pt.z, &s.z_f64(), AGREE).is_ok()),
                "engine z {:?} is none of the enumerated solutions", pt.z
            );
        }
    }
}

fn path_options(target: f64) -> PathOptions {
    PathOptions {
        target,
        follow: Follow::ToEnd,
        tightening: None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Parametric problem with a P-matrix, `q0 ≥ 0` (zeros allowed: degenerate starts):
    /// the solution at random loads (`solution_at`) and at the target (`path.solution`) is the
    /// unique enumerated one, to 1e-9; the path ends on a ray like the oracle's.
    #[test]
    fn p_matrix_path_matches_enumeration(
        (a, b, q0, d, target, us) in (1usize..=8).prop_flat_map(|n| (
            square_i(n, -2, 2),
            square_i(n, -2, 2),
            vec_i(n, 0, 5),
            vec_i(n, -5, 5),
            1i64..=20,
            prop::collection::vec(0.0f64..=1.0, 3),
        ))
    ) {
        let m = psd_plus_skew(&a, &b, 1.0);
        let target = target as f64 / 4.0;
        let problem = ParametricLcp { m: to_mat(&m), q0: q0.clone(), d: d.clone() };
        let opts = path_options(target);
        let settings = Settings::default();
        let path = follow_path(&problem, &opts, &settings).unwrap();
        let exact = oracle::parametric_path(&m, &q0, &d, None, None);
        prop_assert_eq!(exact.status, oracle::PathStatus::Ray);
        prop_assert_eq!(path.status, PathStatus::Ray, "steps {:?}", path.steps);
        prop_assert!(path.steps.iter().all(|s| !s.turning), "p never decreases for a P-matrix");

        let check_at = |p: f64, got: &unilateral_lcp::PathPoint| -> Result<(), TestCaseError> {
            let sols = oracle::enumerate_parametric(&m, &q0, &d, p);
            prop_assert_eq!(sols.len(), 1);
            prop_assert_eq!(got.p, p);
            check_path_point(&m, &q0, &d, got, RESIDUAL)
                .map_err(|e| TestCaseError::fail(format!("p = {p}: {e}")))?;
            assert_close(&format!("z at p = {p}"), &got.z, &sols[0].z_f64(), AGREE)
                .map_err(TestCaseError::fail)?;
            assert_close(&format!("x at p = {p}"), &got.x, &sols[0].w_f64(), AGREE)
                .map_err(TestCaseError::fail)?;
            Ok(())
        };

        let sol = path.solution.as_ref().expect("a ray's path reports the target solution");
        check_at(target, sol)?;

        // Loads on [0, p reached] and a little beyond the last event (on the ray).
        let p_end = path.breakpoints.last().unwrap().p.max(path.p_max);
        let mut loads: Vec<f64> = us.iter().map(|u| u * p_end).collect();
        loads.push(p_end * 1.25 + 0.5);
        loads.extend(path.steps.iter().map(|s| s.p));
        for p in loads {
            let got = solution_at(&problem, &opts, &settings, &path, p).unwrap();
            let got = got.ok_or_else(|| TestCaseError::fail(format!(
                "solution_at({p}) is None; p_max {}, breakpoints {:?}", path.p_max, path.breakpoints)))?;
            check_at(p, &got)?;
        }
    }

    /// Nondegenerate P-matrix paths (`q0 > 0` and `d` with generic `f64` entries): the steps
    /// agree with the oracle's exact parametric Lemke method one for one — the same entering and
    /// leaving variables, the loads to 1e-9 — and so do the breakpoints' `z`.
    #[test]
    fn p_matrix_path_steps_match_oracle(
        (a, b, q0, d) in (1usize..=8).prop_flat_map(|n| (
            square_i(n, -2, 2),
            square_i(n, -2, 2),
            prop::collection::vec(0.25f64..4.0, n),
            prop::collection::vec(-2.0f64..2.0, n),
        ))
    ) {
        let m = psd_plus_skew(&a, &b, 1.0);
        compare_steps(&m, &q0, &d)?;
    }

    /// General integer matrices (any status: ray, mechanism, return to zero) on nondegenerate
    /// data: the same events and the same end as the oracle.
    #[test]
    fn general_path_steps_match_oracle(
        (m, q0, d) in (1usize..=6).prop_flat_map(|n| (
            square_i(n, -3, 3),
            prop::collection::vec(0.25f64..4.0, n),
            prop::collection::vec(-2.0f64..2.0, n),
        ))
    ) {
        compare_steps(&m, &q0, &d)?;
    }
}

fn compare_steps(m: &[Vec<f64>], q0: &[f64], d: &[f64]) -> Result<(), TestCaseError> {
    let n = q0.len();
    let exact = oracle::parametric_path(m, q0, d, None, None);
    prop_assume!(oracle_path_nondegenerate(&exact, n));
    let problem = ParametricLcp {
        m: to_mat(m),
        q0: q0.to_vec(),
        d: d.to_vec(),
    };
    let path = follow_path(&problem, &path_options(1.0), &Settings::default()).unwrap();
    let describe = || {
        format!(
            "\n  engine: {:?} {:?}\n  oracle: {:?} {:?}",
            path.status,
            path.steps
                .iter()
                .map(|s| (s.entering, s.leaving, s.p))
                .collect::<Vec<_>>(),
            exact.status,
            exact
                .steps
                .iter()
                .map(|s| (s.entering, s.leaving, s.p_f64()))
                .collect::<Vec<_>>()
        )
    };
    prop_assert_eq!(path.steps.len(), exact.steps.len(), "{}", describe());
    for (k, (e, o)) in path.steps.iter().zip(&exact.steps).enumerate() {
        prop_assert_eq!(
            oracle_var(e.entering),
            o.entering,
            "step {}{}",
            k + 1,
            describe()
        );
        prop_assert_eq!(
            oracle_var(e.leaving),
            o.leaving,
            "step {}{}",
            k + 1,
            describe()
        );
        let po = o.p_f64();
        prop_assert!(
            (e.p - po).abs() <= AGREE * po.abs().max(1.0),
            "step {}: p = {} vs exact {}{}",
            k + 1,
            e.p,
            po,
            describe()
        );
        prop_assert_eq!(e.turning, o.p_decreased, "step {}{}", k + 1, describe());
    }
    prop_assert!(
        same_status(path.status, exact.status),
        "status{}",
        describe()
    );
    // Breakpoints' z.
    for (k, (bp, pt)) in path.breakpoints.iter().zip(&exact.points).enumerate() {
        let mut z = vec![0.0; n];
        for &(i, v) in &bp.z {
            z[i] = v;
        }
        assert_close(&format!("z at breakpoint {k}"), &z, &pt.z_f64(), AGREE)
            .map_err(TestCaseError::fail)?;
    }
    if path.status == PathStatus::Mechanism {
        let (pl, ol) = (
            path.p_limit.unwrap(),
            oracle::to_f64(exact.last_p().unwrap()),
        );
        prop_assert!(
            (pl - ol).abs() <= AGREE * ol.abs().max(1.0),
            "p_limit {} vs {}",
            pl,
            ol
        );
        let ray = exact.ray.as_ref().unwrap();
        prop_assert_eq!(
            oracle_var(path.mechanism.as_ref().unwrap().entering),
            ray.entering
        );
    }
    Ok(())
}
