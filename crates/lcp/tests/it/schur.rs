//! The Schur-complement engine against the dense engine on the same problems, formed densely.

use crate::schur_beam::{beam_schur, BeamData};
use unilateral_lcp::{
    follow_schur_path, Follow, PathOptions, PathSolver, RowRelation, SchurOptions, Settings,
};

fn compare(m: usize, data: &BeamData) {
    let lcp = beam_schur(m, data);
    lcp.check().unwrap();
    let dense = lcp.dense();
    let opts = PathOptions {
        target: 0.8,
        follow: Follow::ToEnd,
        tightening: None,
    };
    // The contact crate's settings: tangential rows first, each pair's friction relation.
    let order: Vec<usize> = (m..3 * m).chain(0..m).collect();
    let f = data.friction;
    let settings = Settings {
        lexicographic_order: Some(order.clone()),
        row_relations: (0..m)
            .map(|i| RowRelation {
                terms: vec![(m + i, 1.0), (2 * m + i, 1.0), (i, -2.0 * f)],
            })
            .collect(),
        ..Settings::default()
    };
    let relations = settings.row_relations.clone();
    let solver = PathSolver::new(dense, opts, settings).unwrap();
    let want = solver.follow();
    let got = follow_schur_path(
        &lcp,
        &SchurOptions {
            target: 0.8,
            follow: Follow::ToEnd,
            max_pivots: 100 * m,
            max_border: 8,
            order: Some(order),
            relations,
        },
    );
    if let Some(k) = got
        .steps
        .iter()
        .zip(&want.steps)
        .position(|(g, w)| (g.entering, g.leaving) != (w.entering, w.leaving))
    {
        eprintln!(
            "m = {m}: first difference at {k}: got {:?}\nwant {:?}",
            &got.steps[k.saturating_sub(1)..(k + 2).min(got.steps.len())],
            &want.steps[k.saturating_sub(1)..(k + 2).min(want.steps.len())]
        );
    }
    assert_eq!(got.status, want.status, "m = {m}: status");
    assert_eq!(got.steps.len(), want.steps.len(), "m = {m}: steps");
    for (g, w) in got.steps.iter().zip(&want.steps) {
        assert_eq!(
            (g.entering, g.leaving),
            (w.entering, w.leaving),
            "m = {m}, step {}",
            w.index
        );
        // Late on the 150-bearing beam's path the two engines and a full-pivoting solve of the
        // formed basis differ by 1e-8 of p (the kernel's conditioning); 1e-6 leaves room.
        assert!(
            (g.p - w.p).abs() <= 1e-6 * w.p.abs().max(1e-300),
            "m = {m}, step {}: p {} against {}",
            w.index,
            g.p,
            w.p
        );
    }
    let (x, z) = got.at_target.expect("the target on the path");
    let sol = want.solution.expect("the dense engine's solution");
    let xs = sol.x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let zs = sol.z.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for i in 0..x.len() {
        assert!((x[i] - sol.x[i]).abs() <= 1e-8 * xs, "x{i}");
        assert!((z[i] - sol.z[i]).abs() <= 1e-8 * zs, "z{i}");
    }
}

#[test]
fn schur_engine_follows_the_dense_engines_path_on_beams() {
    for m in [2, 5, 12, 30, 60, 150] {
        compare(m, &BeamData::default());
    }
}

#[test]
fn schur_engine_follows_the_dense_engines_path_in_kn_and_mm() {
    let data = BeamData {
        force: 1e-3,
        length: 1e3,
        friction: 0.5,
        ..BeamData::default()
    };
    compare(40, &data);
}
