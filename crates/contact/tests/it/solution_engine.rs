//! The solution keeps the engine of its solve: it answers for any load of the path and shows the
//! tableaux; the solve's settings are checked by the engine, in the words they always had.

use unilateral_contact::{solve, ContactError, Follow, Outcome, SolveSettings};
use unilateral_lcp::Settings;

use crate::common::assert_matches_enumeration;

/// Reference: exhaustive enumeration of the zone's `3m` LCP at each load (`unilateral-oracle`).
/// A zone of two pressed pairs with friction, pushed sideways: `at(p)` at every event load, in
/// between and on the ray beyond the last event agrees with one enumerated solution; the
/// tableaux are the initial one, one per step and the final one of the ray.
#[test]
fn the_kept_engine_answers_every_load_as_enumeration() {
    let b = [3, 1, 0, 1, 1, 2, 1, 0, 0, 1, 2, 1, 1, 0, 1, 3];
    let loads = [4, 6, 0, 0, 0, 0, 3, 5];
    let zone = crate::common::definite_zone(
        2,
        |i, j| b[i * 4 + j] as f64 / 4.0,
        vec![0.5, 0.3],
        vec![0.0, 0.0],
        |kind, i| loads[kind * 2 + i] as f64 / 8.0,
    );
    let settings = SolveSettings {
        follow: Follow::ToEnd,
        ..SolveSettings::default()
    };
    let sol = solve(&zone, &settings).unwrap();
    assert!(
        matches!(sol.outcome, Outcome::Ray { .. }),
        "{:?}",
        sol.outcome
    );
    assert!(
        sol.steps.len() >= 2,
        "the zone must have events to test between"
    );
    let last = sol.steps.last().unwrap().p;
    let mut ps: Vec<f64> = sol.steps.iter().map(|s| s.p).collect();
    ps.extend(sol.steps.windows(2).map(|w| 0.5 * (w[0].p + w[1].p)));
    ps.extend([0.5 * sol.steps[0].p, 1.5 * last + 1.0]);
    for p in ps {
        let (pairs, residual) = sol.at(p).unwrap().expect("on the path");
        assert!(residual.max() < 1e-12, "residual at p = {p}");
        assert_matches_enumeration(&zone, p, &pairs);
    }
    // A clone shares the engine and answers alike.
    let copy = sol.clone();
    assert_eq!(copy.at(last).unwrap(), sol.at(last).unwrap());
    assert_eq!(sol.tableaux(None).unwrap().len(), sol.steps.len() + 2);
}

/// Reference: the messages of the solve settings as the program printed them before the engine
/// checked them (`invalid solve setting: …`), now typed as the engine's settings errors.
#[test]
fn solve_settings_are_checked_by_the_engine_in_their_words() {
    let zone = crate::common::definite_zone(
        1,
        |i, j| if i == j { 1.0 } else { 0.0 },
        vec![0.5],
        vec![0.0],
        |kind, _| if kind == 2 { 1.0 } else { 0.0 },
    );
    let cases = [
        (
            SolveSettings {
                tightening: -1.0,
                ..SolveSettings::default()
            },
            "tightening",
            "invalid solve setting: tightening must be a finite number ≥ 0, got -1",
        ),
        (
            SolveSettings {
                target: 0.0,
                ..SolveSettings::default()
            },
            "target",
            "invalid solve setting: target must be a finite number > 0 (and not below 2.2e-308), got 0e0",
        ),
        (
            SolveSettings {
                engine: Settings {
                    pivot_tolerance: Some(f64::NAN),
                    ..Settings::default()
                },
                ..SolveSettings::default()
            },
            "pivot_tolerance",
            "invalid solve setting: pivot_tolerance must lie in (0, 0.01), got NaN",
        ),
    ];
    for (settings, key, text) in cases {
        let e = solve(&zone, &settings).unwrap_err();
        assert_eq!(e.to_string(), text);
        match e {
            ContactError::Settings(s) => assert_eq!(s.key(), key),
            other => panic!("not a settings error: {other:?}"),
        }
        assert_eq!(settings.validate().unwrap_err().to_string(), text);
    }
}
