//! Larger contact zones: generated beams on many frictional supports. No closed form here; the
//! checks are the ones a wrong pivot breaks: every reported solution verifies from the data,
//! every breakpoint of the traced path is a solution at its load, and a mechanism is only
//! reported where the standard method (with its fallbacks) finds no solution just beyond it —
//! a too tight tie test once ended these paths in false mechanisms.

use crate::beam_zone::beam_on_supports;
use unilateral_contact::{solve, ContactLcp, Follow, Outcome, SolveSettings};
use unilateral_lcp::{solve_lcp, Lcp, LcpStatus, Settings};

fn lcp_at(lcp: &ContactLcp, p: f64) -> Lcp {
    Lcp {
        m: lcp.problem.m.clone(),
        q: lcp
            .problem
            .q0
            .iter()
            .zip(&lcp.problem.d)
            .map(|(q, d)| q + p * d)
            .collect(),
    }
}

#[test]
fn paths_to_the_end_verify_and_never_end_in_a_false_mechanism() {
    for (m, seed) in [
        (20, 1),
        (40, 2),
        (60, 3),
        (100, 7),
        (100, 11),
        (150, 5),
        (400, 7),
    ] {
        let zone = beam_on_supports(m, seed);
        let sol = solve(
            &zone,
            &SolveSettings {
                follow: Follow::ToEnd,
                ..Default::default()
            },
        )
        .unwrap();
        let r = sol.residual.expect("a solution at the target");
        assert!(r.max() <= 1e-10, "m = {m}, seed {seed}: residual {r:?}");
        assert!(
            sol.steps.len() >= m / 2,
            "a good share of pairs change state"
        );
        if let Outcome::Mechanism { p_limit, .. } = sol.outcome {
            let beyond =
                solve_lcp(&lcp_at(sol.lcp(), p_limit * 1.001), &Settings::default()).unwrap();
            assert_ne!(
                beyond.status,
                LcpStatus::Solved,
                "m = {m}, seed {seed}: mechanism at {p_limit} but the LCP is solvable beyond it"
            );
        }
        // Every breakpoint of the traced path is a solution at its load.
        for step in sol.steps.iter().step_by(7) {
            let (pairs, res) = sol
                .at(step.p)
                .expect("the engine answers")
                .expect("breakpoints lie on the path");
            assert_eq!(pairs.len(), m);
            assert!(
                res.max() <= 1e-9,
                "m = {m}, seed {seed}, p = {}: {res:?}",
                step.p
            );
        }
    }
}
