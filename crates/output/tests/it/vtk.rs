//! The ParaView output of the bundled examples, read back with a small XML parser: counts,
//! connectivity, data arrays, the values of the reported solution and the `.pvd` collection.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use unilateral_analysis::{analyze, Analysis};
use unilateral_fem::{Element, Endpoint, Model};
use unilateral_io::{read_problem, Problem};
use unilateral_output::{write_vtk_for, PVD_FILE};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

fn analyse(name: &str) -> (Model, Analysis) {
    let Problem::Structural(problem) = read_problem(&example(name)).unwrap() else {
        panic!("{name} is not a structural model");
    };
    let a = analyze(&problem.model, &problem.settings).unwrap();
    (problem.model, a)
}

// ---------------------------------------------------------------------------------------------
// A small XML parser: elements, attributes, text, the declaration and comments.

#[derive(Debug)]
struct Xml {
    name: String,
    attrs: Vec<(String, String)>,
    children: Vec<Xml>,
    text: String,
}

impl Xml {
    fn attr(&self, key: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
    fn children<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Xml> + 'a {
        self.children.iter().filter(move |c| c.name == name)
    }
    /// The only child called `name`.
    fn child(&self, name: &str) -> &Xml {
        let v: Vec<&Xml> = self.children.iter().filter(|c| c.name == name).collect();
        assert_eq!(v.len(), 1, "<{}> has {} <{name}>", self.name, v.len());
        v[0]
    }
}

struct Parser<'a> {
    s: &'a str,
    i: usize,
}

impl<'a> Parser<'a> {
    fn rest(&self) -> &'a str {
        &self.s[self.i..]
    }
    fn skip_ws(&mut self) {
        let r = self.rest();
        self.i += r.len() - r.trim_start().len();
    }
    fn skip_until(&mut self, end: &str) -> Result<(), String> {
        let k = self
            .rest()
            .find(end)
            .ok_or(format!("unterminated, expected {end}"))?;
        self.i += k + end.len();
        Ok(())
    }
    /// Whitespace, declarations and comments.
    fn skip_misc(&mut self) -> Result<(), String> {
        loop {
            self.skip_ws();
            if self.rest().starts_with("<?") {
                self.skip_until("?>")?;
            } else if self.rest().starts_with("<!--") {
                self.skip_until("-->")?;
            } else {
                return Ok(());
            }
        }
    }
    fn name(&mut self) -> Result<String, String> {
        let r = self.rest();
        let n = r
            .find(|c: char| !(c.is_alphanumeric() || "_-:.".contains(c)))
            .unwrap_or(r.len());
        if n == 0 {
            return Err(format!("expected a name at byte {}", self.i));
        }
        let name = r[..n].to_string();
        self.i += n;
        Ok(name)
    }
    fn expect(&mut self, t: &str) -> Result<(), String> {
        if self.rest().starts_with(t) {
            self.i += t.len();
            Ok(())
        } else {
            Err(format!("expected {t:?} at byte {}", self.i))
        }
    }
    fn element(&mut self) -> Result<Xml, String> {
        self.expect("<")?;
        let name = self.name()?;
        let mut e = Xml {
            name,
            attrs: Vec::new(),
            children: Vec::new(),
            text: String::new(),
        };
        loop {
            self.skip_ws();
            if self.rest().starts_with("/>") {
                self.i += 2;
                return Ok(e);
            }
            if self.rest().starts_with('>') {
                self.i += 1;
                break;
            }
            let key = self.name()?;
            self.skip_ws();
            self.expect("=")?;
            self.skip_ws();
            let q = if self.rest().starts_with('"') {
                "\""
            } else {
                "'"
            };
            self.expect(q)?;
            let k = self.rest().find(q).ok_or("unterminated attribute")?;
            let value = &self.rest()[..k];
            if value.contains('<') {
                return Err(format!("'<' in attribute {key}"));
            }
            if e.attrs.iter().any(|(k, _)| *k == key) {
                return Err(format!("repeated attribute {key}"));
            }
            e.attrs.push((key, unescape(value)?));
            self.i += k + 1;
        }
        loop {
            if self.rest().starts_with("</") {
                self.i += 2;
                let end = self.name()?;
                if end != e.name {
                    return Err(format!("</{end}> closes <{}>", e.name));
                }
                self.skip_ws();
                self.expect(">")?;
                return Ok(e);
            } else if self.rest().starts_with("<!--") {
                self.skip_until("-->")?;
            } else if self.rest().starts_with('<') {
                e.children.push(self.element()?);
            } else {
                let k = self.rest().find('<').ok_or("unterminated element")?;
                e.text.push_str(&unescape(&self.rest()[..k])?);
                self.i += k;
            }
        }
    }
}

fn unescape(s: &str) -> Result<String, String> {
    let mut out = String::new();
    let mut rest = s;
    while let Some(k) = rest.find('&') {
        out.push_str(&rest[..k]);
        let end = rest[k..].find(';').ok_or("bad entity")? + k;
        out.push(match &rest[k + 1..end] {
            "lt" => '<',
            "gt" => '>',
            "amp" => '&',
            "quot" => '"',
            "apos" => '\'',
            e => return Err(format!("unknown entity &{e};")),
        });
        rest = &rest[end + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

fn parse_xml(text: &str) -> Xml {
    let mut p = Parser { s: text, i: 0 };
    p.skip_misc().unwrap();
    let root = p.element().unwrap_or_else(|e| panic!("{e}"));
    p.skip_misc().unwrap();
    assert_eq!(p.i, text.len(), "text after the root element");
    root
}

// ---------------------------------------------------------------------------------------------
// An unstructured grid read back.

#[derive(Debug)]
struct Array {
    ty: String,
    comps: usize,
    values: Vec<f64>,
}

impl Array {
    fn tuple(&self, i: usize) -> &[f64] {
        &self.values[i * self.comps..(i + 1) * self.comps]
    }
}

#[derive(Debug)]
struct Grid {
    time: f64,
    points: Vec<[f64; 3]>,
    connectivity: Vec<usize>,
    offsets: Vec<usize>,
    types: Vec<u8>,
    point_data: BTreeMap<String, Array>,
    cell_data: BTreeMap<String, Array>,
}

impl Grid {
    fn cell(&self, c: usize) -> &[usize] {
        let start = if c == 0 { 0 } else { self.offsets[c - 1] };
        &self.connectivity[start..self.offsets[c]]
    }
    fn point(&self, name: &str, comps: usize) -> &Array {
        let a = self
            .point_data
            .get(name)
            .unwrap_or_else(|| panic!("no point array {name}"));
        assert_eq!(a.comps, comps, "{name}");
        a
    }
    fn cell_array(&self, name: &str, comps: usize) -> &Array {
        let a = self
            .cell_data
            .get(name)
            .unwrap_or_else(|| panic!("no cell array {name}"));
        assert_eq!(a.comps, comps, "{name}");
        a
    }
}

fn array(e: &Xml) -> (String, Array) {
    assert_eq!(e.name, "DataArray");
    assert_eq!(e.attr("format"), Some("ascii"));
    let name = e.attr("Name").expect("a named array").to_string();
    let ty = e.attr("type").unwrap().to_string();
    let comps: usize = e
        .attr("NumberOfComponents")
        .map_or(1, |c| c.parse().unwrap());
    let values: Vec<f64> = e
        .text
        .split_whitespace()
        .map(|v| {
            v.parse::<f64>()
                .unwrap_or_else(|_| panic!("{name}: bad number {v:?}"))
        })
        .collect();
    assert!(comps >= 1);
    assert_eq!(values.len() % comps, 0, "{name}: partial tuple");
    assert!(
        values.iter().all(|v| v.is_finite()),
        "{name}: non-finite value"
    );
    match ty.as_str() {
        "Float64" => {}
        "Int32" | "Int64" | "UInt8" => {
            assert!(values.iter().all(|v| v.fract() == 0.0), "{name}: integers");
            if ty == "UInt8" {
                assert!(values.iter().all(|&v| (0.0..=255.0).contains(&v)));
            }
        }
        _ => panic!("{name}: unexpected type {ty}"),
    }
    for (k, _) in &e.attrs {
        assert!(
            [
                "type",
                "Name",
                "NumberOfComponents",
                "NumberOfTuples",
                "format"
            ]
            .contains(&k.as_str())
                || k.starts_with("ComponentName"),
            "{name}: unexpected attribute {k}"
        );
    }
    (name, Array { ty, comps, values })
}

fn data(piece: &Xml, section: &str, tuples: usize) -> BTreeMap<String, Array> {
    let mut out = BTreeMap::new();
    for sec in piece.children(section) {
        for e in &sec.children {
            let (name, a) = array(e);
            assert_eq!(
                a.values.len(),
                tuples * a.comps,
                "{section} array {name}: wrong number of tuples"
            );
            for key in ["Scalars", "Vectors"] {
                if let Some(n) = sec.attr(key) {
                    assert!(
                        sec.children.iter().any(|c| c.attr("Name") == Some(n)),
                        "{section} names a missing {key} array {n}"
                    );
                }
            }
            assert!(out.insert(name.clone(), a).is_none(), "repeated {name}");
        }
    }
    out
}

/// Reads a `.vtu` file and checks its structure.
fn read_grid(path: &Path) -> Grid {
    let text = std::fs::read_to_string(path).unwrap();
    let root = parse_xml(&text);
    assert_eq!(root.name, "VTKFile");
    assert_eq!(root.attr("type"), Some("UnstructuredGrid"));
    let ug = root.child("UnstructuredGrid");
    let field = ug.child("FieldData");
    let (tname, t) = array(&field.children[0]);
    assert_eq!(tname, "TimeValue");
    assert_eq!(t.values.len(), 1);
    let piece = ug.child("Piece");
    let np: usize = piece.attr("NumberOfPoints").unwrap().parse().unwrap();
    let nc: usize = piece.attr("NumberOfCells").unwrap().parse().unwrap();
    let (_, pts) = array(piece.child("Points").child("DataArray"));
    assert_eq!(pts.comps, 3);
    assert_eq!(pts.values.len(), 3 * np);
    let points: Vec<[f64; 3]> = pts.values.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    assert!(points.iter().all(|p| p[2] == 0.0));
    let cells = piece.child("Cells");
    let mut arrays: BTreeMap<String, Array> = cells.children.iter().map(array).collect();
    assert_eq!(arrays.len(), 3);
    let ints = |a: Array| a.values.iter().map(|&v| v as usize).collect::<Vec<_>>();
    let connectivity = ints(arrays.remove("connectivity").unwrap());
    let offsets = ints(arrays.remove("offsets").unwrap());
    let types_a = arrays.remove("types").unwrap();
    assert_eq!(types_a.ty, "UInt8");
    let types: Vec<u8> = types_a.values.iter().map(|&v| v as u8).collect();
    assert_eq!(offsets.len(), nc);
    assert_eq!(types.len(), nc);
    assert!(
        connectivity.iter().all(|&c| c < np),
        "connectivity in range"
    );
    let mut prev = 0;
    for (c, (&o, &ty)) in offsets.iter().zip(&types).enumerate() {
        let size = match ty {
            1 => 1,
            3 => 2,
            5 => 3,
            9 => 4,
            _ => panic!("cell type {ty}"),
        };
        assert_eq!(o, prev + size, "cell {c}: offset");
        prev = o;
    }
    assert_eq!(prev, connectivity.len());
    Grid {
        time: t.values[0],
        points,
        connectivity,
        offsets,
        types,
        point_data: data(piece, "PointData", np),
        cell_data: data(piece, "CellData", nc),
    }
}

// ---------------------------------------------------------------------------------------------

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-12 * scale.max(a.abs()).max(b.abs()).max(f64::MIN_POSITIVE)
}

fn check_mesh(g: &Grid, model: &Model) {
    assert_eq!(g.points.len(), model.nodes().len());
    for (p, n) in g.points.iter().zip(model.nodes()) {
        assert_eq!([p[0], p[1]], *n);
    }
    assert_eq!(g.types.len(), model.elements().len());
    let kind = g.cell_array("kind", 1);
    let element = g.cell_array("element", 1);
    let material = g.cell_array("material", 1);
    for (c, e) in model.elements().iter().enumerate() {
        let (nodes, ty, k): (Vec<usize>, u8, f64) = match e {
            Element::Frame { nodes, .. } => (nodes.iter().map(|n| n.0).collect(), 3, 1.0),
            Element::Bar { nodes, .. } => (nodes.iter().map(|n| n.0).collect(), 3, 2.0),
            Element::Plane { nodes, .. } => (nodes.iter().map(|n| n.0).collect(), 9, 3.0),
            Element::Triangle { nodes, .. } => (nodes.iter().map(|n| n.0).collect(), 5, 4.0),
        };
        assert_eq!(g.cell(c), nodes, "cell {c}");
        assert_eq!(g.types[c], ty);
        assert_eq!(kind.values[c], k);
        assert_eq!(element.values[c], c as f64);
        assert!(material.values[c] >= 0.0 && material.values[c] < model.elements().len() as f64);
    }
    // The same section or material gives the same number, a different one another.
    for (i, a) in model.elements().iter().enumerate() {
        for (j, b) in model.elements().iter().enumerate().take(i) {
            let same = match (a, b) {
                (Element::Plane { material: x, .. }, Element::Plane { material: y, .. }) => {
                    x == y
                        && matches!((a, b), (Element::Plane { analysis: p, formulation: f, .. }, Element::Plane { analysis: q, formulation: h, .. }) if p == q && f == h)
                }
                (
                    Element::Triangle {
                        material: x,
                        analysis: p,
                        ..
                    },
                    Element::Triangle {
                        material: y,
                        analysis: q,
                        ..
                    },
                ) => x == y && p == q,
                (
                    Element::Frame { section: x, .. } | Element::Bar { section: x, .. },
                    Element::Frame { section: y, .. } | Element::Bar { section: y, .. },
                ) => x == y,
                _ => false,
            };
            assert_eq!(same, material.values[i] == material.values[j], "{i} {j}");
        }
    }
    // The stress arrays with plane elements only, the section forces with lines only: an
    // array the model's kinds of element would leave zero everywhere is not written.
    let line = |e: &Element| matches!(e, Element::Frame { .. } | Element::Bar { .. });
    let has_plane = model.elements().iter().any(|e| !line(e));
    let has_line = model.elements().iter().any(line);
    for (name, expected) in [
        ("stress", has_plane),
        ("szz", has_plane),
        ("von_mises", has_plane),
        ("axial_force", has_line),
        ("max_abs_moment", has_line),
        ("max_abs_shear", has_line),
    ] {
        assert_eq!(g.cell_data.contains_key(name), expected, "{name}");
    }
    for (name, expected) in [("nodal_stress", has_plane), ("nodal_von_mises", has_plane)] {
        assert_eq!(g.point_data.contains_key(name), expected, "{name}");
    }
    g.point("displacement", 3);
    g.point("rotation", 1);
    if has_plane {
        g.point("nodal_stress", 3);
        g.point("nodal_von_mises", 1);
        g.cell_array("stress", 3);
        g.cell_array("von_mises", 1);
    }
    if has_line {
        g.cell_array("axial_force", 1);
        g.cell_array("max_abs_moment", 1);
        g.cell_array("max_abs_shear", 1);
    }
    let disp = g.point("displacement", 3);
    assert!((0..g.points.len()).all(|i| disp.tuple(i)[2] == 0.0));
}

fn check_pairs(g: &Grid, model: &Model, a: &Analysis) {
    let m = model.pairs().len();
    assert_eq!(g.types.len(), m);
    let node_pairs = model
        .pairs()
        .iter()
        .filter(|p| matches!(p.a, Endpoint::Node(_)))
        .count();
    assert_eq!(g.points.len(), m + node_pairs);
    let xy = |n: usize| {
        let [x, y] = model.nodes()[n];
        [x, y, 0.0]
    };
    for (i, p) in model.pairs().iter().enumerate() {
        let cell = g.cell(i);
        assert_eq!(*cell.last().unwrap(), i, "pair {i}: B is point {i}");
        assert_eq!(g.points[i], xy(p.b.0));
        match p.a {
            Endpoint::Ground => assert_eq!(g.types[i], 1),
            Endpoint::Node(n) => {
                assert_eq!(g.types[i], 3);
                assert!(cell[0] >= m);
                // on a segment (node-to-segment), the A point between its nodes
                let want = match p.segment {
                    None => xy(n.0),
                    Some((n2, xi)) => {
                        let (a1, a2) = (xy(n.0), xy(n2.0));
                        [0, 1, 2].map(|c| (1.0 - xi) * a1[c] + xi * a2[c])
                    }
                };
                let got = g.points[cell[0]];
                let size = want.iter().fold(1e-300f64, |s, v| s.max(v.abs()));
                assert!(
                    (0..3).all(|c| (got[c] - want[c]).abs() <= 1e-12 * size),
                    "pair {i}: {got:?} {want:?}"
                );
            }
        }
    }
    let state = g.cell_array("state", 1);
    assert!(state.values.iter().all(|&s| (0.0..=3.0).contains(&s)));
    assert_eq!(state.ty, "Int32");
    let (x_n, x_t) = (g.cell_array("x_n", 1), g.cell_array("x_t", 1));
    g.cell_array("z_n", 1);
    g.cell_array("z_t", 1);
    let force = g.cell_array("force", 3);
    let (normal, tangent) = (g.cell_array("normal", 3), g.cell_array("tangent", 3));
    let scale = x_n
        .values
        .iter()
        .chain(&x_t.values)
        .fold(0.0f64, |s, v| s.max(v.abs()));
    for i in 0..m {
        let [n, t] = [a.condensed.normals[i], a.condensed.tangents[i]];
        assert_eq!(&normal.tuple(i)[..2], &n[..]);
        assert_eq!(&tangent.tuple(i)[..2], &t[..]);
        for k in 0..2 {
            let f = x_n.values[i] * n[k] + x_t.values[i] * t[k];
            assert!(close(force.tuple(i)[k], f, scale), "pair {i}");
        }
        assert_eq!(force.tuple(i)[2], 0.0);
    }
    // Point data: the pair's force on B, its opposite on A.
    let pf = g.point("force", 3);
    let pp = g.point("pair", 1);
    let ps = g.point("state", 1);
    for (k, &pair) in pp.values.iter().enumerate() {
        let i = pair as usize;
        let sign = if k < m { 1.0 } else { -1.0 };
        assert_eq!(k < m, k == i);
        assert_eq!(ps.values[k], state.values[i]);
        for c in 0..3 {
            assert_eq!(pf.tuple(k)[c], sign * force.tuple(i)[c]);
        }
    }
    g.point("displacement", 3);
}

/// The reported solution, read back, against the analysis.
fn check_final(mesh: &Grid, pairs: &Grid, a: &Analysis) {
    let r = a.results.as_ref().unwrap();
    let disp = mesh.point("displacement", 3);
    let rot = mesh.point("rotation", 1);
    for (i, d) in r.displacements.iter().enumerate() {
        assert_eq!(&disp.tuple(i)[..2], &d[..2]);
        assert_eq!(rot.values[i], d[2]);
    }
    // A model without plane elements has no stress arrays (check_mesh), nor one without lines
    // the section forces.
    let stress = (!r.planes.is_empty()).then(|| mesh.cell_array("stress", 3));
    let vm = (!r.planes.is_empty()).then(|| mesh.cell_array("von_mises", 1));
    for pl in &r.planes {
        let (stress, vm) = (stress.unwrap(), vm.unwrap());
        let e = pl.element.0;
        let scale = pl
            .stress
            .iter()
            .flatten()
            .fold(0.0f64, |s, v| s.max(v.abs()));
        for c in 0..3 {
            let avg = pl.stress.iter().map(|s| s[c]).sum::<f64>() / 4.0;
            assert!(close(stress.tuple(e)[c], avg, scale));
        }
        // von Mises of the element's mean stress, by its formula (a bound of 2·max|σ| did not
        // hold: it reaches 3·max|σ| in plane strain)
        let m4 = [0, 1, 2, 3].map(|c| pl.stress.iter().map(|s| s[c]).sum::<f64>() / 4.0);
        let [sx, sy, txy, sz] = m4;
        let want = (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2))
            + 3.0 * txy * txy)
            .sqrt();
        assert!(close(vm.values[e], want, scale), "{} {want}", vm.values[e]);
    }
    for l in &r.lines {
        let axial = mesh.cell_array("axial_force", 1);
        let moment = mesh.cell_array("max_abs_moment", 1);
        let e = l.element.0;
        let nmax = l.diagram.iter().fold(0.0f64, |s, p| s.max(p.n.abs()));
        let mmax = l.diagram.iter().fold(0.0f64, |s, p| s.max(p.m.abs()));
        assert_eq!(axial.values[e].abs(), nmax);
        assert!(l.diagram.iter().any(|p| p.n == axial.values[e]));
        assert_eq!(moment.values[e], mmax);
        if let Some(stress) = stress {
            assert_eq!(stress.tuple(e), &[0.0; 3]);
        }
    }
    for (i, p) in a.solution.pairs.iter().enumerate() {
        assert_eq!(pairs.cell_array("x_n", 1).values[i], p.x_n);
        assert_eq!(pairs.cell_array("x_t", 1).values[i], p.x_t);
        assert_eq!(pairs.cell_array("z_n", 1).values[i], p.z_n);
        assert_eq!(pairs.cell_array("z_t", 1).values[i], p.z_t);
        let code = match p.state {
            unilateral_analysis::PairState::Open => 0.0,
            unilateral_analysis::PairState::Stick => 1.0,
            unilateral_analysis::PairState::SlipPlus => 2.0,
            unilateral_analysis::PairState::SlipMinus => 3.0,
        };
        assert_eq!(pairs.cell_array("state", 1).values[i], code);
    }
}

fn round_trip(name: &str) -> usize {
    let (model, a) = analyse(name);
    round_trip_of(&model, &a)
}

fn round_trip_of(model: &Model, a: &Analysis) -> usize {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("vtk");
    let files = write_vtk_for(model, a, &out).unwrap();
    let pvd = files.last().unwrap();
    assert_eq!(pvd, &out.join(PVD_FILE));
    for f in &files {
        assert!(f.is_file(), "{}", f.display());
    }
    let mut on_disk: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    on_disk.sort();
    let mut listed = files.clone();
    listed.sort();
    assert_eq!(on_disk, listed, "the files returned are the files written");

    let root = parse_xml(&std::fs::read_to_string(pvd).unwrap());
    assert_eq!(root.name, "VTKFile");
    assert_eq!(root.attr("type"), Some("Collection"));
    let sets: Vec<&Xml> = root.child("Collection").children("DataSet").collect();
    assert_eq!(sets.len(), files.len() - 1, "every file in the collection");
    assert_eq!(sets.len() % 2, 0, "a mesh and a pairs file per step");
    let mut steps: Vec<f64> = Vec::new();
    let mut reported = None;
    for (k, pair) in sets.chunks(2).enumerate() {
        let t: f64 = pair[0].attr("timestep").unwrap().parse().unwrap();
        assert_eq!(pair[1].attr("timestep").unwrap().parse::<f64>().unwrap(), t);
        assert_eq!(pair[0].attr("part"), Some("0"));
        assert_eq!(pair[1].attr("part"), Some("1"));
        let (mf, pf) = (pair[0].attr("file").unwrap(), pair[1].attr("file").unwrap());
        assert_eq!(mf, format!("mesh_{k:03}.vtu"));
        assert_eq!(pf, format!("pairs_{k:03}.vtu"));
        assert_eq!(&files[2 * k], &out.join(mf));
        assert_eq!(&files[2 * k + 1], &out.join(pf));
        if let Some(&prev) = steps.last() {
            assert!(t > prev, "timesteps increase: {prev} then {t}");
        }
        steps.push(t);
        let mesh = read_grid(&out.join(mf));
        let pairs = read_grid(&out.join(pf));
        assert_eq!(mesh.time, t);
        assert_eq!(pairs.time, t);
        check_mesh(&mesh, model);
        check_pairs(&pairs, model, a);
        if Some(t) == a.p() {
            reported = Some((mesh, pairs));
        }
    }
    assert!(steps.iter().all(|&p| p >= 0.0));
    let (mesh, pairs) = reported.expect("the reported load is one of the steps");
    check_final(&mesh, &pairs, a);
    steps.len()
}

/// A block of triangles and quadrilaterals (plane strain) on frictional rigid ground under its
/// self-weight and a push below sliding.
fn triangle_block() -> (Model, Analysis) {
    use unilateral_fem::{
        ContactPairSpec, Load, LoadGroup, PlaneAnalysis, PlaneFormulation, PlaneMaterial,
    };
    let mut m = Model::new();
    let (nx, ny) = (3, 2);
    let id: Vec<Vec<_>> = (0..=nx)
        .map(|i| {
            (0..=ny)
                .map(|j| m.add_node(i as f64, 0.5 * j as f64))
                .collect()
        })
        .collect();
    let mat = PlaneMaterial::new(1.0e4, 0.3);
    let an = PlaneAnalysis::PlaneStrain;
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]);
            let els = if i == 1 {
                vec![m.add_plane([a, b, c, d], mat, an, PlaneFormulation::QM6)]
            } else {
                vec![
                    m.add_triangle([a, b, c], mat, an),
                    m.add_triangle([a, c, d], mat, an),
                ]
            };
            for element in els {
                m.add_load(
                    LoadGroup::Constant,
                    Load::BodyForce {
                        element,
                        force: [0.0, -20.0],
                    },
                );
            }
        }
    }
    for col in &id {
        m.add_contact_pair(ContactPairSpec::to_ground(col[0], [0.0, 1.0]).friction(0.5));
    }
    m.add_load(
        LoadGroup::Variable,
        Load::Nodal {
            node: id[0][ny],
            fx: 1.0,
            fy: 0.0,
            m: 0.0,
        },
    );
    let settings = unilateral_contact::SolveSettings {
        tightening: 0.0,
        target: 5.0,
        ..Default::default()
    };
    let a = analyze(&m, &settings).unwrap();
    (m, a)
}

#[test]
fn triangles_are_vtk_triangles_and_pictured_as_triangles() {
    // Cells: the triangles' nodes in their order, VTK_TRIANGLE (5), kind 4, their constant
    // stress as the cell stress (check_mesh, check_final); the structure picture draws every
    // plane element twice (undeformed outline, deformed fill), a triangle with 3 corners.
    let (model, a) = triangle_block();
    assert!(a.results.is_some());
    round_trip_of(&model, &a);
    let svg = unilateral_output::structure_svg(&model, &a, &Default::default());
    // the element outlines: undeformed in light grey, deformed with a dark edge
    let corners = |stroke: &str| -> Vec<usize> {
        svg.lines()
            .filter(|l| l.starts_with("<polygon") && l.contains(&format!("stroke=\"{stroke}\"")))
            .filter_map(|l| l.split("points=\"").nth(1)?.split('"').next())
            .map(|p| p.split_whitespace().count())
            .collect()
    };
    for stroke in ["#d0d0d0", "#555555"] {
        let mut c = corners(stroke);
        c.sort();
        assert_eq!(c, [vec![3; 8], vec![4; 2]].concat(), "{stroke}");
    }
}

#[test]
fn example1_beam() {
    let (_, a) = analyse("example1-beam.toml");
    let n = round_trip("example1-beam.toml");
    // Traced with the tightening c = 1, its one event (p = 32/3) is the paper's, at a load
    // where the structure without c shows no change (the problem is homogeneous): the
    // animation is the start and the reported solution only.
    assert_eq!(a.solution.tightening, 1.0);
    assert_eq!(a.solution.steps.len(), 1);
    assert_eq!(n, 2, "{n} snapshots");
}

#[test]
fn example2_cantilever() {
    let n = round_trip("example2-cantilever.toml");
    assert!(n >= 2, "{n} snapshots");
}

#[test]
fn example3_sheet_pile() {
    let (_, a) = analyse("example3-sheet-pile.toml");
    let n = round_trip("example3-sheet-pile.toml");
    // 39 events of the paper's procedure with c = 1000 (their loads depend on c): the start
    // and the reported solution only.
    assert!(a.solution.steps.len() > 30);
    assert_eq!(n, 2, "{n} snapshots");
}

#[test]
fn sheet_pile_wall_frames_where_the_scheme_changes() {
    // The physical path (c = 0, soil weight constant, then the push): a frame at p = 0, one
    // at every step that changes a pair's state (the summary's listed steps: 29 of the 45,
    // the other 16 trade an open pair's friction parts) and the reported solution at p = 1.
    let (_, a) = analyse("sheet-pile-wall.toml");
    assert_eq!(a.solution.tightening, 0.0);
    let changing = a
        .solution
        .steps
        .iter()
        .filter(|s| !s.settling && !s.events.is_empty())
        .count();
    assert_eq!(changing, 29);
    assert!(a.solution.steps.len() > changing);
    let n = round_trip("sheet-pile-wall.toml");
    assert_eq!(n, 1 + changing + 1, "{n} snapshots");
}

/// The loads of the frames `write_vtk_for` writes (their collection's timesteps), after the
/// round trip's checks of every file.
fn frame_loads(model: &Model, a: &Analysis) -> Vec<f64> {
    round_trip_of(model, a);
    let dir = tempfile::tempdir().unwrap();
    let files = write_vtk_for(model, a, dir.path()).unwrap();
    let root = parse_xml(&std::fs::read_to_string(files.last().unwrap()).unwrap());
    let mut loads: Vec<f64> = root
        .child("Collection")
        .children("DataSet")
        .map(|d| d.attr("timestep").unwrap().parse().unwrap())
        .collect();
    loads.dedup();
    loads
}

/// Every animation starts at p = 0, as documented ("at the start, at every change of the
/// working scheme and at the reported load"). It was missing where the start could not be
/// read or recovered: a tightened path traced to its target before its first event (p = 0 lay
/// beyond the path's breakpoints), pairs open at their gaps under no load (the round-off of
/// z_n − η made the only forces, which the equilibrium check then judged against nothing), and
/// the cylinder touching at one pair with a round-off normal force of 8.5e-9 N.
#[test]
fn every_animation_starts_at_p_0() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/models");
    let structural = |path: PathBuf| {
        let Problem::Structural(p) = read_problem(&path).unwrap() else {
            panic!("{} is not a structural model", path.display());
        };
        p
    };
    let mut p = structural(example("example1-beam.toml"));
    p.settings.follow = unilateral_contact::Follow::ToTarget;
    let a = analyze(&p.model, &p.settings).unwrap();
    assert!(a.solution.steps.is_empty(), "no event before the target");
    assert_eq!(frame_loads(&p.model, &a), [0.0, 1.0]);
    for path in [
        models.join("gap-beam.toml"),
        example("cylinder-on-foundation.toml"),
    ] {
        let p = structural(path.clone());
        let a = analyze(&p.model, &p.settings).unwrap();
        let loads = frame_loads(&p.model, &a);
        assert_eq!(loads[0], 0.0, "{}: {loads:?}", path.display());
        assert_eq!(*loads.last().unwrap(), 1.0, "{}: {loads:?}", path.display());
    }
}

#[test]
fn refuses_another_model() {
    let (_, a) = analyse("example1-beam.toml");
    let (other, _) = analyse("example2-cantilever.toml");
    let dir = tempfile::tempdir().unwrap();
    let e = write_vtk_for(&other, &a, dir.path()).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput, "{e}");
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}

/// A NaN in the results: every structural writer refuses it, names it, and writes nothing.
/// (The reference is the number spoiled on purpose.)
#[test]
fn refuses_a_non_finite_result() {
    let (model, mut bad) = analyse("example1-beam.toml");
    bad.results
        .as_mut()
        .expect("example 1 recovers")
        .displacements[1][1] = f64::NAN;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("vtk");
    let e = write_vtk_for(&model, &bad, &out).unwrap_err();
    let inner = unilateral_output::NonFiniteOutput::in_io_error(&e).expect("a NonFiniteOutput");
    assert_eq!(inner.field, "nodes[2].uy");
    assert!(inner.value.is_nan());
    assert!(!out.exists() || std::fs::read_dir(&out).unwrap().next().is_none());
    assert_eq!(
        unilateral_output::structural_json(&bad).unwrap_err().field,
        "nodes[2].uy"
    );
    assert_eq!(
        unilateral_output::structural_summary(&bad, "t")
            .unwrap_err()
            .field,
        "nodes[2].uy"
    );
    let csv = dir.path().join("csv");
    let e = unilateral_output::write_structural_csv(&bad, &csv).unwrap_err();
    assert!(
        unilateral_output::NonFiniteOutput::in_io_error(&e).is_some(),
        "{e}"
    );
    assert!(!csv.exists());
}
