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

/// The traced path's forces are formed from the zone's four blocks (`M` is never built):
/// against `x = q_c + c·t + p·d + M z` formed independently with the dense `M`, `q_c`, `d` and
/// `t` of `ContactLcp::build` (the formulation's LCP, itself checked against the paper), at
/// every breakpoint and in the middle of every segment. The zones have coupling blocks
/// `Rnt`, `Rtn`, gaps (`q_c` carries `R·η`), constant loads and friction above 1 (`t` has
/// `max(1, f)`), and the path is traced with a tightening, so every term of `x` is there.
#[test]
fn traced_forces_from_the_blocks_are_those_of_the_dense_lcp() {
    use unilateral_contact::{pair_results, ContactLcp};
    let (mut checked, mut gathered) = (0, 0);
    for (m, seed) in [(3usize, 7u64), (5, 11), (8, 13)] {
        let mut rng = unilateral_oracle::fixtures::random::Lcg::new(seed);
        let b: Vec<f64> = (0..4 * m * m).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let friction: Vec<f64> = (0..m).map(|i| [0.3, 1.6, 0.0][i % 3]).collect();
        let gaps: Vec<f64> = (0..m)
            .map(|i| if i % 2 == 0 { 0.01 } else { 0.0 })
            .collect();
        let loads: Vec<f64> = (0..4 * m).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let zone = crate::common::definite_zone(
            m,
            |i, j| b[i * 2 * m + j],
            friction,
            gaps,
            |kind, i| loads[kind * m + i] + if kind == 0 { 2.0 } else { 0.0 },
        );
        for c in [0.0, 0.7] {
            let settings = SolveSettings {
                tightening: c,
                follow: Follow::ToEnd,
                ..Default::default()
            };
            let sol = solve(&zone, &settings).unwrap();
            let lcp = ContactLcp::build(&zone);
            let (prob, t) = (&lcp.problem, &lcp.tightening_direction);
            let n = 3 * m;
            let k = sol.path.breakpoints.len();
            let mut at: Vec<(usize, f64)> = (0..k).map(|j| (j, 0.0)).collect();
            at.extend((0..k.saturating_sub(1)).map(|j| (j, 0.5)));
            let got = sol.traced_on_segments(&at).unwrap();
            // Pairs whose `z_n` (or `z_t`) is zero at every breakpoint: the products leave
            // their columns out where at most three quarters of the pairs are active.
            for part in 0..2 {
                let active = (0..m)
                    .filter(|&i| {
                        sol.path.breakpoints.iter().any(|b| {
                            b.z.iter()
                                .any(|&(l, v)| v != 0.0 && (l / m).min(1) == part && l % m == i)
                        })
                    })
                    .count();
                gathered += usize::from(4 * active <= 3 * m);
            }
            for (&(j, s), g) in at.iter().zip(&got) {
                let (p, pairs) = g.as_ref().expect("on the path");
                // z on the segment, from the breakpoints themselves
                let mut z = vec![0.0; n];
                for &(i, v) in &sol.path.breakpoints[j].z {
                    z[i] += (1.0 - s) * v;
                }
                if s > 0.0 {
                    for &(i, v) in &sol.path.breakpoints[j + 1].z {
                        z[i] += s * v;
                    }
                }
                let x: Vec<f64> = (0..n)
                    .map(|i| {
                        let mz: f64 = (0..n).map(|l| prob.m[(i, l)] * z[l]).sum();
                        let xi = prob.q0[i] + c * t[i] + p * prob.d[i] + mz;
                        if z[i] != 0.0 {
                            0.0
                        } else {
                            xi
                        }
                    })
                    .collect();
                let want = pair_results(&x, &z, &zone.pair_names);
                let scale = want
                    .iter()
                    .flat_map(|r| [r.x_n, r.x_t, r.z_n, r.z_t])
                    .fold(1.0f64, |a, v| a.max(v.abs()));
                for (a, w) in pairs.iter().zip(&want) {
                    assert_eq!(a.state, w.state, "m = {m}, c = {c}, ({j}, {s}): {}", a.name);
                    for (u, v) in [
                        (a.x_n, w.x_n),
                        (a.x_t, w.x_t),
                        (a.z_n, w.z_n),
                        (a.z_t, w.z_t),
                    ] {
                        assert!(
                            (u - v).abs() <= 1e-12 * scale,
                            "m = {m}, c = {c}, ({j}, {s}), {}: {u} vs {v}",
                            a.name
                        );
                    }
                }
                checked += 1;
            }
            // The LCP in the user's units, formed on request, is the zone's.
            assert_eq!(sol.lcp().problem.m, lcp.problem.m);
            assert_eq!(sol.lcp().problem.q0, lcp.problem.q0);
            assert_eq!(sol.label(unilateral_lcp::Var::Z(m + 1)), "z_t2+");
        }
    }
    assert!(checked > 30, "{checked} points");
    assert!(gathered > 0, "no path with few active pairs");
}

/// The traced values at many points are formed in tasks of a fixed number of columns on the
/// thread pool: asked all at once (several tasks, a remainder), in pairs, or in a different
/// order, every point's values are the same, bit for bit, and each is that of its own point
/// (the columns of the tasks put back in their places).
#[test]
fn traced_values_do_not_depend_on_the_points_asked_with_them() {
    let zone = beam_on_supports(120, 5);
    let settings = SolveSettings {
        follow: Follow::ToEnd,
        tightening: 1.0,
        ..Default::default()
    };
    let sol = solve(&zone, &settings).unwrap();
    let segments = sol.steps.len();
    assert!(segments > 70, "a path of {segments} steps: several tasks");
    let points: Vec<(usize, f64)> = (0..segments)
        .map(|k| (k, [0.0, 0.25, 0.5][k % 3]))
        .collect();
    let bits = |r: &unilateral_contact::PairResult| [r.x_n, r.x_t, r.z_n, r.z_t].map(f64::to_bits);
    let all = sol.traced_on_segments(&points).unwrap();
    assert_eq!(all.len(), points.len());
    // unnamed: the same values and states, the names left empty
    let unnamed = sol.traced_on_segments_unnamed(&points).unwrap();
    for (a, u) in all.iter().zip(&unnamed) {
        let (Some((p, a)), Some((q, u))) = (a, u) else {
            assert!(a.is_none() && u.is_none());
            continue;
        };
        assert_eq!(p.to_bits(), q.to_bits());
        for ((x, y), name) in a.iter().zip(u).zip(&zone.pair_names) {
            assert_eq!((bits(x), x.state), (bits(y), y.state));
            assert_eq!((&x.name, y.name.as_str()), (name, ""));
        }
    }
    let reversed: Vec<(usize, f64)> = points.iter().rev().copied().collect();
    let back = sol.traced_on_segments(&reversed).unwrap();
    for (i, pair) in points.chunks(2).enumerate() {
        let two = sol.traced_on_segments(pair).unwrap();
        for (j, got) in two.iter().enumerate() {
            let k = 2 * i + j;
            let (want, rev) = (&all[k], &back[points.len() - 1 - k]);
            match (got, want, rev) {
                (Some((p, g)), Some((q, w)), Some((r, v))) => {
                    assert_eq!((p.to_bits(), q.to_bits()), (q.to_bits(), r.to_bits()));
                    for ((a, b), c) in g.iter().zip(w).zip(v) {
                        assert_eq!(bits(a), bits(b), "point {k}, pair {}", a.name);
                        assert_eq!(bits(a), bits(c), "point {k}, pair {}", a.name);
                        assert_eq!(a.state, b.state);
                    }
                }
                (None, None, None) => {}
                other => panic!("point {k}: {other:?}"),
            }
        }
    }
}
