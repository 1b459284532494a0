//! Plane elements: patch test, cantilever in bending, block under self-weight, free thermal
//! expansion.
#![allow(clippy::needless_range_loop)]

use unilateral_fem::{
    ElementId, LinkValues, Load, LoadGroup, Model, NodeId, PlaneAnalysis, PlaneFormulation,
    PlaneMaterial, Results, SupportDof,
};

fn solve(model: &Model) -> Results {
    let c = model.condense().unwrap();
    let r = c.recover(&LinkValues::bonded(&c, 1.0)).unwrap();
    assert!(r.equilibrium.relative() < 1e-9, "{:?}", r.equilibrium);
    r
}

const FORMS: [PlaneFormulation; 2] = [PlaneFormulation::Q4, PlaneFormulation::QM6];
const ANALYSES: [PlaneAnalysis; 2] = [PlaneAnalysis::PlaneStress, PlaneAnalysis::PlaneStrain];

#[test]
fn patch_test_on_a_distorted_mesh() {
    // MacNeal–Harder patch: boundary displacements of a constant strain field.
    let pts = [
        [0.0, 0.0],
        [0.24, 0.0],
        [0.24, 0.12],
        [0.0, 0.12],
        [0.04, 0.02],
        [0.18, 0.03],
        [0.16, 0.08],
        [0.08, 0.08],
    ];
    let quads = [
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
        [4, 5, 6, 7],
    ];
    let exact = |p: [f64; 2]| [1e-3 * (p[0] + p[1] / 2.0), 1e-3 * (p[1] + p[0] / 2.0)];
    let (e, nu) = (1.0e6, 0.25);
    for form in FORMS {
        for an in ANALYSES {
            let mut m = Model::new();
            let ids: Vec<NodeId> = pts.iter().map(|p| m.add_node(p[0], p[1])).collect();
            let mat = PlaneMaterial::new(e, nu).with_thickness(0.001);
            for q in quads {
                m.add_plane(q.map(|i| ids[i]), mat, an, form);
            }
            for i in 0..4 {
                let u = exact(pts[i]);
                m.pin(ids[i]);
                m.add_load(
                    LoadGroup::Constant,
                    Load::Settlement {
                        node: ids[i],
                        dof: SupportDof::Ux,
                        value: u[0],
                    },
                );
                m.add_load(
                    LoadGroup::Constant,
                    Load::Settlement {
                        node: ids[i],
                        dof: SupportDof::Uy,
                        value: u[1],
                    },
                );
            }
            let r = solve(&m);
            for i in 4..8 {
                let u = exact(pts[i]);
                assert!(
                    (r.displacements[i][0] - u[0]).abs() < 1e-13,
                    "{form:?} {an:?}"
                );
                assert!(
                    (r.displacements[i][1] - u[1]).abs() < 1e-13,
                    "{form:?} {an:?}"
                );
            }
            let (sx, sy, txy) = match an {
                PlaneAnalysis::PlaneStress => (
                    e / (1.0 - nu) * 1e-3,
                    e / (1.0 - nu) * 1e-3,
                    e / (2.0 * (1.0 + nu)) * 1e-3,
                ),
                PlaneAnalysis::PlaneStrain => {
                    let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                    (c * 1e-3, c * 1e-3, e / (2.0 * (1.0 + nu)) * 1e-3)
                }
            };
            for pl in &r.planes {
                for s in &pl.stress {
                    assert!((s[0] - sx).abs() < 1e-9 * sx, "{form:?} {an:?} {s:?}");
                    assert!((s[1] - sy).abs() < 1e-9 * sy);
                    assert!((s[2] - txy).abs() < 1e-9 * sx);
                }
            }
            for s in r.nodal_stress.iter().flatten() {
                assert!((s[0] - sx).abs() < 1e-9 * sx);
            }
        }
    }
}

/// Cantilever 0 ≤ x ≤ l, −h/2 ≤ y ≤ h/2 meshed nx × ny, clamped at x = 0 (ν = 0, plane stress),
/// loaded at x = l by a tip shear `p` (parabolic, consistent) or an end moment `mo` (linear).
/// Returns the vertical tip displacement on the axis.
fn cantilever(nx: usize, ny: usize, form: PlaneFormulation, p: f64, mo: f64) -> f64 {
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
            m.add_plane(
                [id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]],
                mat,
                PlaneAnalysis::PlaneStress,
                form,
            );
        }
    }
    for j in 0..=ny {
        m.pin(id[0][j]);
    }
    // end tractions: σxx = −M y / I, τ = (P / 2I)(h²/4 − y²) (parabolic shear)
    let inertia = h.powi(3) / 12.0;
    let tx = |y: f64| -mo * y / inertia;
    let ty = |y: f64| p / (2.0 * inertia) * (h * h / 4.0 - y * y);
    for j in 0..ny {
        let (y1, y2) = (
            -h / 2.0 + h * j as f64 / ny as f64,
            -h / 2.0 + h * (j + 1) as f64 / ny as f64,
        );
        // consistent nodal forces by 3-point Gauss on the edge
        let g = 0.6f64.sqrt();
        let mut f = [[0.0; 2]; 2];
        for (s, w) in [(-g, 5.0 / 9.0), (0.0, 8.0 / 9.0), (g, 5.0 / 9.0)] {
            let y = 0.5 * (y1 + y2) + 0.5 * (y2 - y1) * s;
            let jw = w * 0.5 * (y2 - y1);
            let n = [0.5 * (1.0 - s), 0.5 * (1.0 + s)];
            for k in 0..2 {
                f[k][0] += jw * n[k] * tx(y);
                f[k][1] += jw * n[k] * ty(y);
            }
        }
        for (k, node) in [id[nx][j], id[nx][j + 1]].into_iter().enumerate() {
            m.add_load(
                LoadGroup::Variable,
                Load::Nodal {
                    node,
                    fx: f[k][0],
                    fy: f[k][1],
                    m: 0.0,
                },
            );
        }
    }
    let r = solve(&m);
    assert_eq!(ny % 2, 0);
    r.displacements[id[nx][ny / 2].0][1]
}

#[test]
fn cantilever_in_bending_converges_to_the_beam_solution() {
    let (l, e, inertia, area) = (10.0, 1000.0, 1.0 / 12.0, 1.0);
    // pure bending (end moment): QM6 is exact on rectangles
    let mo = 1.0;
    let exact_m = mo * l * l / (2.0 * e * inertia);
    let d = cantilever(10, 2, PlaneFormulation::QM6, 0.0, mo);
    assert!((d - exact_m).abs() < 1e-9 * exact_m, "{d} vs {exact_m}");
    // tip shear: beam deflection with shear correction (ν = 0, κ = 5/6)
    let p = -1.0;
    let exact_p = p * l.powi(3) / (3.0 * e * inertia) + p * l / (5.0 / 6.0 * e / 2.0 * area);
    let coarse_qm6 = cantilever(10, 2, PlaneFormulation::QM6, p, 0.0);
    assert!(
        (coarse_qm6 / exact_p - 1.0).abs() < 0.02,
        "QM6 {coarse_qm6} vs {exact_p}"
    );
    // Q4 locks on the coarse mesh and converges under refinement
    let e1 = (cantilever(10, 2, PlaneFormulation::Q4, p, 0.0) / exact_p - 1.0).abs();
    let e2 = (cantilever(20, 4, PlaneFormulation::Q4, p, 0.0) / exact_p - 1.0).abs();
    let e3 = (cantilever(40, 8, PlaneFormulation::Q4, p, 0.0) / exact_p - 1.0).abs();
    eprintln!("QM6 coarse {coarse_qm6} exact {exact_p}; Q4 errors {e1} {e2} {e3}");
    assert!(e1 > 0.1, "Q4 should lock on the coarse mesh: {e1}");
    assert!(
        e2 < e1 / 2.0 && e3 < e2 / 2.0 && e3 < 0.05,
        "{e1} {e2} {e3}"
    );
}

#[test]
fn block_under_self_weight() {
    // laterally confined block, plane strain: σyy = −γ (H − y), σxx = σyy ν/(1 − ν)
    let (w, h, nx, ny, gamma, nu) = (2.0, 4.0, 2, 8, 20.0, 0.3);
    for form in FORMS {
        let mut m = Model::new();
        let mut id = vec![vec![NodeId(0); ny + 1]; nx + 1];
        for (i, col) in id.iter_mut().enumerate() {
            for (j, v) in col.iter_mut().enumerate() {
                // slightly irregular heights of the rows do not matter in 1D
                *v = m.add_node(w * i as f64 / nx as f64, h * j as f64 / ny as f64);
            }
        }
        let mat = PlaneMaterial::new(1.0e4, nu);
        let mut k = 0;
        for i in 0..nx {
            for j in 0..ny {
                m.add_plane(
                    [id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]],
                    mat,
                    PlaneAnalysis::PlaneStrain,
                    form,
                );
                m.add_load(
                    LoadGroup::Constant,
                    Load::BodyForce {
                        element: ElementId(k),
                        force: [0.0, -gamma],
                    },
                );
                k += 1;
            }
        }
        for i in 0..=nx {
            m.add_support(id[i][0], SupportDof::Uy);
        }
        for j in 0..=ny {
            m.add_support(id[0][j], SupportDof::Ux);
            m.add_support(id[nx][j], SupportDof::Ux);
        }
        let r = solve(&m);
        for pl in &r.planes {
            let yc: f64 = pl.gauss_points.iter().map(|g| g[1]).sum::<f64>() / 4.0;
            let syy = -gamma * (h - yc);
            for s in &pl.stress {
                assert!(
                    (s[1] - syy).abs() < 1e-9 * gamma * h,
                    "{form:?} {s:?} vs {syy}"
                );
                assert!((s[0] - syy * nu / (1.0 - nu)).abs() < 1e-9 * gamma * h);
                assert!(s[2].abs() < 1e-9 * gamma * h);
                assert!((s[3] - nu * (s[0] + s[1])).abs() < 1e-9 * gamma * h);
            }
        }
        // averaged nodal stress at interior heights is exact (linear field)
        for j in 1..ny {
            let y = h * j as f64 / ny as f64;
            let s = r.nodal_stress[id[1][j].0].unwrap();
            assert!((s[1] + gamma * (h - y)).abs() < 1e-9 * gamma * h);
        }
        // total base reaction = weight
        let base: f64 = r
            .reactions
            .iter()
            .filter(|x| x.dof == SupportDof::Uy)
            .map(|x| x.value)
            .sum();
        assert!((base - gamma * w * h).abs() < 1e-9 * gamma * w * h);
    }
}

#[test]
fn free_thermal_expansion_is_stress_free() {
    let (alpha, dt, nu) = (1e-5, 30.0, 0.25);
    for form in FORMS {
        for an in ANALYSES {
            let mut m = Model::new();
            let pts = [[0.0, 0.0], [2.0, 0.1], [2.2, 1.5], [-0.1, 1.2]];
            let ids: Vec<NodeId> = pts.iter().map(|p| m.add_node(p[0], p[1])).collect();
            m.add_plane(
                [ids[0], ids[1], ids[2], ids[3]],
                PlaneMaterial::new(1e5, nu).with_alpha(alpha),
                an,
                form,
            );
            m.pin(ids[0]);
            m.add_support(ids[1], SupportDof::Along([-0.1, 2.0]));
            m.add_load(
                LoadGroup::Variable,
                Load::Temperature {
                    element: ElementId(0),
                    uniform: dt,
                    gradient: 0.0,
                },
            );
            let r = solve(&m);
            let strain = alpha
                * dt
                * if an == PlaneAnalysis::PlaneStrain {
                    1.0 + nu
                } else {
                    1.0
                };
            for (i, p) in pts.iter().enumerate() {
                assert!(
                    (r.displacements[i][0] - strain * p[0]).abs() < 1e-14,
                    "{form:?} {an:?}"
                );
                assert!((r.displacements[i][1] - strain * p[1]).abs() < 1e-14);
            }
            for s in &r.planes[0].stress {
                assert!(
                    s[0].abs() < 1e-8 && s[1].abs() < 1e-8 && s[2].abs() < 1e-8,
                    "{s:?}"
                );
                if an == PlaneAnalysis::PlaneStrain {
                    // σzz = −E α ΔT (the out-of-plane restraint)
                    assert!((s[3] + 1e5 * alpha * dt).abs() < 1e-8);
                }
            }
        }
    }
}
