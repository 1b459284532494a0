//! The contact zone kept as the bonded structure's sparse blocks (`sparse_zone_of`, for the
//! engine on sparse data) against the condensed zone: the LCP formed densely from the blocks
//! is the contact crate's LCP of the condensed zone, and the Schur engine's path on the
//! blocks is the dense engine's on the condensed zone.

use std::path::Path;

use unilateral_analysis::{sparse_zone_of, zone_of};
use unilateral_contact::ContactLcp;
use unilateral_fem::Model;
use unilateral_io::{read_problem, Problem};
use unilateral_lcp::{
    first_different_step, follow_schur_path, Follow, PathOptions, PathSolver, SchurOptions,
    Settings,
};
use unilateral_oracle::fixtures::bearings::beam_model;

fn model_of(path: &Path) -> Model {
    match read_problem(path).unwrap() {
        Problem::Structural(p) => p.model,
        Problem::ContactZone(_) => panic!("a structural model"),
    }
}

fn bearing_beam(m: usize) -> Model {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("beam.toml");
    std::fs::write(&path, beam_model(m)).unwrap();
    model_of(&path)
}

fn test_model(name: &str) -> Model {
    model_of(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/models")
            .join(name),
    )
}

/// The largest difference of two vectors against the larger of their largest entries and
/// `floor`.
fn relative_difference(a: &[f64], b: &[f64], floor: f64) -> f64 {
    let scale = a.iter().chain(b).fold(floor, |s, v| s.max(v.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()));
    if scale == 0.0 {
        diff
    } else {
        diff / scale
    }
}

fn same_lcp(model: &Model, what: &str) {
    let zone = zone_of(&model.condense().unwrap());
    let want = ContactLcp::build(&zone).problem;
    let got = sparse_zone_of(model).unwrap().lcp().dense();
    let n = want.q0.len();
    let col = |p: &unilateral_lcp::ParametricLcp| -> Vec<f64> {
        (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| p.m[(i, j)])
            .collect()
    };
    // The condensation zeroes entries at round-off of 8 ε of their terms; the dense solve
    // here does not: both agree to round-off of the Schur complement's cancellation.
    let dm = relative_difference(&col(&got), &col(&want), 0.0);
    // q holds the gaps' forces `R·η`, which cancel to round-off of their terms where a rigid
    // motion closes the gaps (the contact crate sets such a sum to zero): against those terms.
    let gap_terms = col(&want).iter().fold(0.0f64, |s, v| s.max(v.abs()))
        * zone.gap.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    let dq = relative_difference(&got.q0, &want.q0, gap_terms);
    let dd = relative_difference(&got.d, &want.d, 0.0);
    assert!(
        dm < 1e-9 && dq < 1e-9 && dd < 1e-9,
        "{what}: M {dm:e}, q {dq:e}, d {dd:e}"
    );
}

#[test]
fn the_sparse_zones_lcp_is_the_condensed_zones() {
    same_lcp(&bearing_beam(30), "a beam on 30 bearings");
    // gaps (the gap forces enter q through K_Iz and K_zz), plane elements
    same_lcp(&test_model("block-over-gap.toml"), "block-over-gap.toml");
    same_lcp(&test_model("gap-beam.toml"), "gap-beam.toml");
    same_lcp(&test_model("settlement.toml"), "settlement.toml");
    same_lcp(&test_model("footing-surface.toml"), "footing-surface.toml");
}

#[test]
fn the_schur_engine_on_the_sparse_zone_follows_the_dense_path() {
    let m = 200;
    let model = bearing_beam(m);
    let zone = zone_of(&model.condense().unwrap());
    let lcp = ContactLcp::build(&zone);
    let relations = lcp.row_relations();
    let settings = Settings {
        lexicographic_order: Some(lcp.lexicographic_order.clone()),
        row_relations: relations.clone(),
        ..Settings::default()
    };
    let opts = PathOptions {
        target: 1.0,
        follow: Follow::ToEnd,
        tightening: None,
    };
    let want = PathSolver::new(lcp.problem.clone(), opts, settings)
        .unwrap()
        .follow();
    let got = follow_schur_path(
        &sparse_zone_of(&model).unwrap().lcp(),
        &SchurOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            max_pivots: 20 * 3 * m,
            max_border: 40,
            order: Some(lcp.lexicographic_order.clone()),
            relations,
            progress: Default::default(),
        },
    );
    assert_eq!(got.status, want.status);
    assert_eq!(first_different_step(&got.steps, &want.steps), None);
    for (g, w) in got.steps.iter().zip(&want.steps) {
        // Late on the path the bases are ill-conditioned (p ≈ 25 at step 247: the two engines
        // differ by 1.1e-6 of it).
        assert!(
            (g.p - w.p).abs() <= 1e-5 * w.p.abs(),
            "step {}: {} against {}",
            w.index,
            g.p,
            w.p
        );
    }
}

/// `solve_sparse` traces the path to the target on the sparse blocks and the dense solver
/// adopts it: on the 400-bearing beam it reports what the dense engine reports on the
/// condensed zone (the same steps, the same states and forces at the target).
#[test]
fn solve_sparse_reports_at_the_target_what_the_dense_engine_reports() {
    use std::sync::Arc;
    use unilateral_contact::SolveSettings;
    let m = 400;
    let model = bearing_beam(m);
    let zone = Arc::new(zone_of(&model.condense().unwrap()));
    let settings = SolveSettings {
        follow: Follow::ToTarget,
        ..SolveSettings::default()
    };
    let blocks = sparse_zone_of(&model).unwrap();
    let s = unilateral_contact::solve_sparse(Arc::clone(&zone), Some(&blocks), &settings).unwrap();
    let dense = unilateral_contact::solve_shared(zone, &settings).unwrap();
    assert!(s.traced_on_sparse_blocks && !dense.traced_on_sparse_blocks);
    assert_eq!(s.outcome, dense.outcome);
    assert_eq!(s.steps.len(), dense.steps.len());
    for (a, b) in s.steps.iter().zip(&dense.steps) {
        assert_eq!(
            (&a.entering, &a.leaving),
            (&b.entering, &b.leaving),
            "step {}",
            a.index
        );
    }
    let fmax = dense.pairs.iter().fold(0.0f64, |a, r| a.max(r.x_n.abs()));
    for (a, b) in s.pairs.iter().zip(&dense.pairs) {
        assert_eq!(a.state, b.state, "{}", a.name);
        assert!(
            (a.x_n - b.x_n).abs() <= 1e-8 * fmax && (a.x_t - b.x_t).abs() <= 1e-8 * fmax,
            "{a:?} against {b:?}"
        );
    }
}
