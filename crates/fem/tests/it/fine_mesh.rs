//! Finely divided members are not reported as mechanisms, and mechanisms of many elements
//! still are (the stability test of the bonded structure, `factorize` in src/condense.rs).
//!
//! A smallest scaled eigenvalue below round-off cannot tell a mechanism from a stable member
//! of many short elements (a pinned–pinned beam of N elements has λ ≈ (π/N)⁴/12); the element
//! forces of the lowest modes can. The references are closed forms (PL³/48EI, 3EI/L³) and the
//! kinematics of the mechanisms by hand.

use unilateral_fem::{
    ContactPairSpec, DofLabel, Endpoint, FemError, FrameSection, LinkValues, Load, LoadGroup,
    Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial, Releases, Spring, SpringKind,
    SupportDof,
};

const EI: f64 = 2.1e7;
const EA: f64 = 4.2e9;
/// Unit round-off of double precision.
const U: f64 = f64::EPSILON / 2.0;

fn sec() -> FrameSection {
    FrameSection::new(2.1e11, EA / 2.1e11, EI / 2.1e11)
}

/// A straight member along x from 0 to `len` in `n` frame elements; `released` lists the
/// element ends (element index, end) that are hinged.
fn member(m: &mut Model, len: f64, n: usize, released: &[(usize, bool)]) -> Vec<NodeId> {
    let ids: Vec<_> = (0..=n)
        .map(|i| m.add_node(len * i as f64 / n as f64, 0.0))
        .collect();
    for (k, w) in ids.windows(2).enumerate() {
        let rel = Releases {
            start: released.contains(&(k, false)),
            end: released.contains(&(k, true)),
        };
        m.add_frame_with_releases(w[0], w[1], sec(), rel);
    }
    ids
}

fn pinned_pinned(n: usize, load: f64) -> (Model, Vec<NodeId>) {
    let mut m = Model::new();
    let ids = member(&mut m, 10.0, n, &[]);
    m.pin(ids[0]);
    m.add_support(ids[n], SupportDof::Uy);
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: ids[n / 2],
            fx: 0.0,
            fy: -load,
            m: 0.0,
        },
    );
    (m, ids)
}

#[test]
fn fine_pinned_beams_are_not_mechanisms() {
    // Accepted: N = 2000 (λ = 2.5e-13 ≥ 1e-13). Reference PL³/(48EI); the tolerance is the
    // error bound u/λ the stability test promises (4.4e-4; the deflection is measured 1.9e-5
    // off, the round-off of the solve amplified by the conditioning, not a discretization
    // error: cubic frame elements are exact for a point load at a node).
    let (p, len) = (1.0e4, 10.0_f64);
    let (m, ids) = pinned_pinned(2000, p);
    let c = m.condense().unwrap();
    let lambda = c.stats.smallest_eigenvalue;
    assert!(
        lambda < 1e-12,
        "{lambda}: the test must exercise a fine mesh"
    );
    let r = c.recover(&LinkValues::bonded(&c, 1.0)).unwrap();
    let v = r.displacements[ids[1000].0][1];
    let exact = -p * len.powi(3) / (48.0 * EI);
    assert!(
        ((v - exact) / exact).abs() <= U / lambda,
        "{v} vs {exact} (bound {})",
        U / lambda
    );
    // Refused, but not as a mechanism: N = 5000, 20000, 100000. The solve would be wrong by
    // 3e-3, 130 % and 100 % of the deflection (measured), so no tolerance would justify an
    // answer; the error says why and what to do, and the lowest mode's element forces
    // (≈ (π/N)²/25 of the element stiffness) are far above the round-off of a mechanism.
    for n in [5000, 20000, 100_000] {
        let (m, _) = pinned_pinned(n, p);
        match m.condense() {
            Err(FemError::IllConditioned {
                eigenvalue,
                estimated_error,
                element_force_ratio,
            }) => {
                assert!((0.0..1e-13).contains(&eigenvalue), "{n}: {eigenvalue}");
                assert!(estimated_error > 1e-3 && estimated_error <= 1.0, "{n}");
                let smooth = (std::f64::consts::PI / n as f64).powi(2) / 25.0;
                assert!(
                    element_force_ratio > 0.3 * smooth && element_force_ratio < 3.0 * smooth,
                    "{n}: ρ = {element_force_ratio} vs (π/N)²/25 = {smooth}"
                );
                let e = m.condense().unwrap_err();
                assert!(e.is_internal(), "{e}");
                let msg = e.to_string();
                assert!(msg.contains("fewer, longer elements"), "{msg}");
                assert!(!msg.contains("unstable"), "{msg}");
            }
            Err(e) => panic!("{n}: {e}"),
            Ok(_) => panic!("{n}: solved although the solve has no correct digit"),
        }
    }
}

/// The DOF list of an `Unstable` error.
fn unstable(m: &Model) -> Vec<(NodeId, DofLabel, f64)> {
    match m.condense() {
        Err(FemError::Unstable { free, .. }) => {
            free.iter().map(|f| (f.node, f.dof, f.amplitude)).collect()
        }
        Err(e) => panic!("not reported as a mechanism: {e}"),
        Ok(_) => panic!("a mechanism was accepted"),
    }
}

fn amplitude(free: &[(NodeId, DofLabel, f64)], node: NodeId, dof: DofLabel) -> f64 {
    free.iter()
        .find(|f| f.0 == node && f.1 == dof)
        .map_or(0.0, |f| f.2)
}

#[test]
fn a_beam_on_one_pin_rotates_however_finely_divided() {
    // Rigid rotation θ about the pin at x = 0: uy = θ·x, rz = θ, ux = 0. Amplitudes are
    // relative to the largest, uy at x = L = 10: uy(x) = x/10, rz = 1/10 (1/m). The mode is
    // the null vector up to the round-off that mixes it with the lowest deforming modes
    // (measured 1.4e-3 at N = 20000, 1e-6 at 1000): tolerance 1e-2.
    for n in [1, 4, 5000, 20000] {
        let mut m = Model::new();
        let ids = member(&mut m, 10.0, n, &[]);
        m.pin(ids[0]);
        let free = unstable(&m);
        let end = amplitude(&free, ids[n], DofLabel::Uy);
        assert!((end.abs() - 1.0).abs() < 1e-2, "{n}: {end}");
        let sign = end.signum();
        for &i in &[0, n / 2, n] {
            let rz = sign * amplitude(&free, ids[i], DofLabel::Rz);
            assert!((rz - 0.1).abs() < 1e-2 * 0.1, "{n}, node {i}: rz {rz}");
            let uy = sign * amplitude(&free, ids[i], DofLabel::Uy);
            let x = 10.0 * i as f64 / n as f64;
            assert!((uy - x / 10.0).abs() < 1e-2, "{n}, node {i}: uy {uy}");
            assert_eq!(amplitude(&free, ids[i], DofLabel::Ux), 0.0, "{n}");
        }
    }
}

#[test]
fn a_hinge_between_two_pinned_members_is_a_mechanism_however_finely_divided() {
    // Two collinear members pinned at their far ends and hinged to each other (both element
    // ends released at the middle node): the middle node moves across the line, each member
    // turns rigidly about its pin, uy(x) = x/5 then (10 − x)/5, rz = ±1/5. With a roller
    // under the hinge the same model is stable. Tolerance 1e-2 as for the single pin.
    for n in [1, 2, 2500, 10000] {
        let build = |roller: bool| {
            let mut m = Model::new();
            let ids = member(&mut m, 10.0, 2 * n, &[(n - 1, true), (n, false)]);
            m.pin(ids[0]);
            m.pin(ids[2 * n]);
            if roller {
                m.add_support(ids[n], SupportDof::Uy);
            }
            (m, ids)
        };
        let (m, ids) = build(false);
        let free = unstable(&m);
        let mid = amplitude(&free, ids[n], DofLabel::Uy);
        assert!((mid.abs() - 1.0).abs() < 1e-2, "{n}: {mid}");
        let q = ids[n / 2];
        let uy = mid.signum() * amplitude(&free, q, DofLabel::Uy);
        let x = 10.0 * (n / 2) as f64 / (2 * n) as f64;
        assert!((uy - x / 5.0).abs() < 1e-2, "{n}: {uy}");
        let rz0 = mid.signum() * amplitude(&free, ids[0], DofLabel::Rz);
        let rz1 = mid.signum() * amplitude(&free, ids[2 * n], DofLabel::Rz);
        assert!(
            (rz0 - 0.2).abs() < 2e-3 && (rz1 + 0.2).abs() < 2e-3,
            "{n}: {rz0} {rz1}"
        );
        if n <= 2500 {
            // the stable counterpart: 2·2500 elements of 1 mm on 5 m spans are accepted
            let (m, _) = build(true);
            m.condense().unwrap();
        }
    }
}

fn block(nx: usize, ny: usize, x_support: bool) -> (Model, usize) {
    let mut m = Model::new();
    let id = |i: usize, j: usize| NodeId(j * (nx + 1) + i);
    for j in 0..=ny {
        for i in 0..=nx {
            m.add_node(2.0 * i as f64 / nx as f64, j as f64 / ny as f64);
        }
    }
    for j in 0..ny {
        for i in 0..nx {
            m.add_plane(
                [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
                PlaneMaterial::new(2.1e11, 0.3),
                PlaneAnalysis::PlaneStress,
                PlaneFormulation::QM6,
            );
        }
    }
    for i in 0..=nx {
        m.add_support(id(i, 0), SupportDof::Uy);
    }
    if x_support {
        m.add_support(id(0, 0), SupportDof::Ux);
    }
    (m, (nx + 1) * (ny + 1))
}

#[test]
fn a_plane_block_without_support_in_x_slides() {
    // Rollers (uy) along the bottom only: the rigid translation in x, every node ux = ±1 and
    // nothing else. One support in x makes it stable.
    for (nx, ny) in [(1, 1), (2, 2), (100, 50)] {
        let (m, nodes) = block(nx, ny, false);
        let free = unstable(&m);
        assert_eq!(free.len(), nodes, "{nx}x{ny}: {free:?}");
        let s = free[0].2.signum();
        for f in &free {
            assert_eq!(f.1, DofLabel::Ux);
            assert!((s * f.2 - 1.0).abs() < 1e-9, "{f:?}");
        }
        block(nx, ny, true).0.condense().unwrap();
    }
}

#[test]
fn a_cantilever_keeps_its_tip_stiffness_as_finely_divided_as_accepted() {
    // A cantilever of N elements with a contact pair at its tip: Rnn = 3EI/L³ (the tip
    // stiffness). The Schur complement cancels it out of terms 8N³ times larger (12EI/h³),
    // so the round-off filter and the solve both meet it: at N = 2000 the ratio to the
    // magnitude the filter measures is 1.7e-14, nineteen times above its threshold 8u, and
    // the value is right to the order u/λ of the stability test's bound (the Schur complement
    // inherits the error of the solves: measured 1.9e-4 = 1.1·u/λ at N = 2000, where λ =
    // 6.2e-13; the tolerance is 4·u/λ). At N = 10⁵ the ratio of R to its terms is 1.25e-16,
    // below round-off: the structure is refused as ill-conditioned, so no zeroed (or wrong)
    // stiffness is ever returned.
    let len = 10.0;
    let build = |n: usize| {
        let mut m = Model::new();
        let ids = member(&mut m, len, n, &[]);
        m.fix(ids[0]);
        m.add_contact_pair(ContactPairSpec::to_ground(ids[n], [0.0, 1.0]));
        m
    };
    let exact = 3.0 * EI / len.powi(3);
    for n in [1, 10, 2000] {
        let c = build(n).condense().unwrap();
        let lambda = c.stats.smallest_eigenvalue;
        let rnn = c.rnn[(0, 0)];
        assert!(
            ((rnn - exact) / exact).abs() <= 1e-12_f64.max(4.0 * U / lambda),
            "{n}: {rnn} vs {exact}, λ = {lambda}"
        );
        assert_eq!(c.stats.round_off_zeroed, 0, "{n}");
    }
    match build(100_000).condense() {
        Err(FemError::IllConditioned { .. }) => {}
        Err(e) => panic!("{e}"),
        Ok(c) => panic!("accepted with Rnn = {}", c.rnn[(0, 0)]),
    }
}

#[test]
fn a_soft_spring_behind_a_stiff_bar_keeps_its_stiffness() {
    // A contact pair on node B, a bar of axial stiffness k₁ from B down to C, a spring k₂ = 1
    // from C to the ground: the pair's normal stiffness is the series k₁k₂/(k₁ + k₂) (hand
    // calculation), which the Schur complement leaves at k₂/(2k₁) of its terms. The round-off
    // filter keeps it for contrasts k₁/k₂ up to 10¹³ (the value has then about 3 correct
    // digits: its terms are 2·10¹³ and their round-off is a few units of 2·10¹³·u ≈ 2e-3).
    // The tangential stiffness is zero in exact arithmetic (a bar gives no stiffness across
    // itself) and is returned as 0.
    for contrast in [1.0, 1e6, 1e11, 1e13] {
        let mut m = Model::new();
        let b = m.add_node(0.0, 1.0);
        let c = m.add_node(0.0, 0.0);
        m.add_bar(c, b, FrameSection::new(contrast, 1.0, 1.0));
        m.add_support(c, SupportDof::Ux);
        m.add_spring(Spring {
            a: Endpoint::Ground,
            b: c,
            kind: SpringKind::Translational {
                direction: [0.0, 1.0],
                stiffness: 1.0,
            },
        });
        m.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]));
        let cz = m.condense().unwrap();
        let exact = contrast / (contrast + 1.0);
        let tol = 8.0 * U * 2.0 * contrast;
        let rnn = cz.rnn[(0, 0)];
        assert!(
            (rnn - exact).abs() <= tol.max(4.0 * U),
            "{contrast}: {rnn} vs {exact}"
        );
        assert_eq!(cz.rtt[(0, 0)], 0.0, "{contrast}");
    }
}

#[test]
fn a_beam_turning_about_a_pin_has_no_normal_stiffness_at_its_bearing() {
    // A beam pinned at x = 0 on a bearing (ground pair, normal y) at x = L: with the bearing a
    // rigid link the beam is statically determinate, and a normal displacement of the bearing
    // turns it rigidly about the pin, so Rnn = 0 exactly (hand kinematics); Rtt = EA/L (the
    // bar along x), Rnt = 0. Round-off leaves Rnn at a fraction of its terms that grows with
    // the number of elements (2.5e-16 at 8, 3e-14 at 2000 of the terms next to the pair),
    // so the filter must measure the round-off of the solves, not just those terms.
    let len = 10.0;
    for n in [1, 2, 4, 5, 8, 10, 20, 200, 2000] {
        let mut m = Model::new();
        let ids = member(&mut m, len, n, &[]);
        m.pin(ids[0]);
        m.add_contact_pair(ContactPairSpec::to_ground(ids[n], [0.0, 1.0]).friction(0.25));
        let c = m.condense().unwrap();
        assert_eq!(c.rnn[(0, 0)], 0.0, "{n}");
        assert_eq!(c.rnt[(0, 0)], 0.0, "{n}");
        let rtt = c.rtt[(0, 0)];
        assert!(((rtt - EA / len) / (EA / len)).abs() < 1e-9, "{n}: {rtt}");
    }
}

#[test]
fn the_verdicts_do_not_depend_on_the_units() {
    // The same models in other units: lengths × sl, forces × sf (so E × sf/sl², A × sl²,
    // I × sl⁴). Every measure the stability test and the round-off filter use is relative to
    // the element's own diagonal or to the terms of the entry, so the verdicts are the same,
    // and the element-force ratio of the smooth mode of a fine beam (which is not round-off)
    // agrees to the accuracy of the computed mode at this conditioning (u/λ = 1.7e-2 bounds
    // it; measured 1.2e-6): tolerance 1e-4.
    let scaled = |sl: f64, sf: f64| {
        FrameSection::new(2.1e11 * sf / (sl * sl), 2e-2 * sl * sl, 1e-4 * sl.powi(4))
    };
    // at the far end: nothing (a mechanism), a roller, or a contact pair (a bearing)
    #[derive(Clone, Copy)]
    enum End {
        Free,
        Roller,
        Bearing,
    }
    let build = |sl: f64, sf: f64, n: usize, end: End| {
        let mut m = Model::new();
        let ids: Vec<_> = (0..=n)
            .map(|i| m.add_node(10.0 * sl * i as f64 / n as f64, 0.0))
            .collect();
        for w in ids.windows(2) {
            m.add_frame(w[0], w[1], scaled(sl, sf));
        }
        m.pin(ids[0]);
        match end {
            End::Free => {}
            End::Roller => m.add_support(ids[n], SupportDof::Uy),
            End::Bearing => {
                m.add_contact_pair(ContactPairSpec::to_ground(ids[n], [0.0, 1.0]));
            }
        }
        m
    };
    let rho = |m: &Model| match m.condense() {
        Err(FemError::IllConditioned {
            element_force_ratio,
            ..
        }) => element_force_ratio,
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("accepted"),
    };
    let rho0 = rho(&build(1.0, 1.0, 5000, End::Roller));
    for (sl, sf) in [
        (1e-3, 1e3),
        (1e3, 1e-3),
        (1e-12, 1.0),
        (1.0, 1e12),
        (1e6, 1e-12),
    ] {
        let r = rho(&build(sl, sf, 5000, End::Roller));
        assert!(((r - rho0) / rho0).abs() < 1e-4, "{sl} {sf}: {r} vs {rho0}");
        assert!(
            matches!(
                build(sl, sf, 5000, End::Free).condense(),
                Err(FemError::Unstable { .. })
            ),
            "{sl} {sf}"
        );
        let c = build(sl, sf, 2000, End::Bearing).condense().unwrap();
        assert_eq!(c.rnn[(0, 0)], 0.0, "{sl} {sf}");
    }
}
