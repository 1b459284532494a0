//! The names of a model's items, as a model file gives them.

use crate::model::{ElementId, NodeId};
use std::collections::BTreeMap;

/// The names of a model's nodes, elements, contact pairs and sets, indexed by the
/// finite-element ids. Items without a name are named by their 0-based index.
///
/// ```
/// use unilateral_fem::{Names, NodeId};
/// let mut names = Names::default();
/// names.nodes = vec!["A".into(), "B".into()];
/// names.node_sets.insert("beam.end".into(), vec![NodeId(1)]);
/// assert_eq!(names.node(NodeId(1)), "B");
/// assert_eq!(names.node(NodeId(7)), "7");
/// assert_eq!(names.node_id("beam.end"), Some(NodeId(1)));
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Names {
    /// Name of node `NodeId(i)` (for merged nodes: the first name given).
    pub nodes: Vec<String>,
    /// Name of element `ElementId(i)`.
    pub elements: Vec<String>,
    /// Name of contact pair `i` (as in `Model::pairs`).
    pub pairs: Vec<String>,
    /// Every named node set (block edges, member nodes, `[[node_sets]]`), in the set's order.
    pub node_sets: BTreeMap<String, Vec<NodeId>>,
    /// Elements of every block and member, by its name.
    pub element_sets: BTreeMap<String, Vec<ElementId>>,
    /// Every node name (including the other names of merged nodes) → node.
    pub node_ids: BTreeMap<String, NodeId>,
}

impl Names {
    /// The name of a node (its number when it has none).
    pub fn node(&self, id: NodeId) -> String {
        self.nodes
            .get(id.0)
            .cloned()
            .unwrap_or_else(|| id.0.to_string())
    }

    /// The name of an element (its number when it has none).
    pub fn element(&self, id: ElementId) -> String {
        self.elements
            .get(id.0)
            .cloned()
            .unwrap_or_else(|| id.0.to_string())
    }

    /// The node a name refers to: a node's name, or a set of exactly one node
    /// (`beam.end`, `soil.top_left`).
    pub fn node_id(&self, name: &str) -> Option<NodeId> {
        self.node_ids.get(name).copied().or_else(|| {
            self.node_sets
                .get(name)
                .filter(|s| s.len() == 1)
                .map(|s| s[0])
        })
    }

    /// The nodes of a named set (or the single node of that name).
    pub fn set(&self, name: &str) -> Option<Vec<NodeId>> {
        self.node_sets
            .get(name)
            .cloned()
            .or_else(|| self.node_id(name).map(|n| vec![n]))
    }
}
