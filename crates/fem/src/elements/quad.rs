//! The 4-node plane elements: bilinear Q4 and Q4 with incompatible modes QM6, in plane stress
//! or plane strain, with body forces, uniform temperature changes and stress recovery at the
//! 2×2 Gauss points.

use super::dense::{condense_dofs, solve_small};
use super::{positive, ElementUnit, Recovered};
use crate::error::FemError;
use crate::model::{
    ElementId, Load, Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial,
};
use crate::results::PlaneResult;

/// A plane element (the unit of [`crate::Element::Plane`]).
pub(crate) struct Quad<'a> {
    pub nodes: &'a [NodeId; 4],
    pub material: &'a PlaneMaterial,
    pub analysis: PlaneAnalysis,
    pub formulation: PlaneFormulation,
}

/// The uniform temperature change of a plane element: its temperature loads, each times its
/// load factor.
pub(crate) fn uniform_temperature(loads: &[(f64, &Load)]) -> f64 {
    loads
        .iter()
        .filter_map(|(fc, l)| match l {
            Load::Temperature { uniform, .. } => Some(fc * uniform),
            _ => None,
        })
        .sum()
}

/// The two translations of every node of a plane element, in node order.
pub(crate) fn plane_dofs(nodes: &[NodeId]) -> Vec<usize> {
    nodes.iter().flat_map(|n| [3 * n.0, 3 * n.0 + 1]).collect()
}

/// The checks of a plane material shared by every plane element: `E` and the thickness
/// positive, Poisson's ratio in (−1, 0.5), a finite expansion coefficient.
pub(crate) fn check_plane_material(
    material: &PlaneMaterial,
    id: ElementId,
) -> Result<(), FemError> {
    positive(id, "E", material.e)?;
    positive(id, "thickness", material.thickness)?;
    if !(material.nu > -1.0 && material.nu < 0.5) {
        return Err(FemError::PoissonOutOfRange {
            element: id,
            nu: material.nu,
        });
    }
    if !material.alpha.is_finite() {
        return Err(FemError::NotFinite {
            what: format!("alpha of element {}", id.0),
        });
    }
    Ok(())
}

impl Quad<'_> {
    fn xy(&self, model: &Model) -> [[f64; 2]; 4] {
        self.nodes.map(|n| model.nodes[n.0])
    }
}

impl ElementUnit for Quad<'_> {
    fn nodes(&self) -> &[NodeId] {
        self.nodes
    }

    fn dofs(&self) -> Vec<usize> {
        plane_dofs(self.nodes)
    }

    fn check(&self, model: &Model, id: ElementId) -> Result<(), FemError> {
        check_plane_material(self.material, id)?;
        plane_min_det_j(&self.xy(model), id)
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
        plane_stiffness(
            &self.xy(model),
            self.material,
            self.analysis,
            self.formulation,
        )
    }

    fn equivalent_load(&self, model: &Model, load: &Load) -> Option<Vec<f64>> {
        let xy = self.xy(model);
        match *load {
            Load::BodyForce { force, .. } => Some(plane_body_load(&xy, self.material, force)),
            Load::Temperature { uniform, .. } => Some(plane_thermal_load(
                &xy,
                self.material,
                self.analysis,
                self.formulation,
                uniform,
            )),
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
        let dt = uniform_temperature(loads);
        let st = plane_stresses(&xy, self.material, self.analysis, self.formulation, ue, dt);
        Recovered::Plane {
            result: PlaneResult {
                element: id,
                gauss_points: gauss_coordinates(&xy),
                stress: st,
            },
            at_nodes: extrapolate_to_nodes(&st).to_vec(),
        }
    }
}

pub(crate) const XI: [f64; 4] = [-1.0, 1.0, 1.0, -1.0];
pub(crate) const ETA: [f64; 4] = [-1.0, -1.0, 1.0, 1.0];

/// Gauss points (2×2) in node order.
pub(crate) fn gauss_points() -> [[f64; 2]; 4] {
    let g = 1.0 / 3f64.sqrt();
    [[-g, -g], [g, -g], [g, g], [-g, g]]
}

pub(crate) fn shape(xi: f64, eta: f64) -> [f64; 4] {
    let mut n = [0.0; 4];
    for i in 0..4 {
        n[i] = 0.25 * (1.0 + XI[i] * xi) * (1.0 + ETA[i] * eta);
    }
    n
}

/// Jacobian [[x_ξ, y_ξ], [x_η, y_η]] and shape derivatives in ξ, η.
fn jacobian(xy: &[[f64; 2]; 4], xi: f64, eta: f64) -> ([[f64; 2]; 2], [[f64; 4]; 2]) {
    let mut dn = [[0.0; 4]; 2];
    for i in 0..4 {
        dn[0][i] = 0.25 * XI[i] * (1.0 + ETA[i] * eta);
        dn[1][i] = 0.25 * ETA[i] * (1.0 + XI[i] * xi);
    }
    let mut j = [[0.0; 2]; 2];
    for r in 0..2 {
        for i in 0..4 {
            j[r][0] += dn[r][i] * xy[i][0];
            j[r][1] += dn[r][i] * xy[i][1];
        }
    }
    (j, dn)
}

fn det2(j: &[[f64; 2]; 2]) -> f64 {
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

/// Maps (∂/∂ξ, ∂/∂η) to (∂/∂x, ∂/∂y) with the inverse of `j`.
fn map_deriv(j: &[[f64; 2]; 2], d: [f64; 2]) -> [f64; 2] {
    let det = det2(j);
    [
        (j[1][1] * d[0] - j[0][1] * d[1]) / det,
        (-j[1][0] * d[0] + j[0][0] * d[1]) / det,
    ]
}

/// Smallest Jacobian determinant over corners, centre and Gauss points; error if ≤ 0.
fn plane_min_det_j(xy: &[[f64; 2]; 4], id: ElementId) -> Result<(), FemError> {
    let mut pts: Vec<[f64; 2]> = gauss_points().to_vec();
    pts.push([0.0, 0.0]);
    for i in 0..4 {
        pts.push([XI[i], ETA[i]]);
    }
    let mut min = f64::INFINITY;
    let mut scale: f64 = 0.0;
    for i in 0..4 {
        let j = (i + 1) % 4;
        scale = scale.max((xy[j][0] - xy[i][0]).hypot(xy[j][1] - xy[i][1]));
    }
    for p in pts {
        let (j, _) = jacobian(xy, p[0], p[1]);
        min = min.min(det2(&j));
    }
    if !(min > 1e-12 * scale * scale) {
        return Err(FemError::DistortedElement {
            element: id,
            det_j: min,
        });
    }
    Ok(())
}

/// Elasticity matrix (σxx, σyy, τxy) and the thermal strain factor
/// (`ε_th = factor·α·ΔT·[1, 1, 0]`).
pub(crate) fn elasticity(m: &PlaneMaterial, a: PlaneAnalysis) -> ([[f64; 3]; 3], f64) {
    let (e, nu) = (m.e, m.nu);
    match a {
        PlaneAnalysis::PlaneStress => {
            let c = e / (1.0 - nu * nu);
            (
                [
                    [c, c * nu, 0.0],
                    [c * nu, c, 0.0],
                    [0.0, 0.0, c * (1.0 - nu) / 2.0],
                ],
                1.0,
            )
        }
        PlaneAnalysis::PlaneStrain => {
            let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
            (
                [
                    [c * (1.0 - nu), c * nu, 0.0],
                    [c * nu, c * (1.0 - nu), 0.0],
                    [0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0],
                ],
                1.0 + nu,
            )
        }
    }
}

/// Strain-displacement matrix at (ξ, η): 3 × 8 compatible part and 3 × 4 incompatible part
/// (QM6: derivatives with the centre Jacobian, scaled by det J0 / det J), and det J.
fn b_matrices(xy: &[[f64; 2]; 4], xi: f64, eta: f64) -> ([[f64; 8]; 3], [[f64; 4]; 3], f64) {
    let (j, dn) = jacobian(xy, xi, eta);
    let det = det2(&j);
    let mut b = [[0.0; 8]; 3];
    for i in 0..4 {
        let d = map_deriv(&j, [dn[0][i], dn[1][i]]);
        b[0][2 * i] = d[0];
        b[1][2 * i + 1] = d[1];
        b[2][2 * i] = d[1];
        b[2][2 * i + 1] = d[0];
    }
    let (j0, _) = jacobian(xy, 0.0, 0.0);
    let ratio = det2(&j0) / det;
    let p1 = map_deriv(&j0, [-2.0 * xi, 0.0]);
    let p2 = map_deriv(&j0, [0.0, -2.0 * eta]);
    let mut bi = [[0.0; 4]; 3];
    for (k, p) in [p1, p2].iter().enumerate() {
        // u-mode k, v-mode k
        bi[0][k] = p[0] * ratio;
        bi[2][k] = p[1] * ratio;
        bi[1][2 + k] = p[1] * ratio;
        bi[2][2 + k] = p[0] * ratio;
    }
    (b, bi, det)
}

/// Full 12 × 12 stiffness (8 nodal + 4 incompatible DOFs) or 8 × 8 for Q4.
fn plane_full_k(
    xy: &[[f64; 2]; 4],
    m: &PlaneMaterial,
    a: PlaneAnalysis,
    form: PlaneFormulation,
) -> (Vec<f64>, usize) {
    let (d, _) = elasticity(m, a);
    let n = if form == PlaneFormulation::QM6 { 12 } else { 8 };
    let mut k = vec![0.0; n * n];
    for gp in gauss_points() {
        let (b, bi, det) = b_matrices(xy, gp[0], gp[1]);
        let w = det * m.thickness;
        let col = |c: usize, r: usize| if c < 8 { b[r][c] } else { bi[r][c - 8] };
        for i in 0..n {
            let mut db = [0.0; 3];
            for r in 0..3 {
                db[r] = (0..3).map(|s| d[r][s] * col(i, s)).sum();
            }
            for j in 0..n {
                let v: f64 = (0..3).map(|r| col(j, r) * db[r]).sum();
                k[j * n + i] += w * v;
            }
        }
    }
    (k, n)
}

/// Condensed plane element stiffness (8 × 8).
pub(crate) fn plane_stiffness(
    xy: &[[f64; 2]; 4],
    m: &PlaneMaterial,
    a: PlaneAnalysis,
    form: PlaneFormulation,
) -> Vec<f64> {
    let (mut k, n) = plane_full_k(xy, m, a, form);
    if n == 8 {
        return k;
    }
    condense_dofs(&mut k, 12, None, &[8, 9, 10, 11]);
    let mut k8 = vec![0.0; 64];
    for i in 0..8 {
        for j in 0..8 {
            k8[i * 8 + j] = k[i * 12 + j];
        }
    }
    k8
}

fn plane_body_load(xy: &[[f64; 2]; 4], m: &PlaneMaterial, b: [f64; 2]) -> Vec<f64> {
    let mut f = vec![0.0; 8];
    for gp in gauss_points() {
        let (j, _) = jacobian(xy, gp[0], gp[1]);
        let w = det2(&j) * m.thickness;
        let n = shape(gp[0], gp[1]);
        for i in 0..4 {
            f[2 * i] += w * n[i] * b[0];
            f[2 * i + 1] += w * n[i] * b[1];
        }
    }
    f
}

fn plane_thermal_load(
    xy: &[[f64; 2]; 4],
    m: &PlaneMaterial,
    a: PlaneAnalysis,
    _form: PlaneFormulation,
    dt: f64,
) -> Vec<f64> {
    // ∫ Bᵀ D ε_th dV; the incompatible part vanishes for a uniform ΔT (∫ B_inc dV = 0).
    let (d, fac) = elasticity(m, a);
    let eps = fac * m.alpha * dt;
    let sig = [(d[0][0] + d[0][1]) * eps, (d[1][0] + d[1][1]) * eps, 0.0];
    let mut f = vec![0.0; 8];
    for gp in gauss_points() {
        let (b, _, det) = b_matrices(xy, gp[0], gp[1]);
        let w = det * m.thickness;
        for (c, fc) in f.iter_mut().enumerate() {
            *fc += w * (0..3).map(|r| b[r][c] * sig[r]).sum::<f64>();
        }
    }
    f
}

/// Stresses (σxx, σyy, τxy, σzz) at the 2×2 Gauss points for nodal displacements `u`
/// (ux1, uy1, …, ux4, uy4) and a uniform temperature change `dt`.
pub(crate) fn plane_stresses(
    xy: &[[f64; 2]; 4],
    m: &PlaneMaterial,
    a: PlaneAnalysis,
    form: PlaneFormulation,
    u: &[f64],
    dt: f64,
) -> [[f64; 4]; 4] {
    // incompatible mode amplitudes: α = −K_aa⁻¹ K_au u (they carry no load).
    let mut alpha = [0.0; 4];
    if form == PlaneFormulation::QM6 {
        let (k, n) = plane_full_k(xy, m, a, form);
        let mut kaa = vec![0.0; 16];
        let mut rhs = vec![0.0; 4];
        for i in 0..4 {
            for j in 0..4 {
                kaa[i * 4 + j] = k[(8 + i) * n + 8 + j];
            }
            rhs[i] = -(0..8).map(|j| k[(8 + i) * n + j] * u[j]).sum::<f64>();
        }
        solve_small(&mut kaa, 4, &mut rhs, 1);
        alpha.copy_from_slice(&rhs);
    }
    let (d, fac) = elasticity(m, a);
    let eth = fac * m.alpha * dt;
    let mut out = [[0.0; 4]; 4];
    for (g, gp) in gauss_points().iter().enumerate() {
        let (b, bi, _) = b_matrices(xy, gp[0], gp[1]);
        let mut eps = [0.0; 3];
        for r in 0..3 {
            eps[r] = (0..8).map(|c| b[r][c] * u[c]).sum::<f64>()
                + (0..4).map(|c| bi[r][c] * alpha[c]).sum::<f64>();
        }
        eps[0] -= eth;
        eps[1] -= eth;
        let mut s = [0.0; 4];
        for r in 0..3 {
            s[r] = (0..3).map(|c| d[r][c] * eps[c]).sum();
        }
        if a == PlaneAnalysis::PlaneStrain {
            s[3] = m.nu * (s[0] + s[1]) - m.e * m.alpha * dt;
        }
        out[g] = s;
    }
    out
}

/// Global coordinates of the Gauss points of a plane element.
pub(crate) fn gauss_coordinates(xy: &[[f64; 2]; 4]) -> [[f64; 2]; 4] {
    gauss_points().map(|gp| {
        let n = shape(gp[0], gp[1]);
        [
            (0..4).map(|i| n[i] * xy[i][0]).sum(),
            (0..4).map(|i| n[i] * xy[i][1]).sum(),
        ]
    })
}

/// Extrapolates Gauss-point values to the corner nodes (bilinear through the Gauss points).
pub(crate) fn extrapolate_to_nodes(g: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let r = 3f64.sqrt();
    let mut out = [[0.0; 4]; 4];
    for i in 0..4 {
        let n = shape(XI[i] * r, ETA[i] * r);
        for c in 0..4 {
            out[i][c] = (0..4).map(|j| n[j] * g[j][c]).sum();
        }
    }
    out
}
