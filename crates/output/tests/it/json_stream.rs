//! The result document written as it is formed ([`PathDocument`]): the values of every pair at
//! every breakpoint are formed a block of breakpoints at a time while the text is written. The
//! reference is the document built whole ([`contact_json_with`], [`structural_json_with`]) with
//! the same changes applied: the two texts must be the same to the byte, on paths long enough
//! to span several blocks, with and without the tightening.

use unilateral_output::{
    contact_json_with, structural_json_with, with_provenance, with_timings, About, PathDocument,
    PathJsonOptions,
};

fn bearing_beam(
    m: usize,
) -> (
    unilateral_analysis::Analysis,
    unilateral_contact::SolveSettings,
) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("beam{m}.toml"));
    std::fs::write(&path, unilateral_oracle::fixtures::bearings::beam_model(m)).unwrap();
    let unilateral_io::Problem::Structural(p) = unilateral_io::read_problem(&path).unwrap() else {
        panic!("a structural model");
    };
    (
        unilateral_analysis::analyze(&p.model, &p.settings).unwrap(),
        p.settings,
    )
}

fn options(breakpoints: bool) -> PathJsonOptions {
    PathJsonOptions {
        breakpoints,
        about: About {
            title: Some("a beam".into()),
            units: Some("N, m".into()),
        },
    }
}

/// What the command line does to a document before writing it.
fn finish(doc: serde_json::Value) -> serde_json::Value {
    let timings = unilateral_analysis::Timings::default();
    with_provenance(with_timings(doc, &timings))
}

fn streamed(doc: PathDocument<'_>) -> String {
    let timings = unilateral_analysis::Timings::default();
    let doc = doc.map(|d| with_timings(d, &timings)).map(with_provenance);
    serde_json::to_string_pretty(&doc).unwrap()
}

#[test]
fn the_streamed_document_is_the_whole_one() {
    // 622 steps on the path without tightening: three blocks of breakpoints.
    let (a, settings) = bearing_beam(300);
    assert!(
        a.solution.steps.len() > 2 * 256,
        "{} steps",
        a.solution.steps.len()
    );
    assert_eq!(a.solution.tightening, 0.0);
    for breakpoints in [true, false] {
        let whole = finish(structural_json_with(&a, &options(breakpoints)).unwrap());
        let text = streamed(PathDocument::structural(&a, &options(breakpoints)).unwrap());
        assert_eq!(text, serde_json::to_string_pretty(&whole).unwrap());
        if breakpoints {
            // The values are there, in every step (the reference is not empty).
            let steps = whole["steps"].as_array().unwrap();
            assert!(steps.iter().all(|s| s["pairs"].is_array()));
        }
    }
    // The same zone traced with the paper's tightening: the traced values with c in them.
    let mut settings = settings;
    settings.tightening = 1.0;
    let sol = unilateral_contact::solve(&a.zone, &settings).unwrap();
    assert!(
        sol.tightening > 0.0 && sol.steps.len() > 256,
        "{} steps",
        sol.steps.len()
    );
    let whole = finish(contact_json_with(&sol, &options(true)).unwrap());
    let text = streamed(PathDocument::contact(&sol, &options(true)).unwrap());
    assert_eq!(text, serde_json::to_string_pretty(&whole).unwrap());
    assert!(whole["step_pairs"].as_str().unwrap().contains("c = 1"));
}
