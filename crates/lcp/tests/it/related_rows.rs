//! Row relations ([`unilateral_lcp::RowRelation`]) decide the ties they create exactly.
//!
//! In the frictional `3m` LCP of formulation.md §3 the rows of a pair satisfy
//! `x_t+ + x_t- − 2f·x_n = (2·max(1, f) − 2f)·c` (the rows of `M` and `d` of the two friction
//! parts add up to `2f` times the normal row). While a pair slips (`z_t±` basic, `x_t± = 0`) its
//! rows `x_n` and `x_t∓` then reach zero together when `f ≥ 1` (the right-hand side is zero: the
//! lexicographic order decides), and `x_n` first when `f < 1`. Given the relations, the engine
//! decides these ties from them instead of from the basic values.
//!
//! Reference: the oracle's exact rational parametric Lemke method (lexicographic ties on
//! `[rhs | B⁻¹]`, the same row priority) on the same data, which are dyadic rationals so that
//! the `f64` problem is exactly the oracle's and the relations hold exactly. The cases are
//! counted in which the oracle's path opens a slipping pair (its normal row leaves while a
//! friction part is basic): the relation's rule is met there, so the test cannot pass without
//! exercising it.

use crate::common;

use common::*;
use unilateral_lcp::{follow_path, Follow, ParametricLcp, PathOptions, RowRelation, Settings};
use unilateral_oracle as oracle;
use unilateral_oracle::fixtures::random::Lcg;
use unilateral_oracle::Var as OVar;

/// The relations of a contact LCP with friction `f` (pairs `0..m`).
fn relations(f: &[f64]) -> Vec<RowRelation> {
    let m = f.len();
    (0..m)
        .map(|i| RowRelation {
            terms: vec![(m + i, 1.0), (2 * m + i, 1.0), (i, -2.0 * f[i])],
        })
        .collect()
}

/// Steps of the exact path at which a slipping pair opens: `x_n` of a pair leaves while one of
/// its `z_t±` is basic.
fn slipping_openings(path: &oracle::Path, mp: usize) -> usize {
    let mut basic: Vec<OVar> = (0..3 * mp).map(OVar::X).collect();
    let mut count = 0;
    for s in &path.steps {
        if let OVar::X(i) = s.leaving {
            if i < mp && (basic.contains(&OVar::Z(mp + i)) || basic.contains(&OVar::Z(2 * mp + i)))
            {
                count += 1;
            }
        }
        basic.retain(|v| *v != s.leaving);
        basic.push(s.entering);
    }
    count
}

#[test]
fn ties_of_related_rows_follow_the_exact_path() {
    let mut g = Lcg::new(0x005e_ed16);
    let (mut cases, mut openings, mut equal_f) = (0, 0, 0);
    for case in 0..400 {
        let mp = g.int(2, 4) as usize;
        let psd = |g: &mut Lcg| {
            let k = g.int(1, mp as i64) as usize;
            let a: Vec<Vec<f64>> = (0..k)
                .map(|_| (0..mp).map(|_| g.int(-2, 2) as f64 * 0.5).collect())
                .collect();
            psd_plus_skew(&a, &vec![vec![0.0; mp]; mp], 0.0)
        };
        let rnn = psd(&mut g);
        let rtt = psd(&mut g);
        // f in [1/4, 3/2]: both signs of the relation's right-hand side, and zero (f ≥ 1).
        let f: Vec<f64> = (0..mp).map(|_| g.int(4, 24) as f64 / 16.0).collect();
        let rvn: Vec<f64> = (0..mp).map(|_| g.int(-16, 16) as f64 / 16.0).collect();
        let rvt: Vec<f64> = (0..mp).map(|_| g.int(-16, 16) as f64 / 16.0).collect();
        let lcp = oracle::fixtures::frictional_lcp(&rnn, &rtt, &f, &rvn, &rvt);
        let n = 3 * mp;
        let order: Vec<usize> = (mp..n).chain(0..mp).collect();
        let problem = ParametricLcp {
            m: to_mat(&lcp.m),
            q0: lcp.direction.clone(),
            d: lcp.d.clone(),
        };
        let options = PathOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            tightening: None,
        };
        let settings = Settings {
            lexicographic_order: Some(order.clone()),
            row_relations: relations(&f),
            ..Settings::default()
        };
        let path = follow_path(&problem, &options, &settings).unwrap();
        let exact = oracle::parametric_path(&lcp.m, &lcp.direction, &lcp.d, None, Some(&order));
        if let Err(diff) = same_events(&path, &exact) {
            panic!(
                "case {case}: events differ\n  {diff}\n  M = {:?}\n  d = {:?}",
                lcp.m, lcp.d
            );
        }
        let k = slipping_openings(&exact, mp);
        openings += k;
        if k > 0 && f.iter().any(|&v| v >= 1.0) {
            equal_f += 1;
        }
        cases += 1;
    }
    assert_eq!(cases, 400);
    assert!(
        openings >= 20 && equal_f >= 5,
        "the cases must open slipping pairs: {openings} openings, {equal_f} with f ≥ 1"
    );
}
