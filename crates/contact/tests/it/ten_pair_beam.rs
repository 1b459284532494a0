//! The standard LCP of a frictional beam on ten supports: pairs of exactly opposite columns
//! (`z_t+`, `z_t-`) and a singular `M`, on which a widely used implementation of Lemke's method
//! ends on a false ray. Lemke's method itself (covering vector of ones) must solve every one of
//! these problems that has a solution, verified; where the load path shows that the beam has
//! become a mechanism below the load, Lemke must end on a ray (two methods that must agree).

use crate::beam_zone::beam_on_supports;
use unilateral_contact::{solve, ContactLcp, Follow, Outcome, SolveSettings};
use unilateral_lcp::{solve_lcp, Lcp, LcpStatus, Settings, Strategy};

#[test]
fn ten_pair_frictional_beams_are_solved_by_lemke_itself() {
    let (mut solved_by_lemke, mut rays) = (0, 0);
    for seed in 0..40u64 {
        let zone = beam_on_supports(10, seed);
        let lcp = ContactLcp::build(&zone);
        let path = solve(
            &zone,
            &SolveSettings {
                follow: Follow::ToEnd,
                ..Default::default()
            },
        )
        .unwrap();
        let p_lim = match path.outcome {
            Outcome::Mechanism { p_limit, .. } => p_limit,
            _ => f64::INFINITY,
        };
        for p in [0.5, 1.0, 2.0] {
            let q: Vec<f64> = lcp
                .problem
                .q0
                .iter()
                .zip(&lcp.problem.d)
                .map(|(q, d)| q + p * d)
                .collect();
            let problem = Lcp {
                m: lcp.problem.m.clone(),
                q,
            };
            for order in [None, Some(lcp.lexicographic_order.clone())] {
                let settings = Settings {
                    lexicographic_order: order,
                    ..Settings::default()
                };
                let sol = solve_lcp(&problem, &settings).unwrap();
                if p > p_lim * 1.001 {
                    assert_eq!(
                        sol.status,
                        LcpStatus::Ray,
                        "seed {seed}: beyond p_lim = {p_lim}"
                    );
                    rays += 1;
                    continue;
                }
                assert_eq!(
                    sol.status,
                    LcpStatus::Solved,
                    "seed {seed}, p = {p}: {:?}",
                    sol.attempts
                );
                let pt = sol.point.as_ref().unwrap();
                assert!(pt.residual.max() <= 1e-10);
                assert!(
                    matches!(sol.strategy, Strategy::Lemke { covering: "ones" }),
                    "seed {seed}, p = {p}: needed {:?} ({:?})",
                    sol.strategy,
                    sol.attempts
                );
                solved_by_lemke += 1;
            }
        }
    }
    assert_eq!(solved_by_lemke + rays, 240);
    assert!(
        solved_by_lemke >= 200,
        "only {solved_by_lemke} solvable cases"
    );
}
