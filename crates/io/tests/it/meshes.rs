//! `[[meshes]]`: Gmsh meshes read into structural models.
//!
//! References: what Gmsh's own API says of the meshes `tests/data/gmsh/make_blocks.py` wrote
//! (`block_expected.txt`: the nodes elements use, the 2D elements, each group's nodes in order),
//! the same rectangle built as a `[[blocks]]` grid (the same nodes: the same analysis), the mesh
//! with every element written clockwise (turned back: the same analysis), and for the bad meshes
//! the line of the `.msh` text (found by searching the text the test itself wrote).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use unilateral_analysis::{analyze, Analysis};
use unilateral_fem::{Element, Model, NodeId};
use unilateral_io::{read_model, InputErrorKind, StructuralProblem};

fn gmsh_dir() -> PathBuf {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/gmsh");
    assert!(d.is_dir(), "{} is missing", d.display());
    d
}

/// One mesh of `block_expected.txt`.
#[derive(Default)]
struct Expected {
    /// Node tag → coordinates (the nodes 2D elements use).
    nodes: BTreeMap<usize, [f64; 2]>,
    /// 2D element tag → node tags.
    elements: BTreeMap<usize, Vec<usize>>,
    /// (dimension, label) → node tags, in Gmsh's order.
    groups: Vec<(usize, String, Vec<usize>)>,
}

fn expected(mesh: &str) -> Expected {
    let text = std::fs::read_to_string(gmsh_dir().join("block_expected.txt")).unwrap();
    let mut out = Expected::default();
    let mut inside = false;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let w: Vec<&str> = line.split_whitespace().collect();
        let nums =
            |from: usize| -> Vec<usize> { w[from..].iter().map(|x| x.parse().unwrap()).collect() };
        match w[0] {
            "mesh" => inside = w[1] == mesh,
            _ if !inside => {}
            "node" => {
                out.nodes.insert(
                    w[1].parse().unwrap(),
                    [w[2].parse().unwrap(), w[3].parse().unwrap()],
                );
            }
            "element" => {
                out.elements.insert(w[1].parse().unwrap(), nums(2));
            }
            "group" => {
                let label = if w[3] == "-" { w[2] } else { w[3] };
                out.groups
                    .push((w[1].parse().unwrap(), label.to_string(), nums(4)));
            }
            _ => panic!("unexpected line {line}"),
        }
    }
    assert!(
        !out.nodes.is_empty(),
        "no mesh {mesh} in block_expected.txt"
    );
    out
}

/// Writes `model` (and the files `extra`) into a fresh directory and reads it.
fn read(
    model: &str,
    extra: &[(&str, &str)],
) -> (
    tempfile::TempDir,
    Result<StructuralProblem, unilateral_io::InputError>,
) {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in extra {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    for f in ["block_tri_41.msh", "block_quad_22.msh"] {
        std::fs::copy(gmsh_dir().join(f), dir.path().join(f)).unwrap();
    }
    let path = dir.path().join("model.toml");
    std::fs::write(&path, model).unwrap();
    let r = read_model(&path);
    (dir, r)
}

const MATERIAL: &str = r#"
[[materials]]
name = "steel"
E = 2.0e5
nu = 0.3
thickness = 0.1
"#;

/// A block on rigid ground: pairs under every node of `bottom`, pressed down and pushed along.
fn on_ground(mesh_lines: &str) -> String {
    format!(
        r#"{MATERIAL}
[[meshes]]
{mesh_lines}

[[contact]]
from = "ground"
to = "blk.bottom"
normal = [0.0, 1.0]
friction = 0.5

[[loads.constant.nodal]]
nodes = "blk.top"
fy = -10.0

[[loads.variable.nodal]]
nodes = "blk.tip"
fx = 1.0
"#
    )
}

fn check_against_gmsh(p: &StructuralProblem, file: &str, quads: bool) {
    let exp = expected(file);
    let model = &p.model;
    let names = model.names();
    // Nodes: exactly those elements use, named `blk.<tag>`, at Gmsh's coordinates.
    assert_eq!(model.nodes().len(), exp.nodes.len());
    for (tag, xy) in &exp.nodes {
        let id = names.node_ids[&format!("blk.{tag}")];
        // the `.msh` file writes 16 significant digits, Gmsh's API gives 17: equal to the
        // round-off of the last written digit (of the extent, 4)
        let got = model.nodes()[id.0];
        assert!(
            (got[0] - xy[0]).abs() <= 4e-15 && (got[1] - xy[1]).abs() <= 4e-15,
            "node {tag}: {got:?} vs {xy:?}"
        );
    }
    // Elements: Gmsh's 2D elements, named `blk.<tag>`, on the same nodes, counter-clockwise.
    // (MSH 2.2 numbers the elements anew, so they are compared by their nodes.)
    assert_eq!(model.elements().len(), exp.elements.len());
    let tag_of = |n: &NodeId| -> usize {
        names.nodes[n.0]
            .strip_prefix("blk.")
            .unwrap()
            .parse()
            .unwrap()
    };
    let mut got: Vec<Vec<usize>> = Vec::new();
    for (i, e) in model.elements().iter().enumerate() {
        let nodes: Vec<NodeId> = match e {
            Element::Triangle { nodes, .. } if !quads => nodes.to_vec(),
            Element::Plane { nodes, .. } if quads => nodes.to_vec(),
            other => panic!("unexpected element {other:?}"),
        };
        let xy: Vec<[f64; 2]> = nodes.iter().map(|n| model.nodes()[n.0]).collect();
        let k = xy.len();
        let area2: f64 = (0..k)
            .map(|j| xy[j][0] * xy[(j + 1) % k][1] - xy[(j + 1) % k][0] * xy[j][1])
            .sum();
        assert!(
            area2 > 0.0,
            "element {} is not counter-clockwise",
            names.elements[i]
        );
        let mut tags: Vec<usize> = nodes.iter().map(tag_of).collect();
        tags.sort_unstable();
        got.push(tags);
    }
    let mut want: Vec<Vec<usize>> = exp
        .elements
        .values()
        .map(|v| {
            let mut v = v.clone();
            v.sort_unstable();
            v
        })
        .collect();
    want.sort();
    got.sort();
    assert_eq!(got, want);
    assert_eq!(names.element_sets["blk"].len(), exp.elements.len());
    assert_eq!(names.element_sets["blk.body"].len(), exp.elements.len());
    // Node sets: every group, in Gmsh's order (ascending tags; along the line for curves).
    for (dim, label, tags) in &exp.groups {
        let set: Vec<usize> = names.node_sets[&format!("blk.{label}")]
            .iter()
            .map(|n| {
                names.nodes[n.0]
                    .strip_prefix("blk.")
                    .unwrap()
                    .parse()
                    .unwrap()
            })
            .collect();
        assert_eq!(&set, tags, "group {label} (dimension {dim})");
    }
    let all: Vec<usize> = exp.nodes.keys().copied().collect();
    let set: Vec<usize> = names.node_sets["blk.nodes"]
        .iter()
        .map(|n| {
            names.nodes[n.0]
                .strip_prefix("blk.")
                .unwrap()
                .parse()
                .unwrap()
        })
        .collect();
    assert_eq!(set, all);
    // One pair per node of `bottom`, in its order.
    let bottom = &exp.groups.iter().find(|g| g.1 == "bottom").unwrap().2;
    assert_eq!(model.pairs().len(), bottom.len());
}

#[test]
fn triangles_from_msh41_match_gmsh() {
    let (_d, r) = read(
        &on_ground(
            "name = \"blk\"\nfile = \"block_tri_41.msh\"\nanalysis = \"plane_stress\"\nmaterial = \"steel\"",
        ),
        &[],
    );
    check_against_gmsh(&r.unwrap(), "block_tri_41.msh", false);
}

#[test]
fn quadrangles_from_msh22_match_gmsh() {
    let (_d, r) = read(
        &on_ground(
            "name = \"blk\"\nfile = \"block_quad_22.msh\"\nanalysis = \"plane_stress\"\nmaterials = { body = \"steel\" }\nformulation = \"Q4\"",
        ),
        &[],
    );
    check_against_gmsh(&r.unwrap(), "block_quad_22.msh", true);
}

/// A cantilever 4 × 1, clamped on the left, propped at the lower right corner by a frictional
/// contact with the ground, loaded down at the upper right corner.
fn cantilever(body: &str, left: &str, prop: &str, tip: &str) -> String {
    format!(
        r#"{MATERIAL}
{body}

[[supports]]
nodes = "{left}"
pinned = true

[[contact]]
from = "ground"
to = "{prop}"
normal = [0.0, 1.0]
friction = 0.3
gap = 1e-4

[[loads.constant.nodal]]
nodes = "{tip}"
fx = -20.0

[[loads.variable.nodal]]
nodes = "{tip}"
fy = -100.0

[solve]
target = 1.0
"#
    )
}

fn run(p: &StructuralProblem) -> Analysis {
    analyze(&p.model, &p.settings).unwrap()
}

/// Displacements by position, pair forces, and element stresses by element centre.
fn compare(a: &Analysis, b: &Analysis, ma: &Model, mb: &Model) {
    let (ra, rb) = (a.results.as_ref().unwrap(), b.results.as_ref().unwrap());
    let umax = ra
        .displacements
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(umax > 0.0);
    assert_eq!(ma.nodes().len(), mb.nodes().len());
    for (i, xa) in ma.nodes().iter().enumerate() {
        let j = mb
            .nodes()
            .iter()
            .position(|xb| (xb[0] - xa[0]).hypot(xb[1] - xa[1]) < 1e-9)
            .expect("the same node");
        for k in 0..2 {
            let (u, v) = (ra.displacements[i][k], rb.displacements[j][k]);
            assert!((u - v).abs() <= 1e-9 * umax, "node at {xa:?}: {u} vs {v}");
        }
    }
    assert_eq!(a.solution.pairs.len(), b.solution.pairs.len());
    for (p, q) in a.solution.pairs.iter().zip(&b.solution.pairs) {
        let f = p.x_n.abs().max(p.x_t.abs());
        assert!(f > 0.0);
        assert!((p.x_n - q.x_n).abs() <= 1e-9 * f && (p.x_t - q.x_t).abs() <= 1e-9 * f);
        assert_eq!(p.state, q.state);
    }
    let smax = ra
        .planes
        .iter()
        .flat_map(|e| e.stress.iter().flatten())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let centre = |g: &[[f64; 2]; 4]| {
        [
            g.iter().map(|p| p[0]).sum::<f64>() / 4.0,
            g.iter().map(|p| p[1]).sum::<f64>() / 4.0,
        ]
    };
    for ea in &ra.planes {
        let ca = centre(&ea.gauss_points);
        let eb = rb
            .planes
            .iter()
            .find(|e| {
                let c = centre(&e.gauss_points);
                (c[0] - ca[0]).hypot(c[1] - ca[1]) < 1e-9
            })
            .expect("the same element");
        // the mean of the Gauss points' stresses does not depend on where the corners start
        for k in 0..4 {
            let sa: f64 = ea.stress.iter().map(|s| s[k]).sum();
            let sb: f64 = eb.stress.iter().map(|s| s[k]).sum();
            assert!((sa - sb).abs() <= 4e-9 * smax, "element at {ca:?}");
        }
    }
}

#[test]
fn a_quadrangle_mesh_analyses_as_the_same_block() {
    let mesh = "[[meshes]]\nname = \"m\"\nfile = \"block_quad_22.msh\"\nanalysis = \"plane_stress\"\nmaterial = \"steel\"";
    let (_d, a) = read(&cantilever(mesh, "m.left", "m.2", "m.tip"), &[]);
    let block = "[[blocks]]\nname = \"b\"\norigin = [0.0, 0.0]\nwidth = 4.0\nheight = 1.0\nnx = 8\nny = 2\nmaterial = \"steel\"\nanalysis = \"plane_stress\"";
    let (_e, b) = read(&cantilever(block, "b.left", "b.8.0", "b.8.2"), &[]);
    let (a, b) = (a.unwrap(), b.unwrap());
    let (ra, rb) = (run(&a), run(&b));
    // the prop closes under the load: the comparison covers contact
    assert!(ra.solution.pairs[0].x_n > 0.0);
    compare(&ra, &rb, &a.model, &b.model);
}

#[test]
fn clockwise_elements_are_turned_counter_clockwise() {
    // Reference: the same mesh as Gmsh wrote it (counter-clockwise).
    let text = std::fs::read_to_string(gmsh_dir().join("block_quad_22.msh")).unwrap();
    let mut inside = false;
    let mut turned = 0;
    let reversed: Vec<String> = text
        .lines()
        .map(|l| {
            inside = match l {
                "$Elements" => true,
                "$EndElements" => false,
                _ => inside,
            };
            let w: Vec<&str> = l.split_whitespace().collect();
            if inside && w.len() == 9 && w[1] == "3" {
                turned += 1;
                let mut v = w.clone();
                v[5..].reverse();
                v.join(" ")
            } else {
                l.to_string()
            }
        })
        .collect();
    assert_eq!(turned, 16);
    let cw = reversed.join("\n") + "\n";
    let mesh = |f: &str| {
        format!("[[meshes]]\nname = \"m\"\nfile = \"{f}\"\nanalysis = \"plane_stress\"\nmaterial = \"steel\"")
    };
    let (_d, a) = read(
        &cantilever(&mesh("block_quad_22.msh"), "m.left", "m.2", "m.tip"),
        &[],
    );
    let (_e, b) = read(
        &cantilever(&mesh("cw.msh"), "m.left", "m.2", "m.tip"),
        &[("cw.msh", &cw)],
    );
    let (a, b) = (a.unwrap(), b.unwrap());
    compare(&run(&a), &run(&b), &a.model, &b.model);
}

#[test]
fn triangles_in_elements_given_node_by_node() {
    // Reference: a single triangle clamped on one side, written clockwise and counter-clockwise.
    let model = |order: &str| {
        format!(
            r#"{MATERIAL}
[[nodes]]
id = 1
x = 0.0
y = 0.0
[[nodes]]
id = 2
x = 1.0
y = 0.0
[[nodes]]
id = 3
x = 0.0
y = 1.0
[[elements]]
type = "triangle"
nodes = [{order}]
material = "steel"
analysis = "plane_strain"
[[supports]]
nodes = [1, 3]
pinned = true
[[contact]]
from = "ground"
to = 2
normal = [0.0, 1.0]
friction = 0.0
[[loads.variable.nodal]]
nodes = 2
fy = -1.0
"#
        )
    };
    let (_d, a) = read(&model("1, 2, 3"), &[]);
    let (_e, b) = read(&model("1, 3, 2"), &[]);
    let (a, b) = (a.unwrap(), b.unwrap());
    for p in [&a, &b] {
        let Element::Triangle { nodes, .. } = p.model.elements()[0] else {
            panic!("a triangle");
        };
        assert_eq!(nodes, [NodeId(0), NodeId(1), NodeId(2)]);
    }
    let (_f, c) = read(&model("1, 2"), &[]);
    let e = c.unwrap_err();
    assert_eq!(e.kind, InputErrorKind::Size);
    assert!(e.message.contains("a triangle element has 3 nodes"), "{e}");
    let (_g, c) = read(
        &model("1, 2, 3").replace("analysis =", "formulation = \"Q4\"\nanalysis ="),
        &[],
    );
    let e = c.unwrap_err();
    assert!(
        e.to_string()
            .contains("`formulation` does not apply to triangle elements"),
        "{e}"
    );
}

/// A small hand-written MSH 2.2 mesh: the unit square (nodes 1–4) cut into two triangles, with
/// a fifth node, the groups `body` (2D) and `bottom` (1D), and `extra` added to `$Elements`.
fn small_msh(nodes_extra: &str, elements_extra: &[&str]) -> String {
    let mut elements = vec!["1 1 2 2 1 1 2", "2 2 2 1 1 1 2 3", "3 2 2 1 1 1 3 4"];
    elements.extend_from_slice(elements_extra);
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 2 \"bottom\"\n2 1 \"body\"\n$EndPhysicalNames\n\
         $Nodes\n{}\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 2 0 0\n{nodes_extra}$EndNodes\n$Elements\n{}\n{}\n$EndElements\n",
        5 + nodes_extra.lines().count(),
        elements.len(),
        elements.join("\n")
    )
}

fn small_model(materials: &str) -> String {
    format!(
        r#"{MATERIAL}
[[meshes]]
name = "s"
file = "small.msh"
analysis = "plane_strain"
{materials}

[[contact]]
from = "ground"
to = "s.bottom"
normal = [0.0, 1.0]
friction = 0.5

[[loads.variable.nodal]]
nodes = "s.3"
fy = -1.0
"#
    )
}

/// The 1-based line of `needle` in `text` (the reference for the error's line).
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l == needle)
        .expect("the line is in the text")
        + 1
}

/// Reads a model on a bad mesh: the error must name `small.msh` at the line of `needle`.
fn bad_mesh(msh: &str, materials: &str, needle: &str, words: &str) {
    let (_d, r) = read(&small_model(materials), &[("small.msh", msh)]);
    let e = r.unwrap_err();
    let shown = e.to_string();
    let want = format!("small.msh:{}:", line_of(msh, needle));
    assert!(shown.contains(&want), "{shown} should contain {want}");
    assert!(shown.contains(words), "{shown} should say {words}");
    assert!(
        shown.contains("model.toml"),
        "{shown} should say where the mesh is named"
    );
}

#[test]
fn the_small_mesh_reads() {
    // Reference: the text above (4 used nodes; node 5 is on no element and is left out).
    let msh = small_msh("", &[]);
    let (_d, r) = read(&small_model("material = \"steel\""), &[("small.msh", &msh)]);
    let p = r.unwrap();
    assert_eq!(p.model.nodes().len(), 4);
    assert_eq!(p.model.elements().len(), 2);
    assert_eq!(p.model.pairs().len(), 2);
}

#[test]
fn bad_meshes_name_the_msh_file_and_line() {
    let steel = "material = \"steel\"";
    // second order, 3D: refused by the reader, at the element's line
    let m = small_msh("", &["4 9 2 1 1 1 2 3 1 2 3"]);
    bad_mesh(&m, steel, "4 9 2 1 1 1 2 3 1 2 3", "second-order triangle");
    let m = small_msh("6 0.5 0.5 0\n", &["4 4 2 1 1 1 2 3 6"]);
    bad_mesh(&m, steel, "4 4 2 1 1 1 2 3 6", "tetrahedron (3D)");
    // degenerate: nodes 1, 2, 5 on the x axis
    let m = small_msh("", &["4 2 2 1 1 1 2 5"]);
    bad_mesh(
        &m,
        steel,
        "4 2 2 1 1 1 2 5",
        "element 4 (a triangle on nodes 1, 2, 5) is degenerate",
    );
    // concave: the corner (0.5, 0.5)
    let m = small_msh("6 0.5 0.5 0\n7 0 2 0\n", &["4 3 2 1 1 1 5 6 7"]);
    bad_mesh(&m, steel, "4 3 2 1 1 1 5 6 7", "is concave");
    // a quadrangle with a straight corner (node 2 between 1 and 5)
    let m = small_msh("6 2 1 0\n", &["4 3 2 1 1 1 2 5 6"]);
    bad_mesh(&m, steel, "4 3 2 1 1 1 2 5 6", "degenerate");
    // a 2D element in no group of `materials`
    let m = small_msh("", &["4 2 2 7 7 2 5 3"]);
    bad_mesh(
        &m,
        "materials = { body = \"steel\" }",
        "4 2 2 7 7 2 5 3",
        "element 4 (a triangle) has no material",
    );
    // a curve whose node no element uses (node 5, on the line 2–5 of `bottom`)
    let m = small_msh("", &["4 1 2 2 1 2 5"]);
    bad_mesh(
        &m,
        steel,
        "4 1 2 2 1 2 5",
        "node 5 of physical group `bottom`",
    );
    // a mesh of lines only (no section makes them frames)
    let m = small_msh("", &[]).replace(
        "3\n1 1 2 2 1 1 2\n2 2 2 1 1 1 2 3\n3 2 2 1 1 1 3 4\n",
        "1\n1 1 2 2 1 1 2\n",
    );
    let (_d, r) = read(&small_model(steel), &[("small.msh", &m)]);
    let shown = r.unwrap_err().to_string();
    assert!(
        shown.contains("small.msh: mesh `s` has no element the model can use"),
        "{shown}"
    );
    // a named group no element is in: a name without curves, and the line group of a file
    // Gmsh saved with Mesh.SaveAll = 1 in MSH 2.2 (every element's physical tag 0). Either
    // was an empty set, its supports and loads dropped without a word. Unused, it is no
    // error; used (`s.bottom` is the contact's `to`), the reference is refused, saying why.
    let m = small_msh("", &[]).replace("2\n1 2 \"bottom\"\n", "3\n1 9 \"ghost\"\n1 2 \"bottom\"\n");
    assert!(m.contains("ghost"));
    let (_d, r) = read(&small_model(steel), &[("small.msh", &m)]);
    assert_eq!(r.unwrap().model.pairs().len(), 2);
    let m = small_msh("", &[]).replace("1 1 2 2 1 1 2\n", "1 1 2 0 1 1 2\n");
    assert!(m.contains("1 1 2 0 1 1 2"));
    let (_d, r) = read(&small_model(steel), &[("small.msh", &m)]);
    let shown = r.unwrap_err().to_string();
    assert!(
        shown.contains("model.toml:")
            && shown.contains("contact[1].to")
            && shown.contains("`s.bottom` is physical group `bottom` (dimension 1) of ")
            && shown.contains("small.msh (line 6), which has no elements"),
        "{shown}"
    );
    // an empty group named in `materials` (or `sections`) gives its property to nothing:
    // refused at the key (a `sections` group's frames were silently lost)
    let m = small_msh("", &[])
        .replace("2 2 2 1 1 1 2 3\n", "2 2 2 0 1 1 2 3\n")
        .replace("3 2 2 1 1 1 3 4\n", "3 2 2 0 1 1 3 4\n");
    assert!(m.contains("3 2 2 0 1 1 3 4"));
    let (_d, r) = read(
        &small_model("materials = { body = \"steel\" }"),
        &[("small.msh", &m)],
    );
    let shown = r.unwrap_err().to_string();
    assert!(
        shown.contains("materials.body")
            && shown.contains("physical group `body` of the mesh has no elements"),
        "{shown}"
    );
    // the reader's own errors carry where the model names the mesh
    let m = small_msh("", &["4 2 2 1 1 1 3 9"]);
    bad_mesh(&m, steel, "4 2 2 1 1 1 3 9", "node 9");
}

#[test]
fn bad_references_to_meshes_are_located_in_the_model_file() {
    let msh = small_msh("", &[]);
    let cases: &[(&str, &str, &str)] = &[
        (
            "materials = { bdy = \"steel\" }",
            "materials = { bdy",
            "unknown physical group `bdy` (did you mean `body`?)",
        ),
        (
            "materials = { bottom = \"steel\" }",
            "materials = { bottom",
            "has dimension 1, but a group of dimension 2",
        ),
        (
            "materials = { body = \"stel\" }",
            "materials = { body",
            "unknown material `stel` (did you mean `steel`?)",
        ),
        ("", "[[meshes]]", "missing key `material`"),
        (
            "material = \"steel\"\nfile = \"nowhere.msh\"",
            "file = \"nowhere.msh\"",
            "cannot read the mesh file \"nowhere.msh\"",
        ),
    ];
    for (materials, at, words) in cases {
        let mut model = small_model(materials);
        if materials.contains("nowhere") {
            model = model.replacen("file = \"small.msh\"\n", "", 1);
        }
        let (_d, r) = read(&model, &[("small.msh", &msh)]);
        let e = r.unwrap_err();
        let shown = e.to_string();
        let line = model.lines().position(|l| l.starts_with(at)).unwrap() + 1;
        assert!(
            shown.contains(&format!("model.toml:{line}:")),
            "{shown} (line {line})"
        );
        assert!(shown.contains(words), "{shown} should say {words}");
    }
    // a reference to a group the mesh does not have
    let model =
        small_model("material = \"steel\"").replace("to = \"s.bottom\"", "to = \"s.botom\"");
    let (_d, r) = read(&model, &[("small.msh", &msh)]);
    let shown = r.unwrap_err().to_string();
    assert!(
        shown.contains("unknown node or node set `s.botom` (did you mean `s.bottom`?)"),
        "{shown}"
    );
}

#[test]
fn line_groups_become_frames_with_sections_and_meshes_connect() {
    // Reference: the hand-written mesh (line 1–2 in `bottom`, triangles 1-2-3 and 1-3-4).
    let msh = small_msh("", &[]);
    let sections = "material = \"steel\"\nsections = { bottom = \"beam\" }";
    let model = small_model(sections).replace(
        "[[meshes]]",
        "[[sections]]\nname = \"beam\"\nE = 2.0e5\nA = 0.01\nI = 1e-5\n\n[[meshes]]",
    );
    let (_d, r) = read(&model, &[("small.msh", &msh)]);
    let p = r.unwrap();
    let names = p.model.names();
    assert_eq!(p.model.elements().len(), 3);
    let frames: Vec<_> = p
        .model
        .elements()
        .iter()
        .filter_map(|e| match e {
            Element::Frame { nodes, .. } => Some(*nodes),
            _ => None,
        })
        .collect();
    assert_eq!(frames, vec![[names.node_ids["s.1"], names.node_ids["s.2"]]]);
    assert_eq!(names.element_sets["s.bottom"].len(), 1);
    assert_eq!(names.element_sets["s"].len(), 3);
    // a second copy of the mesh connected to the first shares its four nodes
    let second = "[[meshes]]\nname = \"t\"\nfile = \"small.msh\"\nanalysis = \"plane_strain\"\nmaterial = \"steel\"\nconnect_to = \"s\"\n\n[[contact]]";
    let model = small_model("material = \"steel\"").replacen("[[contact]]", second, 1);
    let (_d, r) = read(&model, &[("small.msh", &msh)]);
    let p = r.unwrap();
    assert_eq!(p.model.nodes().len(), 4);
    assert_eq!(p.model.elements().len(), 4);
    let names = p.model.names();
    assert_eq!(names.node_ids["t.3"], names.node_ids["s.3"]);
}

#[test]
fn two_bodies_of_one_mesh_take_materials_by_group() {
    // Reference: Gmsh's API on disc_on_plate (tests/data/gmsh/expected.txt): the half disc has
    // 35 triangles, the plate 25 quadrangles, the arc 9 lines around the centre (0, 1).
    for file in ["disc_on_plate_41.msh", "disc_on_plate_22.msh"] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::copy(gmsh_dir().join(file), dir.path().join(file)).unwrap();
        let path = dir.path().join("model.toml");
        std::fs::write(
            &path,
            format!(
                r#"{MATERIAL}
[[materials]]
name = "soft"
E = 10.0
nu = 0.2

[[meshes]]
name = "d"
file = "{file}"
analysis = "plane_strain"
materials = {{ disc = "steel", plate = "soft" }}

[[contact]]
from = "ground"
to = "d.plate top"
normal = [0.0, 1.0]
friction = 0.5

[[loads.variable.nodal]]
nodes = "d.plate top"
fy = -1.0
"#
            ),
        )
        .unwrap();
        let p = read_model(&path).unwrap();
        let names = p.model.names();
        let els = p.model.elements();
        let e_of = |set: &str| -> Vec<f64> {
            names.element_sets[set]
                .iter()
                .map(|e| match &els[e.0] {
                    Element::Triangle { material, .. } | Element::Plane { material, .. } => {
                        material.e
                    }
                    other => panic!("{other:?}"),
                })
                .collect()
        };
        assert_eq!(e_of("d.disc"), vec![2.0e5; 35]);
        assert_eq!(e_of("d.plate"), vec![10.0; 25]);
        assert!(names.element_sets["d.disc"]
            .iter()
            .all(|e| matches!(els[e.0], Element::Triangle { .. })));
        // the arc's nodes in order along it: their angle about (0, 1) keeps turning one way
        let arc: Vec<f64> = names.node_sets["d.arc"]
            .iter()
            .map(|n| {
                let [x, y] = p.model.nodes()[n.0];
                (1.0 - y).atan2(x).abs() // in [0, π]: the half disc is below its centre (up to round-off)
            })
            .collect();
        assert_eq!(arc.len(), 10);
        let up = arc.windows(2).all(|w| w[1] > w[0]);
        let down = arc.windows(2).all(|w| w[1] < w[0]);
        assert!(up || down, "{arc:?}");
    }
}

/// A closed line group as the surface `from` keeps its closing segment: a block of two
/// quadrilaterals ((0,0)–(2,1), nodes 1…6 counter-clockwise from the origin) whose outline
/// group lists its lines from `2–3` round to `1–2`, on a `[[blocks]]` foundation whose top has
/// nodes at x = 0, 0.5, 1, 1.5, 2. Each top node gets a pair (five); the one at x = 0.5 lies on
/// the closing segment `1–2` at its middle (hand: ξ = 0.5, normal along y). Walking the group's
/// node list pairwise lost that segment (four pairs, the node at 0.5 without one).
#[test]
fn a_closed_line_group_keeps_its_closing_segment() {
    let msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n1 2 \"outline\"\n\
               2 1 \"up\"\n$EndPhysicalNames\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 2 1 0\n\
               5 1 1 0\n6 0 1 0\n$EndNodes\n$Elements\n8\n1 1 2 2 1 2 3\n2 1 2 2 1 3 4\n\
               3 1 2 2 1 4 5\n4 1 2 2 1 5 6\n5 1 2 2 1 6 1\n6 1 2 2 1 1 2\n\
               7 3 2 1 1 1 2 5 6\n8 3 2 1 1 2 3 4 5\n$EndElements\n";
    let model = r#"
[[materials]]
name = "m"
E = 1.0e6
nu = 0.25
[[meshes]]
name = "up"
file = "up.msh"
analysis = "plane_strain"
material = "m"
[[blocks]]
name = "low"
origin = [0.0, -1.0]
width = 2.0
height = 1.0
nx = 4
ny = 2
material = "m"
analysis = "plane_strain"
[[supports]]
nodes = "low.bottom"
fixed = true
[[contact]]
name = "c"
match = "surface"
search = 0.01
from = "up.outline"
to = "low.top"
normal = "surface"
friction = 0.5
[[loads.variable.body]]
elements = "up"
force = [0.0, -100.0]
"#;
    let (_dir, r) = read(model, &[("up.msh", msh)]);
    let p = r.unwrap_or_else(|e| panic!("{e}"));
    let m = &p.model;
    let pairs = m.pairs();
    assert_eq!(pairs.len(), 5, "{pairs:?}");
    let at = |n: NodeId| m.nodes()[n.0];
    let mid = pairs
        .iter()
        .find(|q| (at(q.b)[0] - 0.5).abs() < 1e-12)
        .expect("a pair at x = 0.5");
    let unilateral_fem::Endpoint::Node(a1) = mid.a else {
        panic!("a node-to-segment pair: {mid:?}")
    };
    let (a2, xi) = mid.segment.expect("on a segment");
    let mut ends = [at(a1)[0], at(a2)[0]];
    ends.sort_by(f64::total_cmp);
    assert_eq!(ends, [0.0, 1.0], "{mid:?}");
    assert!((xi - 0.5).abs() < 1e-12, "{mid:?}");
    assert!(mid.normal[0].abs() < 1e-12 && (mid.normal[1].abs() - 1.0).abs() < 1e-12);
}

/// Two line groups of frames walked towards the node they share (`a`: lines 1–2, 2–3; `b`:
/// 5–4, 4–3, on y = 0), named together as the surface `from` under a block whose bottom nodes
/// are at x = 0…4, y = 0.1: the pairs are those of the same lines as one group `ab` (normals,
/// segments, gaps) — a frame's side is not told by the direction its line is walked in (the
/// two groups' left-hand normals cancelled at node 3 and the model was refused).
#[test]
fn line_groups_walked_towards_each_other_make_one_surface() {
    let msh = |groups: &str, b: usize| {
        format!(
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n{groups}$EndPhysicalNames\n\
             $Nodes\n5\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 3 0 0\n5 4 0 0\n$EndNodes\n$Elements\n4\n\
             1 1 2 1 1 1 2\n2 1 2 1 1 2 3\n3 1 2 {b} 2 5 4\n4 1 2 {b} 2 4 3\n$EndElements\n"
        )
    };
    let model = |sections: &str, from: &str| {
        format!(
            r#"
[[materials]]
name = "m"
E = 1.0e6
nu = 0.25
[[sections]]
name = "s"
E = 1.0e6
A = 1.0
I = 1.0
[[meshes]]
name = "beam"
file = "beam.msh"
analysis = "plane_strain"
sections = {sections}
[[blocks]]
name = "up"
origin = [0.0, 0.1]
width = 4.0
height = 1.0
nx = 4
ny = 1
material = "m"
analysis = "plane_strain"
[[supports]]
nodes = ["beam.1", "beam.5"]
fixed = true
[[contact]]
name = "c"
match = "surface"
search = 0.5
from = {from}
to = "up.bottom"
normal = "surface"
gap = "geometry"
friction = 0.0
[[loads.variable.nodal]]
nodes = "beam.3"
fy = 1.0
"#
        )
    };
    let two = msh("2\n1 1 \"a\"\n1 2 \"b\"\n", 2);
    let one = msh("1\n1 1 \"ab\"\n", 1);
    let (_d1, r1) = read(
        &model("{ a = \"s\", b = \"s\" }", "[\"beam.a\", \"beam.b\"]"),
        &[("beam.msh", &two)],
    );
    let (_d2, r2) = read(
        &model("{ ab = \"s\" }", "\"beam.ab\""),
        &[("beam.msh", &one)],
    );
    let (p1, p2) = (
        r1.unwrap_or_else(|e| panic!("{e}")),
        r2.unwrap_or_else(|e| panic!("{e}")),
    );
    let (a, b) = (p1.model.pairs(), p2.model.pairs());
    assert_eq!(a.len(), 5);
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x.normal, y.normal, "{x:?} / {y:?}");
        assert_eq!(x.gap, y.gap, "{x:?} / {y:?}");
        // the normal points from the beam up into the block
        assert!(x.normal[1] > 0.99, "{x:?}");
    }
}
