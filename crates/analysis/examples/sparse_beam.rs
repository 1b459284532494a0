//! The whole-process benchmark's beam on `m` frictional elastic bearings (default 2000) traced
//! to its end by the engine on sparse data, from the model's bonded blocks, timed beside one
//! dense LU of the contact LCP's order; with `--dense`, the condensation and the dense engine
//! on the same model too:
//!
//! ```text
//! cargo run --release -p unilateral-analysis --example sparse_beam -- 2000 [--dense]
//! ```

use std::time::Instant;

use unilateral_analysis::{sparse_zone_of, zone_of};
use unilateral_contact::ContactLcp;
use unilateral_io::{read_problem, Problem};
use unilateral_lcp::{
    basic_after, first_different_step, follow_schur_path, Follow, PathOptions, PathSolver,
    SchurOptions, Settings,
};
use unilateral_oracle::fixtures::bearings::beam_model;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let m: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let dense = args.iter().any(|a| a == "--dense");
    let n = 3 * m;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("beam.toml");
    std::fs::write(&path, beam_model(m)).unwrap();
    let t = Instant::now();
    let Problem::Structural(p) = read_problem(&path).unwrap() else {
        panic!("a structural model")
    };
    let model = p.model;
    let read = t.elapsed().as_secs_f64();
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        1.0 / (1.0 + i.abs_diff(j) as f64) + f64::from(i == j) * n as f64
    });
    let t = Instant::now();
    let lu = a.partial_piv_lu();
    let lu_s = t.elapsed().as_secs_f64();
    std::hint::black_box(&lu);
    drop((lu, a));
    println!("m = {m}: read {read:.3} s; one dense LU of order {n}: {lu_s:.3} s");
    let t = Instant::now();
    let zone = sparse_zone_of(&model).unwrap();
    let lcp = zone.lcp();
    let blocks = t.elapsed().as_secs_f64();
    let (order, relations) = (zone.lexicographic_order(), zone.row_relations());
    let lcp_sparse = lcp.clone();
    let t = Instant::now();
    let got = follow_schur_path(
        &lcp,
        &SchurOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            max_pivots: 20 * n + 100,
            max_border: 40,
            order: Some(order.clone()),
            relations: relations.clone(),
            progress: Default::default(),
        },
    );
    let s = t.elapsed().as_secs_f64();
    println!(
        "sparse: blocks and LCP {blocks:.3} s; path {:?}, {} steps, {s:.3} s; blocks + path {:.2} × one LU",
        got.status,
        got.steps.len(),
        (blocks + s) / lu_s
    );
    if dense {
        let t = Instant::now();
        let zone = zone_of(&model.condense().unwrap());
        let lcp = ContactLcp::build(&zone);
        let cond = t.elapsed().as_secs_f64();
        let settings = Settings {
            lexicographic_order: Some(order),
            row_relations: relations,
            ..Settings::default()
        };
        let opts = PathOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            tightening: None,
        };
        let problem = lcp.problem.clone();
        let t = Instant::now();
        let want = PathSolver::new(lcp.problem, opts, settings)
            .unwrap()
            .follow();
        let d = t.elapsed().as_secs_f64();
        let diff = first_different_step(&want.steps, &got.steps);
        let same = diff.is_none();
        if let Some(k) = diff.filter(|&k| k < want.steps.len().min(got.steps.len())) {
            println!(
                "first difference at step {}: dense {:?}, sparse {:?}",
                k + 1,
                want.steps[k],
                got.steps[k]
            );
            for j in [k + 1, k + 2, k + 3] {
                for (name, steps) in [("dense", &want.steps), ("sparse", &got.steps)] {
                    if j <= steps.len() {
                        let basic = basic_after(steps, j, n);
                        let (v, x, scale) =
                            most_negative(&problem.basis_solution(&basic).unwrap(), n);
                        println!("  {name} after step {j} (p = {}): most negative basic variable {v} = {x:e} (largest of its kind {scale:e})", steps[j - 1].p);
                        if let Ok(var) = std::env::var("CHECK_VAR") {
                            let var: usize = var.parse().unwrap();
                            let sol = lcp_sparse.basis_solution(&basic).unwrap();
                            println!(
                                "    on the sparse equations: variable {var} = {:e}",
                                sol[var]
                            );
                        }
                    }
                }
            }
        }
        println!(
            "dense: condensation and LCP {cond:.3} s; path {:?}, {} steps, {d:.3} s; {:.2} × one LU; the same pivots: {same}",
            want.status,
            want.steps.len(),
            (cond + d) / lu_s
        );
    }
}

/// The most negative `x` or `z` of a solution from [`unilateral_lcp::ParametricLcp::basis_solution`]
/// and the largest of its kind.
fn most_negative(sol: &[f64], n: usize) -> (String, f64, f64) {
    let mut worst = (String::new(), f64::INFINITY, 0.0);
    let mut scale = [0.0f64; 2];
    for (v, &x) in sol.iter().enumerate().take(2 * n) {
        scale[usize::from(v >= n)] = scale[usize::from(v >= n)].max(x.abs());
    }
    for (v, &x) in sol.iter().enumerate().take(2 * n) {
        if x < worst.1 {
            let name = if v < n {
                format!("x{}", v + 1)
            } else {
                format!("z{}", v - n + 1)
            };
            worst = (name, x, scale[usize::from(v >= n)]);
        }
    }
    worst
}
