//! The Schur-complement engine on the continuous beam on `m` frictional bearings (default
//! 2000), timed, beside one dense LU of the contact LCP's order and, with `--dense`, the dense
//! engine on the same problem formed densely:
//!
//! ```text
//! cargo run --release -p unilateral-lcp --example schur_beam -- 2000 [--dense]
//! ```
//!
//! With `--dense`, three checks of single breakpoints by independent solves of a basis
//! (`CHECK_STEPS=k,…` for the Schur path's, `CHECK_DENSE_STEPS=k,…` for the dense path's; the
//! value of the variable `CHECK_VAR=v` there as well): a full-pivoting LU of the basis on the
//! formed `M`, and a dense LU of the basis's sparse equations (no `M` formed).

#[path = "../tests/it/schur_beam.rs"]
mod schur_beam;

use std::time::Instant;
use unilateral_lcp::{
    basic_after, first_different_step, follow_schur_path, Follow, PathOptions, PathSolver,
    SchurOptions, Settings,
};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let m: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let dense = args.iter().any(|a| a == "--dense");
    let n = 3 * m;
    let t = Instant::now();
    let lcp = schur_beam::beam_schur(m, &schur_beam::BeamData::default());
    println!(
        "m = {m}, n = {n}, N = {}: built in {:.3} s",
        lcp.a.nrows(),
        t.elapsed().as_secs_f64()
    );
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        1.0 / (1.0 + i.abs_diff(j) as f64) + f64::from(i == j) * n as f64
    });
    let t = Instant::now();
    let lu = a.partial_piv_lu();
    let lu_s = t.elapsed().as_secs_f64();
    std::hint::black_box(&lu);
    drop(lu);
    drop(a);
    println!("one dense LU of order {n}: {lu_s:.3} s");
    let (order, relations) = schur_beam::contact_order_and_relations(m, 0.3);
    let opts = SchurOptions {
        target: 1.0,
        follow: Follow::ToEnd,
        max_pivots: 20 * n + 100,
        max_border: 40,
        order: Some(order.clone()),
        relations: relations.clone(),
        progress: Default::default(),
    };
    let t = Instant::now();
    let path = follow_schur_path(&lcp, &opts);
    let s = t.elapsed().as_secs_f64();
    println!(
        "schur engine: {:?}, {} steps, {} refactorisations ({} forced), {s:.3} s ({:.2} × one LU, {:.0} µs a step)",
        path.status,
        path.steps.len(),
        path.refactorizations,
        path.singular_updates,
        s / lu_s,
        1e6 * s / path.steps.len().max(1) as f64
    );
    if dense {
        let t = Instant::now();
        let problem = schur_beam::contact_dense(&lcp, 0.3);
        let form = t.elapsed().as_secs_f64();
        let settings = Settings {
            lexicographic_order: Some(order),
            row_relations: relations,
            ..Settings::default()
        };
        let check_var: Option<usize> = std::env::var("CHECK_VAR").ok().and_then(|v| v.parse().ok());
        if let Ok(ks) = std::env::var("CHECK_STEPS") {
            for k in ks.split(',').filter_map(|k| k.parse::<usize>().ok()) {
                let basic = basic_after(&path.steps, k, n);
                let formed = problem.basis_solution(&basic).unwrap();
                let sparse = lcp.basis_solution(&basic).unwrap();
                println!(
                    "step {k}: schur p = {}, formed M (full pivoting) p = {}, dense LU of the sparse equations p = {}",
                    path.steps[k - 1].p,
                    formed[2 * n],
                    sparse[2 * n]
                );
                if let Some(v) = check_var {
                    println!(
                        "  variable {v}: formed M {}, sparse equations {}",
                        formed[v], sparse[v]
                    );
                }
            }
        }
        let popts = PathOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            tightening: None,
        };
        let t = Instant::now();
        let solver = PathSolver::new(problem, popts, settings).unwrap();
        let want = solver.follow();
        let d = t.elapsed().as_secs_f64();
        if let Ok(ks) = std::env::var("CHECK_DENSE_STEPS") {
            for k in ks.split(',').filter_map(|k| k.parse::<usize>().ok()) {
                let formed = solver
                    .problem()
                    .basis_solution(&basic_after(&want.steps, k, n))
                    .unwrap();
                println!(
                    "dense step {k}: p = {}, formed M (full pivoting) p = {}",
                    want.steps[k - 1].p,
                    formed[2 * n]
                );
                if let Some(v) = check_var {
                    println!("  variable {v}: formed M {}", formed[v]);
                }
            }
        }
        let diff = first_different_step(&want.steps, &path.steps);
        let same = diff.is_none();
        if let Some(k) = diff.filter(|&k| k < want.steps.len().min(path.steps.len())) {
            println!(
                "first difference at step {}: dense {:?}, schur {:?}",
                k + 1,
                &want.steps[k.saturating_sub(1)..(k + 2).min(want.steps.len())],
                &path.steps[k.saturating_sub(1)..(k + 2).min(path.steps.len())]
            );
        }
        println!(
            "dense engine: {:?}, {} steps, {d:.3} s ({:.2} × one LU; forming M {form:.3} s); the same pivots: {same}",
            want.status,
            want.steps.len(),
            d / lu_s
        );
    }
}
