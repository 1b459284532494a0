//! The sweep `PathSolver::points_at`: one walk along the path answers at many loads exactly as
//! `PathSolver::solution_at` does at each, and as the oracle's exhaustive enumeration.

use crate::common;

use common::*;
use unilateral_lcp::{
    Follow, LcpError, ParametricLcp, PathOptions, PathPoint, PathSolver, PathStatus, Settings,
    Tightening,
};
use unilateral_oracle as oracle;
use unilateral_oracle::fixtures::{beam, frictional_lcp, random::Lcg};

/// Agreement between the sweep and `solution_at` (the same basis, factorised afresh there and
/// updated by pivots here), relative to the largest value of the point.
const AGREE: f64 = 1e-9;

/// The loads a report asks for: the start, every event, midpoints between events, and (for a
/// ray) beyond the last event; plus loads off the path (negative, and past its end).
fn loads_of(path: &unilateral_lcp::LoadPath) -> Vec<f64> {
    let mut loads = vec![0.0];
    let mut prev = 0.0;
    for s in &path.steps {
        loads.push(0.5 * (prev + s.p));
        loads.push(s.p);
        prev = s.p;
    }
    loads.push(1.5 * path.p_max.max(1.0));
    loads.push(-1.0);
    loads.push(1e6 * path.p_max.max(1.0));
    loads
}

fn same_point(what: &str, got: &Option<PathPoint>, want: &Option<PathPoint>) -> Result<(), String> {
    match (got, want) {
        (None, None) => Ok(()),
        (Some(g), Some(w)) => {
            assert_close(&format!("{what} x"), &g.x, &w.x, AGREE)?;
            assert_close(&format!("{what} z"), &g.z, &w.z, AGREE)?;
            // The sweep's own fallback is `solution_at`'s procedure, so it never needs a fresh
            // solve where `solution_at` does not; it may succeed where `solution_at`'s
            // refactorised basis did not verify (the values are then the same, checked above).
            if g.fallback && !w.fallback {
                return Err(format!("{what}: the sweep fell back, solution_at did not"));
            }
            Ok(())
        }
        _ => Err(format!(
            "{what}: sweep {:?}, solution_at {:?}",
            got.is_some(),
            want.is_some()
        )),
    }
}

/// Reference: `PathSolver::solution_at` at each load (the procedure the sweep replaces) and,
/// for these P-matrices, the unique solution at each load found by exhaustive enumeration of
/// the complementary bases in exact rationals. 200 seeded problems of order 1..=8, with and
/// without a tightening, `q0` often infeasible at `p = 0`.
#[test]
fn random_p_matrices_agree_with_solution_at_and_enumeration() {
    let mut rng = Lcg::new(0x005e_ed11);
    let mut compared = 0usize;
    for case in 0..200 {
        let n = 1 + case % 8;
        let m = rng.p_matrix(n);
        let q0 = rng.vector(n, -4, 6);
        let d = rng.vector(n, -5, 5);
        let tightening = (case % 2 == 0).then(|| Tightening {
            amount: 1.0 + rng.int(0, 3) as f64,
            direction: vec![1.0; n],
        });
        let options = PathOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            tightening,
        };
        let problem = ParametricLcp {
            m: to_mat(&m),
            q0: q0.clone(),
            d: d.clone(),
        };
        let solver = PathSolver::new(problem, options, Settings::default()).unwrap();
        let path = solver.follow();
        let loads = loads_of(&path);
        let swept = solver.points_at(&path, &loads).unwrap();
        assert_eq!(swept.len(), loads.len());
        for (&p, got) in loads.iter().zip(&swept) {
            let want = solver.solution_at(&path, p).unwrap();
            same_point(&format!("case {case}, p = {p}"), got, &want)
                .unwrap_or_else(|e| panic!("{e}\npath {:?}", path.steps));
            if let Some(pt) = got {
                let sols = oracle::enumerate_parametric(&m, &q0, &d, p);
                assert_eq!(sols.len(), 1, "a P-matrix LCP has one solution");
                assert_close("z vs enumeration", &pt.z, &sols[0].z_f64(), AGREE).unwrap();
                assert_close("x vs enumeration", &pt.x, &sols[0].w_f64(), AGREE).unwrap();
                compared += 1;
            }
        }
    }
    assert!(compared > 1000, "only {compared} points compared");
}

/// The frictional `3m` LCP of the generated beam (`fixtures::beam`) with the paper's
/// tightening `c = 1`: where the path's basis is infeasible without the tightening it must be
/// removed by pivots, the case of the sweep that works on a copy of its basis.
fn beam_solver(m: usize, seed: u64) -> (PathSolver, Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let b = beam::beam_on_supports(m, seed);
    let var = frictional_lcp(
        &b.rnn,
        &b.rtt,
        &b.friction,
        &b.variable_normal,
        &b.variable_tangential,
    );
    let zero = vec![0.0; m];
    let con = frictional_lcp(&b.rnn, &b.rtt, &b.friction, &b.constant_normal, &zero);
    let options = PathOptions {
        target: 1.0,
        follow: Follow::ToEnd,
        tightening: Some(Tightening {
            amount: 1.0,
            direction: var.direction.clone(),
        }),
    };
    let problem = ParametricLcp {
        m: to_mat(&var.m),
        q0: con.d.clone(),
        d: var.d.clone(),
    };
    let solver = PathSolver::new(problem, options, Settings::default()).unwrap();
    (solver, var.m, con.d, var.d)
}

/// Reference: `solution_at` at every load (whose points are verified from the original data;
/// the enumeration reference is the P-matrix test above: frictional `M` is singular). The
/// tightening must have been removed by pivots at some of the loads, so that branch of the
/// sweep is exercised.
#[test]
fn frictional_beams_agree_with_solution_at() {
    let mut removed = 0usize;
    for (m, seed) in [
        (4, 1),
        (4, 2),
        (4, 3),
        (4, 5),
        (12, 7),
        (30, 7),
        (30, 11),
        (100, 7),
    ] {
        let (solver, ..) = beam_solver(m, seed);
        let path = solver.follow();
        assert_ne!(path.status, PathStatus::NumericalFailure);
        let loads = loads_of(&path);
        let swept = solver.points_at(&path, &loads).unwrap();
        for (&p, got) in loads.iter().zip(&swept) {
            let want = solver.solution_at(&path, p).unwrap();
            same_point(&format!("m = {m}, seed {seed}, p = {p}"), got, &want).unwrap();
            let Some(pt) = got else { continue };
            removed += usize::from(pt.tightening_pivots > 0);
        }
    }
    assert!(removed > 0, "no load needed the tightening removed");
}

/// Reference: the order of the requests does not matter — the answers are those of the same
/// loads sorted, and repeated loads get the same answer.
#[test]
fn unsorted_and_repeated_loads() {
    let (solver, ..) = beam_solver(12, 3);
    let path = solver.follow();
    let mut loads = loads_of(&path);
    let sorted = solver.points_at(&path, &loads).unwrap();
    loads.reverse();
    loads.push(loads[0]);
    let reversed = solver.points_at(&path, &loads).unwrap();
    let k = sorted.len();
    for i in 0..k {
        same_point("reversed", &reversed[k - 1 - i], &sorted[i]).unwrap();
    }
    same_point("repeated", &reversed[k], &reversed[0]).unwrap();
    assert!(solver.points_at(&path, &[]).unwrap().is_empty());
}

/// Reference: `solution_at`'s own refusal — a path of a problem of another order.
#[test]
fn refuses_a_path_of_another_order() {
    let (solver, ..) = beam_solver(4, 1);
    let (other, ..) = beam_solver(5, 1);
    let path = other.follow();
    assert!(matches!(
        solver.points_at(&path, &[0.0]),
        Err(LcpError::Dimension(_))
    ));
}
