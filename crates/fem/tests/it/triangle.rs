//! The 3-node constant-strain triangle: patch tests (imposed linear displacements, uniform
//! tractions), a cantilever converging to the beam solution, free thermal expansion, the
//! resultant of a body load, node order and degenerate triangles.
//!
//! References: Hooke's law written out here (not the element's elasticity matrix), the
//! Timoshenko beam formula, and statics of the data. Tolerances are relative to the stress,
//! displacement or force scale of each test.
#![allow(clippy::needless_range_loop)]

use unilateral_fem::{
    Element, ElementId, FemError, LinkValues, Load, LoadGroup, Model, NodeId, PlaneAnalysis,
    PlaneMaterial, Results, SupportDof,
};

fn solve(model: &Model) -> Results {
    let c = model.condense().unwrap();
    let r = c.recover(&LinkValues::bonded(&c, 1.0)).unwrap();
    assert!(r.equilibrium.relative() < 1e-9, "{:?}", r.equilibrium);
    r
}

const ANALYSES: [PlaneAnalysis; 2] = [PlaneAnalysis::PlaneStress, PlaneAnalysis::PlaneStrain];

/// A rectangle 2 × 1 in irregular triangles: boundary nodes 0..6 counter-clockwise from the
/// origin (0, 1, 2 on y = 0; 2, 3 on x = 2; 3, 4, 5 on y = 1; 5, 0 on x = 0), interior nodes
/// 6 and 7 off any symmetry. The triangle (4, 7, 6) is given clockwise on purpose.
const PTS: [[f64; 2]; 8] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [2.0, 0.0],
    [2.0, 1.0],
    [1.0, 1.0],
    [0.0, 1.0],
    [0.6, 0.4],
    [1.3, 0.55],
];
const TRIS: [[usize; 3]; 8] = [
    [0, 1, 6],
    [1, 7, 6],
    [1, 2, 7],
    [2, 3, 7],
    [3, 4, 7],
    [4, 7, 6],
    [4, 5, 6],
    [5, 0, 6],
];

/// The patch mesh with material `mat`; returns the model and its node ids.
fn patch(mat: PlaneMaterial, an: PlaneAnalysis) -> (Model, Vec<NodeId>) {
    let mut m = Model::new();
    let ids: Vec<NodeId> = PTS.iter().map(|p| m.add_node(p[0], p[1])).collect();
    let mut area = 0.0;
    for t in TRIS {
        m.add_triangle(t.map(|i| ids[i]), mat, an);
        let [a, b, c] = t.map(|i| PTS[i]);
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
    }
    // the triangles tile the rectangle (no overlap, no hole): their areas add up to 2
    assert!((area - 2.0).abs() < 1e-14, "{area}");
    (m, ids)
}

/// Hooke's law for the strain (εxx, εyy, γxy): (σxx, σyy, τxy, σzz).
fn hooke(e: f64, nu: f64, an: PlaneAnalysis, eps: [f64; 3]) -> [f64; 4] {
    let g = e / (2.0 * (1.0 + nu));
    match an {
        PlaneAnalysis::PlaneStress => {
            let c = e / (1.0 - nu * nu);
            [
                c * (eps[0] + nu * eps[1]),
                c * (eps[1] + nu * eps[0]),
                g * eps[2],
                0.0,
            ]
        }
        PlaneAnalysis::PlaneStrain => {
            let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
            let (sx, sy) = (
                c * ((1.0 - nu) * eps[0] + nu * eps[1]),
                c * ((1.0 - nu) * eps[1] + nu * eps[0]),
            );
            [sx, sy, g * eps[2], nu * (sx + sy)]
        }
    }
}

#[test]
fn patch_test_with_imposed_linear_displacements() {
    // u = (c1 x + c2 y + u0, c3 x + c4 y + v0): εxx = c1, εyy = c4, γxy = c2 + c3, imposed at
    // the six boundary nodes; the interior nodes must take the exact field and every element
    // the stress of Hooke's law.
    let (c1, c2, c3, c4, u0, v0) = (1.0e-3, 4.0e-4, -1.0e-4, -3.0e-4, 2.0e-4, -5.0e-4);
    let exact = |p: [f64; 2]| [c1 * p[0] + c2 * p[1] + u0, c3 * p[0] + c4 * p[1] + v0];
    let (e, nu) = (2.1e5, 0.3);
    for an in ANALYSES {
        let (mut m, ids) = patch(PlaneMaterial::new(e, nu).with_thickness(0.01), an);
        for i in 0..6 {
            let u = exact(PTS[i]);
            m.pin(ids[i]);
            for (dof, value) in [(SupportDof::Ux, u[0]), (SupportDof::Uy, u[1])] {
                m.add_load(
                    LoadGroup::Constant,
                    Load::Settlement {
                        node: ids[i],
                        dof,
                        value,
                    },
                );
            }
        }
        let r = solve(&m);
        let scale = 1.0e-3 * 2.0;
        for i in 6..8 {
            let u = exact(PTS[i]);
            for c in 0..2 {
                assert!(
                    (r.displacements[i][c] - u[c]).abs() < 1e-12 * scale,
                    "{an:?} node {i}: {:?} vs {u:?}",
                    r.displacements[i]
                );
            }
        }
        let s = hooke(e, nu, an, [c1, c4, c2 + c3]);
        let smax = s.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert_eq!(r.planes.len(), TRIS.len());
        for pl in &r.planes {
            for g in &pl.stress {
                for c in 0..4 {
                    assert!((g[c] - s[c]).abs() < 1e-9 * smax, "{an:?} {g:?} vs {s:?}");
                }
            }
        }
        for ns in r.nodal_stress.iter() {
            let ns = ns.expect("every node belongs to a triangle");
            for c in 0..4 {
                assert!((ns[c] - s[c]).abs() < 1e-9 * smax, "{an:?} {ns:?} vs {s:?}");
            }
        }
    }
}

#[test]
fn patch_test_under_uniform_tractions() {
    // The tractions t = σ·n of a uniform stress (σxx, σyy, τxy) on the four sides, as
    // consistent nodal loads of linear edges (t·L·thickness/2 at each end of an edge); the
    // body is held against rigid motion only (node 0 pinned, node 2 on a roller in y), so the
    // reactions vanish and every element carries exactly that stress.
    let (sxx, syy, txy) = (120.0, -45.0, 30.0);
    let (e, nu, thk) = (3.0e4, 0.2, 0.5);
    let edges: [([usize; 2], [f64; 2]); 7] = [
        ([0, 1], [0.0, -1.0]),
        ([1, 2], [0.0, -1.0]),
        ([2, 3], [1.0, 0.0]),
        ([3, 4], [0.0, 1.0]),
        ([4, 5], [0.0, 1.0]),
        ([5, 0], [-1.0, 0.0]),
        ([6, 6], [0.0, 0.0]), // no edge (keeps the array's length fixed)
    ];
    for an in ANALYSES {
        let (mut m, ids) = patch(PlaneMaterial::new(e, nu).with_thickness(thk), an);
        for ([a, b], n) in edges {
            if a == b {
                continue;
            }
            let len = (PTS[b][0] - PTS[a][0]).hypot(PTS[b][1] - PTS[a][1]);
            let t = [sxx * n[0] + txy * n[1], txy * n[0] + syy * n[1]];
            for node in [ids[a], ids[b]] {
                m.add_load(
                    LoadGroup::Variable,
                    Load::Nodal {
                        node,
                        fx: t[0] * len * thk / 2.0,
                        fy: t[1] * len * thk / 2.0,
                        m: 0.0,
                    },
                );
            }
        }
        m.pin(ids[0]);
        m.add_support(ids[2], SupportDof::Uy);
        let r = solve(&m);
        let scale = sxx.abs().max(syy.abs()).max(txy.abs());
        let szz = match an {
            PlaneAnalysis::PlaneStress => 0.0,
            PlaneAnalysis::PlaneStrain => nu * (sxx + syy),
        };
        for pl in &r.planes {
            for g in &pl.stress {
                let want = [sxx, syy, txy, szz];
                for c in 0..4 {
                    assert!((g[c] - want[c]).abs() < 1e-9 * scale, "{an:?} {g:?}");
                }
            }
        }
        for x in &r.reactions {
            assert!(x.value.abs() < 1e-9 * scale * thk, "{an:?} {x:?}");
        }
        // and the strain is Hooke's law's inverse: node 3 at (2, 1) relative to node 0, with
        // εxx from the stresses (plane stress: εxx = (σxx − ν σyy)/E; plane strain:
        // εxx = ((1 − ν²) σxx − ν (1 + ν) σyy)/E)
        let exx = match an {
            PlaneAnalysis::PlaneStress => (sxx - nu * syy) / e,
            PlaneAnalysis::PlaneStrain => ((1.0 - nu * nu) * sxx - nu * (1.0 + nu) * syy) / e,
        };
        assert!(
            (r.displacements[2][0] - 2.0 * exx).abs() < 1e-9 * 2.0 * exx.abs(),
            "{an:?} {:?}",
            r.displacements[2]
        );
    }
}

/// Cantilever 0 ≤ x ≤ 10, −1/2 ≤ y ≤ 1/2 (E = 1000, ν = 0, plane stress), each of nx × ny
/// rectangles split into two triangles along alternating diagonals, pinned at x = 0, with a
/// parabolic tip shear of resultant `p` at x = l as consistent nodal loads. Returns the
/// vertical tip displacement on the axis.
fn cantilever(nx: usize, ny: usize, p: f64) -> f64 {
    let (l, h, e) = (10.0, 1.0, 1000.0);
    let mut m = Model::new();
    let mut id = vec![vec![NodeId(0); ny + 1]; nx + 1];
    for (i, col) in id.iter_mut().enumerate() {
        for (j, v) in col.iter_mut().enumerate() {
            *v = m.add_node(
                l * i as f64 / nx as f64,
                -h / 2.0 + h * j as f64 / ny as f64,
            );
        }
    }
    let mat = PlaneMaterial::new(e, 0.0);
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]);
            let [t1, t2] = if (i + j) % 2 == 0 {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            m.add_triangle(t1, mat, PlaneAnalysis::PlaneStress);
            m.add_triangle(t2, mat, PlaneAnalysis::PlaneStress);
        }
    }
    for j in 0..=ny {
        m.pin(id[0][j]);
    }
    // τ = (P / 2I)(h²/4 − y²) on the end, its consistent loads on linear edges by 3-point
    // Gauss (exact for the cubic integrand)
    let inertia = h.powi(3) / 12.0;
    let ty = |y: f64| p / (2.0 * inertia) * (h * h / 4.0 - y * y);
    for j in 0..ny {
        let (y1, y2) = (
            -h / 2.0 + h * j as f64 / ny as f64,
            -h / 2.0 + h * (j + 1) as f64 / ny as f64,
        );
        let g = 0.6f64.sqrt();
        let mut f = [0.0; 2];
        for (s, w) in [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)] {
            let y = 0.5 * (y1 + y2) + 0.5 * (y2 - y1) * s;
            let jw = w * 0.5 * (y2 - y1);
            f[0] += jw * 0.5 * (1.0 - s) * ty(y);
            f[1] += jw * 0.5 * (1.0 + s) * ty(y);
        }
        for (k, node) in [id[nx][j], id[nx][j + 1]].into_iter().enumerate() {
            m.add_load(
                LoadGroup::Variable,
                Load::Nodal {
                    node,
                    fx: 0.0,
                    fy: f[k],
                    m: 0.0,
                },
            );
        }
    }
    let r = solve(&m);
    r.displacements[id[nx][ny / 2].0][1]
}

#[test]
fn cantilever_converges_to_the_beam_solution() {
    // Timoshenko beam: δ = P L³/(3 E I) + P L/(κ G A), κ = 5/6, G = E/2 (ν = 0).
    let (l, e, inertia, area): (f64, f64, f64, f64) = (10.0, 1000.0, 1.0 / 12.0, 1.0);
    let p = -1.0;
    let exact = p * l.powi(3) / (3.0 * e * inertia) + p * l / (5.0 / 6.0 * e / 2.0 * area);
    // signed relative errors δ/δ_beam − 1 on meshes halved three times
    let errs: Vec<f64> = [(10, 2), (20, 4), (40, 8), (80, 16)]
        .iter()
        .map(|&(nx, ny)| cantilever(nx, ny, p) / exact - 1.0)
        .collect();
    eprintln!("CST cantilever relative errors {errs:?}");
    // The CST is stiff in bending (its strain is constant across each element, so it
    // cannot bend without spurious shear): every mesh is too stiff, the coarse one far off,
    // and each halving of the element size cuts the error by at least half (asymptotically
    // by four: the tip deflection converges like h²).
    assert!(errs.iter().all(|&e| e < 0.0), "{errs:?}");
    assert!(
        errs[0] < -0.2,
        "the coarse CST mesh should be stiff: {errs:?}"
    );
    for w in errs.windows(2) {
        assert!(w[1].abs() < w[0].abs() / 2.0, "{errs:?}");
    }
    // On the finest mesh (16 rows of triangles over the depth, 160 along) the error is
    // within 4%: about a third of the previous mesh's error remains (h² with a ratio near 4).
    assert!(errs[3].abs() < 0.04, "{errs:?}");
    // The Richardson extrapolation of the last two meshes (error ∝ h²: e∞ = e4 + (e4 − e3)/3)
    // removes the discretisation error; what remains is the beam formula's own difference
    // from a plane body pinned over its whole end, a local effect of order (h/L)² = 1%.
    let extrapolated = errs[3] + (errs[3] - errs[2]) / 3.0;
    assert!(extrapolated.abs() < 0.01, "{extrapolated} from {errs:?}");
}

#[test]
fn free_thermal_expansion_is_stress_free() {
    // A free body under a uniform ΔT: u = factor·α·ΔT·(x, y) relative to node 0 at the
    // origin, factor 1 in plane stress and 1 + ν in plane strain (ε_zz = 0 adds ν α ΔT in
    // plane), no in-plane stress, and σzz = −E α ΔT in plane strain.
    let (e, nu, alpha, dt) = (2.0e5, 0.25, 1.2e-5, 40.0);
    for an in ANALYSES {
        let (mut m, ids) = patch(PlaneMaterial::new(e, nu).with_alpha(alpha), an);
        for k in 0..TRIS.len() {
            m.add_load(
                LoadGroup::Variable,
                Load::Temperature {
                    element: ElementId(k),
                    uniform: dt,
                    gradient: 0.0,
                },
            );
        }
        m.pin(ids[0]);
        m.add_support(ids[2], SupportDof::Uy);
        let r = solve(&m);
        let factor = match an {
            PlaneAnalysis::PlaneStress => 1.0,
            PlaneAnalysis::PlaneStrain => 1.0 + nu,
        };
        let strain = factor * alpha * dt;
        for (i, p) in PTS.iter().enumerate() {
            for c in 0..2 {
                assert!(
                    (r.displacements[i][c] - strain * p[c]).abs() < 1e-12 * strain * 2.0,
                    "{an:?} node {i}"
                );
            }
        }
        let szz = e * alpha * dt;
        for pl in &r.planes {
            for s in &pl.stress {
                assert!(
                    s[0].abs() < 1e-9 * szz && s[1].abs() < 1e-9 * szz && s[2].abs() < 1e-9 * szz,
                    "{an:?} {s:?}"
                );
                let want = if an == PlaneAnalysis::PlaneStrain {
                    -szz
                } else {
                    0.0
                };
                assert!((s[3] - want).abs() < 1e-9 * szz, "{an:?} {s:?}");
            }
        }
    }
}

#[test]
fn body_load_resultant_is_the_weight() {
    // Self-weight ρ g per unit volume on every triangle: the equivalent nodal loads sum to
    // −ρ g · area · thickness, and act through each triangle's centroid (a third at each
    // node), so their moment about the origin is Σ x_c,e · (−ρ g A_e t).
    let (rho_g, thk) = (24.0e3, 0.3);
    let (mut m, ids) = patch(
        PlaneMaterial::new(3.0e10, 0.2).with_thickness(thk),
        ANALYSES[0],
    );
    let mut moment = 0.0;
    for (k, t) in TRIS.iter().enumerate() {
        m.add_load(
            LoadGroup::Constant,
            Load::BodyForce {
                element: ElementId(k),
                force: [0.0, -rho_g],
            },
        );
        let [a, b, c] = t.map(|i| PTS[i]);
        let ae = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
        moment += (a[0] + b[0] + c[0]) / 3.0 * (-rho_g * ae * thk);
    }
    for i in [0, 1, 2] {
        m.pin(ids[i]);
    }
    let r = solve(&m);
    let w = rho_g * 2.0 * thk;
    let ap = r.equilibrium.applied;
    assert!(ap[0].abs() < 1e-12 * w, "{ap:?}");
    assert!((ap[1] + w).abs() < 1e-12 * w, "{ap:?} vs {w}");
    assert!((ap[2] - moment).abs() < 1e-12 * w, "{ap:?} vs {moment}");
    // the base reactions carry it
    let base: f64 = r
        .reactions
        .iter()
        .filter(|x| x.dof == SupportDof::Uy)
        .map(|x| x.value)
        .sum();
    assert!((base - w).abs() < 1e-9 * w, "{base} vs {w}");
}

#[test]
fn node_order_does_not_change_the_triangle() {
    // add_triangle stores a clockwise triangle counter-clockwise; an element pushed clockwise
    // directly gives the same stresses (the sign of the area cancels in the stiffness).
    let pts = [[0.0, 0.0], [3.0, 0.5], [1.0, 2.0]];
    let run = |order: [usize; 3], direct: bool| {
        let mut m = Model::new();
        let ids: Vec<NodeId> = pts.iter().map(|p| m.add_node(p[0], p[1])).collect();
        let mat = PlaneMaterial::new(1.0e3, 0.3);
        let nodes = order.map(|i| ids[i]);
        if direct {
            m.push(Element::Triangle {
                nodes,
                material: mat,
                analysis: PlaneAnalysis::PlaneStrain,
            });
        } else {
            m.add_triangle(nodes, mat, PlaneAnalysis::PlaneStrain);
        }
        m.pin(ids[0]);
        m.add_support(ids[1], SupportDof::Uy);
        m.add_load(
            LoadGroup::Variable,
            Load::Nodal {
                node: ids[2],
                fx: 2.0,
                fy: -1.0,
                m: 0.0,
            },
        );
        m.add_load(
            LoadGroup::Variable,
            Load::Nodal {
                node: ids[1],
                fx: -2.0,
                fy: 0.0,
                m: 0.0,
            },
        );
        let stored = match &m.elements()[0] {
            Element::Triangle { nodes, .. } => nodes.map(|n| n.0),
            e => panic!("{e:?}"),
        };
        (stored, solve(&m))
    };
    let (ccw, a) = run([0, 1, 2], false);
    let (cw, b) = run([0, 2, 1], false);
    let (raw, c) = run([0, 2, 1], true);
    assert_eq!(ccw, [0, 1, 2]);
    assert_eq!(cw, [0, 1, 2]);
    assert_eq!(raw, [0, 2, 1]);
    let s = a.planes[0].stress[0];
    let scale = s.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for other in [&b, &c] {
        for (x, y) in s.iter().zip(&other.planes[0].stress[0]) {
            assert!((x - y).abs() < 1e-12 * scale, "{s:?} vs {other:?}");
        }
        for (u, v) in a.displacements.iter().zip(&other.displacements) {
            for k in 0..2 {
                assert!((u[k] - v[k]).abs() < 1e-12 * a.displacements[2][0].abs());
            }
        }
    }
    // the reported sampling points lie inside the triangle and average to its centroid
    let pl = &a.planes[0];
    let centroid = [4.0 / 3.0, 2.5 / 3.0];
    for c in 0..2 {
        let mean = pl.gauss_points.iter().map(|g| g[c]).sum::<f64>() / 4.0;
        assert!((mean - centroid[c]).abs() < 1e-14, "{:?}", pl.gauss_points);
    }
}

#[test]
fn degenerate_triangle_is_refused_naming_it() {
    // Collinear nodes (area 0), and nodes whose area is tiny against the longest edge squared:
    // both refused as element 1 (the second element), never a singular stiffness.
    for third in [[2.0, 0.0], [2.0, 1e-14]] {
        let mut m = Model::new();
        let a = m.add_node(0.0, 0.0);
        let b = m.add_node(1.0, 0.0);
        let c = m.add_node(1.0, 1.0);
        let d = m.add_node(third[0], third[1]);
        let mat = PlaneMaterial::new(1.0, 0.3);
        m.add_triangle([a, b, c], mat, PlaneAnalysis::PlaneStress);
        m.add_triangle([a, b, d], mat, PlaneAnalysis::PlaneStress);
        let err = m.validate().unwrap_err();
        match &err {
            FemError::NonPositiveProperty {
                element, property, ..
            } => {
                assert_eq!(*element, ElementId(1));
                assert!(property.contains("area"), "{err}");
            }
            e => panic!("{e:?}"),
        }
        let msg = err.to_string();
        assert!(msg.contains("element 1") && msg.contains("area"), "{msg}");
    }
    // the material is checked as a quadrilateral's
    let mut m = Model::new();
    let n = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| m.add_node(x, y));
    m.add_triangle(n, PlaneMaterial::new(1.0, 0.5), PlaneAnalysis::PlaneStrain);
    assert!(matches!(
        m.validate(),
        Err(FemError::PoissonOutOfRange { .. })
    ));
}
