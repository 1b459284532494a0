//! `[[meshes]]`: bodies meshed by Gmsh, read from `.msh` files.
//!
//! A mesh `NAME` gives the nodes `NAME.<node tag>` (every node an element of the model uses),
//! the element set `NAME` (all its elements) and `NAME.<group>` for each 2D physical group (and
//! for each 1D group made of frames by `sections`), a node set `NAME.<group>` for every physical
//! group, `NAME.nodes` (every node), and a contact [`Surface`] `NAME.<group>` for each 1D group.
//! Groups are named by their physical names, or by their tags when unnamed. Node sets list their
//! nodes by ascending node tag, except those of 1D groups, which follow the line elements.
//!
//! What the file itself can get wrong is [`crate::read_gmsh`]'s; what the model makes of it
//! (a 2D element without a material, a degenerate or concave element, a group the model file
//! names that the mesh does not have) is checked here, and errors in the mesh name the `.msh`
//! file and its line.

use std::collections::HashSet;
use std::path::Path;

use super::*;
use crate::error::Location;
use crate::msh::{read_gmsh, GmshMesh, MshElement, MshElementType};

/// A contact surface: the segments of a 1D physical group of a mesh, in order along its line
/// elements (each chain of connected segments walked from one end; chains in the order of their
/// first element in the file).
pub(super) struct Surface {
    /// The segments in order; consecutive segments of a chain share a node (`[a1, a2]`, then
    /// `[a2, a3]`, …).
    pub segments: Vec<Segment>,
}

/// One segment of a [`Surface`].
#[derive(Debug, Clone, Copy)]
pub(super) struct Segment {
    /// Its end nodes, as proto nodes (`Builder::final_of` numbers them). The contact builder
    /// orients a segment by the model's elements at it.
    pub nodes: [usize; 2],
}

/// Relative size under which an element's area (a corner's cross product) counts as zero: of the
/// square of the element's longest side or diagonal.
const FLAT: f64 = 1e-9;

/// The mesh file's side of an error: the `.msh` file and a line, and where the model file names it.
struct MeshFile<'a> {
    path: &'a Path,
    from: Location,
}

impl MeshFile<'_> {
    fn err(&self, line: Option<usize>, kind: InputErrorKind, msg: String) -> InputError {
        let mut e = InputError::new(
            Location {
                file: self.path.to_path_buf(),
                line,
                column: None,
            },
            kind,
            msg,
        );
        e.referenced_from = Some(Box::new(self.from.clone()));
        e
    }
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

/// The corners of a 2D element in counter-clockwise order, or why the element cannot be used.
/// A triangle is degenerate when twice its area is at most [`FLAT`] times its longest side
/// squared; a quadrilateral must turn the same way at every corner by more than that.
fn counter_clockwise(xy: &[[f64; 2]], order: &mut [usize]) -> Result<(), &'static str> {
    let n = xy.len();
    let scale = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .map(|(i, j)| dist2(xy[i], xy[j]))
        .fold(0.0f64, f64::max);
    let mut turns = [0.0; 4];
    for (i, t) in turns.iter_mut().enumerate().take(n) {
        *t = cross(xy[i], xy[(i + 1) % n], xy[(i + n - 1) % n]);
    }
    let turns = &turns[..n];
    let flat = FLAT * scale;
    let has_area = scale > 0.0 && scale.is_finite() && turns.iter().all(|t| t.abs() > flat);
    if !has_area {
        return Err(if n == 3 {
            "degenerate: its corners are on one line or coincide (no area)"
        } else {
            "degenerate: two of its sides are on one line or a side has no length"
        });
    }
    let ccw = turns.iter().filter(|&&t| t > 0.0).count();
    if ccw == n {
        Ok(())
    } else if ccw == 0 {
        order[1..].reverse();
        Ok(())
    } else {
        Err("concave or self-intersecting: it does not turn the same way at every corner")
    }
}

fn kind_name(k: MshElementType) -> &'static str {
    match k {
        MshElementType::Point => "point",
        MshElementType::Line => "line",
        MshElementType::Triangle => "triangle",
        MshElementType::Quadrangle => "quadrangle",
    }
}

/// Walks the segments (pairs of node tags, in the file's order) into chains: each chain from an
/// end (or, for a closed loop, from its first segment in the file), chains in the order of
/// their first segment in the file. Returns the oriented segments.
fn chains(segments: &[[usize; 2]]) -> Vec<[usize; 2]> {
    let mut at: HashMap<usize, Vec<usize>> = HashMap::new();
    for (s, seg) in segments.iter().enumerate() {
        for &n in seg {
            at.entry(n).or_default().push(s);
        }
    }
    // The other segment at node `n` of a chain through segment `s`, if the chain goes on there.
    let next = |s: usize, n: usize| -> Option<usize> {
        match at[&n].as_slice() {
            [a, b] if *a == s => Some(*b),
            [a, b] if *b == s => Some(*a),
            _ => None,
        }
    };
    let other = |s: usize, n: usize| {
        let [a, b] = segments[s];
        if a == n {
            b
        } else {
            a
        }
    };
    let mut used = vec![false; segments.len()];
    let mut out = Vec::with_capacity(segments.len());
    for first in 0..segments.len() {
        if used[first] {
            continue;
        }
        // back from the first segment's first node to the chain's start
        let (mut s, mut n) = (first, segments[first][0]);
        loop {
            match next(s, n) {
                Some(p) if p == first => {
                    // a closed loop: it starts where the file starts it
                    (s, n) = (first, segments[first][0]);
                    break;
                }
                Some(p) if !used[p] => {
                    n = other(p, n);
                    s = p;
                }
                _ => break,
            }
        }
        // forward: `n` is the start node of segment `s`
        loop {
            used[s] = true;
            let m = other(s, n);
            out.push([n, m]);
            match next(s, m) {
                Some(p) if !used[p] => {
                    s = p;
                    n = m;
                }
                _ => break,
            }
        }
    }
    out
}

impl Builder<'_> {
    pub(super) fn meshes(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "meshes")? {
            self.mesh(&t)?;
        }
        Ok(())
    }

    fn mesh(&mut self, t: &Table) -> Result<(), InputError> {
        t.check_keys(&[
            "name",
            "file",
            "analysis",
            "materials",
            "material",
            "formulation",
            "sections",
            "connect_to",
        ])?;
        let name = self.object_name(t, "mesh")?;
        let n = name.name.clone();
        let file_node = t.require("file", "the Gmsh mesh file (.msh), relative to this file")?;
        let file_key = t.child("file");
        let file_name = self.doc.string(file_node, &file_key)?;
        if file_name.trim().is_empty() {
            return Err(self.err(
                file_node.pos,
                &file_key,
                InputErrorKind::Value,
                "the mesh file name is empty".into(),
            ));
        }
        let path = self
            .doc
            .path
            .parent()
            .unwrap_or(Path::new(""))
            .join(file_name);
        let from = Location::at(self.doc.path, file_node.pos);
        let mesh = read_gmsh(&path).map_err(|mut e| {
            if e.kind == InputErrorKind::Io {
                // The file named is not there: the error belongs to the model file.
                self.err(
                    file_node.pos,
                    &file_key,
                    InputErrorKind::Io,
                    format!(
                        "cannot read the mesh file \"{file_name}\" (looked for {}): {}",
                        path.display(),
                        e.message.trim_start_matches("cannot read the file: ")
                    ),
                )
            } else {
                e.referenced_from = Some(Box::new(from.clone()));
                e
            }
        })?;
        let mf = MeshFile { path: &path, from };
        let materials = self.mesh_materials(t, &mesh)?;
        let sections = self.mesh_sections(t, &mesh)?;
        let (analysis, formulation) = self.plane_options(t)?;

        // The model's elements and the nodes they use.
        let mut kinds: Vec<(usize, Kind)> = Vec::new();
        for (i, e) in mesh.elements.iter().enumerate() {
            let kind = match e.kind {
                MshElementType::Triangle | MshElementType::Quadrangle => {
                    let m = materials.of(e, &mesh, &mf)?;
                    if e.kind == MshElementType::Triangle {
                        Kind::Triangle(m, analysis)
                    } else {
                        Kind::Plane(m, analysis, formulation)
                    }
                }
                MshElementType::Line => match sections.of(e, &mesh, &mf)? {
                    Some(s) => Kind::Frame(s, Releases::default()),
                    None => continue,
                },
                MshElementType::Point => continue,
            };
            kinds.push((i, kind));
        }
        if kinds.is_empty() {
            return Err(mf.err(
                None,
                InputErrorKind::Invalid,
                format!(
                    "mesh `{n}` has no element the model can use: no triangles or quadrangles{}",
                    if t.get("sections").is_some() {
                        ", and no line in a group of `sections`"
                    } else {
                        " (lines become frames only through `sections`)"
                    }
                ),
            ));
        }
        let max_tag = mesh.nodes.iter().map(|nd| nd.tag).max().unwrap_or(0);
        let mut node_at = TagMap::new(max_tag, mesh.nodes.len());
        for (i, nd) in mesh.nodes.iter().enumerate() {
            node_at.insert(nd.tag, i);
        }
        // (the reader has checked that every element's nodes are defined)
        let node_at = |tag: usize| node_at.get(tag).unwrap_or(0);
        let mut used = vec![false; mesh.nodes.len()];
        for (i, _) in &kinds {
            for &tag in &mesh.elements[*i].nodes {
                used[node_at(tag)] = true;
            }
        }
        // Proto nodes by ascending tag.
        let mut order: Vec<usize> = (0..mesh.nodes.len()).filter(|&i| used[i]).collect();
        order.sort_unstable_by_key(|&i| mesh.nodes[i].tag);
        let mut proto_of = TagMap::new(max_tag, order.len());
        let mut all = Vec::with_capacity(order.len());
        self.node_names.reserve(order.len());
        self.protos.reserve(order.len());
        self.proto_names.reserve(order.len());
        self.element_index.reserve(kinds.len());
        self.pending.reserve(kinds.len());
        for &i in &order {
            let nd = &mesh.nodes[i];
            let nm = format!("{n}.{}", nd.tag);
            self.check_new_name(&nm, name.pos, &name.key)?;
            let p = self.new_proto(nd.xy, nm, name.pos);
            proto_of.insert(nd.tag, p);
            all.push(p);
        }
        let coord = |tag: usize| mesh.nodes[node_at(tag)].xy;

        // Elements, corners counter-clockwise.
        let mut element_of = vec![usize::MAX; mesh.elements.len()];
        let mut everything = Vec::with_capacity(kinds.len());
        for (i, kind) in kinds {
            let e = &mesh.elements[i];
            let k = e.nodes.len();
            let mut order = [0, 1, 2, 3];
            if e.kind.dimension() == 2 {
                let mut xy = [[0.0; 2]; 4];
                for (x, &tag) in xy.iter_mut().zip(&e.nodes) {
                    *x = coord(tag);
                }
                counter_clockwise(&xy[..k], &mut order[..k]).map_err(|why| {
                    mf.err(
                        Some(e.line),
                        InputErrorKind::Invalid,
                        format!(
                            "element {} (a {} on nodes {}) is {why}",
                            e.tag,
                            kind_name(e.kind),
                            e.nodes
                                .iter()
                                .map(|t| t.to_string())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })?;
            } else if e.nodes[0] == e.nodes[1] {
                return Err(mf.err(
                    Some(e.line),
                    InputErrorKind::Invalid,
                    format!(
                        "line element {} has node {} at both ends",
                        e.tag, e.nodes[0]
                    ),
                ));
            }
            let id = self.add_element(Pending {
                kind,
                nodes: order[..k]
                    .iter()
                    .map(|&j| proto_of.get(e.nodes[j]).unwrap_or(0))
                    .collect(),
                name: format!("{n}.{}", e.tag),
                pos: name.pos,
                key: t.key.clone(),
            })?;
            element_of[i] = id;
            everything.push(id);
        }

        // Sets and surfaces of the groups.
        let mut labels: HashMap<String, Option<usize>> = HashMap::new();
        labels.insert("nodes".into(), None);
        for g in &mesh.groups {
            let label = g.label();
            if let Some(first) = labels.insert(label.clone(), g.line) {
                let why = if label == "nodes" {
                    format!("`{n}.nodes` is every node of the mesh: rename the group")
                } else {
                    format!(
                        "another group has that name{}: the model names a group `{n}.<name>` whatever its dimension",
                        first.map(|l| format!(" (line {l})")).unwrap_or_default()
                    )
                };
                return Err(mf.err(
                    g.line,
                    InputErrorKind::Invalid,
                    format!(
                        "physical group `{label}` (dimension {}): {why}",
                        g.dimension
                    ),
                ));
            }
            let set = format!("{n}.{label}");
            let indexed: Vec<usize> = (0..mesh.elements.len())
                .filter(|&i| {
                    let e = &mesh.elements[i];
                    e.kind.dimension() == g.dimension && e.physical.contains(&g.tag)
                })
                .collect();
            let members: Vec<&MshElement> = indexed.iter().map(|&i| &mesh.elements[i]).collect();
            // A named group without elements would be an empty set, supports and loads on it
            // silently dropped: it makes no set, and a reference to it is told why.
            if members.is_empty() {
                self.empty_groups.insert(
                    set.clone(),
                    format!(
                        "`{set}` is physical group `{label}` (dimension {}) of {}{}, which has no \
                         elements of its dimension (Gmsh writes MSH 2.2 with Mesh.SaveAll = 1 \
                         without the elements' groups: save without SaveAll, or in MSH 4.1); \
                         give the group its curves or surfaces",
                        g.dimension,
                        mf.path.display(),
                        g.line.map(|l| format!(" (line {l})")).unwrap_or_default()
                    ),
                );
                continue;
            }
            let mut tags: Vec<usize> = Vec::new();
            if g.dimension == 1 {
                let segs: Vec<[usize; 2]> =
                    members.iter().map(|e| [e.nodes[0], e.nodes[1]]).collect();
                let walked = chains(&segs);
                let mut segments = Vec::with_capacity(walked.len());
                let mut seen = HashSet::new();
                for [a, b] in walked {
                    for tag in [a, b] {
                        if seen.insert(tag) {
                            tags.push(tag);
                        }
                    }
                    segments.push((a, b));
                }
                let mut out = Vec::with_capacity(segments.len());
                for (a, b) in segments {
                    let pa = self.mesh_proto(&proto_of, a, &n, &label, &members, &mf)?;
                    let pb = self.mesh_proto(&proto_of, b, &n, &label, &members, &mf)?;
                    out.push(Segment { nodes: [pa, pb] });
                }
                self.surfaces.insert(set.clone(), Surface { segments: out });
            } else {
                let mut seen = HashSet::new();
                for e in &members {
                    for &tag in &e.nodes {
                        if seen.insert(tag) {
                            tags.push(tag);
                        }
                    }
                }
                tags.sort_unstable();
            }
            let mut protos = Vec::with_capacity(tags.len());
            for tag in tags {
                protos.push(self.mesh_proto(&proto_of, tag, &n, &label, &members, &mf)?);
            }
            self.add_mesh_set(set.clone(), protos, name.pos, &name.key)?;
            let elems: Vec<usize> = indexed
                .iter()
                .map(|&i| element_of[i])
                .filter(|&i| i != usize::MAX)
                .collect();
            if !elems.is_empty() {
                self.add_mesh_element_set(set, elems, &name)?;
            }
        }
        self.add_mesh_set(format!("{n}.nodes"), all.clone(), name.pos, &name.key)?;
        self.element_sets.insert(n, everything);
        if let Some(c) = t.get("connect_to") {
            let targets = refs(self.doc, c, &t.child("connect_to"))?;
            self.connects.push((all, targets));
        }
        Ok(())
    }

    /// The proto node of a node of a group; a group node that no element of the model uses
    /// would be a free node.
    fn mesh_proto(
        &self,
        proto_of: &TagMap,
        tag: usize,
        mesh: &str,
        label: &str,
        members: &[&MshElement],
        mf: &MeshFile,
    ) -> Result<usize, InputError> {
        proto_of.get(tag).ok_or_else(|| {
            let e = members.iter().find(|e| e.nodes.contains(&tag));
            mf.err(
                e.map(|e| e.line),
                InputErrorKind::Invalid,
                format!(
                    "node {tag} of physical group `{label}` belongs to no element of mesh `{mesh}` \
                     (no 2D element, and no line made a frame by `sections`): it would be a free node"
                ),
            )
        })
    }

    /// A node set of a mesh group. An unnamed group's set `NAME.<tag>` may have the name of a
    /// node of the same tag; the set is what the name then means.
    fn add_mesh_set(
        &mut self,
        name: String,
        nodes: Vec<usize>,
        pos: Option<Pos>,
        key: &str,
    ) -> Result<(), InputError> {
        if self.node_names.contains_key(&name) && !self.sets.contains_key(&name) {
            self.set_order.push(name.clone());
            self.sets.insert(name, (nodes, pos));
            Ok(())
        } else {
            self.add_set(name, nodes, pos, key)
        }
    }

    fn add_mesh_element_set(
        &mut self,
        set: String,
        elems: Vec<usize>,
        name: &Ref,
    ) -> Result<(), InputError> {
        if self.element_sets.contains_key(&set) || self.element_index.contains_key(&set) {
            return Err(self.invalid_at(
                name,
                format!("duplicate name `{set}`: a block, member or element of that name already exists"),
            ));
        }
        self.element_sets.insert(set, elems);
        Ok(())
    }

    /// The material of each 2D element: `material` for all, or `materials` by 2D group.
    fn mesh_materials(
        &self,
        t: &Table,
        mesh: &GmshMesh,
    ) -> Result<GroupMap<PlaneMaterial>, InputError> {
        let has_2d = mesh.elements.iter().any(|e| e.kind.dimension() == 2);
        match (t.get("material"), t.get("materials")) {
            (Some(_), Some(n)) => Err(self.err(
                n.pos,
                &t.child("materials"),
                InputErrorKind::Invalid,
                "give `material` (one for the whole mesh) or `materials` (by physical group), not both"
                    .into(),
            )),
            (Some(_), None) => Ok(GroupMap::All(self.material(t)?)),
            (None, Some(_)) => {
                let table = t.table("materials")?.expect("present");
                let mut by_tag = HashMap::new();
                for e in table.entries {
                    let group = self.mesh_group(mesh, 2, &e.key, e.key_pos, &table.child(&e.key))?;
                    let r = id(self.doc, &e.node, &table.child(&e.key))?;
                    let m = self
                        .materials
                        .get(&r.name)
                        .copied()
                        .ok_or_else(|| self.unknown(&r, "material", self.materials.keys()))?;
                    by_tag.insert(group, (m, e.key.clone()));
                }
                Ok(GroupMap::ByGroup(by_tag, "materials"))
            }
            (None, None) if has_2d => {
                let first = mesh.elements.iter().find(|e| e.kind.dimension() == 2);
                Err(self.err(
                    t.pos,
                    &t.child("material"),
                    InputErrorKind::MissingKey,
                    format!(
                        "missing key `material` (or `materials` by physical group) in {}: the mesh has 2D elements (the first, element {}, on line {})",
                        t.name(),
                        first.map_or(0, |e| e.tag),
                        first.map_or(0, |e| e.line)
                    ),
                ))
            }
            (None, None) => Ok(GroupMap::ByGroup(HashMap::new(), "materials")),
        }
    }

    /// The frame section of 1D groups, from `sections`.
    fn mesh_sections(
        &self,
        t: &Table,
        mesh: &GmshMesh,
    ) -> Result<GroupMap<FrameSection>, InputError> {
        let mut by_tag = HashMap::new();
        if let Some(table) = t.table("sections")? {
            for e in table.entries {
                let key = table.child(&e.key);
                let group = self.mesh_group(mesh, 1, &e.key, e.key_pos, &key)?;
                let r = id(self.doc, &e.node, &key)?;
                let Some(s) = self.sections.get(&r.name) else {
                    return Err(self.unknown(&r, "section", self.sections.keys()));
                };
                if !s.has_inertia {
                    return Err(self.invalid_at(
                        &r,
                        format!(
                            "section `{}` has no moment of inertia I, which frame elements need",
                            r.name
                        ),
                    ));
                }
                by_tag.insert(group, (s.section, e.key.clone()));
            }
        }
        Ok(GroupMap::ByGroup(by_tag, "sections"))
    }

    /// The tag of the physical group of dimension `dim` that the model file names `label`.
    fn mesh_group(
        &self,
        mesh: &GmshMesh,
        dim: usize,
        label: &str,
        pos: Option<Pos>,
        key: &str,
    ) -> Result<usize, InputError> {
        let r = Ref {
            name: label.to_string(),
            pos,
            key: key.to_string(),
        };
        match mesh.group(label) {
            // a group with no element of its dimension would give its material or section to
            // nothing: the frames of `sections` were silently lost
            Some(g)
                if g.dimension == dim
                    && !mesh
                        .elements
                        .iter()
                        .any(|e| e.kind.dimension() == dim && e.physical.contains(&g.tag)) =>
            {
                Err(self.invalid_at(
                    &r,
                    format!(
                        "physical group `{label}` of the mesh has no elements of its dimension \
                         (Gmsh writes MSH 2.2 with Mesh.SaveAll = 1 without the elements' \
                         groups: save without SaveAll, or in MSH 4.1)"
                    ),
                ))
            }
            Some(g) if g.dimension == dim => Ok(g.tag),
            Some(g) => Err(self.invalid_at(
                &r,
                format!(
                    "physical group `{label}` of the mesh has dimension {}, but a group of dimension {dim} ({}) is needed here",
                    g.dimension,
                    if dim == 2 { "surfaces: 2D elements" } else { "curves: line elements" }
                ),
            )),
            None => {
                let known: Vec<String> = mesh
                    .groups
                    .iter()
                    .filter(|g| g.dimension == dim)
                    .map(|g| g.label())
                    .collect();
                let list = if known.is_empty() {
                    format!(" (the mesh has no group of dimension {dim})")
                } else {
                    format!(" (its groups of dimension {dim}: {})", known.join(", "))
                };
                let e = self.unknown(&r, "physical group", known.iter());
                Err(InputError {
                    message: format!("{}{list}", e.message),
                    ..e
                })
            }
        }
    }
}

/// Node tags → indices: a table when the tags are dense enough (Gmsh's usually are), else a
/// hash map.
enum TagMap {
    Dense(Vec<usize>),
    Sparse(HashMap<usize, usize>),
}

impl TagMap {
    fn new(max_tag: usize, len: usize) -> Self {
        if max_tag <= len.saturating_mul(4).saturating_add(1024) {
            TagMap::Dense(vec![usize::MAX; max_tag + 1])
        } else {
            TagMap::Sparse(HashMap::with_capacity(len))
        }
    }

    fn insert(&mut self, tag: usize, i: usize) {
        match self {
            TagMap::Dense(v) => v[tag] = i,
            TagMap::Sparse(m) => {
                m.insert(tag, i);
            }
        }
    }

    fn get(&self, tag: usize) -> Option<usize> {
        match self {
            TagMap::Dense(v) => v.get(tag).copied().filter(|&i| i != usize::MAX),
            TagMap::Sparse(m) => m.get(&tag).copied(),
        }
    }
}

/// A property given for the whole mesh or by physical group.
enum GroupMap<T> {
    All(T),
    /// Group tag → (value, the group's label as written); the key of the model file.
    ByGroup(HashMap<usize, (T, String)>, &'static str),
}

impl<T: Copy + PartialEq> GroupMap<T> {
    /// The value of an element: `None` when no group of it is given (an error for 2D elements).
    fn get(&self, e: &MshElement, mf: &MeshFile) -> Result<Option<T>, InputError> {
        let (map, key) = match self {
            GroupMap::All(v) => return Ok(Some(*v)),
            GroupMap::ByGroup(m, k) => (m, *k),
        };
        let mut found: Option<(T, &str)> = None;
        for g in &e.physical {
            if let Some((v, label)) = map.get(g) {
                match found {
                    Some((w, first)) if w != *v => {
                        return Err(mf.err(
                            Some(e.line),
                            InputErrorKind::Invalid,
                            format!(
                                "element {} is in the groups `{first}` and `{label}`, which `{key}` gives different values",
                                e.tag
                            ),
                        ))
                    }
                    Some(_) => {}
                    None => found = Some((*v, label)),
                }
            }
        }
        Ok(found.map(|(v, _)| v))
    }
}

impl GroupMap<PlaneMaterial> {
    fn of(
        &self,
        e: &MshElement,
        mesh: &GmshMesh,
        mf: &MeshFile,
    ) -> Result<PlaneMaterial, InputError> {
        self.get(e, mf)?.ok_or_else(|| {
            let groups: Vec<String> = mesh
                .groups
                .iter()
                .filter(|g| g.dimension == 2 && e.physical.contains(&g.tag))
                .map(|g| format!("`{}`", g.label()))
                .collect();
            let in_groups = if groups.is_empty() {
                "is in no physical group".to_string()
            } else {
                format!("is in the group(s) {} only", groups.join(", "))
            };
            mf.err(
                Some(e.line),
                InputErrorKind::Invalid,
                format!(
                    "element {} (a {}) has no material: it {in_groups}, and `materials` names none of them",
                    e.tag,
                    kind_name(e.kind)
                ),
            )
        })
    }
}

impl GroupMap<FrameSection> {
    fn of(
        &self,
        e: &MshElement,
        _mesh: &GmshMesh,
        mf: &MeshFile,
    ) -> Result<Option<FrameSection>, InputError> {
        self.get(e, mf)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // References: the segments and corners written by hand below.

    #[test]
    fn chains_follow_the_lines_from_an_end() {
        // out of order, one segment reversed, two chains
        let got = chains(&[[3, 4], [1, 2], [3, 2], [7, 8]]);
        assert_eq!(got, vec![[1, 2], [2, 3], [3, 4], [7, 8]]);
        // a closed loop starts with its first segment in the file
        assert_eq!(
            chains(&[[1, 2], [2, 3], [3, 1]]),
            vec![[1, 2], [2, 3], [3, 1]]
        );
        assert_eq!(
            chains(&[[2, 3], [1, 2], [3, 1]]),
            vec![[2, 3], [3, 1], [1, 2]]
        );
        // a branch point ends the chains that meet there
        let got = chains(&[[1, 2], [2, 3], [2, 4]]);
        assert_eq!(got.len(), 3);
    }

    #[test]
    fn corners_are_turned_counter_clockwise_or_refused() {
        let mut o = [0, 1, 2];
        counter_clockwise(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], &mut o).unwrap();
        assert_eq!(o, [0, 1, 2]);
        counter_clockwise(&[[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]], &mut o).unwrap();
        assert_eq!(o, [0, 2, 1]);
        let sq = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        let mut o = [0, 1, 2, 3];
        counter_clockwise(&sq, &mut o).unwrap();
        assert_eq!(o, [0, 3, 2, 1]);
        let concave = [[0.0, 0.0], [2.0, 0.0], [0.5, 0.5], [0.0, 2.0]];
        let e = counter_clockwise(&concave, &mut [0, 1, 2, 3]).unwrap_err();
        assert!(e.starts_with("concave"));
        let flat = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert!(counter_clockwise(&flat, &mut [0, 1, 2]).is_err());
        // the same shapes in kilometres and in millimetres
        for s in [1e-3, 1e6] {
            let tiny: Vec<[f64; 2]> = concave.iter().map(|p| [p[0] * s, p[1] * s]).collect();
            assert!(counter_clockwise(&tiny, &mut [0, 1, 2, 3]).is_err());
            let sq: Vec<[f64; 2]> = sq.iter().map(|p| [p[0] * s, p[1] * s]).collect();
            assert!(counter_clockwise(&sq, &mut [0, 1, 2, 3]).is_ok());
        }
    }
}
