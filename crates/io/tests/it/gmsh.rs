//! The Gmsh reader on meshes Gmsh itself wrote (`tests/data/gmsh/make.py`: a half disc of
//! triangles on a plate of quadrangles, saved as MSH 4.1 and 2.2). Reference: what Gmsh's own
//! API says of the same mesh (`tests/data/gmsh/expected.txt`, written by the script): node count,
//! three nodes' coordinates, and each physical group's dimension, tag, name and element counts.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use unilateral_io::{read_gmsh, GmshMesh, MshElementType, MshVersion};

fn dir() -> PathBuf {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/gmsh");
    assert!(
        d.is_dir(),
        "{} is missing: the test meshes belong to the repository",
        d.display()
    );
    d
}

struct Group {
    dimension: usize,
    tag: usize,
    name: Option<String>,
    /// Gmsh element type → count.
    counts: BTreeMap<u32, usize>,
}

struct Expected {
    nodes: usize,
    coords: Vec<(usize, f64, f64)>,
    groups: Vec<Group>,
}

fn expected() -> Expected {
    let text = std::fs::read_to_string(dir().join("expected.txt")).unwrap();
    let mut e = Expected {
        nodes: 0,
        coords: Vec::new(),
        groups: Vec::new(),
    };
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w[0] {
            "nodes" => e.nodes = w[1].parse().unwrap(),
            "node" => e.coords.push((
                w[1].parse().unwrap(),
                w[2].parse().unwrap(),
                w[3].parse().unwrap(),
            )),
            "group" => e.groups.push(Group {
                dimension: w[1].parse().unwrap(),
                tag: w[2].parse().unwrap(),
                name: (w[3] != "-").then(|| w[3].replace('_', " ")),
                counts: w[4..]
                    .iter()
                    .map(|kv| {
                        let (k, v) = kv.split_once(':').unwrap();
                        (k.parse().unwrap(), v.parse().unwrap())
                    })
                    .collect(),
            }),
            other => panic!("unknown line {other} in expected.txt"),
        }
    }
    assert!(
        e.nodes > 0 && e.groups.len() == 5,
        "expected.txt is incomplete"
    );
    e
}

fn check(mesh: &GmshMesh, e: &Expected) {
    assert_eq!(mesh.nodes.len(), e.nodes);
    for &(tag, x, y) in &e.coords {
        let n = mesh.nodes.iter().find(|n| n.tag == tag).unwrap();
        // The file prints 16 significant digits, the API's list 17.
        assert!(
            (n.xy[0] - x).abs() <= 1e-15 * x.abs().max(1.0),
            "node {tag}"
        );
        assert!(
            (n.xy[1] - y).abs() <= 1e-15 * y.abs().max(1.0),
            "node {tag}"
        );
    }
    for g in &e.groups {
        let label = g.name.clone().unwrap_or_else(|| g.tag.to_string());
        let got = mesh
            .group(&label)
            .unwrap_or_else(|| panic!("group {label}"));
        assert_eq!((got.dimension, got.tag), (g.dimension, g.tag), "{label}");
        assert_eq!(got.name, g.name);
        let mut counts = BTreeMap::new();
        for el in mesh.elements_of(got) {
            *counts.entry(el.kind.gmsh_type()).or_insert(0) += 1;
        }
        assert_eq!(counts, g.counts, "{label}");
    }
    // Every element's nodes are defined (the reader checks it; here by a second look).
    for el in &mesh.elements {
        assert_eq!(el.nodes.len(), el.kind.nodes());
        for n in &el.nodes {
            assert!(mesh.nodes.iter().any(|m| m.tag == *n));
        }
    }
}

#[test]
fn msh41_written_by_gmsh() {
    let mesh = read_gmsh(&dir().join("disc_on_plate_41.msh")).unwrap();
    assert_eq!(mesh.version, MshVersion::V4_1);
    check(&mesh, &expected());
}

#[test]
fn msh22_written_by_gmsh() {
    let mesh = read_gmsh(&dir().join("disc_on_plate_22.msh")).unwrap();
    assert_eq!(mesh.version, MshVersion::V2_2);
    check(&mesh, &expected());
}

#[test]
fn both_versions_give_the_same_mesh() {
    let a = read_gmsh(&dir().join("disc_on_plate_41.msh")).unwrap();
    let b = read_gmsh(&dir().join("disc_on_plate_22.msh")).unwrap();
    let key = |m: &GmshMesh| {
        let mut v: Vec<(usize, MshElementType, Vec<usize>)> = m
            .elements
            .iter()
            .map(|e| (e.tag, e.kind, e.nodes.clone()))
            .collect();
        v.sort_by_key(|x| x.0);
        v
    };
    assert_eq!(key(&a), key(&b));
}
