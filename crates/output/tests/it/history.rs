//! The outputs of a load history on a hand-made history of two pairs and three stages.
//!
//! Reference: the history below is written out by hand (it is a plausible run of two pairs
//! with friction coefficient 0.2 under a constant normal load `dead` and a tangential load
//! `push` taken up, then released); every expected value in these tests is read off it or
//! worked out from it by hand in the comments, never produced by the writers.
//!
//! Set `UNILATERAL_HISTORY_OUT=DIR` to keep the pictures (to render them to PNG by hand).

use unilateral_contact::{
    Event, EventKind, HistoryResidual, HistorySolution, HistoryStep, PairResult, PairState,
    StageSolution, StageStatus,
};
use unilateral_output::{
    busiest_case, history_csv, history_curves_svg, history_document, history_json,
    history_states_svg, history_summary, state_runs, with_history, CurveKind, HistoryChartOptions,
    HISTORY_BREAKPOINTS_CSV, HISTORY_EVENTS_CSV,
};

fn pair(name: &str, x_n: f64, x_t: f64, z_t: f64, state: PairState) -> PairResult {
    PairResult {
        name: name.into(),
        x_n,
        x_t,
        z_n: 0.0,
        z_t,
        state,
    }
}

fn event(pair: usize, kind: EventKind) -> Event {
    Event {
        pair,
        name: ["left", "right"][pair].into(),
        kind,
        while_open: false,
    }
}

#[allow(clippy::too_many_arguments)]
fn step(
    k: usize,
    s: f64,
    factors: [f64; 2],
    entering: &str,
    leaving: &str,
    events: Vec<Event>,
    pairs: Vec<PairResult>,
) -> HistoryStep {
    HistoryStep {
        step: k,
        s,
        factors: factors.to_vec(),
        entering: Var::Z(0),
        leaving: Var::X(0),
        entering_label: entering.into(),
        leaving_label: leaving.into(),
        events,
        pairs,
    }
}

use unilateral_lcp::Var;
use PairState::{SlipMinus, SlipPlus, Stick};

/// Two pairs `left`, `right` (f = 0.2, x_n = 10 under `dead`, so the friction limit is 2).
///
/// * stage 1 "self-weight": `dead` 0 → 1, no change of scheme, both stick, no slip;
/// * stage 2 "push": `push` 0 → 1; `left` starts to slip (+) at s = 0.4, `right` at s = 0.8;
///   at the end slips 3e-3 and 1e-3;
/// * stage 3 "release": `push` 1 → 0; both stick at s = 0 keeping their slips, `left` slips
///   back (−) from s = 0.9 and ends with slip 2.5e-3; `right` sticks with x_t = 1.2.
fn history() -> HistorySolution {
    let r = HistoryResidual {
        equation: 1e-15,
        complementarity: 2e-16,
        feasibility: 0.0,
        dissipation: 3e-16,
    };
    let s1 = StageSolution {
        stage: 1,
        name: "self-weight".into(),
        factors_start: vec![0.0, 0.0],
        factors_end: vec![1.0, 0.0],
        status: StageStatus::Completed,
        s_end: 1.0,
        steps: vec![],
        pairs: vec![
            pair("left", 10.0, 0.0, 0.0, Stick),
            pair("right", 10.0, 0.0, 0.0, Stick),
        ],
        residual: r,
        mechanism: None,
        reason: None,
    };
    let s2 = StageSolution {
        stage: 2,
        name: "push".into(),
        factors_start: vec![1.0, 0.0],
        factors_end: vec![1.0, 1.0],
        status: StageStatus::Completed,
        s_end: 1.0,
        steps: vec![
            step(
                1,
                0.4,
                [1.0, 0.4],
                "z_t1+",
                "x_t1+",
                vec![event(0, EventKind::StartsSlippingPlus)],
                vec![
                    pair("left", 10.0, -2.0, 0.0, SlipPlus),
                    pair("right", 10.0, -1.0, 0.0, Stick),
                ],
            ),
            step(
                2,
                0.8,
                [1.0, 0.8],
                "z_t2+",
                "x_t2+",
                vec![event(1, EventKind::StartsSlippingPlus)],
                vec![
                    pair("left", 10.0, -2.0, 1.5e-3, SlipPlus),
                    pair("right", 10.0, -2.0, 0.0, SlipPlus),
                ],
            ),
        ],
        pairs: vec![
            pair("left", 10.0, -2.0, 3e-3, SlipPlus),
            pair("right", 10.0, -2.0, 1e-3, SlipPlus),
        ],
        residual: r,
        mechanism: None,
        reason: None,
    };
    let s3 = StageSolution {
        stage: 3,
        name: "release".into(),
        factors_start: vec![1.0, 1.0],
        factors_end: vec![1.0, 0.0],
        status: StageStatus::Completed,
        s_end: 1.0,
        steps: vec![
            step(
                1,
                0.0,
                [1.0, 1.0],
                "x_t1+",
                "z_t1+",
                vec![event(0, EventKind::Sticks), event(1, EventKind::Sticks)],
                vec![
                    pair("left", 10.0, -2.0, 3e-3, Stick),
                    pair("right", 10.0, -2.0, 1e-3, Stick),
                ],
            ),
            step(
                2,
                0.9,
                [1.0, 0.1],
                "z_t1-",
                "x_t1-",
                vec![event(0, EventKind::StartsSlippingMinus)],
                vec![
                    pair("left", 10.0, 2.0, 3e-3, SlipMinus),
                    pair("right", 10.0, 1.0, 1e-3, Stick),
                ],
            ),
        ],
        pairs: vec![
            pair("left", 10.0, 2.0, 2.5e-3, SlipMinus),
            pair("right", 10.0, 1.2, 1e-3, Stick),
        ],
        residual: HistoryResidual {
            dissipation: 4e-14,
            ..r
        },
        mechanism: None,
        reason: None,
    };
    HistorySolution {
        cases: vec!["dead".into(), "push".into()],
        names: vec!["left".into(), "right".into()],
        stages: vec![s1, s2, s3],
        notes: vec![],
    }
}

/// The same history stopped by a mechanism in stage 3 at s = 0.5.
fn stopped() -> HistorySolution {
    let mut h = history();
    let st = &mut h.stages[2];
    st.status = StageStatus::Mechanism;
    st.s_end = 0.5;
    st.steps.truncate(1);
    st.mechanism = Some(vec![(0.0, 1.0), (0.0, -0.5)]);
    st.reason = Some("the pairs slide together".into());
    h
}

// ---------------------------------------------------------------------------------------------
// JSON

#[test]
fn json_follows_the_contract_with_the_hand_data() {
    let h = history();
    let doc = history_document(&h).unwrap();
    // It is a JSON document (a round trip through the text parses).
    let text = serde_json::to_string_pretty(&doc).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(doc["status"], "completed");
    // Final state: the end of stage 3, factors dead 1, push 0.
    assert_eq!(
        doc["factors"],
        serde_json::json!({ "dead": 1.0, "push": 0.0 })
    );
    assert_eq!(doc["pairs"][0]["name"], "left");
    assert_eq!(doc["pairs"][0]["z_t"], 2.5e-3);
    assert_eq!(doc["pairs"][0]["state"], "slip-");
    assert_eq!(doc["pairs"][1]["x_t"], 1.2);
    assert_eq!(doc["pivots"], 4); // 0 + 2 + 2 steps
    let hist = doc["history"].as_array().unwrap();
    assert_eq!(hist.len(), 3);
    let keys = |v: &serde_json::Value| {
        let mut k: Vec<String> = v.as_object().unwrap().keys().cloned().collect();
        k.sort();
        k
    };
    // The contract's keys of a stage are all there (and ours beside them).
    for key in [
        "stage",
        "name",
        "factors_start",
        "factors_end",
        "status",
        "s_end",
        "steps",
        "pairs",
        "residual",
    ] {
        assert!(keys(&hist[1]).contains(&key.to_string()), "{key}");
    }
    assert_eq!(hist[1]["stage"], 2);
    assert_eq!(hist[1]["name"], "push");
    assert_eq!(
        hist[1]["factors_start"],
        serde_json::json!({ "dead": 1.0, "push": 0.0 })
    );
    assert_eq!(
        hist[1]["factors_end"],
        serde_json::json!({ "dead": 1.0, "push": 1.0 })
    );
    assert_eq!(hist[1]["status"], "completed");
    assert_eq!(hist[1]["s_end"], 1.0);
    let st = &hist[1]["steps"][0];
    assert_eq!(
        keys(st),
        ["changes", "entering", "events", "factors", "leaving", "pairs", "s", "step"]
    );
    assert_eq!(st["step"], 1);
    assert_eq!(st["s"], 0.4);
    assert_eq!(
        st["factors"],
        serde_json::json!({ "dead": 1.0, "push": 0.4 })
    );
    assert_eq!(st["entering"], "z_t1+");
    assert_eq!(st["leaving"], "x_t1+");
    assert_eq!(
        st["events"],
        serde_json::json!(["pair left starts to slip in the + direction"])
    );
    assert_eq!(
        st["changes"],
        serde_json::json!([{ "pair": 1, "name": "left", "what": "slips", "direction": "+" }])
    );
    // Stage 3 starts by both pairs sticking with the slips they have (3e-3 and 1e-3).
    let st = &hist[2]["steps"][0];
    assert_eq!(
        st["events"],
        serde_json::json!([
            "pair left sticks (slip 3e-3 kept)",
            "pair right sticks (slip 1e-3 kept)"
        ])
    );
    assert_eq!(st["changes"][1]["what"], "sticks");
    assert_eq!(st["changes"][1]["direction"], serde_json::Value::Null);
    assert_eq!(st["changes"][1]["slip_kept"], 1e-3);
    assert_eq!(hist[2]["steps"][1]["changes"][0]["direction"], "-");
    assert_eq!(hist[2]["pairs"][1]["state"], "stick");
    assert_eq!(
        keys(&hist[2]["pairs"][0]),
        ["name", "pair", "state", "x_n", "x_t", "z_n", "z_t"]
    );
    assert_eq!(
        hist[2]["residual"],
        serde_json::json!({ "equation": 1e-15, "complementarity": 2e-16, "feasibility": 0.0, "dissipation": 4e-14 })
    );
    assert_eq!(hist[2]["mechanism"], serde_json::Value::Null);
    // The bare array is the document's `history`.
    assert_eq!(history_json(&h).unwrap(), doc["history"]);
}

#[test]
fn a_stage_stopped_by_a_mechanism_says_where() {
    let h = stopped();
    let doc = history_document(&h).unwrap();
    assert_eq!(doc["status"], "mechanism");
    let st = &doc["history"][2];
    assert_eq!(st["status"], "mechanism");
    assert_eq!(st["s_end"], 0.5);
    // push goes 1 → 0 over the stage: at s = 0.5 it is 1 + 0.5·(0 − 1) = 0.5.
    assert_eq!(
        st["factors_reached"],
        serde_json::json!({ "dead": 1.0, "push": 0.5 })
    );
    assert_eq!(
        doc["factors"],
        serde_json::json!({ "dead": 1.0, "push": 0.5 })
    );
    assert_eq!(
        st["mechanism"],
        serde_json::json!([
            { "pair": 1, "dz_n": 0.0, "dz_t": 1.0 },
            { "pair": 2, "dz_n": 0.0, "dz_t": -0.5 }
        ])
    );
    assert_eq!(doc["mechanism"], st["mechanism"]);
    assert_eq!(st["reason"], "the pairs slide together");
    let reading = doc["reading"].as_str().unwrap();
    assert!(
        reading.contains("stage 3") && reading.contains("push = 0.5"),
        "{reading}"
    );
}

#[test]
fn a_history_is_added_to_a_document_of_the_final_state() {
    let doc = serde_json::json!({ "status": "target_reached", "nodes": [1, 2] });
    let doc = with_history(doc, &stopped()).unwrap();
    assert_eq!(doc["status"], "mechanism");
    assert_eq!(doc["nodes"], serde_json::json!([1, 2]));
    assert_eq!(doc["history"].as_array().unwrap().len(), 3);
}

#[test]
fn every_writer_refuses_a_non_finite_number_and_names_it() {
    type Spoil = fn(&mut HistorySolution);
    let spoil: [(&str, Spoil); 6] = [
        ("history[2].steps[1].s", |h| {
            h.stages[1].steps[0].s = f64::NAN
        }),
        ("history[3].pairs[2].z_t", |h| {
            h.stages[2].pairs[1].z_t = f64::INFINITY
        }),
        ("history[2].steps[2].pairs[1].x_n", |h| {
            h.stages[1].steps[1].pairs[0].x_n = f64::NEG_INFINITY
        }),
        ("history[1].factors_end.push", |h| {
            h.stages[0].factors_end[1] = f64::NAN
        }),
        ("history[3].residual.dissipation", |h| {
            h.stages[2].residual.dissipation = f64::NAN
        }),
        ("history[3].mechanism[1].dz_t", |h| {
            h.stages[2].mechanism = Some(vec![(0.0, f64::NAN)])
        }),
    ];
    let opts = HistoryChartOptions::default();
    for (field, f) in spoil {
        let mut h = history();
        f(&mut h);
        let e = history_document(&h).unwrap_err();
        assert_eq!(e.field, field);
        assert!(e.to_string().contains("fault of the program"));
        assert_eq!(history_csv(&h).unwrap_err().field, field);
        assert_eq!(history_summary(&h, "t").unwrap_err().field, field);
        assert_eq!(history_states_svg(&h).unwrap_err().field, field);
        let k = CurveKind::TangentialForce;
        assert_eq!(history_curves_svg(&h, &opts, &k).unwrap_err().field, field);
    }
}

// ---------------------------------------------------------------------------------------------
// CSV

/// The cells of a CSV line (quoted cells may hold commas and doubled quotes).
fn cells(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    out.push(cur);
    out
}

/// Header and rows of a table, every row as long as the header.
fn table(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let head = cells(lines.next().unwrap());
    let rows: Vec<Vec<String>> = lines.map(cells).collect();
    for r in &rows {
        assert_eq!(r.len(), head.len(), "{r:?} against {head:?}");
    }
    (head, rows)
}

#[test]
fn csv_tables_hold_the_hand_data() {
    let mut h = history();
    h.stages[1].name = "push, then \"more\"".into(); // a name that needs quoting
    let files = history_csv(&h).unwrap();
    let names: Vec<&str> = files.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "history_stage_01.csv",
            "history_stage_02.csv",
            "history_stage_03.csv",
            HISTORY_EVENTS_CSV,
            HISTORY_BREAKPOINTS_CSV
        ]
    );
    let (head, rows) = table(&files[2].1);
    assert_eq!(head, ["pair", "name", "x_n", "x_t", "z_n", "z_t", "state"]);
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0][1], "left");
    assert_eq!(rows[0][5].parse::<f64>().unwrap(), 2.5e-3);
    assert_eq!(rows[0][6], "slip-");
    assert_eq!(rows[1][3].parse::<f64>().unwrap(), 1.2);

    // Events: 0 + 2 + 3 changes of pairs.
    let (head, rows) = table(&files[3].1);
    assert_eq!(
        head,
        [
            "stage",
            "stage_name",
            "step",
            "s",
            "time",
            "factor_dead",
            "factor_push",
            "pair",
            "name",
            "event",
            "direction",
            "slip_kept",
            "description"
        ]
    );
    assert_eq!(rows.len(), 5);
    assert_eq!(rows[0][1], "push, then \"more\"");
    // Stage 2, step 2 (right slips at s = 0.8): pseudo-time 1 + 0.8, push 0.8.
    assert_eq!(rows[1][0], "2");
    assert_eq!(rows[1][2], "2");
    assert!((rows[1][4].parse::<f64>().unwrap() - 1.8).abs() < 1e-12);
    assert_eq!(rows[1][6].parse::<f64>().unwrap(), 0.8);
    assert_eq!(
        (rows[1][8].as_str(), rows[1][9].as_str()),
        ("right", "slips")
    );
    assert_eq!(rows[1][10], "+");
    // Stage 3 step 1: left sticks keeping 3e-3.
    assert_eq!(rows[2][9], "sticks");
    assert_eq!(rows[2][11].parse::<f64>().unwrap(), 3e-3);
    assert_eq!(rows[2][12], "pair left sticks (slip 3e-3 kept)");
    assert_eq!(rows[4][10], "-");

    // Breakpoints: (steps + the end) × 2 pairs per stage = (1 + 3 + 3) × 2.
    let (head, rows) = table(&files[4].1);
    assert_eq!(head[2], "point");
    assert_eq!(head.len(), 5 + 2 + 7);
    assert_eq!(rows.len(), 14);
    // The last two rows: the end of stage 3 (pseudo-time 3, push 0).
    let last = &rows[13];
    assert_eq!((last[0].as_str(), last[2].as_str()), ("3", "end"));
    assert_eq!(last[4].parse::<f64>().unwrap(), 3.0);
    assert_eq!(last[6].parse::<f64>().unwrap(), 0.0);
    assert_eq!(last[8], "right");
    assert_eq!(last[10].parse::<f64>().unwrap(), 1.2);
    // Every number of every table parses and is finite.
    for (_, text) in &files {
        for line in text.lines().skip(1) {
            for c in cells(line) {
                if let Ok(v) = c.parse::<f64>() {
                    assert!(v.is_finite(), "{line}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Summary

#[test]
fn summary_has_a_line_per_stage_and_the_final_pairs() {
    let s = history_summary(&history(), "two pairs").unwrap();
    keep("summary.txt", &s);
    let lines: Vec<&str> = s.lines().collect();
    assert_eq!(lines[0], "two pairs");
    assert!(lines[1].starts_with("status: completed"), "{s}");
    // One line per stage: number, name, status, s_end, changes (0, 2, 3).
    for (k, name, changes) in [(1, "self-weight", 0), (2, "push", 2), (3, "release", 3)] {
        let line = lines
            .iter()
            .find(|l| l.split_whitespace().nth(1) == Some(name))
            .unwrap_or_else(|| panic!("no line of stage {name}:\n{s}"));
        let w: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(w[0], k.to_string());
        assert_eq!(w[2], "completed");
        assert_eq!(w[3], "1");
        assert_eq!(w[4], changes.to_string());
    }
    // Stage 3's residual max is its dissipation, 4e-14.
    assert!(s.contains("4.000e-14"), "{s}");
    let left = lines
        .iter()
        .find(|l| l.trim_start().starts_with("left"))
        .unwrap();
    let w: Vec<&str> = left.split_whitespace().collect();
    assert_eq!(w, ["left", "10", "2", "0", "0.0025", "slip-"]);
}

#[test]
fn summary_counts_states_of_many_pairs() {
    // 30 pairs: 10 open, 12 stick, 5 slip+, 3 slip- by construction.
    let mut h = history();
    h.stages.truncate(1);
    let states: Vec<PairState> = (0..30)
        .map(|i| match i {
            0..=9 => PairState::Open,
            10..=21 => Stick,
            22..=26 => SlipPlus,
            _ => SlipMinus,
        })
        .collect();
    h.names = (0..30).map(|i| format!("p{i}")).collect();
    h.stages[0].pairs = states
        .iter()
        .enumerate()
        .map(|(i, &s)| pair(&format!("p{i}"), 1.0, 0.0, 0.0, s))
        .collect();
    let s = history_summary(&h, "many").unwrap();
    assert!(
        s.contains("final state of the 30 pairs: 10 open, 12 stick, 5 slip+, 3 slip-"),
        "{s}"
    );
    assert!(!s.contains("p29"));
}

#[test]
fn mechanism_in_the_summary() {
    let s = history_summary(&stopped(), "t").unwrap();
    assert!(s.contains("status: mechanism"), "{s}");
    assert!(s.contains("mechanism in stage 3 at s = 0.5"), "{s}");
    assert!(s.contains("stage 3: the pairs slide together"), "{s}");
}

/// A history whose last stage the engine failed in: its pairs are where the engine stopped,
/// and the summary says so instead of calling them the final state (they read like an answer:
/// an open pair carrying a friction force of 1e5 N in a reviewer's run).
#[test]
fn a_failed_stage_is_no_final_state_in_the_summary() {
    let mut h = history();
    let st = &mut h.stages[2];
    st.status = StageStatus::NumericalFailure;
    st.reason = Some("the state reached at s = 1 of stage 3 fails its check".into());
    let s = history_summary(&h, "t").unwrap();
    assert!(
        s.contains("the pairs where the engine stopped (not a solution):"),
        "{s}"
    );
    assert!(!s.contains("final state"), "{s}");
    assert!(
        s.contains("stage 3: the state reached at s = 1 of stage 3 fails its check"),
        "{s}"
    );
    // A completed history keeps its heading.
    let s = history_summary(&history(), "t").unwrap();
    assert!(s.contains("final state of the pairs:"), "{s}");
}

// ---------------------------------------------------------------------------------------------
// Pictures

/// Well-formed XML as far as these writers go: tags nest and close, attribute values are
/// quoted, no stray `<` or `&` in text. Returns the start tags (name and attributes).
fn tags(svg: &str) -> Vec<(String, Vec<(String, String)>)> {
    let mut out = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find('<') {
        let text = &rest[..i];
        assert!(!text.contains('>'), "stray > in {text:?}");
        for (k, _) in text.match_indices('&') {
            let ent = &text[k..text[k..].find(';').map_or(text.len(), |e| k + e + 1)];
            assert!(
                ["&amp;", "&lt;", "&gt;", "&quot;", "&apos;"].contains(&ent),
                "entity {ent}"
            );
        }
        let end = rest[i..].find('>').expect("an unclosed tag") + i;
        let tag = &rest[i + 1..end];
        rest = &rest[end + 1..];
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(stack.pop().as_deref(), Some(name), "closing {name}");
            continue;
        }
        let closed = tag.ends_with('/');
        let tag = tag.trim_end_matches('/');
        let name = tag.split_whitespace().next().unwrap().to_string();
        let mut attrs = Vec::new();
        let mut a = tag[name.len()..].trim();
        while !a.is_empty() {
            let eq = a
                .find("=\"")
                .unwrap_or_else(|| panic!("unquoted attribute in <{tag}>"));
            let key = a[..eq].trim().to_string();
            let close = a[eq + 2..].find('"').expect("an unclosed value") + eq + 2;
            let value = a[eq + 2..close].to_string();
            assert!(!value.contains('<'));
            assert!(
                !attrs.iter().any(|(k, _): &(String, String)| *k == key),
                "{key} twice"
            );
            attrs.push((key, value));
            a = a[close + 1..].trim();
        }
        if !closed {
            stack.push(name.clone());
        }
        out.push((name, attrs));
    }
    assert!(stack.is_empty(), "unclosed {stack:?}");
    assert_eq!(out.first().map(|t| t.0.as_str()), Some("svg"));
    out
}

fn attr<'a>(t: &'a (String, Vec<(String, String)>), key: &str) -> Option<&'a str> {
    t.1.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
}

/// No number outside the titles is `NaN` or infinite: every number of the drawing attributes
/// parses as a finite `f64`.
fn all_numbers_finite(svg: &str) {
    for t in tags(svg) {
        for (k, v) in &t.1 {
            if matches!(
                k.as_str(),
                "d" | "points"
                    | "x"
                    | "y"
                    | "x1"
                    | "y1"
                    | "x2"
                    | "y2"
                    | "cx"
                    | "cy"
                    | "r"
                    | "width"
                    | "height"
                    | "stroke-width"
            ) {
                let sep = |c: char| c == ' ' || c == ',' || (c.is_ascii_alphabetic() && c != 'e');
                for w in v.split(sep).filter(|w| !w.is_empty()) {
                    let x: f64 = w.parse().unwrap_or_else(|_| panic!("{w} in {k}={v}"));
                    assert!(x.is_finite());
                }
            }
        }
    }
}

fn keep(name: &str, svg: &str) {
    if let Ok(dir) = std::env::var("UNILATERAL_HISTORY_OUT") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(std::path::Path::new(&dir).join(name), svg).unwrap();
    }
}

fn polylines(svg: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    tags(svg)
        .iter()
        .filter(|t| t.0 == "polyline")
        .map(|t| {
            let pts = attr(t, "points")
                .unwrap()
                .split(' ')
                .map(|p| {
                    let (a, b) = p.split_once(',').unwrap();
                    (a.parse().unwrap(), b.parse().unwrap())
                })
                .collect();
            (attr(t, "stroke").unwrap().to_string(), pts)
        })
        .collect()
}

#[test]
fn the_curves_pass_through_every_breakpoint_in_order() {
    let h = history();
    let opts = HistoryChartOptions::default();
    let svg = history_curves_svg(&h, &opts, &CurveKind::TangentialForce).unwrap();
    keep("history-curves-force.svg", &svg);
    all_numbers_finite(&svg);
    // Both pairs are drawn (two panels), each as three polylines, one per stage, in three
    // colours: stage 1 from the origin to its end (2 points), stages 2 and 3 from the previous
    // end through their 2 steps to their end (4 points).
    let lines = polylines(&svg);
    assert_eq!(lines.len(), 6);
    let counts: Vec<usize> = lines.iter().map(|l| l.1.len()).collect();
    assert_eq!(counts, [2, 4, 4, 2, 4, 4]);
    assert_ne!(lines[0].0, lines[1].0);
    assert_ne!(lines[1].0, lines[2].0);
    // Each stage starts where the previous ended.
    assert_eq!(lines[0].1[1], lines[1].1[0]);
    assert_eq!(lines[1].1[3], lines[2].1[0]);
    // Pair left, by hand in (z_t, x_t): stage 2 goes (0, 0) → (0, −2) → (1.5e-3, −2) →
    // (3e-3, −2): the slip grows at constant force (a horizontal line to the right, y down in
    // SVG is up in force, so −2 lies below 0); stage 3 goes back up at z_t = 3e-3 to
    // x_t = +2 and then left to z_t = 2.5e-3: the loop of a slip reversed.
    let l2 = &lines[1].1;
    let l3 = &lines[2].1;
    assert!(l2[1].1 > l2[0].1, "x_t falls to −2 (lower on the page)");
    assert_eq!(l2[1].1, l2[2].1);
    assert_eq!(l2[2].1, l2[3].1);
    assert!(l2[1].0 < l2[2].0 && l2[2].0 < l2[3].0, "slip grows");
    assert_eq!(
        l3[0], l3[1],
        "the stick at s = 0 is a breakpoint at the same place"
    );
    assert_eq!(
        l3[1].0, l3[2].0,
        "x_t changes at constant slip while it sticks"
    );
    assert!(l3[2].1 < l3[1].1, "x_t rises from −2 to +2");
    assert!(l3[3].0 < l3[2].0, "the slip goes back");
    // (z_t horizontally): 0, 1.5e-3, 3e-3 are equally spaced.
    let d1 = l2[2].0 - l2[1].0;
    let d2 = l2[3].0 - l2[2].0;
    assert!((d1 - d2).abs() < 0.02, "{d1} {d2}");
}

#[test]
fn the_factor_curve_and_the_chosen_pairs() {
    let h = history();
    let opts = HistoryChartOptions {
        pairs: Some(vec!["right".into(), "nobody".into()]),
    };
    let svg = history_curves_svg(&h, &opts, &CurveKind::Factor("push".into())).unwrap();
    keep("history-curves-factor.svg", &svg);
    all_numbers_finite(&svg);
    let lines = polylines(&svg);
    assert_eq!(lines.len(), 3, "only the pair named that exists");
    // Pair right in (z_t, push): stage 2 (0, 0) → (0, 0.4) → (0, 0.8) → (1e-3, 1): the factor
    // rises at zero slip, then slips; stage 3: (1e-3, 1) → (1e-3, 1) → (1e-3, 0.1) → (1e-3, 0).
    let l2 = &lines[1].1;
    assert_eq!(l2[0].0, l2[1].0);
    assert_eq!(l2[1].0, l2[2].0);
    assert!(l2[3].0 > l2[2].0);
    assert!(l2[1].1 < l2[0].1 && l2[2].1 < l2[1].1 && l2[3].1 < l2[2].1);
    let l3 = &lines[2].1;
    assert!(l3.iter().all(|p| p.0 == l3[0].0), "right keeps its slip");
    // push 1, 0.1 and 0 are at 0.9 and 0.1 of the drop.
    let (a, b, c) = (l3[1].1, l3[2].1, l3[3].1);
    assert!(((b - a) / (c - a) - 0.9).abs() < 0.01);
    // The default case is the one whose factor changes most: dead and push both span 0..1,
    // and the first of equals is dead; with push going up to 3 it is push.
    assert_eq!(busiest_case(&h), Some(0));
    let mut h2 = h.clone();
    h2.stages[1].factors_end[1] = 3.0;
    h2.stages[2].factors_start[1] = 3.0;
    assert_eq!(busiest_case(&h2), Some(1));
    // An unknown case draws nothing, and says so.
    let svg = history_curves_svg(&h, &opts, &CurveKind::Factor("none".into())).unwrap();
    assert!(svg.contains("nothing to draw"));
}

#[test]
fn the_states_over_the_pseudo_time() {
    let h = history();
    let runs = state_runs(&h);
    // By hand (pseudo-time = stage − 1 + s):
    // left: stick 0..1.4 (stage 1, and stage 2 until it slips at s = 0.4), slip+ 1.4..2,
    //   stick 2..2.9, slip− 2.9..3;
    // right: stick 0..1.8, slip+ 1.8..2, stick 2..3.
    let want = [
        vec![
            (0.0, 1.4, Stick),
            (1.4, 2.0, SlipPlus),
            (2.0, 2.9, Stick),
            (2.9, 3.0, SlipMinus),
        ],
        vec![(0.0, 1.8, Stick), (1.8, 2.0, SlipPlus), (2.0, 3.0, Stick)],
    ];
    for (got, want) in runs.iter().zip(&want) {
        assert_eq!(got.len(), want.len(), "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g.t0 - w.0).abs() < 1e-12 && (g.t1 - w.1).abs() < 1e-12,
                "{g:?} {w:?}"
            );
            assert_eq!(g.state, w.2);
        }
    }
    let svg = history_states_svg(&h).unwrap();
    keep("history-states.svg", &svg);
    all_numbers_finite(&svg);
    let t = tags(&svg);
    let fill = |c: &str| {
        t.iter()
            .filter(|x| x.0 == "rect" && attr(x, "fill") == Some(c))
            .count()
    };
    // stick: the legend and 2 runs of each pair; slip+: the legend and one run of each;
    // slip−: the legend and one run of left.
    assert_eq!(fill("#1f5fa8"), 5);
    assert_eq!(fill("#f29e0c"), 3);
    assert_eq!(fill("#d62728"), 2);
    // Stage 3 of a stopped history ends at s = 0.5: marked with its status.
    let svg = history_states_svg(&stopped()).unwrap();
    keep("history-states-stopped.svg", &svg);
    assert!(svg.contains("<title>mechanism</title>"));
}

/// A cyclic history of 300 pairs and 20 stages, made by a formula: pair `i` slips (+) in the
/// odd stages from `s = i/300` on and (−) in the even ones, with slip growing by 1e-4 per
/// stage it slips in. Reference: the formula (states and counts by hand from it).
fn cyclic(m: usize, n: usize) -> HistorySolution {
    let names: Vec<String> = (0..m).map(|i| format!("b{i}")).collect();
    let mut stages = Vec::new();
    let mut z = vec![0.0; m];
    for k in 1..=n {
        let up = k % 2 == 1;
        let (f0, f1) = if k == 1 {
            (0.0, 1.0)
        } else if up {
            (-1.0, 1.0)
        } else {
            (1.0, -1.0)
        };
        let mut steps = Vec::new();
        for i in (0..m).step_by(m.div_ceil(5)) {
            let s = i as f64 / m as f64;
            let kind = if up {
                EventKind::StartsSlippingPlus
            } else {
                EventKind::StartsSlippingMinus
            };
            steps.push(HistoryStep {
                step: steps.len() + 1,
                s,
                factors: vec![1.0, f0 + s * (f1 - f0)],
                entering: Var::Z(i),
                leaving: Var::X(i),
                entering_label: format!("z_t{}", i + 1),
                leaving_label: format!("x_t{}", i + 1),
                events: vec![Event {
                    pair: i,
                    name: names[i].clone(),
                    kind,
                    while_open: false,
                }],
                pairs: (0..m)
                    .map(|j| {
                        let slipping = j <= i;
                        let st = match (slipping, up) {
                            (false, _) => Stick,
                            (true, true) => SlipPlus,
                            (true, false) => SlipMinus,
                        };
                        pair(&names[j], 10.0, if up { -1.0 } else { 1.0 }, z[j], st)
                    })
                    .collect(),
            });
        }
        for zj in z.iter_mut() {
            *zj += if up { 1e-4 } else { -1e-4 };
        }
        stages.push(StageSolution {
            stage: k,
            name: if up { "warm".into() } else { "cool".into() },
            factors_start: vec![if k == 1 { 0.0 } else { 1.0 }, f0],
            factors_end: vec![1.0, f1],
            status: StageStatus::Completed,
            s_end: 1.0,
            steps,
            pairs: (0..m)
                .map(|j| {
                    pair(
                        &names[j],
                        10.0,
                        if up { -2.0 } else { 2.0 },
                        z[j],
                        if up { SlipPlus } else { SlipMinus },
                    )
                })
                .collect(),
            residual: HistoryResidual::default(),
            mechanism: None,
            reason: None,
        });
    }
    HistorySolution {
        cases: vec!["dead".into(), "heat".into()],
        names,
        stages,
        notes: vec![],
    }
}

#[test]
fn a_long_cyclic_history_of_many_pairs() {
    let h = cyclic(300, 20);
    let svg = history_states_svg(&h).unwrap();
    keep("history-states-cyclic.svg", &svg);
    all_numbers_finite(&svg);
    let runs = state_runs(&h);
    // Pair 0 slips from s = 0 in every stage, alternately + and −: 20 runs, no stick.
    assert_eq!(runs[0].len(), 20);
    assert!(runs[0].iter().all(|r| r.state != Stick));
    // Pair 60 (the second of the steps, at s = 0.2) sticks for the first 0.2 of every stage.
    assert!(runs[60].iter().filter(|r| r.state == Stick).count() == 20);
    let svg = history_curves_svg(
        &h,
        &HistoryChartOptions::default(),
        &CurveKind::Factor("heat".into()),
    )
    .unwrap();
    keep("history-curves-cyclic.svg", &svg);
    all_numbers_finite(&svg);
    let s = history_summary(&h, "cyclic").unwrap();
    assert!(
        s.contains("final state of the 300 pairs: 0 open, 0 stick, 0 slip+, 300 slip-"),
        "{s}"
    );
    assert_eq!(
        s.lines()
            .filter(|l| l.contains(" warm ") || l.contains(" cool "))
            .count(),
        20
    );
}

// ---------------------------------------------------------------------------------------------
// ParaView

/// The values of the data array `name` of a VTK file, as numbers.
fn data_array(text: &str, name: &str) -> Vec<f64> {
    let at = text
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no array {name}"));
    let body = &text[at..];
    let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
    body.split_ascii_whitespace()
        .map(|w| w.parse().unwrap())
        .collect()
}

/// Example 1 of the paper (a beam on frictional supports, `examples/example1-beam.toml`)
/// analysed at its load, then a hand-made history of two stages over it: stage 1 ends with
/// the analysis' results, stage 2 stops at s = 0.5 with the displacements doubled and every
/// pair slipping (+) with z_t = 1e-3·(pair number). Reference: those hand-set values, the
/// model's node and pair counts, and the pseudo-times 0, 1, 1.5.
#[test]
fn paraview_files_over_the_history() {
    use unilateral_analysis::{analyze, HistoryAnalysis};
    use unilateral_io::{read_problem, Problem};
    use unilateral_output::{history_vtk, HISTORY_PVD};
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/example1-beam.toml");
    let Problem::Structural(problem) = read_problem(&path).unwrap() else {
        panic!("a structural model");
    };
    let a = analyze(&problem.model, &problem.settings).unwrap();
    let r1 = a.results.clone().unwrap();
    let mut r2 = r1.clone();
    for d in &mut r2.displacements {
        for v in d.iter_mut() {
            *v *= 2.0;
        }
    }
    let m = problem.model.pairs().len();
    let n = problem.model.nodes().len();
    let names: Vec<String> = (0..m).map(|i| format!("p{i}")).collect();
    let pairs_at = |slip: bool| -> Vec<PairResult> {
        (0..m)
            .map(|i| {
                if slip {
                    pair(&names[i], 5.0, -1.0, 1e-3 * (i + 1) as f64, SlipPlus)
                } else {
                    pair(&names[i], 5.0, 0.0, 0.0, Stick)
                }
            })
            .collect()
    };
    let stage = |k: usize, s_end: f64, slip: bool| StageSolution {
        stage: k,
        name: format!("stage {k}"),
        factors_start: vec![(k - 1) as f64],
        factors_end: vec![k as f64],
        status: if s_end < 1.0 {
            StageStatus::Mechanism
        } else {
            StageStatus::Completed
        },
        s_end,
        steps: vec![],
        pairs: pairs_at(slip),
        residual: HistoryResidual::default(),
        mechanism: None,
        reason: None,
    };
    let gaps = a.zone.gap.clone();
    let ha = HistoryAnalysis {
        condensed: a.condensed,
        zone: std::sync::Arc::unwrap_or_clone(a.zone),
        history: HistorySolution {
            cases: vec!["variable".into()],
            names: names.clone(),
            stages: vec![stage(1, 1.0, false), stage(2, 0.5, true)],
            notes: vec![],
        },
        stage_results: vec![r1.clone(), r2.clone()],
        timings: a.timings,
    };
    let files = history_vtk(&ha).unwrap();
    let get = |name: &str| {
        &files
            .iter()
            .find(|f| f.0 == name)
            .unwrap_or_else(|| panic!("{name}"))
            .1
    };
    assert_eq!(
        files.len(),
        7,
        "mesh and pairs at 3 states, and the collection"
    );
    assert_eq!(files.last().unwrap().0, HISTORY_PVD);
    let pvd = get(HISTORY_PVD);
    let steps: Vec<&str> = pvd
        .split("timestep=\"")
        .skip(1)
        .map(|p| p.split('"').next().unwrap())
        .collect();
    assert_eq!(steps, ["0", "0", "1", "1", "1.5", "1.5"]);
    assert!(pvd.contains("file=\"history_pairs_002.vtu\""));
    // The start: unloaded, the pairs at their gaps.
    let start = get("history_mesh_000.vtu");
    assert!(data_array(start, "displacement").iter().all(|v| *v == 0.0));
    assert_eq!(data_array(get("history_pairs_000.vtu"), "z_n"), gaps);
    // Stage 2's end: the doubled displacements (ux, uy, 0 per node) and the hand slips.
    let d = data_array(get("history_mesh_002.vtu"), "displacement");
    assert_eq!(d.len(), 3 * n);
    for (i, dn) in r2.displacements.iter().enumerate() {
        assert_eq!((d[3 * i], d[3 * i + 1], d[3 * i + 2]), (dn[0], dn[1], 0.0));
    }
    let p2 = get("history_pairs_002.vtu");
    let z: Vec<f64> = (0..m).map(|i| 1e-3 * (i + 1) as f64).collect();
    assert_eq!(data_array(p2, "z_t"), z);
    assert!(data_array(p2, "state").iter().all(|s| *s == 2.0));
    assert_eq!(data_array(p2, "TimeValue"), [1.5]);
    assert_eq!(data_array(p2, "stage"), [2.0]);
    for (name, text) in &files {
        tags_xml(text, name);
    }
    // A non-finite displacement is refused and named.
    let mut bad = ha;
    bad.stage_results[1].displacements[0][1] = f64::NAN;
    let e = history_vtk(&bad).unwrap_err();
    let nf = unilateral_output::NonFiniteOutput::in_io_error(&e).unwrap();
    assert_eq!(nf.field, "history[2].nodes[1].uy");
}

/// The VTK files are XML with one root: the same checker as the pictures' after the
/// declaration.
fn tags_xml(text: &str, name: &str) {
    let body = text
        .strip_prefix("<?xml version=\"1.0\"?>\n")
        .unwrap_or_else(|| panic!("{name}"));
    let mut stack: Vec<&str> = Vec::new();
    let mut rest = body;
    while let Some(i) = rest.find('<') {
        let end = rest[i..].find('>').unwrap() + i;
        let tag = &rest[i + 1..end];
        rest = &rest[end + 1..];
        if let Some(close) = tag.strip_prefix('/') {
            assert_eq!(stack.pop(), Some(close), "{name}");
        } else if !tag.ends_with('/') {
            stack.push(tag.split_whitespace().next().unwrap());
        }
    }
    assert!(stack.is_empty(), "{name}: unclosed {stack:?}");
}

/// The structural document of a history holds the final state's results with the keys and
/// values of the structural document of one load. Reference: `structural_json` of Example 2
/// (the cantilever) analysed at its load, the same results handed over as the end of a
/// one-stage history.
#[test]
fn structural_history_document_matches_the_structural_document() {
    use unilateral_analysis::{analyze, HistoryAnalysis};
    use unilateral_io::{read_problem, Problem};
    use unilateral_output::{history_structural_document, structural_json};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/example2-cantilever.toml");
    let Problem::Structural(problem) = read_problem(&path).unwrap() else {
        panic!("a structural model");
    };
    let a = analyze(&problem.model, &problem.settings).unwrap();
    let reference = structural_json(&a).unwrap();
    let r = a.results.clone().unwrap();
    let pairs = a.solution.pairs.clone();
    let names: Vec<String> = pairs.iter().map(|p| p.name.clone()).collect();
    let ha = HistoryAnalysis {
        condensed: a.condensed,
        zone: std::sync::Arc::unwrap_or_clone(a.zone),
        history: HistorySolution {
            cases: vec!["variable".into()],
            names,
            stages: vec![StageSolution {
                stage: 1,
                name: "all".into(),
                factors_start: vec![0.0],
                factors_end: vec![1.0],
                status: StageStatus::Completed,
                s_end: 1.0,
                steps: vec![],
                pairs,
                residual: HistoryResidual::default(),
                mechanism: None,
                reason: None,
            }],
            notes: vec![],
        },
        stage_results: vec![r],
        timings: a.timings,
    };
    let doc = history_structural_document(&ha).unwrap();
    for key in [
        "nodes",
        "reactions",
        "frames",
        "plane_elements",
        "equilibrium",
        "pairs",
    ] {
        assert_eq!(doc[key], reference[key], "{key}");
        if key != "pairs" {
            assert_eq!(doc["history"][0]["structure"][key], reference[key], "{key}");
        }
    }
    let mut bad = ha;
    bad.stage_results[0].displacements[2][0] = f64::INFINITY;
    assert_eq!(
        history_structural_document(&bad).unwrap_err().field,
        "history[1].structure.nodes[3].ux"
    );
}

/// The node curves of a structural history against the propped cantilever of
/// `tests/data/history/model-stages.toml` by hand (`crates/analysis/tests/it/history.rs` derives
/// it): in the push (stage 2, pseudo-time 1 … 2) mid-span moves F/1000 while the tip sticks, up
/// to 0.003 where the tip starts to slip (s = 0.75), and 0.005 at F = 4.
#[test]
fn node_curves_by_hand() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/history/model-stages.toml");
    let Ok(unilateral_io::Problem::Structural(p)) = unilateral_io::read_problem(&file) else {
        panic!("a structural model");
    };
    let stages = p.history.clone().unwrap();
    let a = unilateral_analysis::analyze_history(&p.model, &stages, &p.settings.engine).unwrap();
    let mid = a.condensed.model().names().node_id("beam.1").unwrap().0;
    let push = a.history.cases.iter().position(|c| c == "push").unwrap();
    let curves = unilateral_output::node_curves(&a, &[mid], push).unwrap();
    let c = &curves[0];
    // The start, then stage 1's end, then the push's breakpoints.
    assert_eq!(c[0].t, 0.0);
    let at = |t: f64| {
        c.iter()
            .find(|q| (q.t - t).abs() < 1e-12)
            .unwrap_or_else(|| panic!("t = {t}: {c:?}"))
    };
    assert!((at(1.75).u[0] - 0.003).abs() < 1e-12 && (at(1.75).factor - 0.75).abs() < 1e-12);
    assert!((at(2.0).u[0] - 0.005).abs() < 1e-12 && (at(2.0).factor - 1.0).abs() < 1e-12);
    assert!(c.windows(2).all(|w| w[0].t <= w[1].t));
    let svg = unilateral_output::node_curves_svg(&["beam.1".into()], "push", &curves).unwrap();
    assert!(svg.starts_with("<svg") || svg.contains("<svg"));
    assert!(svg.contains("node beam.1"));
}
