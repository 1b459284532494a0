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
