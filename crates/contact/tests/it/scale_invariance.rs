//! Scale invariance: the same zone in other units gives the same answer.
//!
//! Reference: dimensional analysis. Multiplying forces by `F` and displacements by `U`
//! (stiffness by `F/U`, gaps by `U`, the tightening by `F`) maps every solution of the contact
//! LCP onto one of the rescaled problem with the same load parameter, so the outcome, the event
//! sequence (pair, kind, order), the loads of the events and the states are identical, and the
//! forces and displacements scale by `F` and `U`. The same holds for the loads, gaps and
//! tightening alone scaled by `λ` (stiffness unchanged): the answer is linear in them, so
//! `x → λx`, `z → λz`. Factors from 1e-12 to 1e12, not only powers of two.

use faer::Mat;
use proptest::prelude::*;
use unilateral_contact::{solve, ContactSolution, ContactZone, Follow, Outcome, SolveSettings};

fn rescaled(zone: &ContactZone, f: f64, u: f64) -> ContactZone {
    let k = f / u;
    let mut z = zone.clone();
    for mat in [&mut z.rnn, &mut z.rnt, &mut z.rtn, &mut z.rtt] {
        *mat = Mat::from_fn(mat.nrows(), mat.ncols(), |i, j| mat[(i, j)] * k);
    }
    for v in [
        &mut z.constant.normal,
        &mut z.constant.tangential,
        &mut z.variable.normal,
        &mut z.variable.tangential,
    ] {
        v.iter_mut().for_each(|x| *x *= f);
    }
    z.gap.iter_mut().for_each(|g| *g *= u);
    z
}

fn outcome_kind(o: &Outcome) -> (&'static str, Option<f64>) {
    match o {
        Outcome::Ray { p_from } => ("ray", Some(*p_from)),
        Outcome::Mechanism { p_limit, .. } => ("mechanism", Some(*p_limit)),
        other => (other.status(), None),
    }
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * scale
}

/// The data's own force and displacement scales (the loads and gap forces; the gaps and the
/// displacements those forces make): round-off is measured against them when the solution's
/// numbers are all zero.
fn data_scales(zone: &ContactZone) -> (f64, f64) {
    let amax = |v: &[f64]| v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let kmax = [&zone.rnn, &zone.rnt, &zone.rtn, &zone.rtt]
        .iter()
        .map(|m| {
            (0..m.nrows())
                .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)].abs()))
                .fold(0.0f64, f64::max)
        })
        .fold(0.0f64, f64::max);
    let gmax = amax(&zone.gap);
    let fmax = amax(&zone.constant.normal)
        .max(amax(&zone.constant.tangential))
        .max(amax(&zone.variable.normal))
        .max(amax(&zone.variable.tangential))
        .max(kmax * gmax);
    (fmax, gmax.max(if kmax > 0.0 { fmax / kmax } else { 0.0 }))
}

/// `b` (forces scaled by `f`, displacements by `u`) is `a` in other units; `scales` are the
/// data scales of `a`'s zone.
fn assert_same(
    a: &ContactSolution,
    b: &ContactSolution,
    f: f64,
    u: f64,
    scales: (f64, f64),
) -> Result<(), String> {
    let (ka, pa) = outcome_kind(&a.outcome);
    let (kb, pb) = outcome_kind(&b.outcome);
    if ka != kb {
        return Err(format!("outcome {ka} vs {kb}"));
    }
    if let (Some(x), Some(y)) = (pa, pb) {
        if !close(x, y, x.abs().max(1.0)) {
            return Err(format!("outcome load {x} vs {y}"));
        }
    }
    if a.steps.len() != b.steps.len() {
        return Err(format!("{} steps vs {}", a.steps.len(), b.steps.len()));
    }
    for (s, t) in a.steps.iter().zip(&b.steps) {
        // p is dimensionless: its round-off is relative to the load scale of the path, the
        // target p* = O(1) (an event at p = 0 may come out at 3e-16 in other units).
        if !close(s.p, t.p, s.p.abs().max(1.0)) {
            return Err(format!("step {}: p = {} vs {}", s.index, s.p, t.p));
        }
        let ev = |s: &unilateral_contact::LoadStep| {
            s.events
                .iter()
                .map(|e| (e.pair, e.kind, e.while_open))
                .collect::<Vec<_>>()
        };
        if ev(s) != ev(t) {
            return Err(format!("step {}: {:?} vs {:?}", s.index, ev(s), ev(t)));
        }
    }
    if a.pairs.len() != b.pairs.len() {
        return Err("one has a solution, the other not".into());
    }
    let xs = a
        .pairs
        .iter()
        .fold(scales.0, |m, r| m.max(r.x_n.abs()).max(r.x_t.abs()));
    let zs = a
        .pairs
        .iter()
        .fold(scales.1, |m, r| m.max(r.z_n.abs()).max(r.z_t.abs()));
    for (r, s) in a.pairs.iter().zip(&b.pairs) {
        if r.state != s.state {
            return Err(format!("pair {}: {} vs {}", r.name, r.state, s.state));
        }
        let ok = close(r.x_n * f, s.x_n, xs * f)
            && close(r.x_t * f, s.x_t, xs * f)
            && close(r.z_n * u, s.z_n, zs * u)
            && close(r.z_t * u, s.z_t, zs * u);
        if !ok {
            return Err(format!(
                "pair {}: {r:?} vs {s:?} (F = {f}, U = {u})",
                r.name
            ));
        }
    }
    Ok(())
}

fn check(zone: &ContactZone, settings: &SolveSettings, f: f64, u: f64) -> Result<(), String> {
    let a = solve(zone, settings).map_err(|e| e.to_string())?;
    let scaled = SolveSettings {
        tightening: settings.tightening * f,
        ..settings.clone()
    };
    let b = solve(&rescaled(zone, f, u), &scaled).map_err(|e| e.to_string())?;
    assert_same(&a, &b, f, u, data_scales(zone))
}

/// The paper's Example 1 in contact-zone form (examples/example1-contact-zone.toml).
fn example1() -> (ContactZone, SolveSettings) {
    (
        crate::common::example1_zone(),
        crate::common::example1_paper_settings(),
    )
}

const FACTORS: [f64; 9] = [1e-12, 3.3e-9, 1e-6, 0.001, 0.7, 1.0, 9.81, 1e6, 1e12];

#[test]
fn example1_in_every_unit_system() {
    let (zone, settings) = example1();
    for f in FACTORS {
        for u in FACTORS {
            check(&zone, &settings, f, u).unwrap_or_else(|e| panic!("F = {f}, U = {u}: {e}"));
        }
        // Loads and tightening alone.
        let mut loads = rescaled(&zone, f, 1.0);
        loads.rnn = zone.rnn.clone();
        loads.rtt = zone.rtt.clone();
        let a = solve(&zone, &settings).unwrap();
        let b = solve(
            &loads,
            &SolveSettings {
                tightening: f,
                ..settings.clone()
            },
        )
        .unwrap();
        assert_same(&a, &b, f, f, data_scales(&zone))
            .unwrap_or_else(|e| panic!("loads × {f}: {e}"));
    }
}

fn log_factor() -> impl Strategy<Value = f64> {
    (-12.0f64..12.0).prop_map(|e| 10f64.powf(e))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Random zones with coupling, gaps, friction per pair, constant and variable loads and
    /// sometimes a tightening.
    #[test]
    fn random_zones_in_every_unit_system(
        m in 1usize..=3,
        b in prop::collection::vec(-2i32..=2, 36),
        friction in prop::collection::vec(0u8..=12, 3),
        gaps in prop::collection::vec(0u8..=4, 3),
        loads in prop::collection::vec(-8i32..=8, 12),
        c in prop::sample::select(vec![0.0, 0.0, 0.05, 0.5, 1.0]),
        f in log_factor(),
        u in log_factor(),
    ) {
        // Positive definite: with a singular R the solution is not unique (an open pair free
        // to slide), and which of the solutions a path reaches may rightly change with one
        // rounding; the determinate slider of `units_and_hostile` covers singular R.
        let zone = crate::common::definite_zone(
            m,
            |i, j| b[i * 6 + j] as f64 / 4.0,
            friction[..m].iter().map(|&v| v as f64 / 8.0).collect(),
            gaps[..m].iter().map(|&v| v as f64 / 16.0).collect(),
            |kind, i| loads[3 * kind + i] as f64 / 4.0,
        );
        let settings = SolveSettings {
            tightening: c,
            target: 2.0,
            follow: Follow::ToEnd,
            ..SolveSettings::default()
        };
        if let Err(e) = check(&zone, &settings, f, u) {
            prop_assert!(false, "F = {}, U = {}: {}\n{:?}", f, u, e, zone);
        }
        // Loads, gaps and tightening alone scaled by f.
        let mut lin = rescaled(&zone, f, f);
        lin.rnn = zone.rnn.clone();
        lin.rnt = zone.rnt.clone();
        lin.rtn = zone.rtn.clone();
        lin.rtt = zone.rtt.clone();
        let a = solve(&zone, &settings).unwrap();
        let bsol = solve(&lin, &SolveSettings { tightening: c * f, ..settings.clone() }).unwrap();
        if let Err(e) = assert_same(&a, &bsol, f, f, data_scales(&zone)) {
            prop_assert!(false, "loads × {}: {}\n{:?}", f, e, zone);
        }
    }
}
