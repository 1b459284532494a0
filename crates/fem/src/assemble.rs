//! Sparse assembly of the bonded structure in generalized DOFs: `K_II` (lower triangle),
//! `K_Iz`, `K_zz`, and the generalized loads of every load case, settlements included (and of
//! the paper's two groups, the cases `constant` and `variable`, for the condensation).

use crate::condense::{check_memory, dense_condensation_bytes};
use crate::dofs::{build_dof_map, merge, DofMap, Row};
use crate::elements::spring::spring_matrix;
use crate::elements::{element_stiffness, unit as element_unit, ElemMat};
use crate::error::FemError;
use crate::model::{same_dof, ElementId, Load, LoadGroup, Model};

/// The assembled loads of one load case at factor 1.
#[derive(Clone)]
pub(crate) struct CaseVectors {
    /// Physical equivalent loads, without settlement terms.
    pub f_phys: Vec<f64>,
    /// Prescribed values.
    pub s: Vec<f64>,
    /// Generalized loads: I part and z part (settlements included).
    pub b_i: Vec<f64>,
    pub b_z: Vec<f64>,
}
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;

/// Everything assembled from a model.
pub(crate) struct Assembled {
    pub map: DofMap,
    pub kii: Option<SparseColMat<usize, f64>>,
    pub kii_triplets: Vec<Triplet<usize, usize, f64>>,
    pub diag: Vec<f64>,
    /// Columns of K_Iz: for link DOF r, the (free index, value) pairs.
    pub kiz: Vec<Row>,
    pub kzz: Mat<f64>,
    /// The loads of every case of the model, indexed like [`Model::cases`].
    pub cases: Vec<CaseVectors>,
    /// The index of the case of each group (constant, variable), `None` when absent.
    pub group_case: [Option<usize>; 2],
    /// Physical equivalent loads per group (constant, variable), without settlement terms.
    pub f_phys: [Vec<f64>; 2],
    /// Prescribed values per group.
    pub s: [Vec<f64>; 2],
    /// Generalized loads per group: I part and z part (settlements included).
    pub b_i: [Vec<f64>; 2],
    pub b_z: [Vec<f64>; 2],
}

pub(crate) fn assemble(model: &Model) -> Result<Assembled, FemError> {
    let map = build_dof_map(model)?;
    let (n_i, m) = (map.n_i, map.m);
    let nz = 2 * m;
    let z0 = map.z0();
    let p0 = map.p0();
    let nphys = 3 * model.nodes.len();
    // loads, case by case
    let nc = model.cases.len();
    let mut f_phys = vec![vec![0.0; nphys]; nc];
    let mut s = vec![vec![0.0; map.n_p]; nc];
    for (c, l) in &model.loads {
        let gi = c.0;
        match *l {
            Load::Nodal { node, fx, fy, m } => {
                f_phys[gi][3 * node.0] += fx;
                f_phys[gi][3 * node.0 + 1] += fy;
                f_phys[gi][3 * node.0 + 2] += m;
            }
            Load::Settlement { node, dof, value } => {
                let k = map
                    .prescribed
                    .iter()
                    .position(|(n, d, _)| *n == node && same_dof(*d, dof))
                    .expect("validated");
                s[gi][k] += value;
            }
            Load::Distributed { element, .. }
            | Load::BodyForce { element, .. }
            | Load::Temperature { element, .. } => {
                let el = element_unit(&model.elements[element.0]);
                if let Some(fe) = el.equivalent_load(model, l) {
                    if fe.iter().any(|v| !v.is_finite()) {
                        return Err(FemError::Overflow {
                            element: Some(element),
                            what: "its equivalent nodal load vector".into(),
                        });
                    }
                    for (a, d) in el.dofs().into_iter().enumerate() {
                        f_phys[gi][d] += fe[a];
                    }
                }
            }
        }
    }
    let has_settlement: Vec<bool> = s.iter().map(|s| s.iter().any(|v| *v != 0.0)).collect();
    check_memory(
        &format!("{m} contact pairs"),
        dense_condensation_bytes(m, n_i),
    )?;
    let mut f_set = vec![vec![0.0; nphys]; nc];
    let mut trip: Vec<Triplet<usize, usize, f64>> = Vec::new();
    let mut kiz: Vec<Row> = vec![Row::new(); nz];
    let mut kzz = Mat::<f64>::zeros(nz, nz);
    let mut diag = vec![0.0; n_i];
    let mut handle = |em: &ElemMat| {
        let n = em.dofs.len();
        let rows: Vec<&Row> = em.dofs.iter().map(|&d| &map.rows[d]).collect();
        for a in 0..n {
            for b in 0..n {
                let k = em.k[a * n + b];
                if k == 0.0 {
                    continue;
                }
                for &(gi, ci) in rows[a] {
                    if gi >= z0 && gi < p0 {
                        // z row: only zz (the Iz block is taken from its transpose)
                        for &(gj, cj) in rows[b] {
                            if gj >= z0 && gj < p0 {
                                kzz[(gi - z0, gj - z0)] += ci * cj * k;
                            }
                        }
                    } else if gi < z0 {
                        for &(gj, cj) in rows[b] {
                            if gj < z0 {
                                if gi >= gj {
                                    trip.push(Triplet::new(gi, gj, ci * cj * k));
                                    if gi == gj {
                                        diag[gi] += ci * cj * k;
                                    }
                                }
                            } else if gj < p0 {
                                kiz[gj - z0].push((gi, ci * cj * k));
                            }
                        }
                    }
                }
            }
        }
        // settlement: f -= k u0
        for g in 0..nc {
            if !has_settlement[g] {
                continue;
            }
            let u0: Vec<f64> = rows
                .iter()
                .map(|r| {
                    r.iter()
                        .filter(|(gi, _)| *gi >= p0)
                        .map(|(gi, c)| c * s[g][gi - p0])
                        .sum()
                })
                .collect();
            if u0.iter().any(|v| *v != 0.0) {
                for a in 0..n {
                    let ku: f64 = (0..n).map(|b| em.k[a * n + b] * u0[b]).sum();
                    f_set[g][em.dofs[a]] -= ku;
                }
            }
        }
    };
    for (i, el) in model.elements.iter().enumerate() {
        let em = element_stiffness(model, el);
        if em.k.iter().any(|v| !v.is_finite()) {
            return Err(FemError::Overflow {
                element: Some(ElementId(i)),
                what: "its stiffness matrix".into(),
            });
        }
        handle(&em);
    }
    for sp in &model.springs {
        handle(&spring_matrix(sp));
    }
    if f_phys
        .iter()
        .flatten()
        .chain(f_set.iter().flatten())
        .any(|v| !v.is_finite())
    {
        return Err(FemError::Overflow {
            element: None,
            what: "the sum of the loads at a node".into(),
        });
    }
    for r in kiz.iter_mut() {
        *r = merge(std::mem::take(r));
    }
    // generalized loads
    let mut b_i = vec![vec![0.0; n_i]; nc];
    let mut b_z = vec![vec![0.0; nz]; nc];
    for g in 0..nc {
        for d in 0..nphys {
            let f = f_phys[g][d] + f_set[g][d];
            if f == 0.0 {
                continue;
            }
            for &(gi, c) in &map.rows[d] {
                if gi < z0 {
                    b_i[g][gi] += c * f;
                } else if gi < p0 {
                    b_z[g][gi - z0] += c * f;
                }
            }
        }
    }
    // explicit diagonal so that every free DOF is in the pattern
    for i in 0..n_i {
        trip.push(Triplet::new(i, i, 0.0));
    }
    let kii = if n_i > 0 {
        Some(
            SparseColMat::<usize, f64>::try_new_from_triplets(n_i, n_i, &trip)
                .map_err(|e| FemError::LinearAlgebra(format!("{e:?}")))?,
        )
    } else {
        None
    };
    let cases: Vec<CaseVectors> = (0..nc)
        .map(|c| CaseVectors {
            f_phys: std::mem::take(&mut f_phys[c]),
            s: std::mem::take(&mut s[c]),
            b_i: std::mem::take(&mut b_i[c]),
            b_z: std::mem::take(&mut b_z[c]),
        })
        .collect();
    // The paper's two groups are the cases of their names (zero when the model has none).
    let group_case =
        [LoadGroup::Constant, LoadGroup::Variable].map(|g| model.case(g.case_name()).map(|c| c.0));
    let group = |part: fn(&CaseVectors) -> &Vec<f64>, len: usize| {
        group_case.map(|c| c.map_or_else(|| vec![0.0; len], |c| part(&cases[c]).clone()))
    };
    let (f_phys, s, b_i, b_z) = (
        group(|c| &c.f_phys, nphys),
        group(|c| &c.s, map.n_p),
        group(|c| &c.b_i, n_i),
        group(|c| &c.b_z, nz),
    );
    Ok(Assembled {
        map,
        kii,
        kii_triplets: trip,
        diag,
        kiz,
        kzz,
        cases,
        group_case,
        f_phys,
        s,
        b_i,
        b_z,
    })
}
