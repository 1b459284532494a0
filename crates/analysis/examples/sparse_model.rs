//! A structural model's path traced by the dense engine and by the engine on sparse data
//! (its doubtful rates judged on the dense data), compared pivot by pivot; `beam:M` is the
//! whole-process benchmark's beam on `M` bearings, a `TARGET` traces to it instead of to the
//! end:
//!
//! ```text
//! cargo run --release -p unilateral-analysis --example sparse_model -- MODEL.toml|beam:M [TARGET]
//! ```
//!
//! Diagnostics, each by an environment variable: `CHECK_P` — where the breakpoint loads first
//! part by more than 1e-6, that basis's load on the condensed zone, on the structure's
//! equations (refined) and on an `M` formed by a dense LU of `K_II`; `CHECK_M` — the condensed
//! `M` against that `M` entry by entry; `CHECK_RAY` (with `CHECK_RAY_SPARSE`) — each ray's
//! basis at its start, 10 and 10⁶ times beyond, on the condensed zone (and on the structure's
//! equations); `FOLLOW_SPARSE` — what `PathSolver::follow_sparse` makes of the path;
//! `PRINT_STEPS=A..B` — both engines' steps `A` to `B − 1`.

use std::time::Instant;

use unilateral_analysis::{sparse_zone_of, zone_of};
use unilateral_contact::ContactLcp;
use unilateral_io::{read_problem, Problem};
use unilateral_lcp::{
    basic_after, first_different_step, Follow, PathOptions, PathSolver, SchurOptions, Settings,
};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("a model file");
    // `beam:M`: the whole-process benchmark's beam on M bearings.
    let dir = tempfile::tempdir().unwrap();
    let path = match path.strip_prefix("beam:") {
        Some(m) => {
            let file = dir.path().join("beam.toml");
            let model = unilateral_oracle::fixtures::bearings::beam_model(m.parse().unwrap());
            std::fs::write(&file, model).unwrap();
            file.to_string_lossy().into_owned()
        }
        None => path.clone(),
    };
    let target: Option<f64> = args.get(2).and_then(|s| s.parse().ok());
    let Problem::Structural(p) = read_problem(std::path::Path::new(&path)).unwrap() else {
        panic!("a structural model")
    };
    let model = p.model;
    let sparse = sparse_zone_of(&model).unwrap();
    let lcp = sparse.lcp();
    let n = lcp.order();
    let (order, relations) = (sparse.lexicographic_order(), sparse.row_relations());
    let zone = zone_of(&model.condense().unwrap());
    let dense = ContactLcp::build(&zone);
    let settings = Settings {
        lexicographic_order: Some(order.clone()),
        row_relations: relations.clone(),
        ..Settings::default()
    };
    let (follow, target) = match target {
        Some(t) => (Follow::ToTarget, t),
        None => (Follow::ToEnd, 1.0),
    };
    let opts = PathOptions {
        target,
        follow,
        tightening: None,
    };
    let problem = dense.problem.clone();
    if std::env::var("CHECK_M").is_ok() {
        let other = lcp.dense();
        let (mut zeroed, mut maxrel, mut maxabs_rel_row) = (0usize, 0.0f64, 0.0f64);
        for i in 0..n {
            let row = (0..n).fold(0.0f64, |a, j| a.max(problem.m[(i, j)].abs()));
            for j in 0..n {
                let (a, b) = (problem.m[(i, j)], other.m[(i, j)]);
                if a == 0.0 && b != 0.0 {
                    zeroed += 1;
                    maxabs_rel_row = maxabs_rel_row.max(b.abs() / row);
                }
                if b != 0.0 {
                    maxrel = maxrel.max((a - b).abs() / row);
                }
            }
        }
        let dq = (0..n).fold(0.0f64, |a, i| {
            a.max(
                (problem.q0[i] - other.q0[i]).abs()
                    / problem.q0.iter().fold(0.0f64, |s, v| s.max(v.abs())),
            )
        });
        let dd = (0..n).fold(0.0f64, |a, i| {
            a.max(
                (problem.d[i] - other.d[i]).abs()
                    / problem.d.iter().fold(0.0f64, |s, v| s.max(v.abs())),
            )
        });
        println!("condensed M against M by a dense LU of A: {zeroed} entries zero in the condensed one (largest {maxabs_rel_row:e} of its row), largest difference {maxrel:e} of the row; q0 {dq:e}, d {dd:e}");
    }
    let solver = PathSolver::new(dense.problem, opts, settings).unwrap();
    // `SPARSE_ONLY`: the sparse engine's path alone (for profiling it).
    if std::env::var("SPARSE_ONLY").is_ok() {
        let options = SchurOptions {
            target,
            follow,
            max_pivots: 20 * n + 100,
            max_border: std::env::var("MAX_BORDER").map_or(40, |v| v.parse().unwrap()),
            order: Some(order),
            relations,
            progress: Default::default(),
        };
        let t = Instant::now();
        let got = solver.trace_sparse(&lcp, &options);
        let mut h = 0u64;
        for st in &got.steps {
            h = h.rotate_left(7) ^ st.p.to_bits();
        }
        println!(
            "sparse {:?} {} steps (hash of the loads {h:x}) {:.3} s, {} refactorisations",
            got.status,
            got.steps.len(),
            t.elapsed().as_secs_f64(),
            got.refactorizations
        );
        return;
    }
    let t = Instant::now();
    let want = solver.follow();
    let td = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let options = SchurOptions {
        target,
        follow,
        max_pivots: 20 * n + 100,
        max_border: 40,
        order: Some(order),
        relations,
        progress: Default::default(),
    };
    let got = solver.trace_sparse(&lcp, &options);
    let ts = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let taken = std::env::var("FOLLOW_SPARSE")
        .is_ok()
        .then(|| solver.follow_sparse(&lcp, &options))
        .flatten();
    println!(
        "taken by follow_sparse: {:?} ({:.3} s)",
        taken.map(|p| (p.status, p.steps.len(), p.solution.map(|s| s.p))),
        t.elapsed().as_secs_f64()
    );
    println!(
        "dense {:?} {} steps (limit load {:?}) {td:.3} s; sparse {:?} {} steps {ts:.3} s, {} refactorisations",
        want.status,
        want.steps.len(),
        want.p_limit,
        got.status,
        got.steps.len(),
        got.refactorizations
    );
    let col = |v: unilateral_lcp::Var| match v {
        unilateral_lcp::Var::X(i) => i,
        unilateral_lcp::Var::Z(i) => n + i,
        unilateral_lcp::Var::Driver => 2 * n,
    };
    let want_schur = (
        want.status,
        &want.steps,
        want.last_entering.map_or(2 * n, col),
    );
    let got_schur = (got.status, &got.steps, got.last_entering.unwrap_or(2 * n));
    for (name, path) in [("dense", &want_schur), ("sparse", &got_schur)] {
        if path.0 != unilateral_lcp::PathStatus::Ray || std::env::var("CHECK_RAY").is_err() {
            continue;
        }
        let steps = path.1;
        let k = steps.len();
        let mut basic = basic_after(steps, k, n);
        let e = path.2;
        basic[2 * n] = false;
        basic[e] = true;
        let p_end = steps.last().unwrap().p;
        for far in [p_end * 1.0001, p_end * 10.0, p_end * 1e6] {
            let shifted = unilateral_lcp::ParametricLcp {
                m: problem.m.clone(),
                q0: problem
                    .q0
                    .iter()
                    .zip(&problem.d)
                    .map(|(q, d)| q + far * d)
                    .collect(),
                d: problem.d.clone(),
            };
            let sol = shifted.basis_solution(&basic).unwrap();
            let (v, x, scale) = most_negative(&sol, n);
            println!("{name} ray's basis at p = {far:e}: most negative {v} = {x:e} (largest of its kind {scale:e})");
            if std::env::var("CHECK_RAY_SPARSE").is_ok() {
                let sol = lcp.at_load(far).basis_solution(&basic).unwrap();
                let (v, x, scale) = most_negative(&sol, n);
                println!("  on the sparse equations: most negative {v} = {x:e} (largest of its kind {scale:e})");
            }
        }
    }
    {
        let k = first_different_step(&want.steps, &got.steps)
            .unwrap_or(want.steps.len().min(got.steps.len()));
        let mut first = None;
        for j in 0..k {
            let (a, b) = (want.steps[j].p, got.steps[j].p);
            if (a - b).abs() > 1e-6 * a.abs().max(b.abs()) && first.is_none() {
                first = Some(j);
            }
        }
        if let Some(j) = first {
            println!(
                "breakpoint loads first differ by more than 1e-6 at step {}: dense {} sparse {}",
                j + 1,
                want.steps[j].p,
                got.steps[j].p
            );
            for i in j.saturating_sub(3)..(j + 2).min(k) {
                println!(
                    "   step {}: dense {:?} sparse p {}",
                    i + 1,
                    want.steps[i],
                    got.steps[i].p
                );
            }
            if std::env::var("CHECK_P").is_ok() {
                for step in [j + 1, k] {
                    let basic = basic_after(&want.steps, step, n);
                    let pd = problem.basis_solution(&basic).unwrap()[2 * n];
                    let ps = lcp.basis_solution(&basic).unwrap()[2 * n];
                    let pl = lcp.dense().basis_solution(&basic).unwrap()[2 * n];
                    println!("   after step {step}: p by a dense LU of the condensed data {pd}, of the sparse equations {ps}, of M formed by a dense LU of A {pl}");
                }
            }
        }
    }
    if let Ok(range) = std::env::var("PRINT_STEPS") {
        let (a, b) = range.split_once("..").unwrap();
        let (a, b): (usize, usize) = (a.parse().unwrap(), b.parse().unwrap());
        for (name, steps) in [("dense", &want.steps), ("sparse", &got.steps)] {
            for st in steps.iter().filter(|st| (a..b).contains(&st.index)) {
                println!("{name} {:?}", st);
            }
        }
    }
    let adopted = solver.adopt(got.clone());
    for (name, path) in [("dense", Some(&want)), ("sparse", adopted.as_ref())] {
        let Some(path) = path else { continue };
        if path.status != unilateral_lcp::PathStatus::Ray {
            continue;
        }
        let start = path.breakpoints.last().map_or(0.0, |b| b.p);
        for far in [start * 1.0001, start * 10.0, start * 1e6] {
            let pt = solver.solution_at(path, far).unwrap();
            println!(
                "{name}: the solver's point at {far:e}: {:?}",
                pt.map(|p| (p.fallback, p.tightening_pivots, p.residual))
            );
        }
    }
    if let Some(k) = first_different_step(&want.steps, &got.steps) {
        println!("first difference at step {}", k + 1);
        for j in k.saturating_sub(1)..(k + 3) {
            for (name, steps) in [("dense", &want.steps), ("sparse", &got.steps)] {
                if j < steps.len() {
                    println!("  {name} {:?}", steps[j]);
                }
            }
        }
        for j in [k, k + 1, k + 2] {
            for (name, steps) in [("dense", &want.steps), ("sparse", &got.steps)] {
                if (1..=steps.len()).contains(&j) {
                    let basic = basic_after(steps, j, n);
                    let sol = problem.basis_solution(&basic).unwrap();
                    let (mut worst, mut at) = (0.0f64, 0);
                    let xs = sol[..n].iter().fold(0.0f64, |a, v| a.max(v.abs()));
                    let zs = sol[n..2 * n].iter().fold(0.0f64, |a, v| a.max(v.abs()));
                    for (v, &x) in sol[..2 * n].iter().enumerate() {
                        let r = x / if v < n { xs } else { zs };
                        if r < worst {
                            worst = r;
                            at = v;
                        }
                    }
                    println!(
                        "  {name} after step {j}: most negative {at} at {worst:e} of its kind"
                    );
                }
            }
        }
    }
}

/// The most negative of `x` and `z` against the largest of its kind.
fn most_negative(sol: &[f64], n: usize) -> (usize, f64, f64) {
    let xs = sol[..n].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let zs = sol[n..2 * n].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let (mut worst, mut at) = (0.0f64, 0);
    for (v, &x) in sol[..2 * n].iter().enumerate() {
        let r = x / if v < n { xs } else { zs };
        if r < worst {
            worst = r;
            at = v;
        }
    }
    (at, sol[at], if at < n { xs } else { zs })
}
