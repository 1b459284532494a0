//! The structural model: nodes, elements, springs, supports, loads and contact pairs.

use crate::error::FemError;
use crate::names::Names;
use std::fmt;

/// Index of a node (0-based, in the order of [`Model::add_node`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeId(pub usize);

/// Index of an element (0-based, frames, bars and plane elements share one numbering).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ElementId(pub usize);

impl fmt::Display for NodeId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "node {}", self.0)
    }
}

impl fmt::Display for ElementId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "element {}", self.0)
    }
}

/// One end of a spring or contact pair: a node, or the rigid ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Endpoint {
    /// The rigid, fixed ground.
    Ground,
    /// A node of the model.
    Node(NodeId),
}

/// Cross-section and material of a frame (Euler–Bernoulli beam-column) or of a bar.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameSection {
    /// Young's modulus `E`.
    pub e: f64,
    /// Area `A`.
    pub area: f64,
    /// Second moment of area `I` (ignored by bars).
    pub inertia: f64,
    /// Section depth `h`, needed only by a temperature gradient.
    pub depth: f64,
    /// Coefficient of thermal expansion `α`.
    pub alpha: f64,
}

impl FrameSection {
    /// A section with `E`, `A`, `I`; no depth, no thermal expansion.
    pub fn new(e: f64, area: f64, inertia: f64) -> Self {
        Self {
            e,
            area,
            inertia,
            depth: 0.0,
            alpha: 0.0,
        }
    }
    /// Sets the depth `h` (for temperature gradients).
    pub fn with_depth(mut self, depth: f64) -> Self {
        self.depth = depth;
        self
    }
    /// Sets the coefficient of thermal expansion `α`.
    pub fn with_alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self
    }
}

/// Moment releases (hinges) at the ends of a frame element.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Releases {
    /// Hinge at the start node (zero end moment).
    pub start: bool,
    /// Hinge at the end node (zero end moment).
    pub end: bool,
}

/// Plane stress or plane strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneAnalysis {
    /// `σ_zz = 0` (thin plate loaded in its plane).
    PlaneStress,
    /// `ε_zz = 0` (long body, e.g. soil per metre run).
    PlaneStrain,
}

/// Formulation of a 4-node plane element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlaneFormulation {
    /// Bilinear isoparametric, 2×2 Gauss (locks in bending on coarse meshes).
    Q4,
    /// Bilinear plus the incompatible modes `1 − ξ²`, `1 − η²` (Taylor's QM6: condensed per
    /// element, passes the patch test on distorted meshes, does not lock in bending).
    QM6,
}

/// Material and thickness of a plane element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneMaterial {
    /// Young's modulus `E`.
    pub e: f64,
    /// Poisson's ratio `ν` in (−1, 0.5).
    pub nu: f64,
    /// Thickness `t` (1 for plane strain per unit run).
    pub thickness: f64,
    /// Coefficient of thermal expansion `α`.
    pub alpha: f64,
}

impl PlaneMaterial {
    /// Material with `E`, `ν`, thickness 1 and no thermal expansion.
    pub fn new(e: f64, nu: f64) -> Self {
        Self {
            e,
            nu,
            thickness: 1.0,
            alpha: 0.0,
        }
    }
    /// Sets the thickness.
    pub fn with_thickness(mut self, t: f64) -> Self {
        self.thickness = t;
        self
    }
    /// Sets the coefficient of thermal expansion `α`.
    pub fn with_alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self
    }
}

/// An element of the model.
#[derive(Debug, Clone, PartialEq)]
pub enum Element {
    /// Euler–Bernoulli frame element (3 DOF per node), optional end hinges.
    Frame {
        /// Start and end node.
        nodes: [NodeId; 2],
        /// Section.
        section: FrameSection,
        /// End releases.
        releases: Releases,
    },
    /// Pin-jointed bar (axial force only).
    Bar {
        /// Start and end node.
        nodes: [NodeId; 2],
        /// Section (`inertia` ignored).
        section: FrameSection,
    },
    /// 4-node plane element, nodes counter-clockwise.
    Plane {
        /// Corner nodes, counter-clockwise.
        nodes: [NodeId; 4],
        /// Material.
        material: PlaneMaterial,
        /// Plane stress or strain.
        analysis: PlaneAnalysis,
        /// Q4 or QM6.
        formulation: PlaneFormulation,
    },
    /// 3-node constant-strain triangle (either node order; [`Model::add_triangle`] stores
    /// them counter-clockwise).
    Triangle {
        /// Corner nodes.
        nodes: [NodeId; 3],
        /// Material.
        material: PlaneMaterial,
        /// Plane stress or strain.
        analysis: PlaneAnalysis,
    },
}

/// A linear spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpringKind {
    /// Axial spring acting along `direction` (any non-zero vector) on the relative
    /// displacement `u_b − u_a`.
    Translational {
        /// Direction of action.
        direction: [f64; 2],
        /// Stiffness (force per length).
        stiffness: f64,
    },
    /// Rotational spring on `θ_b − θ_a`.
    Rotational {
        /// Stiffness (moment per radian).
        stiffness: f64,
    },
}

/// A linear spring between a node `b` and the ground or another node `a`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    /// Ground or first node.
    pub a: Endpoint,
    /// Second node.
    pub b: NodeId,
    /// Kind and stiffness.
    pub kind: SpringKind,
}

/// A restrained degree of freedom of a node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupportDof {
    /// Global x translation.
    Ux,
    /// Global y translation.
    Uy,
    /// Rotation.
    Rz,
    /// Translation along the given direction (inclined roller: the direction is the roller's
    /// normal). The vector need not be unit.
    Along([f64; 2]),
}

impl SupportDof {
    /// The node DOF this support restrains, `None` for an inclined roller.
    pub fn label(&self) -> Option<crate::DofLabel> {
        match self {
            SupportDof::Ux => Some(crate::DofLabel::Ux),
            SupportDof::Uy => Some(crate::DofLabel::Uy),
            SupportDof::Rz => Some(crate::DofLabel::Rz),
            SupportDof::Along(_) => None,
        }
    }
}

/// The two load groups of the paper's method (formulation.md §2: `R_F = R_c + p·R_v`): the
/// load cases named `constant` and `variable` (see [`Model::add_case`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadGroup {
    /// Dead load, always present: the case `constant`.
    Constant,
    /// Multiplied by the load parameter `p`: the case `variable`.
    Variable,
}

impl LoadGroup {
    /// The name of the load case of this group: `"constant"` or `"variable"`.
    pub fn case_name(self) -> &'static str {
        match self {
            LoadGroup::Constant => "constant",
            LoadGroup::Variable => "variable",
        }
    }
}

/// A load case of a model (its index in [`Model::cases`]): every load belongs to one, and a
/// load history multiplies each case's loads by the case's factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CaseId(pub usize);

/// Reference frame of a distributed load on a frame or bar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoadFrame {
    /// Components along global x and y, per unit length of the element.
    Global,
    /// Components along the element axis (start → end) and its normal (axis rotated 90°
    /// counter-clockwise), per unit length.
    Local,
}

/// A load. Every load belongs to a load case ([`CaseId`]; the paper's [`LoadGroup`]s are the
/// cases `constant` and `variable`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Load {
    /// Force and moment at a node (global components; moment counter-clockwise positive).
    Nodal {
        /// The node.
        node: NodeId,
        /// Force along x.
        fx: f64,
        /// Force along y.
        fy: f64,
        /// Moment.
        m: f64,
    },
    /// Linearly varying distributed load on a frame or bar, intensity `start` at the start node
    /// and `end` at the end node (two components each, in `frame`).
    Distributed {
        /// The frame or bar.
        element: ElementId,
        /// Intensity at the start node.
        start: [f64; 2],
        /// Intensity at the end node.
        end: [f64; 2],
        /// Global or local components.
        frame: LoadFrame,
    },
    /// Body force (e.g. self-weight `[0, −γ]`): per unit volume on plane elements, per unit
    /// length on frames and bars; global components.
    BodyForce {
        /// The element.
        element: ElementId,
        /// Force density.
        force: [f64; 2],
    },
    /// Prescribed displacement (support settlement) of a supported DOF.
    Settlement {
        /// The node.
        node: NodeId,
        /// The supported DOF (must match a support exactly).
        dof: SupportDof,
        /// Displacement (along the support direction, or rotation).
        value: f64,
    },
    /// Temperature change of an element: uniform part `uniform`; on frames also the difference
    /// `gradient = T(+y_local face) − T(−y_local face)` across the depth `h`.
    Temperature {
        /// The element.
        element: ElementId,
        /// Uniform change (at the centroid).
        uniform: f64,
        /// Through-depth difference (frames only).
        gradient: f64,
    },
}

/// Specification of a contact pair.
///
/// `n` is the unit normal pointing **from `a` into `b`** (for a pair with the ground, from the
/// ground into the body node `b`); the tangent is `t = (n_y, −n_x)` (see `docs/fem.md`).
///
/// A node-to-segment pair ([`ContactPairSpec::on_segment`]) has for its A side the point
/// `(1 − ξ)·a1 + ξ·a2` of the segment from `a = a1` to `segment = (a2, ξ)`: its displacement
/// is `(1 − ξ)·u_a1 + ξ·u_a2`, and the link forces act on `a1` and `a2` with the same weights.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPairSpec {
    /// Ground or node A (for a node-to-segment pair, the segment's first node `a1`).
    pub a: Endpoint,
    /// For a node-to-segment pair, the segment's second node `a2` and the weight `ξ ∈ [0, 1]`
    /// of `a2` in the A point; `None` for a node-to-node or node-to-ground pair.
    pub segment: Option<(NodeId, f64)>,
    /// Node B.
    pub b: NodeId,
    /// Normal direction from A into B (any non-zero vector; normalised).
    pub normal: [f64; 2],
    /// Initial gap `η ≥ 0`.
    pub gap: f64,
    /// Friction coefficient `f ≥ 0`.
    pub friction: f64,
    /// Display name (default: 1-based pair number).
    pub name: Option<String>,
}

impl ContactPairSpec {
    /// A pair between the rigid ground and node `b`, `normal` pointing from the ground into `b`.
    pub fn to_ground(b: NodeId, normal: [f64; 2]) -> Self {
        Self {
            a: Endpoint::Ground,
            segment: None,
            b,
            normal,
            gap: 0.0,
            friction: 0.0,
            name: None,
        }
    }
    /// A pair between nodes `a` and `b`, `normal` pointing from `a` into `b`.
    pub fn between(a: NodeId, b: NodeId, normal: [f64; 2]) -> Self {
        Self {
            a: Endpoint::Node(a),
            segment: None,
            b,
            normal,
            gap: 0.0,
            friction: 0.0,
            name: None,
        }
    }
    /// A node-to-segment pair: node `b` against the point `(1 − xi)·a1 + xi·a2` of the segment
    /// `(a1, a2)`, `normal` pointing from the segment into `b`.
    pub fn on_segment(a1: NodeId, a2: NodeId, xi: f64, b: NodeId, normal: [f64; 2]) -> Self {
        Self {
            segment: Some((a2, xi)),
            ..Self::between(a1, b, normal)
        }
    }
    /// The nodes of the A side with their weights in the A point (empty for the ground; one
    /// node of weight 1 for a node-to-node pair; the two nodes of the segment, without a zero
    /// weight, for a node-to-segment pair).
    pub fn a_weights(&self) -> Vec<(NodeId, f64)> {
        match (self.a, self.segment) {
            (Endpoint::Ground, _) => Vec::new(),
            (Endpoint::Node(a), None) => vec![(a, 1.0)],
            (Endpoint::Node(a1), Some((a2, xi))) => [(a1, 1.0 - xi), (a2, xi)]
                .into_iter()
                .filter(|&(_, w)| w != 0.0)
                .collect(),
        }
    }
    /// Sets the friction coefficient.
    pub fn friction(mut self, f: f64) -> Self {
        self.friction = f;
        self
    }
    /// Sets the initial gap.
    pub fn gap(mut self, g: f64) -> Self {
        self.gap = g;
        self
    }
    /// Sets the name.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }
}

/// A linear elastic 2D structure with contact pairs.
///
/// ```
/// use unilateral_fem::{ContactPairSpec, FrameSection, Load, LoadGroup, Model};
/// // Example 1 of the paper: a two-span beam held only by three contact pairs.
/// let mut model = Model::new();
/// let n: Vec<_> = [0.0, 2.0, 3.0, 4.0].iter().map(|&x| model.add_node(x, 0.0)).collect();
/// let section = FrameSection::new(1.0, 2.0, 1.0);
/// for w in n.windows(2) {
///     model.add_frame(w[0], w[1], section);
/// }
/// for &i in &[n[0], n[1], n[3]] {
///     model.add_contact_pair(ContactPairSpec::to_ground(i, [0.0, 1.0]).friction(0.6));
/// }
/// model.add_load(LoadGroup::Variable, Load::Nodal { node: n[2], fx: 0.0, fy: -1.0, m: 0.0 });
/// let c = model.condense().unwrap();
/// assert!((c.variable.normal[1] - 0.6875).abs() < 1e-12);
/// assert!((c.rnn[(0, 0)] - 0.1875).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Default)]
pub struct Model {
    pub(crate) nodes: Vec<[f64; 2]>,
    pub(crate) elements: Vec<Element>,
    pub(crate) springs: Vec<Spring>,
    pub(crate) supports: Vec<(NodeId, SupportDof)>,
    /// The names of the load cases, in the order they were added.
    pub(crate) cases: Vec<String>,
    pub(crate) loads: Vec<(CaseId, Load)>,
    pub(crate) pairs: Vec<ContactPairSpec>,
    pub(crate) names: Names,
}

impl Model {
    /// An empty model.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a node at `(x, y)`.
    pub fn add_node(&mut self, x: f64, y: f64) -> NodeId {
        self.nodes.push([x, y]);
        NodeId(self.nodes.len() - 1)
    }

    /// Adds a rigidly connected frame element from `a` to `b`.
    pub fn add_frame(&mut self, a: NodeId, b: NodeId, section: FrameSection) -> ElementId {
        self.add_frame_with_releases(a, b, section, Releases::default())
    }

    /// Adds a frame element with end hinges.
    pub fn add_frame_with_releases(
        &mut self,
        a: NodeId,
        b: NodeId,
        section: FrameSection,
        releases: Releases,
    ) -> ElementId {
        self.push(Element::Frame {
            nodes: [a, b],
            section,
            releases,
        })
    }

    /// Adds a pin-jointed bar (truss member).
    pub fn add_bar(&mut self, a: NodeId, b: NodeId, section: FrameSection) -> ElementId {
        self.push(Element::Bar {
            nodes: [a, b],
            section,
        })
    }

    /// Adds a 4-node plane element (nodes counter-clockwise).
    pub fn add_plane(
        &mut self,
        nodes: [NodeId; 4],
        material: PlaneMaterial,
        analysis: PlaneAnalysis,
        formulation: PlaneFormulation,
    ) -> ElementId {
        self.push(Element::Plane {
            nodes,
            material,
            analysis,
            formulation,
        })
    }

    /// Adds a 3-node constant-strain triangle; nodes given clockwise are stored
    /// counter-clockwise (like a quadrilateral's), which does not change the element.
    pub fn add_triangle(
        &mut self,
        mut nodes: [NodeId; 3],
        material: PlaneMaterial,
        analysis: PlaneAnalysis,
    ) -> ElementId {
        let xy = nodes.map(|n| self.nodes.get(n.0).copied());
        if let [Some(a), Some(b), Some(c)] = xy {
            if crate::elements::tri::signed_area(&[a, b, c]) < 0.0 {
                nodes.swap(1, 2);
            }
        }
        self.push(Element::Triangle {
            nodes,
            material,
            analysis,
        })
    }

    /// Adds any element.
    pub fn push(&mut self, e: Element) -> ElementId {
        self.elements.push(e);
        ElementId(self.elements.len() - 1)
    }

    /// Adds a spring; returns its index.
    pub fn add_spring(&mut self, spring: Spring) -> usize {
        self.springs.push(spring);
        self.springs.len() - 1
    }

    /// Restrains one DOF of a node.
    pub fn add_support(&mut self, node: NodeId, dof: SupportDof) {
        self.supports.push((node, dof));
    }

    /// Clamps a node (ux, uy, rz).
    pub fn fix(&mut self, node: NodeId) {
        for d in [SupportDof::Ux, SupportDof::Uy, SupportDof::Rz] {
            self.add_support(node, d);
        }
    }

    /// Pins a node (ux, uy).
    pub fn pin(&mut self, node: NodeId) {
        self.add_support(node, SupportDof::Ux);
        self.add_support(node, SupportDof::Uy);
    }

    /// Inclined roller: restrains the translation along `normal`, frees the one across it.
    pub fn roller(&mut self, node: NodeId, normal: [f64; 2]) {
        self.add_support(node, SupportDof::Along(normal));
    }

    /// Adds a load to a group (the case `constant` or `variable`, added when it is not yet
    /// there); returns its index among all loads.
    pub fn add_load(&mut self, group: LoadGroup, load: Load) -> usize {
        let case = self.add_case(group.case_name());
        self.add_case_load(case, load)
    }

    /// The load case of this name, added (after the cases there are) when the model has none
    /// of that name yet.
    pub fn add_case(&mut self, name: impl Into<String>) -> CaseId {
        let name = name.into();
        match self.case(&name) {
            Some(id) => id,
            None => {
                self.cases.push(name);
                CaseId(self.cases.len() - 1)
            }
        }
    }

    /// The load case of this name, if the model has it.
    pub fn case(&self, name: &str) -> Option<CaseId> {
        self.cases.iter().position(|c| c == name).map(CaseId)
    }

    /// The names of the load cases, indexed by [`CaseId`].
    pub fn cases(&self) -> &[String] {
        &self.cases
    }

    /// Adds a load to a load case; returns its index among all loads.
    ///
    /// # Panics
    ///
    /// When `case` is not a case of this model (a [`CaseId`] of another model): a fault of
    /// the calling program, as an index out of bounds is.
    pub fn add_case_load(&mut self, case: CaseId, load: Load) -> usize {
        assert!(
            case.0 < self.cases.len(),
            "load case {} is not a case of this model ({} cases)",
            case.0,
            self.cases.len()
        );
        self.loads.push((case, load));
        self.loads.len() - 1
    }

    /// Every load with its case, in the order they were added.
    pub fn loads(&self) -> &[(CaseId, Load)] {
        &self.loads
    }

    /// Adds a contact pair; returns its index.
    pub fn add_contact_pair(&mut self, spec: ContactPairSpec) -> usize {
        self.pairs.push(spec);
        self.pairs.len() - 1
    }

    /// Node coordinates.
    pub fn nodes(&self) -> &[[f64; 2]] {
        &self.nodes
    }
    /// Elements.
    pub fn elements(&self) -> &[Element] {
        &self.elements
    }
    /// Which nodes an element turns: a frame's end without a hinge. Plane elements and bars
    /// turn no node, so a moment, a rotational spring or a prescribed rotation at a node no
    /// frame turns would act on nothing.
    pub fn rotating_nodes(&self) -> Vec<bool> {
        let mut turns = vec![false; self.nodes.len()];
        for e in &self.elements {
            for n in crate::elements::unit(e).rotation_nodes() {
                if let Some(t) = turns.get_mut(n.0) {
                    *t = true;
                }
            }
        }
        turns
    }
    /// Contact pairs.
    pub fn pairs(&self) -> &[ContactPairSpec] {
        &self.pairs
    }
    /// The names of the nodes, elements, pairs and sets (empty unless given).
    pub fn names(&self) -> &Names {
        &self.names
    }
    /// Gives the model the names of its items (a model file's names).
    pub fn set_names(&mut self, names: Names) {
        self.names = names;
    }

    fn check_node(&self, what: impl FnOnce() -> String, n: NodeId) -> Result<(), FemError> {
        if n.0 >= self.nodes.len() {
            return Err(FemError::MissingNode {
                what: what(),
                node: n.0,
                count: self.nodes.len(),
            });
        }
        Ok(())
    }

    /// Checks the model: node references, geometry, positive properties, Poisson's ratio,
    /// springs, contact pairs, load targets, supports and where each pair's links can be
    /// placed. Stability is checked by [`Model::condense`].
    pub fn validate(&self) -> Result<(), FemError> {
        for (i, p) in self.nodes.iter().enumerate() {
            if !p[0].is_finite() || !p[1].is_finite() {
                return Err(FemError::NotFinite {
                    what: format!("coordinates of node {i}"),
                });
            }
        }
        for (ei, e) in self.elements.iter().enumerate() {
            let id = ElementId(ei);
            let unit = crate::elements::unit(e);
            let nodes = unit.nodes();
            for &n in nodes {
                self.check_node(|| format!("element {ei}"), n)?;
            }
            for (k, &n) in nodes.iter().enumerate() {
                if nodes[..k].contains(&n) {
                    return Err(FemError::RepeatedNode {
                        element: id,
                        node: n,
                    });
                }
            }
            unit.check(self, id)?;
        }
        for (si, s) in self.springs.iter().enumerate() {
            self.check_node(|| format!("spring {si}"), s.b)?;
            if let Endpoint::Node(a) = s.a {
                self.check_node(|| format!("spring {si}"), a)?;
                if a == s.b {
                    return Err(FemError::BadSpring {
                        spring: si,
                        reason: "both ends on the same node".into(),
                    });
                }
            }
            let (k, ok_dir) = match s.kind {
                SpringKind::Translational {
                    direction,
                    stiffness,
                } => (stiffness, direction[0].hypot(direction[1]) > 0.0),
                SpringKind::Rotational { stiffness } => (stiffness, true),
            };
            if !(k > 0.0 && k.is_finite()) {
                return Err(FemError::BadSpring {
                    spring: si,
                    reason: format!("stiffness must be positive, got {k}"),
                });
            }
            if !ok_dir {
                return Err(FemError::BadSpring {
                    spring: si,
                    reason: "zero direction vector".into(),
                });
            }
        }
        for (n, d) in &self.supports {
            self.check_node(|| format!("support on node {}", n.0), *n)?;
            if let SupportDof::Along(v) = d {
                if !(v[0].hypot(v[1]) > 0.0) {
                    return Err(FemError::BadSupport {
                        node: *n,
                        reason: "inclined support with a zero direction".into(),
                    });
                }
            }
        }
        let mut same_points: std::collections::HashMap<(usize, usize), usize> =
            std::collections::HashMap::new();
        for (pi, p) in self.pairs.iter().enumerate() {
            let name = self.pair_name(pi);
            self.check_node(|| format!("contact pair {pi} ({name})"), p.b)?;
            if let Endpoint::Node(a) = p.a {
                self.check_node(|| format!("contact pair {pi} ({name})"), a)?;
                if a == p.b {
                    return Err(FemError::BadContactPair {
                        pair: pi,
                        name,
                        reason: "both sides are the same node".into(),
                    });
                }
            }
            let bad = |reason: String| FemError::BadContactPair {
                pair: pi,
                name: name.clone(),
                reason,
            };
            if let Some((a2, xi)) = p.segment {
                self.check_node(|| format!("contact pair {pi} ({name})"), a2)?;
                let Endpoint::Node(a1) = p.a else {
                    return Err(bad(
                        "a segment needs a node as its first end, not the ground".into(),
                    ));
                };
                if a2 == a1 || a2 == p.b {
                    return Err(bad(format!(
                        "the segment ({a1}, {a2}) repeats a node of the pair"
                    )));
                }
                if !(0.0..=1.0).contains(&xi) {
                    return Err(bad(format!(
                        "the weight of the segment's second node must be in [0, 1], got {xi}"
                    )));
                }
            }
            // Two pairs whose A side and B are the same (node to node in either order, or
            // the same node twice to the ground) would be two rigid links between the same
            // points in the bonded structure: redundant whatever their normals.
            let key = match (p.a, p.segment) {
                (Endpoint::Ground, _) => Some((usize::MAX, p.b.0)),
                (Endpoint::Node(a), None) => Some((a.0.min(p.b.0), a.0.max(p.b.0))),
                (Endpoint::Node(_), Some(_)) => None,
            };
            if let Some(key) = key {
                if let Some(first) = same_points.insert(key, pi) {
                    let what = match p.a {
                        Endpoint::Ground => format!("{} and the ground", p.b),
                        Endpoint::Node(a) => format!("{a} and {}", p.b),
                    };
                    return Err(bad(format!(
                        "it joins {what}, as pair {first} ({}) does: two pairs between the same \
                         points are redundant (one pair carries both the normal and the \
                         tangential link)",
                        self.pair_name(first)
                    )));
                }
            }
            let len = p.normal[0].hypot(p.normal[1]);
            if !(len > 0.0 && len.is_finite()) {
                return Err(bad("the normal is zero or not finite".into()));
            }
            if !(p.gap >= 0.0 && p.gap.is_finite()) {
                return Err(bad(format!("gap must be >= 0, got {}", p.gap)));
            }
            if !(p.friction >= 0.0 && p.friction.is_finite()) {
                return Err(bad(format!("friction must be >= 0, got {}", p.friction)));
            }
        }
        for (li, (_, l)) in self.loads.iter().enumerate() {
            let elem = |e: ElementId| match self.elements.get(e.0) {
                None => Err(FemError::BadLoadTarget {
                    load: li,
                    element: e,
                    reason: "no such element".into(),
                }),
                Some(el) => Ok(crate::elements::unit(el)),
            };
            let refused = |unit: &dyn crate::elements::ElementUnit, element: ElementId| match unit
                .refuses(l)
            {
                Some(reason) => Err(FemError::BadLoadTarget {
                    load: li,
                    element,
                    reason,
                }),
                None => Ok(()),
            };
            let finite = |v: &[f64]| {
                if v.iter().all(|x| x.is_finite()) {
                    Ok(())
                } else {
                    Err(FemError::NotFinite {
                        what: format!("load {li}"),
                    })
                }
            };
            match *l {
                Load::Nodal { node, fx, fy, m } => {
                    self.check_node(|| format!("load {li}"), node)?;
                    finite(&[fx, fy, m])?;
                }
                Load::Distributed {
                    element,
                    start,
                    end,
                    ..
                } => {
                    refused(&*elem(element)?, element)?;
                    finite(&[start[0], start[1], end[0], end[1]])?;
                }
                Load::BodyForce { element, force } => {
                    let unit = elem(element)?;
                    finite(&force)?;
                    refused(&*unit, element)?;
                }
                Load::Settlement { node, dof, value } => {
                    self.check_node(|| format!("load {li}"), node)?;
                    finite(&[value])?;
                    if !self
                        .supports
                        .iter()
                        .any(|(n, d)| *n == node && same_dof(*d, dof))
                    {
                        return Err(FemError::SettlementWithoutSupport {
                            load: li,
                            node,
                            dof,
                        });
                    }
                }
                Load::Temperature {
                    element,
                    uniform,
                    gradient,
                } => {
                    let unit = elem(element)?;
                    finite(&[uniform, gradient])?;
                    refused(&*unit, element)?;
                }
            }
        }
        // The supports and the placement of every pair's links (the numbering of the DOFs;
        // `O(n)`), so that a reader can place those errors at their item too.
        crate::dofs::build_dof_map(self)?;
        Ok(())
    }

    /// Name of pair `i` (its own, or the 1-based number).
    pub fn pair_name(&self, i: usize) -> String {
        self.pairs[i]
            .name
            .clone()
            .unwrap_or_else(|| (i + 1).to_string())
    }
}

/// Whether two support DOFs are the same (directions compared after normalisation, sign
/// included).
pub(crate) fn same_dof(a: SupportDof, b: SupportDof) -> bool {
    match (a, b) {
        (SupportDof::Along(u), SupportDof::Along(v)) => {
            let (lu, lv) = (u[0].hypot(u[1]), v[0].hypot(v[1]));
            lu > 0.0
                && lv > 0.0
                && (u[0] / lu - v[0] / lv).abs() < 1e-12
                && (u[1] / lu - v[1] / lv).abs() < 1e-12
        }
        _ => a == b,
    }
}
