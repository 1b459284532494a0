//! The solver object: one `PathSolver`, prepared once, answers for every load of its path; it
//! refuses a path of another problem; its settings errors are typed and keep their words.

use crate::common;

use common::*;
use unilateral_lcp::{
    Follow, LcpError, ParametricLcp, PathOptions, PathSolver, PathStatus, Settings, SettingsError,
    Tightening,
};
use unilateral_oracle as oracle;

/// A P-matrix `AᵀA + I + (B − Bᵀ)` (every LCP of it has exactly one solution), with a `q0` that
/// is not feasible at `p = 0` and a tightening that makes it so.
fn p_matrix_problem() -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let a = vec![
        vec![1.0, -1.0, 0.0, 2.0],
        vec![0.0, 1.0, 1.0, -1.0],
        vec![2.0, 0.0, -1.0, 1.0],
        vec![-1.0, 1.0, 1.0, 0.0],
    ];
    let b = vec![
        vec![0.0, 1.0, -2.0, 0.0],
        vec![1.0, 0.0, 1.0, 1.0],
        vec![0.0, -1.0, 0.0, 2.0],
        vec![2.0, 0.0, 1.0, 0.0],
    ];
    let m = psd_plus_skew(&a, &b, 1.0);
    (m, vec![1.0, -0.5, 2.0, 0.25], vec![-1.0, 0.75, -0.5, -2.0])
}

/// A pivot cap that ends the search for the start is an iteration limit, not "no solution at
/// p = 0". A strictly diagonally dominant matrix with a positive diagonal (a P-matrix: every LCP
/// of it has exactly one solution) of order 20 (above the enumeration's 16) and `q0 = −1`:
/// Lemke's method needs a pivot for every row at p = 0. With three pivots allowed the path
/// said `no_solution_at_start` (and the contact layer blamed the constant loads).
#[test]
fn a_pivot_cap_at_the_start_is_an_iteration_limit() {
    let n = 20;
    let m: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    if i == j {
                        4.0
                    } else {
                        0.15 * (((i * 7 + j * 3) % 5) as f64 - 2.0) / 2.0
                    }
                })
                .collect()
        })
        .collect();
    // strictly diagonally dominant: Σ|off-diagonal| ≤ 19·0.15 < 4
    let q0 = vec![-1.0; n];
    let d = vec![1.0; n];
    let problem = || ParametricLcp {
        m: to_mat(&m),
        q0: q0.clone(),
        d: d.clone(),
    };
    let options = PathOptions {
        target: 1.0,
        follow: Follow::ToTarget,
        tightening: None,
    };
    let capped = Settings {
        max_pivots: Some(3),
        ..Settings::default()
    };
    let path = PathSolver::new(problem(), options.clone(), capped)
        .unwrap()
        .follow();
    assert_eq!(path.status, PathStatus::IterationLimit);
    let path = PathSolver::new(problem(), options, Settings::default())
        .unwrap()
        .follow();
    assert_ne!(path.status, PathStatus::NoSolutionAtStart);
    assert!(path.start_pivots > 0, "the start needs pivots");
}

/// Reference: exhaustive enumeration of complementary bases (`unilateral-oracle`), which for a
/// P-matrix finds the unique solution at each load. One solver answers at every load of the
/// traced path (without the tightening), on the ray beyond the last event too, and its
/// tableaux have one per step plus the initial one and — the path ends on a ray — the final
/// one with `p` out of the basis.
#[test]
fn one_solver_answers_every_load_as_enumeration() {
    let (m, q0, d) = p_matrix_problem();
    let n = q0.len();
    let options = PathOptions {
        target: 2.0,
        follow: Follow::ToEnd,
        tightening: Some(Tightening {
            amount: 1.0,
            direction: vec![1.0; n],
        }),
    };
    let problem = ParametricLcp {
        m: to_mat(&m),
        q0: q0.clone(),
        d: d.clone(),
    };
    let solver = PathSolver::new(problem, options, Settings::default()).unwrap();
    let path = solver.follow();
    assert_eq!(path.status, PathStatus::Ray, "steps {:?}", path.steps);
    assert!(
        path.steps.len() >= 2,
        "the problem must have events to test between"
    );
    let p_end = path.breakpoints.last().unwrap().p.max(path.p_max);
    let mut loads: Vec<f64> = (0..=8).map(|k| k as f64 / 8.0 * p_end).collect();
    loads.extend(path.steps.iter().map(|s| s.p));
    loads.push(1.5 * p_end + 1.0);
    for p in loads {
        let got = solver
            .solution_at(&path, p)
            .unwrap()
            .unwrap_or_else(|| panic!("p = {p} lies on the path"));
        let exact = oracle::enumerate_parametric(&m, &q0, &d, p);
        assert_eq!(exact.len(), 1, "a P-matrix: one solution at p = {p}");
        check_path_point(&m, &q0, &d, &got, 1e-10).unwrap();
        assert_close(&format!("z at p = {p}"), &got.z, &exact[0].z_f64(), 1e-9).unwrap();
        assert_close(&format!("x at p = {p}"), &got.x, &exact[0].w_f64(), 1e-9).unwrap();
    }
    let tables = solver.tableaux(&path, None).unwrap();
    assert_eq!(tables.len(), path.steps.len() + 2);
}

/// Reference: the contract of `PathSolver::solution_at` and `PathSolver::tableaux` — a path
/// of a problem of another order is refused with a dimension error, not read out of bounds.
#[test]
fn a_path_of_another_problem_is_refused() {
    let small = ParametricLcp {
        m: to_mat(&[vec![2.0, 1.0], vec![1.0, 2.0]]),
        q0: vec![1.0, 1.0],
        d: vec![-1.0, -1.0],
    };
    let (m, q0, d) = p_matrix_problem();
    let large = ParametricLcp {
        m: to_mat(&m),
        q0,
        d,
    };
    let options = PathOptions::default();
    let small = PathSolver::new(small, options.clone(), Settings::default()).unwrap();
    let large = PathSolver::new(large, options, Settings::default()).unwrap();
    let path = large.follow();
    assert!(matches!(
        small.solution_at(&path, 0.5),
        Err(LcpError::Dimension(_))
    ));
    assert!(matches!(
        small.tableaux(&path, None),
        Err(LcpError::Dimension(_))
    ));
}

/// Reference: the messages of the engine's settings checks as the program has always printed
/// them, and the setting each names (what a reader points at).
#[test]
fn settings_errors_are_typed_and_keep_their_words() {
    let problem = ParametricLcp {
        m: to_mat(&[vec![2.0, 1.0], vec![1.0, 2.0]]),
        q0: vec![1.0, 1.0],
        d: vec![-1.0, -1.0],
    };
    let refused = |options: PathOptions, settings: Settings| match PathSolver::new(
        problem.clone(),
        options,
        settings,
    ) {
        Err(LcpError::Settings(e)) => e,
        other => panic!("expected a settings error, got {other:?}"),
    };
    let cases = [
        (
            refused(
                PathOptions {
                    target: -1.0,
                    ..PathOptions::default()
                },
                Settings::default(),
            ),
            "target",
            "invalid setting: target must be a finite number > 0 (and not below 2.2e-308), got -1e0",
        ),
        // a subnormal target carries no load's digits (1e-320 ran to an internal failure)
        (
            refused(
                PathOptions {
                    target: 1e-320,
                    ..PathOptions::default()
                },
                Settings::default(),
            ),
            "target",
            "invalid setting: target must be a finite number > 0 (and not below 2.2e-308), got 1e-320",
        ),
        (
            refused(
                PathOptions {
                    tightening: Some(Tightening {
                        amount: f64::INFINITY,
                        direction: vec![1.0; 2],
                    }),
                    ..PathOptions::default()
                },
                Settings::default(),
            ),
            "tightening",
            "invalid setting: tightening must be a finite number ≥ 0, got inf",
        ),
        (
            refused(
                PathOptions {
                    tightening: Some(Tightening {
                        amount: 1.0,
                        direction: vec![1.0, -1.0],
                    }),
                    ..PathOptions::default()
                },
                Settings::default(),
            ),
            "tightening",
            "invalid setting: tightening direction entry 2 is negative",
        ),
        (
            refused(
                PathOptions::default(),
                Settings {
                    pivot_tolerance: Some(0.5),
                    ..Settings::default()
                },
            ),
            "pivot_tolerance",
            "invalid setting: pivot_tolerance must lie in (0, 0.01), got 0.5",
        ),
        (
            refused(
                PathOptions::default(),
                Settings {
                    max_pivots: Some(0),
                    ..Settings::default()
                },
            ),
            "max_pivots",
            "invalid setting: max_pivots must be at least 1",
        ),
        (
            refused(
                PathOptions::default(),
                Settings {
                    lexicographic_order: Some(vec![0, 0]),
                    ..Settings::default()
                },
            ),
            "lexicographic_order",
            "invalid setting: lexicographic_order must be a permutation of 0..2",
        ),
        (
            refused(
                PathOptions::default(),
                Settings {
                    covering: Some(vec![1.0, 0.0]),
                    ..Settings::default()
                },
            ),
            "covering",
            "invalid setting: covering vector entry 1 must be a finite number > 0, got 0",
        ),
    ];
    for (e, key, text) in cases {
        assert_eq!(e.key(), key);
        assert_eq!(LcpError::Settings(e).to_string(), text);
    }
    assert_eq!(
        Settings {
            refactor_interval: 0,
            ..Settings::default()
        }
        .validate_values(),
        Err(SettingsError::RefactorInterval)
    );
}
