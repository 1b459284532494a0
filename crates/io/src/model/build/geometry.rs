//! `[[nodes]]` and `[[node_sets]]`, and the names of nodes, sets and elements.

use super::*;

impl Builder<'_> {
    pub(super) fn new_proto(&mut self, xy: [f64; 2], name: String, pos: Option<Pos>) -> usize {
        let i = self.protos.len();
        self.protos.push(xy);
        self.proto_names.push(name.clone());
        self.merge.push();
        self.node_names.insert(name, (i, pos));
        i
    }

    pub(super) fn check_new_name(
        &self,
        name: &str,
        pos: Option<Pos>,
        key: &str,
    ) -> Result<(), InputError> {
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

    pub(super) fn add_set(
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

    pub(super) fn nodes(&mut self, top: &Table) -> Result<(), InputError> {
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

    pub(super) fn node_sets(&mut self, top: &Table) -> Result<(), InputError> {
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

    pub(super) fn object_name(&self, t: &Table, what: &str) -> Result<Ref, InputError> {
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

    pub(super) fn add_element(&mut self, p: Pending) -> Result<usize, InputError> {
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
}
