//! Named load cases: each case's contact load vector and the recovery at any case factors.
//!
//! The model is a propped cantilever: a frame from (0, 0) to (L, 0) clamped at x = 0, its tip
//! held by one contact pair to the ground (normal +y, so tangent +x). Bonded, the pair is a
//! rigid prop in both directions, and the hand values are the textbook ones (any table of
//! fixed-end actions, e.g. Gere & Timoshenko):
//!
//! * a uniform load `q` (distributed, or a body force per length): prop reaction `3qL/8`,
//!   clamp reaction `5qL/8`, clamp moment `qL²/8` (counter-clockwise on the beam);
//! * an axial force `F` at mid-span: the two halves are equal axial springs, the prop takes
//!   `F/2` (so `x_t = −F/2` on the tip);
//! * a uniform temperature change `ΔT`: the blocked elongation pushes the tip with
//!   `EAαΔT` (`x_t = −EAαΔT`);
//! * a settlement `δ` (downwards) of the clamp: the tip is pressed on the prop with
//!   `3EIδ/L³` (compression).

use unilateral_fem::{
    CaseId, Condensed, ContactPairSpec, DofLabel, FemError, FrameSection, Load, LoadFrame,
    LoadGroup, Model, NodeId, Results, SupportDof,
};

const L: f64 = 4.0;
const E: f64 = 100.0;
const A: f64 = 2.0;
const I: f64 = 1.0;
const ALPHA: f64 = 1e-3;
const Q: f64 = 2.0; // distributed, per length
const GAMMA: f64 = 1.0; // body force per length
const F: f64 = 5.0;
const DT: f64 = 10.0;
const DELTA: f64 = 0.01;

struct Propped {
    model: Model,
    cases: [CaseId; 4],
}

/// The propped cantilever with four cases: `dead` (distributed q and body force γ), `push`
/// (F along +x at mid-span), `heat` (ΔT), `settle` (the clamp goes down by δ).
fn propped() -> Propped {
    let mut model = Model::new();
    let n: Vec<NodeId> = (0..=4)
        .map(|i| model.add_node(L * i as f64 / 4.0, 0.0))
        .collect();
    let section = FrameSection::new(E, A, I).with_alpha(ALPHA);
    let elems: Vec<_> = n
        .windows(2)
        .map(|w| model.add_frame(w[0], w[1], section))
        .collect();
    model.fix(n[0]);
    model.add_contact_pair(ContactPairSpec::to_ground(n[4], [0.0, 1.0]).friction(0.5));
    let dead = model.add_case("dead");
    let push = model.add_case("push");
    let heat = model.add_case("heat");
    let settle = model.add_case("settle");
    for &e in &elems {
        model.add_case_load(
            dead,
            Load::Distributed {
                element: e,
                start: [0.0, -Q],
                end: [0.0, -Q],
                frame: LoadFrame::Global,
            },
        );
        model.add_case_load(
            dead,
            Load::BodyForce {
                element: e,
                force: [0.0, -GAMMA],
            },
        );
        model.add_case_load(
            heat,
            Load::Temperature {
                element: e,
                uniform: DT,
                gradient: 0.0,
            },
        );
    }
    model.add_case_load(
        push,
        Load::Nodal {
            node: n[2],
            fx: F,
            fy: 0.0,
            m: 0.0,
        },
    );
    model.add_case_load(
        settle,
        Load::Settlement {
            node: n[0],
            dof: SupportDof::Uy,
            value: -DELTA,
        },
    );
    Propped {
        model,
        cases: [dead, push, heat, settle],
    }
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale
}

// Reference: the fixed-end actions of the module comment, by hand.
#[test]
fn every_case_has_its_own_contact_load_vector() {
    let p = propped();
    assert_eq!(p.model.cases(), ["dead", "push", "heat", "settle"]);
    assert_eq!(p.model.case("heat"), Some(p.cases[2]));
    let c = p.model.condense().unwrap();
    assert_eq!(c.case_names, ["dead", "push", "heat", "settle"]);
    let expected = [
        (3.0 * (Q + GAMMA) * L / 8.0, 0.0),
        (0.0, -F / 2.0),
        (0.0, -E * A * ALPHA * DT),
        (3.0 * E * I * DELTA / L.powi(3), 0.0),
    ];
    for (k, (xn, xt)) in expected.into_iter().enumerate() {
        let v = &c.cases[k];
        let scale = xn.abs().max(xt.abs());
        assert!(close(v.normal[0], xn, scale), "{k}: {v:?} vs {xn}");
        assert!(close(v.tangential[0], xt, scale), "{k}: {v:?} vs {xt}");
    }
    // No case is named constant or variable: the paper's two groups are zero.
    assert_eq!(c.constant.normal, [0.0]);
    assert_eq!(c.variable.tangential, [0.0]);
    assert_eq!(c.case_resultant(p.cases[0]), [0.0, -(Q + GAMMA) * L]);
    assert_eq!(c.case_resultant(p.cases[1]), [F, 0.0]);
}

fn reaction(r: &Results, node: usize, dof: DofLabel) -> f64 {
    r.reactions
        .iter()
        .find(|x| x.node.0 == node && x.dof.label() == Some(dof))
        .unwrap()
        .value
}

// Reference: the fixed-end actions of the module comment (superposed by hand) for the
// reactions, and the equilibrium of the whole structure.
#[test]
fn recovery_at_case_factors_matches_hand_values() {
    let p = propped();
    let c = p.model.condense().unwrap();
    let factors = [2.0, 1.0, 0.0, 0.0];
    let r = c.recover_at(&factors, &c.bonded_at(&factors, 0.5)).unwrap();
    assert_eq!(r.p, 0.5);
    let q = 2.0 * (Q + GAMMA);
    let s = q * L;
    assert!(close(reaction(&r, 0, DofLabel::Uy), 5.0 * q * L / 8.0, s));
    assert!(close(reaction(&r, 0, DofLabel::Ux), -F / 2.0, s));
    assert!(close(reaction(&r, 0, DofLabel::Rz), q * L * L / 8.0, s * L));
    // the bonded tip does not move
    assert!(r.displacements[4][0].abs() < 1e-12 && r.displacements[4][1].abs() < 1e-12);
    assert!(r.equilibrium.relative() < 1e-12);
    // the heated, clamped and propped beam: axial force −EAαΔT in every element
    let r = c
        .recover_at(
            &[0.0, 0.0, 1.0, 0.0],
            &c.bonded_at(&[0.0, 0.0, 1.0, 0.0], 0.0),
        )
        .unwrap();
    let n_axial = E * A * ALPHA * DT;
    for line in &r.lines {
        for d in &line.diagram {
            assert!(close(d.n, -n_axial, n_axial), "{:?}", d);
        }
    }
}

// Reference: linearity of the bonded structure (superposition): the results at factors φ are
// Σ φ_k·(the results of case k alone at factor 1).
#[test]
fn recovery_at_case_factors_is_the_superposition_of_the_cases() {
    let p = propped();
    let c = p.model.condense().unwrap();
    let factors = [1.5, -0.7, 2.0, 0.3];
    let at = |f: &[f64]| c.recover_at(f, &c.bonded_at(f, 0.0)).unwrap();
    let all = at(&factors);
    let alone: Vec<Results> = (0..4)
        .map(|k| {
            let mut e = [0.0; 4];
            e[k] = 1.0;
            at(&e)
        })
        .collect();
    let combine = |get: &dyn Fn(&Results) -> Vec<f64>| -> Vec<f64> {
        let parts: Vec<Vec<f64>> = alone.iter().map(get).collect();
        (0..parts[0].len())
            .map(|i| parts.iter().zip(&factors).map(|(v, f)| f * v[i]).sum())
            .collect()
    };
    type Part = fn(&Results) -> Vec<f64>;
    let checks: [(&str, Part); 3] = [
        ("displacements", |r| {
            r.displacements.iter().flatten().copied().collect()
        }),
        ("reactions", |r| {
            r.reactions.iter().map(|x| x.value).collect()
        }),
        ("end forces", |r| {
            r.lines.iter().flat_map(|l| l.end_forces).collect()
        }),
    ];
    for (what, get) in &checks {
        let want = combine(get);
        let got = get(&all);
        let scale = want.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(scale > 0.0, "{what}");
        for (g, w) in got.iter().zip(&want) {
            assert!(close(*g, *w, scale), "{what}: {g} vs {w}");
        }
    }
}

// Reference: the paper's load `R_c + p·R_v` is the cases `constant` at 1 and `variable` at
// p; the groups of `add_load` are those cases, so `recover` and `recover_at` agree and the
// group vectors are the case vectors.
#[test]
fn the_two_groups_are_the_cases_constant_and_variable() {
    let mut model = Model::new();
    let a = model.add_node(0.0, 0.0);
    let b = model.add_node(2.0, 0.0);
    let m = model.add_node(1.0, 0.0);
    let s = FrameSection::new(1.0, 1.0, 1.0);
    model.add_frame(a, m, s);
    model.add_frame(m, b, s);
    model.fix(a);
    model.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]).friction(0.3));
    model.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: m,
            fx: 1.0,
            fy: -2.0,
            m: 0.0,
        },
    );
    let other = model.add_case("wind");
    model.add_case_load(
        other,
        Load::Nodal {
            node: m,
            fx: 3.0,
            fy: 0.0,
            m: 0.0,
        },
    );
    model.add_load(
        LoadGroup::Constant,
        Load::Nodal {
            node: b,
            fx: 0.0,
            fy: -1.0,
            m: 0.5,
        },
    );
    assert_eq!(model.cases(), ["variable", "wind", "constant"]);
    let c = model.condense().unwrap();
    assert_eq!(c.cases[0], c.variable);
    assert_eq!(c.cases[2], c.constant);
    // by hand: the tip link carries the whole tip force (the tip does not move when bonded),
    // and the counter-clockwise tip moment M of the propped cantilever lifts the tip, which
    // the prop holds down with 3M/(2L): x_n = 1 − 3·0.5/(2·2) = 0.625
    assert!((c.constant.normal[0] - 0.625).abs() < 1e-12);
    let p = 0.75;
    let sol = unilateral_fem::LinkValues::bonded(&c, p);
    let old = c.recover(&sol).unwrap();
    let new = c.recover_at(&[p, 0.0, 1.0], &sol).unwrap();
    assert_eq!(old.displacements, new.displacements);
    assert_eq!(old.reactions, new.reactions);
    assert_eq!(old.lines, new.lines);
}

// Reference: the recovery's contract (one finite factor per case).
#[test]
fn bad_factors_are_refused() {
    let p = propped();
    let c: Condensed = p.model.condense().unwrap();
    let sol = c.bonded_at(&[1.0, 0.0, 0.0, 0.0], 0.0);
    for bad in [vec![1.0], vec![1.0, f64::NAN, 0.0, 0.0]] {
        match c.recover_at(&bad, &sol) {
            Err(FemError::BadSolution(msg)) => assert!(!msg.is_empty()),
            other => panic!("{other:?}"),
        }
    }
}
