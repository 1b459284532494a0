//! A cyclic load history on the generated beam on frictional supports (`beam_on_supports(m, 7)`,
//! its constant load as the dead case and its variable load as the cyclic one): the dead load,
//! then `stages − 1` stages that take the cyclic case alternately to `1` and back to `0` (loading and unloading: reversed, the point loads would lift the floating beam off its bearings, a mechanism), against one
//! dense LU of order `3m` in the same run.
//!
//! ```text
//! cargo bench -p unilateral-contact --bench history            # report + criterion, m = 100, 300
//! UNILATERAL_BENCH_STAGES=20 cargo bench -p unilateral-contact --bench history
//! ```
//!
//! The report pass prints, per size: stages, steps (changes of the working scheme), seconds,
//! seconds per step and the ratio to the LU. Under `cargo test` only m = 30 with 10 stages runs.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, SamplingMode};
use faer::Mat;
#[path = "../tests/it/beam_zone.rs"]
mod beam_zone;
use beam_zone::beam_on_supports;
use unilateral_contact::{follow_history, History, HistorySolution, LoadCase, Stage, StageStatus};

mod common;
use common::one_thread;

fn history_of(m: usize, stages: usize) -> (unilateral_contact::ContactZone, History) {
    let zone = beam_on_supports(m, 7);
    let mut st = vec![Stage {
        name: "dead".into(),
        factors: vec![Some(1.0), None],
    }];
    for k in 1..stages {
        st.push(Stage {
            name: format!("cycle {k}"),
            factors: vec![None, Some(if k % 2 == 1 { 1.0 } else { 0.0 })],
        });
    }
    let history = History {
        cases: vec![
            LoadCase {
                name: "dead".into(),
                load: zone.constant.clone(),
            },
            LoadCase {
                name: "cyclic".into(),
                load: zone.variable.clone(),
            },
        ],
        stages: st,
    };
    (zone, history)
}

fn run(zone: &unilateral_contact::ContactZone, h: &History) -> HistorySolution {
    follow_history(zone, h, &Default::default()).expect("the generated zone is valid")
}

fn lu_seconds(n: usize) -> f64 {
    let a = Mat::<f64>::from_fn(n, n, |i, j| {
        ((i * 31 + j * 17) % 97) as f64 / 97.0 + if i == j { n as f64 } else { 0.0 }
    });
    let t = Instant::now();
    black_box(one_thread(|| a.partial_piv_lu()));
    t.elapsed().as_secs_f64()
}

fn main() {
    let bench = std::env::args().any(|a| a == "--bench");
    let stages: usize = std::env::var("UNILATERAL_BENCH_STAGES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let sizes: Vec<usize> = if bench { vec![100, 300] } else { vec![30] };
    let stages = if bench { stages } else { 10 };
    for &m in &sizes {
        let (zone, h) = history_of(m, stages);
        let t = Instant::now();
        let sol = run(&zone, &h);
        let secs = t.elapsed().as_secs_f64();
        let steps: usize = sol.stages.iter().map(|s| s.steps.len()).sum();
        let done = sol
            .stages
            .iter()
            .filter(|s| s.status == StageStatus::Completed)
            .count();
        let worst = sol
            .stages
            .iter()
            .map(|s| s.residual.max())
            .fold(0.0f64, f64::max);
        let lu = lu_seconds(3 * m);
        println!(
            "history m = {m:4} (n = {:4}): {done}/{} stages completed, {steps} steps, {secs:.3} s \
             ({:.2} ms/step), worst residual {worst:.1e}, one LU {lu:.4} s, ratio {:.1}",
            3 * m,
            h.stages.len(),
            1e3 * secs / steps.max(1) as f64,
            secs / lu
        );
    }
    if bench {
        let mut c = Criterion::default()
            .sample_size(10)
            .measurement_time(Duration::from_secs(5));
        let mut g = c.benchmark_group("history");
        g.sampling_mode(SamplingMode::Flat);
        let (zone, h) = history_of(100, stages);
        g.bench_function("m100", |b| b.iter(|| black_box(run(&zone, &h))));
        g.finish();
        c.final_summary();
    }
}
