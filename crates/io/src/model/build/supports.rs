//! `[[supports]]` and `[[springs]]`.

use super::*;

impl Builder<'_> {
    pub(super) fn supports(&mut self, top: &Table) -> Result<(), InputError> {
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

    pub(super) fn springs(&mut self, top: &Table) -> Result<(), InputError> {
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
            if let SpringKind::Rotational { .. } = kind {
                let mut ends = nodes.clone();
                if let Endpoint::Node(n) = a {
                    ends.push(n);
                }
                self.turned(&t, "rotational", &ends, "a rotational spring")?;
            }
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
}
