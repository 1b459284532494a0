//! Reading structural models: the examples, JSON = TOML, structured meshes, node sets,
//! `connect_to`, supports on sets, springs and every load kind.

use std::path::Path;

use unilateral_fem::Element;
use unilateral_io::{is_structural_model, read_model, read_problem, Problem};

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

#[test]
fn examples_read_and_problem_kinds_are_told_apart() {
    for f in [
        "example1-beam.toml",
        "example2-cantilever.toml",
        "example3-sheet-pile.toml",
    ] {
        let path = examples().join(f);
        assert!(is_structural_model(&path), "{f}");
        assert!(matches!(
            read_problem(&path).unwrap(),
            Problem::Structural(_)
        ));
    }
    let zone = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/good/example1.toml");
    assert!(!is_structural_model(&zone));
    assert!(matches!(
        read_problem(&zone).unwrap(),
        Problem::ContactZone(_)
    ));
    let p = read_model(&examples().join("example3-sheet-pile.toml")).unwrap();
    assert_eq!(p.model.pairs().len(), 24);
    assert_eq!(p.model.names().pairs[0], "left.1");
    assert_eq!(p.model.names().node_sets["soil_left.right"].len(), 13);
    assert_eq!(p.model.names().element_sets["soil_right"].len(), 144);
    assert_eq!(
        p.model
            .names()
            .element(p.model.names().element_sets["wall"][0]),
        "wall.1"
    );
}

#[test]
fn json_reads_like_toml() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("beam.json");
    std::fs::write(
        &path,
        r#"{
  "sections": [{"name": "beam", "E": 1.0, "A": 2.0, "I": 1.0}],
  "nodes": [{"id": "A", "x": 0, "y": 0}, {"id": "B", "x": 2, "y": 0},
            {"id": "P", "x": 3, "y": 0}, {"id": "C", "x": 4, "y": 0}],
  "elements": [
    {"id": "AB", "type": "frame", "nodes": ["A", "B"], "section": "beam"},
    {"id": "BP", "type": "frame", "nodes": ["B", "P"], "section": "beam"},
    {"id": "PC", "type": "frame", "nodes": ["P", "C"], "section": "beam"}],
  "contact": [{"name": "support", "from": "ground", "to": ["A", "B", "C"],
               "normal": [0, 1], "friction": 0.6}],
  "loads": {"variable": {"nodal": [{"nodes": "P", "fy": -1.0}]}},
  "solve": {"tightening": 1.0, "target": 1.0, "trace": "end"}
}"#,
    )
    .unwrap();
    let j = read_model(&path).unwrap();
    let t = read_model(&examples().join("example1-beam.toml")).unwrap();
    assert_eq!(j.model.nodes(), t.model.nodes());
    assert_eq!(j.model.elements(), t.model.elements());
    assert_eq!(j.model.pairs(), t.model.pairs());
    assert_eq!(j.settings, t.settings);
    assert_eq!(j.model.names().nodes, t.model.names().nodes);
    assert_eq!(j.model.names().pairs, t.model.names().pairs);
}

#[test]
fn meshes_sets_connections_and_loads() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model.toml");
    std::fs::write(
        &path,
        r#"
[[materials]]
name = "soil"
E = 1e7
nu = 0.3

[[sections]]
name = "col"
E = 2e11
A = 1e-2
I = 1e-4
depth = 0.3
alpha = 1.2e-5

[[blocks]]
name = "ground"
origin = [0, 0]
width = 2
height = 1
nx = 4
ny = 2
material = "soil"
analysis = "plane_strain"

[[blocks]]
name = "upper"             # touches `ground` along y = 1 and is merged with it there
origin = [0, 1]
width = 2
height = 1
nx = 4
ny = 1
material = "soil"
analysis = "plane_stress"
formulation = "Q4"
connect_to = "ground.top"

[[members]]
name = "post"              # starts on an existing node: shares it
start = "upper.top_left"
end = [0, 4]
divisions = 2
section = "col"
releases = ["end"]

[[node_sets]]
name = "middle"
box = [[0.9, -1], [1.1, 10]]
within = "ground"

[[node_sets]]
name = "ends"
nodes = ["post.end", "upper.top_right"]

[[supports]]
nodes = "ground.bottom"
fixed = true

[[supports]]
nodes = ["ground.left", "ground.right"]
ux = true

[[springs]]
nodes = "post.end"
direction = [1, 0]
stiffness = 1e5

[[springs]]
nodes = "post.1"           # a rotational spring needs nodes a frame turns (post.end is hinged)
to = "post.0"
rotational = true
stiffness = 10

[[contact]]
name = "tip"
from = "ground"
to = "upper.top_right"
normal = [0, 1]
friction = 0.2
gap = 0.001

[[loads.constant.body]]
elements = ["ground", "upper"]
force = [0, -18e3]

[[loads.constant.temperature]]
elements = "post"
uniform = 10
gradient = 5

[[loads.variable.distributed]]
elements = "post"
start = [0, 0]
end = [1000, 0]
frame = "local"

[[loads.variable.nodal]]
nodes = "ends"
fx = 1.0
"#,
    )
    .unwrap();
    let p = read_model(&path).unwrap();
    let n = p.model.names();
    // ground: 5 × 3 nodes; upper: 5 × 2, its bottom row merged with ground.top; post: 2 new.
    assert_eq!(p.model.nodes().len(), 15 + 5 + 2);
    assert_eq!(n.node_id("upper.0.0"), n.node_id("ground.0.2"));
    assert_eq!(n.node_id("post.0"), n.node_id("upper.0.1"));
    assert_ne!(n.node_id("post.end"), n.node_id("upper.top_left"));
    assert_eq!(n.node_sets["middle"].len(), 3);
    for id in &n.node_sets["middle"] {
        assert!((p.model.nodes()[id.0][0] - 1.0).abs() < 1e-12);
    }
    assert_eq!(n.node_sets["ends"].len(), 2);
    // Elements: 8 + 4 plane, 2 frames; release only at the member's far end.
    assert_eq!(p.model.elements().len(), 14);
    let post: Vec<_> = n.element_sets["post"]
        .iter()
        .map(|e| &p.model.elements()[e.0])
        .collect();
    match (post[0], post[1]) {
        (Element::Frame { releases: r0, .. }, Element::Frame { releases: r1, .. }) => {
            assert!(!r0.start && !r0.end && !r1.start && r1.end);
        }
        _ => panic!("post must be frames"),
    }
    // The linearly varying load is interpolated along the member: 0 → 500 → 1000.
    let model_debug = format!("{:?}", p.model);
    assert!(model_debug.contains("start: [500.0, 0.0]"));
    let c = p.model.condense().unwrap();
    assert_eq!(c.pair_names, vec!["tip".to_string()]);
    assert_eq!(c.gap, vec![0.001]);
    // Loads: body force on 12 plane elements and temperature on 2 frames (constant),
    // distributed on 2 frames and nodal on 2 nodes (variable).
    let dbg = model_debug.matches("BodyForce").count();
    assert_eq!(dbg, 12);
    assert_eq!(model_debug.matches("Temperature").count(), 2);
}
