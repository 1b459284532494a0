//! The generalized DOF numbering of the bonded structure (formulation.md §2).
//!
//! Method (exact, no penalty): for every contact pair one node (B, or A if B is supported or
//! already carries links) gets its translations re-expressed as
//! `u_B = u_A + n·z_n + t·z_t` (or `u_A = u_B − n·z_n − t·z_t`), so the mutual displacements
//! `z` become generalized DOFs. Supported translations are rotated to the support frame and
//! prescribed: `u = T·[v_I; z; s]`.

use crate::elements::unit as element_unit;
use crate::error::{DofLabel, FemError};
use crate::model::{same_dof, Endpoint, Load, Model, NodeId, SpringKind, SupportDof};

/// A row of `T`: (generalized DOF, coefficient) pairs.
pub(crate) type Row = Vec<(usize, f64)>;

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
        for n in element_unit(e).rotation_nodes() {
            has_rot[n.0] = true;
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
    // link placement: the node that carries pair k's link DOFs is B if it is free, else the
    // free node of the A side with the largest weight (at least 1/4, so that dividing by it
    // stays well conditioned; the larger of a segment's two weights is at least 1/2)
    let mut pivot_pair: Vec<Option<usize>> = vec![None; nn];
    let mut nt = Vec::with_capacity(m);
    let mut pivot: Vec<Pivot> = Vec::with_capacity(m);
    let weights: Vec<Vec<(NodeId, f64)>> = model.pairs.iter().map(|p| p.a_weights()).collect();
    for (k, p) in model.pairs.iter().enumerate() {
        let n = unit(p.normal);
        nt.push((n, [n[1], -n[0]]));
        let free = |node: NodeId| trans[node.0].is_empty() && pivot_pair[node.0].is_none();
        if free(p.b) {
            pivot_pair[p.b.0] = Some(k);
            pivot.push(Pivot::B);
            continue;
        }
        let mut order: Vec<usize> = (0..weights[k].len()).collect();
        order.sort_by(|&i, &j| weights[k][j].1.total_cmp(&weights[k][i].1));
        if let Some(&j) = order
            .iter()
            .find(|&&j| weights[k][j].1 >= 0.25 && free(weights[k][j].0))
        {
            pivot_pair[weights[k][j].0 .0] = Some(k);
            pivot.push(Pivot::A(j));
            continue;
        }
        // The nodes by the names the model gives them.
        let name = |id: NodeId| format!("`{}`", model.names().node(id));
        let reason = match (p.a, p.segment) {
            (Endpoint::Ground, _) => format!(
                "node {} is supported in translation or already carries the links of another \
                 pair (a node-to-ground pair on a supported DOF is redundant)",
                name(p.b)
            ),
            (Endpoint::Node(a), None) => format!(
                "both node {} and node {} are supported or already carry the links of another \
                 pair",
                name(a),
                name(p.b)
            ),
            (Endpoint::Node(a), Some((a2, _))) => format!(
                "node {} and the segment's nodes {} and {} are supported or already carry the \
                 links of other pairs",
                name(p.b),
                name(a),
                name(a2)
            ),
        };
        return Err(FemError::LinkPlacement {
            pair: k,
            name: model.pair_name(k),
            reason,
        });
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
    let links = Links {
        model,
        pivot_pair: &pivot_pair,
        pivot: &pivot,
        weights: &weights,
        nt: &nt,
        z0,
    };
    for i in 0..nn {
        links.resolve(i, &mut tr_rows, &mut state)?;
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

/// Which node of a pair carries its link DOFs: B, or the A side's node `j` (in the order of
/// [`crate::ContactPairSpec::a_weights`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Pivot {
    B,
    A(usize),
}

/// What the translation rows of the nodes that carry links are resolved from.
struct Links<'a> {
    model: &'a Model,
    pivot_pair: &'a [Option<usize>],
    pivot: &'a [Pivot],
    weights: &'a [Vec<(NodeId, f64)>],
    nt: &'a [([f64; 2], [f64; 2])],
    z0: usize,
}

impl Links<'_> {
    /// The translation rows of node `i`: for the node carrying pair k's links, from
    /// `u_B − Σ w_j·u_Aj = n·z_n + t·z_t` (B: `u_B = Σ w_j·u_Aj + n·z_n + t·z_t`; A's node j:
    /// `u_Aj = (u_B − Σ_{l≠j} w_l·u_Al − n·z_n − t·z_t) / w_j`), the other nodes' rows first
    /// (recursively: chains of pairs).
    fn resolve(
        &self,
        i: usize,
        tr_rows: &mut Vec<Option<[Row; 2]>>,
        state: &mut Vec<u8>,
    ) -> Result<(), FemError> {
        if tr_rows[i].is_some() {
            return Ok(());
        }
        let k = self.pivot_pair[i].expect("pivot");
        if state[i] == 1 {
            return Err(FemError::LinkPlacement {
                pair: k,
                name: self.model.pair_name(k),
                reason: "the contact pairs form a closed loop of links".into(),
            });
        }
        state[i] = 1;
        let p = &self.model.pairs[k];
        let w = &self.weights[k];
        // (other node, coefficient) and the coefficient of the links
        let (others, sign): (Vec<(usize, f64)>, f64) = match self.pivot[k] {
            Pivot::B => (w.iter().map(|&(a, c)| (a.0, c)).collect(), 1.0),
            Pivot::A(j) => {
                let wj = w[j].1;
                let mut o = vec![(p.b.0, 1.0 / wj)];
                o.extend(
                    w.iter()
                        .enumerate()
                        .filter(|&(l, _)| l != j)
                        .map(|(_, &(a, c))| (a.0, -c / wj)),
                );
                (o, -1.0 / wj)
            }
        };
        let mut rows: [Row; 2] = [Row::new(), Row::new()];
        for &(o, c) in &others {
            self.resolve(o, tr_rows, state)?;
            let ro = tr_rows[o].as_ref().unwrap();
            for d in 0..2 {
                if c == 1.0 {
                    rows[d].extend_from_slice(&ro[d]);
                } else {
                    rows[d].extend(ro[d].iter().map(|&(g, v)| (g, c * v)));
                }
            }
        }
        let (n, t) = self.nt[k];
        let m = self.nt.len();
        for c in 0..2 {
            if n[c] != 0.0 {
                rows[c].push((self.z0 + k, sign * n[c]));
            }
            if t[c] != 0.0 {
                rows[c].push((self.z0 + m + k, sign * t[c]));
            }
        }
        tr_rows[i] = Some(rows);
        state[i] = 2;
        Ok(())
    }
}

pub(crate) fn merge(mut r: Row) -> Row {
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
