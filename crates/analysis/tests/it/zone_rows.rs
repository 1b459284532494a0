//! The contact conditions' rows evaluated from a contact zone's own matrices and loads, for the
//! tests that check a reported solution against the zone rather than the engine's values.

use unilateral_analysis::{analyze, Analysis};
use unilateral_contact::{ContactZone, PairResult};
use unilateral_io::{read_problem, Problem};
use unilateral_oracle::fixtures::bearings::beam_model;

/// `x_n` (`normal`) or `x_t` of pair `i` at load `p` for the mutual displacements `zn`, `zt`:
/// `R_c + p·R_v + R z` (formulation.md §2), and the sum of the sizes of the terms that form it.
pub fn zone_row(
    z: &ContactZone,
    p: f64,
    zn: &[f64],
    zt: &[f64],
    i: usize,
    normal: bool,
) -> (f64, f64) {
    let (load_c, load_v, rn, rt) = if normal {
        (&z.constant.normal, &z.variable.normal, &z.rnn, &z.rnt)
    } else {
        (
            &z.constant.tangential,
            &z.variable.tangential,
            &z.rtn,
            &z.rtt,
        )
    };
    let mut v = load_c[i] + p * load_v[i];
    let mut size = load_c[i].abs() + (p * load_v[i]).abs();
    for j in 0..zn.len() {
        v += rn[(i, j)] * zn[j] + rt[(i, j)] * zt[j];
        size += (rn[(i, j)] * zn[j]).abs() + (rt[(i, j)] * zt[j]).abs();
    }
    (v, size)
}

/// The contact conditions of `pairs` at load `p`, from the zone's data; returns the sum of the
/// sizes of the terms that form the normal forces. Each row is measured against the size of
/// its terms; `x_t` is read from the LCP's rows `x_t± = f·x_n ± x_t`, so against those of
/// `f·x_n` as well.
pub fn check_contact_conditions(z: &ContactZone, p: f64, pairs: &[PairResult]) -> f64 {
    let (zn, zt): (Vec<f64>, Vec<f64>) = pairs.iter().map(|r| (r.z_n, r.z_t)).unzip();
    let row = |i: usize, normal: bool| zone_row(z, p, &zn, &zt, i, normal);
    let tol = 1e-9;
    let mut terms = 0.0;
    for (i, r) in pairs.iter().enumerate() {
        let f = z.friction[i];
        let (xn, sn) = row(i, true);
        let (xt, st) = row(i, false);
        let (sn, st) = (sn.max(xn.abs()), st.max(xt.abs()));
        terms += sn;
        assert!(
            (xn - r.x_n).abs() <= tol * sn,
            "p = {p}, pair {i}: x_n {} vs {xn}",
            r.x_n
        );
        // x_t is read from the LCP's rows x_t± = f·x_n ± x_t, each accurate to the round-off
        // of its own terms, which include those of f·x_n.
        assert!(
            (xt - r.x_t).abs() <= tol * (st + f * sn),
            "p = {p}, pair {i}: x_t {} vs {xt}",
            r.x_t
        );
        assert!(xn >= -tol * sn && r.z_n >= 0.0, "p = {p}, pair {i}: signs");
        assert!(
            xn.abs() <= tol * sn || r.z_n == 0.0,
            "p = {p}, pair {i}: x_n·z_n ≠ 0"
        );
        let limit = f * xn;
        let slack = tol * (st + f * sn);
        assert!(
            xt.abs() <= limit + slack,
            "p = {p}, pair {i}: |x_t| {xt} > f·x_n {limit}"
        );
        if r.z_t != 0.0 {
            let at = -r.z_t.signum() * limit;
            assert!(
                (xt - at).abs() <= slack,
                "p = {p}, pair {i}: slip {} with x_t {xt}",
                r.z_t
            );
        }
    }
    terms
}

/// The analysis of the whole-process benchmark's beam on `m` frictional elastic bearings
/// (`unilateral_oracle::fixtures::bearings::beam_model`), read from its model file.
pub fn bearing_beam(m: usize) -> Analysis {
    bearing_beam_with(m, |_| {})
}

/// [`bearing_beam`] traced to the target `p` only (the model file's path goes to its end).
pub fn bearing_beam_to(m: usize, p: f64) -> Analysis {
    bearing_beam_with(m, |s| {
        s.target = p;
        s.follow = unilateral_lcp::Follow::ToTarget;
    })
}

fn bearing_beam_with(
    m: usize,
    settings: impl FnOnce(&mut unilateral_contact::SolveSettings),
) -> Analysis {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("beam{m}.toml"));
    std::fs::write(&path, beam_model(m)).unwrap();
    let mut p = match read_problem(&path).unwrap() {
        Problem::Structural(p) => p,
        Problem::ContactZone(_) => panic!("a structural model"),
    };
    settings(&mut p.settings);
    analyze(&p.model, &p.settings).unwrap()
}
