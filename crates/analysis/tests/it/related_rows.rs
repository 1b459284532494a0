//! The whole-process benchmark's long-path model (a continuous beam on frictional elastic
//! bearings, `crates/cli/benches/whole_process.rs`, case `beam`) at m = 700, the smallest size in
//! 600..=1000 whose path failed: it stopped at a numerically singular basis after 2152 steps
//! (p ≈ 5134). There pair 274, slipping in the + direction (`z_t+` basic, `x_t+ = 0`), had
//! `x_t- = 2f·x_n` by the data, so its rows `x_n` and `x_t-` reach zero at the same load; judged
//! on round-off of the basic values the opposite friction row `x_t-` left instead of the normal
//! row, its complement `z_t-` (the column of `z_t+` negated) entered, and the basis turned
//! singular. The friction rows' relation `x_t+ + x_t- − 2f·x_n = (2·max(1, f) − 2f)·c` is now
//! given to the engine, which decides such ties from it.
//!
//! References, none of them the code under test:
//! * the physics: every bearing has springs, and the friction capacity `0.3·Σx_n` exceeds the
//!   sideways load at every load (by vertical equilibrium `Σx_n = L·(1e4 + 1.5e4·p)` over the
//!   beam of length L, the variable load going linearly from 4e4 down to −1e4 N/m; so a
//!   capacity of `L·(3e3 + 4.5e3·p)` against `L·1e3·p` sideways): the structure is never a
//!   mechanism and the load path ends in a ray (the scheme stops changing);
//! * the contact conditions (formulation.md §1–§3) of the reported solutions, at the target and
//!   on the final ray beyond the last event (the state the failure kept the path from), evaluated
//!   here from the contact zone's matrices and loads (`x = R_c + p·R_v + R z`), each row against
//!   the terms that form it, and the vertical equilibrium `Σx_n` against the hand value above.

use crate::zone_rows::{bearing_beam, check_contact_conditions};
use unilateral_contact::Outcome;

/// The 700-bearing beam is traced to its ray, and its solutions at the target and beyond the
/// last event satisfy the contact conditions, checked from the zone's data.
#[test]
fn the_700_bearing_beam_is_traced_to_its_ray() {
    const M: usize = 700;
    let a = bearing_beam(M);
    let s = &a.solution;
    let Outcome::Ray { p_from } = s.outcome else {
        panic!(
            "the structure is no mechanism and the path must not fail: {:?} after {} steps",
            s.outcome,
            s.steps.len()
        );
    };
    // The failure was at p ≈ 5134 after 2151 steps. Since the engine takes the starts of slip
    // whose rates it used to read as round-off of the column (`docs/performance.md`, round
    // 27), the path is another: it ends in a ray from p ≈ 1178.7 after 2150 steps, whose
    // solution beyond the last event is checked below from the zone's data.
    assert!(
        p_from > 1000.0 && s.steps.len() > 2140,
        "{} steps to {p_from}",
        s.steps.len()
    );
    assert_eq!(s.p, Some(1.0), "the solution is reported at the target");
    let terms = check_contact_conditions(&a.zone, 1.0, &s.pairs);
    let sum: f64 = s.pairs.iter().map(|r| r.x_n).sum();
    let hand = (M - 1) as f64 * (1e4 + 1.5e4);
    assert!(
        (sum - hand).abs() <= 1e-9 * terms,
        "Σx_n = {sum}, by hand {hand}, terms {terms}"
    );

    // On the final ray, beyond the last event.
    let p_end = 2.0 * p_from;
    let (pairs, residual) = s.at(p_end).unwrap().expect("a solution on the ray");
    assert!(
        residual.max() <= unilateral_lcp::ACCEPT_RESIDUAL,
        "verified: {residual:?}"
    );
    let terms = check_contact_conditions(&a.zone, p_end, &pairs);
    // Vertical equilibrium of the beam (length L = M − 1): Σx_n = L·(1e4 + 1.5e4·p), within
    // round-off of the terms that form the normal forces (far beyond the target the slips are
    // large and their terms cancel).
    let sum: f64 = pairs.iter().map(|r| r.x_n).sum();
    let hand = (M - 1) as f64 * (1e4 + 1.5e4 * p_end);
    assert!(
        (sum - hand).abs() <= 1e-9 * terms,
        "Σx_n = {sum}, by hand {hand}, terms {terms}"
    );
}
