//! Degenerate and cycling-prone problems, written out explicitly: duplicate rows, zero rows,
//! ties in the first ratio test, Murty's exponential example and small classics from the
//! literature. Each must end with the right status and a verified residual, and agree with the
//! exact oracle wherever the oracle's answer is unique.

use crate::common;

use common::*;
use unilateral_lcp::{
    follow_path, solve_lcp, Follow, Lcp, LcpSolution, LcpStatus, ParametricLcp, PathOptions,
    PathStatus, Settings, Strategy,
};
use unilateral_oracle as oracle;
use unilateral_oracle::fixtures::random::Lcg;

const TOL: f64 = 1e-10;

fn m_of(rows: &[&[f64]]) -> Vec<Vec<f64>> {
    rows.iter().map(|r| r.to_vec()).collect()
}

fn solve_with(m: &[Vec<f64>], q: &[f64], settings: &Settings) -> LcpSolution {
    let lcp = Lcp {
        m: to_mat(m),
        q: q.to_vec(),
    };
    solve_lcp(&lcp, settings).expect("valid input")
}

/// Solves with the engine and checks it against exhaustive exact enumeration: `Ray` exactly
/// when there is no solution; otherwise `Solved`, a verified residual, and — when the oracle's
/// list of solutions is complete — one of the enumerated solutions.
fn check_against_enumeration(name: &str, m: &[Vec<f64>], q: &[f64]) -> LcpSolution {
    let sol = solve_with(m, q, &Settings::default());
    let sols = oracle::enumerate(m, q);
    if sols.is_empty() {
        assert_eq!(
            sol.status,
            LcpStatus::Ray,
            "{name}: no solution exists; attempts {:?}",
            sol.attempts
        );
        assert!(sol.point.is_none());
        return sol;
    }
    assert_eq!(
        sol.status,
        LcpStatus::Solved,
        "{name}: enumeration finds {} solution(s); attempts {:?}",
        sols.len(),
        sol.attempts
    );
    let pt = sol.point.as_ref().unwrap();
    check_point(m, q, pt, TOL).unwrap_or_else(|e| panic!("{name}: {e}"));
    if sols.iter().all(|s| s.singular_sets.is_empty()) {
        assert!(
            sols.iter()
                .any(|s| assert_close("z", &pt.z, &s.z_f64(), 1e-9).is_ok()
                    && assert_close("w", &pt.w, &s.w_f64(), 1e-9).is_ok()),
            "{name}: engine z = {:?} is none of the enumerated {:?}",
            pt.z,
            sols.iter().map(|s| s.z_f64()).collect::<Vec<_>>()
        );
    }
    sol
}

// ---------------------------------------------------------------------------------------------
// Standard LCP

#[test]
fn duplicate_rows_hand_case() {
    // Rows 0 and 1 of [M | q] are equal: w0 ≡ w1, M singular.
    let m = m_of(&[&[2.0, 1.0, 1.0], &[2.0, 1.0, 1.0], &[1.0, 1.0, 2.0]]);
    let q = [-2.0, -2.0, -1.0];
    let sol = check_against_enumeration("duplicate rows", &m, &q);
    let pt = sol.point.unwrap();
    assert!(
        pt.w[0].abs() < 1e-12 && pt.w[1].abs() < 1e-12,
        "w = {:?}",
        pt.w
    );
}

#[test]
fn duplicate_rows_family() {
    // P-matrices with row i of [M | q] copied into row j (and, every other case, also column
    // i into column j, which makes z_i and z_j interchangeable: a continuum of solutions).
    let mut g = Lcg::new(7);
    let mut statuses = [0usize; 2];
    for case in 0..60 {
        let n = 2 + case % 5;
        let mut m = g.p_matrix(n);
        let mut q = g.vector(n, -6, 6);
        let i = g.int(0, n as i64 - 1) as usize;
        let j = (i + 1 + g.int(0, n as i64 - 2) as usize) % n;
        m[j] = m[i].clone();
        q[j] = q[i];
        if case % 2 == 1 {
            for row in m.iter_mut() {
                row[j] = row[i];
            }
        }
        let sol = check_against_enumeration(&format!("duplicate rows, case {case}"), &m, &q);
        statuses[usize::from(sol.status == LcpStatus::Solved)] += 1;
    }
    assert!(statuses[1] > 0);
}

#[test]
fn zero_row_with_negative_q_has_no_solution() {
    // w0 = −1 whatever z: infeasible.
    let m = m_of(&[&[0.0, 0.0, 0.0], &[1.0, 2.0, 0.0], &[0.0, 1.0, 3.0]]);
    let sol = check_against_enumeration("zero row, q0 < 0", &m, &[-1.0, -1.0, -1.0]);
    assert_eq!(sol.status, LcpStatus::Ray);
}

#[test]
fn zero_row_with_zero_q() {
    // w0 = 0 always: degenerate in every basis.
    let m = m_of(&[&[0.0, 0.0, 0.0], &[1.0, 2.0, 0.0], &[-1.0, 1.0, 3.0]]);
    check_against_enumeration("zero row, q0 = 0", &m, &[0.0, -2.0, -1.0]);
    check_against_enumeration("zero row, q0 = 0, b", &m, &[0.0, 2.0, -1.0]);
}

#[test]
fn zero_row_and_column() {
    // z0 is free of every equation except its own, where it has no effect.
    let m = m_of(&[&[0.0, 0.0, 0.0], &[0.0, 2.0, 1.0], &[0.0, 1.0, 2.0]]);
    let sol = check_against_enumeration("zero row and column", &m, &[1.0, -3.0, -3.0]);
    let pt = sol.point.unwrap();
    assert_close("z", &pt.z, &[0.0, 1.0, 1.0], 1e-12).unwrap();
    let sol = check_against_enumeration("zero row and column, q0 = 0", &m, &[0.0, -3.0, -3.0]);
    let pt = sol.point.unwrap();
    assert!((pt.z[1] - 1.0).abs() < 1e-12 && (pt.z[2] - 1.0).abs() < 1e-12);
    check_against_enumeration("zero matrix", &vec![vec![0.0; 3]; 3], &[0.0, 1.0, 0.0]);
    check_against_enumeration(
        "zero matrix, q < 0",
        &vec![vec![0.0; 3]; 3],
        &[0.0, -1.0, 0.0],
    );
}

#[test]
fn zero_rows_family() {
    // Random P-matrices with one or two rows zeroed, random q: Ray exactly when enumeration
    // finds nothing.
    let mut g = Lcg::new(11);
    let mut seen = [0usize; 2];
    for case in 0..60 {
        let n = 2 + case % 6;
        let mut m = g.p_matrix(n);
        let q = g.vector(n, -4, 4);
        for _ in 0..1 + case % 2 {
            let i = g.int(0, n as i64 - 1) as usize;
            m[i] = vec![0.0; n];
        }
        let sol = check_against_enumeration(&format!("zero rows, case {case}"), &m, &q);
        seen[usize::from(sol.status == LcpStatus::Solved)] += 1;
    }
    assert!(
        seen[0] > 0 && seen[1] > 0,
        "both outcomes exercised: {seen:?}"
    );
}

#[test]
fn all_rows_tie_at_the_first_step() {
    // q = −e with covering vector e: every row attains the first ratio.
    for n in [2usize, 4, 7] {
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| if i == j { 3.0 } else { 1.0 }).collect())
            .collect();
        let sol = check_against_enumeration(&format!("2I + ee', n = {n}"), &m, &vec![-1.0; n]);
        let pt = sol.point.unwrap();
        let v = 1.0 / (n as f64 + 2.0);
        assert_close("z", &pt.z, &vec![v; n], 1e-12).unwrap();
    }
    // lcp_trivial.dat: diag(1..9), q = −e.
    let n = 9;
    let m: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i == j { (i + 1) as f64 } else { 0.0 })
                .collect()
        })
        .collect();
    let sol = check_against_enumeration("lcp_trivial", &m, &vec![-1.0; n]);
    let want: Vec<f64> = (0..n).map(|i| 1.0 / (i + 1) as f64).collect();
    assert_close("z", &sol.point.unwrap().z, &want, 1e-12).unwrap();
}

#[test]
fn ties_at_the_first_step_with_every_lexicographic_order() {
    // Pairs of rows with equal ratios at the first step; the answer must not depend on the
    // tie-break order.
    let m = m_of(&[
        &[2.0, 1.0, 0.0, 0.0],
        &[1.0, 2.0, 1.0, 0.0],
        &[0.0, 1.0, 2.0, 1.0],
        &[0.0, 0.0, 1.0, 2.0],
    ]);
    let q = [-1.0, -2.0, -1.0, -2.0];
    let sols = oracle::enumerate(&m, &q);
    assert_eq!(sols.len(), 1);
    let orders: [[usize; 4]; 4] = [[0, 1, 2, 3], [3, 2, 1, 0], [1, 3, 0, 2], [2, 0, 3, 1]];
    for order in orders {
        for covering in [None, Some(vec![1.0, 2.0, 1.0, 2.0])] {
            let settings = Settings {
                lexicographic_order: Some(order.to_vec()),
                covering: covering.clone(),
                ..Settings::default()
            };
            let sol = solve_with(&m, &q, &settings);
            assert_eq!(sol.status, LcpStatus::Solved, "order {order:?}");
            let pt = sol.point.unwrap();
            check_point(&m, &q, &pt, TOL).unwrap();
            assert_close("z", &pt.z, &sols[0].z_f64(), 1e-12).unwrap();
        }
    }
}

/// Murty's example (lcp_exp_murty.dat): lower triangular, 1 on the diagonal, 2 below, q = −e.
fn murty(n: usize) -> (Vec<Vec<f64>>, Vec<f64>) {
    let m = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| match i.cmp(&j) {
                    std::cmp::Ordering::Equal => 1.0,
                    std::cmp::Ordering::Greater => 2.0,
                    std::cmp::Ordering::Less => 0.0,
                })
                .collect()
        })
        .collect();
    (m, vec![-1.0; n])
}

#[test]
fn murty_exponential_example() {
    for n in [6usize, 10] {
        let (m, q) = murty(n);
        // A P-matrix: the unique solution is z = e1, w = (0, 1, …, 1).
        let sol = check_against_enumeration(&format!("Murty n = {n}"), &m, &q);
        let pt = sol.point.as_ref().unwrap();
        let mut z = vec![0.0; n];
        z[0] = 1.0;
        let mut w = vec![1.0; n];
        w[0] = 0.0;
        assert_close("z", &pt.z, &z, 1e-12).unwrap();
        assert_close("w", &pt.w, &w, 1e-12).unwrap();
        assert!(pt.residual.max() <= 1e-14, "{:?}", pt.residual);
        // Lemke's method proper (not the enumeration fallback) must terminate on it, within the
        // pivot cap, like the exact lexicographic method does.
        let exact = oracle::lemke(&m, &q, &vec![1.0; n]);
        assert_eq!(exact.status, oracle::LemkeStatus::Solved);
        assert!(
            matches!(sol.strategy, Strategy::Lemke { .. }),
            "n = {n}: solved by {:?} after {} pivots (exact lexicographic Lemke: {} pivots); attempts {:?}",
            sol.strategy,
            sol.pivots,
            exact.pivots,
            sol.attempts
        );
    }
}

#[test]
fn literature_classics() {
    // lcp_CPS_1: a continuum of solutions z1 + z2 = 1.
    let m = m_of(&[&[1.0, 1.0], &[1.0, 1.0]]);
    let sol = check_against_enumeration("CPS 4.1.14", &m, &[-1.0, -1.0]);
    let z = sol.point.unwrap().z;
    assert!((z[0] + z[1] - 1.0).abs() < 1e-12, "z = {z:?}");
    // lcp_CPS_2.
    let m = m_of(&[&[0.0, 2.0, -1.0], &[-1.0, 0.0, 1.0], &[2.0, -2.0, 0.0]]);
    check_against_enumeration("CPS 4.4.7", &m, &[-3.0, 6.0, -1.0]);
    // lcp_CPS_3: a bimatrix game, every row ties at the first step.
    let m = m_of(&[
        &[0.0, 0.0, 10.0, 30.0],
        &[0.0, 0.0, 20.0, 15.0],
        &[10.0, 30.0, 0.0, 0.0],
        &[20.0, 15.0, 0.0, 0.0],
    ]);
    check_against_enumeration("CPS 4.4.23 bimatrix", &m, &[-1.0; 4]);
    // lcp_Pang_isolated_sol.
    let m = m_of(&[&[0.0, 1.0, -1.0], &[-1.0, 0.0, 0.0], &[-1.0, 0.0, 0.0]]);
    check_against_enumeration("Pang isolated", &m, &[0.0, -1.0, 1.0]);
    // lcp_ortiz.
    let m = m_of(&[
        &[3.0, -1.0, 0.0, 0.0],
        &[1.0, 2.0, 1.0, 0.0],
        &[0.0, 1.0, 3.0, 1.0],
        &[-1.0, 1.0, -1.0, 2.0],
    ]);
    check_against_enumeration("Ortiz", &m, &[-2.0, 1.0, -1.0, 1.0]);
    // lcp_deudeu.
    let m = m_of(&[&[2.0, 1.0], &[1.0, 2.0]]);
    check_against_enumeration("deudeu", &m, &[-5.0, -6.0]);
}

// ---------------------------------------------------------------------------------------------
// Parametric LCP

/// Follows the path to its end and checks it against the oracle's exact parametric Lemke
/// method with the same lexicographic order: the same events and status; the solution at the
/// target equals the enumerated one when that is unique.
fn check_path_against_oracle(
    name: &str,
    m: &[Vec<f64>],
    q0: &[f64],
    d: &[f64],
    target: f64,
    order: Option<Vec<usize>>,
) -> unilateral_lcp::LoadPath {
    let problem = ParametricLcp {
        m: to_mat(m),
        q0: q0.to_vec(),
        d: d.to_vec(),
    };
    let opts = PathOptions {
        target,
        follow: Follow::ToEnd,
        tightening: None,
    };
    let settings = Settings {
        lexicographic_order: order.clone(),
        ..Settings::default()
    };
    let path = follow_path(&problem, &opts, &settings).unwrap();
    let exact = oracle::parametric_path(m, q0, d, None, order.as_deref());
    if let Err(diff) = same_events(&path, &exact) {
        panic!("{name}:\n  {diff}");
    }
    let sols = oracle::enumerate_parametric(m, q0, d, target);
    if let Some(sol) = &path.solution {
        check_path_point(m, q0, d, sol, TOL).unwrap_or_else(|e| panic!("{name}: {e}"));
        if sol.p == target && sols.len() == 1 && sols[0].singular_sets.is_empty() {
            assert_close("z", &sol.z, &sols[0].z_f64(), 1e-9)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
    path
}

/// A P-matrix with `q0` in `q0_low..=` (up to 3 if `q0_low` ≥ 0, else up to 1) and `d` in
/// `-3..=3`, and one row of `[M | q0 | d]` copied onto another.
fn duplicated_row(g: &mut Lcg, n: usize, q0_low: i64) -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let mut m = g.p_matrix(n);
    let mut q0 = g.vector(n, q0_low, if q0_low >= 0 { 3 } else { 1 });
    let mut d = g.vector(n, -3, 3);
    let i = g.int(0, n as i64 - 1) as usize;
    let j = (i + 1 + g.int(0, n as i64 - 2) as usize) % n;
    m[j] = m[i].clone();
    q0[j] = q0[i];
    d[j] = d[i];
    (m, q0, d)
}

#[test]
fn parametric_duplicate_rows_tie_at_the_first_step() {
    // Rows 1 and 2 of [M | q0 | d] are equal: both reach zero at p = 1 together.
    let m = m_of(&[&[3.0, 1.0, 0.0], &[1.0, 2.0, 1.0], &[1.0, 2.0, 1.0]]);
    let q0 = [2.0, 1.0, 1.0];
    let d = [1.0, -1.0, -1.0];
    for order in [None, Some(vec![2, 1, 0]), Some(vec![1, 2, 0])] {
        let path = check_path_against_oracle(
            &format!("duplicate rows, order {order:?}"),
            &m,
            &q0,
            &d,
            3.0,
            order,
        );
        assert!((path.steps[0].p - 1.0).abs() < 1e-12);
    }
    // A family: P-matrices with a duplicated row, q0 ≥ 0 with zeros, every end status.
    let mut g = Lcg::new(23);
    for case in 0..60 {
        let n = 2 + case % 5;
        let (m, q0, d) = duplicated_row(&mut g, n, 0);
        let order: Vec<usize> = (0..n).rev().collect();
        check_path_against_oracle(&format!("dup family {case}"), &m, &q0, &d, 2.0, None);
        check_path_against_oracle(
            &format!("dup family {case}, reversed"),
            &m,
            &q0,
            &d,
            2.0,
            Some(order),
        );
    }
}

#[test]
fn parametric_all_rows_tie_at_the_first_step() {
    // q0 = e, d = −e: every x_i reaches zero at p = 1.
    for n in [2usize, 3, 5] {
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| if i == j { 3.0 } else { 1.0 }).collect())
            .collect();
        let q0 = vec![1.0; n];
        let d = vec![-1.0; n];
        let path = check_path_against_oracle(&format!("all tie, n = {n}"), &m, &q0, &d, 4.0, None);
        assert_eq!(path.status, PathStatus::Ray);
        // At p = 4: z = 3/(n + 2)·e.
        let sol = path.solution.unwrap();
        assert_close("z", &sol.z, &vec![3.0 / (n as f64 + 2.0); n], 1e-12).unwrap();
        let reversed: Vec<usize> = (0..n).rev().collect();
        check_path_against_oracle(
            &format!("all tie, n = {n}, reversed"),
            &m,
            &q0,
            &d,
            4.0,
            Some(reversed),
        );
    }
}

#[test]
fn parametric_degenerate_start_q0_zero() {
    // q0 = 0 (homogeneous, like contact without tightening): every ratio of the first step is 0.
    let m = m_of(&[&[2.0, -1.0, 0.0], &[-1.0, 2.0, -1.0], &[0.0, -1.0, 2.0]]);
    let q0 = [0.0; 3];
    let d = [-1.0, 0.5, -0.25];
    check_path_against_oracle("q0 = 0", &m, &q0, &d, 1.0, None);
    check_path_against_oracle("q0 = 0, reversed", &m, &q0, &d, 1.0, Some(vec![2, 1, 0]));
}

#[test]
fn parametric_zero_row_ends_in_a_true_mechanism() {
    // Row 0 of M is zero and d0 < 0: x0 = 2 − p whatever z, so no solution exists beyond p = 2.
    let m = m_of(&[&[0.0, 0.0, 0.0], &[0.0, 2.0, 1.0], &[0.0, 1.0, 2.0]]);
    let q0 = [2.0, 1.0, 1.0];
    let d = [-1.0, -1.0, 0.5];
    let path = check_path_against_oracle("zero row", &m, &q0, &d, 5.0, None);
    assert_eq!(path.status, PathStatus::Mechanism);
    assert!((path.p_limit.unwrap() - 2.0).abs() < 1e-12);
    assert!(oracle::enumerate_parametric(&m, &q0, &d, 2.001).is_empty());
    // The reported solution is at the limit load and verifies.
    let sol = path.solution.unwrap();
    assert!((sol.p - 2.0).abs() < 1e-12);
    check_path_point(&m, &q0, &d, &sol, TOL).unwrap();
}

#[test]
fn parametric_degenerate_removal_of_the_tightening() {
    // The tightening is removed from the path's last basis, which is not the slack basis: with a
    // duplicated row of [M | q0 | d] the removal's ratio tests tie, and the lexicographic rule
    // measured against that start basis must break them. References: the oracle's exact path of
    // the tightened problem (q0 + c·e) for the events, and the exact enumeration of the problem
    // without tightening for the reported solution (equal to it when unique; otherwise the
    // solution is checked exactly against the original data).
    let mut g = Lcg::new(41);
    let mut removed = 0;
    for case in 0..80 {
        let n = 2 + case % 5;
        // q0 ≤ 0 somewhere: the start needs the tightening.
        let (m, q0, d) = duplicated_row(&mut g, n, -3);
        let c = 4.0;
        let problem = ParametricLcp {
            m: to_mat(&m),
            q0: q0.clone(),
            d: d.clone(),
        };
        let opts = PathOptions {
            target: 1.5,
            follow: Follow::ToEnd,
            tightening: Some(unilateral_lcp::Tightening {
                amount: c,
                direction: vec![1.0; n],
            }),
        };
        let path = follow_path(&problem, &opts, &Settings::default()).unwrap();
        let tightened: Vec<f64> = q0.iter().map(|q| q + c).collect();
        let exact = oracle::parametric_path(&m, &tightened, &d, None, None);
        // The events on the way up to the target (after a turning point, a return to p = 0
        // may tie between the driver and another row, which the engine gives to the driver by
        // design).
        fn rising(v: Vec<(oracle::Var, oracle::Var, f64)>) -> Vec<(oracle::Var, oracle::Var, f64)> {
            let mut last = 0.0;
            v.into_iter()
                .take_while(|s| {
                    let ok = s.2 >= last && s.2 <= 1.5;
                    last = s.2;
                    ok
                })
                .collect()
        }
        let e = rising(
            path.steps
                .iter()
                .map(|s| (oracle_var(s.entering), oracle_var(s.leaving), s.p))
                .collect(),
        );
        let o = rising(
            exact
                .steps
                .iter()
                .map(|s| (s.entering, s.leaving, s.p_f64()))
                .collect(),
        );
        let same = e.len() == o.len()
            && e.iter().zip(&o).all(|(a, b)| {
                a.0 == b.0 && a.1 == b.1 && (a.2 - b.2).abs() <= 1e-9 * b.2.abs().max(1.0)
            });
        assert!(same, "case {case}:\n  engine {e:?}\n  oracle {o:?}");
        let Some(sol) = &path.solution else { continue };
        removed += usize::from(sol.tightening_pivots > 0);
        check_path_point(&m, &q0, &d, sol, TOL).unwrap_or_else(|e| panic!("case {case}: {e}"));
        let sols = oracle::enumerate_parametric(&m, &q0, &d, sol.p);
        if sols.len() == 1 && sols[0].singular_sets.is_empty() {
            assert_close("z", &sol.z, &sols[0].z_f64(), 1e-9)
                .unwrap_or_else(|e| panic!("case {case}: {e}"));
        }
    }
    // The family exercises the removal (not only starts that were feasible without it).
    assert!(removed >= 20, "only {removed} removals");
}

/// A degenerate solution of a badly scaled 5 × 5 LCP (rows and columns by powers of ten, from a
/// review's random search): every Lemke path ends on a secondary ray, and the only solution,
/// `z = (0, 0, 2e5, 0, 1e-4)`, `w = (1e4, 0, 0, 3e-4, 0)` (exact, found by a review with sympy
/// on the file's binary numbers; `z₂ = w₂ = 0`), lies on the basis `{z₂, z₃, z₅}`. Its
/// solve gives `z₂ ≈ 4e-19`, the only term of row 3 (`−z₂`): that row then verified against
/// that round-off alone (relative residual 1) and the enumeration answered "no solution".
#[test]
fn enumeration_finds_a_degenerate_solution_of_a_badly_scaled_lcp() {
    // Siconos `.dat` order: columns of M.
    let cols: [[f64; 5]; 5] = [
        [40.0, 3e-05, -1e-10, 0.0, 1.0],
        [0.0, -200000.0, -1.0, 40000.0, 20000000000.0],
        [
            0.03,
            -1.9999999999999997e-08,
            0.0,
            4e-09,
            0.0029999999999999996,
        ],
        [0.0, 2e-09, -1e-14, -1e-10, 0.00019999999999999998],
        [20000000.0, 40.0, 0.0, -2.0, -3000000.0],
    ];
    let m: Vec<Vec<f64>> = (0..5)
        .map(|i| (0..5).map(|j| cols[j][i]).collect())
        .collect();
    let q = [2000.0, 0.0, 0.0, -0.00030000000000000003, -300.0];
    let sol = solve_with(&m, &q, &Settings::default());
    assert_eq!(sol.status, LcpStatus::Solved, "{:?}", sol.attempts);
    assert_eq!(sol.strategy, Strategy::Enumeration);
    let pt = sol.point.expect("a point");
    let (z_want, w_want) = ([0.0, 0.0, 2e5, 0.0, 1e-4], [1e4, 0.0, 0.0, 3e-4, 0.0]);
    for i in 0..5 {
        assert!(
            (pt.z[i] - z_want[i]).abs() <= 1e-9 * z_want[i].abs().max(1e-30),
            "{:?}",
            pt.z
        );
        assert!(
            (pt.w[i] - w_want[i]).abs() <= 1e-9 * w_want[i].abs().max(1e-30),
            "{:?}",
            pt.w
        );
    }
}
