//! Load cases by name (`[loads.NAME]`, `[load.NAME]`) and `[[history]]` stages in both file
//! kinds (`history.md`): what the readers make of every key, checked against the files' own
//! numbers and hand computations, and every bad history refused with file, line, column and
//! key.

use std::path::{Path, PathBuf};

use unilateral_io::{read_contact_zone, read_model, read_problem, InputErrorKind, Problem};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/history")
        .join(name)
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A one-pair contact zone with the cases `dead` and `push`, and then `tail`.
fn zone_with(tail: &str) -> String {
    format!(
        "[contact_zone]\nfriction = 0.5\nRnn = [[1000.0]]\nRtt = [[100.0]]\n\n\
         [load.dead]\nnormal = [10.0]\n\n[load.push]\ntangential = [8.0]\n\n{tail}"
    )
}

/// The message of the error reading `path`, checked to be located (`file:line:col: key:`).
fn error_of(path: &Path, at: &str, key: &str, kind: InputErrorKind) -> String {
    let err = read_problem(path).unwrap_err();
    let text = err.to_string();
    let place = format!("{}:{at}: {key}: ", path.display());
    assert!(text.starts_with(&place), "{text}\n  expected at {place}");
    assert_eq!(err.kind, kind, "{text}");
    text[place.len()..].to_string()
}

// Reference: the file's own numbers (tests/data/history/zone-cycle.toml).
#[test]
fn a_contact_zone_file_reads_its_cases_and_stages() {
    let p = read_contact_zone(&data("zone-cycle.toml")).unwrap();
    let names: Vec<&str> = p.zone.cases.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["dead", "push"]);
    assert_eq!(p.zone.cases[0].load.normal, [10.0]);
    assert_eq!(p.zone.cases[0].load.tangential, [0.0]);
    assert_eq!(p.zone.cases[1].load.tangential, [8.0]);
    // no case is called constant or variable: the paper's two groups are zero
    assert_eq!(p.zone.constant.normal, [0.0]);
    assert_eq!(p.zone.variable.tangential, [0.0]);
    let stages = p.history.unwrap();
    let got: Vec<(&str, Vec<Option<f64>>)> = stages
        .iter()
        .map(|s| (s.name.as_str(), s.factors.clone()))
        .collect();
    assert_eq!(
        got,
        [
            ("self-weight", vec![Some(1.0), None]),
            ("push", vec![None, Some(1.0)]),
            ("stage 3", vec![None, Some(0.0)]),
            ("pull", vec![None, Some(-1.0)]),
            ("release", vec![None, Some(0.0)]),
        ]
    );
}

// Reference: the propped cantilever by hand (any table of fixed-end actions): a point load P
// at mid-span puts 5P/16 on the prop (here 5·16/16 = 5 in compression); an axial force F at
// mid-span splits equally between the clamp and the prop, so the tip's link holds it with
// x_t = −F/2 = −2.
#[test]
fn a_structural_model_reads_its_cases_and_stages() {
    let p = read_model(&data("model-stages.toml")).unwrap();
    assert_eq!(p.model.cases(), ["dead", "push"]);
    let stages = p.history.as_ref().unwrap();
    assert_eq!(stages.len(), 4);
    assert_eq!(stages[2].name, "stage 3");
    assert_eq!(stages[3].name, "pull");
    assert_eq!(stages[3].factors, [Some(1.5), Some(-1.0)]);
    let c = p.model.condense().unwrap();
    let zone = unilateral_analysis::zone_of(&c);
    let names: Vec<&str> = zone.cases.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["dead", "push"]);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
    let dead = &zone.cases[0].load;
    let push = &zone.cases[1].load;
    assert!(
        close(dead.normal[0], 5.0) && dead.tangential[0].abs() < 1e-12,
        "{dead:?}"
    );
    assert!(
        close(push.tangential[0], -2.0) && push.normal[0].abs() < 1e-12,
        "{push:?}"
    );
    assert_eq!(zone.variable.normal, [0.0]);
    zone.validate().unwrap();

    // The full results at the end of stage "pull" (dead = 1.5, push = −1) with the tip stuck:
    // the clamp takes 11P/16 vertically, the moment 3PL/16 (counter-clockwise on the beam)
    // and half the axial force, each times its factor (P = 16, L = 4, F = 4).
    let factors = [1.5, -1.0];
    let bonded = c.bonded_at(&factors, 4.0);
    let pairs = [unilateral_contact::PairResult {
        name: "tip".into(),
        x_n: bonded.x_n[0],
        x_t: bonded.x_t[0],
        z_n: bonded.z_n[0],
        z_t: bonded.z_t[0],
        state: unilateral_contact::PairState::Stick,
    }];
    // The end of stage 4 (pseudo-time 3 + s = 4).
    let end = unilateral_analysis::Place::Stage { stage: 4, s: 1.0 };
    let r = unilateral_analysis::recover_at(&c, &factors, end, &pairs).unwrap();
    assert_eq!(r.p, 4.0);
    let at = |label: unilateral_fem::DofLabel| {
        r.reactions
            .iter()
            .find(|x| x.node.0 == 0 && x.dof.label() == Some(label))
            .unwrap()
            .value
    };
    assert!(close(at(unilateral_fem::DofLabel::Uy), 1.5 * 11.0), "{r:?}");
    assert!(close(
        at(unilateral_fem::DofLabel::Rz),
        1.5 * 3.0 * 16.0 * 4.0 / 16.0
    ));
    assert!(close(at(unilateral_fem::DofLabel::Ux), 2.0));
    // one factor per case, or a located refusal of the call (not a panic)
    assert!(unilateral_analysis::recover_at(&c, &[1.0], end, &pairs).is_err());
}

// Reference: the files of the paper's method mean what they meant (no history, the two
// groups as the cases of their names).
#[test]
fn files_without_a_history_keep_their_meaning() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let Problem::ContactZone(z) = read_problem(&root.join("example1-contact-zone.toml")).unwrap()
    else {
        panic!("a contact-zone file")
    };
    assert!(z.history.is_none());
    let names: Vec<&str> = z.zone.cases.iter().map(|c| c.name.as_str()).collect();
    assert!(names.contains(&"variable"));
    let v = z.zone.cases.iter().find(|c| c.name == "variable").unwrap();
    assert_eq!(v.load, z.zone.variable);
    let m = read_model(&root.join("example1-beam.toml")).unwrap();
    assert!(m.history.is_none());
    assert!(m
        .model
        .cases()
        .iter()
        .all(|c| c == "constant" || c == "variable"));
}

// Reference: history.md (a case other than constant/variable has a factor only in a history).
#[test]
fn a_named_case_without_a_history_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "zone.toml", &zone_with(""));
    let msg = error_of(&path, "6:7", "load.dead", InputErrorKind::UnknownKey);
    assert!(msg.contains("is used only by a load history"), "{msg}");
    let text = std::fs::read_to_string(data("model-stages.toml")).unwrap();
    let cut = text.find("[[history]]").unwrap();
    let path = write(dir.path(), "model.toml", &text[..cut]);
    let err = read_problem(&path).unwrap_err().to_string();
    assert!(
        err.contains(": loads.dead: load case `dead` is used only by a load history"),
        "{err}"
    );
    // a typo of the two groups gets its suggestion
    let path = write(
        dir.path(),
        "typo.toml",
        "[contact_zone]\nfriction = 0.5\nRnn = [[1.0]]\nRtt = [[1.0]]\n[load.varaible]\nnormal = [1.0]\n",
    );
    let msg = error_of(&path, "5:7", "load.varaible", InputErrorKind::UnknownKey);
    assert!(msg.contains("(did you mean `variable`?)"), "{msg}");
}

// Reference: history.md, "An unknown case name … exit 2 with file, line and key".
#[test]
fn an_unknown_case_is_named_with_a_suggestion() {
    let path = data("bad-unknown-case.toml");
    let msg = error_of(
        &path,
        "16:13",
        "history[2].factors.puhs",
        InputErrorKind::UnknownKey,
    );
    assert_eq!(
        msg,
        "unknown load case `puhs` in the factors of stage 2 (did you mean `push`?); \
         the load cases are `dead`, `push`"
    );
    // the same in a structural model
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(data("model-stages.toml"))
        .unwrap()
        .replace("factors = { push = 0.0 }", "factors = { wind = 0.0 }");
    let path = write(dir.path(), "model.toml", &text);
    let err = read_problem(&path).unwrap_err().to_string();
    assert!(
        err.contains(
            ": history[3].factors.wind: unknown load case `wind` in the factors of stage 3;"
        ),
        "{err}"
    );
}

// Reference: history.md, "an empty history … exit 2".
#[test]
fn an_empty_history_is_refused() {
    let msg = error_of(
        &data("bad-empty.json"),
        "4:14",
        "history",
        InputErrorKind::Size,
    );
    assert!(msg.starts_with("the history is empty"), "{msg}");
    let dir = tempfile::tempdir().unwrap();
    // (a top-level key in TOML comes before the tables)
    let text = format!("history = []\n{}", zone_with(""));
    let path = write(dir.path(), "zone.toml", &text);
    let msg = error_of(&path, "1:11", "history", InputErrorKind::Size);
    assert!(msg.starts_with("the history is empty"), "{msg}");
}

// Reference: history.md, "A stage in which no factor changes is bad input … naming the stage".
#[test]
fn a_stage_that_changes_nothing_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "zone.toml",
        &zone_with(
            "[[history]]\nfactors = { dead = 1.0 }\n\n\
             [[history]]\nname = \"again\"\nfactors = { dead = 1.0, push = 0 }\n",
        ),
    );
    let msg = error_of(&path, "15:1", "history[2]", InputErrorKind::Invalid);
    assert_eq!(
        msg,
        "stage 2 (\"again\") changes no load factor: every factor it gives is the one the \
         stage starts with (dead = 1, push = 0); a stage must change at least one factor \
         (every case starts at 0)"
    );
    let path = write(
        dir.path(),
        "first.toml",
        &zone_with("[[history]]\nfactors = { push = 0.0 }\n"),
    );
    let msg = error_of(&path, "12:1", "history[1]", InputErrorKind::Invalid);
    assert!(msg.starts_with("stage 1 changes no load factor"), "{msg}");
    let path = write(
        dir.path(),
        "none.toml",
        &zone_with("[[history]]\nfactors = {}\n"),
    );
    let msg = error_of(&path, "12:1", "history[1]", InputErrorKind::Invalid);
    assert!(msg.contains("it names no load case"), "{msg}");
}

// Reference: history.md, "a non-finite factor: exit 2 with file, line and key".
#[test]
fn a_non_finite_factor_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (word, shown) in [("inf", "inf"), ("-inf", "-inf"), ("nan", "NaN")] {
        let path = write(
            dir.path(),
            "zone.toml",
            &zone_with(&format!("[[history]]\nfactors = {{ push = {word} }}\n")),
        );
        let msg = error_of(
            &path,
            "13:20",
            "history[1].factors.push",
            InputErrorKind::Value,
        );
        assert_eq!(msg, format!("{shown} is not a finite number"));
    }
}

// Reference: history.md, "With a [[history]] the [solve] keys target, trace and tightening do
// not apply (reject them with a clear message)".
#[test]
fn the_keys_of_the_single_load_path_are_refused_with_a_history() {
    let msg = error_of(
        &data("bad-tightening.toml"),
        "10:1",
        "solve.tightening",
        InputErrorKind::Invalid,
    );
    assert!(
        msg.starts_with("`tightening` does not apply to a file with a [[history]]"),
        "{msg}"
    );
    let dir = tempfile::tempdir().unwrap();
    for (line, key) in [("target = 2.0", "target"), ("trace = \"end\"", "trace")] {
        let path = write(
            dir.path(),
            "zone.toml",
            &zone_with(&format!(
                "[solve]\npivot_tolerance = 1e-9\n{line}\n\n[[history]]\nfactors = {{ push = 1.0 }}\n"
            )),
        );
        let msg = error_of(
            &path,
            "14:1",
            &format!("solve.{key}"),
            InputErrorKind::Invalid,
        );
        assert!(msg.starts_with(&format!("`{key}` does not apply")), "{msg}");
    }
    // the engine's keys stay
    let path = write(
        dir.path(),
        "ok.toml",
        &zone_with("[solve]\nmax_pivots = 50\n\n[[history]]\nfactors = { push = 1.0 }\n"),
    );
    let p = read_contact_zone(&path).unwrap();
    assert_eq!(p.settings.engine.max_pivots, Some(50));
    // and in a structural model
    let text = std::fs::read_to_string(data("model-stages.toml")).unwrap();
    let path = write(
        dir.path(),
        "model.toml",
        &format!("{text}\n[solve]\ntightening = 0.5\n"),
    );
    let err = read_problem(&path).unwrap_err().to_string();
    assert!(
        err.contains(": solve.tightening: `tightening` does not apply"),
        "{err}"
    );
}

// Reference: the format of a stage (history.md): `name` and `factors`, a table.
#[test]
fn a_malformed_stage_is_located() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "zone.toml",
        &zone_with("[[history]]\nfactors = 1.0\n"),
    );
    let msg = error_of(
        &path,
        "13:11",
        "history[1].factors",
        InputErrorKind::WrongType,
    );
    assert!(msg.starts_with("expected a table of load factors"), "{msg}");
    let path = write(
        dir.path(),
        "zone.toml",
        &zone_with("[[history]]\nfactor = { push = 1.0 }\n"),
    );
    let msg = error_of(
        &path,
        "13:1",
        "history[1].factor",
        InputErrorKind::UnknownKey,
    );
    assert!(msg.contains("(did you mean `factors`?)"), "{msg}");
    let path = write(
        dir.path(),
        "zone.toml",
        &zone_with("[[history]]\nname = \"push\"\n"),
    );
    let msg = error_of(
        &path,
        "12:1",
        "history[1].factors",
        InputErrorKind::MissingKey,
    );
    assert!(msg.starts_with("missing key `factors`"), "{msg}");
    let path = write(
        dir.path(),
        "zone.toml",
        &format!("history = 3\n{}", zone_with("")),
    );
    let msg = error_of(&path, "1:11", "history", InputErrorKind::WrongType);
    assert!(msg.contains("one per stage"), "{msg}");
}
