//! Node-to-segment pairs (the A side a weighted point of a segment) and nodes in several
//! pairs, against the flexibilities of springs worked out by hand.
//!
//! Every node below hangs on two springs to the ground (x and y, stiffness `k` per node), so
//! the link flexibilities add up: a link force `x` on B along `+n` and on the segment's
//! nodes along `−n` with the weights `(1 − ξ, ξ)` opens the link by
//! `x·(1/k_B + (1 − ξ)²/k_1 + ξ²/k_2)` (virtual work), which is the reference of every test.

use unilateral_fem::{
    ContactPairSpec, Endpoint, FemError, LinkValues, Load, LoadGroup, Model, NodeId, Spring,
    SpringKind, SupportDof,
};

/// A node at `(x, y)` held by an x and a y spring of stiffness `k` to the ground.
fn sprung(m: &mut Model, x: f64, y: f64, k: f64) -> NodeId {
    let n = m.add_node(x, y);
    for d in [[1.0, 0.0], [0.0, 1.0]] {
        m.add_spring(Spring {
            a: Endpoint::Ground,
            b: n,
            kind: SpringKind::Translational {
                direction: d,
                stiffness: k,
            },
        });
    }
    n
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale
}

/// B above the segment (a1, a2) at the weight ξ, with stiffnesses (k_B, k_1, k_2) and a
/// downward load P on B.
fn segment_model(xi: f64, kb: f64, k1: f64, k2: f64, p: f64) -> (Model, [NodeId; 3]) {
    let (mut m, [a1, a2, b]) = unpaired(xi, kb, k1, k2, p);
    m.add_contact_pair(ContactPairSpec::on_segment(a1, a2, xi, b, [0.0, 1.0]).friction(0.3));
    (m, [a1, a2, b])
}

/// The model of [`segment_model`] without its pair.
fn unpaired(xi: f64, kb: f64, k1: f64, k2: f64, p: f64) -> (Model, [NodeId; 3]) {
    let mut m = Model::new();
    let a1 = sprung(&mut m, 0.0, 0.0, k1);
    let a2 = sprung(&mut m, 2.0, 0.0, k2);
    let b = sprung(&mut m, 2.0 * xi, 0.0, kb);
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: b,
            fx: 0.0,
            fy: -p,
            m: 0.0,
        },
    );
    (m, [a1, a2, b])
}

/// R_nn = R_tt = 1/(1/k_B + (1 − ξ)²/k_1 + ξ²/k_2), R_nt = 0, and the bonded link force under
/// the load P on B is P·(1/k_B)/(1/k_B + (1 − ξ)²/k_1 + ξ²/k_2) (B's spring and the link share
/// P as two springs in parallel: the link's side has the flexibility of the segment). The
/// recovered displacements of a1, a2 are the link force times their weights over their
/// stiffness; the equilibrium check (moments of the weighted A point included) closes.
#[test]
fn segment_link_stiffness_and_load_by_hand() {
    let (kb, k1, k2, p) = (5.0, 3.0, 7.0, 2.0);
    for xi in [0.0, 0.25, 0.5, 0.9, 1.0] {
        let (m, [a1, a2, b]) = segment_model(xi, kb, k1, k2, p);
        let c = m.condense().unwrap();
        let s = (1.0 - xi) * (1.0 - xi) / k1 + xi * xi / k2;
        let r = 1.0 / (1.0 / kb + s);
        assert!(
            close(c.rnn[(0, 0)], r, r),
            "xi {xi}: {} vs {r}",
            c.rnn[(0, 0)]
        );
        assert!(close(c.rtt[(0, 0)], r, r), "xi {xi}");
        assert!(c.rnt[(0, 0)].abs() <= 1e-12 * r);
        let x = p / kb / (1.0 / kb + s);
        assert!(close(c.variable.normal[0], x, p), "xi {xi}");
        assert!(c.variable.tangential[0].abs() <= 1e-12 * p);
        let res = c.recover(&LinkValues::bonded(&c, 1.0)).unwrap();
        let u = &res.displacements;
        assert!(close(u[a1.0][1], -(1.0 - xi) * x / k1, p / k1), "xi {xi}");
        assert!(close(u[a2.0][1], -xi * x / k2, p / k2), "xi {xi}");
        // bonded: B moves with the A point
        let ua = (1.0 - xi) * u[a1.0][1] + xi * u[a2.0][1];
        assert!(close(u[b.0][1], ua, p / kb));
        assert!(res.equilibrium.relative() < 1e-12, "xi {xi}");
    }
}

/// When B is supported in translation the links go on a segment node (the one of larger
/// weight): the link then sees only the segment, R_nn = 1/((1 − ξ)²/k_1 + ξ²/k_2).
#[test]
fn segment_link_on_a_segment_node_when_b_is_supported() {
    let (k1, k2) = (3.0, 7.0);
    for xi in [0.2, 0.5, 0.7] {
        let mut m = Model::new();
        let a1 = sprung(&mut m, 0.0, 0.0, k1);
        let a2 = sprung(&mut m, 2.0, 0.0, k2);
        let b = m.add_node(2.0 * xi, 0.0);
        m.add_support(b, SupportDof::Ux);
        m.add_support(b, SupportDof::Uy);
        m.add_contact_pair(ContactPairSpec::on_segment(a1, a2, xi, b, [0.0, 1.0]));
        let c = m.condense().unwrap();
        let r = 1.0 / ((1.0 - xi) * (1.0 - xi) / k1 + xi * xi / k2);
        assert!(
            close(c.rnn[(0, 0)], r, r),
            "xi {xi}: {} vs {r}",
            c.rnn[(0, 0)]
        );
        assert!(close(c.rtt[(0, 0)], r, r));
    }
}

/// ξ = 0 is the node-to-node pair exactly (the same generalized DOFs, bit for bit).
#[test]
fn segment_at_its_first_node_is_node_to_node() {
    let build = |seg: bool| {
        let (mut m, [a1, a2, b]) = unpaired(0.0, 5.0, 3.0, 7.0, 2.0);
        let spec = if seg {
            ContactPairSpec::on_segment(a1, a2, 0.0, b, [0.0, 1.0])
        } else {
            ContactPairSpec::between(a1, b, [0.0, 1.0])
        };
        m.add_contact_pair(spec);
        m.condense().unwrap()
    };
    let (s, n) = (build(true), build(false));
    assert_eq!(s.rnn, n.rnn);
    assert_eq!(s.rtt, n.rtt);
    assert_eq!(s.variable.normal, n.variable.normal);
}

/// A node in two pairs (B against two nodes below it): the links are independent, and the
/// 2 × 2 flexibility is `[[1/k_B + 1/k_1, 1/k_B], [1/k_B, 1/k_B + 1/k_2]]` (B's spring is
/// shared by both link forces), so R_nn is its inverse.
#[test]
fn node_in_two_pairs_by_hand() {
    let (kb, k1, k2) = (5.0, 3.0, 7.0);
    let mut m = Model::new();
    let a1 = sprung(&mut m, 0.0, 0.0, k1);
    let a2 = sprung(&mut m, 1.0, 0.0, k2);
    let b = sprung(&mut m, 0.5, 0.0, kb);
    m.add_contact_pair(ContactPairSpec::between(a1, b, [0.0, 1.0]));
    m.add_contact_pair(ContactPairSpec::between(a2, b, [0.0, 1.0]));
    let c = m.condense().unwrap();
    let f = [
        [1.0 / kb + 1.0 / k1, 1.0 / kb],
        [1.0 / kb, 1.0 / kb + 1.0 / k2],
    ];
    let det = f[0][0] * f[1][1] - f[0][1] * f[1][0];
    let r = [
        [f[1][1] / det, -f[0][1] / det],
        [-f[1][0] / det, f[0][0] / det],
    ];
    for i in 0..2 {
        for j in 0..2 {
            assert!(close(c.rnn[(i, j)], r[i][j], r[0][0]), "{i}{j}");
            assert!(close(c.rtt[(i, j)], r[i][j], r[0][0]), "{i}{j}");
        }
    }
}

/// Two pairs between the same two nodes (in either order), or one node twice on the ground,
/// are refused by name; so is a weight outside [0, 1] and a segment repeating B.
#[test]
fn redundant_and_bad_segment_pairs_are_refused() {
    let mut m = Model::new();
    let a = sprung(&mut m, 0.0, 0.0, 1.0);
    let b = sprung(&mut m, 0.0, 0.0, 1.0);
    let c = sprung(&mut m, 1.0, 0.0, 1.0);
    let cases: Vec<(Vec<ContactPairSpec>, &str)> = vec![
        (
            vec![
                ContactPairSpec::between(a, b, [0.0, 1.0]),
                ContactPairSpec::between(b, a, [1.0, 0.0]),
            ],
            "as pair 0 (1) does",
        ),
        (
            vec![
                ContactPairSpec::to_ground(b, [0.0, 1.0]),
                ContactPairSpec::to_ground(b, [1.0, 0.0]),
            ],
            "node 1 and the ground",
        ),
        (
            vec![ContactPairSpec::on_segment(a, c, 1.5, b, [0.0, 1.0])],
            "must be in [0, 1], got 1.5",
        ),
        (
            vec![ContactPairSpec::on_segment(a, b, 0.5, b, [0.0, 1.0])],
            "repeats a node of the pair",
        ),
    ];
    for (pairs, want) in cases {
        let mut mm = m.clone();
        for p in pairs {
            mm.add_contact_pair(p);
        }
        let e = mm.validate().unwrap_err();
        assert!(matches!(e, FemError::BadContactPair { .. }), "{e}");
        assert!(e.to_string().contains(want), "{e}");
    }
}
