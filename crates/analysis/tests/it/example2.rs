//! Example 2 (examples/example2-cantilever.toml): cantilever bar on a rigid base with friction,
//! run for n = 5 … 160 elements. Checks the tip displacement against the continuum solution
//! (relative error < 0.05 % for every n, < 0.001 % for n ≥ 80), against the exact solution of
//! the discretised problem (1e-9 relative), and the order of the slip events.

use std::path::Path;

use unilateral_analysis::{analyze, Outcome, PairState};
use unilateral_contact::EventKind;
use unilateral_io::{read_model, StructuralProblem};

const L: f64 = 260.0;
const Q: f64 = 3975.0;
const F: f64 = 243750.0;
const FRICTION: f64 = 0.3;
const EA: f64 = 2.1e11 * 1.0e-2;

/// The example file with `divisions = n`.
fn model(n: usize, dir: &Path) -> StructuralProblem {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/example2-cantilever.toml");
    let text = std::fs::read_to_string(src).unwrap();
    assert!(text.contains("divisions = 20\n"));
    let text = text.replace("divisions = 20\n", &format!("divisions = {n}\n"));
    let path = dir.join(format!("example2-n{n}.toml"));
    std::fs::write(&path, text).unwrap();
    read_model(&path).unwrap()
}

/// Exact tip displacement of the discretised bar: nodes 1..n carry the normal forces
/// N_k = q·h (q·h/2 at the free end); the nodes that slip are those whose left element is in
/// tension T_j = F − f·Σ_{k>j} N_k > 0 (friction at its limit, f·N_k, against the motion), the
/// others stick (u = 0). Then u_tip = Σ_j h·max(T_j, 0)/EA over the elements j = 0..n−1.
fn discrete_u_tip(n: usize) -> (f64, usize) {
    let h = L / n as f64;
    let normal = |k: usize| if k == n { Q * h / 2.0 } else { Q * h };
    let mut u = 0.0;
    let mut slipping = 0;
    for j in 0..n {
        let t = F - FRICTION * ((j + 1)..=n).map(normal).sum::<f64>();
        if t > 0.0 {
            u += h * t / EA;
            slipping += 1;
        }
    }
    (u, slipping)
}

#[test]
fn example2_release_table() {
    let dir = tempfile::tempdir().unwrap();
    let exact = F * F / (2.0 * FRICTION * Q * EA);
    println!("   n        u_tip (m)      rel. error (%)   discrete exact rel. diff");
    for n in [5usize, 10, 20, 40, 80, 160] {
        let p = model(n, dir.path());
        let a = analyze(&p.model, &p.settings).unwrap();
        assert_eq!(a.solution.outcome, Outcome::TargetReached);
        let r = a.results.as_ref().unwrap();
        let tip = p.model.names().node_id("bar.end").unwrap();
        let u = r.displacements[tip.0][0];
        let rel = (u - exact).abs() / exact;
        let (ud, slipping) = discrete_u_tip(n);
        let rel_d = (u - ud).abs() / ud;
        println!("{n:4}   {u:.10e}   {:.6}          {rel_d:.2e}", 100.0 * rel);
        assert!(rel_d < 1e-9, "n = {n}: {u} vs discrete {ud}");
        assert!(rel < 5e-4, "n = {n}: relative error {rel}");
        if n >= 80 {
            assert!(rel < 1e-5, "n = {n}: relative error {rel}");
        }
        assert!(r.equilibrium.relative() < 1e-9);

        // Every pair stays closed; the last `slipping` pairs (from the free end) slip.
        let pairs = &a.solution.pairs;
        assert_eq!(pairs.len(), n);
        for (k, pr) in pairs.iter().enumerate() {
            assert!(pr.x_n > 0.0);
            if k + slipping >= n {
                assert_eq!(pr.state, PairState::SlipPlus, "n = {n}, pair {}", k + 1);
                assert!((pr.x_t + FRICTION * pr.x_n).abs() < 1e-9 * F);
            } else {
                assert_eq!(pr.state, PairState::Stick, "n = {n}, pair {}", k + 1);
            }
        }

        // Events: one pair starts to slip per step, from the free end towards the clamp.
        let events: Vec<_> = a
            .solution
            .steps
            .iter()
            .flat_map(|s| s.events.iter().map(move |e| (s.p, e.clone())))
            .collect();
        assert_eq!(events.len(), slipping, "n = {n}");
        let mut last_p = 0.0;
        for (i, (p_event, e)) in events.iter().enumerate() {
            assert_eq!(e.kind, EventKind::StartsSlippingPlus);
            assert_eq!(e.pair, n - 1 - i, "n = {n}: event {i} at pair {}", e.name);
            assert!(*p_event > last_p && *p_event <= 1.0);
            last_p = *p_event;
        }
    }
}
