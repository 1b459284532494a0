//! Structural models a new user writes first: gaps, a statically determinate contact support,
//! any units, models that ask for too much memory, a constant load that pulls every pair
//! apart, and which errors are the program's fault. Every expected value is a hand calculation
//! (beam theory, statics) written out in the test's comment; no expected value comes from the
//! code under test.

use unilateral_analysis::{analyze, AnalysisError, Outcome, PairState, Place};
use unilateral_contact::{EventKind, Follow, SolveSettings};
use unilateral_fem::{ContactPairSpec, FemError, FrameSection, Load, LoadFrame, LoadGroup, Model};

/// Relative closeness: `|a − b| ≤ tol·max(|b|, scale)`.
fn close(a: f64, b: f64, tol: f64, scale: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(scale)
}

// ---------------------------------------------------------------------------------------------
// 1. Gaps in structural models
// ---------------------------------------------------------------------------------------------

const BEAM_L: f64 = 12.0;
const BEAM_EI: f64 = 2.1e7;
const BEAM_Q: f64 = 1.0e4;

/// A nodal force `(fx, fy)` without moment.
pub(crate) fn nodal(node: unilateral_fem::NodeId, fx: f64, fy: f64) -> Load {
    Load::Nodal {
        node,
        fx,
        fy,
        m: 0.0,
    }
}

/// Deflection (downwards positive) at `x` of a simply supported beam of span `L` under a unit
/// uniform load, times EI: `x (L³ − 2 L x² + x³) / 24` (any beam-theory table).
fn udl_deflection(x: f64) -> f64 {
    let l = BEAM_L;
    x * (l.powi(3) - 2.0 * l * x * x + x.powi(3)) / 24.0
}

/// Deflection at `x` of a simply supported beam under a unit point load at `a`, times EI:
/// `b x (L² − b² − x²) / (6 L)` for `x ≤ a` (b = L − a), and by Maxwell's reciprocity the
/// mirror formula for `x > a`.
fn point_deflection(x: f64, a: f64) -> f64 {
    let l = BEAM_L;
    if x <= a {
        let b = l - a;
        b * x * (l * l - b * b - x * x) / (6.0 * l)
    } else {
        point_deflection(l - x, l - a)
    }
}

/// The beam: 12 m, EI = 2.1e7 N·m², pinned at both ends, q = 10 kN/m·p downwards
/// (variable), ground pairs (normal up into the beam) at x = 4 m and x = 8 m with the gaps
/// given. Frames of 1 m; Hermite frames under consistent loads give exact nodal deflections.
fn gap_beam(gap4: f64, gap8: f64) -> (Model, Vec<unilateral_fem::NodeId>) {
    let mut m = Model::new();
    let nodes: Vec<_> = (0..=12).map(|i| m.add_node(i as f64, 0.0)).collect();
    let sec = FrameSection::new(2.1e11, 1.0e-2, BEAM_EI / 2.1e11);
    for w in nodes.windows(2) {
        let e = m.add_frame(w[0], w[1], sec);
        m.add_load(
            LoadGroup::Variable,
            Load::Distributed {
                element: e,
                start: [0.0, -BEAM_Q],
                end: [0.0, -BEAM_Q],
                frame: LoadFrame::Global,
            },
        );
    }
    m.pin(nodes[0]);
    m.pin(nodes[12]);
    m.add_contact_pair(ContactPairSpec::to_ground(nodes[4], [0.0, 1.0]).gap(gap4));
    m.add_contact_pair(ContactPairSpec::to_ground(nodes[8], [0.0, 1.0]).gap(gap8));
    (m, nodes)
}

fn settings(target: f64, follow: Follow) -> SolveSettings {
    SolveSettings {
        tightening: 0.0,
        target,
        follow,
        ..Default::default()
    }
}

#[test]
fn gaps_close_at_the_hand_loads_and_the_results_at_p1_are_the_hand_reactions() {
    // Hand values (beam theory, superposition), with w0 = udl_deflection(4) = 234.667 /EI per
    // unit q: the midspan-side points x = 4 and x = 8 deflect equally, w0·q/EI = 0.111746 per
    // unit p. Pair 1 (gap 0.01) closes first at p1 = 0.01·EI/(q·w0) = 0.089489.
    // Afterwards the prop at x = 4 carries R = w0·q·(p − p1)/δ44, which lifts x = 8 by
    // R·δ84: w8(p) = (q/EI)·w0·[p − (δ84/δ44)(p − p1)], δ44 = 28.444, δ84 = 24.889
    // (point_deflection), δ84/δ44 = 0.875. Pair 2 (gap 0.02) closes when w8 = 0.02:
    // 234.667·(0.125 p + 0.875·0.089489) = 0.02·2100 → p2 = 0.805398.
    let w0 = udl_deflection(4.0) * BEAM_Q / BEAM_EI;
    let p1 = 0.01 / w0;
    let ratio = point_deflection(8.0, 4.0) / point_deflection(4.0, 4.0);
    let p2 = (0.02 / w0 - ratio * p1) / (1.0 - ratio);
    assert!((p1 - 0.089489).abs() < 5e-7, "{p1}");
    assert!((p2 - 0.805398).abs() < 5e-7, "{p2}");
    assert!((ratio - 0.875).abs() < 1e-12);

    let (model, nodes) = gap_beam(0.01, 0.02);
    let a = analyze(&model, &settings(1.0, Follow::ToTarget)).expect("the gap beam is analysed");
    let loads = a.event_loads();
    assert_eq!(loads.len(), 2, "{:?}", a.solution.steps);
    assert!(close(loads[0], p1, 1e-9, 0.0), "{} vs {p1}", loads[0]);
    assert!(close(loads[1], p2, 1e-9, 0.0), "{} vs {p2}", loads[1]);
    assert_eq!(a.solution.steps[0].events[0].kind, EventKind::Closes);
    assert_eq!(a.solution.steps[0].events[0].pair, 0);
    assert_eq!(a.solution.steps[1].events[0].kind, EventKind::Closes);
    assert_eq!(a.solution.steps[1].events[0].pair, 1);

    // At p = 1 both props are closed: the beam on four supports with the props pre-displaced
    // downwards by their gaps. Compatibility (flexibilities by point_deflection):
    //   δ44 R4 + δ48 R8 = q·w(4) − EI·0.01,  δ84 R4 + δ88 R8 = q·w(8) − EI·0.02,
    // then the end reactions by statics.
    let (d44, d48) = (point_deflection(4.0, 4.0), point_deflection(4.0, 8.0));
    let (d84, d88) = (point_deflection(8.0, 4.0), point_deflection(8.0, 8.0));
    let b4 = BEAM_Q * udl_deflection(4.0) - BEAM_EI * 0.01;
    let b8 = BEAM_Q * udl_deflection(8.0) - BEAM_EI * 0.02;
    let det = d44 * d88 - d48 * d84;
    let r4 = (b4 * d88 - d48 * b8) / det;
    let r8 = (d44 * b8 - d84 * b4) / det;
    let total = BEAM_Q * BEAM_L;
    let r12 = (total * BEAM_L / 2.0 - 4.0 * r4 - 8.0 * r8) / BEAM_L;
    let r0 = total - r4 - r8 - r12;
    assert!(r4 > 0.0 && r8 > 0.0);

    assert_eq!(a.solution.outcome, Outcome::TargetReached);
    let pairs = &a.solution.pairs;
    assert!(
        close(pairs[0].x_n, r4, 1e-9, total),
        "{} vs {r4}",
        pairs[0].x_n
    );
    assert!(
        close(pairs[1].x_n, r8, 1e-9, total),
        "{} vs {r8}",
        pairs[1].x_n
    );
    assert!(pairs[0].z_n.abs() <= 1e-9 * 0.01);
    assert!(pairs[1].z_n.abs() <= 1e-9 * 0.02);
    let r = a.results.as_ref().unwrap();
    // Displacements consistent with the gaps: the closed props sit exactly one gap lower.
    assert!(close(r.displacements[nodes[4].0][1], -0.01, 1e-9, 0.0));
    assert!(close(r.displacements[nodes[8].0][1], -0.02, 1e-9, 0.0));
    let reaction_y = |n: unilateral_fem::NodeId| {
        r.reactions
            .iter()
            .filter(|x| x.node == n && x.dof == unilateral_fem::SupportDof::Uy)
            .map(|x| x.value)
            .sum::<f64>()
    };
    assert!(close(reaction_y(nodes[0]), r0, 1e-9, total));
    assert!(close(reaction_y(nodes[12]), r12, 1e-9, total));
    assert!(r.equilibrium.relative() < 1e-9);

    // Between the events (p = 0.5): only the first prop is closed; the second is still open by
    // 0.02 − w8(0.5).
    let (pr, res) = a.results_at(0.5).unwrap();
    let w8 = w0 * (0.5 - ratio * (0.5 - p1));
    assert_eq!(pr[1].state, PairState::Open);
    assert!(close(pr[1].z_n, 0.02 - w8, 1e-9, 0.02), "{}", pr[1].z_n);
    assert!(close(res.displacements[nodes[8].0][1], -w8, 1e-9, 0.0));
}

#[test]
fn a_gap_that_never_closes_leaves_the_simply_supported_beam() {
    // Gaps of 1 m at both points: at p = 1 the beam deflects 0.111746 m there (w0 above), the
    // pairs stay open by 1 − 0.111746, carry nothing, and the beam is simply supported:
    // end reactions q L / 2 = 60 kN each.
    let (model, nodes) = gap_beam(1.0, 1.0);
    let a = analyze(&model, &settings(1.0, Follow::ToTarget)).expect("analysed");
    assert!(a.event_loads().is_empty(), "{:?}", a.solution.steps);
    let w0 = udl_deflection(4.0) * BEAM_Q / BEAM_EI;
    for pr in &a.solution.pairs {
        assert_eq!(pr.state, PairState::Open);
        assert!(close(pr.z_n, 1.0 - w0, 1e-9, 0.0), "{}", pr.z_n);
        assert!(pr.x_n.abs() <= 1e-9 * BEAM_Q * BEAM_L);
    }
    let r = a.results.as_ref().unwrap();
    assert!(close(r.displacements[nodes[4].0][1], -w0, 1e-9, 0.0));
    assert!(close(r.displacements[nodes[8].0][1], -w0, 1e-9, 0.0));
    for x in &r.reactions {
        if x.dof == unilateral_fem::SupportDof::Uy {
            assert!(close(x.value, BEAM_Q * BEAM_L / 2.0, 1e-9, 0.0), "{x:?}");
        }
    }
}

/// Two equal cantilevers (L = 2, EI = 3, so the tip flexibility is c = L³/(3EI) = 8/9), one
/// above the other (1 apart), a node-to-node pair between the tips (A = lower tip, B = upper
/// tip, normal `normal` from A into B) with gap `g`, a load p downwards on the upper tip.
fn two_cantilevers(g: f64, normal: [f64; 2]) -> (Model, [unilateral_fem::NodeId; 2]) {
    let mut m = Model::new();
    let sec = FrameSection::new(3.0, 100.0, 1.0);
    let r0 = m.add_node(0.0, 0.0);
    let t0 = m.add_node(2.0, 0.0);
    let r1 = m.add_node(0.0, 1.0);
    let t1 = m.add_node(2.0, 1.0);
    m.add_frame(r0, t0, sec);
    m.add_frame(r1, t1, sec);
    m.fix(r0);
    m.fix(r1);
    m.add_contact_pair(ContactPairSpec::between(t0, t1, normal).gap(g));
    m.add_load(LoadGroup::Variable, nodal(t1, 0.0, -1.0));
    (m, [t0, t1])
}

#[test]
fn node_to_node_pair_with_a_gap() {
    // Hand values (cantilever tip flexibility c = L³/(3EI) = 8/9): with the normal from the
    // lower tip up into the upper one the load closes the pair. The upper tip travels the gap
    // at p_c = g/c = 0.45; beyond, the two equal cantilevers share the extra load equally:
    // x_n = (p − p_c)/2. At p = 1: x_n = 0.275, upper tip uy = −(1 − x_n)·c, lower tip
    // uy = −x_n·c, their difference −g.
    let c = 8.0 / 9.0;
    let g = 0.4;
    let (model, tips) = two_cantilevers(g, [0.0, 1.0]);
    let a = analyze(&model, &settings(1.0, Follow::ToTarget)).expect("analysed");
    let pc = g / c;
    let loads = a.event_loads();
    assert_eq!(loads.len(), 1, "{:?}", a.solution.steps);
    assert!(close(loads[0], pc, 1e-9, 0.0), "{loads:?}");
    let xn = (1.0 - pc) / 2.0;
    let pr = &a.solution.pairs[0];
    assert!(close(pr.x_n, xn, 1e-9, 1.0), "{}", pr.x_n);
    assert!(pr.z_n.abs() < 1e-9 * g);
    let r = a.results.as_ref().unwrap();
    let (ul, uu) = (r.displacements[tips[0].0][1], r.displacements[tips[1].0][1]);
    assert!(close(uu, -(1.0 - xn) * c, 1e-9, 0.0), "{uu}");
    assert!(close(ul, -xn * c, 1e-9, 0.0), "{ul}");
    assert!(close(uu - ul, -g, 1e-9, 0.0));
    assert!(r.equilibrium.relative() < 1e-9);

    // The normal reversed: the load now opens the pair; it never closes, the opening is
    // g + n·(u_B − u_A) = g + (−1)·(−c) = g + c, and the lower cantilever carries nothing.
    let (model, tips) = two_cantilevers(g, [0.0, -1.0]);
    let a = analyze(&model, &settings(1.0, Follow::ToTarget)).expect("analysed");
    let pr = &a.solution.pairs[0];
    assert_eq!(pr.state, PairState::Open);
    assert!(close(pr.z_n, g + c, 1e-9, 0.0), "{}", pr.z_n);
    let r = a.results.as_ref().unwrap();
    assert!(close(r.displacements[tips[1].0][1], -c, 1e-9, 0.0));
    assert!(r.displacements[tips[0].0][1].abs() < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// 2. A statically determinate contact support
// ---------------------------------------------------------------------------------------------

/// The heated beam below in other units: lengths ×`len`, forces ×`force` (E ×force/len²,
/// A ×len², I ×len⁴, q ×force/len; α and ΔT unchanged).
fn heated_beam_in(divisions: usize, len: f64, force: f64) -> Model {
    let mut m = Model::new();
    let nodes: Vec<_> = (0..=divisions)
        .map(|i| m.add_node(10.0 * len * i as f64 / divisions as f64, 0.0))
        .collect();
    let sec = FrameSection::new(
        2.1e11 * force / (len * len),
        0.01 * len * len,
        1e-4 * len.powi(4),
    )
    .with_alpha(1.2e-5);
    for w in nodes.windows(2) {
        let e = m.add_frame(w[0], w[1], sec);
        let q = 2.5e5 * force / len;
        m.add_load(
            LoadGroup::Constant,
            Load::Distributed {
                element: e,
                start: [0.0, -q],
                end: [0.0, -q],
                frame: LoadFrame::Global,
            },
        );
        m.add_load(
            LoadGroup::Variable,
            Load::Temperature {
                element: e,
                uniform: 50.0,
                gradient: 0.0,
            },
        );
    }
    m.pin(nodes[0]);
    m.add_contact_pair(ContactPairSpec::to_ground(nodes[divisions], [0.0, 1.0]).friction(0.3));
    m
}

#[test]
fn the_heated_beam_gives_the_same_answer_in_any_units() {
    // The hand values of the test below, scaled: slip from p = 0.297619 whatever the units,
    // the slip ×len, the forces ×force. The equilibrium check of the recovered results must
    // not depend on the units either (moments are force × length).
    let p_slip: f64 = 0.3 * 1.25e6 / (2.1e9 * 1.2e-5 * 50.0);
    let slip = 1.2e-5 * 50.0 * 10.0 - 0.3 * 1.25e6 * 10.0 / 2.1e9;
    let mut failed = Vec::new();
    for len in [1e-12, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e12] {
        for force in [1e-12, 1e-3, 1.0, 1e3, 1e12] {
            let what = format!("lengths ×{len:e}, forces ×{force:e}");
            let a = match analyze(
                &heated_beam_in(8, len, force),
                &settings(1.0, Follow::ToTarget),
            ) {
                Ok(a) => a,
                Err(e) => {
                    failed.push(format!("{what}: {e}"));
                    continue;
                }
            };
            let loads = a.event_loads();
            let pr = &a.solution.pairs[0];
            let ok = loads.len() == 1
                && close(loads[0], p_slip, 1e-9, 0.0)
                && close(pr.x_n, 1.25e6 * force, 1e-9, 0.0)
                && close(pr.x_t.abs(), 3.75e5 * force, 1e-9, 0.0)
                && close(pr.z_t, slip * len, 1e-9, 0.0)
                && a.results.as_ref().unwrap().equilibrium.relative() < 1e-9;
            if !ok {
                failed.push(format!("{what}: {loads:?} {pr:?}"));
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

/// A 10 m beam pinned at x = 0, on a frictional bearing (ground pair, normal up, f = 0.3) at
/// x = 10, under its weight q = 250 kN/m (constant) and heated uniformly by ΔT = 50 K·p
/// (variable); E = 2.1e11 Pa, A = 0.01 m², I = 1e-4 m⁴, α = 1.2e-5 /K.
fn heated_beam(divisions: usize) -> Model {
    // ×1.0 is exact: the same numbers as written out in N and m.
    heated_beam_in(divisions, 1.0, 1.0)
}

#[test]
fn a_determinate_contact_support_gives_the_same_answer_for_every_mesh() {
    // Hand values: the bearing carries qL/2 = 1.25e6 N; bonded, the heating is fully
    // restrained: N = EA·α·ΔT·p = 2.1e9·1.2e-5·50·p = 1.26e6·p in the bearing's tangential
    // link. It slips when 1.26e6·p = f·qL/2 = 3.75e5: p = 0.297619. Afterwards the beam is
    // determinate (the bearing slides with the friction force 3.75e5 N): at p = 1 the slip is
    // the free expansion less the elastic shortening, α·ΔT·L − f·R·L/EA
    // = 6e-3 − 3.75e5·10/2.1e9 = 4.214286e-3 m (along t = +x).
    // The normal stiffness of the bearing is exactly zero (the beam turns about the pin).
    let p_slip: f64 = 0.3 * 1.25e6 / (2.1e9 * 1.2e-5 * 50.0);
    assert!((p_slip - 0.297619).abs() < 5e-7);
    let slip = 1.2e-5 * 50.0 * 10.0 - 0.3 * 1.25e6 * 10.0 / 2.1e9;
    for div in [1, 2, 4, 5, 8, 10, 20] {
        let model = heated_beam(div);
        let a = analyze(&model, &settings(1.0, Follow::ToTarget))
            .unwrap_or_else(|e| panic!("{div} divisions: {e}"));
        assert_eq!(a.zone.rnn[(0, 0)], 0.0, "{div} divisions: Rnn is round-off");
        let loads = a.event_loads();
        assert_eq!(loads.len(), 1, "{div} divisions: {:?}", a.solution.steps);
        assert!(close(loads[0], p_slip, 1e-9, 0.0), "{div}: {}", loads[0]);
        let ev = &a.solution.steps[0].events[0];
        assert!(
            matches!(
                ev.kind,
                EventKind::StartsSlippingPlus | EventKind::StartsSlippingMinus
            ),
            "{div}: {ev:?}"
        );
        let pr = &a.solution.pairs[0];
        assert!(close(pr.x_n, 1.25e6, 1e-9, 0.0), "{div}: {}", pr.x_n);
        assert!(close(pr.x_t.abs(), 3.75e5, 1e-9, 0.0), "{div}: {}", pr.x_t);
        assert!(
            close(pr.z_t, slip, 1e-9, 0.0),
            "{div}: {} vs {slip}",
            pr.z_t
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Units: the two-node frame slider
// ---------------------------------------------------------------------------------------------

/// A frame of length `len` (E, A, I) between two nodes, each on a ground pair (normal up,
/// f = 0.3), pressed by `w` per node (constant) and pulled along +x at the second node by
/// H = 0.05·w (variable).
fn slider(len: f64, e: f64, area: f64, inertia: f64, w: f64) -> Model {
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(len, 0.0);
    m.add_frame(a, b, FrameSection::new(e, area, inertia));
    for n in [a, b] {
        m.add_contact_pair(ContactPairSpec::to_ground(n, [0.0, 1.0]).friction(0.3));
        m.add_load(LoadGroup::Constant, nodal(n, 0.0, -w));
    }
    m.add_load(LoadGroup::Variable, nodal(b, 0.05 * w, 0.0));
    m
}

/// Hand values: bonded, the pull goes straight into the second node's rigid tangential link
/// (x_t2 = H·p, x_t1 = 0). The second pair slips when H·p = f·W: p = 0.3/0.05 = 6; then the
/// frame carries the rest to the first pair: x_t1 = H·p − f·W, which slips when it reaches
/// f·W: p = 12, and with both pairs slipping the slider is a mechanism: p_lim = 12.
fn check_slider(model: &Model, what: &str) {
    let a =
        analyze(model, &settings(20.0, Follow::ToTarget)).unwrap_or_else(|e| panic!("{what}: {e}"));
    let loads = a.event_loads();
    assert_eq!(loads.len(), 2, "{what}: {:?}", a.solution.steps);
    assert!(close(loads[0], 6.0, 1e-9, 0.0), "{what}: {loads:?}");
    assert!(close(loads[1], 12.0, 1e-9, 0.0), "{what}: {loads:?}");
    assert_eq!(a.solution.steps[0].events[0].pair, 1, "{what}");
    assert_eq!(a.solution.steps[1].events[0].pair, 0, "{what}");
    match a.solution.outcome {
        Outcome::Mechanism { p_limit, .. } => {
            assert!(close(p_limit, 12.0, 1e-9, 0.0), "{what}: {p_limit}")
        }
        ref o => panic!("{what}: expected a mechanism at 12, got {o:?}"),
    }
}

/// The zone `z` equals `base` with stiffnesses scaled by `k` (force/length) and loads by `f`
/// (force), to 1e-12 of each block's largest entry.
fn same_zone(
    z: &unilateral_contact::ContactZone,
    base: &unilateral_contact::ContactZone,
    k: f64,
    f: f64,
    what: &str,
) {
    let m = base.friction.len();
    for (a, b, name) in [
        (&z.rnn, &base.rnn, "rnn"),
        (&z.rnt, &base.rnt, "rnt"),
        (&z.rtn, &base.rtn, "rtn"),
        (&z.rtt, &base.rtt, "rtt"),
    ] {
        let big = (0..m)
            .flat_map(|i| (0..m).map(move |j| (i, j)))
            .fold(0.0f64, |s, (i, j)| s.max(b[(i, j)].abs()));
        for i in 0..m {
            for j in 0..m {
                assert!(
                    (a[(i, j)] / k - b[(i, j)]).abs() <= 1e-12 * big,
                    "{what}: {name}[{i},{j}] = {} vs {}·{k}",
                    a[(i, j)],
                    b[(i, j)]
                );
            }
        }
    }
    for (a, b, name) in [
        (&z.constant.normal, &base.constant.normal, "constant.normal"),
        (
            &z.constant.tangential,
            &base.constant.tangential,
            "constant.tangential",
        ),
        (&z.variable.normal, &base.variable.normal, "variable.normal"),
        (
            &z.variable.tangential,
            &base.variable.tangential,
            "variable.tangential",
        ),
    ] {
        let big = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for i in 0..m {
            assert!(
                (a[i] / f - b[i]).abs() <= 1e-12 * big,
                "{what}: {name}[{i}] = {} vs {}·{f}",
                a[i],
                b[i]
            );
        }
    }
}

#[test]
fn the_slider_gives_the_same_events_for_any_load_scale() {
    // EA = 2e9 (E = 2e11, A = 0.01), I = 1e-4, L = 1; the answer is independent of W.
    // The structural side first: the condensed zone is W-independent in R and proportional
    // to W in the loads (to round-off), so any failure below is the contact engine's.
    let base =
        unilateral_analysis::zone_of(&slider(1.0, 2e11, 0.01, 1e-4, 1.0).condense().unwrap());
    let ks = [
        -150, -100, -50, -20, -10, -1, 0, 1, 5, 10, 20, 25, 30, 50, 100,
    ];
    for k in ks {
        let w = 10f64.powi(k);
        let z = unilateral_analysis::zone_of(&slider(1.0, 2e11, 0.01, 1e-4, w).condense().unwrap());
        same_zone(&z, &base, 1.0, w, &format!("W = 1e{k}"));
    }
    // Then the path, every scale tried and every failure listed.
    let failed: Vec<String> = ks
        .iter()
        .filter_map(|&k| {
            let w = 10f64.powi(k);
            std::panic::catch_unwind(|| {
                check_slider(&slider(1.0, 2e11, 0.01, 1e-4, w), &format!("W = 1e{k}"))
            })
            .err()
            .map(|_| format!("1e{k}"))
        })
        .collect();
    assert!(failed.is_empty(), "wrong events for W = {failed:?}");
}

#[test]
fn the_slider_gives_the_same_events_in_any_units() {
    // N and m; kN and mm (lengths ×1e3, forces ×1e-3, so E ×1e-9, A ×1e6, I ×1e12); MN and m.
    check_slider(&slider(1.0, 2e11, 0.01, 1e-4, 1e3), "N, m");
    check_slider(
        &slider(1e3, 2e11 * 1e-9, 0.01 * 1e6, 1e-4 * 1e12, 1.0),
        "kN, mm",
    );
    check_slider(&slider(1.0, 2e11 * 1e-6, 0.01, 1e-4, 1e-3), "MN, m");
    check_slider(&slider(1e-3, 2e11 * 1e3, 1e-8, 1e-16, 1e3), "N, km");
}

#[test]
fn the_gap_beam_gives_the_same_answer_in_any_units() {
    // The gap beam with lengths ×len and forces ×force (E ×force/len², A ×len², I ×len⁴,
    // q ×force/len, gaps ×len): the closure loads are dimensionless and must not move.
    let mut failed = Vec::new();
    for len in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        for force in [1e-9, 1e-3, 1.0, 1e3, 1e9] {
            let what = format!("lengths ×{len:e}, forces ×{force:e}");
            let mut m = Model::new();
            let nodes: Vec<_> = (0..=12).map(|i| m.add_node(i as f64 * len, 0.0)).collect();
            let e = 2.1e11 * force / (len * len);
            let sec = FrameSection::new(e, 1e-2 * len * len, BEAM_EI / 2.1e11 * len.powi(4));
            for w in nodes.windows(2) {
                let el = m.add_frame(w[0], w[1], sec);
                let q = BEAM_Q * force / len;
                m.add_load(
                    LoadGroup::Variable,
                    Load::Distributed {
                        element: el,
                        start: [0.0, -q],
                        end: [0.0, -q],
                        frame: LoadFrame::Global,
                    },
                );
            }
            m.pin(nodes[0]);
            m.pin(nodes[12]);
            m.add_contact_pair(ContactPairSpec::to_ground(nodes[4], [0.0, 1.0]).gap(0.01 * len));
            m.add_contact_pair(ContactPairSpec::to_ground(nodes[8], [0.0, 1.0]).gap(0.02 * len));
            // The structural side: stiffness ×force/length, loads ×force, gaps ×length, to
            // round-off; a failure after this is the contact engine's.
            let z = unilateral_analysis::zone_of(&m.condense().unwrap());
            let base = unilateral_analysis::zone_of(&gap_beam(0.01, 0.02).0.condense().unwrap());
            same_zone(&z, &base, force / len, force, &what);
            assert!(close(z.gap[0], 0.01 * len, 1e-15, 0.0));
            assert!(close(z.gap[1], 0.02 * len, 1e-15, 0.0));
            match analyze(&m, &settings(1.0, Follow::ToTarget)) {
                Err(e) => failed.push(format!("{what}: {e}")),
                Ok(a) => {
                    let loads = a.event_loads();
                    let ok = loads.len() == 2
                        && close(loads[0], 0.089489, 5e-6, 0.0)
                        && close(loads[1], 0.805398, 5e-6, 0.0);
                    if !ok {
                        failed.push(format!("{what}: events at {loads:?}"));
                    }
                }
            }
        }
    }
    assert!(failed.is_empty(), "{failed:#?}");
}

// ---------------------------------------------------------------------------------------------
// 5. Models that ask for too much memory
// ---------------------------------------------------------------------------------------------

#[test]
fn a_model_with_too_many_pairs_is_refused_before_allocating() {
    // 100 001 ground pairs on a 100 000-element beam: the dense contact matrices alone
    // (4 blocks of m² doubles) would take 4·100001²·8 B ≈ 320 GB. The analysis must refuse it
    // with a clear message (no panic, no abort), quickly.
    let n = 100_000;
    let mut m = Model::new();
    let nodes: Vec<_> = (0..=n).map(|i| m.add_node(i as f64, 0.0)).collect();
    let sec = FrameSection::new(1.0, 1.0, 1.0);
    for w in nodes.windows(2) {
        m.add_frame(w[0], w[1], sec);
    }
    for &nd in &nodes {
        m.add_contact_pair(ContactPairSpec::to_ground(nd, [0.0, 1.0]));
    }
    m.add_load(LoadGroup::Variable, nodal(nodes[3], 0.0, -1.0));
    let r = std::panic::catch_unwind(|| analyze(&m, &SolveSettings::default()));
    let r = r.expect("no panic");
    let e = r.expect_err("refused");
    let msg = e.to_string();
    assert!(
        matches!(
            e,
            AnalysisError::Model {
                source: FemError::TooLarge { .. },
                ..
            }
        ),
        "{msg}"
    );
    assert!(msg.contains("100001 contact pairs"), "{msg}");
    assert!(msg.contains("GB"), "{msg}");
    assert!(!e.is_internal());
}

// ---------------------------------------------------------------------------------------------
// 8. A constant load that pulls every pair apart
// ---------------------------------------------------------------------------------------------

#[test]
fn a_constant_load_that_pulls_every_pair_apart_is_diagnosed() {
    // A beam (no supports) resting on two ground pairs whose normal was typed reversed
    // ([0, −1]): its weight (constant, 1 kN per node) now *opens* both pairs, nothing holds
    // the beam, and there is no equilibrium at p = 0. The message must say so, name the pairs
    // and the load, and be a bad-input error (the user's model), not an internal one.
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(4.0, 0.0);
    m.add_frame(a, b, FrameSection::new(1e7, 1.0, 1.0));
    for (n, name) in [(a, "left"), (b, "right")] {
        m.add_contact_pair(
            ContactPairSpec::to_ground(n, [0.0, -1.0])
                .friction(0.3)
                .name(name),
        );
        m.add_load(LoadGroup::Constant, nodal(n, 0.0, -1e3));
    }
    m.add_load(LoadGroup::Variable, nodal(b, 1.0, 0.0));
    let e = analyze(&m, &SolveSettings::default()).expect_err("no equilibrium at p = 0");
    let msg = e.to_string();
    println!("{msg}");
    assert!(
        matches!(e, AnalysisError::PulledApart { .. }),
        "{msg} ({e:?})"
    );
    assert!(msg.contains("left") && msg.contains("right"), "{msg}");
    assert!(msg.contains("constant load"), "{msg}");
    assert!(!e.is_internal(), "{msg}");

    // The same reversed pair under a cantilever that its support holds: a well-defined
    // answer, the pair simply open. Hand value: the tip deflects P·L³/(3EI) = 1e3·64/3e7
    // downwards, which opens the reversed pair by that much.
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(4.0, 0.0);
    m.add_frame(a, b, FrameSection::new(1e7, 1.0, 1.0));
    m.fix(a);
    m.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, -1.0]).friction(0.3));
    m.add_load(LoadGroup::Constant, nodal(b, 0.0, -1e3));
    m.add_load(LoadGroup::Variable, nodal(b, 1.0, 0.0));
    let an = analyze(&m, &SolveSettings::default()).expect("held by its support");
    let pr = &an.solution.pairs[0];
    assert_eq!(pr.state, PairState::Open);
    assert!(close(pr.z_n, 1e3 * 64.0 / 3e7, 1e-9, 0.0), "{}", pr.z_n);
}

// ---------------------------------------------------------------------------------------------
// 6. Which errors are the program's fault
// ---------------------------------------------------------------------------------------------

#[test]
fn internal_failures_are_told_from_bad_input() {
    // The program's fault: recovery, equilibrium check, numerical failure of the linear
    // algebra. The user's: an invalid model, a mechanism, contact data refused, a load off the
    // path.
    let internal = [
        AnalysisError::Equilibrium {
            at: Place::Load(1.0),
            relative: 1.0,
        },
        AnalysisError::Recovery {
            at: Place::Stage { stage: 3, s: 0.25 },
            source: FemError::BadSolution("x_n is not finite".into()),
        },
        AnalysisError::Internal {
            what: "the bonded contact stiffness".into(),
            message: "Rnn has a negative diagonal entry".into(),
        },
    ];
    // A history's point is named by its stage and the stage's parameter, not by a
    // pseudo-time the user never wrote.
    let msg = internal[1].to_string();
    assert!(msg.contains("at s = 0.25 of stage 3:"), "{msg}");
    assert!(
        internal[0].to_string().contains("at p = 1 are"),
        "{}",
        internal[0]
    );
    for e in &internal {
        assert!(e.is_internal(), "{e}");
        assert!(
            e.to_string().contains("fault") || e.to_string().contains("internal"),
            "{e}"
        );
    }
    let bad_input = [
        AnalysisError::Unstable { free: vec![] },
        AnalysisError::NotOnPath {
            p: 2.0,
            end: "p = 1".into(),
        },
        AnalysisError::Model {
            message: "zero length".into(),
            source: FemError::ZeroLength {
                element: unilateral_fem::ElementId(0),
                a: unilateral_fem::NodeId(0),
                b: unilateral_fem::NodeId(1),
            },
        },
    ];
    for e in &bad_input {
        assert!(!e.is_internal(), "{e}");
    }
    // A real bad model through the whole chain: a zero-length element.
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(0.0, 0.0);
    m.add_frame(a, b, FrameSection::new(1.0, 1.0, 1.0));
    let e = analyze(&m, &SolveSettings::default()).unwrap_err();
    assert!(!e.is_internal(), "{e}");
}

#[test]
fn values_that_overflow_are_bad_input_not_infinities() {
    // E = 1e308 and A = 1e10 are finite, but E·A/L = 1e318 is not: the model is refused as
    // bad input naming the element, and no infinity reaches the contact zone or the results.
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(1.0, 0.0);
    m.add_frame(a, b, FrameSection::new(1e308, 1e10, 1.0));
    m.fix(a);
    m.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]));
    m.add_load(LoadGroup::Variable, nodal(b, 0.0, -1.0));
    let e = analyze(&m, &SolveSettings::default()).expect_err("overflow");
    let msg = e.to_string();
    assert!(
        matches!(
            e,
            AnalysisError::Model {
                source: FemError::Overflow { .. },
                ..
            }
        ),
        "{msg}"
    );
    assert!(
        msg.contains("element `0`") && msg.contains("stiffness"),
        "{msg}"
    );
    assert!(!e.is_internal());
}

#[test]
fn a_short_file_cannot_ask_for_unbounded_nodes() {
    // Two members of 2.1 million divisions each: each is within the per-member limit of
    // 4 million nodes, together they are not. The reader refuses the second one, naming the
    // file and the place, before building any (a 1 MB file of such members would ask for
    // 10¹¹ nodes).
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("many.toml");
    let mut text = String::from("[[sections]]\nname = \"s\"\nE = 1.0\nA = 1.0\nI = 1.0\n");
    for k in 0..2 {
        text.push_str(&format!(
            "[[members]]\nname = \"m{k}\"\nstart = [0.0, {k}.0]\nend = [1.0, {k}.0]\n\
             divisions = 2100000\nsection = \"s\"\n"
        ));
    }
    std::fs::write(&path, text).unwrap();
    let e = unilateral_io::read_model(&path).expect_err("too many nodes in all");
    let msg = e.to_string();
    assert!(msg.contains("many.toml:"), "{msg}");
    assert!(msg.contains("members[2].divisions"), "{msg}");
    assert!(msg.contains("in all"), "{msg}");
}

#[test]
fn the_round_off_filter_keeps_the_real_stiffness_of_a_fine_mesh() {
    // A cantilever (L = 10, EI = 1) of N elements with a ground pair at the tip: its normal
    // stiffness is 3EI/L³ = 0.003 whatever N (Hermite frames are exact), while the terms
    // that form it in the condensation are of the order of the element stiffness 12EI/l³,
    // 8N³ times larger. None of it may be taken for round-off. (The cancellation itself costs
    // about log10(8N³) digits: 9 for N = 500, so 1e-4 is the accuracy to ask there.)
    for n in [1, 10, 100, 500] {
        let mut m = Model::new();
        let nodes: Vec<_> = (0..=n)
            .map(|i| m.add_node(10.0 * i as f64 / n as f64, 0.0))
            .collect();
        for w in nodes.windows(2) {
            m.add_frame(w[0], w[1], FrameSection::new(1.0, 1e3, 1.0));
        }
        m.fix(nodes[0]);
        m.add_contact_pair(ContactPairSpec::to_ground(nodes[n], [0.0, 1.0]));
        let c = m.condense().unwrap();
        assert!(
            close(c.rnn[(0, 0)], 3e-3, 1e-4, 0.0),
            "{n} elements: Rnn = {}",
            c.rnn[(0, 0)]
        );
        // the axial (tangential) stiffness EA/L = 100
        assert!(
            close(c.rtt[(0, 0)], 100.0, 1e-6, 0.0),
            "{n}: {}",
            c.rtt[(0, 0)]
        );
    }
}
