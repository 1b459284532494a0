//! `[[contact]]`: contact pairs, to the ground, between coincident nodes of two bodies, between
//! each node of one body and the nearest node of another (`match = "nearest"`), or between
//! each node of one body and its projection on a surface of another (`match = "surface"`,
//! node-to-segment); gaps and friction as one number or one per pair, gaps from the geometry,
//! normals given or from the surface.

use std::collections::{HashMap, HashSet};

use super::*;
use crate::tree::Node;

/// How the nodes of `to` find their partners.
#[derive(Clone, Copy, PartialEq)]
enum Match {
    Coincident,
    Nearest,
    Surface,
}

/// A per-pair quantity: one number for every pair, or a list (one per pair, with where each
/// is written).
enum PerPair {
    One(f64),
    List(Vec<(f64, Option<Pos>)>),
}

/// A gap: as `PerPair`, or the initial distance along the normal.
enum Gap {
    Given(PerPair),
    Geometry,
}

/// One pair before its gap, friction and name: the A side (the ground, a node, or a point
/// of a segment), the node B, the A point and the normal of the surface there (when it is
/// known from the geometry).
struct Found {
    a: Endpoint,
    segment: Option<(NodeId, f64)>,
    b: NodeId,
    at: [f64; 2],
    surface_normal: Option<[f64; 2]>,
}

/// One segment of a surface: its nodes and its outward unit normal when the side of the body
/// is known (an edge of exactly one plane element), else the unit normal to its left.
struct Segment {
    a1: NodeId,
    a2: NodeId,
    normal: [f64; 2],
    oriented: bool,
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let l = v[0].hypot(v[1]);
    [v[0] / l, v[1] / l]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

impl Builder<'_> {
    pub(super) fn contact(&mut self, top: &Table) -> Result<(), InputError> {
        let entries = table_array(top, "contact")?;
        let tol = self.tolerance();
        let mut used_names: HashMap<String, Option<Pos>> = HashMap::new();
        for t in entries {
            t.check_keys(&[
                "name", "from", "to", "match", "search", "normal", "friction", "gap", "exclude",
            ])?;
            let name = match t.get("name") {
                Some(n) => Some(id(self.doc, n, &t.child("name"))?),
                None => None,
            };
            let how = match choice(
                &t,
                "match",
                &["coincident", "nearest", "surface"],
                Some("coincident"),
                "pair matching",
            )? {
                "nearest" => Match::Nearest,
                "surface" => Match::Surface,
                _ => Match::Coincident,
            };
            let search = match (how, t.get("search")) {
                (Match::Coincident, None) => None,
                (Match::Coincident, Some(n)) => {
                    return Err(self.err(
                        n.pos,
                        &t.child("search"),
                        InputErrorKind::Invalid,
                        "`search` is for `match = \"nearest\"` or `\"surface\"`; coincident \
                         nodes are paired at the same position"
                            .into(),
                    ))
                }
                _ => Some(positive(
                    &t,
                    "search",
                    "the largest distance at which a partner is accepted",
                )?),
            };
            let normal_node = t.require(
                "normal",
                "the contact normal [nx, ny] pointing from `from` into `to`, or \"surface\"",
            )?;
            let given_normal = match &normal_node.value {
                Value::String(_) => {
                    let word = choice(&t, "normal", &["surface"], None, "normal")?;
                    debug_assert_eq!(word, "surface");
                    if how != Match::Surface {
                        return Err(self.err(
                            normal_node.pos,
                            &t.child("normal"),
                            InputErrorKind::Invalid,
                            "`normal = \"surface\"` needs `match = \"surface\"` (the normal of \
                             the surface `from` at the paired point); give [nx, ny] otherwise"
                                .into(),
                        ));
                    }
                    None
                }
                _ => Some(direction(self.doc, normal_node, &t.child("normal"))?),
            };
            let friction = self.per_pair(
                &t,
                "friction",
                t.require(
                    "friction",
                    "the friction coefficient f (0 for frictionless), or one per pair",
                )?,
                "the friction coefficient",
            )?;
            let gap = match t.get("gap") {
                None => Gap::Given(PerPair::One(0.0)),
                Some(n) if matches!(n.value, Value::String(_)) => {
                    choice(&t, "gap", &["geometry"], None, "gap")?;
                    Gap::Geometry
                }
                Some(n) => Gap::Given(self.per_pair(&t, "gap", n, "the initial gap")?),
            };
            let from_node =
                t.require("from", "\"ground\", or the nodes (ids or sets) of body A")?;
            let to_node = t.require("to", "the nodes (ids or sets) of body B")?;
            let from = refs(self.doc, from_node, &t.child("from"))?;
            let to = refs(self.doc, to_node, &t.child("to"))?;
            let exclude: Vec<NodeId> = match t.get("exclude") {
                Some(n) => self.fe_nodes(&refs(self.doc, n, &t.child("exclude"))?)?,
                None => Vec::new(),
            };
            let exclude: HashSet<NodeId> = exclude.into_iter().collect();
            let ground = from.len() == 1 && from[0].name == "ground";
            if ground && how != Match::Coincident {
                return Err(self.err(
                    t.get("match").and_then(|n| n.pos),
                    &t.child("match"),
                    InputErrorKind::Invalid,
                    "the rigid ground has no position to match: with `from = \"ground\"` leave \
                     `match` out (every node of `to` gets a pair)"
                        .into(),
                ));
            }
            if ground && matches!(gap, Gap::Geometry) {
                return Err(self.err(
                    t.get("gap").and_then(|n| n.pos),
                    &t.child("gap"),
                    InputErrorKind::Invalid,
                    "the rigid ground has no position: with `from = \"ground\"` give the gap \
                     as a number or a list (one per pair)"
                        .into(),
                ));
            }
            let coords = self.model.nodes().to_vec();
            let pairs: Vec<Found> = if ground {
                self.fe_nodes(&to)?
                    .into_iter()
                    .filter(|b| !exclude.contains(b))
                    .map(|b| Found {
                        a: Endpoint::Ground,
                        segment: None,
                        b,
                        at: coords[b.0],
                        surface_normal: None,
                    })
                    .collect()
            } else {
                let a_nodes = self.fe_nodes(&from)?;
                let b_nodes = self.fe_nodes(&to)?;
                match how {
                    Match::Coincident => {
                        self.coincident(&t, to_node, &a_nodes, &b_nodes, &exclude, tol)?
                    }
                    Match::Nearest => {
                        let search = search.expect("required");
                        let index = PointIndex::new(
                            &coords,
                            &a_nodes.iter().map(|n| n.0).collect::<Vec<_>>(),
                            search,
                        );
                        let mut out = Vec::new();
                        for &b in b_nodes.iter().filter(|b| !exclude.contains(b)) {
                            let pb = coords[b.0];
                            let mut best: Option<(f64, usize)> = None;
                            for a in index.near(pb) {
                                let d = sub(coords[a], pb);
                                let d = d[0].hypot(d[1]);
                                if a != b.0 && d <= search && best.is_none_or(|(e, _)| d < e) {
                                    best = Some((d, a));
                                }
                            }
                            if let Some((_, a)) = best {
                                out.push(Found {
                                    a: Endpoint::Node(NodeId(a)),
                                    segment: None,
                                    b,
                                    at: coords[a],
                                    surface_normal: None,
                                });
                            }
                        }
                        out
                    }
                    Match::Surface => {
                        let segments = self.segments(&t, from_node, &from, &a_nodes)?;
                        let search = search.expect("required");
                        self.on_surface(&segments, &b_nodes, &exclude, search, tol)
                    }
                }
            };
            if pairs.is_empty() {
                let why = match how {
                    _ if ground => "every node is excluded".to_string(),
                    Match::Coincident => "every node is excluded".to_string(),
                    _ => format!(
                        "no node of `to` has a partner in `from` within `search` = {}",
                        search.unwrap_or(0.0)
                    ),
                };
                return Err(self.err(
                    t.pos,
                    &t.key,
                    InputErrorKind::Invalid,
                    format!("{} makes no pairs ({why})", t.name()),
                ));
            }
            let count = pairs.len();
            self.contact_counts.push((
                name.as_ref()
                    .map_or_else(|| t.key.to_string(), |r| r.name.clone()),
                count,
            ));
            let gap_list = match &gap {
                Gap::Given(v) => Some(v),
                Gap::Geometry => None,
            };
            for (key, v) in [("friction", Some(&friction)), ("gap", gap_list)] {
                let Some(v) = v else { continue };
                if let PerPair::List(l) = v {
                    if l.len() != count {
                        return Err(self.err(
                            t.get(key).and_then(|n| n.pos),
                            &t.child(key),
                            InputErrorKind::Size,
                            format!(
                                "`{key}` lists {} values, but {} makes {count} pairs (one value \
                                 per pair, in the order of the nodes of `{}`)",
                                l.len(),
                                t.name(),
                                if how == Match::Coincident && !ground {
                                    "from"
                                } else {
                                    "to"
                                }
                            ),
                        ));
                    }
                }
            }
            for (k, f) in pairs.into_iter().enumerate() {
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
                let normal = match (given_normal, f.surface_normal) {
                    (Some(n), _) => n,
                    (None, Some(n)) => n,
                    (None, None) => {
                        return Err(self.err(
                            normal_node.pos,
                            &t.child("normal"),
                            InputErrorKind::Invalid,
                            format!(
                                "contact pair `{pname}`: the side of `from` that faces node `{}` \
                                 cannot be told (a surface of frames or bars, or an inner edge, \
                                 with the node on it); give `normal` as [nx, ny]",
                                self.node_name(f.b)
                            ),
                        ))
                    }
                };
                let value = |v: &PerPair| match v {
                    PerPair::One(x) => *x,
                    PerPair::List(l) => l[k].0,
                };
                let gap = match &gap {
                    Gap::Given(v) => value(v),
                    Gap::Geometry => {
                        let g = dot(unit(normal), sub(coords[f.b.0], f.at));
                        if g < -tol {
                            return Err(self.err(
                                t.get("gap").and_then(|n| n.pos),
                                &t.child("gap"),
                                InputErrorKind::Invalid,
                                format!(
                                    "contact pair `{pname}`: node `{}` is {} inside `from` \
                                     along the normal (the bodies overlap); `gap = \"geometry\"` \
                                     needs bodies that do not overlap",
                                    self.node_name(f.b),
                                    -g
                                ),
                            ));
                        }
                        if g <= tol {
                            0.0
                        } else {
                            g
                        }
                    }
                };
                let mut spec = match f.a {
                    Endpoint::Ground => ContactPairSpec::to_ground(f.b, normal),
                    Endpoint::Node(a) => match f.segment {
                        None => ContactPairSpec::between(a, f.b, normal),
                        Some((a2, xi)) => ContactPairSpec::on_segment(a, a2, xi, f.b, normal),
                    },
                };
                spec = spec.friction(value(&friction)).gap(gap).name(pname.clone());
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

    /// A number `≥ 0`, or a non-empty list of them (one per pair).
    fn per_pair(&self, t: &Table, k: &str, node: &Node, what: &str) -> Result<PerPair, InputError> {
        let check = |x: f64, pos: Option<Pos>, key: &str| {
            if x < 0.0 {
                Err(self.err(
                    pos,
                    key,
                    InputErrorKind::Value,
                    format!("{what} must be ≥ 0, got {x}"),
                ))
            } else {
                Ok(x)
            }
        };
        match &node.value {
            Value::Array(items) => {
                if items.is_empty() {
                    return Err(self.err(
                        node.pos,
                        &t.child(k),
                        InputErrorKind::Size,
                        format!("the list is empty: give {what} as a number, or one per pair"),
                    ));
                }
                let mut out = Vec::with_capacity(items.len());
                for (i, n) in items.iter().enumerate() {
                    let key = format!("{}[{}]", t.child(k), i + 1);
                    let x = self.doc.number(n, &key)?;
                    out.push((check(x, n.pos.or(node.pos), &key)?, n.pos));
                }
                Ok(PerPair::List(out))
            }
            _ => {
                let x = self.doc.number(node, &t.child(k))?;
                Ok(PerPair::One(check(x, node.pos, &t.child(k))?))
            }
        }
    }

    /// Today's pairing: each node of `from` with the node of `to` at the same position.
    fn coincident(
        &self,
        t: &Table,
        to_node: &Node,
        a_nodes: &[NodeId],
        b_nodes: &[NodeId],
        exclude: &HashSet<NodeId>,
        tol: f64,
    ) -> Result<Vec<Found>, InputError> {
        let coords = self.model.nodes();
        let b_idx: Vec<usize> = b_nodes.iter().map(|n| n.0).collect();
        let index = PointIndex::new(coords, &b_idx, tol);
        let mut pairs = Vec::new();
        for &a in a_nodes {
            if exclude.contains(&a) {
                continue;
            }
            let near: Vec<usize> = index
                .near(coords[a.0])
                .into_iter()
                .filter(|&b| b != a.0)
                .collect();
            match near.as_slice() {
                [b] => pairs.push(Found {
                    a: Endpoint::Node(a),
                    segment: None,
                    b: NodeId(*b),
                    at: coords[a.0],
                    surface_normal: None,
                }),
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
        Ok(pairs)
    }

    /// The segments of the surface `from`: a mesh's line groups by their own line elements (a
    /// closed loop keeps its closing segment, separate lines are not bridged); otherwise
    /// consecutive nodes of its (ordered) node list, so that a block's edge or a member is a
    /// surface. Either way only where an element joins the two nodes (an edge of a plane
    /// element, or a frame or bar), so that a break in the list is not bridged.
    fn segments(
        &self,
        t: &Table,
        from_node: &Node,
        from: &[Ref],
        chain: &[NodeId],
    ) -> Result<Vec<Segment>, InputError> {
        let candidates: Vec<(NodeId, NodeId)> =
            if from.iter().all(|r| self.surfaces.contains_key(&r.name)) {
                from.iter()
                    .flat_map(|r| &self.surfaces[&r.name].segments)
                    .map(|g| (self.final_of[g.nodes[0]], self.final_of[g.nodes[1]]))
                    .collect()
            } else {
                chain.windows(2).map(|w| (w[0], w[1])).collect()
            };
        let on: HashSet<NodeId> = chain.iter().copied().collect();
        let coords = self.model.nodes();
        // edge (sorted) → the centroids of the plane elements that have it (none for an edge
        // that only a frame or bar makes)
        let mut edges: HashMap<(NodeId, NodeId), Vec<[f64; 2]>> = HashMap::new();
        let key = |a: NodeId, b: NodeId| if a < b { (a, b) } else { (b, a) };
        for e in self.model.elements() {
            let (nodes, plane): (&[NodeId], bool) = match e {
                Element::Frame { nodes, .. } | Element::Bar { nodes, .. } => (nodes, false),
                Element::Plane { nodes, .. } => (nodes, true),
                Element::Triangle { nodes, .. } => (nodes, true),
            };
            if nodes.iter().filter(|n| on.contains(n)).count() < 2 {
                continue;
            }
            let c = nodes.len();
            let centroid = {
                let s = nodes.iter().fold([0.0, 0.0], |s, n| {
                    [s[0] + coords[n.0][0], s[1] + coords[n.0][1]]
                });
                [s[0] / c as f64, s[1] / c as f64]
            };
            let sides = if plane { c } else { 1 };
            for i in 0..sides {
                let (a, b) = (nodes[i], nodes[(i + 1) % c]);
                if on.contains(&a) && on.contains(&b) {
                    let entry = edges.entry(key(a, b)).or_default();
                    if plane {
                        entry.push(centroid);
                    }
                }
            }
        }
        let mut out = Vec::new();
        for (a1, a2) in candidates {
            let Some(inside) = edges.get(&key(a1, a2)) else {
                continue;
            };
            let d = sub(coords[a2.0], coords[a1.0]);
            let mut normal = unit([-d[1], d[0]]);
            let oriented = inside.len() == 1;
            if oriented {
                let mid = [
                    0.5 * (coords[a1.0][0] + coords[a2.0][0]),
                    0.5 * (coords[a1.0][1] + coords[a2.0][1]),
                ];
                if dot(normal, sub(mid, inside[0])) < 0.0 {
                    normal = [-normal[0], -normal[1]];
                }
            }
            out.push(Segment {
                a1,
                a2,
                normal,
                oriented,
            });
        }
        if out.is_empty() {
            return Err(self.err(
                from_node.pos,
                &t.child("from"),
                InputErrorKind::Invalid,
                "`from` is not a surface: no two consecutive nodes of it are joined by an \
                 element (use a block's edge such as `NAME.top`, a member, or a mesh's line \
                 group)"
                    .into(),
            ));
        }
        Ok(out)
    }

    /// Each node of `to` with its projection on the nearest segment within `search` (the
    /// segments are indexed by their midpoints, within `search` plus half the longest
    /// segment, so that no segment within `search` of a node is missed). A projection within
    /// the coincidence tolerance of a segment's end is that node (a node-to-node pair).
    fn on_surface(
        &self,
        segments: &[Segment],
        b_nodes: &[NodeId],
        exclude: &HashSet<NodeId>,
        search: f64,
        tol: f64,
    ) -> Vec<Found> {
        let coords = self.model.nodes();
        let mids: Vec<[f64; 2]> = segments
            .iter()
            .map(|s| {
                let (p, q) = (coords[s.a1.0], coords[s.a2.0]);
                [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]
            })
            .collect();
        let longest = segments.iter().fold(0.0f64, |l, s| {
            let d = sub(coords[s.a2.0], coords[s.a1.0]);
            l.max(d[0].hypot(d[1]))
        });
        let all: Vec<usize> = (0..segments.len()).collect();
        let index = PointIndex::new(&mids, &all, search + 0.5 * longest);
        // the normal at a surface node: the average of its segments' normals
        let mut at_node: HashMap<NodeId, ([f64; 2], bool)> = HashMap::new();
        for s in segments {
            for n in [s.a1, s.a2] {
                let e = at_node.entry(n).or_insert(([0.0, 0.0], true));
                // An unoriented segment's normal is its left-hand one, which depends on the
                // direction its line is walked in: two lines walked towards a shared node
                // would cancel there. It is taken on the side of the normals met so far.
                let sign = if !s.oriented && dot(e.0, s.normal) < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                e.0 = [e.0[0] + sign * s.normal[0], e.0[1] + sign * s.normal[1]];
                e.1 &= s.oriented;
            }
        }
        let mut out = Vec::new();
        for &b in b_nodes.iter().filter(|b| !exclude.contains(b)) {
            let pb = coords[b.0];
            // (distance, segment, ξ)
            let mut best: Option<(f64, usize, f64)> = None;
            for si in index.near(pb) {
                let s = &segments[si];
                if s.a1 == b || s.a2 == b {
                    continue;
                }
                let (p, q) = (coords[s.a1.0], coords[s.a2.0]);
                let d = sub(q, p);
                let xi = (dot(sub(pb, p), d) / dot(d, d)).clamp(0.0, 1.0);
                let at = [p[0] + xi * d[0], p[1] + xi * d[1]];
                let r = sub(pb, at);
                let dist = r[0].hypot(r[1]);
                if dist <= search && best.is_none_or(|(e, _, _)| dist < e) {
                    best = Some((dist, si, xi));
                }
            }
            let Some((_, si, xi)) = best else {
                continue;
            };
            let s = &segments[si];
            let len = {
                let d = sub(coords[s.a2.0], coords[s.a1.0]);
                d[0].hypot(d[1])
            };
            let end = if xi * len <= tol {
                Some(s.a1)
            } else if (1.0 - xi) * len <= tol {
                Some(s.a2)
            } else {
                None
            };
            let (segment, a, at, normal) = match end {
                Some(n) => {
                    let (v, oriented) = at_node[&n];
                    (None, n, coords[n.0], (oriented, v))
                }
                None => {
                    let (p, q) = (coords[s.a1.0], coords[s.a2.0]);
                    let at = [p[0] + xi * (q[0] - p[0]), p[1] + xi * (q[1] - p[1])];
                    (Some((s.a2, xi)), s.a1, at, (s.oriented, s.normal))
                }
            };
            // an unoriented normal (frames, inner edges) points to the side of B, when B is
            // off the surface
            let (oriented, v) = normal;
            let surface_normal = if v[0].hypot(v[1]) <= 1e-12 {
                None
            } else if oriented {
                Some(unit(v))
            } else {
                let side = dot(v, sub(pb, at));
                let off = tol * v[0].hypot(v[1]);
                if side > off {
                    Some(unit(v))
                } else if side < -off {
                    Some(unit([-v[0], -v[1]]))
                } else {
                    None
                }
            };
            out.push(Found {
                a: Endpoint::Node(a),
                segment,
                b,
                at,
                surface_normal,
            });
        }
        out
    }
}
