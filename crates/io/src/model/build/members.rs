//! `[[members]]`: frames and bars divided into elements along a segment.

use super::*;

impl Builder<'_> {
    /// A member end: coordinates, or an existing node (the member then ends on that node).
    pub(super) fn member_end(
        &mut self,
        t: &Table,
        k: &str,
    ) -> Result<Result<[f64; 2], usize>, InputError> {
        let node = t.require(k, "a point [x, y] or the id of an existing node")?;
        if matches!(node.value, Value::Array(_)) {
            return Ok(Ok(vec2(self.doc, node, &t.child(k))?));
        }
        let r = id(self.doc, node, &t.child(k))?;
        Ok(Err(self.one_proto(&r)?))
    }

    pub(super) fn members(&mut self, top: &Table) -> Result<(), InputError> {
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
            let points = divide_segment(pa, pb, n);
            let mut nodes = Vec::with_capacity(n + 1);
            for (k, &xy) in points.iter().enumerate() {
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
                    None => self.new_proto(xy, node_name, name.pos),
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
}
