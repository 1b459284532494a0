#![allow(clippy::needless_range_loop)]
//! Example 1 in structural form (examples/example1-beam.toml): the condensed matrices are the
//! paper's, the path reaches the ray at p = 10.6667, and at p = 1 the left support lifts off.

use std::path::{Path, PathBuf};

use unilateral_analysis::{analyze, Outcome, PairState};
use unilateral_contact::EventKind;
use unilateral_io::{read_problem, Problem, StructuralProblem};
use unilateral_oracle::fixtures::example1 as ex1;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

fn read(name: &str) -> StructuralProblem {
    match read_problem(&example(name)).unwrap() {
        Problem::Structural(p) => p,
        Problem::ContactZone(_) => panic!("{name} is not a structural model"),
    }
}

#[test]
fn example1_structural_reproduces_the_paper() {
    let p = read("example1-beam.toml");
    assert_eq!(
        p.model.names().pairs,
        ["support.1", "support.2", "support.3"]
    );
    let a = analyze(&p.model, &p.settings).unwrap();

    // The condensed matrices are the paper's.
    let (rnn, rtt) = (ex1::RNN, ex1::RTT);
    for i in 0..3 {
        for j in 0..3 {
            assert!((a.zone.rnn[(i, j)] - rnn[i][j]).abs() < 1e-12);
            assert!((a.zone.rtt[(i, j)] - rtt[i][j]).abs() < 1e-12);
            assert!(a.zone.rnt[(i, j)].abs() < 1e-12);
            assert!(a.zone.rtn[(i, j)].abs() < 1e-12);
        }
    }
    let rv = ex1::RV_N;
    for i in 0..3 {
        assert!((a.zone.variable.normal[i] - rv[i]).abs() < 1e-12);
        assert!(a.zone.variable.tangential[i].abs() < 1e-12);
        assert_eq!(a.zone.constant.normal[i], 0.0);
    }

    // The path: pair 1 opens at p = 1/0.09375, then a ray.
    let Outcome::Ray { p_from } = a.solution.outcome else {
        panic!("expected a ray, got {:?}", a.solution.outcome)
    };
    assert!((p_from - ex1::FIRST_EVENT_P).abs() < 1e-9, "{p_from}");
    assert_eq!(a.solution.steps[0].events[0].kind, EventKind::Opens);
    assert_eq!(a.solution.steps[0].events[0].name, "support.1");

    // At p = 1: the left support lifts off by P L³/(16 EI) = 0.5, the others carry 0.5 each.
    assert_eq!(a.p(), Some(1.0));
    let pairs = &a.solution.pairs;
    assert_eq!(pairs[0].state, PairState::Open);
    assert!((pairs[0].z_n - 0.5).abs() < 1e-12);
    assert!((pairs[1].x_n - 0.5).abs() < 1e-12);
    assert!((pairs[2].x_n - 0.5).abs() < 1e-12);
    for pr in pairs {
        assert!(pr.x_t.abs() < 1e-12);
    }
    let r = a.results.as_ref().unwrap();
    let node_a = p.model.names().node_id("A").unwrap();
    assert!((r.displacements[node_a.0][1] - 0.5).abs() < 1e-9);
    assert!(r.equilibrium.relative() < 1e-10);

    // Extremes: the uplift at A, the largest moment under the load (0.5·1 = 0.5... with the
    // left span unloaded: M = R_C·1 = 0.5 at P).
    let ex = a.extremes().unwrap();
    assert_eq!(ex.displacement.as_ref().unwrap().name, "A");
    let m = ex.moment.unwrap();
    assert!((m.value.abs() - 0.5).abs() < 1e-9, "{m:?}");

    // Results elsewhere on the path: before the event (p = 5) every support is pressed? With
    // c removed, the solution at any p ≥ 0 of this homogeneous problem is p times the p = 1
    // solution.
    let (pairs5, r5) = a.results_at(5.0).unwrap();
    assert!((pairs5[0].z_n - 2.5).abs() < 1e-9);
    assert!((r5.displacements[node_a.0][1] - 2.5).abs() < 1e-9);
}
