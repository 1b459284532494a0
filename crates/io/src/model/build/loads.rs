//! `[loads.NAME]`: the load cases (`constant` and `variable` for the paper's method, any name
//! with a `[[history]]`), each with nodal, distributed, body, settlement and temperature loads.

use super::*;

impl Builder<'_> {
    /// Reads `[loads.NAME]`. Without a history (`history` false) only the cases `constant`
    /// and `variable` are accepted and the variable one must load something, as in the
    /// paper's method; with one, any case. The cases are added to the model in file order.
    pub(super) fn loads(&mut self, top: &Table, history: bool) -> Result<(), InputError> {
        let Some(loads) = top.table("loads")? else {
            if history {
                return Ok(());
            }
            return Err(self.err(
                Some(Pos { line: 1, col: 1 }),
                "loads.variable",
                InputErrorKind::MissingKey,
                "the model has no variable load ([loads.variable]): it is the load multiplied by the parameter p".into(),
            ));
        };
        let names: Vec<String> = loads.entries.iter().map(|e| e.key.clone()).collect();
        if !history {
            if let Some(e) = names
                .iter()
                .find_map(|n| crate::history::case_without_history(&loads, n))
            {
                return Err(e);
            }
        }
        let cases: Vec<CaseId> = names.iter().map(|n| self.model.add_case(n)).collect();
        let mut any_variable = false;
        for (k, group) in names.iter().zip(cases) {
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
            if k == "variable" && self.model_load_count() > before {
                any_variable = true;
            }
        }
        if !any_variable && !history {
            return Err(self.err(
                loads.pos,
                "loads.variable",
                InputErrorKind::MissingKey,
                "the model has no variable load ([loads.variable]): it is the load multiplied by the parameter p".into(),
            ));
        }
        Ok(())
    }

    pub(super) fn model_load_count(&self) -> usize {
        self.load_count
    }

    pub(super) fn push_load(&mut self, case: CaseId, load: Load) {
        self.model.add_case_load(case, load);
        self.load_count += 1;
    }

    pub(super) fn distributed(&mut self, t: &Table, group: CaseId) -> Result<(), InputError> {
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
            Element::Plane { .. } | Element::Triangle { .. } => None,
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

    pub(super) fn settlement(&mut self, t: &Table, group: CaseId) -> Result<(), InputError> {
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

    pub(super) fn model_has_support(&self, node: NodeId, dof: SupportDof) -> bool {
        self.supported.iter().any(|&(n, d)| n == node && d == dof)
    }
}

fn dof_word(d: SupportDof) -> &'static str {
    d.label()
        .map_or("inclined", unilateral_fem::DofLabel::as_str)
}
