//! Fixtures shared by the contact tests.

use faer::Mat;
use unilateral_contact::{ContactLcp, ContactZone, Follow, SolveSettings};
use unilateral_oracle as oracle;
use unilateral_oracle::fixtures::example1;

/// The paper's Example 1 in contact-zone form (formulation.md §5, the oracle's fixture; the data
/// of examples/example1-contact-zone.toml): three pairs, `f = 0.6`, the variable normal load
/// only.
pub fn example1_zone() -> ContactZone {
    let mat = |a: [[f64; 3]; 3]| Mat::<f64>::from_fn(3, 3, |i, j| a[i][j]);
    let mut zone = ContactZone::new(mat(example1::RNN), mat(example1::RTT));
    zone.friction = vec![example1::FRICTION; example1::PAIRS];
    zone.variable.normal = example1::RV_N.to_vec();
    zone
}

/// The paper's procedure for Example 1: tightening c = 1, target 1, traced to its end.
pub fn example1_paper_settings() -> SolveSettings {
    SolveSettings {
        tightening: 1.0,
        target: 1.0,
        follow: Follow::ToEnd,
        ..SolveSettings::default()
    }
}

/// A contact zone of `m` pairs whose full stiffness `[[Rnn, Rnt], [Rtn, Rtt]]` is the symmetric
/// positive definite `B Bᵀ + I/4` for the `2m × 2m` matrix `B` given entry by entry (`b(i, j)`).
/// Definite: a structure held by its supports, not a mechanism — with a singular `R` the
/// solution need not be unique, and the exact data can have solutions only at numerically
/// singular bases. `load(kind, i)` gives the loads of pair `i`: kind 0 constant normal,
/// 1 constant tangential, 2 variable normal, 3 variable tangential.
pub fn definite_zone(
    m: usize,
    b: impl Fn(usize, usize) -> f64,
    friction: Vec<f64>,
    gap: Vec<f64>,
    load: impl Fn(usize, usize) -> f64,
) -> ContactZone {
    let k = 2 * m;
    let r = Mat::<f64>::from_fn(k, k, |i, j| {
        (0..k).map(|l| b(i, l) * b(j, l)).sum::<f64>() + if i == j { 0.25 } else { 0.0 }
    });
    let block = |r0: usize, c0: usize| Mat::<f64>::from_fn(m, m, |i, j| r[(r0 + i, c0 + j)]);
    let mut zone = ContactZone::new(block(0, 0), block(m, m));
    zone.rnt = block(0, m);
    zone.rtn = block(m, 0);
    zone.friction = friction;
    zone.gap = gap;
    zone.constant.normal = (0..m).map(|i| load(0, i)).collect();
    zone.constant.tangential = (0..m).map(|i| load(1, i)).collect();
    zone.variable.normal = (0..m).map(|i| load(2, i)).collect();
    zone.variable.tangential = (0..m).map(|i| load(3, i)).collect();
    zone
}

/// A matrix as rows (the oracle's layout).
pub fn rows(m: &Mat<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
        .collect()
}

/// Every solution of the zone's LCP at load `p`, by exhaustive enumeration (exact).
pub fn enumerated(zone: &ContactZone, p: f64) -> Vec<(Vec<f64>, Vec<f64>)> {
    let lcp = ContactLcp::build(zone);
    oracle::enumerate_parametric(&rows(&lcp.problem.m), &lcp.problem.q0, &lcp.problem.d, p)
        .into_iter()
        .map(|s| (s.w_f64(), s.z_f64()))
        .collect()
}

/// The reported pair values agree with one of the enumerated solutions at the reported load.
pub fn assert_matches_enumeration(
    zone: &ContactZone,
    p: f64,
    pairs: &[unilateral_contact::PairResult],
) {
    let m = zone.pairs();
    let sols = enumerated(zone, p);
    assert!(!sols.is_empty(), "enumeration finds no solution at p = {p}");
    let found = sols.iter().any(|(x, z)| {
        (0..m).all(|i| {
            let xt = (x[m + i] - x[2 * m + i]) / 2.0;
            let zt = (z[m + i] - z[2 * m + i]) / 2.0;
            let scale = 1.0 + x[i].abs() + z[i].abs();
            (pairs[i].x_n - x[i]).abs() <= 1e-9 * scale
                && (pairs[i].z_n - z[i]).abs() <= 1e-9 * scale
                && (pairs[i].x_t - xt).abs() <= 1e-9 * scale
                && (pairs[i].z_t - zt).abs() <= 1e-9 * scale
        })
    });
    assert!(
        found,
        "reported solution at p = {p} is none of the {} enumerated",
        sols.len()
    );
}
