//! Element stiffness matrices, equivalent nodal loads and stress recovery.
//!
//! Physical DOF numbering: node `i` owns `3i` (ux), `3i+1` (uy), `3i+2` (rz).
//! Dense element matrices are row-major `Vec<f64>` of size `n × n`.

use crate::error::FemError;
use crate::model::{
    Element, ElementId, Load, LoadFrame, Model, PlaneAnalysis, PlaneFormulation, PlaneMaterial,
    Releases,
};

/// An element matrix in global physical DOFs.
pub(crate) struct ElemMat {
    pub dofs: Vec<usize>,
    pub k: Vec<f64>,
}

/// Solves `a x = b` in place for `nrhs` right-hand sides stored row-major in `b` (`n × nrhs`).
/// Gaussian elimination with partial pivoting; the matrices here are at most 12 × 12.
pub(crate) fn solve_small(a: &mut [f64], n: usize, b: &mut [f64], nrhs: usize) {
    for col in 0..n {
        let mut piv = col;
        for r in col + 1..n {
            if a[r * n + col].abs() > a[piv * n + col].abs() {
                piv = r;
            }
        }
        if piv != col {
            for c in 0..n {
                a.swap(col * n + c, piv * n + c);
            }
            for c in 0..nrhs {
                b.swap(col * nrhs + c, piv * nrhs + c);
            }
        }
        let d = a[col * n + col];
        for r in col + 1..n {
            let f = a[r * n + col] / d;
            if f != 0.0 {
                for c in col..n {
                    a[r * n + c] -= f * a[col * n + c];
                }
                for c in 0..nrhs {
                    b[r * nrhs + c] -= f * b[col * nrhs + c];
                }
            }
        }
    }
    for col in (0..n).rev() {
        let d = a[col * n + col];
        for c in 0..nrhs {
            let mut s = b[col * nrhs + c];
            for k in col + 1..n {
                s -= a[col * n + k] * b[k * nrhs + c];
            }
            b[col * nrhs + c] = s / d;
        }
    }
}

/// Static condensation of the DOFs `drop` out of `k` (n × n) and the load `f`:
/// `k ← k_kk − k_kd k_dd⁻¹ k_dk`, `f ← f_k − k_kd k_dd⁻¹ f_d`; dropped rows/cols become zero.
pub(crate) fn condense_dofs(k: &mut [f64], n: usize, f: Option<&mut [f64]>, drop: &[usize]) {
    if drop.is_empty() {
        return;
    }
    let nd = drop.len();
    let keep: Vec<usize> = (0..n).filter(|i| !drop.contains(i)).collect();
    // X = k_dd⁻¹ [k_dk | f_d]
    let mut kdd = vec![0.0; nd * nd];
    for (a, &i) in drop.iter().enumerate() {
        for (b, &j) in drop.iter().enumerate() {
            kdd[a * nd + b] = k[i * n + j];
        }
    }
    let nrhs = n + 1;
    let mut x = vec![0.0; nd * nrhs];
    for (a, &i) in drop.iter().enumerate() {
        for j in 0..n {
            x[a * nrhs + j] = k[i * n + j];
        }
    }
    let have_f = f.is_some();
    let mut fv = f;
    if let Some(f) = fv.as_deref() {
        for (a, &i) in drop.iter().enumerate() {
            x[a * nrhs + n] = f[i];
        }
    }
    solve_small(&mut kdd, nd, &mut x, nrhs);
    let old = k.to_vec();
    for &i in &keep {
        for &j in &keep {
            let mut s = old[i * n + j];
            for (a, &d) in drop.iter().enumerate() {
                s -= old[i * n + d] * x[a * nrhs + j];
            }
            k[i * n + j] = s;
        }
        if have_f {
            let f = fv.as_deref_mut().unwrap();
            let mut s = f[i];
            for (a, &d) in drop.iter().enumerate() {
                s -= old[i * n + d] * x[a * nrhs + n];
            }
            f[i] = s;
        }
    }
    for &d in drop {
        for j in 0..n {
            k[d * n + j] = 0.0;
            k[j * n + d] = 0.0;
        }
        if let Some(f) = fv.as_deref_mut() {
            f[d] = 0.0;
        }
    }
}

/// Geometry of a two-node line element: length, cos, sin.
pub(crate) fn line_geometry(model: &Model, a: usize, b: usize) -> (f64, f64, f64) {
    let (pa, pb) = (model.nodes[a], model.nodes[b]);
    let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
    let l = dx.hypot(dy);
    (l, dx / l, dy / l)
}

/// Local frame stiffness (u1, v1, θ1, u2, v2, θ2), before releases.
fn frame_local_k(e: f64, a: f64, i: f64, l: f64) -> Vec<f64> {
    let mut k = vec![0.0; 36];
    let ea = e * a / l;
    let (b1, b2, b3, b4) = (
        12.0 * e * i / l.powi(3),
        6.0 * e * i / (l * l),
        4.0 * e * i / l,
        2.0 * e * i / l,
    );
    let mut set = |r: usize, c: usize, v: f64| {
        k[r * 6 + c] = v;
        k[c * 6 + r] = v;
    };
    set(0, 0, ea);
    set(3, 3, ea);
    set(0, 3, -ea);
    set(1, 1, b1);
    set(4, 4, b1);
    set(1, 4, -b1);
    set(1, 2, b2);
    set(1, 5, b2);
    set(2, 4, -b2);
    set(4, 5, -b2);
    set(2, 2, b3);
    set(5, 5, b3);
    set(2, 5, b4);
    k
}

fn release_dofs(r: Releases) -> Vec<usize> {
    let mut d = Vec::new();
    if r.start {
        d.push(2);
    }
    if r.end {
        d.push(5);
    }
    d
}

/// Rotates a local 6-vector (frame) or 4-vector (bar) to global.
fn to_global_vec(v: &[f64], c: f64, s: f64) -> Vec<f64> {
    let mut g = v.to_vec();
    let step = if v.len() == 6 { 3 } else { 2 };
    for node in 0..2 {
        let o = node * step;
        g[o] = c * v[o] - s * v[o + 1];
        g[o + 1] = s * v[o] + c * v[o + 1];
    }
    g
}

/// Rotates a global 6-vector (frame) or 4-vector (bar) to local.
pub(crate) fn to_local_vec(v: &[f64], c: f64, s: f64) -> Vec<f64> {
    let mut g = v.to_vec();
    let step = if v.len() == 6 { 3 } else { 2 };
    for node in 0..2 {
        let o = node * step;
        g[o] = c * v[o] + s * v[o + 1];
        g[o + 1] = -s * v[o] + c * v[o + 1];
    }
    g
}

/// `Tᵀ k T` for a local line-element matrix.
fn to_global_mat(k: &[f64], n: usize, c: f64, s: f64) -> Vec<f64> {
    // T is block diagonal with [[c, s], [-s, c]] on the translations.
    let mut t = vec![0.0; n * n];
    let step = if n == 6 { 3 } else { 2 };
    for node in 0..2 {
        let o = node * step;
        t[o * n + o] = c;
        t[o * n + o + 1] = s;
        t[(o + 1) * n + o] = -s;
        t[(o + 1) * n + o + 1] = c;
        if step == 3 {
            t[(o + 2) * n + o + 2] = 1.0;
        }
    }
    // Tᵀ (k T): two products of small row-major matrices, `a` read transposed or not.
    let product = |a: &[f64], a_transposed: bool, b: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                out[i * n + j] = (0..n)
                    .map(|m| {
                        let aim = if a_transposed {
                            a[m * n + i]
                        } else {
                            a[i * n + m]
                        };
                        aim * b[m * n + j]
                    })
                    .sum();
            }
        }
        out
    };
    product(&t, true, &product(k, false, &t))
}

/// Local stiffness of a frame or bar after releases (6 × 6 or 4 × 4), with (L, c, s).
pub(crate) fn line_local_k(model: &Model, el: &Element) -> (Vec<f64>, usize, f64, f64, f64) {
    match el {
        Element::Frame {
            nodes,
            section,
            releases,
        } => {
            let (l, c, s) = line_geometry(model, nodes[0].0, nodes[1].0);
            let mut k = frame_local_k(section.e, section.area, section.inertia, l);
            condense_dofs(&mut k, 6, None, &release_dofs(*releases));
            (k, 6, l, c, s)
        }
        Element::Bar { nodes, section } => {
            let (l, c, s) = line_geometry(model, nodes[0].0, nodes[1].0);
            let ea = section.e * section.area / l;
            let mut k = vec![0.0; 16];
            k[0] = ea;
            k[2] = -ea;
            k[2 * 4] = -ea;
            k[2 * 4 + 2] = ea;
            (k, 4, l, c, s)
        }
        Element::Plane { .. } => unreachable!("not a line element"),
    }
}

/// Physical DOFs of an element.
pub(crate) fn element_dofs(el: &Element) -> Vec<usize> {
    match el {
        Element::Frame { nodes, .. } => nodes
            .iter()
            .flat_map(|n| [3 * n.0, 3 * n.0 + 1, 3 * n.0 + 2])
            .collect(),
        Element::Bar { nodes, .. } => nodes.iter().flat_map(|n| [3 * n.0, 3 * n.0 + 1]).collect(),
        Element::Plane { nodes, .. } => nodes.iter().flat_map(|n| [3 * n.0, 3 * n.0 + 1]).collect(),
    }
}

/// Global stiffness of an element.
pub(crate) fn element_stiffness(model: &Model, el: &Element) -> ElemMat {
    let dofs = element_dofs(el);
    let k = match el {
        Element::Frame { .. } | Element::Bar { .. } => {
            let (k, n, _, c, s) = line_local_k(model, el);
            to_global_mat(&k, n, c, s)
        }
        Element::Plane {
            nodes,
            material,
            analysis,
            formulation,
        } => {
            let xy = nodes.map(|n| model.nodes[n.0]);
            plane_stiffness(&xy, material, *analysis, *formulation)
        }
    };
    ElemMat { dofs, k }
}

/// Local distributed load on a line element: intensities (axial, transverse) at start and end.
pub(crate) fn line_local_intensity(load: &Load, c: f64, s: f64) -> Option<([f64; 2], [f64; 2])> {
    let rot = |v: [f64; 2]| [c * v[0] + s * v[1], -s * v[0] + c * v[1]];
    match *load {
        Load::Distributed {
            start, end, frame, ..
        } => Some(match frame {
            LoadFrame::Local => (start, end),
            LoadFrame::Global => (rot(start), rot(end)),
        }),
        Load::BodyForce { force, .. } => {
            let f = rot(force);
            Some((f, f))
        }
        _ => None,
    }
}

/// Equivalent nodal load of an element load, in global physical DOFs of the element
/// (`element_dofs` order). `None` if the load is not an element load.
pub(crate) fn element_load(model: &Model, el: &Element, load: &Load) -> Option<Vec<f64>> {
    match el {
        Element::Frame { section, .. } | Element::Bar { section, .. } => {
            let is_frame = matches!(el, Element::Frame { .. });
            let (k, n, l, c, s) = line_local_k(model, el);
            let mut f = vec![0.0; 6];
            if let Some((q1, q2)) = line_local_intensity(load, c, s) {
                // 3-point Gauss on [0, 1]: exact for linear load × cubic shape.
                let g = (0.6f64).sqrt();
                for (xi, w) in [
                    (0.5 * (1.0 - g), 5.0 / 18.0),
                    (0.5, 8.0 / 18.0),
                    (0.5 * (1.0 + g), 5.0 / 18.0),
                ] {
                    let qa = q1[0] + (q2[0] - q1[0]) * xi;
                    let qt = q1[1] + (q2[1] - q1[1]) * xi;
                    let wl = w * l;
                    f[0] += wl * qa * (1.0 - xi);
                    f[3] += wl * qa * xi;
                    if is_frame {
                        f[1] += wl * qt * (1.0 - 3.0 * xi * xi + 2.0 * xi.powi(3));
                        f[2] += wl * qt * l * (xi - 2.0 * xi * xi + xi.powi(3));
                        f[4] += wl * qt * (3.0 * xi * xi - 2.0 * xi.powi(3));
                        f[5] += wl * qt * l * (-xi * xi + xi.powi(3));
                    } else {
                        f[1] += wl * qt * (1.0 - xi);
                        f[4] += wl * qt * xi;
                    }
                }
            } else if let Load::Temperature {
                uniform, gradient, ..
            } = *load
            {
                let n_th = section.e * section.area * section.alpha * uniform;
                f[0] -= n_th;
                f[3] += n_th;
                if is_frame && gradient != 0.0 {
                    // thermal curvature κ = −α·ΔT/h (hotter +y face elongates).
                    let m_th =
                        section.e * section.inertia * section.alpha * gradient / section.depth;
                    f[2] += m_th;
                    f[5] -= m_th;
                }
            } else {
                return None;
            }
            let mut fl = if is_frame {
                f
            } else {
                vec![f[0], f[1], f[3], f[4]]
            };
            if let Element::Frame { releases, .. } = el {
                let mut k0 = frame_local_k(section.e, section.area, section.inertia, l);
                condense_dofs(&mut k0, 6, Some(&mut fl), &release_dofs(*releases));
            }
            let _ = (k, n);
            Some(to_global_vec(&fl, c, s))
        }
        Element::Plane {
            nodes,
            material,
            analysis,
            formulation,
        } => {
            let xy = nodes.map(|n| model.nodes[n.0]);
            match *load {
                Load::BodyForce { force, .. } => Some(plane_body_load(&xy, material, force)),
                Load::Temperature { uniform, .. } => Some(plane_thermal_load(
                    &xy,
                    material,
                    *analysis,
                    *formulation,
                    uniform,
                )),
                _ => None,
            }
        }
    }
}

// ---------------------------------------------------------------- plane elements

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
pub(crate) fn plane_min_det_j(model: &Model, el: &Element, id: ElementId) -> Result<(), FemError> {
    if let Element::Plane { nodes, .. } = el {
        let xy = nodes.map(|n| model.nodes[n.0]);
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
            let (j, _) = jacobian(&xy, p[0], p[1]);
            min = min.min(det2(&j));
        }
        if !(min > 1e-12 * scale * scale) {
            return Err(FemError::DistortedElement {
                element: id,
                det_j: min,
            });
        }
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
