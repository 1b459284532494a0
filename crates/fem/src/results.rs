//! The condensed contact zone and the recovery of full results from a contact solution.

use crate::condense::{
    assemble, condense, factorize, spring_matrix, timed, Assembled, CondensationStats,
};
use crate::elements::{
    element_dofs, element_load, element_stiffness, extrapolate_to_nodes, gauss_coordinates,
    line_local_intensity, line_local_k, plane_stresses, to_local_vec,
};
use crate::error::FemError;
use crate::model::{
    Element, ElementId, Endpoint, Load, LoadGroup, Model, NodeId, SpringKind, SupportDof,
};
use faer::linalg::solvers::SolveCore;
use faer::sparse::linalg::solvers::Llt;
use faer::{Conj, Mat};

/// Contact load vector (CLV) of one load group: link forces of the bonded structure,
/// compression positive, one entry per pair.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactLoadVector {
    /// Normal link forces (compression positive).
    pub normal: Vec<f64>,
    /// Tangential link forces (positive along `+t` on node B).
    pub tangential: Vec<f64>,
}

/// The structure condensed to its contact zone (formulation.md §2), ready for the LCP, plus
/// what is needed to recover full results.
///
/// ```
/// use unilateral_fem::{ContactPairSpec, ContactSolution, FrameSection, Load, LoadGroup, Model};
/// let mut model = Model::new();
/// let a = model.add_node(0.0, 0.0);
/// let b = model.add_node(2.0, 0.0);
/// model.add_frame(a, b, FrameSection::new(1.0, 1.0, 1.0));
/// model.fix(a);
/// model.add_contact_pair(ContactPairSpec::to_ground(b, [0.0, 1.0]));
/// model.add_load(LoadGroup::Variable, Load::Nodal { node: b, fx: 0.0, fy: -1.0, m: 0.0 });
/// let c = model.condense().unwrap();
/// // bonded: the link at the tip carries the whole load in compression
/// assert!((c.variable.normal[0] - 1.0).abs() < 1e-12);
/// // suppose the LCP says the pair stays closed at p = 1
/// let sol = ContactSolution::bonded(&c, 1.0);
/// let r = c.recover(&sol).unwrap();
/// assert!(r.equilibrium.relative() < 1e-12);
/// ```
pub struct Condensed {
    /// Normal–normal block `Rnn` (m × m), symmetric positive semidefinite.
    pub rnn: Mat<f64>,
    /// `Rnt`: normal force from a tangential dislocation.
    pub rnt: Mat<f64>,
    /// `Rtn`: tangential force from a normal dislocation.
    pub rtn: Mat<f64>,
    /// `Rtt`, symmetric positive semidefinite.
    pub rtt: Mat<f64>,
    /// `R_c`: bonded link forces under the constant group.
    pub constant: ContactLoadVector,
    /// `R_v`: bonded link forces under the variable group (per unit `p`).
    pub variable: ContactLoadVector,
    /// Friction coefficient per pair.
    pub friction: Vec<f64>,
    /// Initial gap per pair.
    pub gap: Vec<f64>,
    /// Pair names.
    pub pair_names: Vec<String>,
    /// Unit normal `n` per pair (from A into B).
    pub normals: Vec<[f64; 2]>,
    /// Unit tangent `t = (n_y, −n_x)` per pair.
    pub tangents: Vec<[f64; 2]>,
    /// Sizes and timings.
    pub stats: CondensationStats,
    model: Model,
    asm: Assembled,
    llt: Option<Llt<usize, f64>>,
}

impl std::fmt::Debug for Condensed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Condensed")
            .field("rnn", &self.rnn)
            .field("rnt", &self.rnt)
            .field("rtn", &self.rtn)
            .field("rtt", &self.rtt)
            .field("constant", &self.constant)
            .field("variable", &self.variable)
            .field("friction", &self.friction)
            .field("gap", &self.gap)
            .field("pair_names", &self.pair_names)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl Model {
    /// Validates the model, assembles the bonded structure (every pair a rigid normal and
    /// tangential link), factorizes it once (sparse Cholesky) and condenses it to the contact
    /// zone: `R = [[Rnn, Rnt], [Rtn, Rtt]]` and the CLVs `R_c`, `R_v`.
    ///
    /// Errors: any [`FemError`] from [`Model::validate`], link placement problems, and
    /// [`FemError::Unstable`] naming the free DOFs when the bonded structure is a mechanism.
    pub fn condense(&self) -> Result<Condensed, FemError> {
        self.validate()?;
        let (asm, t_asm) = timed(|| assemble(self));
        let mut asm = asm?;
        let nnz_lower = asm.kii.as_ref().map_or(0, |k| k.compute_nnz());
        let (llt, t_fac) = timed(|| factorize(self, &asm));
        let (llt, lambda) = llt?;
        asm.kii_triplets = Vec::new();
        let kzz = std::mem::replace(&mut asm.kzz, Mat::zeros(0, 0));
        let kii = asm.kii.take();
        let (c, t_con) = timed(|| condense(&asm, kii.as_ref(), kzz, llt.as_ref()));
        drop(kii);
        let m = asm.map.m;
        let block = |r0: usize, c0: usize| Mat::<f64>::from_fn(m, m, |i, j| c.r[(r0 + i, c0 + j)]);
        let clv = |g: usize| ContactLoadVector {
            normal: c.rf[g][..m].to_vec(),
            tangential: c.rf[g][m..].to_vec(),
        };
        let stats = CondensationStats {
            free_dofs: asm.map.n_i,
            pairs: m,
            prescribed_dofs: asm.map.n_p,
            nnz_lower,
            assembly_s: t_asm,
            factorization_s: t_fac,
            condensation_s: t_con,
            asymmetry: c.asymmetry,
            smallest_eigenvalue: lambda,
            round_off_zeroed: c.zeroed,
        };
        if c.r.col_iter().any(|col| col.iter().any(|v| !v.is_finite()))
            || c.rf.iter().flatten().any(|v| !v.is_finite())
        {
            return Err(FemError::LinearAlgebra(
                "non-finite contact stiffness (ill-conditioned bonded structure)".into(),
            ));
        }
        Ok(Condensed {
            rnn: block(0, 0),
            rnt: block(0, m),
            rtn: block(m, 0),
            rtt: block(m, m),
            constant: clv(0),
            variable: clv(1),
            friction: self.pairs.iter().map(|p| p.friction).collect(),
            gap: self.pairs.iter().map(|p| p.gap).collect(),
            pair_names: (0..m).map(|i| self.pair_name(i)).collect(),
            normals: asm.map.nt.iter().map(|x| x.0).collect(),
            tangents: asm.map.nt.iter().map(|x| x.1).collect(),
            stats,
            model: self.clone(),
            asm,
            llt,
        })
    }
}

/// A solution of the contact problem at load parameter `p` (per pair, formulation.md §1).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactSolution {
    /// Load parameter.
    pub p: f64,
    /// Normal link forces (compression positive).
    pub x_n: Vec<f64>,
    /// Tangential link forces.
    pub x_t: Vec<f64>,
    /// Normal openings (opening positive) measured as the LCP measures them: from closed
    /// contact, so `z_n = η + n·(u_B − u_A)` with `η` the pair's initial gap (`z_n = 0` is
    /// closed, `z_n = η` is the undeformed position).
    pub z_n: Vec<f64>,
    /// Tangential mutual displacements.
    pub z_t: Vec<f64>,
}

impl ContactSolution {
    /// The bonded solution at `p`: every link at its undeformed length (`n·(u_B − u_A) = 0`,
    /// so `z_n = η`, `z_t = 0`) and `x = R_c + p·R_v`.
    pub fn bonded(c: &Condensed, p: f64) -> Self {
        let m = c.friction.len();
        Self {
            p,
            x_n: (0..m)
                .map(|i| c.constant.normal[i] + p * c.variable.normal[i])
                .collect(),
            x_t: (0..m)
                .map(|i| c.constant.tangential[i] + p * c.variable.tangential[i])
                .collect(),
            z_n: c.gap.clone(),
            z_t: vec![0.0; m],
        }
    }
}

/// A support reaction: force along the restrained direction (or moment).
#[derive(Debug, Clone, PartialEq)]
pub struct Reaction {
    /// The node.
    pub node: NodeId,
    /// The restrained DOF.
    pub dof: SupportDof,
    /// Reaction force along the support direction (or moment, counter-clockwise positive).
    pub value: f64,
}

/// Internal forces at a section of a frame or bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiagramPoint {
    /// Distance from the start node.
    pub s: f64,
    /// Axial force, tension positive.
    pub n: f64,
    /// Shear force, `Q = dM/ds`.
    pub q: f64,
    /// Bending moment, positive when it stretches the `−y_local` fibre (sagging for a
    /// left-to-right beam).
    pub m: f64,
}

/// End forces and internal force diagrams of a frame or bar.
#[derive(Debug, Clone, PartialEq)]
pub struct LineResult {
    /// The element.
    pub element: ElementId,
    /// Forces exerted by the nodes on the element, local axes:
    /// `[N1, V1, M1, N2, V2, M2]` (axial, transverse, moment at start and end).
    pub end_forces: [f64; 6],
    /// `N`, `Q`, `M` sampled at equal intervals along the element.
    pub diagram: Vec<DiagramPoint>,
}

/// Stresses in a plane element.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneResult {
    /// The element.
    pub element: ElementId,
    /// Global coordinates of the 2×2 Gauss points (node order).
    pub gauss_points: [[f64; 2]; 4],
    /// `[σxx, σyy, τxy, σzz]` at each Gauss point (tension positive).
    pub stress: [[f64; 4]; 4],
}

/// Global equilibrium check: applied loads + reactions + contact forces + springs = 0.
/// Each entry is `[Fx, Fy, M about the origin]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Equilibrium {
    /// Resultant of the applied loads (equivalent nodal loads).
    pub applied: [f64; 3],
    /// Resultant of the support reactions.
    pub reactions: [f64; 3],
    /// Resultant of the contact forces acting on the structure (both sides of node-to-node
    /// pairs: they cancel unless the pair's nodes are apart and `n` is not along them).
    pub contact: [f64; 3],
    /// Resultant of the spring forces acting on the structure (both ends of node-to-node
    /// springs, as for pairs).
    pub springs: [f64; 3],
    /// Sum of the four (≈ 0).
    pub resultant: [f64; 3],
    /// Largest nodal out-of-balance force at a free DOF.
    pub free_dof_residual: f64,
    /// Largest `|x − x(z)|`: difference between the given link forces and those implied by the
    /// given mutual displacements (0 for a consistent contact solution).
    pub link_force_mismatch: f64,
    /// Force scale of the resultant: the largest applied force, reaction or contact force.
    pub scale: f64,
    /// `free_dof_residual` relative to the forces meeting at the free DOFs: the largest
    /// residual at a free translation over the largest magnitude of the forces (applied and
    /// element end forces) meeting at one, and likewise for rotations with moments; the larger
    /// of the two. Independent of the units.
    pub free_dof_relative: f64,
    /// `link_force_mismatch` relative to the largest link force (given or implied).
    pub link_force_relative: f64,
}

/// `a / b`, 0 when `a = 0` (nothing to compare), infinite when only `b` is 0.
fn ratio(a: f64, b: f64) -> f64 {
    if a == 0.0 {
        0.0
    } else {
        a / b
    }
}

impl Equilibrium {
    /// Largest of the relative residuals: at the free DOFs, in the links, and of the
    /// resultant (forces over [`Equilibrium::scale`], the moment over the scale times the
    /// model's size). Every one is a ratio of quantities of the same units, so the check does
    /// not depend on the units of the model. NaN when a residual is not finite.
    pub fn relative(&self) -> f64 {
        let res = self.resultant.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let parts = [
            self.free_dof_relative,
            self.link_force_relative,
            ratio(res, self.scale),
        ];
        if parts.iter().any(|v| v.is_nan()) {
            return f64::NAN;
        }
        parts.into_iter().fold(0.0, f64::max)
    }
}

/// Full results of the structure for a contact solution.
#[derive(Debug, Clone, PartialEq)]
pub struct Results {
    /// Load parameter.
    pub p: f64,
    /// `[ux, uy, rz]` per node (`rz = 0` for nodes without a rotational DOF).
    pub displacements: Vec<[f64; 3]>,
    /// Support reactions, one per restrained DOF.
    pub reactions: Vec<Reaction>,
    /// Link forces implied by the displacements (compare with the given `x`).
    pub link_forces: ContactLoadVector,
    /// Frames and bars.
    pub lines: Vec<LineResult>,
    /// Plane elements.
    pub planes: Vec<PlaneResult>,
    /// Nodal stresses `[σxx, σyy, τxy, σzz]` averaged over the plane elements at a node
    /// (extrapolated from the Gauss points); `None` where no plane element is attached.
    pub nodal_stress: Vec<Option<[f64; 4]>>,
    /// Spring forces (tension / elongation positive) or moments.
    pub spring_forces: Vec<f64>,
    /// Equilibrium check.
    pub equilibrium: Equilibrium,
}

impl Results {
    /// `true` when every reported number (displacements, reactions, link forces, internal
    /// forces, stresses, spring forces, equilibrium check) is finite.
    pub fn all_finite(&self) -> bool {
        let fin = |v: &f64| v.is_finite();
        self.p.is_finite()
            && self.displacements.iter().flatten().all(fin)
            && self.reactions.iter().all(|r| r.value.is_finite())
            && self.link_forces.normal.iter().all(fin)
            && self.link_forces.tangential.iter().all(fin)
            && self.lines.iter().all(|l| {
                l.end_forces.iter().all(fin)
                    && l.diagram
                        .iter()
                        .all(|d| [d.s, d.n, d.q, d.m].iter().all(fin))
            })
            && self
                .planes
                .iter()
                .all(|p| p.stress.iter().flatten().all(fin))
            && self.nodal_stress.iter().flatten().flatten().all(fin)
            && self.spring_forces.iter().all(fin)
            && self.equilibrium.relative().is_finite()
    }
}

/// Number of sections sampled along a frame.
pub const DIAGRAM_SAMPLES: usize = 11;

impl Condensed {
    /// Number of contact pairs.
    pub fn pairs(&self) -> usize {
        self.friction.len()
    }

    /// The resultant `[Fx, Fy]` of a load group's equivalent nodal loads (the variable group
    /// per unit `p`).
    pub fn load_resultant(&self, group: LoadGroup) -> [f64; 2] {
        let f = &self.asm.f_phys[match group {
            LoadGroup::Constant => 0,
            LoadGroup::Variable => 1,
        }];
        let mut r = [0.0; 2];
        for node in f.chunks_exact(3) {
            r[0] += node[0];
            r[1] += node[1];
        }
        r
    }

    /// The full contact stiffness matrix `[[Rnn, Rnt], [Rtn, Rtt]]` (2m × 2m).
    pub fn csm(&self) -> Mat<f64> {
        let m = self.pairs();
        Mat::from_fn(2 * m, 2 * m, |i, j| match (i < m, j < m) {
            (true, true) => self.rnn[(i, j)],
            (true, false) => self.rnt[(i, j - m)],
            (false, true) => self.rtn[(i - m, j)],
            (false, false) => self.rtt[(i - m, j - m)],
        })
    }

    /// Recovers displacements, reactions, internal forces, stresses and the equilibrium check
    /// for a contact solution at load parameter `sol.p`.
    pub fn recover(&self, sol: &ContactSolution) -> Result<Results, FemError> {
        let model = &self.model;
        let map = &self.asm.map;
        let m = map.m;
        for (name, v) in [
            ("x_n", &sol.x_n),
            ("x_t", &sol.x_t),
            ("z_n", &sol.z_n),
            ("z_t", &sol.z_t),
        ] {
            if v.len() != m {
                return Err(FemError::BadSolution(format!(
                    "{name} has {} entries, the model has {m} pairs",
                    v.len()
                )));
            }
            if v.iter().any(|x| !x.is_finite()) {
                return Err(FemError::BadSolution(format!("{name} is not finite")));
            }
        }
        if !sol.p.is_finite() {
            return Err(FemError::BadSolution("p is not finite".into()));
        }
        let p = sol.p;
        let fac = |g: LoadGroup| match g {
            LoadGroup::Constant => 1.0,
            LoadGroup::Variable => p,
        };
        let (n_i, z0, p0) = (map.n_i, map.z0(), map.p0());
        // The link dislocations are the mutual displacements n·(u_B − u_A) = z_n − η and
        // t·(u_B − u_A) = z_t: the LCP measures z_n from closed contact (formulation §3, the
        // gaps enter q_c as −Rnn·η, −Rtn·η).
        let z: Vec<f64> = sol
            .z_n
            .iter()
            .zip(&self.gap)
            .map(|(z, g)| z - g)
            .chain(sol.z_t.iter().copied())
            .collect();
        // free DOFs
        let mut v_i = vec![0.0; n_i];
        if let Some(llt) = &self.llt {
            let mut rhs =
                Mat::<f64>::from_fn(n_i, 1, |i, _| self.asm.b_i[0][i] + p * self.asm.b_i[1][i]);
            for (r, col) in self.asm.kiz.iter().enumerate() {
                for &(i, v) in col {
                    rhs[(i, 0)] -= v * z[r];
                }
            }
            llt.solve_in_place_with_conj(Conj::No, rhs.as_mut());
            for (i, x) in v_i.iter_mut().enumerate() {
                *x = rhs[(i, 0)];
            }
        }
        let s: Vec<f64> = (0..map.n_p)
            .map(|k| self.asm.s[0][k] + p * self.asm.s[1][k])
            .collect();
        let gen = |g: usize| -> f64 {
            if g < z0 {
                v_i[g]
            } else if g < p0 {
                z[g - z0]
            } else {
                s[g - p0]
            }
        };
        let nn = model.nodes.len();
        let u: Vec<f64> = map
            .rows
            .iter()
            .map(|r| r.iter().map(|&(g, c)| c * gen(g)).sum())
            .collect();
        let displacements: Vec<[f64; 3]> = (0..nn)
            .map(|i| [u[3 * i], u[3 * i + 1], u[3 * i + 2]])
            .collect();

        // element loads per element
        let mut loads_of: Vec<Vec<(f64, &Load)>> = vec![Vec::new(); model.elements.len()];
        for (g, l) in &model.loads {
            match l {
                Load::Distributed { element, .. }
                | Load::BodyForce { element, .. }
                | Load::Temperature { element, .. } => loads_of[element.0].push((fac(*g), l)),
                _ => {}
            }
        }

        // residual r = K u − f, element by element
        let f: Vec<f64> = (0..3 * nn)
            .map(|d| self.asm.f_phys[0][d] + p * self.asm.f_phys[1][d])
            .collect();
        let mut r: Vec<f64> = f.iter().map(|v| -v).collect();
        // magnitude of the forces that meet at each DOF (the scale of its residual)
        let mut r_mag: Vec<f64> = f.iter().map(|v| v.abs()).collect();
        let mut lines = Vec::new();
        let mut planes = Vec::new();
        let mut stress_sum: Vec<[f64; 4]> = vec![[0.0; 4]; nn];
        let mut stress_cnt = vec![0usize; nn];
        for (ei, el) in model.elements.iter().enumerate() {
            let em = element_stiffness(model, el);
            let n = em.dofs.len();
            let ue: Vec<f64> = em.dofs.iter().map(|&d| u[d]).collect();
            for a in 0..n {
                let fa = (0..n).map(|b| em.k[a * n + b] * ue[b]).sum::<f64>();
                r[em.dofs[a]] += fa;
                r_mag[em.dofs[a]] += fa.abs();
            }
            match el {
                Element::Frame { .. } | Element::Bar { .. } => {
                    lines.push(self.line_result(ElementId(ei), el, &ue, &loads_of[ei]));
                }
                Element::Plane {
                    nodes,
                    material,
                    analysis,
                    formulation,
                } => {
                    let xy = nodes.map(|n| model.nodes[n.0]);
                    let dt: f64 = loads_of[ei]
                        .iter()
                        .filter_map(|(fc, l)| match l {
                            Load::Temperature { uniform, .. } => Some(fc * uniform),
                            _ => None,
                        })
                        .sum();
                    let st = plane_stresses(&xy, material, *analysis, *formulation, &ue, dt);
                    let at_nodes = extrapolate_to_nodes(&st);
                    for (k, nd) in nodes.iter().enumerate() {
                        for c in 0..4 {
                            stress_sum[nd.0][c] += at_nodes[k][c];
                        }
                        stress_cnt[nd.0] += 1;
                    }
                    planes.push(PlaneResult {
                        element: ElementId(ei),
                        gauss_points: gauss_coordinates(&xy),
                        stress: st,
                    });
                }
            }
        }
        let mut spring_forces = Vec::new();
        let mut ground = [0.0; 3];
        for sp in &model.springs {
            let em = spring_matrix(sp);
            let n = em.dofs.len();
            for a in 0..n {
                let fa = (0..n).map(|b| em.k[a * n + b] * u[em.dofs[b]]).sum::<f64>();
                r[em.dofs[a]] += fa;
                r_mag[em.dofs[a]] += fa.abs();
            }
            let ua = |d: usize| match sp.a {
                Endpoint::Ground => 0.0,
                Endpoint::Node(a) => u[3 * a.0 + d],
            };
            let b = sp.b.0;
            let pos = model.nodes[b];
            match sp.kind {
                SpringKind::Translational {
                    direction,
                    stiffness,
                } => {
                    let l = direction[0].hypot(direction[1]);
                    let d = [direction[0] / l, direction[1] / l];
                    let e = d[0] * (u[3 * b] - ua(0)) + d[1] * (u[3 * b + 1] - ua(1));
                    let force = stiffness * e;
                    spring_forces.push(force);
                    let fb = [-force * d[0], -force * d[1]];
                    ground[0] += fb[0];
                    ground[1] += fb[1];
                    ground[2] += pos[0] * fb[1] - pos[1] * fb[0];
                    if let Endpoint::Node(a) = sp.a {
                        let pa = model.nodes[a.0];
                        ground[0] -= fb[0];
                        ground[1] -= fb[1];
                        ground[2] -= pa[0] * fb[1] - pa[1] * fb[0];
                    }
                }
                SpringKind::Rotational { stiffness } => {
                    let mo = stiffness * (u[3 * b + 2] - ua(2));
                    spring_forces.push(mo);
                    if sp.a == Endpoint::Ground {
                        ground[2] -= mo;
                    }
                }
            }
        }
        // generalized residuals
        let mut res_i = vec![0.0; n_i];
        let mut mag_i = vec![0.0; n_i];
        let mut mag_z = vec![0.0; 2 * m];
        let mut x_of_z = vec![0.0; 2 * m];
        let mut lambda = vec![0.0; map.n_p];
        for (d, row) in map.rows.iter().enumerate() {
            for &(g, c) in row {
                if g < z0 {
                    res_i[g] += c * r[d];
                    mag_i[g] += c.abs() * r_mag[d];
                } else if g < p0 {
                    x_of_z[g - z0] += c * r[d];
                    mag_z[g - z0] += c.abs() * r_mag[d];
                } else {
                    lambda[g - p0] += c * r[d];
                }
            }
        }
        let moment = |pos: [f64; 2], fx: f64, fy: f64| pos[0] * fy - pos[1] * fx;
        let mut applied = [0.0; 3];
        let mut scale = 0.0f64;
        for i in 0..nn {
            let (fx, fy, mz) = (f[3 * i], f[3 * i + 1], f[3 * i + 2]);
            applied[0] += fx;
            applied[1] += fy;
            applied[2] += mz + moment(model.nodes[i], fx, fy);
            scale = scale.max(fx.abs()).max(fy.abs());
        }
        let mut reactions = Vec::with_capacity(map.n_p);
        let mut reac = [0.0; 3];
        for (k, &(node, dof, dir)) in map.prescribed.iter().enumerate() {
            let v = lambda[k];
            reactions.push(Reaction {
                node,
                dof,
                value: v,
            });
            let (fx, fy) = (v * dir[0], v * dir[1]);
            reac[0] += fx;
            reac[1] += fy;
            reac[2] += dir[2] * v + moment(model.nodes[node.0], fx, fy);
            scale = scale.max(v.abs());
        }
        let mut contact = [0.0; 3];
        for (k, pair) in model.pairs.iter().enumerate() {
            let (nv, tv) = map.nt[k];
            let fx = nv[0] * sol.x_n[k] + tv[0] * sol.x_t[k];
            let fy = nv[1] * sol.x_n[k] + tv[1] * sol.x_t[k];
            scale = scale.max(sol.x_n[k].abs()).max(sol.x_t[k].abs());
            let pb = model.nodes[pair.b.0];
            contact[0] += fx;
            contact[1] += fy;
            contact[2] += moment(pb, fx, fy);
            if let Endpoint::Node(a) = pair.a {
                // the reaction on A; with A and B at different places and n not along AB the
                // pair carries a couple, which is part of the balance
                let pa = model.nodes[a.0];
                contact[0] -= fx;
                contact[1] -= fy;
                contact[2] -= moment(pa, fx, fy);
            }
        }
        let mut resultant = [0.0; 3];
        for c in 0..3 {
            resultant[c] = applied[c] + reac[c] + contact[c] + ground[c];
        }
        let x_given: Vec<f64> = sol.x_n.iter().chain(&sol.x_t).copied().collect();
        let mismatch = x_of_z
            .iter()
            .zip(&x_given)
            .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()));
        let free_res = res_i.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let nodal_stress = (0..nn)
            .map(|i| (stress_cnt[i] > 0).then(|| stress_sum[i].map(|v| v / stress_cnt[i] as f64)))
            .collect();
        // moment scale: forces times the model's size (its extent)
        let extent = |c: usize| {
            let (lo, hi) = model
                .nodes
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
                    (a.0.min(p[c]), a.1.max(p[c]))
                });
            if hi >= lo {
                hi - lo
            } else {
                0.0
            }
        };
        let size = extent(0).max(extent(1));
        let size = if size > 0.0 { size } else { 1.0 };
        // Relative residuals, each against forces (or moments) of its own units, so that they
        // do not depend on the units of the model: the largest residual at a free translation
        // over the largest force meeting at one (or the largest applied force, reaction or
        // contact force when larger), the same for rotations against moments (and the force
        // scale times the model's size), the link force mismatch against the largest link
        // force.
        let mut worst = [(0.0f64, scale), (0.0f64, scale * size)];
        for g in 0..n_i {
            let k = usize::from(map.free_label[g].1 == crate::error::DofLabel::Rz);
            worst[k].0 = worst[k].0.max(res_i[g].abs());
            worst[k].1 = worst[k].1.max(mag_i[g]);
        }
        let link_mag = mag_z.iter().fold(scale, |a, b| a.max(b.abs()));
        let free_rel = ratio(worst[0].0, worst[0].1).max(ratio(worst[1].0, worst[1].1));
        Ok(Results {
            p,
            displacements,
            reactions,
            link_forces: ContactLoadVector {
                normal: x_of_z[..m].to_vec(),
                tangential: x_of_z[m..].to_vec(),
            },
            lines,
            planes,
            nodal_stress,
            spring_forces,
            equilibrium: Equilibrium {
                applied,
                reactions: reac,
                contact,
                springs: ground,
                resultant: [resultant[0], resultant[1], resultant[2] / size],
                free_dof_residual: free_res,
                link_force_mismatch: mismatch,
                free_dof_relative: free_rel,
                link_force_relative: ratio(mismatch, link_mag),
                scale: scale.max(f64::MIN_POSITIVE),
            },
        })
    }

    fn line_result(
        &self,
        id: ElementId,
        el: &Element,
        ue: &[f64],
        loads: &[(f64, &Load)],
    ) -> LineResult {
        let model = &self.model;
        let (k, n, l, c, s) = line_local_k(model, el);
        let ul = to_local_vec(ue, c, s);
        let mut fl = vec![0.0; n];
        for (fc, load) in loads {
            if let Some(fe) = element_load(model, el, load) {
                let fe = to_local_vec(&fe, c, s);
                for a in 0..n {
                    fl[a] += fc * fe[a];
                }
            }
        }
        let mut end = vec![0.0; n];
        for a in 0..n {
            end[a] = (0..n).map(|b| k[a * n + b] * ul[b]).sum::<f64>() - fl[a];
        }
        let end6 = if n == 6 {
            [end[0], end[1], end[2], end[3], end[4], end[5]]
        } else {
            [end[0], end[1], 0.0, end[2], end[3], 0.0]
        };
        let _ = element_dofs(el);
        let intens: Vec<(f64, [f64; 2], [f64; 2])> = loads
            .iter()
            .filter_map(|(fc, ld)| line_local_intensity(ld, c, s).map(|(a, b)| (*fc, a, b)))
            .collect();
        let diagram = (0..DIAGRAM_SAMPLES)
            .map(|i| {
                let x = l * i as f64 / (DIAGRAM_SAMPLES - 1) as f64;
                let (mut ia, mut it, mut im) = (0.0, 0.0, 0.0);
                for (fc, q1, q2) in &intens {
                    // ∫0^x q, ∫0^x q(x − s) ds for linear q
                    let da = (q2[0] - q1[0]) / l;
                    let dt = (q2[1] - q1[1]) / l;
                    ia += fc * (q1[0] * x + da * x * x / 2.0);
                    it += fc * (q1[1] * x + dt * x * x / 2.0);
                    im += fc * (q1[1] * x * x / 2.0 + dt * x.powi(3) / 6.0);
                }
                DiagramPoint {
                    s: x,
                    n: -end6[0] - ia,
                    q: end6[1] + it,
                    m: -end6[2] + end6[1] * x + im,
                }
            })
            .collect();
        LineResult {
            element: id,
            end_forces: end6,
            diagram,
        }
    }
}
