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
    follow_schur_path, Follow, PathOptions, PathSolver, RowRelation, SchurOptions, Settings,
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
    let order: Vec<usize> = (m..3 * m).chain(0..m).collect();
    let opts = SchurOptions {
        target: 1.0,
        follow: Follow::ToEnd,
        max_pivots: 20 * n + 100,
        max_border: 40,
        order: Some(order.clone()),
        relations: relations(m, 0.3),
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
        let f = 0.3;
        let settings = Settings {
            lexicographic_order: Some(order),
            row_relations: relations(m, f),
            ..Settings::default()
        };
        if let Ok(ks) = std::env::var("CHECK_STEPS") {
            for k in ks.split(',').filter_map(|k| k.parse::<usize>().ok()) {
                println!(
                    "step {k}: schur p = {}, formed M (full pivoting) p = {}, dense LU of the sparse equations p = {}",
                    path.steps[k - 1].p,
                    exact_p(&problem, &path.steps, k),
                    augmented_p(&lcp, &path, k)
                );
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
                println!(
                    "dense step {k}: p = {}, formed M (full pivoting) p = {}",
                    want.steps[k - 1].p,
                    exact_p(&solver.problem(), &want.steps, k)
                );
            }
        }
        let same = want.steps.len() == path.steps.len()
            && want
                .steps
                .iter()
                .zip(&path.steps)
                .all(|(a, b)| (a.entering, a.leaving) == (b.entering, b.leaving));
        if let Some(k) = want
            .steps
            .iter()
            .zip(&path.steps)
            .position(|(a, b)| (a.entering, a.leaving) != (b.entering, b.leaving))
        {
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

/// Each pair's friction relation `x_t+ + x_t- − 2f·x_n = 0`.
fn relations(m: usize, f: f64) -> Vec<RowRelation> {
    (0..m)
        .map(|i| RowRelation {
            terms: vec![(m + i, 1.0), (2 * m + i, 1.0), (i, -2.0 * f)],
        })
        .collect()
}

/// The load after step `k` of `path` from a full-pivoting solve of its basis on the formed problem.
#[allow(dead_code)]
fn exact_p(
    problem: &unilateral_lcp::ParametricLcp,
    steps: &[unilateral_lcp::Step],
    k: usize,
) -> f64 {
    use faer::linalg::solvers::Solve;
    use unilateral_lcp::Var;
    let n = problem.q0.len();
    let col = |v: Var| match v {
        Var::X(i) => i,
        Var::Z(i) => n + i,
        Var::Driver => 2 * n,
    };
    let mut basic: Vec<bool> = (0..=2 * n).map(|v| v < n).collect();
    for s in &steps[..k] {
        basic[col(s.entering)] = true;
        basic[col(s.leaving)] = false;
    }
    let vars: Vec<usize> = (0..=2 * n).filter(|&v| basic[v]).collect();
    let a = faer::Mat::<f64>::from_fn(n, n, |i, c| {
        let v = vars[c];
        if v < n {
            f64::from(v == i)
        } else if v < 2 * n {
            -problem.m[(i, v - n)]
        } else {
            -problem.d[i]
        }
    });
    let rhs = faer::Mat::<f64>::from_fn(n, 1, |i, _| problem.q0[i]);
    let sol = a.full_piv_lu().solve(&rhs);
    if let Ok(v) = std::env::var("CHECK_VAR") {
        let v: usize = v.parse().unwrap();
        if let Some(c) = vars.iter().position(|&u| u == v) {
            println!(
                "  variable {v} after step {k}: {} (formed M, full pivoting)",
                sol[(c, 0)]
            );
        }
    }
    sol[(vars.iter().position(|&v| v == 2 * n).unwrap(), 0)]
}

/// The load after step `k` from a dense LU of the basis's equations on the sparse data
/// (`y` and the basic variables: no formed `M`).
#[allow(dead_code)]
fn augmented_p(lcp: &unilateral_lcp::SchurLcp, path: &unilateral_lcp::SchurPath, k: usize) -> f64 {
    use faer::linalg::solvers::Solve;
    use unilateral_lcp::Var;
    let n = lcp.order();
    let big_n = lcp.a.nrows();
    let col = |v: Var| match v {
        Var::X(i) => i,
        Var::Z(i) => n + i,
        Var::Driver => 2 * n,
    };
    let mut basic: Vec<bool> = (0..=2 * n).map(|v| v < n).collect();
    for s in &path.steps[..k] {
        basic[col(s.entering)] = true;
        basic[col(s.leaving)] = false;
    }
    let vars: Vec<usize> = (0..=2 * n).filter(|&v| basic[v]).collect();
    let size = big_n + n;
    let mut a = faer::Mat::<f64>::zeros(size, size);
    let mut put = |m: &faer::sparse::SparseColMat<usize, f64>,
                   r0: usize,
                   cmap: &dyn Fn(usize) -> Option<usize>,
                   sign: f64| {
        for j in 0..m.ncols() {
            if let Some(c) = cmap(j) {
                for (&i, &v) in m.row_idx_of_col_raw(j).iter().zip(m.val_of_col(j)) {
                    a[(r0 + i, c)] += sign * v;
                }
            }
        }
    };
    let pos = |v: usize| vars.iter().position(|&u| u == v).map(|c| big_n + c);
    put(&lcp.a, 0, &|j| Some(j), 1.0);
    put(&lcp.b, 0, &|j| pos(n + j), -1.0);
    put(&lcp.c, big_n, &|j| Some(j), 1.0);
    put(&lcp.d, big_n, &|j| pos(n + j), -1.0);
    for i in 0..n {
        if let Some(c) = pos(i) {
            a[(big_n + i, c)] += 1.0;
        }
    }
    let pc = pos(2 * n).unwrap();
    for i in 0..big_n {
        a[(i, pc)] -= lcp.da[i];
    }
    for i in 0..n {
        a[(big_n + i, pc)] -= lcp.d0[i];
    }
    let rhs = faer::Mat::<f64>::from_fn(size, 1, |i, _| {
        if i < big_n {
            lcp.qa[i]
        } else {
            lcp.q0[i - big_n]
        }
    });
    let sol = a.partial_piv_lu().solve(&rhs);
    if let Ok(v) = std::env::var("CHECK_VAR") {
        let v: usize = v.parse().unwrap();
        if let Some(c) = pos(v) {
            println!(
                "  variable {v} after step {k}: {} (dense LU of the sparse equations)",
                sol[(c, 0)]
            );
        }
    }
    sol[(pc, 0)]
}
