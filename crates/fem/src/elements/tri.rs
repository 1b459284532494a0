//! The 3-node constant-strain triangle (CST), in plane stress or plane strain, with body
//! forces, uniform temperature changes and stress recovery, with the conventions of the
//! quadrilaterals ([`super::quad`]): the same elasticity matrix and thermal strain factor, body
//! forces per unit volume, stresses `[σxx, σyy, τxy, σzz]` (tension positive).
//!
//! The strain is constant, so the stiffness, the loads and the stresses are exact closed forms
//! (no quadrature): with the signed area `A` and `b_i = y_j − y_k`, `c_i = x_k − x_j` over the
//! cyclic node triples `(i, j, k)`, `B = 1/(2A)·[[b_i, 0], [0, c_i], [c_i, b_i]]`,
//! `K = t·|A|·Bᵀ D B`. Both node orders give the same element (the sign of `A` cancels), so
//! the unit accepts either; [`crate::Model::add_triangle`] stores the nodes counter-clockwise
//! like the quadrilaterals'. A triangle whose area is zero relative to its longest edge
//! squared (collinear or coincident nodes) is refused, naming the element.

use super::quad::elasticity;
use super::{ElementUnit, Recovered};
use crate::error::FemError;
use crate::model::{ElementId, Load, Model, NodeId, PlaneAnalysis, PlaneMaterial};
use crate::results::PlaneResult;

/// A triangle (the unit of [`crate::Element::Triangle`]).
pub(crate) struct Tri<'a> {
    pub nodes: &'a [NodeId; 3],
    pub material: &'a PlaneMaterial,
    pub analysis: PlaneAnalysis,
}

/// The geometry of a triangle: the signed area and the strain–displacement matrix.
struct Geometry {
    /// Signed area (positive counter-clockwise).
    area: f64,
    /// `B` (3 × 6, columns ux1, uy1, …, ux3, uy3).
    b: [[f64; 6]; 3],
}

/// The signed area of a triangle (positive for counter-clockwise nodes).
pub(crate) fn signed_area(xy: &[[f64; 2]; 3]) -> f64 {
    0.5 * ((xy[1][0] - xy[0][0]) * (xy[2][1] - xy[0][1])
        - (xy[2][0] - xy[0][0]) * (xy[1][1] - xy[0][1]))
}

fn geometry(xy: &[[f64; 2]; 3]) -> Geometry {
    let area = signed_area(xy);
    let mut b = [[0.0; 6]; 3];
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let bi = (xy[j][1] - xy[k][1]) / (2.0 * area);
        let ci = (xy[k][0] - xy[j][0]) / (2.0 * area);
        b[0][2 * i] = bi;
        b[1][2 * i + 1] = ci;
        b[2][2 * i] = ci;
        b[2][2 * i + 1] = bi;
    }
    Geometry { area, b }
}

impl Tri<'_> {
    fn xy(&self, model: &Model) -> [[f64; 2]; 3] {
        self.nodes.map(|n| model.nodes[n.0])
    }

    /// The element volume `t·|A|`.
    fn volume(&self, g: &Geometry) -> f64 {
        self.material.thickness * g.area.abs()
    }
}

impl ElementUnit for Tri<'_> {
    fn nodes(&self) -> &[NodeId] {
        self.nodes
    }

    fn dofs(&self) -> Vec<usize> {
        crate::elements::quad::plane_dofs(self.nodes)
    }

    fn check(&self, model: &Model, id: ElementId) -> Result<(), FemError> {
        // the material checks of the quadrilaterals (the same plane material)
        crate::elements::quad::check_plane_material(self.material, id)?;
        let xy = self.xy(model);
        let scale = (0..3)
            .map(|i| {
                let j = (i + 1) % 3;
                (xy[j][0] - xy[i][0]).hypot(xy[j][1] - xy[i][1])
            })
            .fold(0.0f64, f64::max);
        let area = signed_area(&xy).abs();
        if !(area > 1e-12 * scale * scale) {
            return Err(FemError::NonPositiveProperty {
                element: id,
                property: "area of the triangle (its nodes are collinear or coincide)",
                value: area,
            });
        }
        Ok(())
    }

    fn refuses(&self, load: &Load) -> Option<String> {
        match *load {
            Load::Distributed { .. } => Some("this load applies to frames and bars only".into()),
            Load::Temperature { gradient, .. } if gradient != 0.0 => {
                Some("a temperature gradient applies to frames only".into())
            }
            _ => None,
        }
    }

    fn stiffness(&self, model: &Model) -> Vec<f64> {
        let g = geometry(&self.xy(model));
        let (d, _) = elasticity(self.material, self.analysis);
        let w = self.volume(&g);
        let mut k = vec![0.0; 36];
        for i in 0..6 {
            let db: [f64; 3] =
                std::array::from_fn(|r| (0..3).map(|s| d[r][s] * g.b[s][i]).sum::<f64>());
            for j in 0..6 {
                k[j * 6 + i] = w * (0..3).map(|r| g.b[r][j] * db[r]).sum::<f64>();
            }
        }
        k
    }

    fn equivalent_load(&self, model: &Model, load: &Load) -> Option<Vec<f64>> {
        let g = geometry(&self.xy(model));
        let w = self.volume(&g);
        match *load {
            // ∫ N_i b dV = b·t·|A|/3 at each node (linear shape functions)
            Load::BodyForce { force, .. } => Some((0..6).map(|c| w / 3.0 * force[c % 2]).collect()),
            // ∫ Bᵀ D ε_th dV, ε_th = factor·α·ΔT·[1, 1, 0] (the quadrilaterals' convention)
            Load::Temperature { uniform, .. } => {
                let (d, fac) = elasticity(self.material, self.analysis);
                let eps = fac * self.material.alpha * uniform;
                let sig = [(d[0][0] + d[0][1]) * eps, (d[1][0] + d[1][1]) * eps, 0.0];
                Some(
                    (0..6)
                        .map(|c| w * (0..3).map(|r| g.b[r][c] * sig[r]).sum::<f64>())
                        .collect(),
                )
            }
            _ => None,
        }
    }

    fn recover(
        &self,
        model: &Model,
        id: ElementId,
        ue: &[f64],
        loads: &[(f64, &Load)],
    ) -> Recovered {
        let xy = self.xy(model);
        let g = geometry(&xy);
        let dt = crate::elements::quad::uniform_temperature(loads);
        let (d, fac) = elasticity(self.material, self.analysis);
        let eth = fac * self.material.alpha * dt;
        let mut eps: [f64; 3] =
            std::array::from_fn(|r| (0..6).map(|c| g.b[r][c] * ue[c]).sum::<f64>());
        eps[0] -= eth;
        eps[1] -= eth;
        let mut s = [0.0; 4];
        for r in 0..3 {
            s[r] = (0..3).map(|c| d[r][c] * eps[c]).sum();
        }
        if self.analysis == PlaneAnalysis::PlaneStrain {
            let m = self.material;
            s[3] = m.nu * (s[0] + s[1]) - m.e * m.alpha * dt;
        }
        Recovered::Plane {
            result: PlaneResult {
                element: id,
                gauss_points: sampling_points(&xy),
                stress: [s; 4],
            },
            at_nodes: vec![s; 3],
        }
    }
}

/// The four points at which a triangle reports its (constant) stress, in the four-point slot
/// of [`PlaneResult`]: the points of the four-point Gauss rule of the triangle, its centroid
/// and the points with area coordinates `(3/5, 1/5, 1/5)` and their permutations (their mean
/// is the centroid, as the mean of a quadrilateral's Gauss points is its centre).
fn sampling_points(xy: &[[f64; 2]; 3]) -> [[f64; 2]; 4] {
    let at = |l: [f64; 3]| -> [f64; 2] {
        std::array::from_fn(|c| (0..3).map(|i| l[i] * xy[i][c]).sum::<f64>())
    };
    let (a, b, t) = (0.6, 0.2, 1.0 / 3.0);
    [at([t, t, t]), at([a, b, b]), at([b, a, b]), at([b, b, a])]
}
