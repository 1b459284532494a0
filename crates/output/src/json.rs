//! The JSON documents of `interfaces.md`: of a contact solution, a plain LCP, the tableaux and a
//! structural analysis. Every number is checked finite first ([`NonFiniteOutput`] otherwise):
//! no `null`, `NaN` or `inf` is ever written.

use serde_json::{json, Value};
use unilateral_contact::{ContactError, ContactSolution, LoadStep, Outcome, PairResult};
use unilateral_lcp::{LcpSolution, Residual, Tableau};

use crate::finite::{self, NonFiniteOutput};

/// The version of the layout of the JSON documents (`schema` in every document): raised when a
/// key changes its meaning or disappears, not when one is added.
pub const SCHEMA: u64 = 1;

/// What the problem file says about itself: its `title` and `units`, carried into the outputs
/// (the JSON documents, the CSV column names, the summary, the report).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct About {
    /// The file's `title`.
    pub title: Option<String>,
    /// The file's `units`, as written (`"N, m"`: the force, then the length).
    pub units: Option<String>,
}

impl About {
    /// The force and length units of [`About::units`]: its first two comma-separated words
    /// (`"N, m, K"` → `("N", "m")`); `None` unless both are there and non-empty, and then no
    /// column is labelled (the units are still written as given).
    pub fn force_length(&self) -> Option<(&str, &str)> {
        let mut words = self.units.as_deref()?.split(',').map(str::trim);
        match (words.next(), words.next()) {
            (Some(f), Some(l)) if !f.is_empty() && !l.is_empty() => Some((f, l)),
            _ => None,
        }
    }

    /// `name [unit]` when the unit is known, else `name`.
    pub(crate) fn column(&self, name: &str, unit: impl FnOnce(&str, &str) -> String) -> String {
        match self.force_length() {
            Some((f, l)) => format!("{name} [{}]", unit(f, l)),
            None => name.to_string(),
        }
    }

    /// The four value columns of a pair, `x_n,x_t,z_n,z_t`, each with its unit when known
    /// (forces for `x`, lengths for `z`), as every pair table names them.
    pub(crate) fn pair_columns(&self) -> String {
        [
            self.column("x_n", |f, _| f.into()),
            self.column("x_t", |f, _| f.into()),
            self.column("z_n", |_, l| l.into()),
            self.column("z_t", |_, l| l.into()),
        ]
        .join(",")
    }
}

/// Options of the JSON document of the paper's load path ([`contact_json_with`],
/// [`structural_json_with`]).
#[derive(Debug, Clone, Default)]
pub struct PathJsonOptions {
    /// Write the values of every pair at every breakpoint (`steps[k].pairs`), computed without
    /// the tightening in one walk along the path ([`ContactSolution::at_many`]).
    pub breakpoints: bool,
    /// The file's title and units.
    pub about: About,
}

/// Why a table of the whole path could not be written: a number that is not finite (the
/// program's fault), or the solution could not be evaluated at a breakpoint.
#[derive(Debug, thiserror::Error)]
pub enum PathOutputError {
    /// A number that is not finite.
    #[error(transparent)]
    NonFinite(#[from] NonFiniteOutput),
    /// The solution at a breakpoint leaves the floating-point range, or the engine refused
    /// the path.
    #[error("the values at the breakpoints of the load path could not be computed: {0}")]
    Contact(#[from] ContactError),
}

/// `program` (name and version) and `schema` added to a JSON document (when it is an object
/// and does not have them yet), and every negative zero written as `0.0`: what every document
/// of the program carries. The command line passes every document it writes through it.
pub fn with_provenance(mut doc: Value) -> Value {
    plain_zeros(&mut doc);
    if let Some(obj) = doc.as_object_mut() {
        obj.entry("program").or_insert_with(
            || json!({ "name": "unilateral", "version": env!("CARGO_PKG_VERSION") }),
        );
        obj.entry("schema").or_insert_with(|| json!(SCHEMA));
    }
    doc
}

/// `-0.0` as `0.0` (the same number, without a sign a reader would misread), any other
/// number as it is.
fn plain_zero(v: f64) -> f64 {
    if v == 0.0 {
        0.0
    } else {
        v
    }
}

/// Every `-0.0` of a document as `0.0` ([`plain_zero`]).
fn plain_zeros(v: &mut Value) {
    match v {
        Value::Number(n) if n.is_f64() && n.as_f64() == Some(0.0) => *v = json!(0.0),
        Value::Array(a) => a.iter_mut().for_each(plain_zeros),
        Value::Object(o) => o.values_mut().for_each(plain_zeros),
        _ => {}
    }
}

/// The pairs of one load as JSON (1-based `pair`, name, forces, displacements, state).
pub(crate) fn pairs_json(ps: &[PairResult]) -> Value {
    Value::Array(
        ps.iter()
            .enumerate()
            .map(|(i, p)| {
                json!({
                    "pair": i + 1,
                    "name": p.name,
                    "x_n": p.x_n,
                    "x_t": p.x_t,
                    "z_n": p.z_n,
                    "z_t": p.z_t,
                    "state": p.state.as_str(),
                })
            })
            .collect(),
    )
}

/// The values of every pair at every breakpoint of the path (`None` where a load is not on
/// it), each number checked finite ([`breakpoint_blocks`], collected).
pub(crate) fn breakpoint_pairs(
    sol: &ContactSolution,
) -> Result<Vec<Option<Vec<PairResult>>>, PathOutputError> {
    let mut out = Vec::with_capacity(sol.steps.len());
    breakpoint_blocks(sol, true, |_, block| {
        out.extend(block);
        Ok(())
    })?;
    Ok(out)
}

/// The values of every pair at every breakpoint of the path, handed to `f` block by block
/// (the steps of the block and, for each, the pairs or `None` where its load is not on the
/// path), each number checked finite. They are the path's own breakpoints, `x` formed from
/// their `z` by one product per block: without tightening the solution at each step's `p`
/// (and, after a turning point, that step's point, not another of the same load). Traced with the paper's tightening `c > 0`
/// they are the traced path itself at its breakpoints (with `c` in them, as the steps' events
/// are): never tightening-free values beside `c`-dependent events, and no removal of `c` at
/// every breakpoint (which cost far more than the path); each block of [`BREAKPOINT_BLOCK`]
/// breakpoints is formed, handed over and dropped, so a writer that streams holds no more
/// than one block.
///
/// With `named` false the pairs' names are left empty (pair `i` is `sol.zone().pair_names[i]`):
/// a writer that names the pairs by their place saves an allocation a pair a breakpoint.
pub(crate) fn breakpoint_blocks(
    sol: &ContactSolution,
    named: bool,
    mut f: impl FnMut(&[LoadStep], Vec<Option<Vec<PairResult>>>) -> Result<(), PathOutputError>,
) -> Result<(), PathOutputError> {
    let check = |steps: &[LoadStep],
                 at: Vec<Option<(f64, Vec<PairResult>)>>|
     -> Result<Vec<Option<Vec<PairResult>>>, PathOutputError> {
        let mut out = Vec::with_capacity(at.len());
        for (st, point) in steps.iter().zip(at) {
            let pairs = point.map(|(_, pairs)| pairs);
            for (i, p) in pairs.iter().flatten().enumerate() {
                let at = |what: &str| format!("steps[{}].pairs[{}].{what}", st.index, i + 1);
                finite::finite(p.x_n, || at("x_n"))?;
                finite::finite(p.x_t, || at("x_t"))?;
                finite::finite(p.z_n, || at("z_n"))?;
                finite::finite(p.z_t, || at("z_t"))?;
            }
            out.push(pairs);
        }
        Ok(out)
    };
    // Breakpoint `k` of the traced path is the point after step `k`: its values are the
    // path's own, `x` formed from its `z` by one matrix product per block of steps. Without
    // the tightening they are the solution at the step's load (the path is continuous there),
    // and at a step after a turning point they are that step's point, not another point of
    // the path at the same load.
    // Where the product leaves the floating-point range although the solution does not (a
    // friction coefficient near the end of the range: `x_t± = f·x_n ± x_t`), a path without
    // tightening is evaluated at the steps' loads instead, as its reported solution was.
    for block in sol.steps.chunks(BREAKPOINT_BLOCK) {
        let points: Vec<(usize, f64)> = block.iter().map(|st| (st.index, 0.0)).collect();
        let traced = if named {
            sol.traced_on_segments(&points)
        } else {
            sol.traced_on_segments_unnamed(&points)
        };
        let at = match traced {
            Err(unilateral_contact::ContactError::OutOfRange(_)) if sol.tightening == 0.0 => {
                let loads: Vec<f64> = block.iter().map(|s| s.p).collect();
                sol.at_many(&loads)?
                    .into_iter()
                    .zip(loads)
                    .map(|(point, p)| point.map(|(pairs, _)| (p, pairs)))
                    .collect()
            }
            other => other?,
        };
        f(block, check(block, at)?)?;
    }
    Ok(())
}

/// Breakpoints of a tightened path formed at once by [`breakpoint_blocks`] (one product of
/// `M` with as many columns).
pub(crate) const BREAKPOINT_BLOCK: usize = 256;

/// The JSON value of a residual.
pub fn residual_json(r: Option<&Residual>) -> Result<Value, NonFiniteOutput> {
    if let Some(r) = r {
        finite::residual(r, "residual")?;
    }
    Ok(residual_json_unchecked(r))
}

fn residual_json_unchecked(r: Option<&Residual>) -> Value {
    match r {
        Some(r) => json!({
            "equation": r.equation,
            "complementarity": r.complementarity,
            "feasibility": r.feasibility,
        }),
        None => Value::Null,
    }
}

/// The result document of a contact solve (`interfaces.md`, "Result JSON"), without the values
/// at the breakpoints and without the file's title and units ([`contact_json_with`]).
pub fn contact_json(sol: &ContactSolution) -> Result<Value, NonFiniteOutput> {
    path_document(sol, None, &About::default())
}

/// The result document of a contact solve with its options: the file's `title` and `units`
/// and, on request, `steps[k].pairs`, the values of every pair at every breakpoint without
/// the tightening (labelled so in `step_pairs`).
pub fn contact_json_with(
    sol: &ContactSolution,
    options: &PathJsonOptions,
) -> Result<Value, PathOutputError> {
    finite::contact_solution(sol)?;
    let at = if options.breakpoints {
        Some(breakpoint_pairs(sol)?)
    } else {
        None
    };
    path_document(sol, at.as_deref(), &options.about).map_err(PathOutputError::from)
}

fn path_document(
    sol: &ContactSolution,
    at: Option<&[Option<Vec<PairResult>>]>,
    about: &About,
) -> Result<Value, NonFiniteOutput> {
    finite::contact_solution(sol)?;
    let p_limit = match &sol.outcome {
        Outcome::Mechanism { p_limit, .. } => json!(p_limit),
        _ => Value::Null,
    };
    let mechanism = match &sol.outcome {
        Outcome::Mechanism { mode, .. } => Value::Array(
            mode.iter()
                .enumerate()
                .map(|(i, (dn, dt))| json!({ "pair": i + 1, "dz_n": dn, "dz_t": dt }))
                .collect(),
        ),
        _ => Value::Null,
    };
    let steps: Vec<Value> = sol
        .steps
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let mut step = json!({
                "step": s.index,
                "p": s.p,
                "entering": s.entering,
                "leaving": s.leaving,
                "events": s.events.iter().map(|e| e.to_string()).collect::<Vec<_>>(),
                "changes": s.events.iter().map(|e| {
                    let (what, direction) = crate::history::change_word(e.kind);
                    json!({
                        "pair": e.pair + 1,
                        "name": e.name,
                        "what": what,
                        "direction": direction,
                        "while_open": e.while_open,
                    })
                }).collect::<Vec<_>>(),
                "turning": s.turning,
                "settling": s.settling,
                "beyond_target": s.index > sol.steps_before_target,
            });
            if let Some(at) = at {
                step["pairs"] = at[k].as_deref().map_or(Value::Null, pairs_json);
            }
            step
        })
        .collect();
    let mut doc = json!({
        "status": sol.outcome.status(),
        "reading": sol.reading(),
        "physical_path": sol.physical_reading(),
        "p": sol.p,
        "p_limit": p_limit,
        "target": sol.settings.target,
        "trace": match sol.settings.follow {
            unilateral_contact::Follow::ToTarget => "target",
            unilateral_contact::Follow::ToEnd => "end",
        },
        "tightening": sol.tightening,
        "events_depend_on_tightening": sol.tightening > 0.0,
        "tightening_pivots": sol.tightening_pivots,
        "pivots": sol.steps.len(),
        "steps": steps,
        "pairs": pairs_json(&sol.pairs),
        "mechanism": mechanism,
        "residual": residual_json_unchecked(sol.residual.as_ref()),
        "notes": sol.notes,
    });
    // The file's title and units, when it gives them.
    for (key, v) in [("title", &about.title), ("units", &about.units)] {
        if let Some(v) = v {
            doc[key] = json!(v);
        }
    }
    if at.is_some() {
        doc["step_pairs"] = step_pairs_label(sol);
    }
    Ok(with_provenance(doc))
}

/// What `steps[k].pairs` hold (`step_pairs` of a document with the values at the breakpoints).
fn step_pairs_label(sol: &ContactSolution) -> Value {
    if sol.tightening > 0.0 {
        json!(format!(
            "steps[k].pairs: every pair at the step's breakpoint of the path traced with the \
             tightening c = {}: these values, like the steps' events, depend on c (the \
             solution at the reported load, `pairs`, is free of it)",
            sol.tightening
        ))
    } else {
        json!(
            "steps[k].pairs: every pair at the step's breakpoint of the path: the solution \
             at the step's p"
        )
    }
}

/// A result document to be written, whose `steps[k].pairs` (the values of every pair at every
/// breakpoint, on request) are formed and written a block of breakpoints at a time while the
/// document is serialized, never all at once: a path of thousands of steps with hundreds of
/// pairs is a document of hundreds of megabytes, and held whole (as [`contact_json_with`]
/// returns it) it took several times that in memory. Serialized (`serde`), it is the same text
/// as [`contact_json_with`]'s document with the same changes applied.
///
/// An error met while the values are formed (a number that is not finite, a point the engine
/// cannot evaluate) makes the serialization fail; [`PathDocument::take_error`] then gives it.
pub struct PathDocument<'a> {
    /// The document without `steps[k].pairs`.
    value: Value,
    /// The solution whose breakpoints fill `steps[k].pairs`, when they are asked for.
    breakpoints: Option<&'a ContactSolution>,
    error: std::cell::RefCell<Option<PathOutputError>>,
}

impl From<Value> for PathDocument<'_> {
    /// A document written as it is.
    fn from(value: Value) -> Self {
        Self {
            value,
            breakpoints: None,
            error: Default::default(),
        }
    }
}

impl<'a> PathDocument<'a> {
    /// The document of a contact solve with its options ([`contact_json_with`]), the values at
    /// the breakpoints left to the serialization.
    pub fn contact(
        sol: &'a ContactSolution,
        options: &PathJsonOptions,
    ) -> Result<Self, PathOutputError> {
        finite::contact_solution(sol)?;
        let mut value = path_document(sol, None, &options.about)?;
        if options.breakpoints {
            value["step_pairs"] = step_pairs_label(sol);
        }
        Ok(Self {
            value,
            breakpoints: options.breakpoints.then_some(sol),
            error: Default::default(),
        })
    }

    /// The document of a structural analysis with its options ([`structural_json_with`]), the
    /// values at the breakpoints left to the serialization.
    pub fn structural(
        a: &'a unilateral_analysis::Analysis,
        options: &PathJsonOptions,
    ) -> Result<Self, PathOutputError> {
        finite::analysis(a)?;
        Ok(Self::contact(&a.solution, options)?.map(|doc| with_results(a, doc)))
    }

    /// The document with `f` applied to its parts other than `steps[k].pairs` (such as
    /// [`with_timings`], [`with_provenance`]).
    pub fn map(mut self, f: impl FnOnce(Value) -> Value) -> Self {
        self.value = f(self.value);
        self
    }

    /// The error that made the last serialization fail, if the values at the breakpoints did.
    pub fn take_error(&self) -> Option<PathOutputError> {
        self.error.borrow_mut().take()
    }
}

impl serde::Serialize for PathDocument<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let (Some(sol), Value::Object(obj)) = (self.breakpoints, &self.value) else {
            return self.value.serialize(s);
        };
        let mut map = s.serialize_map(Some(obj.len()))?;
        for (key, v) in obj {
            if key == "steps" {
                let steps = StepsWithPairs {
                    steps: v,
                    sol,
                    error: &self.error,
                };
                map.serialize_entry(key, &steps)?;
            } else {
                map.serialize_entry(key, v)?;
            }
        }
        map.end()
    }
}

/// `steps` with every step's `pairs`, formed a block of breakpoints at a time
/// ([`breakpoint_blocks`]) as the array is serialized.
struct StepsWithPairs<'a> {
    steps: &'a Value,
    sol: &'a ContactSolution,
    error: &'a std::cell::RefCell<Option<PathOutputError>>,
}

impl serde::Serialize for StepsWithPairs<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{Error as _, SerializeSeq};
        let Value::Array(steps) = self.steps else {
            return self.steps.serialize(s);
        };
        let mut seq = s.serialize_seq(Some(steps.len()))?;
        let mut failed: Option<S::Error> = None;
        let mut k = 0usize;
        let formed = breakpoint_blocks(self.sol, true, |_, block| {
            for pairs in block {
                let step = StepWithPairs {
                    step: steps.get(k).unwrap_or(&Value::Null),
                    pairs: pairs.as_deref(),
                };
                k += 1;
                if let Err(e) = seq.serialize_element(&step) {
                    failed = Some(e);
                    // Only a signal to stop: the serializer's error is the one returned.
                    return Err(NonFiniteOutput {
                        field: String::new(),
                        value: 0.0,
                    }
                    .into());
                }
            }
            Ok(())
        });
        if let Some(e) = failed {
            return Err(e);
        }
        if let Err(e) = formed {
            let text = e.to_string();
            *self.error.borrow_mut() = Some(e);
            return Err(S::Error::custom(text));
        }
        seq.end()
    }
}

/// One step of `steps` with its `pairs` inserted in their place among its keys (in order, as
/// [`Value`]'s map keeps them), written straight from the pairs: the text of the step's
/// [`Value`] with `pairs` = [`pairs_json`] and no negative zero, without building that value.
struct StepWithPairs<'a> {
    step: &'a Value,
    pairs: Option<&'a [PairResult]>,
}

impl serde::Serialize for StepWithPairs<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let Value::Object(obj) = self.step else {
            return self.step.serialize(s);
        };
        let pairs = PairRows(self.pairs);
        let mut map = s.serialize_map(Some(obj.len() + 1))?;
        let mut placed = false;
        for (key, v) in obj {
            if !placed && key.as_str() > "pairs" {
                map.serialize_entry("pairs", &pairs)?;
                placed = true;
            }
            let mut v = v.clone();
            plain_zeros(&mut v);
            map.serialize_entry(key, &v)?;
        }
        if !placed {
            map.serialize_entry("pairs", &pairs)?;
        }
        map.end()
    }
}

/// [`pairs_json`]'s array (or `null`), written straight from the pairs.
struct PairRows<'a>(Option<&'a [PairResult]>);

impl serde::Serialize for PairRows<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let Some(pairs) = self.0 else {
            return s.serialize_none();
        };
        let mut seq = s.serialize_seq(Some(pairs.len()))?;
        for (i, p) in pairs.iter().enumerate() {
            seq.serialize_element(&PairRow(i, p))?;
        }
        seq.end()
    }
}

/// One object of [`pairs_json`] (pair `.0`, 0-based), written straight from the pair.
struct PairRow<'a>(usize, &'a PairResult);

impl serde::Serialize for PairRow<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let p = self.1;
        // The keys in the order of `pairs_json`'s map (sorted).
        let mut m = s.serialize_map(Some(7))?;
        m.serialize_entry("name", &p.name)?;
        m.serialize_entry("pair", &(self.0 as u64 + 1))?;
        m.serialize_entry("state", p.state.as_str())?;
        m.serialize_entry("x_n", &plain_zero(p.x_n))?;
        m.serialize_entry("x_t", &plain_zero(p.x_t))?;
        m.serialize_entry("z_n", &plain_zero(p.z_n))?;
        m.serialize_entry("z_t", &plain_zero(p.z_t))?;
        m.end()
    }
}

/// The result document of a plain LCP solve.
pub fn lcp_json(sol: &LcpSolution) -> Result<Value, NonFiniteOutput> {
    finite::lcp_solution(sol)?;
    let (z, w, r) = match &sol.point {
        Some(p) => (
            json!(p.z),
            json!(p.w),
            residual_json_unchecked(Some(&p.residual)),
        ),
        None => (Value::Null, Value::Null, Value::Null),
    };
    Ok(with_provenance(json!({
        "status": sol.status.as_str(),
        "z": z,
        "w": w,
        "pivots": sol.pivots,
        "residual": r,
        "strategy": strategy_json(&sol.strategy),
        "attempts": sol.attempts,
    })))
}

/// How an LCP was solved, as data: `{"method": "trivial"}`, `{"method": "lemke", "covering":
/// "ones"}` (or `"user"`, `"graded"`, `"|q|"`), `{"method": "enumeration"}`.
fn strategy_json(s: &unilateral_lcp::Strategy) -> Value {
    match s {
        unilateral_lcp::Strategy::Trivial => json!({ "method": "trivial" }),
        unilateral_lcp::Strategy::Lemke { covering } => {
            json!({ "method": "lemke", "covering": covering })
        }
        unilateral_lcp::Strategy::Enumeration => json!({ "method": "enumeration" }),
    }
}

/// The tableaux as JSON (entries by row).
pub fn tableaux_json(
    ts: &[Tableau],
    label: &dyn Fn(unilateral_lcp::Var) -> String,
) -> Result<Value, NonFiniteOutput> {
    finite::tableaux(ts)?;
    Ok(Value::Array(
        ts.iter()
            .map(|t| {
                json!({
                    "title": t.title,
                    "after_steps": t.after_steps,
                    "basis": t.basis.iter().map(|v| label(*v)).collect::<Vec<_>>(),
                    "columns": t.columns.iter().map(|v| label(*v)).collect::<Vec<_>>(),
                    "entries": t.entries,
                    "rhs": t.rhs,
                    "ratios": t.ratios,
                    "entering": t.entering.map(label),
                    "leaving_row": t.leaving_row,
                })
            })
            .collect(),
    ))
}

/// The name of a restrained DOF in result files: `ux`, `uy`, `rz` or `along(nx, ny)`.
pub(crate) fn dof_name(d: &unilateral_fem::SupportDof) -> String {
    match (d.label(), d) {
        (Some(l), _) => l.as_str().into(),
        (None, unilateral_fem::SupportDof::Along(v)) => format!("along({}, {})", v[0], v[1]),
        (None, _) => String::new(),
    }
}

/// The result document of a structural analysis: the contact document plus node
/// displacements, reactions, frame end forces, plane-element stresses and the equilibrium check.
pub fn structural_json(a: &unilateral_analysis::Analysis) -> Result<Value, NonFiniteOutput> {
    finite::analysis(a)?;
    let doc = contact_json(&a.solution)?;
    Ok(with_results(a, doc))
}

/// [`structural_json`] with the options of [`contact_json_with`].
pub fn structural_json_with(
    a: &unilateral_analysis::Analysis,
    options: &PathJsonOptions,
) -> Result<Value, PathOutputError> {
    finite::analysis(a)?;
    let doc = contact_json_with(&a.solution, options)?;
    Ok(with_results(a, doc))
}

fn with_results(a: &unilateral_analysis::Analysis, mut doc: Value) -> Value {
    let Some(r) = &a.results else {
        return doc;
    };
    let obj = doc.as_object_mut().expect("an object");
    obj.extend(crate::history_structure::results_json(a.names(), r));
    with_provenance(doc)
}

/// The `timings` object of a result document: the seconds of each part of the run that
/// happened (`read`, `condense`, `solve`, `recover`, `write`, in that order of the run; the
/// keys of the parts that did not happen are absent). Durations are finite and non-negative by
/// construction, so no finite-number check is needed.
pub fn timings_json(t: &unilateral_analysis::Timings) -> Value {
    Value::Object(
        t.present()
            .map(|(name, d)| (name.to_string(), Value::from(d.as_secs_f64())))
            .collect(),
    )
}

/// The result document with its `timings` added.
pub fn with_timings(mut doc: Value, t: &unilateral_analysis::Timings) -> Value {
    if let Some(obj) = doc.as_object_mut() {
        obj.insert("timings".into(), timings_json(t));
    }
    doc
}

#[cfg(test)]
mod tests {
    /// A step written straight from its pairs is the text of the step's value with
    /// `pairs_json` inserted and no negative zero (the reference: `serde_json`'s own writing of
    /// that value), for negative zeros, a `null` for a load off the path, and keys on both sides
    /// of `pairs`.
    #[test]
    fn a_step_written_from_its_pairs_is_its_value_written() {
        use unilateral_contact::{PairResult, PairState};
        let pairs = [
            PairResult {
                name: "Stütze \"1\"".into(),
                x_n: -0.0,
                x_t: 1.5e-300,
                z_n: 2.0,
                z_t: -0.0,
                state: PairState::Open,
            },
            PairResult {
                name: "b".into(),
                x_n: 3.25,
                x_t: -1.0 / 3.0,
                z_n: 0.0,
                z_t: 7e12,
                state: PairState::SlipMinus,
            },
        ];
        let step =
            serde_json::json!({ "step": 3, "p": -0.0, "entering": "z_n 1", "turning": false });
        for at in [Some(&pairs[..]), None] {
            let mut want = step.clone();
            want["pairs"] = at.map_or(serde_json::Value::Null, super::pairs_json);
            super::plain_zeros(&mut want);
            let got = super::StepWithPairs {
                step: &step,
                pairs: at,
            };
            assert_eq!(
                serde_json::to_string_pretty(&got).unwrap(),
                serde_json::to_string_pretty(&want).unwrap()
            );
        }
    }

    use std::time::Duration;

    use crate::{timings_json, timings_summary, with_timings};
    use unilateral_analysis::Timings;

    /// Hand-made timings: only the parts given appear, in the order of a run, in seconds.
    #[test]
    fn timings_are_written_in_seconds_for_the_parts_that_happened() {
        let t = Timings {
            read: Some(Duration::from_millis(12)),
            solve: Some(Duration::from_millis(1500)),
            write: Some(Duration::from_micros(250)),
            ..Timings::default()
        };
        assert_eq!(
            timings_json(&t),
            serde_json::json!({ "read": 0.012, "solve": 1.5, "write": 0.00025 })
        );
        assert_eq!(
            timings_summary(&t),
            "\ntime: read 0.01 s, solve 1.50 s, write 0.00 s\n"
        );
        let doc = with_timings(serde_json::json!({ "status": "solved" }), &t);
        assert_eq!(doc["status"], "solved");
        assert_eq!(doc["timings"]["solve"], 1.5);
        assert!(doc["timings"].get("condense").is_none());
    }
}
