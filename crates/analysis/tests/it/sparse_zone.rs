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
    basic_after, first_different_step, follow_schur_path, Follow, PathOptions, PathSolver,
    PathStatus, SchurLcp, SchurOptions, Settings,
};
use unilateral_oracle::fixtures::bearings::Bearings;

fn model_of(path: &Path) -> Model {
    match read_problem(path).unwrap() {
        Problem::Structural(p) => p.model,
        Problem::ContactZone(_) => panic!("a structural model"),
    }
}

fn bearing_beam(m: usize) -> Model {
    crate::bearings_model(&Bearings::new(m))
}

/// The dense solver of a model's condensed zone (its LCP in the model's units, the contact
/// crate's order and relations) and the LCP of its sparse blocks with the options of the
/// engine on sparse data.
fn both_engines(
    model: &Model,
    follow: Follow,
    target: f64,
) -> (PathSolver, SchurLcp, SchurOptions) {
    let zone = zone_of(&model.condense().unwrap());
    let lcp = ContactLcp::build(&zone);
    let relations = lcp.row_relations();
    let settings = Settings {
        lexicographic_order: Some(lcp.lexicographic_order.clone()),
        row_relations: relations.clone(),
        ..Settings::default()
    };
    let n = lcp.problem.q0.len();
    let options = SchurOptions {
        target,
        follow,
        max_pivots: 20 * n,
        max_border: 40,
        order: Some(lcp.lexicographic_order.clone()),
        relations,
        progress: Default::default(),
    };
    let opts = PathOptions {
        target,
        follow,
        tightening: None,
    };
    let solver = PathSolver::new(lcp.problem, opts, settings).unwrap();
    (solver, sparse_zone_of(model).unwrap().lcp(), options)
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
    let (solver, lcp, options) = both_engines(&bearing_beam(200), Follow::ToEnd, 1.0);
    let want = solver.follow();
    let got = follow_schur_path(&lcp, &options);
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
    assert_same_pairs(&s.pairs, &dense.pairs, 1e-8);
}

/// The same states, and forces within `tol` of the largest normal force of `want`.
fn assert_same_pairs(
    got: &[unilateral_contact::PairResult],
    want: &[unilateral_contact::PairResult],
    tol: f64,
) {
    assert_eq!(got.len(), want.len());
    let fmax = want.iter().fold(0.0f64, |a, r| a.max(r.x_n.abs()));
    for (a, b) in got.iter().zip(want) {
        assert_eq!(a.state, b.state, "{}", a.name);
        assert!(
            (a.x_n - b.x_n).abs() <= tol * fmax && (a.x_t - b.x_t).abs() <= tol * fmax,
            "{a:?} against {b:?}"
        );
    }
}

/// A beam of a reviewer's sweep (500 bearings in kN and mm, stiff vertical springs, ten times
/// the loads, no sideways load) on which the engine on sparse data went astray: its rows of an
/// open pair's friction, at round-off (1e-3 against terms of 1e11) and "decreasing" at 1e-4,
/// left as events; after 6258 pivots it "returned to zero", 47 s of lexicographic ties (each
/// candidate a row of the basis inverse), where the dense engine ends in a ray after 849
/// pivots. With the rates it cannot tell from round-off judged on the dense data
/// (`PathSolver::trace_sparse`) and the ties computed a column at a time, it takes the dense
/// engine's pivots to the same ray, and `follow_sparse` takes the path: its ray's basis still
/// solves the problem 10⁶ times beyond its start.
#[test]
fn judged_sparse_engine_takes_the_dense_pivots_on_a_beam_where_it_went_astray() {
    let model = crate::bearings_model(&Bearings {
        m: 500,
        friction: 0.3,
        springs: [1e10, 2e6],
        load_scale: 10.0,
        sideways: 0.0,
        kn_mm: true,
    });
    let (solver, lcp, options) = both_engines(&model, Follow::ToEnd, 1.0);
    let want = solver.follow();
    let got = solver.trace_sparse(&lcp, &options);
    assert_eq!(want.status, PathStatus::Ray);
    assert_eq!(got.status, PathStatus::Ray);
    assert_eq!(want.steps.len(), 849);
    assert_eq!(first_different_step(&got.steps, &want.steps), None);
    assert_eq!(got.steps.len(), want.steps.len());
    let taken = solver
        .follow_sparse(&lcp, &options)
        .expect("a verified ray");
    assert_eq!(taken.status, PathStatus::Ray);
}

/// On a beam of a reviewer's sweep (600 bearings, soft horizontal springs, friction 0.1), the
/// breakpoints late on the path are those of ill-conditioned bases (the condensed basis
/// matrix's condition number is 8e10). The load after step 1404, from an independent solve of
/// that basis's equations on the structure's sparse blocks refined in double-double
/// arithmetic, is the reference: the engine on sparse data traces it to 1e-6, and the same
/// basis on the condensed zone (the dense engine's data) gives it to 1e-4 — where the
/// condensation that zeroed the far-field couplings below 8 round-offs of their terms gave
/// 136.54 for 136.688 (1.1e-3; `docs/fem-performance.md`).
#[test]
fn sparse_engine_breakpoints_solve_the_structures_own_equations_late_on_a_long_path() {
    let model = crate::bearings_model(&Bearings {
        m: 600,
        friction: 0.1,
        springs: [1e8, 1e5],
        load_scale: 0.3,
        sideways: 1000.0,
        kn_mm: false,
    });
    let (solver, lcp, options) = both_engines(&model, Follow::ToTarget, 200.0);
    let got = solver.trace_sparse(&lcp, &options);
    assert_eq!(got.status, PathStatus::TargetReached);
    let k = 1404;
    assert!(got.steps.len() >= k, "{} steps", got.steps.len());
    let n = lcp.order();
    let basic = basic_after(&got.steps, k, n);
    let reference = lcp.basis_solution(&basic).unwrap()[2 * n];
    let traced = got.steps[k - 1].p;
    assert!(
        (traced - reference).abs() <= 1e-6 * reference,
        "step {k}: traced {traced}, the structure's equations {reference}"
    );
    // The same basis on the condensed zone (a full-pivoting solve of what the dense engine
    // traces): 3.5e-5 away, from the condensation's own round-off.
    let condensed = solver.problem().basis_solution(&basic).unwrap()[2 * n];
    assert!(
        (condensed - reference).abs() <= 1e-4 * reference,
        "step {k}: condensed {condensed}, the structure's equations {reference}"
    );
}

/// The most negative `x` and `z` of the basis a path ends in (its last segment's, the driver
/// replaced by the entering variable) at load `p`, each against the largest of its kind, from a
/// dense LU of that basis's equations on the structure's sparse blocks refined in double-double
/// arithmetic (`SchurLcp::basis_solution`): neither engine's factorisations, nor the condensed
/// data.
fn last_basis_at(lcp: &SchurLcp, path: &unilateral_lcp::LoadPath, p: f64) -> (f64, f64) {
    let n = lcp.order();
    let mut basic = basic_after(&path.steps, path.steps.len(), n);
    let entering = match path.last_entering.expect("a ray's entering variable") {
        unilateral_lcp::Var::X(i) => i,
        unilateral_lcp::Var::Z(i) => n + i,
        unilateral_lcp::Var::Driver => panic!("the driver enters no ray"),
    };
    basic[2 * n] = false;
    basic[entering] = true;
    let v = lcp
        .at_load(p)
        .basis_solution(&basic)
        .expect("a basis of n variables");
    let worst = |v: &[f64]| {
        let top = v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        v.iter().fold(0.0f64, |a, &b| a.min(b / top))
    };
    (worst(&v[..n]), worst(&v[n..2 * n]))
}

/// From `SPARSE_ENGINE_PAIRS` (1000) pairs on, `analyze` traces the path on the structure's
/// sparse blocks. On the whole-process benchmark's beam on 1000 bearings, traced to its end:
/// the path is taken from the engine on sparse data and ends in a ray whose basis, formed
/// independently on the structure's equations at 10 and 10⁶ times the ray's start, has no
/// variable below −1e-8 of its kind; the dense engine's path on the condensed zone ends in a
/// "ray" from p ≈ 1800 whose basis has a force at −2.9e-3 of the largest at 10 times its start —
/// an event it passed. At the target both report the same states and forces.
#[test]
fn a_beam_on_a_thousand_bearings_is_traced_on_its_sparse_blocks_to_a_ray_that_holds() {
    use std::sync::Arc;
    use unilateral_contact::SolveSettings;
    let m = unilateral_analysis::SPARSE_ENGINE_PAIRS;
    assert_eq!(m, 1000);
    let model = bearing_beam(m);
    let settings = SolveSettings {
        follow: Follow::ToEnd,
        ..SolveSettings::default()
    };
    let a = unilateral_analysis::analyze(&model, &settings).unwrap();
    let sparse = &a.solution;
    assert!(sparse.traced_on_sparse_blocks);
    assert_eq!(sparse.path.status, PathStatus::Ray);
    let lcp = sparse_zone_of(&model).unwrap().lcp();
    let start = sparse.path.breakpoints.last().unwrap().p;
    for far in [10.0 * start, 1e6 * start] {
        let (x, z) = last_basis_at(&lcp, &sparse.path, far);
        assert!(
            x >= -1e-8 && z >= -1e-8,
            "the ray from p = {start} at p = {far}: x {x:e}, z {z:e} of their largest"
        );
    }
    // The dense engine on the condensed zone (what `analyze` ran below 1000 pairs).
    let blocks = sparse_zone_of(&model).unwrap();
    let dense =
        unilateral_contact::solve_judged(Arc::clone(&a.zone), Some(&blocks), &settings).unwrap();
    assert!(!dense.traced_on_sparse_blocks);
    assert_eq!(dense.path.status, PathStatus::Ray);
    let dense_start = dense.path.breakpoints.last().unwrap().p;
    let (x, _) = last_basis_at(&lcp, &dense.path, 10.0 * dense_start);
    assert!(
        x < -1e-3,
        "the dense engine's ray from p = {dense_start}: x {x:e} of the largest"
    );
    // The reported solution at the target: the same states, forces to round-off.
    assert_eq!(sparse.p, Some(1.0));
    assert_eq!(dense.p, Some(1.0));
    assert_same_pairs(&sparse.pairs, &dense.pairs, 1e-9);
}

/// A beam on 1100 bearings (a reviewer's) pushed sideways hard enough to slide on all of them
/// before the target: by hand the bearings slip when `p·H = f·(V_c + p·V_v)` per metre —
/// `H` = 10 kN/m sideways, the weight `V_c` = 10 kN/m and the variable `V_v` = 15 kN/m down,
/// `f` = 0.3 — at `p* = f·V_c/(H − f·V_v)` = 6/11.
fn beam_sliding_before_the_target() -> Model {
    crate::bearings_model(&Bearings {
        m: 1100,
        friction: 0.3,
        springs: [6.53e9, 2.261e5],
        load_scale: 1.0,
        sideways: 1e4,
        kn_mm: false,
    })
}

/// That beam analysed: the mechanism at 6/11, with the dense engine's path. The engine on
/// sparse data first passed the limit (its load rate round-off of its data) and reached the
/// target with slips of 1e20, which the structure's check refused (exit 2). Two defences now:
/// the sparse path ends at such a runaway step (the next test), and a sparse path's state that
/// the structure refuses is traced again by the dense engine (`analyze`). The progress handle
/// counts the reported path's steps and pivots only (it counted both traces' before: 2200).
#[test]
fn a_beam_on_1100_bearings_sliding_before_the_target_ends_at_its_limit_by_hand() {
    use unilateral_contact::{Outcome, SolveSettings};
    let model = beam_sliding_before_the_target();
    assert!(model.pairs().len() >= unilateral_analysis::SPARSE_ENGINE_PAIRS);
    let mut settings = SolveSettings {
        follow: Follow::ToTarget,
        ..SolveSettings::default()
    };
    settings.engine.progress = unilateral_lcp::Progress::new();
    let a = unilateral_analysis::analyze(&model, &settings).unwrap();
    // The progress counts are the reported path's (the dense engine's), not also those of the
    // sparse engine's trace that was not taken.
    let seen = settings.engine.progress.snapshot().unwrap();
    assert_eq!(seen.steps as usize, a.solution.path.steps.len(), "{seen:?}");
    assert_eq!(seen.pivots as usize, a.solution.steps.len(), "{seen:?}");
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!("{:?}", a.solution.outcome)
    };
    assert!(
        (p_limit - 6.0 / 11.0).abs() <= 1e-9,
        "the limit load {p_limit}, by hand 6/11"
    );
    assert!(!a.solution.traced_on_sparse_blocks);
    assert!(a.results.is_some());
}

/// The engine on sparse data on that beam (1100 bearings sliding at 6/11 before the target):
/// the step past the limit has a load rate of round-off and would move the slips by far more
/// than their size — the path ends there as a mechanism, at the limit by hand, where it went
/// on to the target with slips of 1e20 (and on other beams wandered for thousands of pivots)
/// before the caller could hand the path to the dense engine.
#[test]
fn the_sparse_engine_ends_at_a_sliding_limit_instead_of_running_past_it() {
    let model = beam_sliding_before_the_target();
    let (solver, lcp, options) = both_engines(&model, Follow::ToTarget, 1.0);
    let got = solver.trace_sparse(&lcp, &options);
    assert_eq!(got.status, PathStatus::Mechanism);
    let p_end = got.breakpoints.last().unwrap().p;
    assert!(
        (p_end - 6.0 / 11.0).abs() <= 1e-9,
        "the path ends at {p_end}, the limit by hand 6/11"
    );
    assert!(got.at_target.is_none());
}
