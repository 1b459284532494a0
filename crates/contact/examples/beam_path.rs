//! Follows the load path of the generated beam on `m` frictional supports to its end and prints
//! what happened: `cargo run --release -p unilateral-contact --example beam_path -- 300`; a
//! second argument is the tightening `c` (default 0), e.g. `-- 300 1`.

use std::collections::BTreeMap;
use std::time::Instant;

#[path = "../tests/it/beam_zone.rs"]
mod beam_zone;
use beam_zone::beam_on_supports;
use unilateral_contact::{solve, Follow, SolveSettings};

fn main() {
    let m: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let tightening: f64 = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.0);
    let zone = beam_on_supports(m, 7);
    let t = Instant::now();
    let settings = SolveSettings {
        follow: Follow::ToEnd,
        tightening,
        ..Default::default()
    };
    let sol = solve(&zone, &settings).expect("a valid generated zone");
    let dt = t.elapsed();
    let mut states = BTreeMap::new();
    for p in &sol.pairs {
        *states.entry(p.state.as_str()).or_insert(0) += 1;
    }
    println!(
        "m = {m}: {} after {} steps ({} refactorisations) in {:.3} s; at p* = 1: {states:?}; residual {:.1e}",
        sol.outcome.status(),
        sol.steps.len(),
        sol.path.refactorizations,
        dt.as_secs_f64(),
        sol.residual.map_or(f64::NAN, |r| r.max()),
    );
    for note in &sol.notes {
        println!("note: {note}");
    }
}
