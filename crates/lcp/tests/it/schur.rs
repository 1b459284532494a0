//! The Schur-complement engine against the dense engine on the same problems, formed densely.

use crate::schur_beam::{beam_schur, contact_order_and_relations, BeamData};
use unilateral_lcp::{
    basic_after, first_different_step, follow_schur_path, Follow, PathOptions, PathSolver,
    SchurOptions, Settings,
};

fn compare(m: usize, data: &BeamData) {
    let lcp = beam_schur(m, data);
    lcp.check().unwrap();
    let dense = crate::schur_beam::contact_dense(&lcp, data.friction);
    let opts = PathOptions {
        target: 0.8,
        follow: Follow::ToEnd,
        tightening: None,
    };
    // The contact crate's settings: tangential rows first, each pair's friction relation.
    let (order, relations) = contact_order_and_relations(m, data.friction);
    let settings = Settings {
        lexicographic_order: Some(order.clone()),
        row_relations: relations.clone(),
        ..Settings::default()
    };
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
            progress: Default::default(),
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
    assert_eq!(
        first_different_step(&got.steps, &want.steps),
        None,
        "m = {m}"
    );
    for (g, w) in got.steps.iter().zip(&want.steps) {
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

/// On the 600-bearing beam the dense engine passed a pair's start of slip (the rate of its
/// `x_t+`, −3.9e3 against `z` rates many orders larger, read as round-off of the column): its
/// breakpoint after step 1710 had that `x_t+` at −22 337 N, found by this engine and checked
/// by a solve of the formed basis. Now the two engines take the same pivots, and every basic
/// variable at that breakpoint of the dense path is non-negative by an independent solve.
#[test]
fn dense_engine_takes_the_start_of_slip_it_passed_on_a_600_bearing_beam() {
    let m = 600;
    let data = BeamData::default();
    let lcp = beam_schur(m, &data);
    let dense = crate::schur_beam::contact_dense(&lcp, data.friction);
    let n = 3 * m;
    let (order, relations) = contact_order_and_relations(m, data.friction);
    let settings = Settings {
        lexicographic_order: Some(order.clone()),
        row_relations: relations.clone(),
        ..Settings::default()
    };
    let opts = PathOptions {
        target: 1.0,
        follow: Follow::ToEnd,
        tightening: None,
    };
    let want = PathSolver::new(dense.clone(), opts, settings)
        .unwrap()
        .follow();
    let got = follow_schur_path(
        &lcp,
        &SchurOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            max_pivots: 100 * m,
            max_border: 40,
            order: Some(order),
            relations,
            progress: Default::default(),
        },
    );
    assert_eq!(first_different_step(&want.steps, &got.steps), None);
    // The dense path's basis after step 1710, solved afresh on the formed problem.
    let sol = dense
        .basis_solution(&basic_after(&want.steps, 1710, n))
        .unwrap();
    let xs: Vec<(usize, f64)> = (0..n).map(|v| (v, sol[v])).collect();
    let scale = xs.iter().fold(0.0f64, |s, &(_, x)| s.max(x.abs()));
    let worst = xs
        .iter()
        .fold((0, 0.0f64), |w, &(v, x)| if x < w.1 { (v, x) } else { w });
    assert!(
        worst.1 >= -1e-6 * scale,
        "x{} = {} at the breakpoint after step 1710 (largest {scale})",
        worst.0 + 1,
        worst.1
    );
}

/// The sparse engine's path adopted by the dense solver is the dense solver's own: the same
/// pivots, status and target segment, and the solutions it reports at the target and at
/// another load, formed and verified from the dense data, agree with those of the path the
/// dense solver followed itself — to the end and to the target.
#[test]
fn an_adopted_sparse_path_answers_as_the_dense_one() {
    for (m, follow) in [
        (12, Follow::ToEnd),
        (60, Follow::ToEnd),
        (150, Follow::ToTarget),
    ] {
        let data = BeamData::default();
        let lcp = beam_schur(m, &data);
        let dense = crate::schur_beam::contact_dense(&lcp, data.friction);
        let (order, relations) = contact_order_and_relations(m, data.friction);
        let settings = Settings {
            lexicographic_order: Some(order.clone()),
            row_relations: relations.clone(),
            ..Settings::default()
        };
        let target = 0.9;
        let opts = PathOptions {
            target,
            follow,
            tightening: None,
        };
        let solver = PathSolver::new(dense, opts, settings).unwrap();
        let want = solver.follow();
        let schur = follow_schur_path(
            &lcp,
            &SchurOptions {
                target,
                follow,
                max_pivots: 100 * m,
                max_border: 40,
                order: Some(order),
                relations,
                progress: Default::default(),
            },
        );
        let got = solver.adopt(schur).expect("a slack start");
        assert_eq!(got.status, want.status, "m = {m}");
        assert_eq!(
            first_different_step(&got.steps, &want.steps),
            None,
            "m = {m}"
        );
        assert_eq!(got.target_segment, want.target_segment, "m = {m}");
        let close = |a: &[f64], b: &[f64], what: &str| {
            let scale = b.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for (x, y) in a.iter().zip(b) {
                assert!(
                    (x - y).abs() <= 1e-8 * scale,
                    "m = {m}, {what}: {x} against {y}"
                );
            }
        };
        let (g, w) = (
            got.solution.clone().expect("reported"),
            want.solution.clone().expect("reported"),
        );
        assert_eq!(g.p, w.p);
        assert!(g.residual.max() <= unilateral_lcp::ACCEPT_RESIDUAL);
        close(&g.x, &w.x, "x at the target");
        close(&g.z, &w.z, "z at the target");
        let (g, w) = (
            solver.solution_at(&got, 0.5 * target).unwrap().unwrap(),
            solver.solution_at(&want, 0.5 * target).unwrap().unwrap(),
        );
        close(&g.x, &w.x, "x at half the target");
        close(&g.z, &w.z, "z at half the target");
    }
}
