//! The recovery of full results from the link values of a contact solution: displacements,
//! reactions, internal forces and stresses element by element, spring forces, and the
//! equilibrium check of the whole structure.

use crate::condense::Condensed;
use crate::elements::frame::LinePrepared;
use crate::elements::spring::{spring_direction, spring_force, spring_matrix};
use crate::elements::{element_stiffness, unit as element_unit, ElemMat, Recovered, Unit};
use crate::error::FemError;
use crate::model::{ElementId, Endpoint, Load};
use crate::results::{ratio, ContactLoadVector, Equilibrium, LinkValues, Reaction, Results};
use faer::linalg::solvers::SolveCore;
use faer::{Conj, Mat};

/// The elements' global stiffness matrices of a condensed model, and its line elements
/// prepared for recovery ([`Line::prepare`](crate::elements::frame::Line::prepare)), formed
/// once the model is recovered a second time (the frames of a load path recover it thousands
/// of times, and forming every element's matrix again each time cost more than the rest of a
/// recovery).
#[derive(Debug, Default)]
pub(crate) struct ElementCache {
    recoveries: std::sync::atomic::AtomicUsize,
    kept: std::sync::OnceLock<Kept>,
}

/// What [`ElementCache`] keeps, element by element.
#[derive(Debug)]
struct Kept {
    k: Vec<ElemMat>,
    /// A line element's recovery data for its element loads in the model's order (the order
    /// of [`Condensed::results_of`]'s loads of the element); `None` for other elements.
    lines: Vec<Option<LinePrepared>>,
    /// Each spring's matrix and unit direction.
    springs: Vec<(ElemMat, [f64; 2])>,
    /// The element loads by element ([`ElementLoads`]).
    loads: ElementLoads,
    /// The model's size ([`model_size`]).
    size: f64,
}

impl ElementCache {
    /// What is kept (from the second call on), `None` at the first call.
    fn get(&self, model: &crate::model::Model) -> Option<&Kept> {
        use std::sync::atomic::Ordering;
        if self.recoveries.fetch_add(1, Ordering::Relaxed) == 0 {
            return None;
        }
        Some(self.kept.get_or_init(|| {
            let loads = ElementLoads::new(model);
            let lines: Vec<Option<LinePrepared>> = model
                .elements
                .iter()
                .enumerate()
                .map(|(e, el)| match element_unit(el) {
                    Unit::Line(line) => {
                        Some(line.prepare(model, loads.of(e).iter().map(|&li| &model.loads[li].1)))
                    }
                    _ => None,
                })
                .collect();
            Kept {
                k: model
                    .elements
                    .iter()
                    .map(|el| element_stiffness(model, el))
                    .collect(),
                lines,
                springs: model
                    .springs
                    .iter()
                    .map(|sp| (spring_matrix(sp), spring_direction(sp)))
                    .collect(),
                loads,
                size: model_size(model),
            }
        }))
    }
}

/// The element loads of a model element by element, each element's in the model's order:
/// one list of load indices with each element's range (`start[e]..start[e + 1]`).
#[derive(Debug)]
struct ElementLoads {
    order: Vec<usize>,
    start: Vec<usize>,
}

impl ElementLoads {
    fn new(model: &crate::model::Model) -> Self {
        // a stable sort keeps each element's loads in the model's order
        let mut by_element: Vec<(usize, usize)> = model
            .loads
            .iter()
            .enumerate()
            .filter_map(|(li, (_, l))| load_element(l).map(|e| (e, li)))
            .collect();
        by_element.sort_by_key(|&(e, _)| e);
        let mut start = vec![0usize; model.elements.len() + 1];
        for &(e, _) in &by_element {
            start[e + 1] += 1;
        }
        for e in 0..model.elements.len() {
            start[e + 1] += start[e];
        }
        Self {
            order: by_element.into_iter().map(|(_, li)| li).collect(),
            start,
        }
    }

    /// The indices of element `e`'s loads.
    fn of(&self, e: usize) -> &[usize] {
        &self.order[self.start[e]..self.start[e + 1]]
    }
}

/// The model's size, the scale of moments against forces: its larger extent along x or y
/// (1 for a model at one point).
fn model_size(model: &crate::model::Model) -> f64 {
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
    if size > 0.0 {
        size
    } else {
        1.0
    }
}

/// The element an element load acts on; `None` for a load on nodes or links.
fn load_element(l: &Load) -> Option<usize> {
    match l {
        Load::Distributed { element, .. }
        | Load::BodyForce { element, .. }
        | Load::Temperature { element, .. } => Some(element.0),
        _ => None,
    }
}

/// The applied load of one recovery: the generalized loads at the free DOFs, the prescribed
/// values, the physical equivalent loads, and the factor of every load case (for the element
/// loads).
struct Applied {
    b_i: Vec<f64>,
    s: Vec<f64>,
    f: Vec<f64>,
    case_factor: Vec<f64>,
}

impl Condensed {
    /// Recovers displacements, reactions, internal forces, stresses and the equilibrium check
    /// for a contact solution at load parameter `sol.p`: the case `constant` at factor 1, the
    /// case `variable` at factor `p`, every other case at 0.
    pub fn recover(&self, sol: &LinkValues) -> Result<Results, FemError> {
        self.check_links(sol)?;
        let p = sol.p;
        let asm = &self.asm;
        let map = &asm.map;
        let applied = Applied {
            b_i: (0..map.n_i)
                .map(|i| asm.b_i[0][i] + p * asm.b_i[1][i])
                .collect(),
            s: (0..map.n_p)
                .map(|k| asm.s[0][k] + p * asm.s[1][k])
                .collect(),
            f: (0..asm.f_phys[0].len())
                .map(|d| asm.f_phys[0][d] + p * asm.f_phys[1][d])
                .collect(),
            case_factor: (0..asm.cases.len())
                .map(|c| {
                    if asm.group_case[0] == Some(c) {
                        1.0
                    } else if asm.group_case[1] == Some(c) {
                        p
                    } else {
                        0.0
                    }
                })
                .collect(),
        };
        self.recover_applied(sol, &applied)
    }

    /// Recovers the full results (as [`Condensed::recover`]) for the link values `sol` under
    /// the load `Σ factors[c]·(case c)`, the factors indexed like [`Condensed::case_names`]:
    /// every load of a case (nodal, distributed, body, settlement, temperature) is multiplied
    /// by its case's factor. `sol.p` is not read as a load; it is copied to [`Results::p`] as
    /// the caller's label of the point (a history's pseudo-time, say).
    ///
    /// Errors: [`FemError::BadSolution`] when `factors` does not have one finite entry per
    /// case, or the link values do not fit the model.
    pub fn recover_at(&self, factors: &[f64], sol: &LinkValues) -> Result<Results, FemError> {
        let asm = &self.asm;
        if factors.len() != asm.cases.len() {
            return Err(FemError::BadSolution(format!(
                "{} load factors given, the model has {} load cases",
                factors.len(),
                asm.cases.len()
            )));
        }
        if let Some(c) = factors.iter().position(|f| !f.is_finite()) {
            return Err(FemError::BadSolution(format!(
                "the factor of load case `{}` is not finite",
                self.case_names[c]
            )));
        }
        self.check_links(sol)?;
        let combine = |part: fn(&crate::assemble::CaseVectors) -> &Vec<f64>, len: usize| {
            let mut v = vec![0.0; len];
            for (c, f) in asm.cases.iter().zip(factors) {
                if *f != 0.0 {
                    for (a, b) in v.iter_mut().zip(part(c)) {
                        *a += f * b;
                    }
                }
            }
            v
        };
        let applied = Applied {
            b_i: combine(|c| &c.b_i, asm.map.n_i),
            s: combine(|c| &c.s, asm.map.n_p),
            f: combine(|c| &c.f_phys, 3 * self.model.nodes.len()),
            case_factor: factors.to_vec(),
        };
        self.recover_applied(sol, &applied)
    }

    /// The largest force that the displacements of `results` make term by term in one row of
    /// an element or a spring: `max Σ_b |k_ab u_b|`. Where a body has moved far as a whole (a
    /// block sliding hundreds of metres on a soft spring), these terms are its stiffness times
    /// that motion, and their round-off is in every force recovered — whether the motion is a
    /// link's dislocation or the free DOFs that follow it (the dislocations' own measure,
    /// [`crate::Equilibrium::dislocation_force`], sees only the links' couplings: a steel block
    /// sliding 346 m on a soft foundation's pairs coupled to the foundation's 38 kN/mm, its own
    /// nodes' terms were 130 times the links' summed over its 14 pairs).
    pub fn displacement_terms(&self, results: &Results) -> f64 {
        let model = &self.model;
        let u = |d: usize| results.displacements.get(d / 3).map_or(0.0, |n| n[d % 3]);
        let kept = self.element_k.get(model);
        let row_terms = |em: &ElemMat| {
            let n = em.dofs.len();
            (0..n)
                .map(|a| {
                    (0..n)
                        .map(|b| (em.k[a * n + b] * u(em.dofs[b])).abs())
                        .sum::<f64>()
                })
                .fold(0.0f64, f64::max)
        };
        let mut terms = 0.0f64;
        for (ei, el) in model.elements.iter().enumerate() {
            terms = terms.max(match kept {
                Some(k) => row_terms(&k.k[ei]),
                None => row_terms(&element_stiffness(model, el)),
            });
        }
        for (si, sp) in model.springs.iter().enumerate() {
            terms = terms.max(match kept {
                Some(k) => row_terms(&k.springs[si].0),
                None => row_terms(&spring_matrix(sp)),
            });
        }
        terms
    }

    fn check_links(&self, sol: &LinkValues) -> Result<(), FemError> {
        let m = self.asm.map.m;
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
        Ok(())
    }

    fn recover_applied(&self, sol: &LinkValues, applied: &Applied) -> Result<Results, FemError> {
        let map = &self.asm.map;
        let n_i = map.n_i;
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
        let rhs0 = self.llt.as_ref().map(|_| {
            let mut rhs = applied.b_i.clone();
            for (r, col) in self.asm.kiz.iter().enumerate() {
                for &(i, v) in col {
                    rhs[i] -= v * z[r];
                }
            }
            rhs
        });
        let solve = |v: &[f64]| -> Vec<f64> {
            let llt = self.llt.as_ref().expect("a factorisation with free DOFs");
            let mut rhs = Mat::<f64>::from_fn(n_i, 1, |i, _| v[i]);
            llt.solve_in_place_with_conj(Conj::No, rhs.as_mut());
            (0..n_i).map(|i| rhs[(i, 0)]).collect()
        };
        if let Some(rhs) = &rhs0 {
            v_i = solve(rhs);
        }
        let (mut results, mut res_i) = self.results_of(sol, applied, &z, &v_i)?;
        // A structure close to a mechanism (displacements over many orders) can be left out
        // of balance by more than an analysis accepts: then up to two steps of iterative
        // refinement, `v −= K_II⁻¹ (K_II v + K_Iz z − b_I)` with the residual the recovery has
        // just formed element by element, each kept only if it balances better. Results that
        // are accepted as they are stay as they are (the same bits, and no second recovery
        // for every frame of a long path).
        for _ in 0..2 {
            if rhs0.is_none() || !(results.equilibrium.relative() > EQUILIBRIUM_ACCEPT) {
                break;
            }
            let d = solve(&res_i);
            let v: Vec<f64> = v_i.iter().zip(&d).map(|(a, b)| a - b).collect();
            let (r2, res2) = self.results_of(sol, applied, &z, &v)?;
            if !(r2.equilibrium.relative() < results.equilibrium.relative()) {
                break;
            }
            (results, res_i, v_i) = (r2, res2, v);
        }
        Ok(results)
    }

    /// The results of the free-DOF values `v_i` (with the link dislocations `z`), and the
    /// free DOFs' residuals `K_II v + K_Iz z − b_I` formed element by element.
    fn results_of(
        &self,
        sol: &LinkValues,
        applied: &Applied,
        z: &[f64],
        v_i: &[f64],
    ) -> Result<(Results, Vec<f64>), FemError> {
        let model = &self.model;
        let map = &self.asm.map;
        let m = map.m;
        let p = sol.p;
        let (n_i, z0, p0) = (map.n_i, map.z0(), map.p0());
        let s = &applied.s;
        // no applied force, settlement or temperature (see the check below; the link forces
        // are judged there, against the dislocations' round-off)
        let unloaded = applied
            .f
            .iter()
            .chain(&applied.b_i)
            .chain(&applied.s)
            .all(|&v| v == 0.0);
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

        let kept = self.element_k.get(model);
        let formed_loads;
        let element_loads = match kept {
            Some(k) => &k.loads,
            None => {
                formed_loads = ElementLoads::new(model);
                &formed_loads
            }
        };

        // residual r = K u − f, element by element
        let f = &applied.f;
        let mut r: Vec<f64> = f.iter().map(|v| -v).collect();
        // magnitude of the forces that meet at each DOF (the scale of its residual)
        let mut r_mag: Vec<f64> = f.iter().map(|v| v.abs()).collect();
        let mut lines = Vec::with_capacity(kept.map_or(0, |k| k.lines.iter().flatten().count()));
        let mut planes = Vec::new();
        let mut stress_mean: Vec<[f64; 4]> = vec![[0.0; 4]; nn];
        let mut stress_cnt = vec![0usize; nn];
        // One buffer for every element's displacements (a path's frames recover thousands of
        // times).
        let mut ue: Vec<f64> = Vec::with_capacity(12);
        // Unloaded: the largest force the displacements make in an element or spring term by
        // term (the scale of an unloaded state's round-off, below).
        let mut elastic_terms = 0.0f64;
        for (ei, el) in model.elements.iter().enumerate() {
            let unit = element_unit(el);
            let formed;
            let em = match kept {
                Some(k) => &k.k[ei],
                None => {
                    formed = element_stiffness(model, el);
                    &formed
                }
            };
            let n = em.dofs.len();
            ue.clear();
            ue.extend(em.dofs.iter().map(|&d| u[d]));
            for a in 0..n {
                let fa = (0..n).map(|b| em.k[a * n + b] * ue[b]).sum::<f64>();
                r[em.dofs[a]] += fa;
                r_mag[em.dofs[a]] += fa.abs();
                if unloaded {
                    let terms = (0..n).map(|b| (em.k[a * n + b] * ue[b]).abs()).sum::<f64>();
                    elastic_terms = elastic_terms.max(terms);
                }
            }
            let loads = element_loads.of(ei);
            let factor = |li: usize| applied.case_factor[model.loads[li].0 .0];
            let recovered = match kept.and_then(|k| k.lines[ei].as_ref()) {
                Some(line) => line.recover(ElementId(ei), &ue, loads.iter().map(|&li| factor(li))),
                None => {
                    let loads: Vec<(f64, &Load)> = loads
                        .iter()
                        .map(|&li| (factor(li), &model.loads[li].1))
                        .collect();
                    unit.recover(model, ElementId(ei), &ue, &loads)
                }
            };
            // Finite displacements whose stresses or internal forces leave the range (a
            // stiff material in units where stresses are near 1e308): the model's units.
            if !recovered.is_finite() && ue.iter().all(|v| v.is_finite()) {
                return Err(FemError::Overflow {
                    element: Some(ElementId(ei)),
                    what: "a recovered stress or internal force".into(),
                });
            }
            match recovered {
                Recovered::Line(line) => lines.push(line),
                Recovered::Plane { result, at_nodes } => {
                    // the running mean of the elements' values at the node (a sum of values
                    // near the top of the range would leave it)
                    for (nd, s) in unit.nodes().iter().zip(&at_nodes) {
                        stress_cnt[nd.0] += 1;
                        let k = stress_cnt[nd.0] as f64;
                        for c in 0..4 {
                            let mean = &mut stress_mean[nd.0][c];
                            *mean += (s[c] - *mean) / k;
                        }
                    }
                    planes.push(result);
                }
            }
        }
        let mut spring_forces = Vec::with_capacity(model.springs.len());
        let mut ground = [0.0; 3];
        for (si, sp) in model.springs.iter().enumerate() {
            let formed;
            let (em, d) = match kept {
                Some(k) => (&k.springs[si].0, k.springs[si].1),
                None => {
                    formed = spring_matrix(sp);
                    (&formed, spring_direction(sp))
                }
            };
            let n = em.dofs.len();
            for a in 0..n {
                let fa = (0..n).map(|b| em.k[a * n + b] * u[em.dofs[b]]).sum::<f64>();
                r[em.dofs[a]] += fa;
                r_mag[em.dofs[a]] += fa.abs();
                if unloaded {
                    let terms = (0..n)
                        .map(|b| (em.k[a * n + b] * u[em.dofs[b]]).abs())
                        .sum::<f64>();
                    elastic_terms = elastic_terms.max(terms);
                }
            }
            spring_forces.push(spring_force(model, sp, d, &u, &mut ground));
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
                // pair carries a couple, which is part of the balance. On a segment the
                // reaction is shared by its nodes with the weights of the A point, so its
                // moment is that of the force at the A point.
                let pa = match pair.segment {
                    None => model.nodes[a.0],
                    Some((a2, xi)) => {
                        let (p1, p2) = (model.nodes[a.0], model.nodes[a2.0]);
                        [
                            (1.0 - xi) * p1[0] + xi * p2[0],
                            (1.0 - xi) * p1[1] + xi * p2[1],
                        ]
                    }
                };
                contact[0] -= fx;
                contact[1] -= fy;
                contact[2] -= moment(pa, fx, fy);
            }
        }
        let mut resultant = [0.0; 3];
        for c in 0..3 {
            resultant[c] = applied[c] + reac[c] + contact[c] + ground[c];
        }
        // Forces near the top of the range (1e308) times their lever arms leave it: the
        // model's numbers are too large for its units, which the user can change. (Only where
        // every force summed is finite: a non-finite force is not an overflow of the sums, and
        // the checks of the results after this say whose fault it is.)
        // The fifteen sums first: the scans of the forces summed only where one has left.
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        let sums = [applied, reac, contact, ground, resultant];
        if !sums.iter().all(|s| finite(s))
            && finite(f)
            && finite(&lambda)
            && finite(&sol.x_n)
            && finite(&sol.x_t)
        {
            return Err(FemError::Overflow {
                element: None,
                what: "the resultant of the forces on the structure (the sums of the forces and \
                       of their moments about the origin)"
                    .into(),
            });
        }
        // An unloaded state (no applied force, settlement or temperature, no link force: an
        // open pair standing at its gap at p = 0) has nothing to scale its residuals but the
        // round-off of the dislocations z_n − η, differences of terms |z_n| + |η|, times the
        // links' stiffness: every force it makes is that round-off. With any load, the loads
        // scale the check (a state whose loads the gaps' round-off swamps fails it). Summed
        // over the links: a link force sums the terms of every link it couples to.
        let mut dislocation_force = 0.0f64;
        for k in 0..2 * m {
            let terms = if k < m {
                sol.z_n[k].abs() + self.gap[k].abs()
            } else {
                sol.z_t[k - m].abs()
            };
            if terms > 0.0 {
                // Its couplings to translations only (force per length): a rotation's (6EI/L²,
                // a force per radian) times a length is a moment, counted as a force in the
                // model's length unit — a thousand times more in kN·mm than in N·m against the
                // same state (a reviewer's beams on 50–300 bearings: internal failures read as
                // the data's round-off in kN·mm only).
                let stiffness = self.asm.kiz[k]
                    .iter()
                    .filter(|&&(j, _)| map.free_label[j].1 != crate::error::DofLabel::Rz)
                    .fold(0.0f64, |a, &(_, v)| a.max(v.abs()));
                dislocation_force += terms * stiffness;
            }
        }
        // unloaded, with link forces no larger than the dislocations' round-off (8.5e-9 N at
        // the cylinder's pair touching at p = 0)
        let link_max = sol
            .x_n
            .iter()
            .chain(&sol.x_t)
            .fold(0.0f64, |a, v| a.max(v.abs()));
        // Nor but the round-off of the forces its displacements make term by term in the
        // elements and springs: a frame held only by its pairs, its gap shut by a free turn
        // under a load since taken off, stands turned by 1.3e-3 rad with no force anywhere;
        // its residuals (5e-11 N, of end-force terms of 5e6 N) read 1.0 against nothing.
        let roundoff_of = dislocation_force.max(elastic_terms);
        if unloaded && link_max <= 64.0 * f64::EPSILON * roundoff_of {
            scale = scale.max(roundoff_of);
        }
        let x_given: Vec<f64> = sol.x_n.iter().chain(&sol.x_t).copied().collect();
        let mismatch = x_of_z
            .iter()
            .zip(&x_given)
            .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()));
        let free_res = res_i.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let nodal_stress = (0..nn)
            .map(|i| (stress_cnt[i] > 0).then_some(stress_mean[i]))
            .collect();
        // moment scale: forces times the model's size (its extent)
        let size = kept.map_or_else(|| model_size(model), |k| k.size);
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
        let results = Results {
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
                dislocation_force,
            },
        };
        Ok((results, res_i))
    }
}

/// The largest relative out-of-balance ([`crate::Equilibrium::relative`]) of recovered results
/// that an analysis accepts; above it the recovery refines its displacements
/// (`Condensed::recover` and the others) before it returns them.
pub const EQUILIBRIUM_ACCEPT: f64 = 1e-6;
