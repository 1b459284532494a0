//! A block on rigid ground meshed with triangles and with quadrilaterals slides at
//! `H = f·W` exactly.
//!
//! Reference: statics of the whole block. Whatever the mesh and however the contact forces are
//! distributed along the base, vertical equilibrium gives `Σ x_n = W` and horizontal
//! equilibrium `Σ x_t = H`; the block can slide only when every pair is at its friction limit,
//! `|x_t| = f·x_n`, i.e. at `H = f·Σ x_n = f·W`; before that it cannot move as a rigid body
//! (and with its resultant within the base's middle third it does not tip). The mechanism is
//! then the rigid translation: no normal rate, the same tangential rate at every pair.

use unilateral_analysis::{analyze, Outcome};
use unilateral_contact::{Follow, SolveSettings};
use unilateral_fem::{
    ContactPairSpec, Load, LoadGroup, Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial,
};

/// The mesh of the block.
#[derive(Debug, Clone, Copy)]
enum Mesh {
    Quads(PlaneFormulation),
    /// Each quadrilateral split into two triangles, along alternating diagonals.
    Triangles,
}

/// A block `width × height` (plane strain, unit thickness, unit weight `gamma`) meshed
/// `nx × ny`, on rigid ground through a frictional pair at each bottom node, pushed by `h` at
/// the middle node of its left side (the variable load). Returns the model.
fn block(mesh: Mesh, width: f64, height: f64, gamma: f64, f: f64, h: f64) -> Model {
    let (nx, ny) = (6, 4);
    let mut m = Model::new();
    let mut id = vec![vec![NodeId(0); ny + 1]; nx + 1];
    for (i, col) in id.iter_mut().enumerate() {
        for (j, v) in col.iter_mut().enumerate() {
            *v = m.add_node(width * i as f64 / nx as f64, height * j as f64 / ny as f64);
        }
    }
    // concrete in N and m (E = 30 GPa); the answer is a ratio of forces
    let mat = PlaneMaterial::new(3.0e10, 0.2);
    let an = PlaneAnalysis::PlaneStrain;
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]);
            let elements = match mesh {
                Mesh::Quads(form) => vec![m.add_plane([a, b, c, d], mat, an, form)],
                Mesh::Triangles => {
                    let [t1, t2] = if (i + j) % 2 == 0 {
                        [[a, b, c], [a, c, d]]
                    } else {
                        [[a, b, d], [b, c, d]]
                    };
                    vec![m.add_triangle(t1, mat, an), m.add_triangle(t2, mat, an)]
                }
            };
            for element in elements {
                m.add_load(
                    LoadGroup::Constant,
                    Load::BodyForce {
                        element,
                        force: [0.0, -gamma],
                    },
                );
            }
        }
    }
    for col in &id {
        m.add_contact_pair(ContactPairSpec::to_ground(col[0], [0.0, 1.0]).friction(f));
    }
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: id[0][ny / 2],
            fx: h,
            fy: 0.0,
            m: 0.0,
        },
    );
    m
}

#[test]
fn triangle_and_quadrilateral_blocks_slide_at_f_times_w() {
    let (width, height, gamma, f, h) = (2.0, 1.0, 24.0e3, 0.35, 1.0e3);
    let w = gamma * width * height;
    let p_slide = f * w / h;
    let settings = SolveSettings {
        tightening: 0.0,
        follow: Follow::ToEnd,
        ..Default::default()
    };
    for mesh in [
        Mesh::Triangles,
        Mesh::Quads(PlaneFormulation::QM6),
        Mesh::Quads(PlaneFormulation::Q4),
    ] {
        let model = block(mesh, width, height, gamma, f, h);
        // the mesh is what it says: 48 triangles or 24 quadrilaterals
        let count = model.elements().len();
        assert_eq!(
            count,
            if matches!(mesh, Mesh::Triangles) {
                48
            } else {
                24
            }
        );
        let a = analyze(&model, &settings).unwrap_or_else(|e| panic!("{mesh:?}: {e}"));
        let Outcome::Mechanism { p_limit, mode } = &a.solution.outcome else {
            panic!(
                "{mesh:?}: expected a mechanism, got {:?}",
                a.solution.outcome
            )
        };
        assert!(
            (p_limit - p_slide).abs() < 1e-9 * p_slide,
            "{mesh:?}: p_lim = {p_limit}, f·W/H = {p_slide}"
        );
        // the rigid slide in +x (t = (n_y, −n_x) = (1, 0)): no opening, the same positive
        // slip rate at every pair (the mode is scaled, only the ratios count)
        assert_eq!(mode.len(), 7, "{mesh:?}");
        let rate = mode
            .iter()
            .fold(0.0f64, |r, m| r.max(m.0.abs()).max(m.1.abs()));
        assert!(rate > 0.0, "{mesh:?}: {mode:?}");
        for &(zn, zt) in mode {
            assert!(zn.abs() < 1e-9 * rate, "{mesh:?}: {mode:?}");
            assert!((zt - rate).abs() < 1e-9 * rate, "{mesh:?}: {mode:?}");
        }
        // and just below the limit the base carries the weight (Σ x_n = W) and the push
        // (Σ |x_t| = p H, all pairs pushed the same way)
        let p = 0.999 * p_slide;
        let (pairs, _) = a.results_at(p).unwrap();
        let sum_n: f64 = pairs.iter().map(|r| r.x_n).sum();
        let sum_t: f64 = pairs.iter().map(|r| r.x_t).sum();
        assert!(
            (sum_n - w).abs() < 1e-9 * w,
            "{mesh:?}: Σ x_n = {sum_n} vs {w}"
        );
        assert!(
            (sum_t.abs() - p * h).abs() < 1e-9 * w,
            "{mesh:?}: Σ x_t = {sum_t} vs {}",
            p * h
        );
    }
}
