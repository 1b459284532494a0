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
                if m != 0.0 {
                    self.turned(&t, "m", &nodes, "a moment")?;
                }
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
        // Linear variation with the distance along the chain the listed elements make (e.g. a
        // member's elements): from `start` at its free end whose element is listed first to
        // `end` at the other ([`chain_positions`]; one element: from its first node to its
        // second).
        let ends = |e: ElementId| match &self.model.elements()[e.0] {
            Element::Frame { nodes, .. } | Element::Bar { nodes, .. } => Some(*nodes),
            Element::Plane { .. } | Element::Triangle { .. } => None,
        };
        let mut chain = Vec::with_capacity(elems.len());
        for &e in &elems {
            match ends(e) {
                Some(n) => chain.push((e, n[0], n[1])),
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
        let lerp = |s: f64| [qa[0] + s * (qb[0] - qa[0]), qa[1] + s * (qb[1] - qa[1])];
        let at: Vec<(f64, f64)> = if chain.len() == 1 {
            vec![(0.0, 1.0)]
        } else if qa == qb {
            vec![(0.0, 0.0); chain.len()]
        } else {
            let ends: Vec<(NodeId, NodeId)> = chain.iter().map(|&(_, a, b)| (a, b)).collect();
            let ids: Vec<usize> = chain.iter().map(|&(e, _, _)| e.0).collect();
            match chain_positions(self.model.nodes(), &ids, &ends) {
                Ok(at) => at,
                Err(problem) => {
                    let name = |i: usize| self.pending[chain[i].0 .0].name.clone();
                    let node = |n: NodeId| self.node_name(n);
                    let why = match problem {
                        ChainProblem::Repeated(i) => format!("element `{}` is listed twice", name(i)),
                        ChainProblem::Branch(n) => format!(
                            "the listed elements branch at node `{}` (list each branch as a load of its own)",
                            node(n)
                        ),
                        ChainProblem::Loop => "the listed elements close a loop".to_string(),
                        ChainProblem::Apart { element, start } => format!(
                            "element `{}` is not connected to the chain that starts at element `{}`",
                            name(element),
                            name(start)
                        ),
                    };
                    return Err(self.err(
                        t.get("elements").and_then(|n| n.pos),
                        &t.child("elements"),
                        InputErrorKind::Invalid,
                        format!(
                            "a load varying from `start` to `end` needs one unbranched chain of elements, joined at shared nodes: {why}"
                        ),
                    ));
                }
            }
        };
        for (&(element, _, _), &(sa, sb)) in chain.iter().zip(&at) {
            self.push_load(
                group,
                Load::Distributed {
                    element,
                    start: lerp(sa),
                    end: lerp(sb),
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
        if dof == SupportDof::Rz && value != 0.0 {
            self.turned(t, "value", &nodes, "a prescribed rotation")?;
        }
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

    /// Refuses `what` (a moment, a rotational spring, a prescribed rotation) at key `key` of
    /// `t` on a node that no frame turns ([`unilateral_fem::Model::rotating_nodes`]): it would
    /// act on nothing (a moment there made a false "unstable at rz"; a prescribed rotation was
    /// reported as the node's rotation).
    pub(super) fn turned(
        &self,
        t: &Table,
        key: &str,
        nodes: &[NodeId],
        what: &str,
    ) -> Result<(), InputError> {
        let turns = self.model.rotating_nodes();
        if let Some(&node) = nodes
            .iter()
            .find(|n| !turns.get(n.0).copied().unwrap_or(false))
        {
            return Err(self.err(
                t.get(key).and_then(|v| v.pos).or(t.pos),
                &t.child(key),
                InputErrorKind::Invalid,
                format!(
                    "{what} at node `{}`, which no frame turns (plane elements and bars have no \
                     rotation, nor a frame's hinged end): it would act on nothing",
                    self.node_name(node)
                ),
            ));
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

/// Why listed line elements are not one chain ([`chain_positions`]); indices into the list.
#[derive(Debug, PartialEq)]
enum ChainProblem {
    /// The same element twice.
    Repeated(usize),
    /// Three or more listed elements meet at a node.
    Branch(NodeId),
    /// Every node joins two listed elements.
    Loop,
    /// `element` is not reached from the chain's start, the free end of element `start`.
    Apart { element: usize, start: usize },
}

/// The place of each listed line element's first and second node along the chain the
/// elements make (joined where they share a node), as the fraction of the chain's length from
/// the chain's start: of its two free ends, the one whose element comes first in the list (a
/// member listed whole starts where its first element does; two members drawn away from a
/// shared node start at the free end of the first one listed). What a load varying linearly
/// along the chain takes at each element's ends. `ids` are the elements (each at most once),
/// `ends` their nodes in their own order.
fn chain_positions(
    nodes: &[[f64; 2]],
    ids: &[usize],
    ends: &[(NodeId, NodeId)],
) -> Result<Vec<(f64, f64)>, ChainProblem> {
    let mut seen = std::collections::HashSet::new();
    if let Some(i) = ids.iter().position(|&e| !seen.insert(e)) {
        return Err(ChainProblem::Repeated(i));
    }
    // The elements at each node.
    let mut at: HashMap<usize, Vec<usize>> = HashMap::new();
    for (i, &(a, b)) in ends.iter().enumerate() {
        at.entry(a.0).or_default().push(i);
        at.entry(b.0).or_default().push(i);
    }
    let mut branched: Vec<usize> = at
        .iter()
        .filter(|(_, es)| es.len() > 2)
        .map(|(&n, _)| n)
        .collect();
    branched.sort_unstable();
    if let Some(&n) = branched.first() {
        return Err(ChainProblem::Branch(NodeId(n)));
    }
    // The free end whose element is listed first (the lower node for an element whose both
    // ends are free: its own first node).
    let Some((start, first)) = ends
        .iter()
        .enumerate()
        .flat_map(|(i, &(a, b))| [(a, i), (b, i)])
        .find(|(n, _)| at[&n.0].len() == 1)
    else {
        return Err(ChainProblem::Loop);
    };
    // Walk the chain from its start: the distance of every node reached.
    let length = |a: NodeId, b: NodeId| {
        let (p, q) = (nodes[a.0], nodes[b.0]);
        (q[0] - p[0]).hypot(q[1] - p[1])
    };
    let mut dist: HashMap<usize, f64> = HashMap::from([(start.0, 0.0)]);
    let (mut node, mut from, mut s) = (start, usize::MAX, 0.0);
    while let Some(&e) = at[&node.0].iter().find(|&&e| e != from) {
        let (a, b) = ends[e];
        let next = if a == node { b } else { a };
        s += length(node, next);
        dist.insert(next.0, s);
        (node, from) = (next, e);
    }
    if let Some(i) = ends.iter().position(|(a, _)| !dist.contains_key(&a.0)) {
        return Err(ChainProblem::Apart {
            element: i,
            start: first,
        });
    }
    let frac = |n: NodeId| if s > 0.0 { dist[&n.0] / s } else { 0.0 };
    Ok(ends.iter().map(|&(a, b)| (frac(a), frac(b))).collect())
}

#[cfg(test)]
mod tests {
    use super::{chain_positions, ChainProblem};
    use unilateral_fem::NodeId;

    fn ids(pairs: &[(usize, usize)]) -> Vec<(NodeId, NodeId)> {
        pairs.iter().map(|&(a, b)| (NodeId(a), NodeId(b))).collect()
    }

    /// The elements numbered as listed.
    fn at(nodes: &[[f64; 2]], pairs: &[(usize, usize)]) -> Result<Vec<(f64, f64)>, ChainProblem> {
        let elements: Vec<usize> = (0..pairs.len()).collect();
        chain_positions(nodes, &elements, &ids(pairs))
    }

    /// Positions by the distance along the chain, whatever the elements' own directions and
    /// the order they are listed in; a bent chain by its length, not its chord.
    #[test]
    fn positions_along_a_chain() {
        // nodes 0 (0,0), 1 (2,0), 2 (4,0), 3 (4,4): a beam of two elements and a post
        let nodes = [[0.0, 0.0], [2.0, 0.0], [4.0, 0.0], [4.0, 4.0]];
        assert_eq!(
            at(&nodes, &[(0, 1), (1, 2)]).unwrap(),
            vec![(0.0, 0.5), (0.5, 1.0)]
        );
        // listed from the other end: the chain starts at node 2
        assert_eq!(
            at(&nodes, &[(1, 2), (0, 1)]).unwrap(),
            vec![(0.5, 0.0), (1.0, 0.5)]
        );
        // the first element drawn backwards, the second listed before the third; length 8
        assert_eq!(
            at(&nodes, &[(1, 0), (3, 2), (1, 2)]).unwrap(),
            vec![(0.25, 0.0), (1.0, 0.5), (0.25, 0.5)]
        );
        // two members drawn away from node 1, listed whole: (1,0) then (1,2),(2,3); the first
        // listed element is inside the chain, the free end listed first is node 0
        assert_eq!(
            at(&nodes, &[(1, 0), (1, 2), (2, 3)]).unwrap(),
            vec![(0.25, 0.0), (0.25, 0.5), (0.5, 1.0)]
        );
        // the same members listed the other way: the chain starts at node 3
        assert_eq!(
            at(&nodes, &[(1, 2), (2, 3), (1, 0)]).unwrap(),
            vec![(0.75, 0.5), (0.5, 0.0), (0.75, 1.0)]
        );
    }

    #[test]
    fn what_is_not_a_chain() {
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [1.0, 1.0],
            [5.0, 0.0],
            [6.0, 0.0],
        ];
        // the same element twice
        assert_eq!(
            chain_positions(&nodes, &[7, 8, 7], &ids(&[(0, 1), (1, 2), (0, 1)])),
            Err(ChainProblem::Repeated(2))
        );
        // two elements on the same two nodes: a loop, not a repeat
        assert_eq!(at(&nodes, &[(0, 1), (1, 0)]), Err(ChainProblem::Loop));
        assert_eq!(
            at(&nodes, &[(0, 1), (1, 2), (1, 3)]),
            Err(ChainProblem::Branch(NodeId(1)))
        );
        assert_eq!(
            at(&nodes, &[(0, 1), (1, 3), (3, 0)]),
            Err(ChainProblem::Loop)
        );
        assert_eq!(
            at(&nodes, &[(0, 1), (1, 2), (4, 5)]),
            Err(ChainProblem::Apart {
                element: 2,
                start: 0
            })
        );
        // a loop beside a chain: the chain starts at its own free end and the loop is apart
        assert_eq!(
            at(&nodes, &[(0, 1), (1, 3), (3, 0), (4, 5)]),
            Err(ChainProblem::Apart {
                element: 0,
                start: 3
            })
        );
    }
}
