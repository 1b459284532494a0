//! Typed errors of the finite-element crate.

use crate::model::{ElementId, NodeId};
use std::fmt;

/// A degree of freedom of a node, as named in error messages and reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DofLabel {
    /// Global x translation.
    Ux,
    /// Global y translation.
    Uy,
    /// Rotation (counter-clockwise positive).
    Rz,
}

impl DofLabel {
    /// The three DOFs of a node, in the order of the node's unknowns.
    pub const ALL: [DofLabel; 3] = [DofLabel::Ux, DofLabel::Uy, DofLabel::Rz];

    /// The DOF's name in messages, model files and result files: `ux`, `uy`, `rz`.
    pub fn as_str(self) -> &'static str {
        match self {
            DofLabel::Ux => "ux",
            DofLabel::Uy => "uy",
            DofLabel::Rz => "rz",
        }
    }
}

impl fmt::Display for DofLabel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One free degree of freedom of a mechanism: node, DOF and the (normalised) amplitude of the
/// mechanism's displacement there.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeDof {
    /// The node that moves.
    pub node: NodeId,
    /// Which of its DOFs.
    pub dof: DofLabel,
    /// Amplitude in the mechanism mode (largest = ±1).
    pub amplitude: f64,
}

/// Formats a list of free DOFs, at most 12 of them.
fn list_free(dofs: &[FreeDof]) -> String {
    let mut s: Vec<String> = dofs
        .iter()
        .take(12)
        .map(|d| format!("{} {}", d.node, d.dof))
        .collect();
    if dofs.len() > 12 {
        s.push(format!("… ({} in all)", dofs.len()));
    }
    s.join(", ")
}

fn gigabytes(bytes: Option<u64>) -> String {
    match bytes {
        Some(b) => format!("{:.1} GB", b as f64 / 1e9),
        None => "more bytes than can be counted".to_string(),
    }
}

fn machine_has(bytes: Option<u64>) -> String {
    match bytes {
        Some(b) => format!(", this machine has {:.1} GB", b as f64 / 1e9),
        None => String::new(),
    }
}

/// Everything that can go wrong while building, condensing or recovering a model.
///
/// Ids are the 0-based indices returned by the [`Model`](crate::Model) builder.
#[derive(Debug, Clone, thiserror::Error)]
pub enum FemError {
    /// An element, support, spring, load or contact pair refers to a node that does not exist.
    #[error("{what} refers to node {node}, which does not exist ({count} nodes in the model)")]
    MissingNode {
        /// Description of the referring item, e.g. `"contact pair 2"`.
        what: String,
        /// The missing node index.
        node: usize,
        /// Number of nodes in the model.
        count: usize,
    },
    /// A load refers to an element that does not exist or has the wrong type.
    #[error("load {load} refers to {element}: {reason}")]
    BadLoadTarget {
        /// Index of the load within its group.
        load: usize,
        /// The element.
        element: ElementId,
        /// What is wrong.
        reason: String,
    },
    /// An element uses the same node twice.
    #[error("{element} uses {node} more than once")]
    RepeatedNode {
        /// The element.
        element: ElementId,
        /// The repeated node.
        node: NodeId,
    },
    /// A frame or bar whose two nodes coincide.
    #[error("{element} has zero length (nodes {a} and {b} coincide)")]
    ZeroLength {
        /// The element.
        element: ElementId,
        /// First node.
        a: NodeId,
        /// Second node.
        b: NodeId,
    },
    /// A non-positive (or non-finite) property such as E, A, I or thickness.
    #[error("{element}: {}", self.detail().unwrap_or_default())]
    NonPositiveProperty {
        /// The element.
        element: ElementId,
        /// Name of the property.
        property: &'static str,
        /// The offending value.
        value: f64,
    },
    /// Poisson's ratio outside (−1, 0.5).
    #[error("{element}: {}", self.detail().unwrap_or_default())]
    PoissonOutOfRange {
        /// The element.
        element: ElementId,
        /// The offending value.
        nu: f64,
    },
    /// A plane element with non-positive Jacobian (wrong node order, concave or degenerate).
    #[error("{element}: {}", self.detail().unwrap_or_default())]
    DistortedElement {
        /// The element.
        element: ElementId,
        /// The smallest Jacobian determinant found.
        det_j: f64,
    },
    /// A spring with non-positive stiffness or a zero direction.
    #[error("spring {spring}: {}", self.detail().unwrap_or_default())]
    BadSpring {
        /// Spring index.
        spring: usize,
        /// What is wrong.
        reason: String,
    },
    /// A contact pair with a bad normal, gap or friction coefficient.
    #[error("contact pair {pair} ({name}): {}", self.detail().unwrap_or_default())]
    BadContactPair {
        /// Pair index.
        pair: usize,
        /// Pair name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// No node of a pair can carry the pair's link DOFs (both are supported, or already carry the
    /// links of other pairs).
    #[error("contact pair {pair} ({name}): {}", self.detail().unwrap_or_default())]
    LinkPlacement {
        /// Pair index.
        pair: usize,
        /// Pair name.
        name: String,
        /// Why.
        reason: String,
    },
    /// Supports on a node that are redundant or parallel.
    #[error("{node}: {}", self.detail().unwrap_or_default())]
    BadSupport {
        /// The node.
        node: NodeId,
        /// What is wrong.
        reason: String,
    },
    /// A prescribed displacement on a DOF that has no support.
    #[error(
        "load {load}: prescribed displacement on {node} {dof:?}, which is not supported there"
    )]
    SettlementWithoutSupport {
        /// Index of the load within its group.
        load: usize,
        /// The node.
        node: NodeId,
        /// The DOF as given.
        dof: crate::model::SupportDof,
    },
    /// A non-finite number in the input.
    #[error("{what}: value is not finite")]
    NotFinite {
        /// Where.
        what: String,
    },
    /// The bonded structure (contact pairs made rigid links) is a mechanism.
    #[error("the bonded structure (every contact pair a rigid link) is unstable: free DOFs {}{}", list_free(.free), .hint)]
    Unstable {
        /// DOFs that move in a mechanism mode found by inverse iteration.
        free: Vec<FreeDof>,
        /// Smallest scaled eigenvalue estimate of the bonded stiffness (≈ 0 for a mechanism).
        eigenvalue: f64,
        /// Extra hint (may be empty).
        hint: String,
    },
    /// The bonded structure is stable but too ill-conditioned for its displacements to be
    /// computed in double precision: the smallest eigenvalue of its Jacobi-scaled stiffness
    /// is so small that the round-off of the factorization, amplified by its inverse, could
    /// reach `estimated_error` of the answer. Its lowest mode deforms the elements, which a
    /// mechanism does not: a member divided into very many short elements does this, since
    /// the eigenvalue falls as the fourth power of the element length (below the accepted
    /// 1e-13 from about 2500 elements in a pinned–pinned beam).
    #[error(
        "the bonded structure is too ill-conditioned to be solved accurately in double \
             precision: the smallest eigenvalue of its scaled stiffness is {eigenvalue:.2e}, so \
             round-off could reach {estimated_error:.1e} of the displacements. Its lowest mode \
             deforms the elements by {element_force_ratio:.1e} of their stiffness, which a \
             mechanism (rigid motion of every element) would not do beyond round-off. This is a \
             limit of the program, not an error in the model: divide the members into fewer, \
             longer elements (a few thousand per member at most)"
    )]
    IllConditioned {
        /// Smallest scaled eigenvalue estimate of the bonded stiffness.
        eigenvalue: f64,
        /// Unit round-off over `eigenvalue`: the relative error the solve could have.
        estimated_error: f64,
        /// How far the least deforming low mode is from a rigid motion of every element:
        /// `Σ_e ‖k̃_e ũ_e‖ / Σ_e ‖k̃_e‖·‖ũ_e‖`, each element scaled by its own diagonal
        /// (round-off, below 1e-11, for a mechanism).
        element_force_ratio: f64,
    },
    /// A contact solution whose vectors have the wrong length or non-finite entries.
    #[error("contact solution: {0}")]
    BadSolution(String),
    /// A value computed from finite input overflows double precision (for instance `E·A/L`
    /// with E and A near 1e308): the numbers are out of range for the units used.
    #[error("{}{}", element.map_or(String::new(), |e| format!("{e}: ")), self.detail().unwrap_or_default())]
    Overflow {
        /// The element whose data overflow, if one.
        element: Option<ElementId>,
        /// What overflows.
        what: String,
    },
    /// A stiffness computed from finite input underflows double precision (for instance
    /// `E·I/L³` with L near 1e150): the element would stiffen nothing, and the structure would
    /// read as a mechanism; the numbers are out of range for the units used.
    #[error("{}{}", element.map_or(String::new(), |e| format!("{e}: ")), self.detail().unwrap_or_default())]
    Underflow {
        /// The element whose data underflow, if one.
        element: Option<ElementId>,
        /// What underflows.
        what: String,
    },
    /// The model needs more memory than the machine has (checked before allocating).
    #[error("the model is too large: {what} need {} of memory for the dense contact matrices{}; \
             reduce the number of contact pairs", gigabytes(*.needed), machine_has(*.available))]
    TooLarge {
        /// What is too large, e.g. `"100001 contact pairs"`.
        what: String,
        /// Bytes needed (`None`: more than can be counted).
        needed: Option<u64>,
        /// Bytes this machine has (`None`: unknown).
        available: Option<u64>,
    },
    /// Failure inside the sparse linear algebra that is not a mechanism.
    #[error("sparse linear algebra failed: {0}")]
    LinearAlgebra(String),
}

/// The item of the model a [`FemError`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Subject {
    /// An element.
    Element(ElementId),
    /// A contact pair, by its index.
    Pair(usize),
    /// A spring, by its index.
    Spring(usize),
    /// A node.
    Node(NodeId),
}

impl FemError {
    /// The item of the model the error is about, when it is about one: so that a reader can
    /// say where the file wrote it, and name it as the file does.
    pub fn subject(&self) -> Option<Subject> {
        match self {
            FemError::RepeatedNode { element, .. }
            | FemError::ZeroLength { element, .. }
            | FemError::NonPositiveProperty { element, .. }
            | FemError::PoissonOutOfRange { element, .. }
            | FemError::DistortedElement { element, .. }
            | FemError::Overflow {
                element: Some(element),
                ..
            }
            | FemError::Underflow {
                element: Some(element),
                ..
            } => Some(Subject::Element(*element)),
            FemError::BadContactPair { pair, .. } | FemError::LinkPlacement { pair, .. } => {
                Some(Subject::Pair(*pair))
            }
            FemError::BadSpring { spring, .. } => Some(Subject::Spring(*spring)),
            FemError::BadSupport { node, .. } => Some(Subject::Node(*node)),
            _ => None,
        }
    }

    /// What is wrong with the [`FemError::subject`], for the errors whose message is
    /// "subject: what is wrong" (the message reads `{subject}: {detail}`); `None` for the
    /// others.
    pub fn detail(&self) -> Option<String> {
        Some(match self {
            FemError::NonPositiveProperty {
                property, value, ..
            } => format!("{property} must be positive and finite, got {value}"),
            FemError::PoissonOutOfRange { nu, .. } => {
                format!("Poisson's ratio must lie in (-1, 0.5), got {nu}")
            }
            FemError::DistortedElement { det_j, .. } => format!(
                "non-positive Jacobian {det_j} (nodes must be counter-clockwise and the \
                 quadrilateral convex)"
            ),
            FemError::BadSpring { reason, .. } | FemError::BadContactPair { reason, .. } => {
                reason.clone()
            }
            FemError::LinkPlacement { reason, .. } => format!("cannot place its links: {reason}"),
            FemError::BadSupport { reason, .. } => format!("bad supports: {reason}"),
            FemError::Overflow { what, .. } => format!(
                "{what} overflows double precision: the values are too large (or the lengths \
                 too small) for the units used; choose other units"
            ),
            FemError::Underflow { what, .. } => format!(
                "{what} underflows double precision: the values are too small (or the lengths \
                 too large) for the units used; choose other units"
            ),
            _ => return None,
        })
    }

    /// `true` for failures that are the program's fault rather than the model's: the sparse
    /// linear algebra failing on a valid model ([`FemError::LinearAlgebra`]) and a contact
    /// solution handed to the recovery that does not fit the model
    /// ([`FemError::BadSolution`], which only the program produces), and a valid model that
    /// double precision cannot solve accurately ([`FemError::IllConditioned`]). Every other
    /// variant describes the model.
    pub fn is_internal(&self) -> bool {
        matches!(
            self,
            FemError::LinearAlgebra(_) | FemError::BadSolution(_) | FemError::IllConditioned { .. }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::{FemError, Subject};
    use crate::model::{ElementId, NodeId};

    /// Hand-written messages: each error about an item reads `{subject}: {detail}`, the subject
    /// typed, so that a reader can name the item its own way and keep the detail.
    #[test]
    fn subject_and_detail_make_the_message() {
        let cases = [
            (
                FemError::NonPositiveProperty {
                    element: ElementId(4),
                    property: "E",
                    value: -1.0,
                },
                Some(Subject::Element(ElementId(4))),
                "element 4: E must be positive and finite, got -1",
            ),
            (
                FemError::BadSupport {
                    node: NodeId(2),
                    reason: "two parallel translational restraints".into(),
                },
                Some(Subject::Node(NodeId(2))),
                "node 2: bad supports: two parallel translational restraints",
            ),
            (
                FemError::LinkPlacement {
                    pair: 1,
                    name: "tip".into(),
                    reason: "the contact pairs form a closed loop of links".into(),
                },
                Some(Subject::Pair(1)),
                "contact pair 1 (tip): cannot place its links: the contact pairs form a closed \
                 loop of links",
            ),
            (
                FemError::Overflow {
                    element: Some(ElementId(0)),
                    what: "its stiffness matrix".into(),
                },
                Some(Subject::Element(ElementId(0))),
                "element 0: its stiffness matrix overflows double precision: the values are too \
                 large (or the lengths too small) for the units used; choose other units",
            ),
        ];
        for (e, subject, text) in cases {
            assert_eq!(e.to_string(), text);
            assert_eq!(e.subject(), subject);
            let detail = e.detail().expect("a detail");
            assert!(text.ends_with(&format!(": {detail}")), "{text} / {detail}");
        }
        // Without an element, the overflow has no subject and its message is the detail.
        let e = FemError::Overflow {
            element: None,
            what: "the sum of the loads at a node".into(),
        };
        assert_eq!(e.subject(), None);
        assert_eq!(Some(e.to_string()), e.detail());
        // A zero length reads on from its subject without a colon: no detail.
        let e = FemError::ZeroLength {
            element: ElementId(1),
            a: NodeId(0),
            b: NodeId(1),
        };
        assert_eq!(e.subject(), Some(Subject::Element(ElementId(1))));
        assert_eq!(e.detail(), None);
        assert_eq!(
            e.to_string(),
            "element 1 has zero length (nodes node 0 and node 1 coincide)"
        );
    }
}
