//! `[[contact]]`: contact pairs, to the ground or between coincident nodes of two bodies.

use super::*;

impl Builder<'_> {
    pub(super) fn contact(&mut self, top: &Table) -> Result<(), InputError> {
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
}
