//! Scale invariance of structural analyses: the answer may not depend on the units the engineer
//! types.
//!
//! Every bundled structural example (`examples/*.toml`) and every test model
//! (`tests/data/models/*.toml`) is rewritten in other units — a force unit F and a length unit L
//! applied separately and together, from 1e-12 to 1e12 — by scaling each key of the model
//! document by its dimension (docs/model-format.md, "Units"):
//!
//! | quantity | keys | scales as |
//! |---|---|---|
//! | lengths | node `x`, `y`; block `origin`, `width`, `height`; member `start`, `end` points; node-set `box`; `gap`; `depth`; `thickness`; settlements in `ux`, `uy` | L |
//! | section | `A` | L² |
//! | section | `I` | L⁴ |
//! | moduli | `E` | F/L² |
//! | nodal loads | `fx`, `fy` | F |
//! | nodal moments | `m` | F·L |
//! | distributed loads | `q`, `start`, `end` | F/L |
//! | body forces | `force` | F/L³ on plane elements (per unit volume), F/L on frames and bars (per unit length) |
//! | springs | `stiffness` | F/L (translational), F·L (rotational) |
//! | tightening | `tightening` | F |
//! | dimensionless | `nu`, `alpha`, `friction`, temperatures, rotations, directions, `target`, `pivot_tolerance`, `max_pivots` | 1 |
//!
//! The reference is the model as written. The rescaled model must give the same outcome, the
//! same events in the same order at the same loads, the same pair states, and every reported
//! number equal to the reference's times its unit factor, to 1e-9 relative to the size of that
//! kind of quantity in the reference (forces to the largest force, lengths to the largest
//! displacement, …).
//!
//! Second, where the answer is linear in the loads — every load, settlement, temperature, gap
//! and the tightening multiplied by the same `s` — the events stay where they are and every
//! force and displacement is multiplied by `s`.

use std::path::{Path, PathBuf};

use unilateral_analysis::{analyze, Analysis, Outcome};
use unilateral_fem::SupportDof;
use unilateral_io::{read_problem, Problem, StructuralProblem};

/// The unit factors (deterministic, from 1e-12 to 1e12).
const FACTORS: [f64; 8] = [1e-12, 1e-6, 1e-3, 0.3, 7.0, 1e3, 1e6, 1e12];

/// Relative agreement required of rescaled numbers.
const REL: f64 = 1e-9;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `.toml` files of a directory of the repository, sorted; a missing or empty directory is
/// a failure.
fn toml_files(dir: &str) -> Vec<PathBuf> {
    let d = root().join(dir);
    let mut v: Vec<PathBuf> = std::fs::read_dir(&d)
        .unwrap_or_else(|e| panic!("the data directory {} is missing: {e}", d.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    v.sort();
    assert!(!v.is_empty(), "no .toml files in {}", d.display());
    v
}

fn doc_of(path: &Path) -> toml::Table {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("the data file {} is missing: {e}", path.display()));
    text.parse()
        .unwrap_or_else(|e| panic!("{} is not TOML: {e}", path.display()))
}

fn is_structural(doc: &toml::Table) -> bool {
    !doc.contains_key("contact_zone")
}

/// Analyses a model document (written to a temporary file named like `name`).
fn analyse(name: &str, doc: &toml::Table) -> Result<(StructuralProblem, Analysis), String> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(name);
    std::fs::write(&file, toml::to_string(doc).unwrap()).unwrap();
    let p = match read_problem(&file) {
        Ok(Problem::Structural(p)) => p,
        Ok(Problem::ContactZone(_)) => return Err("not a structural model".into()),
        Err(e) => return Err(format!("read: {e}")),
    };
    let a = analyze(&p.model, &p.settings).map_err(|e| e.to_string())?;
    Ok((p, a))
}

// ---------------------------------------------------------------------------------------------
// rewriting a model document

/// Multiplies every number in `v` (a number or nested arrays of numbers) by `k`.
fn scale_value(v: &mut toml::Value, k: f64) {
    match v {
        toml::Value::Float(x) => *x *= k,
        toml::Value::Integer(i) => *v = toml::Value::Float(*i as f64 * k),
        toml::Value::Array(a) => a.iter_mut().for_each(|x| scale_value(x, k)),
        _ => {}
    }
}

fn scale_key(t: &mut toml::Table, key: &str, k: f64) {
    if let Some(v) = t.get_mut(key) {
        scale_value(v, k);
    }
}

fn tables<'a>(doc: &'a mut toml::Table, key: &str) -> Vec<&'a mut toml::Table> {
    match doc.get_mut(key) {
        Some(toml::Value::Array(a)) => a.iter_mut().filter_map(|v| v.as_table_mut()).collect(),
        _ => Vec::new(),
    }
}

/// The names a reference value holds (a string, a number or a list of them).
fn refs(v: Option<&toml::Value>) -> Vec<String> {
    match v {
        Some(toml::Value::String(s)) => vec![s.clone()],
        Some(toml::Value::Integer(i)) => vec![i.to_string()],
        Some(toml::Value::Array(a)) => a.iter().flat_map(|x| refs(Some(x))).collect(),
        _ => Vec::new(),
    }
}

/// Whether the element references of a body load are plane elements: a block, an element of
/// a block (`block.i.j`), or an `[[elements]]` entry of type "plane" (by id or 1-based position).
fn body_on_plane(doc: &toml::Table, elements: &[String]) -> bool {
    let blocks: Vec<String> = doc
        .get("blocks")
        .and_then(|v| v.as_array())
        .map(|a| {
            a.iter()
                .filter_map(|b| b.get("name").and_then(|n| n.as_str()).map(String::from))
                .collect()
        })
        .unwrap_or_default();
    let plane_elements: Vec<String> = doc
        .get("elements")
        .and_then(|v| v.as_array())
        .map(|a| {
            a.iter()
                .enumerate()
                .filter(|(_, e)| e.get("type").and_then(|t| t.as_str()) == Some("plane"))
                .map(|(i, e)| refs(e.get("id")).pop().unwrap_or((i + 1).to_string()))
                .collect()
        })
        .unwrap_or_default();
    elements.iter().any(|r| {
        blocks
            .iter()
            .any(|b| r == b || r.starts_with(&format!("{b}.")))
            || plane_elements.contains(r)
    })
}

/// Rewrites a model in the units (force unit F = `f`, length unit L = `l`): a quantity of
/// dimension F^a·L^b is multiplied by f^a·l^b.
pub(crate) fn rescale_units(doc: &mut toml::Table, f: f64, l: f64) {
    for n in tables(doc, "nodes") {
        scale_key(n, "x", l);
        scale_key(n, "y", l);
    }
    for s in tables(doc, "sections") {
        scale_key(s, "E", f / (l * l));
        scale_key(s, "A", l * l);
        scale_key(s, "I", l.powi(4));
        scale_key(s, "depth", l);
    }
    for m in tables(doc, "materials") {
        scale_key(m, "E", f / (l * l));
        scale_key(m, "thickness", l);
    }
    for b in tables(doc, "blocks") {
        scale_key(b, "origin", l);
        scale_key(b, "width", l);
        scale_key(b, "height", l);
    }
    for m in tables(doc, "members") {
        for end in ["start", "end"] {
            if m.get(end).is_some_and(|v| v.is_array()) {
                scale_key(m, end, l);
            }
        }
    }
    for s in tables(doc, "node_sets") {
        scale_key(s, "box", l);
    }
    for s in tables(doc, "springs") {
        let rotational = s.get("rotational").and_then(|v| v.as_bool()) == Some(true);
        scale_key(s, "stiffness", if rotational { f * l } else { f / l });
    }
    for c in tables(doc, "contact") {
        scale_key(c, "gap", l);
        scale_key(c, "search", l);
    }
    // Every load case (`constant`, `variable`, or any name a history uses), in file order.
    let case_names: Vec<String> = doc
        .get("loads")
        .and_then(|x| x.as_table())
        .map(|t| t.keys().cloned().collect())
        .unwrap_or_default();
    let on_plane: Vec<bool> = case_names
        .iter()
        .flat_map(|g| {
            doc.get("loads")
                .and_then(|x| x.get(g.as_str()))
                .and_then(|x| x.get("body"))
                .and_then(|x| x.as_array())
                .cloned()
                .unwrap_or_default()
        })
        .map(|b| body_on_plane(doc, &refs(b.get("elements"))))
        .collect();
    let mut on_plane = on_plane.into_iter();
    if let Some(loads) = doc.get_mut("loads").and_then(|x| x.as_table_mut()) {
        for g in &case_names {
            let Some(group) = loads.get_mut(g.as_str()).and_then(|x| x.as_table_mut()) else {
                continue;
            };
            for n in tables(group, "nodal") {
                scale_key(n, "fx", f);
                scale_key(n, "fy", f);
                scale_key(n, "m", f * l);
            }
            for d in tables(group, "distributed") {
                for k in ["q", "start", "end"] {
                    scale_key(d, k, f / l);
                }
            }
            for b in tables(group, "body") {
                let plane = on_plane.next().unwrap();
                scale_key(b, "force", if plane { f / l.powi(3) } else { f / l });
            }
            for s in tables(group, "settlement") {
                if s.get("dof").and_then(|d| d.as_str()) != Some("rz") {
                    scale_key(s, "value", l);
                }
            }
        }
    }
    if let Some(s) = doc.get_mut("solve").and_then(|x| x.as_table_mut()) {
        scale_key(s, "tightening", f);
    }
}

/// Multiplies every load — forces, moments, settlements, temperatures — and every gap and the
/// tightening by `s`: the problem is positively homogeneous in them.
fn rescale_loads(doc: &mut toml::Table, s: f64) {
    for c in tables(doc, "contact") {
        scale_key(c, "gap", s);
    }
    if let Some(loads) = doc.get_mut("loads").and_then(|x| x.as_table_mut()) {
        for g in ["constant", "variable"] {
            let Some(group) = loads.get_mut(g).and_then(|x| x.as_table_mut()) else {
                continue;
            };
            for (kind, keys) in [
                ("nodal", &["fx", "fy", "m"][..]),
                ("distributed", &["q", "start", "end"][..]),
                ("body", &["force"][..]),
                ("settlement", &["value"][..]),
                ("temperature", &["uniform", "gradient"][..]),
            ] {
                for t in tables(group, kind) {
                    for k in keys {
                        scale_key(t, k, s);
                    }
                }
            }
        }
    }
    if let Some(t) = doc.get_mut("solve").and_then(|x| x.as_table_mut()) {
        scale_key(t, "tightening", s);
    }
}

// ---------------------------------------------------------------------------------------------
// comparing two analyses

/// How each kind of reported number scales.
#[derive(Clone, Copy)]
struct Factors {
    force: f64,
    length: f64,
    /// Of displacements (L, or s for load scaling) and rotations.
    disp: f64,
    rot: f64,
    moment: f64,
    stress: f64,
}

impl Factors {
    fn units(f: f64, l: f64) -> Self {
        Factors {
            force: f,
            length: l,
            disp: l,
            rot: 1.0,
            moment: f * l,
            stress: f / (l * l),
        }
    }
    fn loads(s: f64) -> Self {
        Factors {
            force: s,
            length: 1.0,
            disp: s,
            rot: s,
            moment: s,
            stress: s,
        }
    }
}

fn max_abs<'a>(v: impl IntoIterator<Item = &'a f64>) -> f64 {
    v.into_iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Whether each spring of the model (in the model's order: entry by entry, node by node) is
/// rotational.
fn spring_is_rotational(doc: &toml::Table, p: &StructuralProblem) -> Vec<bool> {
    let mut v = Vec::new();
    for s in doc
        .get("springs")
        .and_then(|x| x.as_array())
        .into_iter()
        .flatten()
    {
        let rot = s.get("rotational").and_then(|x| x.as_bool()) == Some(true);
        let n: usize = refs(s.get("nodes"))
            .iter()
            .map(|r| p.model.names().set(r).map_or(1, |s| s.len()))
            .sum();
        v.extend(std::iter::repeat_n(rot, n));
    }
    v
}

struct Cmp {
    errors: Vec<String>,
}

impl Cmp {
    /// `got` must be `want·k` to REL·scale·k.
    fn num(&mut self, what: &str, got: f64, want: f64, k: f64, scale: f64) {
        let ok = got.is_finite() && (got / k - want).abs() <= REL * scale.max(want.abs());
        if !ok && self.errors.len() < 8 {
            self.errors.push(format!(
                "{what}: got {got:e}, want {:e} (= {want:e}·{k:e})",
                want * k
            ));
        }
    }
    fn same<T: PartialEq + std::fmt::Debug>(&mut self, what: &str, got: T, want: T) {
        if got != want && self.errors.len() < 8 {
            self.errors
                .push(format!("{what}: got {got:?}, want {want:?}"));
        }
    }
}

/// Compares a rescaled analysis with the reference; returns the differences.
fn compare(
    doc: &toml::Table,
    (rp, ra): &(StructuralProblem, Analysis),
    (_, sa): &(StructuralProblem, Analysis),
    k: Factors,
) -> Vec<String> {
    let mut c = Cmp { errors: Vec::new() };
    // Outcome and path: loads are dimensionless.
    let (ro, so) = (&ra.solution.outcome, &sa.solution.outcome);
    c.same("outcome", so.status(), ro.status());
    match (ro, so) {
        (Outcome::Ray { p_from: a }, Outcome::Ray { p_from: b }) => c.num("ray", *b, *a, 1.0, 1.0),
        (
            Outcome::Mechanism {
                p_limit: a,
                mode: ma,
            },
            Outcome::Mechanism {
                p_limit: b,
                mode: mb,
            },
        ) => {
            c.num("p_limit", *b, *a, 1.0, 1.0);
            c.same("mode length", mb.len(), ma.len());
            for (x, y) in ma.iter().zip(mb) {
                c.num("mode z_n", y.0, x.0, 1.0, 1.0);
                c.num("mode z_t", y.1, x.1, 1.0, 1.0);
            }
        }
        _ => {}
    }
    // The target is given, so the same number; a mechanism's p_lim is computed (above).
    match (ra.p(), sa.p(), ro) {
        (Some(a), Some(b), Outcome::Mechanism { .. }) => c.num("reported p", b, a, 1.0, 1.0),
        _ => c.same("reported p", sa.p(), ra.p()),
    }
    c.same("steps", sa.solution.steps.len(), ra.solution.steps.len());
    for (r, s) in ra.solution.steps.iter().zip(&sa.solution.steps) {
        c.num(&format!("step {} load", r.index), s.p, r.p, 1.0, r.p.abs());
        let ev = |x: &unilateral_contact::LoadStep| {
            x.events
                .iter()
                .map(|e| (e.pair, e.kind, e.while_open))
                .collect::<Vec<_>>()
        };
        c.same(&format!("step {} events", r.index), ev(s), ev(r));
    }
    // Structure.
    let (Some(rr), Some(sr)) = (&ra.results, &sa.results) else {
        c.same(
            "results present",
            sa.results.is_some(),
            ra.results.is_some(),
        );
        c.same("pairs", sa.solution.pairs.len(), ra.solution.pairs.len());
        return c.errors;
    };
    let size = {
        let xs = rp.model.nodes().iter().map(|n| n[0]);
        let ys = rp.model.nodes().iter().map(|n| n[1]);
        let span = |v: Vec<f64>| {
            v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
        };
        span(xs.collect())
            .hypot(span(ys.collect()))
            .max(f64::MIN_POSITIVE)
    };
    let us = max_abs(rr.displacements.iter().flat_map(|d| &d[..2]));
    let rs = max_abs(rr.displacements.iter().map(|d| &d[2])).max(us / size);
    for (i, (r, s)) in rr.displacements.iter().zip(&sr.displacements).enumerate() {
        let n = &rp.model.names().nodes[i];
        c.num(&format!("node {n} ux"), s[0], r[0], k.disp, us);
        c.num(&format!("node {n} uy"), s[1], r[1], k.disp, us);
        c.num(&format!("node {n} rz"), s[2], r[2], k.rot, rs);
    }
    let line_f = max_abs(rr.lines.iter().flat_map(|l| {
        [
            &l.end_forces[0],
            &l.end_forces[1],
            &l.end_forces[3],
            &l.end_forces[4],
        ]
    }));
    let react_f = max_abs(
        rr.reactions
            .iter()
            .filter(|r| r.dof != SupportDof::Rz)
            .map(|r| &r.value),
    );
    // Forces are compared with the largest force of the solution: pair forces, reactions,
    // frame end forces, and the equilibrium check's own force scale.
    let fs = max_abs(ra.solution.pairs.iter().flat_map(|p| [&p.x_n, &p.x_t]));
    let force_scale = fs.max(line_f).max(react_f).max(rr.equilibrium.scale);
    let moment_scale = max_abs(
        rr.lines
            .iter()
            .flat_map(|l| [&l.end_forces[2], &l.end_forces[5]])
            .chain(
                rr.reactions
                    .iter()
                    .filter(|r| r.dof == SupportDof::Rz)
                    .map(|r| &r.value),
            ),
    )
    .max(force_scale * size);
    // Pairs.
    let (rpairs, spairs) = (&ra.solution.pairs, &sa.solution.pairs);
    c.same("pairs", spairs.len(), rpairs.len());
    let zs = max_abs(rpairs.iter().flat_map(|p| [&p.z_n, &p.z_t])).max(us);
    for (r, s) in rpairs.iter().zip(spairs) {
        c.same(&format!("pair {} state", r.name), s.state, r.state);
        c.num(
            &format!("pair {} x_n", r.name),
            s.x_n,
            r.x_n,
            k.force,
            force_scale,
        );
        c.num(
            &format!("pair {} x_t", r.name),
            s.x_t,
            r.x_t,
            k.force,
            force_scale,
        );
        c.num(&format!("pair {} z_n", r.name), s.z_n, r.z_n, k.disp, zs);
        c.num(&format!("pair {} z_t", r.name), s.z_t, r.z_t, k.disp, zs);
    }
    c.same("reactions", sr.reactions.len(), rr.reactions.len());
    for (r, s) in rr.reactions.iter().zip(&sr.reactions) {
        let what = format!(
            "reaction {:?} at {}",
            r.dof,
            rp.model.names().nodes[r.node.0]
        );
        if r.dof == SupportDof::Rz {
            c.num(&what, s.value, r.value, k.moment, moment_scale);
        } else {
            c.num(&what, s.value, r.value, k.force, force_scale);
        }
    }
    for (r, s) in rr.lines.iter().zip(&sr.lines) {
        let e = &rp.model.names().elements[r.element.0];
        for j in 0..6 {
            let (kk, sc) = if j % 3 == 2 {
                (k.moment, moment_scale)
            } else {
                (k.force, force_scale)
            };
            c.num(
                &format!("element {e} end force {j}"),
                s.end_forces[j],
                r.end_forces[j],
                kk,
                sc,
            );
        }
        for (a, b) in r.diagram.iter().zip(&s.diagram) {
            c.num(&format!("element {e} s"), b.s, a.s, k.length, size);
            c.num(&format!("element {e} N"), b.n, a.n, k.force, force_scale);
            c.num(&format!("element {e} Q"), b.q, a.q, k.force, force_scale);
            c.num(&format!("element {e} M"), b.m, a.m, k.moment, moment_scale);
        }
    }
    let ss = max_abs(rr.planes.iter().flat_map(|p| p.stress.iter().flatten()));
    for (r, s) in rr.planes.iter().zip(&sr.planes) {
        let e = &rp.model.names().elements[r.element.0];
        for g in 0..4 {
            for j in 0..4 {
                c.num(
                    &format!("element {e} stress {j} at Gauss point {g}"),
                    s.stress[g][j],
                    r.stress[g][j],
                    k.stress,
                    ss,
                );
            }
            for j in 0..2 {
                c.num(
                    &format!("element {e} Gauss point"),
                    s.gauss_points[g][j],
                    r.gauss_points[g][j],
                    k.length,
                    size,
                );
            }
        }
    }
    let rot = spring_is_rotational(doc, rp);
    c.same("springs", rr.spring_forces.len(), rot.len());
    let sf = max_abs(&rr.spring_forces);
    for (i, (r, s)) in rr.spring_forces.iter().zip(&sr.spring_forces).enumerate() {
        let kk = if rot.get(i) == Some(&true) {
            k.moment
        } else {
            k.force
        };
        c.num(&format!("spring {i}"), *s, *r, kk, sf);
    }
    c.errors
}

/// A rewriting of a model document, with its label and how the answer must scale.
type Case = (String, Box<dyn Fn(&mut toml::Table)>, Factors);

/// Runs every model of `files` in every rescaling `cases` gives, and fails with a list of every
/// model and rescaling that did not reproduce the reference.
fn check(files: &[PathBuf], cases: &[Case]) {
    let mut failures = Vec::new();
    let mut runs = 0;
    for path in files {
        let doc = doc_of(path);
        if !is_structural(&doc) {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let reference = match analyse(&name, &doc) {
            Ok(r) => r,
            Err(e) => {
                failures.push(format!("{name}: the reference run fails: {e}"));
                continue;
            }
        };
        for (label, edit, k) in cases {
            let mut d = doc.clone();
            edit(&mut d);
            runs += 1;
            match analyse(&name, &d) {
                Ok(s) => {
                    let errs = compare(&doc, &reference, &s, *k);
                    if !errs.is_empty() {
                        failures.push(format!("{name} with {label}:\n    {}", errs.join("\n    ")));
                    }
                }
                Err(e) => failures.push(format!("{name} with {label}: {e}")),
            }
        }
    }
    assert!(runs > 0, "nothing was run");
    assert!(
        failures.is_empty(),
        "{} of {runs} rescaled runs differ from their reference:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

fn unit_cases() -> Vec<Case> {
    let mut v: Vec<Case> = Vec::new();
    for &x in &FACTORS {
        for (f, l) in [(x, 1.0), (1.0, x), (x, 1.0 / x)] {
            v.push((
                format!("F = {f:e}, L = {l:e}"),
                Box::new(move |d| rescale_units(d, f, l)),
                Factors::units(f, l),
            ));
        }
    }
    v
}

fn load_cases() -> Vec<Case> {
    FACTORS
        .iter()
        .map(|&s| {
            let case: Case = (
                format!("loads × {s:e}"),
                Box::new(move |d| rescale_loads(d, s)),
                Factors::loads(s),
            );
            case
        })
        .collect()
}

/// The bundled structural examples (the contact-zone example has no structure to rescale).
fn structural_examples() -> Vec<PathBuf> {
    let files: Vec<PathBuf> = toml_files("examples")
        .into_iter()
        // Models whose geometry lives in `.msh` files are left out: rewriting the model file
        // cannot rescale the coordinates of its meshes (their own tests check their physics).
        .filter(|f| {
            let d = doc_of(f);
            is_structural(&d) && !d.contains_key("history") && !d.contains_key("meshes")
        })
        .collect();
    assert_eq!(
        files.len(),
        4,
        "examples 1 (beam), 2 and 3 in structural form, and the sheet pile wall with real loads: {files:?}"
    );
    files
}

#[test]
fn bundled_examples_do_not_depend_on_the_units() {
    check(&structural_examples(), &unit_cases());
}

#[test]
fn test_models_do_not_depend_on_the_units() {
    check(&toml_files("tests/data/models"), &unit_cases());
}

#[test]
fn bundled_examples_scale_with_their_loads() {
    check(&structural_examples(), &load_cases());
}

#[test]
fn test_models_scale_with_their_loads() {
    check(&toml_files("tests/data/models"), &load_cases());
}

/// The rewriting itself: a unit change of a small model, checked key by key against the
/// dimensions of docs/model-format.md (so that the property tests above test what they say).
#[test]
fn the_rewriting_scales_each_key_by_its_dimension() {
    let mut d: toml::Table = r#"
        [[sections]]
        name = "s"
        E = 1.0
        A = 1.0
        I = 1.0
        depth = 1.0
        [[materials]]
        name = "m"
        E = 1.0
        nu = 0.3
        thickness = 1.0
        alpha = 1.0
        [[blocks]]
        name = "b"
        origin = [1, 1]
        width = 1.0
        height = 1.0
        nx = 1
        ny = 1
        material = "m"
        [[members]]
        name = "w"
        start = "b.top_left"
        end = [1.0, 1.0]
        section = "s"
        [[springs]]
        nodes = "w.end"
        rotational = true
        stiffness = 1.0
        [[springs]]
        nodes = "w.end"
        direction = [1.0, 0.0]
        stiffness = 1.0
        [[contact]]
        from = "ground"
        to = "b.bottom"
        normal = [0.0, 1.0]
        friction = 0.5
        gap = 1.0
        [[loads.variable.nodal]]
        nodes = "w.end"
        fx = 1.0
        m = 1.0
        [[loads.variable.body]]
        elements = "b"
        force = [1.0, 1.0]
        [[loads.variable.body]]
        elements = "w"
        force = [1.0, 1.0]
        [[loads.constant.settlement]]
        nodes = "w.start"
        dof = "rz"
        value = 1.0
        [[loads.constant.temperature]]
        elements = "w"
        uniform = 1.0
        [solve]
        tightening = 1.0
        target = 1.0
    "#
    .parse()
    .unwrap();
    let (f, l) = (2.0, 10.0);
    rescale_units(&mut d, f, l);
    let get = |d: &toml::Table, path: &[&str]| -> toml::Value {
        let mut v = toml::Value::Table(d.clone());
        for p in path {
            v = match p.parse::<usize>() {
                Ok(i) => v.as_array().unwrap()[i].clone(),
                Err(_) => v.get(*p).unwrap().clone(),
            };
        }
        v
    };
    let num = |v: toml::Value| v.as_float().unwrap();
    assert_eq!(num(get(&d, &["sections", "0", "E"])), f / (l * l));
    assert_eq!(num(get(&d, &["sections", "0", "A"])), l * l);
    assert_eq!(num(get(&d, &["sections", "0", "I"])), l.powi(4));
    assert_eq!(num(get(&d, &["sections", "0", "depth"])), l);
    assert_eq!(num(get(&d, &["materials", "0", "E"])), f / (l * l));
    assert_eq!(num(get(&d, &["materials", "0", "nu"])), 0.3);
    assert_eq!(num(get(&d, &["materials", "0", "thickness"])), l);
    assert_eq!(num(get(&d, &["materials", "0", "alpha"])), 1.0);
    assert_eq!(num(get(&d, &["blocks", "0", "origin", "1"])), l);
    assert_eq!(num(get(&d, &["blocks", "0", "width"])), l);
    assert_eq!(get(&d, &["blocks", "0", "nx"]).as_integer(), Some(1));
    assert_eq!(
        get(&d, &["members", "0", "start"]).as_str(),
        Some("b.top_left")
    );
    assert_eq!(num(get(&d, &["members", "0", "end", "0"])), l);
    assert_eq!(num(get(&d, &["springs", "0", "stiffness"])), f * l);
    assert_eq!(num(get(&d, &["springs", "1", "stiffness"])), f / l);
    assert_eq!(num(get(&d, &["springs", "1", "direction", "0"])), 1.0);
    assert_eq!(num(get(&d, &["contact", "0", "gap"])), l);
    assert_eq!(num(get(&d, &["contact", "0", "friction"])), 0.5);
    let var = ["loads", "variable"];
    let at = |rest: &[&'static str]| [&var[..], rest].concat();
    assert_eq!(num(get(&d, &at(&["nodal", "0", "fx"]))), f);
    assert_eq!(num(get(&d, &at(&["nodal", "0", "m"]))), f * l);
    assert_eq!(
        num(get(&d, &at(&["body", "0", "force", "1"]))),
        f / l.powi(3)
    );
    assert_eq!(num(get(&d, &at(&["body", "1", "force", "1"]))), f / l);
    assert_eq!(
        num(get(&d, &["loads", "constant", "settlement", "0", "value"])),
        1.0
    );
    assert_eq!(
        num(get(
            &d,
            &["loads", "constant", "temperature", "0", "uniform"]
        )),
        1.0
    );
    assert_eq!(num(get(&d, &["solve", "tightening"])), f);
    assert_eq!(num(get(&d, &["solve", "target"])), 1.0);
}

/// The bundled load histories (`[[history]]` files of `examples/`) in other units: the same
/// stages, statuses, changes of the working scheme at the same stage parameters, and forces and
/// displacements scaled by the units (reference: dimensional analysis — `s` and the states are
/// dimensionless). Powers of two and others (rounding then differs in the last bits).
#[test]
fn bundled_histories_do_not_depend_on_the_units() {
    let files: Vec<PathBuf> = toml_files("examples")
        .into_iter()
        .filter(|f| doc_of(f).contains_key("history"))
        .collect();
    assert_eq!(
        files.len(),
        2,
        "the deck and the sheet pile histories: {files:?}"
    );
    let run = |name: &str, doc: &toml::Table| {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join(name);
        std::fs::write(&file, toml::to_string(doc).unwrap()).unwrap();
        let Ok(Problem::Structural(p)) = read_problem(&file) else {
            panic!("{name}: not read as a structural model");
        };
        let stages = p.history.clone().expect("a history");
        unilateral_analysis::analyze_history(&p.model, &stages, &p.settings.engine)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let mut runs = 0;
    for path in &files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let doc = doc_of(path);
        let reference = run(&name, &doc);
        for (f, l) in [(1e-3, 1e-3), (1024.0, 0.5), (1e6, 1.0), (1.0, 1e3)] {
            let mut d = doc.clone();
            rescale_units(&mut d, f, l);
            let other = run(&name, &d);
            runs += 1;
            let (a, b) = (&reference.history, &other.history);
            assert_eq!(a.stages.len(), b.stages.len(), "{name} F = {f}, L = {l}");
            for (sa, sb) in a.stages.iter().zip(&b.stages) {
                let at = format!("{name} F = {f}, L = {l}, stage {}", sa.stage);
                assert_eq!(sa.status, sb.status, "{at}");
                // The changes of the working scheme inside the stage (s > 0): the pivots that
                // only settle the scheme at s = 0 (a degenerate vertex: their order among ties
                // is decided by round-off of the units) may differ, the scheme they settle on
                // may not.
                let changes = |st: &unilateral_contact::StageSolution| -> Vec<(f64, Vec<String>)> {
                    st.steps
                        .iter()
                        .filter(|x| x.s > 0.0 && !x.events.is_empty())
                        .map(|x| (x.s, x.events.iter().map(|e| e.to_string()).collect()))
                        .collect()
                };
                let (ca, cb) = (changes(sa), changes(sb));
                assert_eq!(ca.len(), cb.len(), "{at}");
                for (x, y) in ca.iter().zip(&cb) {
                    assert!((x.0 - y.0).abs() <= 1e-9, "{at}: s {} vs {}", x.0, y.0);
                    assert_eq!(x.1, y.1, "{at} at s = {}", x.0);
                }
                let xs = sa.pairs.iter().fold(0.0f64, |m, p| m.max(p.x_n.abs()));
                let zs = sa
                    .pairs
                    .iter()
                    .fold(0.0f64, |m, p| m.max(p.z_n.abs()).max(p.z_t.abs()));
                for (p, q) in sa.pairs.iter().zip(&sb.pairs) {
                    assert_eq!(p.state, q.state, "{at}: {p:?} vs {q:?}");
                    assert!(
                        (p.x_n * f - q.x_n).abs() <= 1e-9 * xs * f,
                        "{at}: {p:?} vs {q:?}"
                    );
                    assert!(
                        (p.x_t * f - q.x_t).abs() <= 1e-9 * xs * f,
                        "{at}: {p:?} vs {q:?}"
                    );
                    assert!(
                        (p.z_n * l - q.z_n).abs() <= 1e-9 * zs * l,
                        "{at}: {p:?} vs {q:?}"
                    );
                    assert!(
                        (p.z_t * l - q.z_t).abs() <= 1e-9 * zs * l,
                        "{at}: {p:?} vs {q:?}"
                    );
                }
            }
        }
    }
    assert_eq!(runs, 8);
}
