//! Building a [`Model`] from the document tree of a model file: the builder's core (the
//! passes in order, the references between items, the numbering of the finite-element nodes,
//! the errors of `Model::validate` placed in the file, the names). Each section of the file
//! has its own module: `sections` (materials and sections), `geometry` (nodes and node sets),
//! `blocks`, `members`, `meshes` (Gmsh files), `elements`, `supports` (supports and springs),
//! `loads`, `contact`.
//! The meshing itself (block grids, member division, coincident nodes) is pure geometry in
//! [`unilateral_fem::mesh`].
//!
//! Geometry is created first as *proto nodes* (explicit nodes, block and member nodes); nodes
//! that the file asks to connect (`connect_to`, or a member ending on an existing node) are
//! merged, and only then are the finite-element nodes numbered. Blocks and members never share
//! nodes otherwise: separate bodies touch only through contact pairs.

mod blocks;
mod contact;
mod elements;
mod geometry;
mod loads;
mod members;
mod meshes;
mod sections;
mod supports;

use std::collections::{BTreeMap, HashMap};

use unilateral_fem::mesh::{
    coincidence_tolerance, divide_segment, BlockGrid, NodeMerge, PointIndex,
};
use unilateral_fem::{
    CaseId, ContactPairSpec, Element, ElementId, Endpoint, FemError, FrameSection, Load, LoadFrame,
    Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial, Releases, Spring, SpringKind,
    SupportDof,
};
use unilateral_fem::{Names, Subject};

use super::values::{
    choice, direction, id, number, opt_bool, opt_number, positive, refs, solve_settings,
    table_array, vec2, Ref,
};
use super::StructuralProblem;
use crate::error::{InputError, InputErrorKind, Pos};
use crate::reader::{Doc, Table};
use crate::tree::{did_you_mean, Value};

const TOP_KEYS: &[&str] = &[
    "title",
    "units",
    "description",
    "materials",
    "sections",
    "nodes",
    "elements",
    "blocks",
    "members",
    "meshes",
    "node_sets",
    "supports",
    "springs",
    "loads",
    "contact",
    "solve",
    "history",
];

/// The largest number of nodes the structured blocks and members of a model may create, each
/// and in all (it bounds the memory a short file can ask for).
const MAX_GENERATED: usize = 4_000_000;

/// What an element will be, before its nodes are numbered.
#[derive(Clone)]
enum Kind {
    Frame(FrameSection, Releases),
    Bar(FrameSection),
    Plane(PlaneMaterial, PlaneAnalysis, PlaneFormulation),
    Triangle(PlaneMaterial, PlaneAnalysis),
}

struct Pending {
    kind: Kind,
    nodes: Vec<usize>,
    name: String,
    pos: Option<Pos>,
    key: String,
}

/// Where an item of the model was written (for errors found by `Model::validate`).
#[derive(Clone)]
struct Origin {
    pos: Option<Pos>,
    key: String,
}

struct Section {
    section: FrameSection,
    has_inertia: bool,
}

struct Builder<'d> {
    doc: &'d Doc<'d>,
    protos: Vec<[f64; 2]>,
    proto_names: Vec<String>,
    node_names: HashMap<String, (usize, Option<Pos>)>,
    sets: HashMap<String, (Vec<usize>, Option<Pos>)>,
    set_order: Vec<String>,
    materials: HashMap<String, PlaneMaterial>,
    sections: HashMap<String, Section>,
    pending: Vec<Pending>,
    element_index: HashMap<String, usize>,
    element_sets: BTreeMap<String, Vec<usize>>,
    connects: Vec<(Vec<usize>, Vec<Ref>)>,
    /// The merging of the proto nodes that `connect_to` (or a member ending on a node) joins.
    merge: NodeMerge,
    blocks: Vec<(String, [f64; 4], Option<Pos>)>,
    /// Contact surfaces by name (the 1D groups of meshes), segments in order.
    surfaces: HashMap<String, meshes::Surface>,
    /// The named physical groups of meshes that hold no element of their dimension, by the
    /// set name they would have: why a reference to one finds nothing.
    empty_groups: HashMap<String, String>,
    /// How many pairs each `[[contact]]` entry made, with its name (`contact[K]` unnamed).
    contact_counts: Vec<(String, usize)>,
    /// Nodes created so far by blocks and members (bounded by [`MAX_GENERATED`] in all).
    generated: usize,
    // after numbering
    final_of: Vec<NodeId>,
    model: Model,
    elem_origin: Vec<Origin>,
    pair_origin: Vec<Origin>,
    spring_origin: Vec<Origin>,
    support_origin: HashMap<usize, Origin>,
    pair_names: Vec<String>,
    load_count: usize,
    fe_names: Vec<String>,
    supported: Vec<(NodeId, SupportDof)>,
}

pub(crate) fn read(doc: &Doc, top: &Table) -> Result<StructuralProblem, InputError> {
    top.check_keys(TOP_KEYS)?;
    let title = match top.get("title") {
        Some(n) => Some(doc.string(n, "title")?.to_string()),
        None => None,
    };
    let units = match top.get("units") {
        Some(n) => Some(doc.string(n, "units")?.to_string()),
        None => None,
    };
    for k in ["description"] {
        if let Some(n) = top.get(k) {
            doc.string(n, k)?;
        }
    }
    let mut b = Builder {
        doc,
        protos: Vec::new(),
        proto_names: Vec::new(),
        node_names: HashMap::new(),
        sets: HashMap::new(),
        set_order: Vec::new(),
        materials: HashMap::new(),
        sections: HashMap::new(),
        pending: Vec::new(),
        element_index: HashMap::new(),
        element_sets: BTreeMap::new(),
        connects: Vec::new(),
        merge: NodeMerge::default(),
        blocks: Vec::new(),
        surfaces: HashMap::new(),
        empty_groups: HashMap::new(),
        contact_counts: Vec::new(),
        generated: 0,
        final_of: Vec::new(),
        model: Model::new(),
        elem_origin: Vec::new(),
        pair_origin: Vec::new(),
        spring_origin: Vec::new(),
        support_origin: HashMap::new(),
        pair_names: Vec::new(),
        load_count: 0,
        fe_names: Vec::new(),
        supported: Vec::new(),
    };
    b.materials(top)?;
    b.sections(top)?;
    b.nodes(top)?;
    b.count_all_generated(top)?;
    b.blocks(top)?;
    b.members(top)?;
    b.meshes(top)?;
    b.explicit_elements(top)?;
    b.node_sets(top)?;
    if b.protos.is_empty() {
        return Err(doc.err(
            Some(Pos { line: 1, col: 1 }),
            "",
            InputErrorKind::MissingKey,
            "the model has no nodes: give [[nodes]], [[blocks]] or [[members]]",
        ));
    }
    b.number_nodes()?;
    b.supports(top)?;
    b.springs(top)?;
    let has_history = top.get("history").is_some();
    b.loads(top, has_history)?;
    b.contact(top)?;
    crate::history::refuse_path_keys(top)?;
    let history = crate::history::read_history(top, b.model.cases(), "loads")?;
    let settings = match top.table("solve")? {
        Some(t) => solve_settings(&t)?,
        None => Default::default(),
    };
    if b.model.pairs().is_empty() {
        return Err(doc.err(
            Some(Pos { line: 1, col: 1 }),
            "contact",
            InputErrorKind::MissingKey,
            "the model has no contact pairs: give at least one [[contact]] entry",
        ));
    }
    // Named first, so that what the model's checks say of a node names it as the file does.
    let names = b.names();
    b.model.set_names(names);
    b.validate()?;
    Ok(StructuralProblem {
        model: b.model,
        settings,
        title,
        units,
        history,
        contact_entries: b.contact_counts,
    })
}

impl<'d> Builder<'d> {
    fn err(&self, pos: Option<Pos>, key: &str, kind: InputErrorKind, msg: String) -> InputError {
        self.doc.err(pos, key, kind, msg)
    }

    /// Counts the nodes every block and member will create, before any is created, and
    /// refuses a total above [`MAX_GENERATED`] at the item that passes it. Items whose counts
    /// do not read are skipped here: the pass that builds them reports them.
    fn count_all_generated(&mut self, top: &Table) -> Result<(), InputError> {
        let count = |t: &Table, k: &str| {
            t.get(k)
                .and_then(|node| self.doc.positive_integer(node, &t.child(k)).ok())
        };
        let mut items: Vec<(usize, Option<Pos>, String)> = Vec::new();
        for t in table_array(top, "blocks")? {
            if let (Some(nx), Some(ny)) = (count(&t, "nx"), count(&t, "ny")) {
                let n = nx.saturating_add(1).saturating_mul(ny.saturating_add(1));
                items.push((n, t.get("nx").and_then(|x| x.pos).or(t.pos), t.child("nx")));
            }
        }
        for t in table_array(top, "members")? {
            let n = count(&t, "divisions").unwrap_or(1).saturating_add(1);
            items.push((
                n,
                t.get("divisions").and_then(|x| x.pos).or(t.pos),
                t.child("divisions"),
            ));
        }
        for (n, pos, key) in items {
            self.count_generated(n, pos, &key)?;
        }
        Ok(())
    }

    /// Adds `count` generated nodes to the model's total, refusing a total above
    /// [`MAX_GENERATED`].
    fn count_generated(
        &mut self,
        count: usize,
        pos: Option<Pos>,
        key: &str,
    ) -> Result<(), InputError> {
        let total = self.generated.saturating_add(count);
        if total > MAX_GENERATED {
            return Err(self.err(
                pos,
                key,
                InputErrorKind::Value,
                format!(
                    "the blocks and members up to this one would create {total} nodes, too many (at most \
                     {MAX_GENERATED} in all)"
                ),
            ));
        }
        self.generated = total;
        Ok(())
    }

    /// An `Invalid` error located at a name or reference read from the file.
    fn invalid_at(&self, r: &Ref, msg: String) -> InputError {
        self.err(r.pos, &r.key, InputErrorKind::Invalid, msg)
    }

    fn line_of(pos: Option<Pos>) -> String {
        pos.map(|p| format!(" (line {})", p.line))
            .unwrap_or_default()
    }

    fn unknown<'a>(
        &self,
        r: &Ref,
        what: &str,
        known: impl Iterator<Item = &'a String>,
    ) -> InputError {
        if let Some(why) = self.empty_groups.get(&r.name) {
            return self.invalid_at(r, why.clone());
        }
        let known: Vec<&str> = known.map(String::as_str).take(20_000).collect();
        let hint = match did_you_mean(&r.name, &known) {
            Some(k) => format!(" (did you mean `{k}`?)"),
            None => String::new(),
        };
        self.invalid_at(
            r,
            format!("unknown {what} `{}`{hint}", crate::tree::short(&r.name)),
        )
    }

    /// Proto nodes of a reference: a set, a node, or a block/member name (its nodes).
    fn resolve(&self, r: &Ref) -> Result<Vec<usize>, InputError> {
        if let Some((s, _)) = self.sets.get(&r.name) {
            return Ok(s.clone());
        }
        if let Some((p, _)) = self.node_names.get(&r.name) {
            return Ok(vec![*p]);
        }
        if let Some((s, _)) = self.sets.get(&format!("{}.nodes", r.name)) {
            return Ok(s.clone());
        }
        let known = self.sets.keys().chain(self.node_names.keys());
        Err(self.unknown(r, "node or node set", known))
    }

    fn one_proto(&self, r: &Ref) -> Result<usize, InputError> {
        let v = self.resolve(r)?;
        if v.len() != 1 {
            return Err(self.invalid_at(
                r,
                format!(
                    "`{}` is a set of {} nodes, but one node is needed here",
                    r.name,
                    v.len()
                ),
            ));
        }
        Ok(v[0])
    }

    /// Coincidence tolerance: 1e-9 of the model's extent.
    fn tolerance(&self) -> f64 {
        coincidence_tolerance(&self.protos)
    }

    /// Merges the nodes asked to connect, then numbers the finite-element nodes and creates
    /// the elements.
    fn number_nodes(&mut self) -> Result<(), InputError> {
        let tol = self.tolerance();
        let connects = std::mem::take(&mut self.connects);
        for (own, targets) in &connects {
            let mut target_nodes = Vec::new();
            for r in targets {
                target_nodes.extend(self.resolve(r)?);
            }
            let index = PointIndex::new(&self.protos, &target_nodes, tol);
            let mut any = false;
            for &p in own {
                for q in index.near(self.protos[p]) {
                    if q != p {
                        self.merge.union(p, q);
                        any = true;
                    }
                }
            }
            if !any {
                let r = &targets[0];
                return Err(self.invalid_at(
                    r,
                    "`connect_to` found no coincident nodes to merge with".to_string(),
                ));
            }
        }
        let mut final_of = vec![NodeId(0); self.protos.len()];
        for p in 0..self.protos.len() {
            let root = self.merge.find(p);
            if root == p {
                final_of[p] = self.model.add_node(self.protos[p][0], self.protos[p][1]);
                self.fe_names.push(self.proto_names[p].clone());
            } else {
                final_of[p] = final_of[root];
            }
        }
        self.final_of = final_of;
        for e in &self.pending {
            let n: Vec<NodeId> = e.nodes.iter().map(|&p| self.final_of[p]).collect();
            match &e.kind {
                Kind::Frame(s, r) => {
                    self.model.add_frame_with_releases(n[0], n[1], *s, *r);
                }
                Kind::Bar(s) => {
                    self.model.add_bar(n[0], n[1], *s);
                }
                Kind::Plane(m, a, f) => {
                    self.model.add_plane([n[0], n[1], n[2], n[3]], *m, *a, *f);
                }
                Kind::Triangle(m, a) => {
                    self.model.add_triangle([n[0], n[1], n[2]], *m, *a);
                }
            }
            self.elem_origin.push(Origin {
                pos: e.pos,
                key: e.key.clone(),
            });
        }
        Ok(())
    }

    /// Finite-element nodes of references, without repetitions, in order.
    fn fe_nodes(&self, rs: &[Ref]) -> Result<Vec<NodeId>, InputError> {
        let mut out = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for r in rs {
            for p in self.resolve(r)? {
                let n = self.final_of[p];
                if seen.insert(n) {
                    out.push(n);
                }
            }
        }
        Ok(out)
    }

    fn fe_nodes_of(&self, t: &Table, k: &str, what: &str) -> Result<Vec<NodeId>, InputError> {
        let node = t.require(k, what)?;
        let rs = refs(self.doc, node, &t.child(k))?;
        self.fe_nodes(&rs)
    }

    /// Elements of references (element ids, block or member names), in order.
    fn fe_elements(&self, t: &Table, k: &str) -> Result<Vec<ElementId>, InputError> {
        let node = t.require(k, "element ids, or names of blocks or members")?;
        let rs = refs(self.doc, node, &t.child(k))?;
        let mut out = Vec::new();
        for r in &rs {
            if let Some(v) = self.element_sets.get(&r.name) {
                out.extend(v.iter().map(|&e| ElementId(e)));
            } else if let Some(&e) = self.element_index.get(&r.name) {
                out.push(ElementId(e));
            } else {
                let known = self.element_sets.keys().chain(self.element_index.keys());
                return Err(self.unknown(r, "element, block or member", known));
            }
        }
        Ok(out)
    }

    fn has_frame(&self) -> Vec<bool> {
        let mut v = vec![false; self.model.nodes().len()];
        for e in self.model.elements() {
            if let Element::Frame { nodes, .. } = e {
                v[nodes[0].0] = true;
                v[nodes[1].0] = true;
            }
        }
        v
    }

    fn node_name(&self, n: NodeId) -> String {
        self.fe_names[n.0].clone()
    }

    /// Runs `Model::validate` and places its errors in the file, naming the item as the
    /// file does.
    fn validate(&self) -> Result<(), InputError> {
        let Err(e) = self.model.validate() else {
            return Ok(());
        };
        let (pos, key, who) = match e.subject() {
            Some(Subject::Element(id)) => {
                let o = &self.elem_origin[id.0];
                (
                    o.pos,
                    o.key.clone(),
                    format!("element `{}`", self.pending[id.0].name),
                )
            }
            Some(Subject::Pair(i)) => {
                let o = &self.pair_origin[i];
                (
                    o.pos,
                    o.key.clone(),
                    format!("contact pair `{}`", self.pair_names[i]),
                )
            }
            Some(Subject::Spring(spring)) => {
                let o = &self.spring_origin[spring];
                (o.pos, o.key.clone(), format!("spring {}", spring + 1))
            }
            Some(Subject::Node(node)) => {
                let o = self.support_origin.get(&node.0).cloned().unwrap_or(Origin {
                    pos: None,
                    key: "supports".into(),
                });
                (o.pos, o.key, format!("node `{}`", self.node_name(node)))
            }
            None => (None, String::new(), String::new()),
        };
        let msg = match (&e, e.detail()) {
            (FemError::ZeroLength { a, b, .. }, _) => format!(
                "{who} has zero length: its nodes `{}` and `{}` are at the same place",
                self.node_name(*a),
                self.node_name(*b)
            ),
            (FemError::RepeatedNode { node, .. }, _) => {
                format!("{who} uses node `{}` more than once", self.node_name(*node))
            }
            (_, Some(detail)) if !who.is_empty() => format!("{who}: {detail}"),
            _ => e.to_string(),
        };
        Err(self.err(pos, &key, InputErrorKind::Invalid, msg))
    }

    fn names(&self) -> Names {
        let mut node_ids = BTreeMap::new();
        for (name, (p, _)) in &self.node_names {
            node_ids.insert(name.clone(), self.final_of[*p]);
        }
        let mut node_sets = BTreeMap::new();
        for name in &self.set_order {
            let (v, _) = &self.sets[name];
            let mut seen = std::collections::HashSet::new();
            let nodes: Vec<NodeId> = v
                .iter()
                .map(|&p| self.final_of[p])
                .filter(|n| seen.insert(*n))
                .collect();
            node_sets.insert(name.clone(), nodes);
        }
        Names {
            nodes: self.fe_names.clone(),
            elements: self.pending.iter().map(|e| e.name.clone()).collect(),
            pairs: self.pair_names.clone(),
            node_sets,
            element_sets: self
                .element_sets
                .iter()
                .map(|(k, v)| (k.clone(), v.iter().map(|&e| ElementId(e)).collect()))
                .collect(),
            node_ids,
        }
    }
}
