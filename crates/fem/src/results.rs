//! The public results of the recovery: link values handed to it, reactions, internal forces,
//! stresses, the equilibrium check.

use crate::condense::Condensed;
use crate::model::{ElementId, NodeId, SupportDof};

/// Contact load vector (CLV) of one load group: link forces of the bonded structure,
/// compression positive, one entry per pair.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactLoadVector {
    /// Normal link forces (compression positive).
    pub normal: Vec<f64>,
    /// Tangential link forces (positive along `+t` on node B).
    pub tangential: Vec<f64>,
}

/// The values of the contact links at load parameter `p` that the recovery imposes on the
/// structure: per pair, the link forces `x` and the mutual displacements `z` of a solution of
/// the contact problem (formulation.md §1). Not to be confused with the contact solver's
/// solution (the whole load path): this is one point of it, as the structure sees it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinkValues {
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

impl LinkValues {
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
    /// `N`, `Q`, `M` sampled at [`DIAGRAM_SAMPLES`] equal intervals along the element (a
    /// fixed array: a path's frames recover every element thousands of times).
    pub diagram: [DiagramPoint; DIAGRAM_SAMPLES],
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
    /// The size of the forces the links' dislocations make term by term: |z_n| + |η| and
    /// |z_t| times the link's largest stiffness, summed over the links (a link force sums the
    /// terms of every link it couples to: a block sliding 21.6 m on eight pairs carried the
    /// round-off of eight pairs' terms, 2.1 times what the largest alone allowed). Where they
    /// cancel (a gap closed by a rigid motion, metres of slip on a soft spring) their round-off,
    /// about 1e-16 of this, is in every force recovered; against loads smaller than that
    /// round-off allows, a state cannot be resolved in double precision.
    pub dislocation_force: f64,
}

/// `a / b`, 0 when `a = 0` (nothing to compare), infinite when only `b` is 0.
pub(crate) fn ratio(a: f64, b: f64) -> f64 {
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

/// Full results of the structure for the link values of a contact solution.
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
