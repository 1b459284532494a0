//! The contact stiffness matrix and load vectors computed two independent ways.
#![allow(clippy::needless_range_loop)]

use faer::linalg::solvers::DenseSolveCore;
use faer::{Mat, Side};
use unilateral_fem::{
    ContactPairSpec, ElementId, Endpoint, FrameSection, LinkValues, Load, LoadFrame, LoadGroup,
    Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial, Spring, SpringKind, SupportDof,
};

/// A column (frames) beside a small soil block (QM6), two extra nodes on springs, and six
/// contact pairs: node-to-node (column → soil), node-to-ground, one whose node B is supported
/// (the link goes on A), and one chained onto another pair's node.
fn model(with_pairs: bool, with_loads: bool) -> (Model, Vec<ContactPairSpec>) {
    let mut m = Model::new();
    let mut soil = vec![vec![NodeId(0); 3]; 3];
    for (i, col) in soil.iter_mut().enumerate() {
        for (j, v) in col.iter_mut().enumerate() {
            *v = m.add_node(1.0 + i as f64, j as f64 * 1.1);
        }
    }
    let mat = PlaneMaterial::new(100.0, 0.3).with_alpha(1e-3);
    for i in 0..2 {
        for j in 0..2 {
            m.add_plane(
                [
                    soil[i][j],
                    soil[i + 1][j],
                    soil[i + 1][j + 1],
                    soil[i][j + 1],
                ],
                mat,
                PlaneAnalysis::PlaneStrain,
                PlaneFormulation::QM6,
            );
        }
    }
    for i in 0..3 {
        m.pin(soil[i][0]);
    }
    for j in 1..3 {
        m.add_support(soil[2][j], SupportDof::Ux);
    }
    let col: Vec<NodeId> = (0..3).map(|j| m.add_node(1.0, j as f64 * 1.1)).collect();
    let sec = FrameSection::new(1000.0, 1.0, 0.1)
        .with_depth(0.3)
        .with_alpha(1e-3);
    let c0 = m.add_frame(col[0], col[1], sec);
    let c1 = m.add_frame(col[1], col[2], sec);
    m.fix(col[0]);
    let q = m.add_node(3.5, 1.1);
    let r = m.add_node(1.5, 1.6);
    for (node, dirs) in [(q, [[1.0, 0.3], [0.0, 1.0]]), (r, [[1.0, 0.0], [0.2, 1.0]])] {
        for d in dirs {
            m.add_spring(Spring {
                a: Endpoint::Ground,
                b: node,
                kind: SpringKind::Translational {
                    direction: d,
                    stiffness: 7.0,
                },
            });
        }
    }
    m.add_spring(Spring {
        a: Endpoint::Node(col[2]),
        b: soil[1][2],
        kind: SpringKind::Translational {
            direction: [1.0, -1.0],
            stiffness: 3.0,
        },
    });
    let pairs = vec![
        ContactPairSpec::between(col[1], soil[0][1], [1.0, 0.0]).friction(0.4),
        ContactPairSpec::between(col[2], soil[0][2], [1.0, 0.2])
            .friction(0.4)
            .gap(0.01),
        ContactPairSpec::to_ground(soil[1][2], [0.3, 1.0]).name("ground"),
        ContactPairSpec::between(q, soil[2][1], [-1.0, 0.0]).name("B supported"),
        ContactPairSpec::between(soil[0][1], r, [0.6, 0.8]).name("chained"),
    ];
    if with_pairs {
        for p in &pairs {
            m.add_contact_pair(p.clone());
        }
    }
    if with_loads {
        use LoadGroup::{Constant as C, Variable as V};
        for e in 0..4 {
            m.add_load(
                C,
                Load::BodyForce {
                    element: ElementId(e),
                    force: [0.0, -2.0],
                },
            );
        }
        m.add_load(
            C,
            Load::Nodal {
                node: col[2],
                fx: 0.5,
                fy: -1.0,
                m: 0.3,
            },
        );
        m.add_load(
            C,
            Load::Temperature {
                element: c0,
                uniform: 5.0,
                gradient: 10.0,
            },
        );
        m.add_load(
            C,
            Load::Settlement {
                node: soil[1][0],
                dof: SupportDof::Uy,
                value: -0.01,
            },
        );
        m.add_load(
            V,
            Load::Nodal {
                node: col[2],
                fx: 1.0,
                fy: 0.0,
                m: 0.0,
            },
        );
        m.add_load(
            V,
            Load::Distributed {
                element: c1,
                start: [0.1, 1.0],
                end: [0.0, 2.0],
                frame: LoadFrame::Local,
            },
        );
        m.add_load(
            V,
            Load::Temperature {
                element: ElementId(3),
                uniform: 20.0,
                gradient: 0.0,
            },
        );
        m.add_load(
            V,
            Load::Settlement {
                node: soil[2][1],
                dof: SupportDof::Ux,
                value: 0.02,
            },
        );
        m.add_load(
            V,
            Load::Nodal {
                node: r,
                fx: -0.3,
                fy: 0.7,
                m: 0.0,
            },
        );
    }
    (m, pairs)
}

fn nt(p: &ContactPairSpec) -> ([f64; 2], [f64; 2]) {
    let l = p.normal[0].hypot(p.normal[1]);
    let n = [p.normal[0] / l, p.normal[1] / l];
    (n, [n[1], -n[0]])
}

/// `C u` for the pairs: normal rows then tangential rows.
fn relative(pairs: &[ContactPairSpec], u: &[[f64; 3]]) -> Vec<f64> {
    let m = pairs.len();
    let mut z = vec![0.0; 2 * m];
    for (k, p) in pairs.iter().enumerate() {
        let ub = u[p.b.0];
        let ua = match p.a {
            Endpoint::Ground => [0.0; 3],
            Endpoint::Node(a) => u[a.0],
        };
        let (n, t) = nt(p);
        let d = [ub[0] - ua[0], ub[1] - ua[1]];
        z[k] = n[0] * d[0] + n[1] * d[1];
        z[m + k] = t[0] * d[0] + t[1] * d[1];
    }
    z
}

fn max_abs(m: &Mat<f64>) -> f64 {
    let mut a = 0.0f64;
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            a = a.max(m[(i, j)].abs());
        }
    }
    a
}

/// The blocks moved out whole (what an analysis does with them) are the blocks of `csm`, and
/// what is left recovers as before: the same displacements, and an empty `csm` instead of a
/// panic on the `0 × 0` blocks.
#[test]
fn taken_blocks_are_the_csm_and_leave_the_recovery() {
    let (linked, pairs) = model(true, true);
    let m = pairs.len();
    let mut c = linked.condense().unwrap();
    let r = c.csm();
    let before = c.recover(&LinkValues::bonded(&c, 1.0)).unwrap();
    let blocks = c.take_blocks();
    for (b, (r0, c0)) in blocks.iter().zip([(0, 0), (0, m), (m, 0), (m, m)]) {
        assert_eq!((b.nrows(), b.ncols()), (m, m));
        for j in 0..m {
            for i in 0..m {
                assert_eq!(b[(i, j)], r[(r0 + i, c0 + j)]);
            }
        }
    }
    assert_eq!((c.rnn.nrows(), c.rtt.ncols()), (0, 0));
    assert_eq!(c.pairs(), m);
    assert_eq!(c.csm().nrows(), 0);
    let after = c.recover(&LinkValues::bonded(&c, 1.0)).unwrap();
    assert_eq!(before.displacements, after.displacements);
}

#[test]
fn csm_equals_inverse_flexibility_and_clv_matches() {
    let (linked, pairs) = model(true, true);
    let c = linked.condense().unwrap();
    let r = c.csm();
    let m = pairs.len();
    // flexibility F = C K⁻¹ Cᵀ from unit pair forces on the structure without links
    let mut f = Mat::<f64>::zeros(2 * m, 2 * m);
    for j in 0..2 * m {
        let (mut free, _) = model(false, false);
        let k = j % m;
        let (n, t) = nt(&pairs[k]);
        let d = if j < m { n } else { t };
        free.add_load(
            LoadGroup::Constant,
            Load::Nodal {
                node: pairs[k].b,
                fx: d[0],
                fy: d[1],
                m: 0.0,
            },
        );
        if let Endpoint::Node(a) = pairs[k].a {
            free.add_load(
                LoadGroup::Constant,
                Load::Nodal {
                    node: a,
                    fx: -d[0],
                    fy: -d[1],
                    m: 0.0,
                },
            );
        }
        let cf = free.condense().unwrap();
        let res = cf.recover(&LinkValues::bonded(&cf, 0.0)).unwrap();
        let z = relative(&pairs, &res.displacements);
        for i in 0..2 * m {
            f[(i, j)] = z[i];
        }
    }
    let rinv = f.partial_piv_lu().inverse();
    let scale = max_abs(&r);
    let diff = max_abs(&(&r - &rinv));
    assert!(
        diff <= 1e-10 * scale,
        "|R − F⁻¹| = {diff:e}, |R| = {scale:e}"
    );
    // symmetric positive (semi)definite
    for i in 0..2 * m {
        for j in 0..2 * m {
            assert!((r[(i, j)] - r[(j, i)]).abs() <= 1e-12 * scale);
        }
    }
    let ev = r.self_adjoint_eigenvalues(Side::Lower).unwrap();
    assert!(ev[0] >= -1e-12 * scale, "{ev:?}");
    for blk in [&c.rnn, &c.rtt] {
        let ev = blk.self_adjoint_eigenvalues(Side::Lower).unwrap();
        assert!(ev[0] >= -1e-12 * scale);
    }
    assert!(c.stats.asymmetry < 1e-12, "{}", c.stats.asymmetry);
    // CLVs: R_F = −R·z0, z0 = relative displacements of the unlinked structure under the load
    let (free, _) = model(false, true);
    let cf = free.condense().unwrap();
    for (p, clv) in [(0.0, &c.constant), (1.0, &c.variable)] {
        let z_c = relative(
            &pairs,
            &cf.recover(&LinkValues::bonded(&cf, 0.0))
                .unwrap()
                .displacements,
        );
        let z = if p == 0.0 {
            z_c
        } else {
            let z1 = relative(
                &pairs,
                &cf.recover(&LinkValues::bonded(&cf, 1.0))
                    .unwrap()
                    .displacements,
            );
            z1.iter().zip(&z_c).map(|(a, b)| a - b).collect()
        };
        let zm = Mat::<f64>::from_fn(2 * m, 1, |i, _| z[i]);
        let rf = -(&r * &zm);
        let got: Vec<f64> = clv.normal.iter().chain(&clv.tangential).copied().collect();
        let s = got.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for i in 0..2 * m {
            assert!(
                (got[i] - rf[(i, 0)]).abs() <= 1e-10 * s,
                "{i}: {} vs {}",
                got[i],
                rf[(i, 0)]
            );
        }
    }
    assert_eq!(c.pair_names[2], "ground");
    assert_eq!(c.gap[1], 0.01);
}

#[test]
fn recovery_reproduces_the_imposed_mutual_displacements() {
    let (linked, pairs) = model(true, true);
    let c = linked.condense().unwrap();
    let m = pairs.len();
    let r = c.csm();
    let z: Vec<f64> = (0..2 * m)
        .map(|i| 0.01 * ((i * 7 % 5) as f64 - 2.0))
        .collect();
    let p = 0.7;
    let zm = Mat::<f64>::from_fn(2 * m, 1, |i, _| z[i]);
    let rz = &r * &zm;
    let x: Vec<f64> = (0..2 * m)
        .map(|i| {
            let (rc, rv) = if i < m {
                (c.constant.normal[i], c.variable.normal[i])
            } else {
                (c.constant.tangential[i - m], c.variable.tangential[i - m])
            };
            rz[(i, 0)] + rc + p * rv
        })
        .collect();
    let sol = LinkValues {
        p,
        x_n: x[..m].to_vec(),
        x_t: x[m..].to_vec(),
        // the LCP's z_n is the opening measured from closed contact: the gap plus the mutual
        // displacement
        z_n: (0..m).map(|i| z[i] + c.gap[i]).collect(),
        z_t: z[m..].to_vec(),
    };
    let res = c.recover(&sol).unwrap();
    let zz = relative(&pairs, &res.displacements);
    for i in 0..2 * m {
        assert!((zz[i] - z[i]).abs() < 1e-13, "{i}");
    }
    assert!(res.equilibrium.relative() < 1e-10, "{:?}", res.equilibrium);
    // a wrong x shows up as a mismatch
    let mut bad = sol.clone();
    bad.x_n[0] += 1.0;
    let res = c.recover(&bad).unwrap();
    assert!((res.equilibrium.link_force_mismatch - 1.0).abs() < 1e-9);
}
