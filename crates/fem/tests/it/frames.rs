//! Frame, bar, spring and support tests against textbook closed forms.
#![allow(clippy::needless_range_loop)]

use unilateral_fem::{
    Endpoint, FrameSection, LinkValues, Load, LoadFrame, LoadGroup, Model, Releases, Results,
    Spring, SpringKind, SupportDof,
};
use unilateral_oracle::fixtures::example1 as ex1;

fn solve(model: &Model, p: f64) -> Results {
    let c = model.condense().unwrap();
    let r = c.recover(&LinkValues::bonded(&c, p)).unwrap();
    assert!(r.equilibrium.relative() < 1e-10, "{:?}", r.equilibrium);
    r
}

fn close(a: f64, b: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol * b.abs().max(1e-300) || (a - b).abs() < 1e-14,
        "{a} != {b}"
    );
}

fn reaction(r: &Results, node: usize, dof: SupportDof) -> f64 {
    r.reactions
        .iter()
        .find(|x| x.node.0 == node && x.dof == dof)
        .unwrap()
        .value
}

/// Beam along x from 0 to `len` in `n` elements; returns node ids.
fn beam(model: &mut Model, len: f64, n: usize, s: FrameSection) -> Vec<unilateral_fem::NodeId> {
    let ids: Vec<_> = (0..=n)
        .map(|i| model.add_node(len * i as f64 / n as f64, 0.0))
        .collect();
    for w in ids.windows(2) {
        model.add_frame(w[0], w[1], s);
    }
    ids
}

#[test]
fn cantilever_tip_deflection_and_rotation() {
    let (e, i, l, p, mo) = (210.0, 3.0, 4.0, 2.0, 5.0);
    for n in [1, 4] {
        let mut m = Model::new();
        let ids = beam(&mut m, l, n, FrameSection::new(e, 1.0, i));
        m.fix(ids[0]);
        let tip = *ids.last().unwrap();
        m.add_load(
            LoadGroup::Variable,
            Load::Nodal {
                node: tip,
                fx: 0.0,
                fy: -p,
                m: 0.0,
            },
        );
        m.add_load(
            LoadGroup::Constant,
            Load::Nodal {
                node: tip,
                fx: 0.0,
                fy: 0.0,
                m: mo,
            },
        );
        let r = solve(&m, 1.0);
        let d = r.displacements[tip.0];
        // δ = −PL³/3EI + ML²/2EI, θ = −PL²/2EI + ML/EI
        close(
            d[1],
            -p * l.powi(3) / (3.0 * e * i) + mo * l * l / (2.0 * e * i),
            1e-12,
        );
        close(d[2], -p * l * l / (2.0 * e * i) + mo * l / (e * i), 1e-12);
        // clamped moment reaction: P·L − M (counter-clockwise)
        close(reaction(&r, 0, SupportDof::Rz), p * l - mo, 1e-12);
        close(reaction(&r, 0, SupportDof::Uy), p, 1e-12);
        // moment diagram at the wall: hogging −PL + M
        close(r.lines[0].diagram[0].m, -p * l + mo, 1e-12);
    }
}

#[test]
fn fixed_end_moments_uniform_and_linear_load() {
    let (l, q) = (6.0, 2.0);
    // uniform downward load: FEM = qL²/12, midspan moment qL²/24
    let mut m = Model::new();
    let ids = beam(&mut m, l, 1, FrameSection::new(1.0, 1.0, 1.0));
    m.fix(ids[0]);
    m.fix(ids[1]);
    m.add_load(
        LoadGroup::Variable,
        Load::Distributed {
            element: unilateral_fem::ElementId(0),
            start: [0.0, -q],
            end: [0.0, -q],
            frame: LoadFrame::Global,
        },
    );
    let r = solve(&m, 1.0);
    close(reaction(&r, 0, SupportDof::Rz), q * l * l / 12.0, 1e-12);
    close(reaction(&r, 1, SupportDof::Rz), -q * l * l / 12.0, 1e-12);
    close(reaction(&r, 0, SupportDof::Uy), q * l / 2.0, 1e-12);
    let dg = &r.lines[0].diagram;
    close(dg[0].m, -q * l * l / 12.0, 1e-12);
    close(dg[5].m, q * l * l / 24.0, 1e-12);
    close(dg[10].m, -q * l * l / 12.0, 1e-12);
    close(dg[0].q, q * l / 2.0, 1e-12);

    // triangular load 0 → q (downward): FEM qL²/30 at the zero end, qL²/20 at the other;
    // vertical reactions 3qL/20 and 7qL/20. Given in local components on a beam in 3 parts.
    let mut m = Model::new();
    let ids = beam(&mut m, l, 3, FrameSection::new(1.0, 1.0, 1.0));
    m.fix(ids[0]);
    m.fix(ids[3]);
    for k in 0..3 {
        let (a, b) = (q * k as f64 / 3.0, q * (k + 1) as f64 / 3.0);
        m.add_load(
            LoadGroup::Constant,
            Load::Distributed {
                element: unilateral_fem::ElementId(k),
                start: [0.0, -a],
                end: [0.0, -b],
                frame: LoadFrame::Local,
            },
        );
    }
    let r = solve(&m, 0.0);
    close(reaction(&r, 0, SupportDof::Rz), q * l * l / 30.0, 1e-12);
    close(reaction(&r, 3, SupportDof::Rz), -q * l * l / 20.0, 1e-12);
    close(reaction(&r, 0, SupportDof::Uy), 3.0 * q * l / 20.0, 1e-12);
    close(reaction(&r, 3, SupportDof::Uy), 7.0 * q * l / 20.0, 1e-12);
}

#[test]
fn two_span_continuous_beam_reactions() {
    // spans of 2, unit downward load in the middle of the right span: R = −3/32, 11/16, 13/32
    // (three-moment equation; Example 1's Rv_n, the oracle's fixture)
    let mut m = Model::new();
    let ids = beam(
        &mut m,
        4.0,
        4,
        FrameSection::new(ex1::beam::E, ex1::beam::AREA, ex1::beam::INERTIA),
    );
    m.pin(ids[0]);
    m.add_support(ids[2], SupportDof::Uy);
    m.add_support(ids[4], SupportDof::Uy);
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: ids[3],
            fx: 0.0,
            fy: -1.0,
            m: 0.0,
        },
    );
    let r = solve(&m, 1.0);
    close(reaction(&r, 0, SupportDof::Uy), ex1::RV_N[0], 1e-12);
    close(reaction(&r, 2, SupportDof::Uy), ex1::RV_N[1], 1e-12);
    close(reaction(&r, 4, SupportDof::Uy), ex1::RV_N[2], 1e-12);
}

#[test]
fn thermal_gradient_and_uniform_change_on_clamped_beam() {
    let (e, a, i, h, alpha, dt, grad) = (200.0, 3.0, 2.0, 0.5, 1e-3, 10.0, 20.0);
    let mut m = Model::new();
    let ids = beam(
        &mut m,
        5.0,
        3,
        FrameSection::new(e, a, i).with_depth(h).with_alpha(alpha),
    );
    m.fix(ids[0]);
    m.fix(ids[3]);
    for k in 0..3 {
        m.add_load(
            LoadGroup::Variable,
            Load::Temperature {
                element: unilateral_fem::ElementId(k),
                uniform: dt,
                gradient: grad,
            },
        );
    }
    let r = solve(&m, 1.0);
    // no displacement, constant moment EIαΔT/h (top hotter: compression on top = sagging),
    // axial force −EAαT
    for d in &r.displacements {
        for v in d {
            assert!(v.abs() < 1e-14);
        }
    }
    for line in &r.lines {
        for s in &line.diagram {
            close(s.m, e * i * alpha * grad / h, 1e-12);
            close(s.n, -e * a * alpha * dt, 1e-12);
            assert!(s.q.abs() < 1e-12);
        }
    }
    // free cantilever bends with κ = −αΔT/h: tip deflection κL²/2
    let mut m = Model::new();
    let ids = beam(
        &mut m,
        5.0,
        2,
        FrameSection::new(e, a, i).with_depth(h).with_alpha(alpha),
    );
    m.fix(ids[0]);
    for k in 0..2 {
        m.add_load(
            LoadGroup::Constant,
            Load::Temperature {
                element: unilateral_fem::ElementId(k),
                uniform: dt,
                gradient: grad,
            },
        );
    }
    let r = solve(&m, 0.0);
    let kappa = -alpha * grad / h;
    close(r.displacements[2][1], kappa * 25.0 / 2.0, 1e-12);
    close(r.displacements[2][0], alpha * dt * 5.0, 1e-12);
    assert!(r.lines[0].diagram[0].m.abs() < 1e-12);
}

#[test]
fn support_settlement_of_a_propped_cantilever() {
    let (e, i, l, delta) = (100.0, 2.0, 3.0, 0.01);
    let mut m = Model::new();
    let ids = beam(&mut m, l, 3, FrameSection::new(e, 1.0, i));
    m.fix(ids[0]);
    m.add_support(ids[3], SupportDof::Uy);
    m.add_load(
        LoadGroup::Variable,
        Load::Settlement {
            node: ids[3],
            dof: SupportDof::Uy,
            value: -delta,
        },
    );
    let r = solve(&m, 1.0);
    // the roller must pull the tip down: R = −3EIδ/L³; like a tip load, the wall answers with
    // a counter-clockwise moment 3EIδ/L²
    close(
        reaction(&r, 3, SupportDof::Uy),
        -3.0 * e * i * delta / l.powi(3),
        1e-12,
    );
    close(
        reaction(&r, 0, SupportDof::Rz),
        3.0 * e * i * delta / (l * l),
        1e-12,
    );
    close(r.displacements[3][1], -delta, 1e-15);
    // half the load parameter, half the settlement
    let r = solve(&m, 0.5);
    close(
        reaction(&r, 3, SupportDof::Uy),
        -1.5 * e * i * delta / l.powi(3),
        1e-12,
    );
}

#[test]
fn hinge_at_midspan_splits_the_load() {
    // clamped–clamped, hinge in the middle, load P at the hinge: two cantilevers share it.
    let (e, i, a, p) = (10.0, 1.0, 2.0, 3.0);
    let mut m = Model::new();
    let n0 = m.add_node(0.0, 0.0);
    let n1 = m.add_node(a, 0.0);
    let n2 = m.add_node(2.0 * a, 0.0);
    let s = FrameSection::new(e, 1.0, i);
    m.add_frame_with_releases(
        n0,
        n1,
        s,
        Releases {
            start: false,
            end: true,
        },
    );
    m.add_frame(n1, n2, s);
    m.fix(n0);
    m.fix(n2);
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: n1,
            fx: 0.0,
            fy: -p,
            m: 0.0,
        },
    );
    let r = solve(&m, 1.0);
    close(
        r.displacements[1][1],
        -(p / 2.0) * a.powi(3) / (3.0 * e * i),
        1e-12,
    );
    assert!(r.lines[0].end_forces[5].abs() < 1e-12);
    close(reaction(&r, 0, SupportDof::Rz), p / 2.0 * a, 1e-12);
}

#[test]
fn springs_and_inclined_roller() {
    // cantilever tip on a vertical spring: δ = P / (k + 3EI/L³)
    let (e, i, l, p, k) = (1.0, 1.0, 2.0, 1.0, 0.5);
    let mut m = Model::new();
    let ids = beam(&mut m, l, 2, FrameSection::new(e, 1.0, i));
    m.fix(ids[0]);
    m.add_spring(Spring {
        a: Endpoint::Ground,
        b: ids[2],
        kind: SpringKind::Translational {
            direction: [0.0, 2.0],
            stiffness: k,
        },
    });
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: ids[2],
            fx: 0.0,
            fy: -p,
            m: 0.0,
        },
    );
    let r = solve(&m, 1.0);
    let d = -p / (k + 3.0 * e * i / l.powi(3));
    close(r.displacements[2][1], d, 1e-12);
    close(r.spring_forces[0], k * d, 1e-12);

    // bar on an inclined roller: a horizontal bar pinned at 0, roller at L with normal
    // (1, 1)/√2 (rolls along (1, −1)). A vertical load F at L: reaction along the normal R with
    // R/√2 + F = 0 → R = −√2 F, and the horizontal pin reaction balances it.
    let mut m = Model::new();
    let a0 = m.add_node(0.0, 0.0);
    let a1 = m.add_node(3.0, 0.0);
    m.add_bar(a0, a1, FrameSection::new(100.0, 1.0, 0.0));
    m.pin(a0);
    m.roller(a1, [1.0, 1.0]);
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: a1,
            fx: 0.0,
            fy: 2.0,
            m: 0.0,
        },
    );
    let r = solve(&m, 1.0);
    let rn = reaction(&r, 1, SupportDof::Along([1.0, 1.0]));
    close(rn, -2.0 * 2f64.sqrt(), 1e-12);
    close(reaction(&r, 0, SupportDof::Ux), 2.0, 1e-12);
    // bar force: tension −2 (compressed by the roller's horizontal push)
    close(r.lines[0].diagram[3].n, -2.0, 1e-12);
    // the roller's node moves along (1, −1)
    let d = r.displacements[1];
    close(d[0] + d[1], 0.0, 1e-12);
}

#[test]
fn truss_triangle() {
    // two bars meeting at the apex (0, 1) from (−1, 0) and (1, 0): vertical load P down gives
    // compression P/(2 sin 45°) in each.
    let mut m = Model::new();
    let l = m.add_node(-1.0, 0.0);
    let rgt = m.add_node(1.0, 0.0);
    let top = m.add_node(0.0, 1.0);
    let s = FrameSection::new(1000.0, 1.0, 0.0);
    m.add_bar(l, top, s);
    m.add_bar(rgt, top, s);
    m.pin(l);
    m.pin(rgt);
    m.add_load(
        LoadGroup::Constant,
        Load::Nodal {
            node: top,
            fx: 0.0,
            fy: -1.0,
            m: 0.0,
        },
    );
    let r = solve(&m, 0.0);
    for line in &r.lines {
        close(line.diagram[0].n, -1.0 / 2f64.sqrt(), 1e-12);
    }
}

#[test]
fn self_weight_on_an_inclined_frame_is_global() {
    // simply supported inclined member under its weight w per length: vertical reactions wL/2.
    let mut m = Model::new();
    let a = m.add_node(0.0, 0.0);
    let b = m.add_node(3.0, 4.0);
    m.add_frame(a, b, FrameSection::new(1.0, 1.0, 1.0));
    m.pin(a);
    m.add_support(b, SupportDof::Uy);
    m.add_load(
        LoadGroup::Constant,
        Load::BodyForce {
            element: unilateral_fem::ElementId(0),
            force: [0.0, -2.0],
        },
    );
    let r = solve(&m, 0.0);
    close(reaction(&r, 0, SupportDof::Uy), 5.0, 1e-12);
    close(reaction(&r, 1, SupportDof::Uy), 5.0, 1e-12);
    // maximal moment of the horizontal projection: w·L·a/8 with a = 3 → 2·5·3/8
    let mmax = r.lines[0]
        .diagram
        .iter()
        .map(|s| s.m)
        .fold(f64::MIN, f64::max);
    close(mmax, 2.0 * 5.0 * 3.0 / 8.0, 1e-12);
}

/// A fixed-fixed beam under a uniform load given as six loads on its one element (two of them
/// triangular, in both frames and both groups), recovered once and again (the second time from
/// the element's kept data): the textbook values of the uniform load, `M = −qL²/12` at the ends, `qL²/24`
/// at midspan, `V = qL/2`, at every diagram sample `M(x) = q(6Lx − 6x² − L²)/12`.
#[test]
fn six_loads_on_one_frame_sum_as_one() {
    let (l, q) = (6.0, 5.0);
    let mut m = Model::new();
    let ids = beam(&mut m, l, 1, FrameSection::new(1.0, 1.0, 1.0));
    m.fix(ids[0]);
    m.fix(ids[1]);
    // (start, end) transverse intensities, the load's frame and group
    let (g, lo) = (LoadFrame::Global, LoadFrame::Local);
    let (v, c) = (LoadGroup::Variable, LoadGroup::Constant);
    let parts: [(f64, f64, LoadFrame, LoadGroup); 6] = [
        (q / 4.0, q / 4.0, g, v),
        (q / 4.0, q / 4.0, lo, c),
        (q / 8.0, q / 8.0, g, c),
        (q / 8.0, q / 8.0, lo, v),
        // a triangle 0 → q/4 and its mirror q/4 → 0 sum to a uniform q/4
        (0.0, q / 4.0, g, v),
        (q / 4.0, 0.0, lo, c),
    ];
    for (start, end, frame, group) in parts {
        m.add_load(
            group,
            Load::Distributed {
                element: unilateral_fem::ElementId(0),
                start: [0.0, -start],
                end: [0.0, -end],
                frame,
            },
        );
    }
    let cm = m.condense().unwrap();
    let first = cm.recover(&LinkValues::bonded(&cm, 1.0)).unwrap();
    let again = cm.recover(&LinkValues::bonded(&cm, 1.0)).unwrap();
    assert_eq!(first, again);
    let r = first;
    assert!(r.equilibrium.relative() < 1e-10, "{:?}", r.equilibrium);
    let dg = &r.lines[0].diagram;
    assert_eq!(dg.len(), 11);
    close(dg[0].m, -q * l * l / 12.0, 1e-12);
    close(dg[5].m, q * l * l / 24.0, 1e-12);
    close(dg[10].m, -q * l * l / 12.0, 1e-12);
    close(dg[0].q, q * l / 2.0, 1e-12);
    for d in dg {
        let x = d.s;
        let want = q * (6.0 * l * x - 6.0 * x * x - l * l) / 12.0;
        assert!(
            (d.m - want).abs() < 1e-12 * q * l * l,
            "M({x}) = {} != {want}",
            d.m
        );
        assert!((d.q - q * (l / 2.0 - x)).abs() < 1e-12 * q * l, "V({x})");
    }
}

/// From its second recovery on, a structure recovers its line elements from data kept once
/// (stiffness, geometry and each element load as local forces and intensities): the results
/// are those of a first recovery to the bit, at the same load and at another one. The loads
/// are interleaved between elements and groups (a factor paired with the wrong load would move
/// the values), on a hinged frame, a frame and a bar, with every kind of element load.
#[test]
fn kept_line_data_recover_as_a_first_recovery() {
    let build = || {
        let mut m = Model::new();
        let n0 = m.add_node(0.0, 0.0);
        let n1 = m.add_node(3.0, 1.0);
        let n2 = m.add_node(6.0, 0.0);
        let s = FrameSection::new(200.0, 2.0, 3.0)
            .with_depth(0.5)
            .with_alpha(1e-3);
        m.add_frame_with_releases(
            n0,
            n1,
            s,
            Releases {
                start: false,
                end: true,
            },
        );
        m.add_frame(n1, n2, s);
        m.add_bar(n0, n2, s);
        m.fix(n0);
        m.pin(n2);
        // springs: their matrices and directions are kept too
        m.add_spring(Spring {
            a: Endpoint::Node(n0),
            b: n1,
            kind: SpringKind::Translational {
                direction: [2.0, -3.0],
                stiffness: 40.0,
            },
        });
        m.add_spring(Spring {
            a: Endpoint::Ground,
            b: n1,
            kind: SpringKind::Rotational { stiffness: 90.0 },
        });
        let e = unilateral_fem::ElementId;
        let dist = |element: usize, start, end, frame| Load::Distributed {
            element: e(element),
            start,
            end,
            frame,
        };
        let loads = [
            (
                LoadGroup::Variable,
                dist(1, [0.0, -2.0], [1.0, -5.0], LoadFrame::Global),
            ),
            (
                LoadGroup::Constant,
                dist(0, [0.5, -1.0], [0.0, -3.0], LoadFrame::Local),
            ),
            (
                LoadGroup::Constant,
                Load::Temperature {
                    element: e(1),
                    uniform: 4.0,
                    gradient: -6.0,
                },
            ),
            (
                LoadGroup::Variable,
                Load::BodyForce {
                    element: e(0),
                    force: [0.3, -1.5],
                },
            ),
            (
                LoadGroup::Variable,
                dist(2, [2.0, 0.0], [-1.0, 0.0], LoadFrame::Local),
            ),
            (
                LoadGroup::Constant,
                dist(1, [0.0, 4.0], [0.0, 4.0], LoadFrame::Local),
            ),
            (
                LoadGroup::Variable,
                Load::Nodal {
                    node: n1,
                    fx: 1.0,
                    fy: -2.0,
                    m: 0.5,
                },
            ),
        ];
        for (g, l) in loads {
            m.add_load(g, l);
        }
        m
    };
    let m = build();
    let kept = m.condense().unwrap();
    let first = kept.recover(&LinkValues::bonded(&kept, 0.7)).unwrap();
    let again = kept.recover(&LinkValues::bonded(&kept, 0.7)).unwrap();
    assert_eq!(first, again);
    let other = kept.recover(&LinkValues::bonded(&kept, -1.3)).unwrap();
    let fresh = m.condense().unwrap();
    let first_other = fresh.recover(&LinkValues::bonded(&fresh, -1.3)).unwrap();
    assert_eq!(other, first_other);
    assert!(other != first, "the load moves the results");
    assert!(
        other.spring_forces.iter().all(|f| f.abs() > 1e-6),
        "the springs carry force: {:?}",
        other.spring_forces
    );
    assert!(
        first.equilibrium.relative() < 1e-10,
        "{:?}",
        first.equilibrium
    );
}
