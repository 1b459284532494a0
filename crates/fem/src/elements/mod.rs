//! Element kinds as units behind one interface.
//!
//! Every kind of [`Element`] is a unit in a file of its own — [`frame`] (Euler–Bernoulli
//! frames and pin-jointed bars, one unit with or without end rotations), [`quad`] (the 4-node plane elements Q4 and QM6) — that
//! implements [`ElementUnit`]: its DOFs, its property and geometry checks, its stiffness, the
//! equivalent nodal loads of element loads, and the recovery of its end forces or stresses.
//! [`unit`] is the one place that maps an [`Element`] to its unit: a new element kind is a
//! new file and one line there. Springs ([`spring`]) act between nodes or on the ground
//! rather than being elements of the mesh; [`dense`] holds the small dense solver the units
//! share.
//!
//! Physical DOF numbering: node `i` owns `3i` (ux), `3i+1` (uy), `3i+2` (rz).
//! Dense element matrices are row-major `Vec<f64>` of size `n × n`.

pub(crate) mod dense;
pub(crate) mod frame;
pub(crate) mod quad;
pub(crate) mod spring;
pub(crate) mod tri;

use crate::error::FemError;
use crate::model::{Element, ElementId, Load, Model, NodeId};
use crate::results::{LineResult, PlaneResult};

/// An element matrix in global physical DOFs.
#[derive(Debug)]
pub(crate) struct ElemMat {
    pub dofs: Vec<usize>,
    pub k: Vec<f64>,
}

/// What the recovery gives for one element.
pub(crate) enum Recovered {
    /// End forces and internal force diagrams of a line element.
    Line(LineResult),
    /// Stresses of a plane element, and its stresses extrapolated to its nodes (in the order
    /// of [`ElementUnit::nodes`]).
    Plane {
        result: PlaneResult,
        at_nodes: Vec<[f64; 4]>,
    },
}

impl Recovered {
    /// `true` when every recovered number is finite.
    pub fn is_finite(&self) -> bool {
        let fin = |v: &f64| v.is_finite();
        match self {
            Recovered::Line(l) => {
                l.end_forces.iter().all(fin)
                    && l.diagram
                        .iter()
                        .all(|d| [d.s, d.n, d.q, d.m].iter().all(fin))
            }
            Recovered::Plane { result, at_nodes } => {
                result.stress.iter().flatten().all(fin) && at_nodes.iter().flatten().all(fin)
            }
        }
    }
}

/// The behaviour of one kind of element.
pub(crate) trait ElementUnit {
    /// The element's nodes.
    fn nodes(&self) -> &[NodeId];

    /// The physical DOFs of the element matrix and load vectors, in their order.
    fn dofs(&self) -> Vec<usize>;

    /// The nodes whose rotation the element stiffens (its ends, for a frame without hinges).
    fn rotation_nodes(&self) -> Vec<NodeId> {
        Vec::new()
    }

    /// The checks of the element's properties and geometry (the node references are checked
    /// before).
    fn check(&self, model: &Model, id: ElementId) -> Result<(), FemError>;

    /// Why the element cannot carry `load`, if it cannot.
    fn refuses(&self, load: &Load) -> Option<String>;

    /// The stiffness in global physical DOFs ([`ElementUnit::dofs`] order).
    fn stiffness(&self, model: &Model) -> Vec<f64>;

    /// The equivalent nodal load of an element load, in global physical DOFs
    /// ([`ElementUnit::dofs`] order); `None` if the load is not an element load this element
    /// carries.
    fn equivalent_load(&self, model: &Model, load: &Load) -> Option<Vec<f64>>;

    /// End forces or stresses for the element displacements `ue` ([`ElementUnit::dofs`]
    /// order) under its element loads, each with its load factor.
    fn recover(
        &self,
        model: &Model,
        id: ElementId,
        ue: &[f64],
        loads: &[(f64, &Load)],
    ) -> Recovered;
}

/// The unit of an element: the one place that maps each kind of [`Element`] to its code. On
/// the stack (it derefs to the [`ElementUnit`]): a load path's frames ask for every element's
/// unit thousands of times.
pub(crate) fn unit(el: &Element) -> Unit<'_> {
    match el {
        Element::Frame {
            nodes,
            section,
            releases,
        } => Unit::Line(frame::Line {
            nodes,
            section,
            releases: Some(*releases),
        }),
        Element::Bar { nodes, section } => Unit::Line(frame::Line {
            nodes,
            section,
            releases: None,
        }),
        Element::Plane {
            nodes,
            material,
            analysis,
            formulation,
        } => Unit::Quad(quad::Quad {
            nodes,
            material,
            analysis: *analysis,
            formulation: *formulation,
        }),
        Element::Triangle {
            nodes,
            material,
            analysis,
        } => Unit::Tri(tri::Tri {
            nodes,
            material,
            analysis: *analysis,
        }),
    }
}

/// An element's unit of code ([`unit`]).
pub(crate) enum Unit<'a> {
    Line(frame::Line<'a>),
    Quad(quad::Quad<'a>),
    Tri(tri::Tri<'a>),
}

impl<'a> std::ops::Deref for Unit<'a> {
    type Target = dyn ElementUnit + 'a;

    fn deref(&self) -> &Self::Target {
        match self {
            Unit::Line(u) => u,
            Unit::Quad(u) => u,
            Unit::Tri(u) => u,
        }
    }
}

/// Global stiffness of an element.
pub(crate) fn element_stiffness(model: &Model, el: &Element) -> ElemMat {
    let u = unit(el);
    ElemMat {
        dofs: u.dofs(),
        k: u.stiffness(model),
    }
}

/// A positive, finite property of an element, or the error naming it.
pub(crate) fn positive(id: ElementId, property: &'static str, value: f64) -> Result<(), FemError> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(FemError::NonPositiveProperty {
            element: id,
            property,
            value,
        })
    }
}
