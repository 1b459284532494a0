//! `[[elements]]`: elements given node by node.

use super::*;

impl Builder<'_> {
    pub(super) fn explicit_elements(&mut self, top: &Table) -> Result<(), InputError> {
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
            let ty = choice(
                &t,
                "type",
                &["frame", "bar", "plane", "triangle"],
                None,
                "element type",
            )?;
            let count = match ty {
                "plane" => 4,
                "triangle" => 3,
                _ => 2,
            };
            let nodes_node = t.require("nodes", "the element's node ids")?;
            let rs = refs(self.doc, nodes_node, &t.child("nodes"))?;
            if rs.len() != count {
                return Err(self.err(
                    nodes_node.pos,
                    &t.child("nodes"),
                    InputErrorKind::Size,
                    format!(
                        "a {ty} element has {count} nodes{}, found {}",
                        match ty {
                            "plane" => " (counter-clockwise)",
                            "triangle" => " (in either order)",
                            _ => "",
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
                "triangle" => {
                    forbid("section", "plane elements take a `material`")?;
                    forbid("releases", "plane elements have no end moments")?;
                    forbid(
                        "formulation",
                        "the triangle has one formulation, constant strain",
                    )?;
                    let m = self.material(&t)?;
                    let (a, _) = self.plane_options(&t)?;
                    Kind::Triangle(m, a)
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
}
