//! Contact-zone problems (`[contact_zone]`, `[load.*]`, `[solve]`) and plain LCPs in TOML/JSON.

use std::collections::HashMap;
use std::path::Path;

use faer::Mat;
use unilateral_contact::{
    ContactError, ContactLoad, ContactZone, Follow, LoadCase, SolveSettings, Stage,
};
use unilateral_lcp::Lcp;

use crate::dat::read_siconos_lcp;
use crate::error::{InputError, InputErrorKind, Pos};
use crate::reader::{format_of, Doc, Format, MatrixInput, Table};
use crate::tree::{did_you_mean, short, Node, Value};

/// A contact-zone problem as read from a file: the zone and the `[solve]` settings.
#[derive(Debug, Clone)]
pub struct ContactZoneProblem {
    /// The contact stiffness matrices, friction, gaps and loads.
    pub zone: ContactZone,
    /// The `[solve]` settings (defaults where the file gives none).
    pub settings: SolveSettings,
    /// The stages of the file's `[[history]]`, their factors indexed like the zone's load
    /// cases ([`ContactZone::cases`]); `None` without a history (the paper's single load path).
    pub history: Option<Vec<Stage>>,
    /// The optional top-level `title` of the file.
    pub title: Option<String>,
    /// The optional top-level `units` of the file, as written (`"N, m"`: force, then length).
    pub units: Option<String>,
}

const TOP_KEYS: &[&str] = &["title", "units", "contact_zone", "load", "solve", "history"];
const ZONE_KEYS: &[&str] = &["friction", "gap", "Rnn", "Rtt", "Rnt", "Rtn", "names"];
const LOAD_PART_KEYS: &[&str] = &["normal", "tangential"];
const SOLVE_KEYS: &[&str] = &[
    "tightening",
    "target",
    "trace",
    "pivot_tolerance",
    "max_pivots",
];

/// Reads a contact-zone problem from a `.toml` or `.json` file.
///
/// The keys are those of `interfaces.md`: `[contact_zone]` with `friction` (one number, or one
/// per pair), `gap` (optional, default 0), `Rnn` and `Rtt` (required), `Rnt` and `Rtn`
/// (optional, default zero), `names` (optional pair names, default `"1"`, `"2"`, …);
/// `[load.constant]` (optional) and `[load.variable]` (required) with `normal` and/or
/// `tangential` per-pair vectors (a missing one is zero); `[solve]` (optional) with
/// `tightening`, `target`, `trace` (`"target"` or `"end"`), and the expert keys
/// `pivot_tolerance` and `max_pivots`; optional top-level strings `title` and `units` (as in a
/// structural model: the writers label their outputs with them).
///
/// With `[[history]]` stages (`history.md`), `[load.NAME]` may name any load case (each with
/// `normal` and/or `tangential`; `[load.variable]` is then not required), the stages'
/// `factors` name those cases, and `tightening`, `target` and `trace` are refused. Every case
/// is in [`ContactZone::cases`] in file order; `constant` and `variable` also fill the
/// zone's fields of those names (zero when absent).
///
/// A matrix is an inline array of rows, or the name of a Matrix Market file relative to the
/// problem file. The number of pairs `m` is the size of `Rnn`. Unknown keys are errors.
/// Everything is checked ([`ContactZone::validate`], [`SolveSettings::validate`]) and every
/// problem is reported as an [`InputError`] naming the file, the line and column, and the key.
///
/// # Example
///
/// ```
/// use unilateral_io::read_contact_zone;
///
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("beam.toml");
/// std::fs::write(&path, r#"
/// [contact_zone]
/// friction = 0.6
/// Rnn = [[0.1875, -0.375, 0.1875], [-0.375, 0.75, -0.375], [0.1875, -0.375, 0.1875]]
/// Rtt = [[1, -1, 0], [-1, 2, -1], [0, -1, 1]]
///
/// [load.variable]
/// normal = [-0.09375, 0.6875, 0.40625]
///
/// [solve]
/// tightening = 1.0
/// trace = "end"
/// "#)?;
///
/// let problem = read_contact_zone(&path)?;
/// assert_eq!(problem.zone.pairs(), 3);
/// assert_eq!(problem.zone.friction, vec![0.6; 3]);
/// assert_eq!(problem.zone.variable.tangential, vec![0.0; 3]);
/// assert_eq!(problem.settings.tightening, 1.0);
///
/// // A typo is reported with its place and a suggestion.
/// std::fs::write(&path, "[contact_zone]\nfriction = 0.6\nRn = [[1.0]]\n")?;
/// let err = read_contact_zone(&path).unwrap_err();
/// assert!(err.to_string().ends_with(
///     "beam.toml:3:1: contact_zone.Rn: unknown key `Rn` in [contact_zone] (did you mean `Rnn`?); \
///      the keys here are: friction, gap, Rnn, Rtt, Rnt, Rtn, names"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_contact_zone(path: &Path) -> Result<ContactZoneProblem, InputError> {
    let (doc, root) = Doc::load(path, "a contact-zone problem")?;
    let top = doc.table(&root, "")?;
    top.check_keys(TOP_KEYS)?;
    let text = |k: &str| -> Result<Option<String>, InputError> {
        top.get(k)
            .map(|n| doc.string(n, k).map(str::to_string))
            .transpose()
    };
    let (title, units) = (text("title")?, text("units")?);

    let Some(cz) = top.table("contact_zone")? else {
        return Err(doc.err(
            None,
            "contact_zone",
            InputErrorKind::MissingKey,
            format!(
                "missing the `contact_zone` {}: a contact-zone problem gives the matrices Rnn and Rtt (and friction) there",
                doc.table_word()
            ),
        ));
    };
    cz.check_keys(ZONE_KEYS)?;

    // The matrices; m is the size of Rnn.
    let rnn_node = cz.require(
        "Rnn",
        "the normal contact stiffness matrix (m × m, m = number of pairs)",
    )?;
    let rnn = doc.matrix(rnn_node, &cz.child("Rnn"))?;
    let m = rnn.mat.nrows();
    if m == 0 {
        return Err(rnn.err(
            &doc,
            InputErrorKind::Size,
            "Rnn is empty: the contact zone needs at least one pair",
        ));
    }
    if rnn.mat.ncols() != m {
        return Err(rnn.err(
            &doc,
            InputErrorKind::Size,
            format!(
                "Rnn must be square (m × m), but it is {}×{}",
                m,
                rnn.mat.ncols()
            ),
        ));
    }
    let rtt_node = cz.require(
        "Rtt",
        &format!("the tangential contact stiffness matrix ({m} × {m})"),
    )?;
    let rtt = doc.matrix(rtt_node, &cz.child("Rtt"))?;
    let rnt = optional_matrix(&cz, "Rnt")?;
    let rtn = optional_matrix(&cz, "Rtn")?;
    for (name, mat) in [
        ("Rtt", Some(&rtt)),
        ("Rnt", rnt.as_ref()),
        ("Rtn", rtn.as_ref()),
    ] {
        if let Some(mat) = mat {
            let (r, c) = (mat.mat.nrows(), mat.mat.ncols());
            if (r, c) != (m, m) {
                return Err(mat.err(
                    &doc,
                    InputErrorKind::Size,
                    format!(
                        "{name} is {r}×{c}, but Rnn is {m}×{m} (the contact zone has {m} pairs)"
                    ),
                ));
            }
        }
    }

    // Friction and gaps.
    let friction_node = cz.require(
        "friction",
        "the Coulomb friction coefficient: one number for all pairs or one per pair (0 for frictionless contact)",
    )?;
    let friction = per_pair(&doc, friction_node, &cz.child("friction"), m, true)?;
    non_negative(&doc, &friction, &cz.child("friction"), "friction")?;
    let gap = match cz.get("gap") {
        Some(node) => {
            let g = per_pair(&doc, node, &cz.child("gap"), m, true)?;
            non_negative(&doc, &g, &cz.child("gap"), "the initial gap")?;
            g.values
        }
        None => vec![0.0; m],
    };
    let pair_names = match cz.get("names") {
        Some(node) => names(&doc, node, &cz.child("names"), m)?,
        None => (1..=m).map(|i| i.to_string()).collect(),
    };

    // Loads.
    let has_history = top.get("history").is_some();
    let load = top.table("load")?;
    let mut cases: Vec<LoadCase> = Vec::new();
    if let Some(load) = &load {
        for e in load.entries {
            if !has_history {
                if let Some(err) = crate::history::case_without_history(load, &e.key) {
                    return Err(err);
                }
            }
            let t = doc.table(&e.node, &load.child(&e.key))?;
            cases.push(LoadCase {
                name: e.key.clone(),
                load: contact_load(&t, m, e.key != "constant")?,
            });
        }
    }
    let case = |name: &str| {
        cases
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.load.clone())
    };
    let constant = case("constant").unwrap_or_else(|| ContactLoad::zeros(m));
    let variable = match case("variable") {
        Some(v) => v,
        None if has_history => ContactLoad::zeros(m),
        None => {
            return Err(doc.err(
                load.as_ref().and_then(|l| l.pos),
                "load.variable",
                InputErrorKind::MissingKey,
                format!(
                    "missing the variable load `load.variable` ({} with `normal` and/or `tangential`): it is the load multiplied by the parameter p; without it the load path is trivial",
                    doc.a_table()
                ),
            ))
        }
    };
    crate::history::refuse_path_keys(&top)?;
    let names: Vec<String> = cases.iter().map(|c| c.name.clone()).collect();
    let history = crate::history::read_history(&top, &names, "load")?;

    let settings = match top.table("solve")? {
        Some(t) => solve_settings(&t)?,
        None => SolveSettings::default(),
    };

    let zone = ContactZone {
        rnn: rnn.mat.clone(),
        rnt: rnt
            .as_ref()
            .map_or_else(|| Mat::zeros(m, m), |x| x.mat.clone()),
        rtn: rtn
            .as_ref()
            .map_or_else(|| Mat::zeros(m, m), |x| x.mat.clone()),
        rtt: rtt.mat.clone(),
        friction: friction.values,
        gap,
        constant,
        variable,
        cases,
        pair_names,
    };
    // A user's matrices are checked to be semidefinite as well (`O(m³)`, not done for a
    // zone the program condenses itself).
    if let Err(e) = zone.validate().and_then(|()| zone.check_semidefinite()) {
        let mats = [
            ("Rnn", Some(&rnn)),
            ("Rtt", Some(&rtt)),
            ("Rnt", rnt.as_ref()),
            ("Rtn", rtn.as_ref()),
        ];
        let find = |name: &str| mats.iter().find(|(n, _)| *n == name).and_then(|(_, m)| *m);
        let msg = e.to_string();
        let err = match &e {
            ContactError::NotSymmetric { name, row, col, .. } => find(name).map(|mat| {
                mat.entry_err(&doc, row - 1, col - 1, InputErrorKind::Invalid, msg.clone())
            }),
            ContactError::NotSemidefinite { name, row, col, .. } => find(name).map(|mat| {
                mat.entry_err(&doc, row - 1, col - 1, InputErrorKind::Invalid, msg.clone())
            }),
            ContactError::NegativeDiagonal { name, pair, .. } => find(name).map(|mat| {
                mat.entry_err(
                    &doc,
                    pair - 1,
                    pair - 1,
                    InputErrorKind::Invalid,
                    msg.clone(),
                )
            }),
            _ => None,
        };
        return Err(err.unwrap_or_else(|| {
            // Everything else is checked above with a precise place; keep a sound fallback.
            let key = match &e {
                ContactError::MatrixSize { name, .. } | ContactError::NotSymmetric { name, .. } => {
                    format!("contact_zone.{name}")
                }
                ContactError::VectorSize { name, .. } | ContactError::NotFinite { name, .. } => {
                    if name.starts_with("load.") {
                        name.clone()
                    } else {
                        format!("contact_zone.{name}")
                    }
                }
                _ => "contact_zone".to_string(),
            };
            doc.err(None, &key, InputErrorKind::Invalid, msg)
        }));
    }
    Ok(ContactZoneProblem {
        zone,
        settings,
        history,
        title,
        units,
    })
}

fn optional_matrix(t: &Table, k: &str) -> Result<Option<MatrixInput>, InputError> {
    t.get(k)
        .map(|node| t.doc.matrix(node, &t.child(k)))
        .transpose()
}

/// A per-pair vector and where it was written.
struct PerPair {
    values: Vec<f64>,
    /// Position of each entry (all the same for a scalar).
    pos: Vec<Option<Pos>>,
    /// Whether one number was given for all pairs.
    scalar: bool,
}

fn per_pair(
    doc: &Doc,
    node: &Node,
    key: &str,
    m: usize,
    allow_scalar: bool,
) -> Result<PerPair, InputError> {
    if allow_scalar && node.as_number().is_some() {
        let x = doc.number(node, key)?;
        return Ok(PerPair {
            values: vec![x; m],
            pos: vec![node.pos; m],
            scalar: true,
        });
    }
    if !matches!(node.value, Value::Array(_)) {
        let expected = if allow_scalar {
            format!("a number or an array of {m} numbers (one per pair)")
        } else {
            format!("an array of {m} numbers (one per pair)")
        };
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::WrongType,
            format!("expected {expected}, found {}", doc.describe(node)),
        ));
    }
    let (values, pos) = doc.vector(node, key)?;
    if values.len() != m {
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::Size,
            format!(
                "has {} entries, but the contact zone has {m} pairs (the size of Rnn)",
                values.len()
            ),
        ));
    }
    Ok(PerPair {
        values,
        pos,
        scalar: false,
    })
}

fn non_negative(doc: &Doc, v: &PerPair, key: &str, what: &str) -> Result<(), InputError> {
    if let Some(i) = v.values.iter().position(|&x| x < 0.0) {
        let (key, whose) = if v.scalar {
            (key.to_string(), String::new())
        } else {
            (format!("{key}[{}]", i + 1), format!(" for pair {}", i + 1))
        };
        return Err(doc.err(
            v.pos[i],
            &key,
            InputErrorKind::Value,
            format!("{what} must be ≥ 0, but it is {}{whose}", v.values[i]),
        ));
    }
    Ok(())
}

fn names(doc: &Doc, node: &Node, key: &str, m: usize) -> Result<Vec<String>, InputError> {
    let Value::Array(items) = &node.value else {
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::WrongType,
            format!(
                "expected an array of {m} pair names (strings), found {}",
                doc.describe(node)
            ),
        ));
    };
    if items.len() != m {
        return Err(doc.err(
            node.pos,
            key,
            InputErrorKind::Size,
            format!(
                "has {} names, but the contact zone has {m} pairs (the size of Rnn)",
                items.len()
            ),
        ));
    }
    let mut out: Vec<String> = Vec::with_capacity(m);
    // Pair index of each name, so that a duplicate is found without a scan of the names.
    let mut index: HashMap<&str, usize> = HashMap::with_capacity(m);
    for (i, item) in items.iter().enumerate() {
        let k = format!("{key}[{}]", i + 1);
        let s = doc.string(item, &k)?.trim();
        if s.is_empty() {
            return Err(doc.err(
                item.pos,
                &k,
                InputErrorKind::Value,
                "a pair name must not be empty",
            ));
        }
        if let Some(j) = index.insert(s, i) {
            return Err(doc.err(
                item.pos,
                &k,
                InputErrorKind::Value,
                format!(
                    "the name \"{}\" is already used by pair {}",
                    short(s),
                    j + 1
                ),
            ));
        }
        out.push(s.to_string());
    }
    Ok(out)
}

fn contact_load(t: &Table, m: usize, required: bool) -> Result<ContactLoad, InputError> {
    t.check_keys(LOAD_PART_KEYS)?;
    if required && t.get("normal").is_none() && t.get("tangential").is_none() {
        return Err(t.doc.err(
            t.pos,
            &t.key,
            InputErrorKind::MissingKey,
            format!(
                "{} needs `normal` and/or `tangential` (one value per pair; a missing one is zero)",
                t.name()
            ),
        ));
    }
    let part = |k: &str| -> Result<Vec<f64>, InputError> {
        match t.get(k) {
            Some(node) => per_pair(t.doc, node, &t.child(k), m, false).map(|p| p.values),
            None => Ok(vec![0.0; m]),
        }
    };
    Ok(ContactLoad {
        normal: part("normal")?,
        tangential: part("tangential")?,
    })
}

/// The `[solve]` table, shared by contact-zone problems and structural models.
pub(crate) fn solve_settings(t: &Table) -> Result<SolveSettings, InputError> {
    t.check_keys(SOLVE_KEYS)?;
    let doc = t.doc;
    let mut s = SolveSettings::default();
    let range_err = |node: &Node, k: &str, msg: String| {
        doc.err(node.pos, &t.child(k), InputErrorKind::Value, msg)
    };
    if let Some(node) = t.get("tightening") {
        let c = doc.number(node, &t.child("tightening"))?;
        if c < 0.0 {
            return Err(range_err(
                node,
                "tightening",
                format!("the tightening c must be ≥ 0, got {c}"),
            ));
        }
        s.tightening = c;
    }
    if let Some(node) = t.get("target") {
        let p = doc.number(node, &t.child("target"))?;
        if p <= 0.0 {
            return Err(range_err(
                node,
                "target",
                format!("the target load p* must be > 0, got {p}"),
            ));
        }
        s.target = p;
    }
    if let Some(node) = t.get("trace") {
        let v = doc.string(node, &t.child("trace"))?;
        s.follow = match v {
            "target" => Follow::ToTarget,
            "end" => Follow::ToEnd,
            other => {
                let hint = match did_you_mean(other, &["target", "end"]) {
                    Some(k) => format!(" (did you mean \"{k}\"?)"),
                    None => String::new(),
                };
                return Err(range_err(
                    node,
                    "trace",
                    format!(
                        "unknown trace \"{}\"{hint}: use \"target\" (stop at the target load p*) or \"end\" (follow the load path to its end)", short(other)
                    ),
                ));
            }
        };
    }
    if let Some(node) = t.get("pivot_tolerance") {
        s.engine.pivot_tolerance = Some(doc.number(node, &t.child("pivot_tolerance"))?);
    }
    if let Some(node) = t.get("max_pivots") {
        s.engine.max_pivots = Some(doc.positive_integer(node, &t.child("max_pivots"))?);
    }
    if let Err(e) = s.validate() {
        // The engine's check names the setting at fault.
        let (key, msg) = match &e {
            ContactError::Settings(bad) => (bad.key(), bad.to_string()),
            other => ("", other.to_string()),
        };
        let key = SOLVE_KEYS
            .iter()
            .find(|k| **k == key)
            .copied()
            .unwrap_or("");
        let pos = t.get(key).and_then(|n| n.pos).or(t.pos);
        let key = if key.is_empty() {
            t.key.clone()
        } else {
            t.child(key)
        };
        return Err(doc.err(pos, &key, InputErrorKind::Value, msg));
    }
    Ok(s)
}

/// Reads a plain LCP `w = Mz + q`: Siconos `.dat` (see [`read_siconos_lcp`]), or `.toml` /
/// `.json` with the keys `M` (an array of rows, or a Matrix Market file name) and `q`.
///
/// # Example
///
/// ```
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("small.toml");
/// std::fs::write(&path, "M = [[2, 1], [1, 2]]\nq = [-5, -6]\n")?;
/// let lcp = unilateral_io::read_lcp(&path)?;
/// assert_eq!(lcp.m[(0, 1)], 1.0);
/// assert_eq!(lcp.q, vec![-5.0, -6.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_lcp(path: &Path) -> Result<Lcp, InputError> {
    if format_of(path) == Some(Format::Dat) {
        return read_siconos_lcp(path);
    }
    let (doc, root) = Doc::load(path, "a plain LCP (or a Siconos .dat file)")?;
    let top = doc.table(&root, "")?;
    top.check_keys(&["M", "q"])?;
    let m_node = top.require("M", "the n × n matrix of w = Mz + q")?;
    let m = doc.matrix(m_node, "M")?;
    let n = m.mat.nrows();
    if n == 0 {
        return Err(m.err(&doc, InputErrorKind::Size, "M is empty"));
    }
    if m.mat.ncols() != n {
        return Err(m.err(
            &doc,
            InputErrorKind::Size,
            format!("M must be square, but it is {n}×{}", m.mat.ncols()),
        ));
    }
    let q_node = top.require("q", "the vector of w = Mz + q")?;
    let (q, _) = doc.vector(q_node, "q")?;
    if q.len() != n {
        return Err(doc.err(
            q_node.pos,
            "q",
            InputErrorKind::Size,
            format!("q has {} entries, but M is {n}×{n}", q.len()),
        ));
    }
    Ok(Lcp { m: m.mat, q })
}
