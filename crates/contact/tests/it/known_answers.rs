//! Contact zones with known answers, each checked against an independent computation:
//! closed forms, exhaustive enumeration of the `3m` LCP in exact arithmetic (the oracle crate),
//! the oracle's exact parametric path, and — for frictionless cases — a quadratic program
//! solved by projected Gauss–Seidel.

use faer::Mat;
use unilateral_contact::{
    solve, ContactLcp, ContactZone, EventKind, Follow, Outcome, PairState, SolveSettings,
};
use unilateral_oracle as oracle;

use crate::common::{
    assert_matches_enumeration, enumerated, example1_paper_settings, example1_zone, rows,
};

/// A bar of `m` nodes on a rigid base, clamped at its far end, pressed by a constant force `N` at
/// every node and pulled by `F·p` at the free end (the discrete form of the paper's Example 2).
/// Axial springs of stiffness `k` join the nodes; node 1 is joined to the clamp.
fn pulled_bar(m: usize, k: f64, n: f64, f: f64, force: f64) -> ContactZone {
    let rtt = Mat::<f64>::from_fn(m, m, |i, j| {
        if i == j {
            if i == m - 1 {
                k
            } else {
                2.0 * k
            }
        } else if i.abs_diff(j) == 1 {
            -k
        } else {
            0.0
        }
    });
    let mut zone = ContactZone::new(Mat::zeros(m, m), rtt);
    zone.friction = vec![f; m];
    zone.constant.normal = vec![n; m];
    zone.variable.tangential = (0..m)
        .map(|i| if i == m - 1 { -force } else { 0.0 })
        .collect();
    zone
}

/// With a physical pressing load, nodes start to slip one by one from the free end, the j-th at
/// `p_j = j·f·N/F` (the load not carried by the friction of the slipping nodes goes through one
/// spring into the first stuck node); when all slip the clamp takes the rest: a ray.
#[test]
fn pressed_bar_slips_node_by_node_from_the_free_end() {
    let (m, k, n, f, force) = (4, 100.0, 10.0, 0.25, 1.0);
    let zone = pulled_bar(m, k, n, f, force);
    let settings = SolveSettings {
        follow: Follow::ToEnd,
        target: 12.0,
        ..Default::default()
    };
    let sol = solve(&zone, &settings).unwrap();
    assert_eq!(sol.steps.len(), m, "{:?}", sol.steps);
    for (j, step) in sol.steps.iter().enumerate() {
        let expect = (j + 1) as f64 * f * n / force;
        assert!(
            (step.p - expect).abs() < 1e-10 * expect,
            "step {j}: p = {}",
            step.p
        );
        // The independent evaluation of the step's load (its basis factorised anew) gives
        // the closed form too.
        let fresh = sol.event_load(j + 1).expect("the step's basis");
        assert!((fresh - expect).abs() < 1e-12 * expect, "step {j}: {fresh}");
        assert_eq!(step.events.len(), 1);
        assert_eq!(step.events[0].pair, m - 1 - j, "slips from the free end");
        assert_eq!(step.events[0].kind, EventKind::StartsSlippingPlus);
    }
    assert!(matches!(sol.outcome, Outcome::Ray { .. }));
    assert_eq!(sol.event_load(0), None, "steps count from 1");
    assert_eq!(sol.event_load(m + 1), None, "no step beyond the path");
    // At p* = 12 > 4·fN/F every node slips; the clamp spring carries F·p − m·f·N.
    let p = sol.p.unwrap();
    assert_eq!(p, 12.0);
    for pr in &sol.pairs {
        assert_eq!(pr.state, PairState::SlipPlus);
        assert!(
            (pr.x_t + f * n).abs() < 1e-10,
            "friction at its limit against the slip"
        );
        assert!((pr.x_n - n).abs() < 1e-12);
    }
    let clamp_force = force * p - m as f64 * f * n;
    assert!((sol.pairs[0].z_t - clamp_force / k).abs() < 1e-10);
    assert_matches_enumeration(&zone, p, &sol.pairs);
    // Between events: two nodes slip at p = 2.5·fN/F.
    let (pairs, res) = sol.at(2.5 * f * n / force).unwrap().unwrap();
    assert!(res.max() < 1e-12);
    let slipping: Vec<_> = pairs.iter().map(|p| p.state).collect();
    assert_eq!(
        slipping,
        [
            PairState::Stick,
            PairState::Stick,
            PairState::SlipPlus,
            PairState::SlipPlus
        ]
    );
    assert_matches_enumeration(&zone, 2.5 * f * n / force, &pairs);
}

/// Projected Gauss–Seidel for `min ½zᵀAz + bᵀz, z ≥ 0` (A symmetric positive definite): the
/// frictionless contact problem as a quadratic program, an independent method.
fn qp_pgs(a: &Mat<f64>, b: &[f64]) -> Vec<f64> {
    let n = b.len();
    let mut z = vec![0.0; n];
    for _ in 0..20000 {
        for i in 0..n {
            let r: f64 = b[i]
                + (0..n)
                    .filter(|&j| j != i)
                    .map(|j| a[(i, j)] * z[j])
                    .sum::<f64>();
            z[i] = (-r / a[(i, i)]).max(0.0);
        }
    }
    z
}

/// Two supports with initial gaps under a growing pressing load, frictionless: the start is not
/// feasible (`q(0) = −Rnn·η`), so the scheme at `p = 0` comes from a standard Lemke solve (both
/// pairs open by their gaps); then the pairs close one after the other.
#[test]
fn gaps_close_one_after_the_other() {
    let rnn = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { 2.0 } else { -1.0 });
    let mut zone = ContactZone::new(rnn.clone(), Mat::<f64>::identity(2, 2));
    zone.gap = vec![0.1, 0.3];
    zone.variable.normal = vec![1.0, 1.0];
    let sol = solve(
        &zone,
        &SolveSettings {
            follow: Follow::ToEnd,
            target: 2.0,
            ..Default::default()
        },
    )
    .unwrap();
    let closes: Vec<(usize, f64)> = sol
        .steps
        .iter()
        .flat_map(|s| s.events.iter().map(move |e| (e, s.p)))
        .filter(|(e, _)| e.kind == EventKind::Closes)
        .map(|(e, p)| (e.pair, p))
        .collect();
    // Both open: z = η − p·Rnn⁻¹·Rv = η − p·(1, 1) → pair 1 closes at p = 0.1.
    assert_eq!(closes[0].0, 0);
    assert!((closes[0].1 - 0.1).abs() < 1e-12);
    // Then pair 1 closed, pair 2 open: x_1 = 0 ... z_2 = 0.3 − 2p + (stuff): from the LCP with
    // z_1 = 0: x_2 = 2(z_2 − 0.3) − (0 − 0.1) + p = 0 → z_2 = 0.3 − (p + 0.1)/2 → p = 0.5.
    assert_eq!(closes[1].0, 1);
    assert!((closes[1].1 - 0.5).abs() < 1e-12);
    assert!(matches!(sol.outcome, Outcome::Ray { .. }));
    // The same problem as a QP at p = 2: min ½zᵀRz + (p·Rv − R·η)ᵀz over z ≥ 0.
    let p = 2.0;
    let b: Vec<f64> = (0..2)
        .map(|i| {
            p * zone.variable.normal[i] - (0..2).map(|j| rnn[(i, j)] * zone.gap[j]).sum::<f64>()
        })
        .collect();
    let z_qp = qp_pgs(&rnn, &b);
    for (pair, zq) in sol.pairs.iter().zip(&z_qp) {
        assert!((pair.z_n - zq).abs() < 1e-9);
        assert_eq!(pair.state, PairState::Stick);
    }
    // x = Rnn(z − η) + p·Rv: both carry p·1 + ... compare with the closed form at z = 0.
    assert!((sol.pairs[0].x_n - (2.0 - 0.2 + 0.3)).abs() < 1e-12);
    assert_matches_enumeration(&zone, p, &sol.pairs);
}

/// A block on two supports pressed by `N` each, pushed sideways by `p·H` shared 60/40: support 1
/// slips at `p = f·N/(0.6·H)`, support 2 when the rest reaches `f·N`, and then nothing holds the
/// block horizontally: a mechanism at `p_lim = 2·f·N/H`.
#[test]
fn sliding_block_becomes_a_mechanism() {
    let (n, f, h) = (10.0, 0.5, 4.0);
    let rtt = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { 3.0 } else { -3.0 });
    let rnn = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { 5.0 } else { 1.0 });
    let mut zone = ContactZone::new(rnn, rtt);
    zone.friction = vec![f; 2];
    zone.constant.normal = vec![n; 2];
    zone.variable.tangential = vec![-0.6 * h, -0.4 * h];
    let sol = solve(
        &zone,
        &SolveSettings {
            follow: Follow::ToEnd,
            target: 10.0,
            ..Default::default()
        },
    )
    .unwrap();
    let p_lim = 2.0 * f * n / h;
    match &sol.outcome {
        Outcome::Mechanism { p_limit, mode } => {
            assert!((p_limit - p_lim).abs() < 1e-12, "p_lim = {p_limit}");
            // Both supports slide together, nothing opens.
            assert!((mode[0].1 - mode[1].1).abs() < 1e-12 && mode[0].1.abs() > 0.1);
            assert!(mode[0].0.abs() < 1e-12 && mode[1].0.abs() < 1e-12);
        }
        other => panic!("expected a mechanism, got {other:?}"),
    }
    assert!((sol.steps[0].p - f * n / (0.6 * h)).abs() < 1e-12);
    assert_eq!(sol.steps[0].events[0].pair, 0);
    // The reported solution is at p_lim, both at the friction limit.
    assert_eq!(sol.p, Some(p_lim));
    for pr in &sol.pairs {
        assert!((pr.x_t.abs() - f * n).abs() < 1e-10);
    }
    // Independent: a solution exists just below p_lim and none just above.
    assert!(!enumerated(&zone, p_lim * 0.999).is_empty());
    assert!(enumerated(&zone, p_lim * 1.001).is_empty());
}

/// Coupled normal and tangential stiffness with high friction (non-symmetric M, no uniqueness):
/// after two pairs reach the friction limit the load parameter decreases while the scheme keeps
/// changing — a turning point of the load path. The path is compared step by step with the
/// oracle's exact parametric path, and every breakpoint is checked by enumeration.
#[test]
fn path_turns_back() {
    let r = [
        [1.125, -0.5, 0.5, 0.1875],
        [-0.5, 2.3125, 0.5625, 0.0],
        [0.5, 0.5625, 0.625, -0.0625],
        [0.1875, 0.0, -0.0625, 0.375],
    ];
    let blk = |i0: usize, j0: usize| Mat::<f64>::from_fn(2, 2, |i, j| r[i0 + i][j0 + j]);
    let mut zone = ContactZone::new(blk(0, 0), blk(2, 2));
    zone.rnt = blk(0, 2);
    zone.rtn = blk(2, 0);
    zone.friction = vec![1.25, 1.75];
    zone.constant.normal = vec![1.0, 0.5];
    zone.variable.normal = vec![-0.25, 0.0];
    zone.variable.tangential = vec![0.75, 0.25];
    let sol = solve(
        &zone,
        &SolveSettings {
            follow: Follow::ToEnd,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(sol.steps.iter().any(|s| s.turning), "{:?}", sol.steps);
    assert!(sol.notes.iter().any(|n| n.contains("turning point")));
    let lcp = ContactLcp::build(&zone);
    let exact = oracle::parametric_path(
        &rows(&lcp.problem.m),
        &lcp.problem.q0,
        &lcp.problem.d,
        None,
        Some(&lcp.lexicographic_order),
    );
    assert_eq!(exact.steps.len(), sol.steps.len());
    for (mine, theirs) in sol.steps.iter().zip(&exact.steps) {
        assert!(
            (mine.p - theirs.p_f64()).abs() < 1e-10,
            "{} vs {}",
            mine.p,
            theirs.p_f64()
        );
        assert_eq!(mine.turning, theirs.p_decreased);
    }
    for step in &sol.steps {
        assert!(
            !enumerated(&zone, step.p).is_empty(),
            "no solution at breakpoint p = {}",
            step.p
        );
    }
}

/// The paper's Example 1 traced with its tightening c = 1: the first event (pair 1 opens) at
/// p = 32/3 (the paper's Table 2), from the traced path and from the independent evaluation of
/// the step's basis with the tightening in it.
#[test]
fn example1_event_load_afresh_is_the_papers() {
    let zone = crate::common::example1_zone();
    let sol = solve(&zone, &crate::common::example1_paper_settings()).unwrap();
    let expect = 32.0 / 3.0;
    assert!((sol.steps[0].p - expect).abs() < 1e-12 * expect);
    let fresh = sol.event_load(1).expect("the first step's basis");
    assert!((fresh - expect).abs() < 1e-12 * expect, "{fresh}");
}

/// Without a constant load the problem is homogeneous, and the structure's own path is said
/// before the path traced with the paper's tightening: Example 1 traced with c = 1 has an
/// event at p = 32/3 (a load that depends on c), the structure none. The claim is checked
/// independently: the reported state at p = 1, scaled by p, is a solution of the zone without
/// the tightening at loads below, at and far beyond that event, by exhaustive enumeration of
/// the LCP in exact arithmetic; and the path traced with c = 0 gives the same states with no
/// event.
#[test]
fn a_homogeneous_zone_traced_with_the_tightening_says_its_physical_path_first() {
    let zone = example1_zone();
    let sol = solve(&zone, &example1_paper_settings()).unwrap();
    assert!(sol.homogeneous());
    // the tightened path's event: support 1 lifts off at p = 32/3 with c = 1
    assert!(sol
        .steps
        .iter()
        .any(|s| (s.p - 32.0 / 3.0).abs() < 1e-12 * s.p));
    let reading = sol.physical_reading().expect("traced with c > 0");
    assert!(
        reading.contains("the solution at p = 1 below, every force and displacement scaled by p, is a solution at every p > 0")
            && reading.contains("no event and no limit")
            && !reading.contains("not be unique"),
        "{reading}"
    );
    assert_eq!(sol.p, Some(1.0));
    let states: Vec<PairState> = sol.pairs.iter().map(|r| r.state).collect();
    // by hand (formulation.md §5): support 1 lifts off, 2 and 3 carry the load and stick
    assert_eq!(
        states,
        [PairState::Open, PairState::Stick, PairState::Stick]
    );
    for p in [0.25, 1.0, 10.0, 40.0, 1e6] {
        let scaled: Vec<_> = sol
            .pairs
            .iter()
            .map(|r| unilateral_contact::PairResult {
                x_n: p * r.x_n,
                x_t: p * r.x_t,
                z_n: p * r.z_n,
                z_t: p * r.z_t,
                ..r.clone()
            })
            .collect();
        assert_matches_enumeration(&zone, p, &scaled);
        let physical = solve(
            &zone,
            &SolveSettings {
                tightening: 0.0,
                target: p,
                follow: Follow::ToEnd,
                ..SolveSettings::default()
            },
        )
        .unwrap();
        assert!(physical.physical_reading().is_none(), "c = 0: its own path");
        assert!(
            physical.steps.iter().all(|s| s.settling),
            "no event on the structure's own path: {:?}",
            physical.steps
        );
        let own: Vec<PairState> = physical.pairs.iter().map(|r| r.state).collect();
        assert_eq!(own, states, "p = {p}");
        for (a, b) in physical.pairs.iter().zip(&scaled) {
            assert!((a.x_n - b.x_n).abs() <= 1e-12 * p, "p = {p}: {a:?} {b:?}");
            assert!((a.z_n - b.z_n).abs() <= 1e-12 * p, "p = {p}: {a:?} {b:?}");
        }
    }
    // With a constant load the structure's own path is another trace (not made): said so.
    let mut pressed = zone.clone();
    pressed.constant.normal = vec![0.1; 3];
    let sol = solve(&pressed, &example1_paper_settings()).unwrap();
    assert!(!sol.homogeneous());
    let reading = sol.physical_reading().expect("traced with c > 0");
    assert!(reading.contains("traced with tightening 0"), "{reading}");
    // A rigid block on two pairs pushed sideways and lifted by the same load (a reviewer's
    // zone): the tightening c presses it and its friction holds it up to p = 2, a load of c;
    // without c no state exists at any p > 0 (by hand: `Rnn` and `Rtt` are singular along the
    // block's rigid motion, so the pairs' forces together balance the load — the push 2p
    // sideways needs 0.5·(x_n1 + x_n2) ≥ 2p, while x_n1 + x_n2 is at most the normal load's
    // 2p). No state free of c is reported, and the reading claims none.
    let mut block = ContactZone::new(
        Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { -1.0 }),
        Mat::from_fn(2, 2, |i, j| if i == j { 1.0 } else { -1.0 }),
    );
    block.friction = vec![0.5; 2];
    block.variable.normal = vec![1.0; 2];
    block.variable.tangential = vec![1.0; 2];
    let sol = solve(&block, &example1_paper_settings()).unwrap();
    assert!(sol.homogeneous());
    assert!(
        matches!(sol.outcome, Outcome::Mechanism { .. }),
        "{:?}",
        sol.outcome
    );
    assert_eq!(sol.p, None, "{:?}", sol.notes);
    let reading = sol.physical_reading().expect("traced with c > 0");
    assert!(reading.contains("reported none free of c"), "{reading}");
    assert!(!reading.contains("is a solution at every"), "{reading}");
    // An initial gap also makes the problem inhomogeneous.
    let mut gapped = example1_zone();
    gapped.gap = vec![0.0, 1e-3, 0.0];
    let sol = solve(&gapped, &example1_paper_settings()).unwrap();
    assert!(!sol.homogeneous());
}

/// A pressed pair on a soft tangential spring beside a frictionless pair pushed sideways by
/// `1e12·p`, uncoupled (the rev40 model `z3_k30_K1000_V1e+12`, reduced). By hand at p = 1:
/// pair 1 is pressed by 400 and pulled by 500 on a spring of 30, so it slips at its limit,
/// `x_t = −f·x_n = −120`, `z_t = (500 − 120)/30`; pair 2 is pressed by 400 and slides freely,
/// `x_t = 0`, `z_t = −1e12/1000`. Both are closed. The huge push is carried by neither pair as
/// a force (it goes into pair 2's slip), so it is no scale for their normal forces: 400 beside
/// `1e-9·1e12` read "open" with the friction force zeroed. The same in N·m and kN·mm.
#[test]
fn a_huge_load_that_only_slides_a_frictionless_pair_leaves_the_others_closed() {
    for (name, f, u) in [("N·m", 1.0, 1.0), ("kN·mm", 1e-3, 1e3)] {
        let k = f / u;
        let mut zone = ContactZone::new(
            Mat::zeros(2, 2),
            Mat::from_fn(2, 2, |i, j| match (i, j) {
                (0, 0) => 30.0 * k,
                (1, 1) => 1000.0 * k,
                _ => 0.0,
            }),
        );
        zone.friction = vec![0.3, 0.0];
        zone.constant.normal = vec![400.0 * f; 2];
        zone.variable.tangential = vec![-500.0 * f, 1e12 * f];
        let sol = solve(&zone, &SolveSettings::default()).unwrap();
        assert_eq!(sol.p, Some(1.0), "{name}");
        let states: Vec<_> = sol.pairs.iter().map(|r| r.state).collect();
        assert_eq!(
            states,
            [PairState::SlipPlus, PairState::SlipMinus],
            "{name}: {:?}",
            sol.pairs
        );
        let (a, b) = (&sol.pairs[0], &sol.pairs[1]);
        assert!((a.x_n - 400.0 * f).abs() <= 1e-12 * f, "{name}: {a:?}");
        assert!((a.x_t + 120.0 * f).abs() <= 1e-9 * f, "{name}: {a:?}");
        assert!(
            (a.z_t - 380.0 / 30.0 * u).abs() <= 1e-9 * u,
            "{name}: {a:?}"
        );
        assert!((b.x_n - 400.0 * f).abs() <= 1e-12 * f, "{name}: {b:?}");
        assert_eq!(b.x_t, 0.0, "{name}: {b:?}");
        assert!((b.z_t + 1e9 * u).abs() <= 1e-6 * u, "{name}: {b:?}");
        assert_matches_enumeration(&zone, 1.0, &sol.pairs);
    }
}

/// Two zones that do not act on each other, solved as one: each keeps the states and forces it
/// has alone, however much larger the other's forces. Part A is the paper's Example 1 zone
/// under a constant pressure and a variable load with a tangential part; part B two pairs of
/// their own (one lifted off at `p = 1`), its stiffness and loads multiplied by `s` (its
/// displacements unchanged, its forces `s` times). Before round 41 a pair's state was judged
/// against the largest force of the whole solution: beside `s = 1e9` every pair of part A read
/// "open" and its friction forces were zeroed as an open pair's round-off. Each part alone is
/// checked against the exact enumeration of its LCP.
#[test]
fn a_zone_of_two_parts_that_do_not_touch_gives_each_its_own_answer() {
    let part_a = |zone: &mut ContactZone, at: usize| {
        let ex = example1_zone();
        for i in 0..3 {
            for j in 0..3 {
                zone.rnn[(at + i, at + j)] = ex.rnn[(i, j)];
                zone.rtt[(at + i, at + j)] = ex.rtt[(i, j)];
            }
            zone.friction[at + i] = 0.6;
            zone.constant.normal[at + i] = 0.6875;
        }
        zone.variable.normal[at..at + 3].copy_from_slice(&[-0.09375, 0.6875, 0.40625]);
        zone.variable.tangential[at..at + 3].copy_from_slice(&[0.5, -0.1, 0.2]);
    };
    let part_b = |zone: &mut ContactZone, at: usize, s: f64| {
        let (rnn, rtt) = ([[2.0, -1.0], [-1.0, 2.0]], [[3.0, -1.0], [-1.0, 3.0]]);
        for i in 0..2 {
            for j in 0..2 {
                zone.rnn[(at + i, at + j)] = s * rnn[i][j];
                zone.rtt[(at + i, at + j)] = s * rtt[i][j];
            }
            zone.friction[at + i] = 0.3;
            zone.constant.normal[at + i] = s;
        }
        zone.variable.normal[at..at + 2].copy_from_slice(&[-1.5 * s, 0.3 * s]);
        zone.variable.tangential[at..at + 2].copy_from_slice(&[0.4 * s, 0.1 * s]);
    };
    let empty = |m: usize| ContactZone::new(Mat::zeros(m, m), Mat::zeros(m, m));
    let settings = SolveSettings::default();
    let mut a = empty(3);
    part_a(&mut a, 0);
    let mut b = empty(2);
    part_b(&mut b, 0, 1.0);
    let alone: Vec<_> = [&a, &b]
        .iter()
        .map(|zone| {
            let sol = solve(zone, &settings).unwrap();
            assert_eq!(sol.p, Some(1.0));
            assert_matches_enumeration(zone, 1.0, &sol.pairs);
            sol.pairs
        })
        .collect();
    let states = |pairs: &[unilateral_contact::PairResult]| -> Vec<PairState> {
        pairs.iter().map(|r| r.state).collect()
    };
    // The parts have what the test is about: an open pair, a slipping one and sticking ones.
    assert_eq!(
        [states(&alone[0]), states(&alone[1])].concat(),
        [
            PairState::SlipMinus,
            PairState::Stick,
            PairState::Stick,
            PairState::Open,
            PairState::Stick
        ]
    );
    for s in [1e-9, 1.0, 1e6, 1e9, 1e12] {
        for b_first in [false, true] {
            let what = format!("s = {s:e}, part B first {b_first}");
            let mut zone = empty(5);
            let (at_a, at_b) = if b_first { (2, 0) } else { (0, 3) };
            part_a(&mut zone, at_a);
            part_b(&mut zone, at_b, s);
            let sol = solve(&zone, &settings).unwrap();
            assert_eq!(sol.p, Some(1.0), "{what}");
            for (part, at, k, scale) in [(&alone[0], at_a, 3, 1.0), (&alone[1], at_b, 2, s)] {
                let got = &sol.pairs[at..at + k];
                assert_eq!(states(got), states(part), "{what}: {got:?}");
                for (g, r) in got.iter().zip(part.iter()) {
                    let close = |x: f64, y: f64, size: f64| (x - y).abs() <= 1e-12 * size;
                    let force = scale * (r.x_n.abs() + r.x_t.abs());
                    let slip = r.z_n.abs() + r.z_t.abs();
                    assert!(
                        close(g.x_n, scale * r.x_n, force)
                            && close(g.x_t, scale * r.x_t, force)
                            && close(g.z_n, r.z_n, slip)
                            && close(g.z_t, r.z_t, slip),
                        "{what}: {g:?} against {r:?}"
                    );
                }
            }
        }
    }
}

/// A reviewer's zone: pair 1 behind a gap of 1 mm that nothing closes, pair 2 frictionless and
/// pushed sideways by 5.5e11, pair 3 (f = 0.4) tied to pair 2 by `R_tt`. Pair 2 slides some 8e9
/// m; its slip's terms (1e13) leave round-off in the tangential rows of the pairs beside it.
/// The friction law allows no tangential force where `f·x_n` is zero: pair 1 (open, no normal
/// force) and pair 2 (no friction) carry exactly none, in N·m and kN·mm alike — before, 7e-4 N
/// and 1.2e-4 N in N·m, 0.21 N on pair 1 in kN·mm.
#[test]
fn no_tangential_force_where_the_friction_law_allows_none() {
    let rtt = [
        [701.5463661686019, -690.2486213647242, 0.0],
        [-690.2486213647242, 752.6400131971335, -32.956212316547955],
        [0.0, -32.956212316547955, 329.56212316547953],
    ];
    let rnn = [1243.1526306379114, 1000.0, 800.0];
    for (name, f, u) in [("N·m", 1.0, 1.0), ("kN·mm", 1e-3, 1e3)] {
        let k = f / u;
        let mut zone = ContactZone::new(
            Mat::from_fn(3, 3, |i, j| if i == j { rnn[i] * k } else { 0.0 }),
            Mat::from_fn(3, 3, |i, j| rtt[i][j] * k),
        );
        zone.friction = vec![0.3, 0.0, 0.4];
        zone.gap = vec![0.001 * u, 0.0, 0.0];
        zone.constant.normal = vec![0.0, 389.89821295774766 * f, 430.3185945445526 * f];
        zone.variable.tangential = vec![
            0.5774467022710263 * f,
            546929793387.11743 * f,
            -47.16525234779937 * f,
        ];
        let sol = solve(&zone, &SolveSettings::default()).unwrap();
        assert_eq!(sol.p, Some(1.0), "{name}");
        let states: Vec<_> = sol.pairs.iter().map(|r| r.state).collect();
        assert_eq!(
            states,
            [PairState::Open, PairState::SlipMinus, PairState::SlipMinus],
            "{name}: {:?}",
            sol.pairs
        );
        let (a, b, c) = (&sol.pairs[0], &sol.pairs[1], &sol.pairs[2]);
        assert_eq!((a.x_n, a.x_t), (0.0, 0.0), "{name}: {a:?}");
        assert_eq!(b.x_t, 0.0, "{name}: {b:?}");
        // By hand: no normal coupling, so each normal force is its own load and pair 1 keeps
        // its gap; pair 3 slides with x_t = +f·x_n.
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
        assert!(close(a.z_n, 0.001 * u), "{name}: {a:?}");
        assert!(close(b.x_n, 389.89821295774766 * f), "{name}: {b:?}");
        assert!(close(c.x_n, 430.3185945445526 * f), "{name}: {c:?}");
        // Its tangential row sums pair 2's slip times `R_tt` (33 × 7.8e9 = 2.6e11 N): 1.7e-5 N
        // of round-off beside its 172 N.
        let terms = 32.956212316547955 * b.z_t.abs() * k;
        assert!(
            (c.x_t - 0.4 * c.x_n).abs() <= 1e3 * f64::EPSILON * terms,
            "{name}: {c:?}"
        );
    }
}
