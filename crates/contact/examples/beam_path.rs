//! Runs the generated beam benchmark problem once and prints what happened.
//! `cargo run --release -p unilateral-contact --example beam_path -- 300`
use std::time::Instant;
use unilateral_contact::{generate::beam_on_supports, solve, SolveSettings, Trace};

fn main() {
    let m: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let zone = beam_on_supports(m, 7);
    let t = Instant::now();
    let sol = solve(
        &zone,
        &SolveSettings {
            trace: Trace::End,
            ..Default::default()
        },
    )
    .unwrap();
    let dt = t.elapsed();
    let mut counts = std::collections::BTreeMap::new();
    for p in &sol.pairs {
        *counts.entry(p.state.as_str()).or_insert(0) += 1;
    }
    println!(
        "m = {m}: {} in {} steps ({} refactorisations), {:.3} s, residual {:?}, states at p*: {counts:?}",
        sol.outcome.status(),
        sol.steps.len(),
        sol.path.refactorizations,
        dt.as_secs_f64(),
        sol.residual.map(|r| r.max())
    );
    println!(
        "notes: {:?}; solution fallback: {:?}",
        sol.notes,
        sol.path
            .solution
            .as_ref()
            .map(|s| (s.fallback, s.tightening_pivots))
    );
    if let unilateral_contact::Outcome::Mechanism { p_limit, mode } = &sol.outcome {
        let big: Vec<_> = mode
            .iter()
            .enumerate()
            .filter(|(_, v)| v.0.abs() + v.1.abs() > 1e-6)
            .collect();
        println!("p_lim = {p_limit}, mode entries: {}", big.len());
        println!(
            "last steps: {:?}",
            &sol.steps[sol.steps.len().saturating_sub(3)..]
                .iter()
                .map(|s| (s.p, s.entering.clone(), s.leaving.clone()))
                .collect::<Vec<_>>()
        );
        if std::env::var("LCP_DEBUG").is_ok() {
            return;
        }
        for fac in [1.0001, 1.5, 3.0] {
            let p = p_limit * fac;
            let q: Vec<f64> = sol
                .lcp
                .problem
                .q0
                .iter()
                .zip(&sol.lcp.problem.d)
                .map(|(a, b)| a + p * b)
                .collect();
            let r = unilateral_lcp::solve_lcp(
                &unilateral_lcp::Lcp {
                    m: sol.lcp.problem.m.clone(),
                    q,
                },
                &Default::default(),
            )
            .unwrap();
            println!("standard LCP at p = {p}: {:?} {:?}", r.status, r.attempts);
        }
    }
}

#[allow(dead_code)]
fn unused() {}
