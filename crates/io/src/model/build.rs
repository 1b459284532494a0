//! Building a [`Model`] from the document tree of a model file.
//!
//! Geometry is created first as *proto nodes* (explicit nodes, block and member nodes); nodes
//! that the file asks to connect (`connect_to`, or a member ending on an existing node) are
//! merged, and only then are the finite-element nodes numbered. Blocks and members never share
//! nodes otherwise: separate bodies touch only through contact pairs.

use std::collections::{BTreeMap, HashMap};

use unilateral_fem::{
    ContactPairSpec, Element, ElementId, Endpoint, FemError, FrameSection, Load, LoadFrame,
    LoadGroup, Model, NodeId, PlaneAnalysis, PlaneFormulation, PlaneMaterial, Releases, Spring,
    SpringKind, SupportDof,
};

use super::values::{
    choice, direction, id, number, opt_bool, opt_number, positive, refs, solve_settings,
    table_array, vec2, Ref,
};
use super::{ModelNames, StructuralProblem};
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
    "node_sets",
    "supports",
    "springs",
    "loads",
    "contact",
    "solve",
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
    parent: Vec<usize>,
    blocks: Vec<(String, [f64; 4], Option<Pos>)>,
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
    for k in ["units", "description"] {
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
        parent: Vec::new(),
        blocks: Vec::new(),
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
    b.loads(top)?;
    b.contact(top)?;
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
    b.validate()?;
    let names = b.names();
    Ok(StructuralProblem {
        model: b.model,
        settings,
        names,
        title,
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

    // ---------------------------------------------------------------- materials, sections

    fn materials(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "materials")? {
            t.check_keys(&["name", "E", "nu", "thickness", "alpha"])?;
            let name = id(
                self.doc,
                t.require("name", "the material's name")?,
                &t.child("name"),
            )?;
            let e = positive(&t, "E", "Young's modulus E")?;
            let nu = number(&t, "nu", "Poisson's ratio nu")?;
            if !(nu > -1.0 && nu < 0.5) {
                return Err(self.err(
                    t.get("nu").and_then(|n| n.pos),
                    &t.child("nu"),
                    InputErrorKind::Value,
                    format!("Poisson's ratio must lie in (-1, 0.5), got {nu}"),
                ));
            }
            let mut m = PlaneMaterial::new(e, nu);
            if t.get("thickness").is_some() {
                m = m.with_thickness(positive(&t, "thickness", "the thickness")?);
            }
            if let Some(a) = opt_number(&t, "alpha")? {
                m = m.with_alpha(a);
            }
            if self.materials.insert(name.name.clone(), m).is_some() {
                return Err(
                    self.invalid_at(&name, format!("duplicate material name `{}`", name.name))
                );
            }
        }
        Ok(())
    }

    fn sections(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "sections")? {
            t.check_keys(&["name", "E", "A", "I", "depth", "alpha"])?;
            let name = id(
                self.doc,
                t.require("name", "the section's name")?,
                &t.child("name"),
            )?;
            let e = positive(&t, "E", "Young's modulus E")?;
            let a = positive(&t, "A", "the area A")?;
            let has_inertia = t.get("I").is_some();
            let i = if has_inertia {
                positive(&t, "I", "the second moment of area I")?
            } else {
                0.0
            };
            let mut s = FrameSection::new(e, a, i);
            if t.get("depth").is_some() {
                s = s.with_depth(positive(&t, "depth", "the section depth")?);
            }
            if let Some(al) = opt_number(&t, "alpha")? {
                s = s.with_alpha(al);
            }
            let prev = self.sections.insert(
                name.name.clone(),
                Section {
                    section: s,
                    has_inertia,
                },
            );
            if prev.is_some() {
                return Err(
                    self.invalid_at(&name, format!("duplicate section name `{}`", name.name))
                );
            }
        }
        Ok(())
    }

    fn section(&self, t: &Table, frame: bool) -> Result<FrameSection, InputError> {
        let r = id(
            self.doc,
            t.require("section", "the name of a [[sections]] entry")?,
            &t.child("section"),
        )?;
        let Some(s) = self.sections.get(&r.name) else {
            return Err(self.unknown(&r, "section", self.sections.keys()));
        };
        if frame && !s.has_inertia {
            return Err(self.invalid_at(&r, format!(
                    "section `{}` has no moment of inertia I, which frame elements need (give I, or use bars)",
                    r.name
                ),
            ));
        }
        Ok(s.section)
    }

    fn material(&self, t: &Table) -> Result<PlaneMaterial, InputError> {
        let r = id(
            self.doc,
            t.require("material", "the name of a [[materials]] entry")?,
            &t.child("material"),
        )?;
        self.materials
            .get(&r.name)
            .copied()
            .ok_or_else(|| self.unknown(&r, "material", self.materials.keys()))
    }

    fn unknown<'a>(
        &self,
        r: &Ref,
        what: &str,
        known: impl Iterator<Item = &'a String>,
    ) -> InputError {
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

    fn plane_options(&self, t: &Table) -> Result<(PlaneAnalysis, PlaneFormulation), InputError> {
        let analysis = match choice(
            t,
            "analysis",
            &["plane_strain", "plane_stress"],
            None,
            "plane analysis",
        )? {
            "plane_strain" => PlaneAnalysis::PlaneStrain,
            _ => PlaneAnalysis::PlaneStress,
        };
        let formulation = match choice(
            t,
            "formulation",
            &["QM6", "Q4"],
            Some("QM6"),
            "plane element formulation",
        )? {
            "Q4" => PlaneFormulation::Q4,
            _ => PlaneFormulation::QM6,
        };
        Ok((analysis, formulation))
    }

    fn releases(&self, t: &Table) -> Result<Releases, InputError> {
        let mut r = Releases::default();
        if let Some(node) = t.get("releases") {
            let key = t.child("releases");
            let items: Vec<&crate::tree::Node> = match &node.value {
                Value::Array(items) => items.iter().collect(),
                _ => vec![node],
            };
            for (i, item) in items.into_iter().enumerate() {
                let k = format!("{key}[{}]", i + 1);
                match self.doc.string(item, &k)? {
                    "start" => r.start = true,
                    "end" => r.end = true,
                    other => {
                        return Err(self.err(
                            item.pos,
                            &k,
                            InputErrorKind::Value,
                            format!(
                                "unknown release \"{}\": use \"start\" and/or \"end\" (a hinge at that end)",
                                crate::tree::short(other)
                            ),
                        ))
                    }
                }
            }
        }
        Ok(r)
    }

    // ---------------------------------------------------------------- geometry

    fn new_proto(&mut self, xy: [f64; 2], name: String, pos: Option<Pos>) -> usize {
        let i = self.protos.len();
        self.protos.push(xy);
        self.proto_names.push(name.clone());
        self.parent.push(i);
        self.node_names.insert(name, (i, pos));
        i
    }

    fn check_new_name(&self, name: &str, pos: Option<Pos>, key: &str) -> Result<(), InputError> {
        if name == "ground" {
            return Err(self.err(
                pos,
                key,
                InputErrorKind::Invalid,
                "`ground` is reserved for the rigid ground of contact pairs and springs".into(),
            ));
        }
        if let Some((_, p)) = self.node_names.get(name) {
            return Err(self.err(
                pos,
                key,
                InputErrorKind::Invalid,
                format!(
                    "duplicate id `{name}`: a node of that name already exists{}",
                    Self::line_of(*p)
                ),
            ));
        }
        if let Some((_, p)) = self.sets.get(name) {
            return Err(self.err(
                pos,
                key,
                InputErrorKind::Invalid,
                format!(
                    "duplicate id `{name}`: a node set of that name already exists{}",
                    Self::line_of(*p)
                ),
            ));
        }
        Ok(())
    }

    fn add_set(
        &mut self,
        name: String,
        nodes: Vec<usize>,
        pos: Option<Pos>,
        key: &str,
    ) -> Result<(), InputError> {
        self.check_new_name(&name, pos, key)?;
        self.set_order.push(name.clone());
        self.sets.insert(name, (nodes, pos));
        Ok(())
    }

    fn nodes(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "nodes")? {
            t.check_keys(&["id", "x", "y"])?;
            let r = id(
                self.doc,
                t.require("id", "the node's id (a name or a number)")?,
                &t.child("id"),
            )?;
            let x = number(&t, "x", "the x coordinate")?;
            let y = number(&t, "y", "the y coordinate")?;
            self.check_new_name(&r.name, r.pos, &r.key)?;
            self.new_proto([x, y], r.name, r.pos);
        }
        Ok(())
    }

    fn object_name(&self, t: &Table, what: &str) -> Result<Ref, InputError> {
        let r = id(
            self.doc,
            t.require("name", &format!("the {what}'s name"))?,
            &t.child("name"),
        )?;
        if self.element_sets.contains_key(&r.name) || self.element_index.contains_key(&r.name) {
            return Err(self.invalid_at(
                &r,
                format!(
                    "duplicate name `{}`: a block, member or element of that name already exists",
                    r.name
                ),
            ));
        }
        Ok(r)
    }

    fn add_element(&mut self, p: Pending) -> Result<usize, InputError> {
        if self.element_index.contains_key(&p.name) {
            return Err(self.err(
                p.pos,
                &p.key,
                InputErrorKind::Invalid,
                format!("duplicate element id `{}`", p.name),
            ));
        }
        let i = self.pending.len();
        self.element_index.insert(p.name.clone(), i);
        self.pending.push(p);
        Ok(i)
    }

    fn blocks(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "blocks")? {
            t.check_keys(&[
                "name",
                "origin",
                "width",
                "height",
                "nx",
                "ny",
                "material",
                "analysis",
                "formulation",
                "connect_to",
            ])?;
            let name = self.object_name(&t, "block")?;
            let origin = vec2(
                self.doc,
                t.require("origin", "the lower-left corner [x, y]")?,
                &t.child("origin"),
            )?;
            let w = positive(&t, "width", "the width")?;
            let h = positive(&t, "height", "the height")?;
            let nx = self.doc.positive_integer(
                t.require("nx", "the number of divisions along x")?,
                &t.child("nx"),
            )?;
            let ny = self.doc.positive_integer(
                t.require("ny", "the number of divisions along y")?,
                &t.child("ny"),
            )?;
            if (nx + 1).saturating_mul(ny + 1) > MAX_GENERATED {
                return Err(self.err(
                    t.pos,
                    &t.child("nx"),
                    InputErrorKind::Value,
                    format!("{nx} × {ny} divisions is too many (at most {MAX_GENERATED} nodes per block)"),
                ));
            }
            let material = self.material(&t)?;
            let (analysis, formulation) = self.plane_options(&t)?;
            let rect = [origin[0], origin[1], origin[0] + w, origin[1] + h];
            for (other, r, p) in &self.blocks {
                let ox = rect[2].min(r[2]) - rect[0].max(r[0]);
                let oy = rect[3].min(r[3]) - rect[1].max(r[1]);
                let scale = w.min(h).min(r[2] - r[0]).min(r[3] - r[1]);
                if ox > 1e-9 * scale && oy > 1e-9 * scale {
                    return Err(self.invalid_at(&name, format!(
                            "block `{}` overlaps block `{other}`{}: separate bodies must not overlap (blocks may touch along an edge)",
                            name.name,
                            Self::line_of(*p)
                        ),
                    ));
                }
            }
            self.blocks.push((name.name.clone(), rect, name.pos));
            let n = &name.name;
            let mut grid = vec![0usize; (nx + 1) * (ny + 1)];
            let at = |i: usize, j: usize| j * (nx + 1) + i;
            for j in 0..=ny {
                for i in 0..=nx {
                    let xy = [
                        origin[0] + w * i as f64 / nx as f64,
                        origin[1] + h * j as f64 / ny as f64,
                    ];
                    let nm = format!("{n}.{i}.{j}");
                    self.check_new_name(&nm, name.pos, &name.key)?;
                    grid[at(i, j)] = self.new_proto(xy, nm, name.pos);
                }
            }
            let col = |i: usize| (0..=ny).map(|j| grid[at(i, j)]).collect::<Vec<_>>();
            let row = |j: usize| (0..=nx).map(|i| grid[at(i, j)]).collect::<Vec<_>>();
            let sets = [
                ("nodes", grid.clone()),
                ("left", col(0)),
                ("right", col(nx)),
                ("bottom", row(0)),
                ("top", row(ny)),
                ("bottom_left", vec![grid[at(0, 0)]]),
                ("bottom_right", vec![grid[at(nx, 0)]]),
                ("top_left", vec![grid[at(0, ny)]]),
                ("top_right", vec![grid[at(nx, ny)]]),
            ];
            for (s, nodes) in sets {
                self.add_set(format!("{n}.{s}"), nodes, name.pos, &name.key)?;
            }
            let mut elems = Vec::with_capacity(nx * ny);
            for j in 0..ny {
                for i in 0..nx {
                    let e = self.add_element(Pending {
                        kind: Kind::Plane(material, analysis, formulation),
                        nodes: vec![
                            grid[at(i, j)],
                            grid[at(i + 1, j)],
                            grid[at(i + 1, j + 1)],
                            grid[at(i, j + 1)],
                        ],
                        name: format!("{n}.{i}.{j}"),
                        pos: name.pos,
                        key: t.key.clone(),
                    })?;
                    elems.push(e);
                }
            }
            self.element_sets.insert(n.clone(), elems);
            if let Some(c) = t.get("connect_to") {
                let targets = refs(self.doc, c, &t.child("connect_to"))?;
                self.connects.push((grid, targets));
            }
        }
        Ok(())
    }

    /// A member end: coordinates, or an existing node (the member then ends on that node).
    fn member_end(&mut self, t: &Table, k: &str) -> Result<Result<[f64; 2], usize>, InputError> {
        let node = t.require(k, "a point [x, y] or the id of an existing node")?;
        if matches!(node.value, Value::Array(_)) {
            return Ok(Ok(vec2(self.doc, node, &t.child(k))?));
        }
        let r = id(self.doc, node, &t.child(k))?;
        Ok(Err(self.one_proto(&r)?))
    }

    fn members(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "members")? {
            t.check_keys(&[
                "name",
                "type",
                "start",
                "end",
                "divisions",
                "section",
                "releases",
                "connect_to",
            ])?;
            let name = self.object_name(&t, "member")?;
            let frame =
                choice(&t, "type", &["frame", "bar"], Some("frame"), "member type")? == "frame";
            let a = self.member_end(&t, "start")?;
            let b = self.member_end(&t, "end")?;
            let n = match t.get("divisions") {
                Some(node) => self.doc.positive_integer(node, &t.child("divisions"))?,
                None => 1,
            };
            if n > MAX_GENERATED {
                return Err(self.err(
                    t.get("divisions").and_then(|x| x.pos),
                    &t.child("divisions"),
                    InputErrorKind::Value,
                    format!("at most {MAX_GENERATED} divisions"),
                ));
            }
            let section = self.section(&t, frame)?;
            let releases = self.releases(&t)?;
            if !frame && (releases.start || releases.end) {
                return Err(self.err(
                    t.get("releases").and_then(|x| x.pos),
                    &t.child("releases"),
                    InputErrorKind::Invalid,
                    "bars carry no moment: releases apply to frames only".into(),
                ));
            }
            let pa = match a {
                Ok(xy) => xy,
                Err(p) => self.protos[p],
            };
            let pb = match b {
                Ok(xy) => xy,
                Err(p) => self.protos[p],
            };
            let nm = name.name.clone();
            let mut nodes = Vec::with_capacity(n + 1);
            for k in 0..=n {
                let node_name = format!("{nm}.{k}");
                self.check_new_name(&node_name, name.pos, &name.key)?;
                let existing = match (k, a, b) {
                    (0, Err(p), _) => Some(p),
                    (k, _, Err(p)) if k == n => Some(p),
                    _ => None,
                };
                let p = match existing {
                    Some(p) => {
                        self.node_names.insert(node_name, (p, name.pos));
                        p
                    }
                    None => {
                        let s = k as f64 / n as f64;
                        let xy = [pa[0] + s * (pb[0] - pa[0]), pa[1] + s * (pb[1] - pa[1])];
                        self.new_proto(xy, node_name, name.pos)
                    }
                };
                nodes.push(p);
            }
            let mut elems = Vec::with_capacity(n);
            for k in 0..n {
                let kind = if frame {
                    Kind::Frame(
                        section,
                        Releases {
                            start: releases.start && k == 0,
                            end: releases.end && k == n - 1,
                        },
                    )
                } else {
                    Kind::Bar(section)
                };
                elems.push(self.add_element(Pending {
                    kind,
                    nodes: vec![nodes[k], nodes[k + 1]],
                    name: format!("{nm}.{}", k + 1),
                    pos: name.pos,
                    key: t.key.clone(),
                })?);
            }
            self.element_sets.insert(nm.clone(), elems);
            self.add_set(format!("{nm}.nodes"), nodes.clone(), name.pos, &name.key)?;
            self.add_set(format!("{nm}.start"), vec![nodes[0]], name.pos, &name.key)?;
            self.add_set(format!("{nm}.end"), vec![nodes[n]], name.pos, &name.key)?;
            if let Some(c) = t.get("connect_to") {
                let targets = refs(self.doc, c, &t.child("connect_to"))?;
                self.connects.push((nodes, targets));
            }
        }
        Ok(())
    }

    fn explicit_elements(&mut self, top: &Table) -> Result<(), InputError> {
        for (idx, t) in table_array(top, "elements")?.into_iter().enumerate() {
            t.check_keys(&[
                "id",
                "type",
                "nodes",
                "section",
                "material",
                "analysis",
                "formulation",
                "releases",
            ])?;
            let name = match t.get("id") {
                Some(n) => id(self.doc, n, &t.child("id"))?,
                None => Ref {
                    name: (idx + 1).to_string(),
                    pos: t.pos,
                    key: t.key.clone(),
                },
            };
            if self.element_sets.contains_key(&name.name) {
                return Err(self.invalid_at(
                    &name,
                    format!(
                        "duplicate id `{}`: a block or member of that name already exists",
                        name.name
                    ),
                ));
            }
            let ty = choice(&t, "type", &["frame", "bar", "plane"], None, "element type")?;
            let count = if ty == "plane" { 4 } else { 2 };
            let nodes_node = t.require("nodes", "the element's node ids")?;
            let rs = refs(self.doc, nodes_node, &t.child("nodes"))?;
            if rs.len() != count {
                return Err(self.err(
                    nodes_node.pos,
                    &t.child("nodes"),
                    InputErrorKind::Size,
                    format!(
                        "a {ty} element has {count} nodes{}, found {}",
                        if ty == "plane" {
                            " (counter-clockwise)"
                        } else {
                            ""
                        },
                        rs.len()
                    ),
                ));
            }
            let nodes = rs
                .iter()
                .map(|r| self.one_proto(r))
                .collect::<Result<Vec<_>, _>>()?;
            let forbid = |k: &str, why: &str| -> Result<(), InputError> {
                match t.get(k) {
                    Some(n) => Err(self.err(
                        n.pos,
                        &t.child(k),
                        InputErrorKind::Invalid,
                        format!("`{k}` does not apply to {ty} elements ({why})"),
                    )),
                    None => Ok(()),
                }
            };
            let kind = match ty {
                "plane" => {
                    forbid("section", "plane elements take a `material`")?;
                    forbid("releases", "plane elements have no end moments")?;
                    let m = self.material(&t)?;
                    let (a, f) = self.plane_options(&t)?;
                    Kind::Plane(m, a, f)
                }
                _ => {
                    for k in ["material", "analysis", "formulation"] {
                        forbid(k, "frames and bars take a `section`")?;
                    }
                    let s = self.section(&t, ty == "frame")?;
                    if ty == "frame" {
                        Kind::Frame(s, self.releases(&t)?)
                    } else {
                        forbid("releases", "bars carry no moment")?;
                        Kind::Bar(s)
                    }
                }
            };
            self.add_element(Pending {
                kind,
                nodes,
                name: name.name,
                pos: name.pos,
                key: t.key.clone(),
            })?;
        }
        Ok(())
    }

    fn node_sets(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "node_sets")? {
            t.check_keys(&["name", "nodes", "box", "within"])?;
            let name = id(
                self.doc,
                t.require("name", "the set's name")?,
                &t.child("name"),
            )?;
            let mut nodes: Vec<usize> = Vec::new();
            if let Some(n) = t.get("nodes") {
                let rs = refs(self.doc, n, &t.child("nodes"))?;
                for r in &rs {
                    nodes.extend(self.resolve(r)?);
                }
            }
            if let Some(n) = t.get("box") {
                let key = t.child("box");
                let Value::Array(corners) = &n.value else {
                    return Err(self.err(
                        n.pos,
                        &key,
                        InputErrorKind::WrongType,
                        format!(
                            "expected two corners [[xmin, ymin], [xmax, ymax]], found {}",
                            self.doc.describe(n)
                        ),
                    ));
                };
                if corners.len() != 2 {
                    return Err(self.err(
                        n.pos,
                        &key,
                        InputErrorKind::Size,
                        "expected two corners [[xmin, ymin], [xmax, ymax]]".into(),
                    ));
                }
                let lo = vec2(self.doc, &corners[0], &format!("{key}[1]"))?;
                let hi = vec2(self.doc, &corners[1], &format!("{key}[2]"))?;
                let tol = self.tolerance();
                let candidates: Vec<usize> = match t.get("within") {
                    Some(w) => {
                        let mut c = Vec::new();
                        for r in refs(self.doc, w, &t.child("within"))? {
                            c.extend(self.resolve(&r)?);
                        }
                        c
                    }
                    None => (0..self.protos.len()).collect(),
                };
                for p in candidates {
                    let [x, y] = self.protos[p];
                    if x >= lo[0] - tol && x <= hi[0] + tol && y >= lo[1] - tol && y <= hi[1] + tol
                    {
                        nodes.push(p);
                    }
                }
            } else if let Some(w) = t.get("within") {
                return Err(self.err(
                    w.pos,
                    &t.child("within"),
                    InputErrorKind::Invalid,
                    "`within` restricts a `box`: give `box` too".into(),
                ));
            }
            if t.get("nodes").is_none() && t.get("box").is_none() {
                return Err(self.err(
                    t.pos,
                    &t.key,
                    InputErrorKind::MissingKey,
                    format!(
                        "{} needs `nodes` (a list of ids or sets) and/or `box`",
                        t.name()
                    ),
                ));
            }
            let mut seen = std::collections::HashSet::new();
            nodes.retain(|p| seen.insert(*p));
            if nodes.is_empty() {
                return Err(self.err(
                    t.get("box").and_then(|b| b.pos).or(t.pos),
                    &t.child("box"),
                    InputErrorKind::Invalid,
                    format!(
                        "the node set `{}` is empty: no node lies in the box",
                        name.name
                    ),
                ));
            }
            self.add_set(name.name, nodes, name.pos, &name.key)?;
        }
        Ok(())
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
        let mut ext = 0.0f64;
        for p in &self.protos {
            ext = ext.max(p[0].abs()).max(p[1].abs());
        }
        1e-9 * ext.max(1e-300)
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
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
                        let (a, b) = (self.find(p), self.find(q));
                        if a != b {
                            self.parent[a.max(b)] = a.min(b);
                        }
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
            let root = self.find(p);
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

    // ---------------------------------------------------------------- supports, springs

    fn supports(&mut self, top: &Table) -> Result<(), InputError> {
        let has_frame = self.has_frame();
        let mut per_node: BTreeMap<usize, Vec<SupportDof>> = BTreeMap::new();
        for t in table_array(top, "supports")? {
            t.check_keys(&["nodes", "fixed", "pinned", "ux", "uy", "rz", "roller"])?;
            let nodes = self.fe_nodes_of(&t, "nodes", "the supported nodes or node sets")?;
            let fixed = opt_bool(&t, "fixed")?;
            let pinned = opt_bool(&t, "pinned")?;
            let ux = opt_bool(&t, "ux")? || fixed || pinned;
            let uy = opt_bool(&t, "uy")? || fixed || pinned;
            let rz_given = opt_bool(&t, "rz")?;
            let roller = match t.get("roller") {
                Some(n) => Some(direction(self.doc, n, &t.child("roller"))?),
                None => None,
            };
            if !(ux || uy || rz_given || fixed || roller.is_some()) {
                return Err(self.err(
                    t.pos,
                    &t.key,
                    InputErrorKind::MissingKey,
                    format!(
                        "{} restrains nothing: give fixed, pinned, ux, uy, rz = true or roller = [nx, ny]",
                        t.name()
                    ),
                ));
            }
            for n in nodes {
                let dofs = per_node.entry(n.0).or_default();
                let mut add = |d: SupportDof| {
                    if !dofs.contains(&d) {
                        dofs.push(d);
                    }
                };
                if ux {
                    add(SupportDof::Ux);
                }
                if uy {
                    add(SupportDof::Uy);
                }
                if rz_given || (fixed && has_frame[n.0]) {
                    add(SupportDof::Rz);
                }
                if let Some(r) = roller {
                    add(SupportDof::Along(r));
                }
                self.support_origin.entry(n.0).or_insert(Origin {
                    pos: t.pos,
                    key: t.key.clone(),
                });
            }
        }
        for (n, dofs) in per_node {
            for d in dofs {
                self.model.add_support(NodeId(n), d);
                self.supported.push((NodeId(n), d));
            }
        }
        Ok(())
    }

    fn springs(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "springs")? {
            t.check_keys(&["nodes", "to", "direction", "rotational", "stiffness"])?;
            let nodes = self.fe_nodes_of(&t, "nodes", "the node(s) the spring acts on")?;
            let a = match t.get("to") {
                None => Endpoint::Ground,
                Some(n) => {
                    let r = id(self.doc, n, &t.child("to"))?;
                    if r.name == "ground" {
                        Endpoint::Ground
                    } else {
                        Endpoint::Node(self.final_of[self.one_proto(&r)?])
                    }
                }
            };
            let k = positive(&t, "stiffness", "the spring stiffness")?;
            let rotational = opt_bool(&t, "rotational")?;
            let kind = match (t.get("direction"), rotational) {
                (Some(d), false) => SpringKind::Translational {
                    direction: direction(self.doc, d, &t.child("direction"))?,
                    stiffness: k,
                },
                (None, true) => SpringKind::Rotational { stiffness: k },
                _ => {
                    return Err(self.err(t.pos, &t.key, InputErrorKind::Invalid, format!(
                            "{} needs either `direction = [dx, dy]` (a translational spring) or `rotational = true`",
                            t.name()
                        ),
                    ))
                }
            };
            for b in nodes {
                self.model.add_spring(Spring { a, b, kind });
                self.spring_origin.push(Origin {
                    pos: t.pos,
                    key: t.key.clone(),
                });
            }
        }
        Ok(())
    }

    // ---------------------------------------------------------------- loads

    fn loads(&mut self, top: &Table) -> Result<(), InputError> {
        let Some(loads) = top.table("loads")? else {
            return Err(self.err(
                Some(Pos { line: 1, col: 1 }),
                "loads.variable",
                InputErrorKind::MissingKey,
                "the model has no variable load ([loads.variable]): it is the load multiplied by the parameter p".into(),
            ));
        };
        loads.check_keys(&["constant", "variable"])?;
        let mut any_variable = false;
        for (k, group) in [
            ("constant", LoadGroup::Constant),
            ("variable", LoadGroup::Variable),
        ] {
            let Some(g) = loads.table(k)? else { continue };
            g.check_keys(&["nodal", "distributed", "body", "settlement", "temperature"])?;
            let before = self.model_load_count();
            for t in table_array(&g, "nodal")? {
                t.check_keys(&["nodes", "fx", "fy", "m"])?;
                let nodes = self.fe_nodes_of(&t, "nodes", "the loaded nodes or node sets")?;
                let fx = opt_number(&t, "fx")?.unwrap_or(0.0);
                let fy = opt_number(&t, "fy")?.unwrap_or(0.0);
                let m = opt_number(&t, "m")?.unwrap_or(0.0);
                for node in nodes {
                    self.push_load(group, Load::Nodal { node, fx, fy, m });
                }
            }
            for t in table_array(&g, "distributed")? {
                self.distributed(&t, group)?;
            }
            for t in table_array(&g, "body")? {
                t.check_keys(&["elements", "force"])?;
                let elems = self.fe_elements(&t, "elements")?;
                let force = vec2(
                    self.doc,
                    t.require(
                        "force",
                        "the force per unit volume (plane) or length (frames) [bx, by]",
                    )?,
                    &t.child("force"),
                )?;
                for element in elems {
                    self.push_load(group, Load::BodyForce { element, force });
                }
            }
            for t in table_array(&g, "settlement")? {
                self.settlement(&t, group)?;
            }
            for t in table_array(&g, "temperature")? {
                t.check_keys(&["elements", "uniform", "gradient"])?;
                let elems = self.fe_elements(&t, "elements")?;
                let uniform = opt_number(&t, "uniform")?.unwrap_or(0.0);
                let gradient = opt_number(&t, "gradient")?.unwrap_or(0.0);
                for element in elems {
                    if gradient != 0.0 {
                        match self.model.elements()[element.0] {
                            Element::Frame { section, .. } if section.depth > 0.0 => {}
                            _ => {
                                return Err(self.err(
                                    t.get("gradient").and_then(|n| n.pos),
                                    &t.child("gradient"),
                                    InputErrorKind::Invalid,
                                    format!(
                                        "a temperature gradient needs frame elements whose section has a `depth`; element `{}` has none",
                                        self.pending[element.0].name
                                    ),
                                ))
                            }
                        }
                    }
                    self.push_load(
                        group,
                        Load::Temperature {
                            element,
                            uniform,
                            gradient,
                        },
                    );
                }
            }
            if group == LoadGroup::Variable && self.model_load_count() > before {
                any_variable = true;
            }
        }
        if !any_variable {
            return Err(self.err(
                loads.pos,
                "loads.variable",
                InputErrorKind::MissingKey,
                "the model has no variable load ([loads.variable]): it is the load multiplied by the parameter p".into(),
            ));
        }
        Ok(())
    }

    fn model_load_count(&self) -> usize {
        self.load_count
    }

    fn push_load(&mut self, group: LoadGroup, load: Load) {
        self.model.add_load(group, load);
        self.load_count += 1;
    }
}

/// Finds points of a list near a given point (a uniform grid of cells of the tolerance's size).
struct PointIndex {
    cells: HashMap<(i64, i64), Vec<usize>>,
    points: Vec<[f64; 2]>,
    tol: f64,
}

impl PointIndex {
    fn new(all: &[[f64; 2]], subset: &[usize], tol: f64) -> Self {
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        let cell = 4.0 * tol;
        for &i in subset {
            let p = all[i];
            cells
                .entry(((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64))
                .or_default()
                .push(i);
        }
        Self {
            cells,
            points: all.to_vec(),
            tol,
        }
    }

    fn near(&self, p: [f64; 2]) -> Vec<usize> {
        let cell = 4.0 * self.tol;
        let (cx, cy) = ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64);
        let mut out = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(v) = self.cells.get(&(cx + dx, cy + dy)) {
                    for &i in v {
                        let q = self.points[i];
                        if (q[0] - p[0]).abs() <= self.tol && (q[1] - p[1]).abs() <= self.tol {
                            out.push(i);
                        }
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}

impl Builder<'_> {
    fn distributed(&mut self, t: &Table, group: LoadGroup) -> Result<(), InputError> {
        t.check_keys(&["elements", "q", "start", "end", "frame"])?;
        let elems = self.fe_elements(t, "elements")?;
        let frame = match choice(
            t,
            "frame",
            &["global", "local"],
            Some("global"),
            "load frame",
        )? {
            "local" => LoadFrame::Local,
            _ => LoadFrame::Global,
        };
        let (qa, qb) = match (t.get("q"), t.get("start"), t.get("end")) {
            (Some(q), None, None) => {
                let q = vec2(self.doc, q, &t.child("q"))?;
                (q, q)
            }
            (None, Some(a), Some(b)) => (
                vec2(self.doc, a, &t.child("start"))?,
                vec2(self.doc, b, &t.child("end"))?,
            ),
            _ => {
                return Err(self.err(t.pos, &t.key, InputErrorKind::Invalid, format!(
                        "{} needs either `q = [q1, q2]` (uniform) or both `start` and `end` (linearly varying)",
                        t.name()
                    ),
                ))
            }
        };
        // Linear variation along the chain of listed elements (e.g. a member's elements):
        // position = projection on the line from the first node to the last.
        let nodes = self.model.nodes().to_vec();
        let ends = |e: ElementId| match &self.model.elements()[e.0] {
            Element::Frame { nodes, .. } | Element::Bar { nodes, .. } => Some(*nodes),
            Element::Plane { .. } => None,
        };
        let mut chain = Vec::with_capacity(elems.len());
        for &e in &elems {
            match ends(e) {
                Some(n) => chain.push((e, nodes[n[0].0], nodes[n[1].0])),
                None => {
                    return Err(self.err(
                        t.get("elements").and_then(|n| n.pos),
                        &t.child("elements"),
                        InputErrorKind::Invalid,
                        format!(
                            "element `{}` is a plane element: distributed loads act on frames and bars (use a body force or nodal loads on plane elements)",
                            self.pending[e.0].name
                        ),
                    ))
                }
            }
        }
        let p0 = chain[0].1;
        let p1 = chain[chain.len() - 1].2;
        let d = [p1[0] - p0[0], p1[1] - p0[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let s = |p: [f64; 2]| {
            if len2 > 0.0 {
                (((p[0] - p0[0]) * d[0] + (p[1] - p0[1]) * d[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let lerp = |s: f64| [qa[0] + s * (qb[0] - qa[0]), qa[1] + s * (qb[1] - qa[1])];
        for (element, a, b) in chain {
            let (start, end) = if elems.len() == 1 {
                (qa, qb)
            } else {
                (lerp(s(a)), lerp(s(b)))
            };
            self.push_load(
                group,
                Load::Distributed {
                    element,
                    start,
                    end,
                    frame,
                },
            );
        }
        Ok(())
    }

    fn settlement(&mut self, t: &Table, group: LoadGroup) -> Result<(), InputError> {
        t.check_keys(&["nodes", "dof", "value"])?;
        let nodes = self.fe_nodes_of(t, "nodes", "the supported nodes that settle")?;
        let dof = match choice(t, "dof", &["ux", "uy", "rz"], None, "settled DOF")? {
            "ux" => SupportDof::Ux,
            "uy" => SupportDof::Uy,
            _ => SupportDof::Rz,
        };
        let value = number(t, "value", "the prescribed displacement (or rotation)")?;
        for node in nodes {
            if !self.model_has_support(node, dof) {
                return Err(self.err(
                    t.get("nodes").and_then(|n| n.pos),
                    &t.child("nodes"),
                    InputErrorKind::Invalid,
                    format!(
                        "node `{}` has no {} support: a settlement prescribes the displacement of a supported DOF",
                        self.node_name(node),
                        dof_word(dof)
                    ),
                ));
            }
            self.push_load(group, Load::Settlement { node, dof, value });
        }
        Ok(())
    }

    fn model_has_support(&self, node: NodeId, dof: SupportDof) -> bool {
        self.supported.iter().any(|&(n, d)| n == node && d == dof)
    }

    fn node_name(&self, n: NodeId) -> String {
        self.fe_names[n.0].clone()
    }

    fn contact(&mut self, top: &Table) -> Result<(), InputError> {
        let entries = table_array(top, "contact")?;
        let tol = self.tolerance();
        let mut used_names: HashMap<String, Option<Pos>> = HashMap::new();
        for t in entries {
            t.check_keys(&["name", "from", "to", "normal", "friction", "gap", "exclude"])?;
            let name = match t.get("name") {
                Some(n) => Some(id(self.doc, n, &t.child("name"))?),
                None => None,
            };
            let normal = direction(
                self.doc,
                t.require(
                    "normal",
                    "the contact normal [nx, ny], pointing from `from` into `to`",
                )?,
                &t.child("normal"),
            )?;
            let friction = number(
                &t,
                "friction",
                "the friction coefficient f (0 for frictionless)",
            )?;
            if friction < 0.0 {
                return Err(self.err(
                    t.get("friction").and_then(|n| n.pos),
                    &t.child("friction"),
                    InputErrorKind::Value,
                    format!("the friction coefficient must be ≥ 0, got {friction}"),
                ));
            }
            let gap = opt_number(&t, "gap")?.unwrap_or(0.0);
            if gap < 0.0 {
                return Err(self.err(
                    t.get("gap").and_then(|n| n.pos),
                    &t.child("gap"),
                    InputErrorKind::Value,
                    format!("the initial gap must be ≥ 0, got {gap}"),
                ));
            }
            let from_node =
                t.require("from", "\"ground\", or the nodes (ids or sets) of body A")?;
            let to_node = t.require("to", "the nodes (ids or sets) of body B")?;
            let from = refs(self.doc, from_node, &t.child("from"))?;
            let to = refs(self.doc, to_node, &t.child("to"))?;
            let exclude: Vec<NodeId> = match t.get("exclude") {
                Some(n) => self.fe_nodes(&refs(self.doc, n, &t.child("exclude"))?)?,
                None => Vec::new(),
            };
            let ground = from.len() == 1 && from[0].name == "ground";
            // (A, B) pairs.
            let mut pairs: Vec<(Endpoint, NodeId)> = Vec::new();
            if ground {
                for b in self.fe_nodes(&to)? {
                    if !exclude.contains(&b) {
                        pairs.push((Endpoint::Ground, b));
                    }
                }
            } else {
                let a_nodes = self.fe_nodes(&from)?;
                let b_nodes = self.fe_nodes(&to)?;
                let coords = self.model.nodes().to_vec();
                let b_idx: Vec<usize> = b_nodes.iter().map(|n| n.0).collect();
                let index = PointIndex::new(&coords, &b_idx, tol);
                for a in a_nodes {
                    if exclude.contains(&a) {
                        continue;
                    }
                    let near: Vec<usize> = index
                        .near(coords[a.0])
                        .into_iter()
                        .filter(|&b| b != a.0)
                        .collect();
                    match near.as_slice() {
                        [b] => pairs.push((Endpoint::Node(a), NodeId(*b))),
                        [] => {
                            let same = b_nodes.contains(&a);
                            let why = if same {
                                " (it is itself a node of `to`: the two bodies share this node instead of touching; keep blocks and members separate, without `connect_to`)"
                            } else {
                                ""
                            };
                            return Err(self.err(
                                to_node.pos,
                                &t.child("to"),
                                InputErrorKind::Invalid,
                                format!(
                                    "node `{}` of `from` at ({}, {}) has no coincident node in `to`{why}",
                                    self.node_name(a),
                                    coords[a.0][0],
                                    coords[a.0][1]
                                ),
                            ));
                        }
                        _ => {
                            return Err(self.err(
                                to_node.pos,
                                &t.child("to"),
                                InputErrorKind::Invalid,
                                format!(
                                    "node `{}` of `from` coincides with {} nodes of `to` ({}); pair it explicitly",
                                    self.node_name(a),
                                    near.len(),
                                    near.iter()
                                        .map(|&b| format!("`{}`", self.node_name(NodeId(b))))
                                        .collect::<Vec<_>>()
                                        .join(", ")
                                ),
                            ))
                        }
                    }
                }
            }
            if pairs.is_empty() {
                return Err(self.err(
                    t.pos,
                    &t.key,
                    InputErrorKind::Invalid,
                    format!("{} makes no pairs (every node is excluded)", t.name()),
                ));
            }
            let count = pairs.len();
            for (k, (a, b)) in pairs.into_iter().enumerate() {
                let pname = match &name {
                    Some(n) if count == 1 => n.name.clone(),
                    Some(n) => format!("{}.{}", n.name, k + 1),
                    None => (self.pair_names.len() + 1).to_string(),
                };
                let pos = name.as_ref().map_or(t.pos, |n| n.pos);
                if let Some(p) = used_names.insert(pname.clone(), pos) {
                    return Err(self.err(
                        pos,
                        &name.as_ref().map_or(t.key.clone(), |n| n.key.clone()),
                        InputErrorKind::Invalid,
                        format!(
                            "duplicate contact pair name `{pname}` (first used{})",
                            Self::line_of(p)
                        ),
                    ));
                }
                let spec = match a {
                    Endpoint::Ground => ContactPairSpec::to_ground(b, normal),
                    Endpoint::Node(a) => ContactPairSpec::between(a, b, normal),
                }
                .friction(friction)
                .gap(gap)
                .name(pname.clone());
                self.model.add_contact_pair(spec);
                self.pair_names.push(pname);
                self.pair_origin.push(Origin {
                    pos: t.pos,
                    key: t.key.clone(),
                });
            }
        }
        Ok(())
    }

    /// Runs `Model::validate` and places its errors in the file.
    fn validate(&self) -> Result<(), InputError> {
        let Err(e) = self.model.validate() else {
            return Ok(());
        };
        let elem = |id: ElementId| {
            let o = &self.elem_origin[id.0];
            (
                o.pos,
                o.key.clone(),
                format!("element `{}`", self.pending[id.0].name),
            )
        };
        let pair = |i: usize| {
            let o = &self.pair_origin[i];
            (
                o.pos,
                o.key.clone(),
                format!("contact pair `{}`", self.pair_names[i]),
            )
        };
        let (pos, key, who) = match &e {
            FemError::RepeatedNode { element, .. }
            | FemError::ZeroLength { element, .. }
            | FemError::NonPositiveProperty { element, .. }
            | FemError::PoissonOutOfRange { element, .. }
            | FemError::DistortedElement { element, .. } => elem(*element),
            FemError::BadContactPair { pair: i, .. } | FemError::LinkPlacement { pair: i, .. } => {
                pair(*i)
            }
            FemError::BadSpring { spring, .. } => {
                let o = &self.spring_origin[*spring];
                (o.pos, o.key.clone(), format!("spring {}", spring + 1))
            }
            FemError::BadSupport { node, .. } => {
                let o = self.support_origin.get(&node.0).cloned().unwrap_or(Origin {
                    pos: None,
                    key: "supports".into(),
                });
                (o.pos, o.key, format!("node `{}`", self.node_name(*node)))
            }
            _ => (None, String::new(), String::new()),
        };
        let msg = match &e {
            FemError::ZeroLength { a, b, .. } => format!(
                "{who} has zero length: its nodes `{}` and `{}` are at the same place",
                self.node_name(*a),
                self.node_name(*b)
            ),
            FemError::RepeatedNode { node, .. } => {
                format!("{who} uses node `{}` more than once", self.node_name(*node))
            }
            _ if who.is_empty() => e.to_string(),
            _ => {
                // Drop the finite-element prefix ("element 4: ", "contact pair 2 (name): ").
                let text = e.to_string();
                let rest = match text.split_once(": ") {
                    Some((head, rest))
                        if head.starts_with("element ")
                            || head.starts_with("contact pair ")
                            || head.starts_with("spring ")
                            || head.starts_with("node ") =>
                    {
                        rest.to_string()
                    }
                    _ => text,
                };
                format!("{who}: {rest}")
            }
        };
        Err(self.err(pos, &key, InputErrorKind::Invalid, msg))
    }

    fn names(&self) -> ModelNames {
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
        ModelNames {
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

fn dof_word(d: SupportDof) -> &'static str {
    match d {
        SupportDof::Ux => "ux",
        SupportDof::Uy => "uy",
        SupportDof::Rz => "rz",
        SupportDof::Along(_) => "inclined",
    }
}
