//! Structural results along a load history (`analyze_history`, `HistoryAnalysis::results_at`)
//! against hand values on `tests/data/history/model-stages.toml`: a propped cantilever (EA = 1000,
//! two elements of 2, clamped at x = 0, the tip on frictional ground, f = 0.3) with a dead load
//! of 16 down and a push of 4 along the beam, both at mid-span (node `beam.1`).

use std::path::Path;

use unilateral_analysis::analyze_history;
use unilateral_contact::{PairState, StageStatus};
use unilateral_io::{read_problem, Problem};

fn model_stages() -> (
    unilateral_io::StructuralProblem,
    Vec<unilateral_contact::Stage>,
) {
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/history/model-stages.toml");
    let Ok(Problem::Structural(p)) = read_problem(&file) else {
        panic!("{} is a structural model", file.display());
    };
    let stages = p.history.clone().expect("the file has a history");
    (p, stages)
}

/// By hand: under the dead load the tip carries 5P/16 = 5 (compression), so its friction
/// capacity is 0.3·5 = 1.5. The push F·s at mid-span is shared by the two axial halves (each
/// EA/2 = 500) while the tip sticks: the tip takes F/2, mid-span moves F/1000; the tip slips
/// once F/2 = 1.5, at s = 0.75 (F = 3, u = 0.003). From there the tip carries 1.5 and the left
/// half the rest: at s = 0.875 (F = 3.5) u = 2.0/500 = 0.004, at s = 1 (F = 4) u = 0.005.
#[test]
fn results_along_the_history_by_hand() {
    let (p, stages) = model_stages();
    let a = analyze_history(&p.model, &stages, &p.settings.engine).unwrap();
    assert!(a
        .history
        .stages
        .iter()
        .all(|s| s.status == StageStatus::Completed));
    assert_eq!(a.stage_results.len(), 4);
    let mid = a.condensed.model().names().node_id("beam.1").unwrap().0;
    // Stage 1: the clamp's vertical reaction 11P/16 = 11, the tip's 5.
    assert!((a.history.stages[0].pairs[0].x_n - 5.0).abs() < 1e-9);
    let r0 = &a.stage_results[0];
    let clamp_fy: f64 = r0
        .reactions
        .iter()
        .filter(|r| r.dof == unilateral_fem::SupportDof::Uy)
        .map(|r| r.value)
        .sum();
    assert!((clamp_fy - 11.0).abs() < 1e-9, "{clamp_fy}");
    // Stage 1 is proportional and elastic: at s = 1/2 half of everything.
    let (_, half) = a.results_at(1, 0.5).unwrap();
    for (u, v) in half.displacements.iter().zip(&r0.displacements) {
        for k in 0..3 {
            assert!((u[k] - 0.5 * v[k]).abs() <= 1e-12 * v[k].abs().max(1e-9));
        }
    }
    // Stage 2, the push: where the tip starts to slip, and mid-span's displacement before,
    // at and after it.
    let push = &a.history.stages[1];
    let start = push
        .steps
        .iter()
        .find(|s| {
            s.events
                .iter()
                .any(|e| e.kind != unilateral_contact::EventKind::Sticks)
        })
        .expect("the tip starts to slip");
    assert!((start.s - 0.75).abs() < 1e-12, "{}", start.s);
    for (s, u) in [(0.5, 0.002), (0.75, 0.003), (0.875, 0.004), (1.0, 0.005)] {
        let (pairs, r) = a.results_at(2, s).unwrap();
        assert!(
            (r.displacements[mid][0] - u).abs() < 1e-12,
            "s = {s}: {:?}",
            r.displacements[mid]
        );
        let tip = &pairs[0];
        let want = if s <= 0.75 { 2.0 * s } else { 1.5 };
        assert!((tip.x_t.abs() - want).abs() < 1e-12, "s = {s}: {tip:?}");
    }
    // The tip moves in +x, the pair's tangent (the normal (0, 1) turned clockwise): slip+.
    assert_eq!(push.pairs[0].state, PairState::SlipPlus);
    assert!(push.pairs[0].z_t > 0.0);
    // Outside the history: refused.
    assert!(a.results_at(5, 0.5).is_err());
    assert!(a.results_at(2, 1.5).is_err());
}

/// A stage the structure cannot carry to its end: the friction slider of
/// `tests/data/models/friction-slider.toml` (a bar on two ground pairs, f = 0.2 and 0.5, each
/// pressed by 10) as a history — the dead load, then the pull at node 2 taken to 10. By hand
/// (statics of the bar): node 2 slips at a pull of 0.5·10 = 5 (s = 0.5), node 1 as well at
/// (0.2 + 0.5)·10 = 7 (s = 0.7): a mechanism there, with both pairs sliding together.
#[test]
fn a_stage_ends_in_a_mechanism_with_its_limit_factor() {
    let src = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/models/friction-slider.toml"),
    )
    .unwrap();
    let src = src
        .replace("[[loads.constant.nodal]]", "[[loads.dead.nodal]]")
        .replace("[[loads.variable.nodal]]", "[[loads.pull.nodal]]");
    let src = src[..src.find("[solve]").unwrap()].to_string()
        + "[[history]]\nfactors = { dead = 1.0 }\n\n[[history]]\nname = \"pull\"\nfactors = { pull = 10.0 }\n";
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("slider-history.toml");
    std::fs::write(&file, src).unwrap();
    let Ok(Problem::Structural(p)) = read_problem(&file) else {
        panic!("a structural model")
    };
    let a = analyze_history(&p.model, p.history.as_ref().unwrap(), &p.settings.engine).unwrap();
    assert_eq!(a.history.stages.len(), 2);
    let st = &a.history.stages[1];
    assert_eq!(st.status, StageStatus::Mechanism, "{:?}", st.reason);
    assert!((st.s_end - 0.7).abs() < 1e-12, "{}", st.s_end);
    let pull = a.history.cases.iter().position(|c| c == "pull").unwrap();
    let reached =
        st.factors_start[pull] + st.s_end * (st.factors_end[pull] - st.factors_start[pull]);
    assert!((reached - 7.0).abs() < 1e-11);
    let first = st
        .steps
        .iter()
        .find(|s| s.events.iter().any(|e| e.name == "b"))
        .expect("pair b starts to slip");
    assert!((first.s - 0.5).abs() < 1e-12, "{}", first.s);
    // The mode: both pairs slide together (equal tangential rates), no opening.
    let mode = st.mechanism.as_ref().expect("a mechanism mode");
    assert!(mode.iter().all(|&(dn, _)| dn.abs() < 1e-9), "{mode:?}");
    assert!(
        (mode[0].1 - mode[1].1).abs() < 1e-9 && mode[0].1.abs() > 0.5,
        "{mode:?}"
    );
    // At the limit both pairs slide, in the mode's direction (read from the mode: the
    // mechanism's last breakpoint has no segment after it, and the slips since that
    // breakpoint — none — made both read "stick" until round 29).
    let slip = if mode[0].1 > 0.0 {
        PairState::SlipPlus
    } else {
        PairState::SlipMinus
    };
    let states: Vec<PairState> = st.pairs.iter().map(|r| r.state).collect();
    assert_eq!(states, vec![slip; 2]);
    assert_eq!(a.history.status(), &StageStatus::Mechanism);
    // The results at the limit are in equilibrium (checked by the recovery) and reported.
    assert_eq!(a.stage_results.len(), 2);
}
