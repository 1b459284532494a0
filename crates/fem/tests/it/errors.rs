//! Bad models are typed errors naming the offending ids; mechanisms name the free DOFs.

use unilateral_fem::{
    ContactPairSpec, DofLabel, ElementId, FemError, FrameSection, Load, LoadGroup, Model, NodeId,
    PlaneAnalysis, PlaneFormulation, PlaneMaterial,
};

fn sec() -> FrameSection {
    FrameSection::new(1.0, 1.0, 1.0)
}

#[test]
fn zero_length_and_repeated_nodes() {
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(0.0, 0.0);
    m.add_frame(a, b, sec());
    match m.condense().unwrap_err() {
        FemError::ZeroLength { element, .. } => assert_eq!(element, ElementId(0)),
        e => panic!("{e}"),
    }
    let mut m = Model::new();
    let n: Vec<_> = (0..3)
        .map(|i| m.add_node(i as f64, (i * i) as f64))
        .collect();
    m.add_plane(
        [n[0], n[1], n[2], n[1]],
        PlaneMaterial::new(1.0, 0.2),
        PlaneAnalysis::PlaneStress,
        PlaneFormulation::Q4,
    );
    match m.validate().unwrap_err() {
        FemError::RepeatedNode { element, node } => {
            assert_eq!((element, node), (ElementId(0), NodeId(1)))
        }
        e => panic!("{e}"),
    }
}

#[test]
fn non_positive_properties_and_poisson() {
    let cases: Vec<(FrameSection, &str)> = vec![
        (FrameSection::new(0.0, 1.0, 1.0), "E"),
        (FrameSection::new(1.0, -1.0, 1.0), "A"),
        (FrameSection::new(1.0, 1.0, 0.0), "I"),
        (FrameSection::new(f64::NAN, 1.0, 1.0), "E"),
    ];
    for (s, prop) in cases {
        let mut m = Model::new();
        let a = m.add_node(0.0, 0.0);
        let b = m.add_node(1.0, 0.0);
        m.add_frame(a, b, sec());
        m.add_frame(a, b, s);
        match m.validate().unwrap_err() {
            FemError::NonPositiveProperty {
                element, property, ..
            } => {
                assert_eq!((element, property), (ElementId(1), prop))
            }
            e => panic!("{e}"),
        }
    }
    let quad = |m: &mut Model| {
        [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| m.add_node(x, y))
    };
    for (mat, ok) in [
        (PlaneMaterial::new(1.0, 0.5), false),
        (PlaneMaterial::new(1.0, -1.0), false),
        (PlaneMaterial::new(1.0, 0.49), true),
        (PlaneMaterial::new(1.0, 0.2).with_thickness(0.0), false),
    ] {
        let mut m = Model::new();
        let n = quad(&mut m);
        m.add_plane(n, mat, PlaneAnalysis::PlaneStrain, PlaneFormulation::QM6);
        let r = m.validate();
        assert_eq!(r.is_ok(), ok, "{mat:?}: {r:?}");
        if let Err(e) = r {
            assert!(
                matches!(
                    e,
                    FemError::PoissonOutOfRange {
                        element: ElementId(0),
                        ..
                    } | FemError::NonPositiveProperty {
                        element: ElementId(0),
                        property: "thickness",
                        ..
                    }
                ),
                "{e}"
            );
        }
    }
    // clockwise node order
    let mut m = Model::new();
    let n = quad(&mut m);
    m.add_plane(
        [n[0], n[3], n[2], n[1]],
        PlaneMaterial::new(1.0, 0.2),
        PlaneAnalysis::PlaneStress,
        PlaneFormulation::Q4,
    );
    assert!(matches!(
        m.validate().unwrap_err(),
        FemError::DistortedElement {
            element: ElementId(0),
            ..
        }
    ));
}

#[test]
fn contact_pair_with_a_missing_node() {
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(1.0, 0.0);
    m.add_frame(a, b, sec());
    m.fix(a);
    m.add_contact_pair(ContactPairSpec::between(b, NodeId(7), [1.0, 0.0]).name("P7"));
    let e = m.condense().unwrap_err();
    match &e {
        FemError::MissingNode { what, node, .. } => {
            assert_eq!(*node, 7);
            assert!(
                what.contains("contact pair 0") && what.contains("P7"),
                "{what}"
            );
        }
        e => panic!("{e}"),
    }
    let mut m2 = Model::new();
    let a = m2.add_node(0.0, 0.0);
    m2.add_contact_pair(ContactPairSpec::to_ground(a, [0.0, 0.0]));
    assert!(matches!(
        m2.validate().unwrap_err(),
        FemError::BadContactPair { pair: 0, .. }
    ));
}

#[test]
fn unsupported_structure_names_free_dofs() {
    // a beam resting on one contact pair: rotation about the pair is a mechanism
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(2.0, 0.0);
    m.add_frame(a, b, sec());
    m.add_contact_pair(ContactPairSpec::to_ground(a, [0.0, 1.0]));
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: b,
            fx: 0.0,
            fy: -1.0,
            m: 0.0,
        },
    );
    let e = m.condense().unwrap_err();
    let msg = e.to_string();
    match e {
        FemError::Unstable {
            free, eigenvalue, ..
        } => {
            assert!(eigenvalue < 1e-12);
            // node 1 moves vertically, both rotate; nothing NaN
            assert!(
                free.iter()
                    .any(|d| d.node == NodeId(1) && d.dof == DofLabel::Uy),
                "{msg}"
            );
            assert!(free.iter().any(|d| d.dof == DofLabel::Rz), "{msg}");
            assert!(free.iter().all(|d| d.amplitude.is_finite()));
        }
        e => panic!("{e}"),
    }
    assert!(msg.contains("node 1 uy"), "{msg}");

    // no support at all: plane element floating
    let mut m = Model::new();
    let n = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| m.add_node(x, y));
    m.add_plane(
        n,
        PlaneMaterial::new(1.0, 0.2),
        PlaneAnalysis::PlaneStress,
        PlaneFormulation::QM6,
    );
    assert!(matches!(
        m.condense().unwrap_err(),
        FemError::Unstable { .. }
    ));

    // a node connected to nothing
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(1.0, 0.0);
    let lonely = m.add_node(5.0, 5.0);
    m.add_frame(a, b, sec());
    m.fix(a);
    m.add_load(
        LoadGroup::Constant,
        Load::Nodal {
            node: lonely,
            fx: 1.0,
            fy: 0.0,
            m: 0.0,
        },
    );
    match m.condense().unwrap_err() {
        FemError::Unstable { free, .. } => {
            assert!(
                free.iter().all(|d| d.node == lonely) && free.len() == 2,
                "{free:?}"
            )
        }
        e => panic!("{e}"),
    }

    // internal mechanism: three hinged bars in a row between two pins (collinear) → the middle
    // node is free across the line
    let mut m = Model::new();
    let n: Vec<_> = (0..3).map(|i| m.add_node(i as f64, 0.0)).collect();
    m.add_bar(n[0], n[1], sec());
    m.add_bar(n[1], n[2], sec());
    m.pin(n[0]);
    m.pin(n[2]);
    match m.condense().unwrap_err() {
        FemError::Unstable { free, .. } => {
            assert_eq!(free.len(), 1, "{free:?}");
            assert_eq!((free[0].node, free[0].dof), (n[1], DofLabel::Uy));
        }
        e => panic!("{e}"),
    }
}

#[test]
fn pair_on_a_supported_node_to_ground_is_rejected() {
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(1.0, 0.0);
    m.add_frame(a, b, sec());
    m.fix(a);
    m.add_contact_pair(ContactPairSpec::to_ground(a, [0.0, 1.0]));
    assert!(matches!(
        m.condense().unwrap_err(),
        FemError::LinkPlacement { pair: 0, .. }
    ));
}

#[test]
fn memory_needs_are_counted_without_overflow_and_refused_before_allocating() {
    // 8 doubles per m² (K_zz as R, (2m)², and its four m×m blocks) plus n_i × min(64, 2m):
    // m = 10, n_i = 100 → (800 + 2000)·8 bytes, by hand.
    assert_eq!(
        unilateral_fem::dense_condensation_bytes(10, 100),
        Some(22_400)
    );
    // a count that overflows u64 is no count, and is refused
    assert_eq!(
        unilateral_fem::dense_condensation_bytes(usize::MAX, 0),
        None
    );
    let e = unilateral_fem::check_memory("many pairs", None).unwrap_err();
    assert!(matches!(e, FemError::TooLarge { .. }), "{e}");
    assert!(e.to_string().contains("many pairs"), "{e}");
    assert!(!e.is_internal());
    // 1 EB is more than any machine this runs on has
    let e = unilateral_fem::check_memory("a lot", Some(1 << 60)).unwrap_err();
    assert!(e.to_string().contains("GB"), "{e}");
    // a need of a few bytes passes
    unilateral_fem::check_memory("a little", Some(1024)).unwrap();
}

#[test]
fn a_stiffness_that_overflows_names_the_element() {
    // 12·E·I/L³ with E·I = 1e300·1e10 overflows; the inputs themselves are finite.
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(1.0, 0.0);
    m.add_frame(a, b, FrameSection::new(1e300, 1.0, 1e10));
    m.fix(a);
    m.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]));
    match m.condense().unwrap_err() {
        FemError::Overflow { element, .. } => assert_eq!(element, Some(ElementId(0))),
        e => panic!("{e}"),
    }
}
