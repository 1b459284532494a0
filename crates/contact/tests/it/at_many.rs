//! `ContactSolution::at_many`: the answers of `ContactSolution::at` at many loads, in one walk.

use crate::beam_zone::beam_on_supports;
use unilateral_contact::{solve, Follow, SolveSettings};

/// Reference: `ContactSolution::at` at each load (the engine's `solution_at`, whose equality
/// with enumeration and the sweep is tested in `unilateral-lcp`): the same states and the same
/// forces and displacements, relative to the largest of them; `None` off the path.
#[test]
fn at_many_answers_as_at() {
    for (m, seed) in [(10, 1), (40, 2), (60, 3)] {
        let zone = beam_on_supports(m, seed);
        let settings = SolveSettings {
            follow: Follow::ToEnd,
            ..Default::default()
        };
        let sol = solve(&zone, &settings).unwrap();
        let mut loads = vec![0.0, -1.0];
        loads.extend(sol.steps.iter().map(|s| s.p));
        loads.extend(sol.steps.windows(2).map(|w| 0.5 * (w[0].p + w[1].p)));
        let many = sol.at_many(&loads).unwrap();
        assert_eq!(many.len(), loads.len());
        let mut compared = 0;
        for (&p, got) in loads.iter().zip(&many) {
            let want = sol.at(p).unwrap();
            match (got, &want) {
                (None, None) => {}
                (Some((g, _)), Some((w, _))) => {
                    let scale = w
                        .iter()
                        .flat_map(|r| [r.x_n, r.x_t, r.z_n, r.z_t])
                        .fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
                    for (a, b) in g.iter().zip(w) {
                        assert_eq!(a.state, b.state, "m = {m}, p = {p}, pair {}", a.name);
                        for (u, v) in [
                            (a.x_n, b.x_n),
                            (a.x_t, b.x_t),
                            (a.z_n, b.z_n),
                            (a.z_t, b.z_t),
                        ] {
                            assert!(
                                (u - v).abs() <= 1e-9 * scale,
                                "m = {m}, p = {p}: {u} vs {v}"
                            );
                        }
                    }
                    compared += 1;
                }
                _ => panic!(
                    "m = {m}, p = {p}: at_many {:?} vs at {:?}",
                    got.is_some(),
                    want.is_some()
                ),
            }
        }
        assert!(compared > sol.steps.len(), "m = {m}: {compared} points");
        assert!(many[1].is_none(), "a negative load is off the path");
    }
}

/// The breakpoints of a path traced without tightening are its solutions at the steps' loads:
/// `traced_on_segments` at `(k, 0)` (the path's own `z`, `x` formed by one product) against
/// `ContactSolution::at` at the load of step `k` (the reference: the engine's `solution_at`,
/// a fresh basis at that load) — the same states, the same values to round-off of the largest,
/// and an open pair's normal force exactly zero (complementary to its opening).
#[test]
fn breakpoints_without_tightening_are_the_solutions_at_the_steps() {
    for (m, seed) in [(10, 1), (40, 2)] {
        let zone = beam_on_supports(m, seed);
        let settings = SolveSettings {
            follow: Follow::ToEnd,
            tightening: 0.0,
            ..Default::default()
        };
        let sol = solve(&zone, &settings).unwrap();
        assert!(sol.steps.len() > 5, "m = {m}: a path with events");
        let points: Vec<(usize, f64)> = sol.steps.iter().map(|s| (s.index, 0.0)).collect();
        let traced = sol.traced_on_segments(&points).unwrap();
        let mut open = 0;
        for (st, got) in sol.steps.iter().zip(&traced) {
            let (p, g) = got.as_ref().expect("every step has its breakpoint");
            assert_eq!(*p, st.p);
            let (w, _) = sol.at(st.p).unwrap().expect("on the path");
            let scale = w
                .iter()
                .flat_map(|r| [r.x_n, r.x_t, r.z_n, r.z_t])
                .fold(f64::MIN_POSITIVE, |a, b| a.max(b.abs()));
            for (a, b) in g.iter().zip(&w) {
                assert_eq!(
                    a.state, b.state,
                    "m = {m}, step {}, pair {}",
                    st.index, a.name
                );
                for (u, v) in [
                    (a.x_n, b.x_n),
                    (a.x_t, b.x_t),
                    (a.z_n, b.z_n),
                    (a.z_t, b.z_t),
                ] {
                    assert!((u - v).abs() <= 1e-9 * scale, "m = {m}: {u} vs {v}");
                }
                if a.z_n > 0.0 {
                    assert_eq!(a.x_n, 0.0, "m = {m}, step {}: open {}", st.index, a.name);
                    open += 1;
                }
            }
        }
        assert!(open > 0, "m = {m}: some pair opens on the path");
    }
}
