//! The paper's Example 1 (formulation.md §5): the `3m` LCP built by hand from its data, its
//! path and Tables 1–3.

use crate::common::to_mat;
use unilateral_lcp::{
    follow_path, tableaux, Follow, ParametricLcp, PathOptions, PathStatus, Settings, Tightening,
    Var,
};
use unilateral_oracle::fixtures::example1 as ex1;

/// `M`, `d` of formulation.md §3 for Example 1 (f = 0.6, Rnt = Rtn = 0), from the shared
/// fixture.
fn example1() -> ParametricLcp {
    let lcp = ex1::lcp();
    ParametricLcp {
        m: to_mat(&lcp.m),
        q0: vec![0.0; 9],
        d: lcp.d,
    }
}

fn options(follow: Follow) -> PathOptions {
    PathOptions {
        target: 1.0,
        follow,
        tightening: Some(Tightening {
            amount: 1.0,
            direction: vec![1.0; 9],
        }),
    }
}

#[test]
fn path_is_one_event_then_a_ray() {
    let problem = example1();
    let path = follow_path(&problem, &options(Follow::ToEnd), &Settings::default()).unwrap();
    assert_eq!(path.status, PathStatus::Ray);
    assert_eq!(path.steps.len(), 1);
    assert!((path.steps[0].p - ex1::FIRST_EVENT_P).abs() < 1e-12);
    assert_eq!(path.steps[0].entering, Var::Driver);
    assert_eq!(path.steps[0].leaving, Var::X(0));
    assert_eq!(path.last_entering, Some(Var::Z(0)));
    let sol = path.solution.as_ref().unwrap();
    assert_eq!(sol.p, 1.0);
    let (expect_z, expect_x) = (ex1::Z_AT_TARGET, ex1::X_AT_TARGET);
    for i in 0..9 {
        assert!(
            (sol.z[i] - expect_z[i]).abs() < 1e-12,
            "z{i} = {}",
            sol.z[i]
        );
        assert!(
            (sol.x[i] - expect_x[i]).abs() < 1e-12,
            "x{i} = {}",
            sol.x[i]
        );
    }
    assert!(sol.residual.max() < 1e-14);
}

#[test]
fn default_trace_stops_before_the_first_event_with_the_same_answer() {
    let problem = example1();
    let path = follow_path(&problem, &options(Follow::ToTarget), &Settings::default()).unwrap();
    assert_eq!(path.status, PathStatus::TargetReached);
    assert!(path.steps.is_empty());
    let sol = path.solution.as_ref().unwrap();
    assert!(sol.tightening_pivots > 0, "c must be driven out");
    assert!(
        !sol.fallback,
        "c must be removed along the path, not by a fresh solve"
    );
    assert!((sol.z[0] - 0.5).abs() < 1e-12);
    assert!((sol.x[1] - 0.5).abs() < 1e-12 && (sol.x[2] - 0.5).abs() < 1e-12);
}

#[test]
fn tables_1_2_3() {
    let problem = example1();
    let opts = options(Follow::ToEnd);
    let path = follow_path(&problem, &opts, &Settings::default()).unwrap();
    let t = tableaux(&problem, &opts, &path, None).unwrap();
    assert_eq!(t.len(), 3);
    // Table 1: p column = -d, rhs = 1, ratio 10.6667 for x_n1 and 17.7778 for x_t1±.
    assert!((t[0].entries[0][18] + ex1::RV_N[0]).abs() < 1e-12);
    assert!((t[0].ratios[0].unwrap() - 10.0 - 2.0 / 3.0).abs() < 1e-9);
    assert!((t[0].ratios[3].unwrap() - 17.0 - 7.0 / 9.0).abs() < 1e-9);
    assert_eq!(t[0].leaving_row, Some(0));
    // Table 2: p row
    assert_eq!(t[1].basis[0], Var::Driver);
    assert!((t[1].rhs[0] - ex1::FIRST_EVENT_P).abs() < 1e-9);
    assert!((t[1].entries[0][9] + 2.0).abs() < 1e-9);
    assert!(t[1].ratios.iter().all(|r| r.is_none()));
    // Table 3: rhs and p column
    let (rhs3, pcol) = (ex1::TABLE3_RHS, ex1::TABLE3_P_COLUMN);
    for i in 0..9 {
        assert!(
            (t[2].rhs[i] - rhs3[i]).abs() < 1e-9,
            "rhs {i}: {}",
            t[2].rhs[i]
        );
        assert!((t[2].entries[i][18] - pcol[i]).abs() < 1e-9, "p col {i}");
    }
}
