//! DOF numbering with link DOFs, sparse assembly, factorization of the bonded structure and
//! condensation to the contact zone (formulation.md §2).
//!
//! Method (exact, no penalty): for every contact pair one node (B, or A if B is supported or
//! already carries links) gets its translations re-expressed as
//! `u_B = u_A + n·z_n + t·z_t` (or `u_A = u_B − n·z_n − t·z_t`), so the mutual displacements
//! `z` become generalized DOFs. Supported translations are rotated to the support frame and
//! prescribed. With `u = T·[v_I; z; s]`, the bonded structure (`z = 0`) has stiffness
//! `K_II = T_Iᵀ K T_I` (symmetric positive definite when stable, sparse Cholesky), and
//! `R = K_zz − K_zI K_II⁻¹ K_Iz` (the Schur complement), `R_F = K_zI K_II⁻¹ b_I − b_z`.

use crate::elements::{element_dofs, element_load, element_stiffness, ElemMat};
use crate::error::{DofLabel, FemError, FreeDof};
use crate::model::{
    same_dof, Element, Endpoint, Load, LoadGroup, Model, NodeId, SpringKind, SupportDof,
};
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, Mat, Side};
use std::time::Instant;

type Row = Vec<(usize, f64)>;

/// Generalized DOF numbering: `[I (free) | z (2m: normal then tangential) | P (prescribed)]`.
#[derive(Debug, Clone)]
pub(crate) struct DofMap {
    pub n_i: usize,
    pub m: usize,
    pub n_p: usize,
    /// Per physical DOF (3 per node): its expression in generalized DOFs.
    pub rows: Vec<Row>,
    /// Per prescribed DOF: node, support DOF, physical direction (dx, dy, rot).
    pub prescribed: Vec<(NodeId, SupportDof, [f64; 3])>,
    /// Per free DOF: the node and a label (for diagnosis).
    pub free_label: Vec<(NodeId, DofLabel)>,
    /// Unit normal and tangent per pair.
    pub nt: Vec<([f64; 2], [f64; 2])>,
}

impl DofMap {
    pub fn z0(&self) -> usize {
        self.n_i
    }
    pub fn p0(&self) -> usize {
        self.n_i + 2 * self.m
    }
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let l = v[0].hypot(v[1]);
    [v[0] / l, v[1] / l]
}

fn support_dir(d: SupportDof) -> Option<[f64; 2]> {
    match d {
        SupportDof::Ux => Some([1.0, 0.0]),
        SupportDof::Uy => Some([0.0, 1.0]),
        SupportDof::Along(v) => Some(unit(v)),
        SupportDof::Rz => None,
    }
}

pub(crate) fn build_dof_map(model: &Model) -> Result<DofMap, FemError> {
    let nn = model.nodes.len();
    let m = model.pairs.len();
    // supports per node
    let mut trans: Vec<Vec<(SupportDof, [f64; 2])>> = vec![Vec::new(); nn];
    let mut rot_fixed: Vec<Option<SupportDof>> = vec![None; nn];
    for &(n, d) in &model.supports {
        match support_dir(d) {
            Some(dir) => {
                if !trans[n.0].iter().any(|(e, _)| same_dof(*e, d)) {
                    trans[n.0].push((d, dir));
                }
            }
            None => rot_fixed[n.0] = Some(d),
        }
    }
    for (i, t) in trans.iter().enumerate() {
        if t.len() > 2 {
            return Err(FemError::BadSupport {
                node: NodeId(i),
                reason: format!("{} translational restraints (at most 2)", t.len()),
            });
        }
        if t.len() == 2 {
            let (a, b) = (t[0].1, t[1].1);
            if (a[0] * b[1] - a[1] * b[0]).abs() < 1e-9 {
                return Err(FemError::BadSupport {
                    node: NodeId(i),
                    reason: "two parallel translational restraints".into(),
                });
            }
        }
    }
    // rotation DOFs
    let mut has_rot = vec![false; nn];
    for e in &model.elements {
        if let Element::Frame {
            nodes, releases, ..
        } = e
        {
            if !releases.start {
                has_rot[nodes[0].0] = true;
            }
            if !releases.end {
                has_rot[nodes[1].0] = true;
            }
        }
    }
    for s in &model.springs {
        if let SpringKind::Rotational { .. } = s.kind {
            has_rot[s.b.0] = true;
            if let Endpoint::Node(a) = s.a {
                has_rot[a.0] = true;
            }
        }
    }
    for (_, l) in &model.loads {
        if let Load::Nodal { node, m, .. } = l {
            if *m != 0.0 {
                has_rot[node.0] = true;
            }
        }
    }
    for (i, r) in rot_fixed.iter().enumerate() {
        if r.is_some() {
            has_rot[i] = true;
        }
    }
    // link placement
    let mut pivot_pair: Vec<Option<usize>> = vec![None; nn];
    let mut nt = Vec::with_capacity(m);
    let mut pivot_is_b = vec![true; m];
    for (k, p) in model.pairs.iter().enumerate() {
        let n = unit(p.normal);
        nt.push((n, [n[1], -n[0]]));
        let free = |node: NodeId| trans[node.0].is_empty() && pivot_pair[node.0].is_none();
        if free(p.b) {
            pivot_pair[p.b.0] = Some(k);
        } else if let Endpoint::Node(a) = p.a {
            if free(a) {
                pivot_pair[a.0] = Some(k);
                pivot_is_b[k] = false;
            } else {
                return Err(FemError::LinkPlacement {
                    pair: k,
                    name: model.pair_name(k),
                    reason: format!(
                        "both {} and {} are supported or already carry the links of another pair",
                        a, p.b
                    ),
                });
            }
        } else {
            return Err(FemError::LinkPlacement {
                pair: k,
                name: model.pair_name(k),
                reason: format!(
                    "{} is supported in translation or already carries the links of another pair \
                     (a node-to-ground pair on a supported DOF is redundant)",
                    p.b
                ),
            });
        }
    }
    // numbering of free and prescribed DOFs
    let mut n_i = 0usize;
    let mut free_label = Vec::new();
    let mut p_list: Vec<(NodeId, SupportDof, [f64; 3])> = Vec::new();
    // temporary codes: free = Free(i), prescribed = Pres(k)
    #[derive(Clone, Copy)]
    enum G {
        Free(usize),
        Pres(usize),
    }
    let mut trans_gen: Vec<Vec<(G, [f64; 2])>> = vec![Vec::new(); nn]; // u = Σ g·vec
    let mut rot_gen: Vec<Option<G>> = vec![None; nn];
    for i in 0..nn {
        let node = NodeId(i);
        if has_rot[i] {
            rot_gen[i] = Some(match rot_fixed[i] {
                Some(d) => {
                    p_list.push((node, d, [0.0, 0.0, 1.0]));
                    G::Pres(p_list.len() - 1)
                }
                None => {
                    free_label.push((node, DofLabel::Rz));
                    n_i += 1;
                    G::Free(n_i - 1)
                }
            });
        }
        if pivot_pair[i].is_some() {
            continue;
        }
        match trans[i].len() {
            0 => {
                free_label.push((node, DofLabel::Ux));
                free_label.push((node, DofLabel::Uy));
                trans_gen[i].push((G::Free(n_i), [1.0, 0.0]));
                trans_gen[i].push((G::Free(n_i + 1), [0.0, 1.0]));
                n_i += 2;
            }
            1 => {
                let (d, dir) = trans[i][0];
                p_list.push((node, d, [dir[0], dir[1], 0.0]));
                trans_gen[i].push((G::Pres(p_list.len() - 1), dir));
                let perp = [-dir[1], dir[0]];
                free_label.push((
                    node,
                    if perp[0].abs() >= perp[1].abs() {
                        DofLabel::Ux
                    } else {
                        DofLabel::Uy
                    },
                ));
                trans_gen[i].push((G::Free(n_i), perp));
                n_i += 1;
            }
            _ => {
                // u = D⁻¹ s with D = [d1ᵀ; d2ᵀ]: columns of D⁻¹
                let (a, b) = (trans[i][0].1, trans[i][1].1);
                let det = a[0] * b[1] - a[1] * b[0];
                let c1 = [b[1] / det, -b[0] / det];
                let c2 = [-a[1] / det, a[0] / det];
                p_list.push((node, trans[i][0].0, [a[0], a[1], 0.0]));
                trans_gen[i].push((G::Pres(p_list.len() - 1), c1));
                p_list.push((node, trans[i][1].0, [b[0], b[1], 0.0]));
                trans_gen[i].push((G::Pres(p_list.len() - 1), c2));
            }
        }
    }
    let z0 = n_i;
    let p0 = n_i + 2 * m;
    let gidx = |g: G| match g {
        G::Free(i) => i,
        G::Pres(k) => p0 + k,
    };
    // translation rows of every node, resolving link chains
    let mut tr_rows: Vec<Option<[Row; 2]>> = vec![None; nn];
    for i in 0..nn {
        if pivot_pair[i].is_none() {
            let mut rx = Row::new();
            let mut ry = Row::new();
            for &(g, v) in &trans_gen[i] {
                if v[0] != 0.0 {
                    rx.push((gidx(g), v[0]));
                }
                if v[1] != 0.0 {
                    ry.push((gidx(g), v[1]));
                }
            }
            tr_rows[i] = Some([rx, ry]);
        }
    }
    let mut state = vec![0u8; nn];
    fn resolve(
        i: usize,
        model: &Model,
        pivot_pair: &[Option<usize>],
        pivot_is_b: &[bool],
        nt: &[([f64; 2], [f64; 2])],
        z0: usize,
        tr_rows: &mut Vec<Option<[Row; 2]>>,
        state: &mut Vec<u8>,
    ) -> Result<(), FemError> {
        if tr_rows[i].is_some() {
            return Ok(());
        }
        let k = pivot_pair[i].expect("pivot");
        if state[i] == 1 {
            return Err(FemError::LinkPlacement {
                pair: k,
                name: model.pair_name(k),
                reason: "the contact pairs form a closed loop of links".into(),
            });
        }
        state[i] = 1;
        let p = &model.pairs[k];
        let other = if pivot_is_b[k] {
            match p.a {
                Endpoint::Ground => None,
                Endpoint::Node(a) => Some(a.0),
            }
        } else {
            Some(p.b.0)
        };
        let mut rows: [Row; 2] = [Row::new(), Row::new()];
        if let Some(o) = other {
            resolve(o, model, pivot_pair, pivot_is_b, nt, z0, tr_rows, state)?;
            rows = tr_rows[o].clone().unwrap();
        }
        let sign = if pivot_is_b[k] { 1.0 } else { -1.0 };
        let (n, t) = nt[k];
        let m = nt.len();
        for c in 0..2 {
            if n[c] != 0.0 {
                rows[c].push((z0 + k, sign * n[c]));
            }
            if t[c] != 0.0 {
                rows[c].push((z0 + m + k, sign * t[c]));
            }
        }
        tr_rows[i] = Some(rows);
        state[i] = 2;
        Ok(())
    }
    for i in 0..nn {
        resolve(
            i,
            model,
            &pivot_pair,
            &pivot_is_b,
            &nt,
            z0,
            &mut tr_rows,
            &mut state,
        )?;
    }
    let mut rows = vec![Row::new(); 3 * nn];
    for i in 0..nn {
        let [rx, ry] = tr_rows[i].take().unwrap();
        rows[3 * i] = merge(rx);
        rows[3 * i + 1] = merge(ry);
        if let Some(g) = rot_gen[i] {
            rows[3 * i + 2] = vec![(gidx(g), 1.0)];
        }
    }
    Ok(DofMap {
        n_i,
        m,
        n_p: p_list.len(),
        rows,
        prescribed: p_list,
        free_label,
        nt,
    })
}

fn merge(mut r: Row) -> Row {
    r.sort_by_key(|e| e.0);
    let mut out: Row = Vec::with_capacity(r.len());
    for (g, c) in r {
        match out.last_mut() {
            Some(last) if last.0 == g => last.1 += c,
            _ => out.push((g, c)),
        }
    }
    out.retain(|e| e.1 != 0.0);
    out
}

/// Stiffness of a spring as an element matrix.
pub(crate) fn spring_matrix(s: &crate::model::Spring) -> ElemMat {
    let b = s.b.0;
    match s.kind {
        SpringKind::Translational {
            direction,
            stiffness,
        } => {
            let d = unit(direction);
            let kd = [
                stiffness * d[0] * d[0],
                stiffness * d[0] * d[1],
                stiffness * d[1] * d[1],
            ];
            match s.a {
                Endpoint::Ground => ElemMat {
                    dofs: vec![3 * b, 3 * b + 1],
                    k: vec![kd[0], kd[1], kd[1], kd[2]],
                },
                Endpoint::Node(a) => {
                    let a = a.0;
                    let blk = [[kd[0], kd[1]], [kd[1], kd[2]]];
                    let mut k = vec![0.0; 16];
                    for i in 0..2 {
                        for j in 0..2 {
                            k[i * 4 + j] = blk[i][j];
                            k[(i + 2) * 4 + j + 2] = blk[i][j];
                            k[i * 4 + j + 2] = -blk[i][j];
                            k[(i + 2) * 4 + j] = -blk[i][j];
                        }
                    }
                    ElemMat {
                        dofs: vec![3 * a, 3 * a + 1, 3 * b, 3 * b + 1],
                        k,
                    }
                }
            }
        }
        SpringKind::Rotational { stiffness } => match s.a {
            Endpoint::Ground => ElemMat {
                dofs: vec![3 * b + 2],
                k: vec![stiffness],
            },
            Endpoint::Node(a) => ElemMat {
                dofs: vec![3 * a.0 + 2, 3 * b + 2],
                k: vec![stiffness, -stiffness, -stiffness, stiffness],
            },
        },
    }
}

/// Bytes of the dense matrices the condensation of `m` pairs with `n_i` free DOFs holds at
/// once: `K_zz` (becoming `R`, (2m)²), its four m×m blocks, and one chunk of solves
/// (`n_i × min(64, 2m)`). `None` when the count overflows.
pub fn dense_condensation_bytes(m: usize, n_i: usize) -> Option<u64> {
    let chunk = CHUNK.min(m.saturating_mul(2)) as u64;
    let m = m as u64;
    let doubles = m
        .checked_mul(m)?
        .checked_mul(8)?
        .checked_add((n_i as u64).checked_mul(chunk)?)?;
    doubles.checked_mul(8)
}

/// The memory of this machine in bytes (`MemTotal` of `/proc/meminfo`), `None` when it is not
/// known.
pub fn machine_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// Refuses a need of `bytes` (`None`: beyond any count) that this machine cannot hold, before
/// anything of that size is allocated. Where the machine's memory is unknown, the allocation
/// itself is tried without aborting.
pub fn check_memory(what: &str, bytes: Option<u64>) -> Result<(), FemError> {
    let too_large = |needed: Option<u64>, available: Option<u64>| FemError::TooLarge {
        what: what.to_string(),
        needed,
        available,
    };
    let Some(needed) = bytes else {
        return Err(too_large(None, machine_memory()));
    };
    match machine_memory() {
        Some(total) if needed > total => Err(too_large(Some(needed), Some(total))),
        Some(_) => Ok(()),
        None => {
            let mut probe: Vec<u8> = Vec::new();
            let len = usize::try_from(needed).map_err(|_| too_large(Some(needed), None))?;
            probe
                .try_reserve_exact(len)
                .map_err(|_| too_large(Some(needed), None))
        }
    }
}

/// Timings and sizes of a condensation.
#[derive(Debug, Clone, Default)]
pub struct CondensationStats {
    /// Number of free DOFs of the bonded structure (size of the factorized matrix).
    pub free_dofs: usize,
    /// Number of contact pairs `m`.
    pub pairs: usize,
    /// Number of prescribed (supported) DOFs.
    pub prescribed_dofs: usize,
    /// Stored entries of the lower triangle of the bonded stiffness.
    pub nnz_lower: usize,
    /// Seconds spent assembling (element matrices, triplets, CSC).
    pub assembly_s: f64,
    /// Seconds in the symbolic + numeric sparse Cholesky factorization and the stability check.
    pub factorization_s: f64,
    /// Seconds computing the Schur complement and the load vectors (2m + 2 solves).
    pub condensation_s: f64,
    /// Largest `|R − Rᵀ|` before symmetrization, relative to the largest `|R|`.
    pub asymmetry: f64,
    /// Estimate of the smallest eigenvalue of the Jacobi-scaled bonded stiffness (its inverse
    /// estimates the condition number; 1 when no DOF is free).
    pub smallest_eigenvalue: f64,
    /// Entries of `R` and of the contact load vectors that were round-off of an exact zero and
    /// were set to zero.
    pub round_off_zeroed: usize,
}

/// Everything assembled from a model.
pub(crate) struct Assembled {
    pub map: DofMap,
    pub kii: Option<SparseColMat<usize, f64>>,
    pub kii_triplets: Vec<Triplet<usize, usize, f64>>,
    pub diag: Vec<f64>,
    /// Columns of K_Iz: for link DOF r, the (free index, value) pairs.
    pub kiz: Vec<Row>,
    pub kzz: Mat<f64>,
    /// Physical equivalent loads per group (constant, variable), without settlement terms.
    pub f_phys: [Vec<f64>; 2],
    /// Prescribed values per group.
    pub s: [Vec<f64>; 2],
    /// Generalized loads per group: I part and z part (settlements included).
    pub b_i: [Vec<f64>; 2],
    pub b_z: [Vec<f64>; 2],
}

fn group_index(g: LoadGroup) -> usize {
    match g {
        LoadGroup::Constant => 0,
        LoadGroup::Variable => 1,
    }
}

pub(crate) fn assemble(model: &Model) -> Result<Assembled, FemError> {
    let map = build_dof_map(model)?;
    let (n_i, m) = (map.n_i, map.m);
    let nz = 2 * m;
    let z0 = map.z0();
    let p0 = map.p0();
    let nphys = 3 * model.nodes.len();
    // loads
    let mut f_phys = [vec![0.0; nphys], vec![0.0; nphys]];
    let mut s = [vec![0.0; map.n_p], vec![0.0; map.n_p]];
    for (g, l) in &model.loads {
        let gi = group_index(*g);
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
                let el = &model.elements[element.0];
                if let Some(fe) = element_load(model, el, l) {
                    if fe.iter().any(|v| !v.is_finite()) {
                        return Err(FemError::Overflow {
                            element: Some(element),
                            what: "its equivalent nodal loads".into(),
                        });
                    }
                    for (a, d) in element_dofs(el).into_iter().enumerate() {
                        f_phys[gi][d] += fe[a];
                    }
                }
            }
        }
    }
    let has_settlement = [
        s[0].iter().any(|v| *v != 0.0),
        s[1].iter().any(|v| *v != 0.0),
    ];
    check_memory(
        &format!("{m} contact pairs"),
        dense_condensation_bytes(m, n_i),
    )?;
    let mut f_set = [vec![0.0; nphys], vec![0.0; nphys]];
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
        for g in 0..2 {
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
                element: Some(crate::model::ElementId(i)),
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
    let mut b_i = [vec![0.0; n_i], vec![0.0; n_i]];
    let mut b_z = [vec![0.0; nz], vec![0.0; nz]];
    for g in 0..2 {
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
    Ok(Assembled {
        map,
        kii,
        kii_triplets: trip,
        diag,
        kiz,
        kzz,
        f_phys,
        s,
        b_i,
        b_z,
    })
}

/// A deterministic pseudo-random vector in (−1, 1).
fn pseudo_random(n: usize) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// Inverse iteration on the Jacobi-scaled matrix. Returns (eigenvalue estimate, mode in
/// unscaled coordinates).
///
/// At least `min_iters` iterations; then, up to `max_iters`, until the eigenvalue estimate
/// changes by less than 1e-6 of itself from one iteration to the next. The components of the
/// mode along the second eigenvector shrink by `λ₁/λ₂` per iteration, which for the lowest
/// modes of a fine mesh is only about 1/16 (the eigenvalues of a beam grow as k⁴): the few
/// iterations that estimate `λ` well are not always enough for the mode itself, which the
/// mechanism test reads.
fn inverse_iteration(
    llt: &Llt<usize, f64>,
    diag: &[f64],
    min_iters: usize,
    max_iters: usize,
) -> (f64, Vec<f64>) {
    let n = diag.len();
    let sq: Vec<f64> = diag
        .iter()
        .map(|d| d.abs().max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let mut v = pseudo_random(n);
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nv = norm(&v);
    v.iter_mut().for_each(|x| *x /= nv);
    let mut lambda = f64::INFINITY;
    for it in 0..max_iters {
        // A = D^{-1/2} K D^{-1/2}, so A⁻¹ v = D^{1/2} K⁻¹ D^{1/2} v.
        let mut w = Mat::<f64>::from_fn(n, 1, |i, _| v[i] * sq[i]);
        llt.solve_in_place_with_conj(Conj::No, w.as_mut());
        let wv: Vec<f64> = (0..n).map(|i| w[(i, 0)] * sq[i]).collect();
        let nw = norm(&wv);
        if !nw.is_finite() || nw == 0.0 {
            return (0.0, v.iter().zip(&sq).map(|(a, s)| a / s).collect());
        }
        let previous = lambda;
        lambda = 1.0 / nw;
        v = wv.iter().map(|x| x / nw).collect();
        if it + 1 >= min_iters && (previous - lambda).abs() <= 1e-6 * lambda {
            break;
        }
    }
    (lambda, v.iter().zip(&sq).map(|(a, s)| a / s).collect())
}

/// Threshold on the smallest eigenvalue of the Jacobi-scaled bonded stiffness below which the
/// mode is examined by [`element_force_ratio`]; above it the structure is stable.
const SINGULAR_EIG: f64 = 1e-13;

/// Threshold on [`element_force_ratio`] below which a mode of small eigenvalue is a mechanism.
///
/// A mechanism moves every element and spring rigidly, so the exact ratio is zero and the
/// computed one is round-off: 1e-16 for a few elements; for a member of `N` elements the
/// factorization mixes the null mode with the lowest deforming modes, and the least deforming
/// combination of six vectors of block inverse iteration still leaves 2e-14 (N = 1000),
/// 3e-13 (5000), 5e-12 (20000), 1e-10 (2×50000, a hinge chain). The lowest mode of a stable
/// member is smooth: an element of length `h` on a span `L` carries forces of relative size
/// ≈ (πh/L)²/25 (1.4e-8 for a pinned–pinned beam of 5000 elements, 3.7e-11 for 10⁵), and only
/// their assembly cancels further, to the eigenvalue ≈ (πh/L)⁴/12. The threshold separates the
/// two up to 10⁵ elements per member for a stable member (never a false mechanism) and to
/// 2·10⁴ for a mechanism (above, it is reported as ill-conditioned, which it also is).
const MECHANISM_RATIO: f64 = 1e-11;

/// The physical displacements (3 per node) of a free-DOF vector with `z = 0` and `s = 0`.
fn physical_mode(map: &DofMap, mode: &[f64]) -> Vec<f64> {
    map.rows
        .iter()
        .map(|r| {
            r.iter()
                .filter(|(g, _)| *g < map.n_i)
                .map(|(g, c)| c * mode[*g])
                .sum()
        })
        .collect()
}

/// How far a displacement field is from moving every element and spring rigidly:
///
/// `ρ = Σ_e ‖k̃_e ũ_e‖ / Σ_e ‖k̃_e‖·‖ũ_e‖`, with each element's (or spring's) matrix and
/// displacements scaled by its own diagonal `D_e` (`k̃_e = D_e^{-1/2} k_e D_e^{-1/2}`,
/// `ũ_e = D_e^{1/2} u_e`, DOFs with a zero diagonal left out, `‖k̃_e‖` the Frobenius norm).
///
/// The scaling makes `ρ` independent of units and of the mix of translations and rotations.
/// The element forces are computed before assembly, so they are not lost in the cancellation
/// that makes the assembled `K u` of a smooth mode of a fine mesh as small as round-off:
/// `ρ` is ≈ 1e-16 for a rigid motion of every element (a mechanism), and of order (h/L)²
/// for the smooth lowest mode of a stable member divided into elements of length `h`.
fn element_force_ratio(model: &Model, phys: &[f64]) -> f64 {
    let mut num = 0.0;
    let mut den = 0.0;
    let mut add = |em: &ElemMat| {
        let n = em.dofs.len();
        let d: Vec<f64> = (0..n).map(|a| em.k[a * n + a]).collect();
        let live: Vec<usize> = (0..n).filter(|&a| d[a] > 0.0).collect();
        let sq: Vec<f64> = d.iter().map(|x| x.max(0.0).sqrt()).collect();
        let mut force2 = 0.0;
        let mut kn2 = 0.0;
        let mut un2 = 0.0;
        for &a in &live {
            let mut f = 0.0;
            for &b in &live {
                let kab = em.k[a * n + b] / (sq[a] * sq[b]);
                kn2 += kab * kab;
                f += kab * sq[b] * phys[em.dofs[b]];
            }
            force2 += f * f;
            let u = sq[a] * phys[em.dofs[a]];
            un2 += u * u;
        }
        num += force2.sqrt();
        den += kn2.sqrt() * un2.sqrt();
    };
    for el in &model.elements {
        add(&element_stiffness(model, el));
    }
    for sp in &model.springs {
        add(&spring_matrix(sp));
    }
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

fn free_dofs_from_mode(map: &DofMap, mode: &[f64]) -> Vec<FreeDof> {
    // physical displacement of the mode (z = 0, s = 0)
    let phys = physical_mode(map, mode);
    let max = phys.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let mut out = Vec::new();
    if max == 0.0 {
        return out;
    }
    for (d, v) in phys.iter().enumerate() {
        if v.abs() > 1e-3 * max {
            out.push(FreeDof {
                node: NodeId(d / 3),
                dof: [DofLabel::Ux, DofLabel::Uy, DofLabel::Rz][d % 3],
                amplitude: v / max,
            });
        }
    }
    out
}

/// Number of vectors of the block inverse iteration that looks for a mechanism mode.
const BLOCK: usize = 6;

/// Block inverse iteration on the Jacobi-scaled matrix: an orthonormal basis (in scaled
/// coordinates) of its lowest `BLOCK` eigenvectors, returned in unscaled coordinates.
///
/// When the structure is a mechanism, round-off of the factorization mixes its null mode with
/// the lowest deforming modes whose eigenvalues are not far above round-off (those of a
/// member of many elements); a single vector of inverse iteration is such a mixture, while
/// the span of a few of them holds the null mode much more accurately.
fn block_inverse_iteration(llt: &Llt<usize, f64>, diag: &[f64], iters: usize) -> Vec<Vec<f64>> {
    let n = diag.len();
    let k = BLOCK.min(n);
    let sq: Vec<f64> = diag
        .iter()
        .map(|d| d.abs().max(f64::MIN_POSITIVE).sqrt())
        .collect();
    let start = pseudo_random(n * k);
    let mut v = Mat::<f64>::from_fn(n, k, |i, j| start[j * n + i]);
    let orthonormalize = |v: &mut Mat<f64>| {
        for _ in 0..2 {
            for j in 0..k {
                for i in 0..j {
                    let d: f64 = (0..n).map(|r| v[(r, i)] * v[(r, j)]).sum();
                    for r in 0..n {
                        let x = v[(r, i)];
                        v[(r, j)] -= d * x;
                    }
                }
                let nj = (0..n).map(|r| v[(r, j)] * v[(r, j)]).sum::<f64>().sqrt();
                if nj.is_finite() && nj > 0.0 {
                    for r in 0..n {
                        v[(r, j)] /= nj;
                    }
                }
            }
        }
    };
    orthonormalize(&mut v);
    for _ in 0..iters {
        let mut w = Mat::<f64>::from_fn(n, k, |i, j| v[(i, j)] * sq[i]);
        llt.solve_in_place_with_conj(Conj::No, w.as_mut());
        v = Mat::<f64>::from_fn(n, k, |i, j| w[(i, j)] * sq[i]);
        if v.col_iter().any(|c| c.iter().any(|x| !x.is_finite())) {
            break;
        }
        orthonormalize(&mut v);
    }
    (0..k)
        .map(|j| (0..n).map(|i| v[(i, j)] / sq[i]).collect())
        .collect()
}

/// The combination of `basis` (free-DOF vectors) that deforms the elements least: it
/// minimizes `Σ_e ‖k̃_e ũ_e‖² / Σ_e ‖k̃_e‖²·‖ũ_e‖²` (the squared, smooth form of
/// [`element_force_ratio`]) over the span, a small generalized eigenproblem whose matrices are
/// summed element by element, without the cancellation of the assembly.
fn least_deforming_combination(model: &Model, map: &DofMap, basis: &[Vec<f64>]) -> Vec<f64> {
    let k = basis.len();
    let phys: Vec<Vec<f64>> = basis.iter().map(|b| physical_mode(map, b)).collect();
    let mut g = Mat::<f64>::zeros(k, k);
    let mut w = Mat::<f64>::zeros(k, k);
    let mut add = |em: &ElemMat| {
        let n = em.dofs.len();
        let sq: Vec<f64> = (0..n).map(|a| em.k[a * n + a].max(0.0).sqrt()).collect();
        let live: Vec<usize> = (0..n).filter(|&a| sq[a] > 0.0).collect();
        let mut kn2 = 0.0;
        for &a in &live {
            for &b in &live {
                let kab = em.k[a * n + b] / (sq[a] * sq[b]);
                kn2 += kab * kab;
            }
        }
        // scaled displacements and forces of every basis vector on this element
        let u: Vec<Vec<f64>> = phys
            .iter()
            .map(|p| live.iter().map(|&a| sq[a] * p[em.dofs[a]]).collect())
            .collect();
        let f: Vec<Vec<f64>> = phys
            .iter()
            .map(|p| {
                live.iter()
                    .map(|&a| {
                        live.iter()
                            .map(|&b| em.k[a * n + b] / sq[a] * p[em.dofs[b]])
                            .sum::<f64>()
                    })
                    .collect()
            })
            .collect();
        for i in 0..k {
            for j in 0..k {
                let fij: f64 = f[i].iter().zip(&f[j]).map(|(x, y)| x * y).sum();
                let uij: f64 = u[i].iter().zip(&u[j]).map(|(x, y)| x * y).sum();
                g[(i, j)] += fij;
                w[(i, j)] += kn2 * uij;
            }
        }
    };
    for el in &model.elements {
        add(&element_stiffness(model, el));
    }
    for sp in &model.springs {
        add(&spring_matrix(sp));
    }
    // W = L Lᵀ (small Cholesky), C = L⁻¹ G L⁻ᵀ, smallest eigenvector y, c = L⁻ᵀ y
    let mut l = Mat::<f64>::zeros(k, k);
    for j in 0..k {
        let d = w[(j, j)] - (0..j).map(|m| l[(j, m)] * l[(j, m)]).sum::<f64>();
        if !(d > 0.0) {
            return basis[0].clone();
        }
        l[(j, j)] = d.sqrt();
        for i in j + 1..k {
            l[(i, j)] =
                (w[(i, j)] - (0..j).map(|m| l[(i, m)] * l[(j, m)]).sum::<f64>()) / l[(j, j)];
        }
    }
    let lower_solve = |b: &[f64]| {
        let mut x = vec![0.0; k];
        for i in 0..k {
            x[i] = (b[i] - (0..i).map(|m| l[(i, m)] * x[m]).sum::<f64>()) / l[(i, i)];
        }
        x
    };
    // columns of L⁻¹ G, then rows: C = L⁻¹ (L⁻¹ G)ᵀ
    let lg: Vec<Vec<f64>> = (0..k)
        .map(|j| lower_solve(&(0..k).map(|i| g[(i, j)]).collect::<Vec<_>>()))
        .collect();
    let c = {
        let cols: Vec<Vec<f64>> = (0..k)
            .map(|i| lower_solve(&(0..k).map(|j| lg[j][i]).collect::<Vec<_>>()))
            .collect();
        Mat::<f64>::from_fn(k, k, |i, j| 0.5 * (cols[j][i] + cols[i][j]))
    };
    let Ok(evd) = c.self_adjoint_eigen(Side::Lower) else {
        return basis[0].clone();
    };
    let y: Vec<f64> = (0..k).map(|i| evd.U()[(i, 0)]).collect();
    // c = L⁻ᵀ y
    let mut coef = vec![0.0; k];
    for i in (0..k).rev() {
        coef[i] = (y[i] - (i + 1..k).map(|m| l[(m, i)] * coef[m]).sum::<f64>()) / l[(i, i)];
    }
    let n = basis[0].len();
    (0..n)
        .map(|r| (0..k).map(|a| coef[a] * basis[a][r]).sum())
        .collect()
}

/// The unit round-off of double precision.
const UNIT_ROUND_OFF: f64 = f64::EPSILON / 2.0;

/// Tells a mechanism from an ill-conditioned stable structure by the lowest mode `mode` (free
/// DOFs) of eigenvalue `lambda`: see [`MECHANISM_RATIO`].
fn small_eigenvalue_error(
    model: &Model,
    asm: &Assembled,
    llt: &Llt<usize, f64>,
    lambda: f64,
) -> FemError {
    let map = &asm.map;
    let basis = block_inverse_iteration(llt, &asm.diag, 30);
    let mode = least_deforming_combination(model, map, &basis);
    let mode = &mode[..];
    let rho = element_force_ratio(model, &physical_mode(map, mode));
    if rho < MECHANISM_RATIO {
        FemError::Unstable {
            free: free_dofs_from_mode(map, mode),
            eigenvalue: lambda,
            hint: String::new(),
        }
    } else {
        FemError::IllConditioned {
            eigenvalue: lambda,
            estimated_error: (UNIT_ROUND_OFF / lambda).min(1.0),
            element_force_ratio: rho,
        }
    }
}

/// Factorizes the bonded stiffness; a mechanism is a typed error naming the free DOFs.
/// Returns the factor and the estimate of the smallest eigenvalue of the Jacobi-scaled
/// bonded stiffness (1 when there is no free DOF).
///
/// The stiffness is accepted when its Cholesky factorization succeeds and the smallest
/// eigenvalue `λ` of its Jacobi-scaled form (inverse iteration) is at least [`SINGULAR_EIG`]:
/// the relative error of the solves is then below about `u/λ` ≈ 1e-3 (`u` the unit
/// round-off; measured at a twentieth of that on beams: 1.9e-5 for the mid-span deflection of
/// a pinned–pinned beam of 2000 elements, where `u/λ` = 4.4e-4). Below it, or when the
/// factorization fails (then on `K + σ·diag K` with the smallest `σ` that factorizes), the
/// structure is either a mechanism or stable but too ill-conditioned for double precision,
/// and the eigenvalue cannot tell which: the lowest mode of a pinned–pinned beam of `N`
/// elements has `λ ≈ (π/N)⁴/12`, at round-off level from about 10⁴ elements on, and the
/// solves lose every digit there (the mid-span deflection is off by 3e-3 at N = 5000 and by
/// more than 100 % at 2·10⁴). The low modes do tell: the least deforming combination of six
/// vectors of block inverse iteration ([`least_deforming_combination`]) has an
/// [`element_force_ratio`] at round-off level for a mechanism ([`FemError::Unstable`],
/// naming the DOFs that move) and not for the smooth modes of a fine mesh
/// ([`FemError::IllConditioned`]); see [`MECHANISM_RATIO`].
pub(crate) fn factorize(
    model: &Model,
    asm: &Assembled,
) -> Result<(Option<Llt<usize, f64>>, f64), FemError> {
    let Some(kii) = asm.kii.as_ref() else {
        return Ok((None, 1.0));
    };
    // DOFs without any stiffness
    let zero: Vec<FreeDof> = asm
        .diag
        .iter()
        .enumerate()
        .filter(|(_, d)| **d <= 0.0)
        .map(|(i, _)| {
            let (node, dof) = asm.map.free_label[i];
            FreeDof {
                node,
                dof,
                amplitude: 1.0,
            }
        })
        .collect();
    if !zero.is_empty() {
        return Err(FemError::Unstable {
            free: zero,
            eigenvalue: 0.0,
            hint: " (no element, spring, support or contact link acts on them)".into(),
        });
    }
    let symbolic = SymbolicLlt::try_new(kii.symbolic(), Side::Lower)
        .map_err(|e| FemError::LinearAlgebra(format!("{e:?}")))?;
    match Llt::try_new_with_symbolic(symbolic.clone(), kii.as_ref(), Side::Lower) {
        Ok(llt) => {
            let (lambda, _) = inverse_iteration(&llt, &asm.diag, 3, 3);
            if lambda >= SINGULAR_EIG {
                return Ok((Some(llt), lambda));
            }
            let (lambda, _) = inverse_iteration(&llt, &asm.diag, 10, 200);
            Err(small_eigenvalue_error(model, asm, &llt, lambda))
        }
        Err(_) => {
            // Shifted matrix, same pattern: K + σ·diag(K), with the smallest shift that
            // factorizes, so that inverse iteration still separates the null mode of a
            // mechanism from the lowest deforming modes (eigenvalues σ and σ + λ_k).
            let n = asm.diag.len();
            let mut last = None;
            for sigma in [1e-15, 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8] {
                let mut trip = asm.kii_triplets.clone();
                for (i, d) in asm.diag.iter().enumerate() {
                    trip.push(Triplet::new(i, i, sigma * d));
                }
                let shifted = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trip)
                    .map_err(|e| FemError::LinearAlgebra(format!("{e:?}")))?;
                match Llt::try_new_with_symbolic(symbolic.clone(), shifted.as_ref(), Side::Lower) {
                    Ok(llt) => {
                        let (lambda, _) = inverse_iteration(&llt, &asm.diag, 4, 200);
                        return Err(small_eigenvalue_error(
                            model,
                            asm,
                            &llt,
                            (lambda - sigma).max(0.0),
                        ));
                    }
                    Err(e) => last = Some(e),
                }
            }
            Err(FemError::LinearAlgebra(format!(
                "the bonded stiffness is not positive semidefinite ({last:?})"
            )))
        }
    }
}

/// The condensed contact-zone data.
pub(crate) struct Condensation {
    pub r: Mat<f64>,
    pub rf: [Vec<f64>; 2],
    pub asymmetry: f64,
    /// Entries of `R` and `R_F` set to zero as round-off (see [`ROUND_OFF`]).
    pub zeroed: usize,
}

/// Number of right-hand sides solved together.
const CHUNK: usize = 64;

/// An entry of `R = K_zz − K_zI K_II⁻¹ K_Iz` (or of `R_F`) is round-off when it is smaller
/// than this fraction of the magnitude of what formed it: `|K_zz|`, the sum of the absolute
/// values of the products in `K_zI·x_j` (`x_j = K_II⁻¹ K_Iz,j`), and the bound
/// `|x_i|ᵀ|K_II||x_j|` of how far the round-off of the solves (a residual of order
/// `u·|K_II||x_j|`) reaches the entry. The last term grows with the number of elements the
/// static modes span, as the round-off does; the first two do not, so a threshold on them
/// alone either lets the round-off of a fine mesh through or zeroes real stiffness.
///
/// The threshold is 8 unit round-offs. Measured over the test models (any mesh from 1 to
/// 2000 elements, any units), an exact zero (for instance the normal stiffness of a bearing
/// on which a beam turns freely about a pin) comes out below 4e-17 of this magnitude, and
/// the smallest genuine entries at 1.7e-14 (the tip stiffness of a cantilever of 2000
/// elements, `1/(8N³)` of its terms; finer members are refused as ill-conditioned by
/// `factorize` before this point) and 3.3e-14 (a spring behind a bar 10¹³ times stiffer).
pub(crate) const ROUND_OFF: f64 = 8.0 * f64::EPSILON / 2.0;

/// `|K|·|x|` for a symmetric `K` stored as its lower triangle.
fn abs_product(k: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let k = k.as_ref();
    let mut y = vec![0.0; x.len()];
    for j in 0..x.len() {
        let rows = k.symbolic().row_idx_of_col_raw(j);
        let vals = k.val_of_col(j);
        for (&i, &v) in rows.iter().zip(vals) {
            y[i] += v.abs() * x[j].abs();
            if i != j {
                y[j] += v.abs() * x[i].abs();
            }
        }
    }
    y
}

/// `|x_j|ᵀ|K||x_j|` for every column `x_j` of `x`, `K` symmetric and stored as its lower
/// triangle, in one pass over `K` for the whole block (the block is copied row-major so the
/// inner loop runs over contiguous columns): one sparse pass per block of right-hand sides
/// instead of one per column.
fn abs_quadratic_forms(k: &SparseColMat<usize, f64>, x: &Mat<f64>) -> Vec<f64> {
    let (n, w) = (x.nrows(), x.ncols());
    let mut a = vec![0.0; n * w];
    for j in 0..w {
        for (i, v) in x.col_as_slice(j).iter().enumerate() {
            a[i * w + j] = v.abs();
        }
    }
    let k = k.as_ref();
    let mut e = vec![0.0; w];
    for c in 0..n {
        let rows = k.symbolic().row_idx_of_col_raw(c);
        let vals = k.val_of_col(c);
        let ac = &a[c * w..(c + 1) * w];
        for (&i, &v) in rows.iter().zip(vals) {
            let f = if i == c { v.abs() } else { 2.0 * v.abs() };
            let ai = &a[i * w..(i + 1) * w];
            for ((ej, &x_i), &x_c) in e.iter_mut().zip(ai).zip(ac) {
                *ej += f * x_i * x_c;
            }
        }
    }
    e
}

pub(crate) fn condense(
    asm: &Assembled,
    kii: Option<&SparseColMat<usize, f64>>,
    kzz: Mat<f64>,
    llt: Option<&Llt<usize, f64>>,
) -> Condensation {
    let n_i = asm.map.n_i;
    let nz = 2 * asm.map.m;
    let mut r = kzz;
    // magnitude of the terms of each diagonal entry of R, and of each entry of R_F
    let mut mag: Vec<f64> = (0..nz).map(|k| r[(k, k)].abs()).collect();
    let mut rf = [vec![0.0; nz], vec![0.0; nz]];
    let mut rf_mag = [vec![0.0; nz], vec![0.0; nz]];
    for g in 0..2 {
        for k in 0..nz {
            rf[g][k] = -asm.b_z[g][k];
            rf_mag[g][k] = asm.b_z[g][k].abs();
        }
    }
    if let Some(llt) = llt {
        // the load columns first: their |K_II|·|x| enter the magnitudes of R_F below
        let mut xb = Mat::<f64>::from_fn(n_i, 2, |i, g| asm.b_i[g][i]);
        llt.solve_in_place_with_conj(Conj::No, xb.as_mut());
        let kxb: Vec<Vec<f64>> = (0..2)
            .map(|g| kii.map_or_else(Vec::new, |k| abs_product(k, xb.col_as_slice(g))))
            .collect();
        for g in 0..2 {
            let xg = xb.col_as_slice(g);
            for row in 0..nz {
                let col = &asm.kiz[row];
                rf[g][row] += col.iter().map(|&(i, v)| v * xg[i]).sum::<f64>();
                rf_mag[g][row] += col.iter().map(|&(i, v)| (v * xg[i]).abs()).sum::<f64>();
            }
        }
        let mut c0 = 0;
        while c0 < nz {
            let w = CHUNK.min(nz - c0);
            let mut x = Mat::<f64>::zeros(n_i, w);
            for j in 0..w {
                for &(i, v) in &asm.kiz[c0 + j] {
                    x[(i, j)] = v;
                }
            }
            llt.solve_in_place_with_conj(Conj::No, x.as_mut());
            for row in 0..nz {
                let col = &asm.kiz[row];
                if col.is_empty() {
                    continue;
                }
                for j in 0..w {
                    let xj = x.col_as_slice(j);
                    let s: f64 = col.iter().map(|&(i, v)| v * xj[i]).sum();
                    r[(row, c0 + j)] -= s;
                    if row == c0 + j {
                        mag[row] += col.iter().map(|&(i, v)| (v * xj[i]).abs()).sum::<f64>();
                    }
                }
            }
            // The round-off of the solves: the computed x_j satisfies K_II x_j = K_Iz,j up
            // to a residual of order u·|K_II|·|x_j|, which reaches R_ij as x_iᵀ·residual
            // (K_zI K_II⁻¹ = x_iᵀ): bounded by |x_i|ᵀ|K_II||x_j|. This grows with the number
            // of elements the static mode x_j spans, where the terms of K_zz and K_zI x_j
            // alone do not.
            if let Some(k) = kii {
                let forms = abs_quadratic_forms(k, &x);
                for j in 0..w {
                    let xj = x.col_as_slice(j);
                    mag[c0 + j] += forms[j];
                    for g in 0..2 {
                        if !kxb[g].is_empty() {
                            rf_mag[g][c0 + j] += xj
                                .iter()
                                .zip(&kxb[g])
                                .map(|(a, b)| a.abs() * b)
                                .sum::<f64>();
                        }
                    }
                }
            }
            c0 += w;
        }
    }
    // symmetrize, recording the round-off asymmetry
    let mut maxr = 0.0f64;
    let mut maxd = 0.0f64;
    for i in 0..nz {
        for j in 0..nz {
            maxr = maxr.max(r[(i, j)].abs());
            if j > i {
                maxd = maxd.max((r[(i, j)] - r[(j, i)]).abs());
                let a = 0.5 * (r[(i, j)] + r[(j, i)]);
                r[(i, j)] = a;
                r[(j, i)] = a;
            }
        }
    }
    // round-off to zero: for a symmetric positive semidefinite K the terms of R_ij are
    // bounded by √(mag_i·mag_j) (Cauchy–Schwarz in the energy product)
    let tau = ROUND_OFF;
    let mut zeroed = 0;
    for j in 0..nz {
        for i in 0..nz {
            let v = r[(i, j)];
            if v != 0.0 && v.abs() <= tau * (mag[i] * mag[j]).sqrt() {
                r[(i, j)] = 0.0;
                zeroed += 1;
            }
        }
    }
    for g in 0..2 {
        for k in 0..nz {
            let v = rf[g][k];
            if v != 0.0 && v.abs() <= tau * rf_mag[g][k] {
                rf[g][k] = 0.0;
                zeroed += 1;
            }
        }
    }
    Condensation {
        r,
        rf,
        asymmetry: if maxr > 0.0 { maxd / maxr } else { 0.0 },
        zeroed,
    }
}

/// Times a closure.
pub(crate) fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let v = f();
    (v, t.elapsed().as_secs_f64())
}

#[cfg(test)]
mod abs_form_tests {
    use super::{abs_product, abs_quadratic_forms};
    use faer::sparse::{SparseColMat, Triplet};
    use faer::Mat;

    /// The block form agrees with `|x|ᵀ(|K||x|)` column by column (a 3×3 symmetric `K` with
    /// negative entries, stored as its lower triangle; hand value of the first column:
    /// |x| = (1, 2, 0.5), |K| = [[4,1,0],[1,3,2],[0,2,5]] → 4 + 2·1·2 + 3·4 + 2·2·2·0.5 + 5·0.25).
    #[test]
    fn block_forms_agree_with_the_products() {
        let lower = [
            (0, 0, 4.0),
            (1, 0, -1.0),
            (1, 1, 3.0),
            (2, 1, 2.0),
            (2, 2, 5.0),
        ];
        let trip: Vec<_> = lower
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        let k = SparseColMat::<usize, f64>::try_new_from_triplets(3, 3, &trip).unwrap();
        let x = Mat::from_fn(3, 2, |i, j| [[1.0, -2.0, 0.5], [0.0, 1.0, -3.0]][j][i]);
        let e = abs_quadratic_forms(&k, &x);
        assert_eq!(e[0], 4.0 + 4.0 + 12.0 + 4.0 + 1.25);
        for j in 0..2 {
            let xj = x.col_as_slice(j);
            let y = abs_product(&k, xj);
            let direct: f64 = xj.iter().zip(&y).map(|(a, b)| a.abs() * b).sum();
            assert!(
                (e[j] - direct).abs() <= 1e-15 * direct,
                "{} vs {direct}",
                e[j]
            );
        }
    }
}
