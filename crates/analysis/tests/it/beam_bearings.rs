//! The whole-process benchmark's long-path model (`crates/cli/benches/whole_process.rs`, case
//! `beam`: a continuous beam on frictional elastic bearings) at m = 5, read from its file
//! text, against an independent computation: the bonded structure written out by hand (the
//! textbook stiffness of Euler–Bernoulli frames, bars and springs, the consistent loads of a
//! uniform and a linearly varying distributed load) and solved exactly in rationals with the
//! oracle (`unilateral_oracle::solve`), with the links as Lagrange multipliers — no
//! condensation, no sparse factorization, nothing of the code under test. From that contact
//! zone: the condensed matrices and load vectors, the first event in closed form, and the
//! contact conditions (formulation.md §1–§3) at every breakpoint of the traced path.

use unilateral_analysis::analyze;
use unilateral_io::{read_problem, Problem};
use unilateral_oracle::fixtures::bearings::beam_model;
use unilateral_oracle::{rat, solve, to_f64, Rat};

/// Five bearings: the path has a slip, a lift-off and a slip again before its ray.
const M: usize = 5;
const EA: f64 = 3.0e10 * 0.5;
const EI: f64 = 3.0e10 * 0.04;
const EA_TIE: f64 = 2.0e11 * 1.0e-7;
const K_V: f64 = 1.0e9;
const K_H: f64 = 2.0e6;
const FRICTION: f64 = 0.3;

/// The independent contact zone: `R` (2m × 2m, normal links first) and the bonded link forces
/// `R_c`, `R_v` (normal entries, then tangential).
struct HandZone {
    r: Vec<Vec<f64>>,
    rc: Vec<f64>,
    rv: Vec<f64>,
}

/// DOFs: beam node `i` (at x = i) has u, v, θ at `3i..3i+3`; sole `i` has its ux, uy at
/// `3m + 2i`. Pair `i` joins sole `i` (A) and beam node `i` (B), `n = (0, 1)`, `t = (1, 0)`:
/// `z_n = v_i − uy_i`, `z_t = u_i − ux_i` (docs/fem.md), and with `K u = f + Cᵀ x`,
/// `C u = z` the bordered system `[[K, −Cᵀ], [C, 0]]·[u; x] = [f; z]` gives `x = R z + R_F`
/// exactly (formulation.md §2).
fn hand_zone() -> HandZone {
    let nb = 3 * M;
    let n = nb + 2 * M;
    let mut k = vec![vec![0.0f64; n]; n];
    let mut add = |dofs: &[usize], ke: &[Vec<f64>]| {
        for (a, &da) in dofs.iter().enumerate() {
            for (b, &db) in dofs.iter().enumerate() {
                k[da][db] += ke[a][b];
            }
        }
    };
    let h = 1.0; // spans of 1 m
    for e in 0..M - 1 {
        let (i, j) = (e, e + 1);
        // axial EA/h·[[1, −1], [−1, 1]] on u
        let ka = EA / h;
        add(&[3 * i, 3 * j], &[vec![ka, -ka], vec![-ka, ka]]);
        // bending on (v_i, θ_i, v_j, θ_j): EI/h³·[[12, 6h, −12, 6h], …]
        let c = EI / (h * h * h);
        let kb = [
            [12.0, 6.0 * h, -12.0, 6.0 * h],
            [6.0 * h, 4.0 * h * h, -6.0 * h, 2.0 * h * h],
            [-12.0, -6.0 * h, 12.0, -6.0 * h],
            [6.0 * h, 2.0 * h * h, -6.0 * h, 4.0 * h * h],
        ];
        let kb: Vec<Vec<f64>> = kb
            .iter()
            .map(|r| r.iter().map(|v| c * v).collect())
            .collect();
        add(&[3 * i + 1, 3 * i + 2, 3 * j + 1, 3 * j + 2], &kb);
        // the soles' tie bar on their ux
        let kt = EA_TIE / h;
        add(&[nb + 2 * i, nb + 2 * j], &[vec![kt, -kt], vec![-kt, kt]]);
    }
    for i in 0..M {
        k[nb + 2 * i][nb + 2 * i] += K_H;
        k[nb + 2 * i + 1][nb + 2 * i + 1] += K_V;
    }
    // link rows: normal links first, then tangential
    let mut c = vec![vec![0.0f64; n]; 2 * M];
    for i in 0..M {
        c[i][3 * i + 1] = 1.0;
        c[i][nb + 2 * i + 1] = -1.0;
        c[M + i][3 * i] = 1.0;
        c[M + i][nb + 2 * i] = -1.0;
    }
    // consistent loads (equivalent nodal forces of a load varying linearly from a to b over an
    // element of length h: transverse L(7a+3b)/20, L²(3a+2b)/60, L(3a+7b)/20, −L²(2a+3b)/60;
    // axial L(2a+b)/6, L(a+2b)/6)
    let consistent = |qx: &dyn Fn(f64) -> f64, qy: &dyn Fn(f64) -> f64| {
        let mut f = vec![0.0f64; n];
        for e in 0..M - 1 {
            let (x0, x1) = (e as f64, e as f64 + h);
            let (i, j) = (e, e + 1);
            let (a, b) = (qy(x0), qy(x1));
            f[3 * i + 1] += h * (7.0 * a + 3.0 * b) / 20.0;
            f[3 * i + 2] += h * h * (3.0 * a + 2.0 * b) / 60.0;
            f[3 * j + 1] += h * (3.0 * a + 7.0 * b) / 20.0;
            f[3 * j + 2] -= h * h * (2.0 * a + 3.0 * b) / 60.0;
            let (a, b) = (qx(x0), qx(x1));
            f[3 * i] += h * (2.0 * a + b) / 6.0;
            f[3 * j] += h * (a + 2.0 * b) / 6.0;
        }
        f
    };
    let len = (M - 1) as f64;
    let f_c = consistent(&|_| 0.0, &|_| -1.0e4);
    let f_v = consistent(&|_| 1.0e3, &|x| -4.0e4 + (1.0e4 + 4.0e4) * x / len);

    // the bordered system, exactly
    let nn = n + 2 * M;
    let mut a = vec![vec![rat(0.0); nn]; nn];
    for r in 0..n {
        for s in 0..n {
            a[r][s] = rat(k[r][s]);
        }
    }
    for l in 0..2 * M {
        for s in 0..n {
            a[n + l][s] = rat(c[l][s]);
            a[s][n + l] = -rat(c[l][s]);
        }
    }
    let link_forces = |rhs: Vec<Rat>| -> Vec<f64> {
        let y = solve(&a, &rhs).expect("the bonded structure is stable");
        y[n..].iter().map(to_f64).collect()
    };
    let mut r = vec![vec![0.0; 2 * M]; 2 * M];
    for j in 0..2 * M {
        let mut rhs = vec![rat(0.0); nn];
        rhs[n + j] = rat(1.0);
        let col = link_forces(rhs);
        for i in 0..2 * M {
            r[i][j] = col[i];
        }
    }
    let load = |f: &[f64]| {
        let mut rhs: Vec<Rat> = f.iter().map(|&v| rat(v)).collect();
        rhs.extend((0..2 * M).map(|_| rat(0.0)));
        link_forces(rhs)
    };
    HandZone {
        r,
        rc: load(&f_c),
        rv: load(&f_v),
    }
}

fn analysis() -> unilateral_analysis::Analysis {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("beam5.toml");
    std::fs::write(&path, beam_model(M)).unwrap();
    let p = match read_problem(&path).unwrap() {
        Problem::Structural(p) => p,
        Problem::ContactZone(_) => panic!("a structural model"),
    };
    assert_eq!(p.model.names().pairs.len(), M);
    analyze(&p.model, &p.settings).unwrap()
}

/// The condensed matrices and load vectors are those of the bonded structure solved by hand:
/// every entry to 1e-9 of the largest entry of its block (the round-off of a sparse
/// factorization of a structure whose stiffnesses span 2e4 … 1.4e10 stays far below that).
#[test]
fn the_condensed_zone_is_the_hand_zone() {
    let a = analysis();
    let c = &a.condensed;
    let z = &a.zone;
    let hz = hand_zone();
    let blocks = [
        (&z.rnn, 0, 0, "Rnn"),
        (&z.rnt, 0, M, "Rnt"),
        (&z.rtn, M, 0, "Rtn"),
        (&z.rtt, M, M, "Rtt"),
    ];
    // scale of each block: its largest entry; the coupling blocks (zero for a straight beam:
    // axial and bending decoupled) against the geometric mean of the two diagonal blocks
    let big = |r0: usize, c0: usize| {
        (0..M)
            .flat_map(|i| (0..M).map(move |j| (i, j)))
            .fold(0.0f64, |s, (i, j)| s.max(hz.r[r0 + i][c0 + j].abs()))
    };
    let (snn, stt) = (big(0, 0), big(M, M));
    assert!(snn > 0.0 && stt > 0.0);
    for (blk, r0, c0, name) in blocks {
        let scale = if r0 == c0 {
            big(r0, c0)
        } else {
            (snn * stt).sqrt()
        };
        for i in 0..M {
            for j in 0..M {
                let (got, want) = (blk[(i, j)], hz.r[r0 + i][c0 + j]);
                assert!(
                    (got - want).abs() <= 1e-9 * scale,
                    "{name}[{i}][{j}]: {got} vs hand {want}"
                );
            }
        }
    }
    for (clv, hand, name) in [(&c.constant, &hz.rc, "R_c"), (&c.variable, &hz.rv, "R_v")] {
        let scale = hand.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        assert!(scale > 0.0);
        let got: Vec<f64> = clv.normal.iter().chain(&clv.tangential).copied().collect();
        for (k, (g, w)) in got.iter().zip(hand).enumerate() {
            assert!(
                (g - w).abs() <= 1e-9 * scale,
                "{name}[{k}]: {g} vs hand {w}"
            );
        }
    }
    // statics of the hand zone: the bonded normal reactions carry the whole weight, 1e4 N/m
    // over the length, and the variable vertical load's resultant, (−4e4 + 1e4)/2 N/m over
    // the length, downwards
    let len = (M - 1) as f64;
    let sum = |v: &[f64]| v[..M].iter().sum::<f64>();
    assert!((sum(&hz.rc) - 1.0e4 * len).abs() <= 1e-12 * 1.0e4 * len);
    assert!((sum(&hz.rv) - 1.5e4 * len).abs() <= 1e-12 * 1.5e4 * len);
    // and the tangential ones the sideways 1e3 N/m, against the push (x_t acts on the beam
    // along +t: the bearings hold the beam back)
    assert!((hz.rv[M..].iter().sum::<f64>() + 1.0e3 * len).abs() <= 1e-12 * 1.0e3 * len);
}

/// The first event of the path is where the first bonded pair reaches a limit in closed form:
/// with the hand zone's `x(p) = R_c + p·R_v` (bonded), the smallest `p > 0` at which a pair's
/// `x_n` vanishes or `|x_t|` reaches `f·x_n`. And at every breakpoint the pairs satisfy the
/// contact conditions in the hand zone: `x = R_c + p·R_v + R·z`, `x_n ≥ 0`, `z_n ≥ 0`,
/// `x_n·z_n = 0`, `|x_t| ≤ f·x_n`, a slip against its friction force at the limit; and so on
/// the ray beyond the last breakpoint (at 1.5 times its load).
#[test]
fn the_path_satisfies_the_contact_conditions_of_the_hand_zone() {
    let a = analysis();
    let hz = hand_zone();
    let sol = &a.solution;
    let steps: Vec<_> = sol.steps.iter().filter(|s| !s.settling).collect();
    assert!(
        steps.len() >= 3,
        "a path with events: {} steps",
        steps.len()
    );

    // closed-form first event
    let (rc, rv) = (&hz.rc, &hz.rv);
    let mut first = f64::INFINITY;
    for i in 0..M {
        let (n0, n1, t0, t1) = (rc[i], rv[i], rc[M + i], rv[M + i]);
        assert!(n0 > 0.0, "every bearing pressed by the weight at p = 0");
        // x_n = 0, x_t − f·x_n = 0, x_t + f·x_n = 0, each linear in p
        for (c0, c1) in [
            (n0, n1),
            (FRICTION * n0 - t0, FRICTION * n1 - t1),
            (FRICTION * n0 + t0, FRICTION * n1 + t1),
        ] {
            if c1 < 0.0 {
                first = first.min(-c0 / c1);
            }
        }
    }
    let p1 = steps[0].p;
    assert!(
        (p1 - first).abs() <= 1e-9 * first,
        "first event at p = {p1}, closed form {first}"
    );

    // the conditions at every breakpoint and on the final ray
    let last = steps.last().expect("steps").p;
    let loads: Vec<f64> = steps.iter().map(|s| s.p).chain([1.5 * last]).collect();
    let scale_x = rc[..M]
        .iter()
        .chain(&rv[..M])
        .fold(0.0f64, |s, v| s.max(v.abs()));
    for &p in &loads {
        let Some((pairs, _)) = sol.at(p).unwrap() else {
            panic!("no solution at p = {p}")
        };
        let sx = scale_x * p.abs().max(1.0);
        let tol = 1e-9 * sx;
        let z: Vec<f64> = pairs
            .iter()
            .map(|q| q.z_n)
            .chain(pairs.iter().map(|q| q.z_t))
            .collect();
        let sz = z.iter().fold(0.0f64, |s, v| s.max(v.abs())).max(sx / K_V);
        for (i, q) in pairs.iter().enumerate() {
            for (row, got) in [(i, q.x_n), (M + i, q.x_t)] {
                let want =
                    rc[row] + p * rv[row] + (0..2 * M).map(|j| hz.r[row][j] * z[j]).sum::<f64>();
                assert!(
                    (got - want).abs() <= tol,
                    "p = {p}, pair {i}, row {row}: {got} vs hand {want}"
                );
            }
            assert!(q.x_n >= -tol && q.z_n >= -1e-9 * sz, "p = {p}, pair {i}");
            assert!(
                q.x_n <= tol || q.z_n <= 1e-9 * sz,
                "p = {p}, pair {i}: pressed and open ({}, {})",
                q.x_n,
                q.z_n
            );
            assert!(q.x_t.abs() <= FRICTION * q.x_n + tol, "p = {p}, pair {i}");
            if q.z_t.abs() > 1e-9 * sz {
                // slip along +t: the friction force on the beam acts along −t at its limit
                let limit = -q.z_t.signum() * FRICTION * q.x_n;
                assert!(
                    (q.x_t - limit).abs() <= tol,
                    "p = {p}, pair {i}: slip {} with x_t {} (limit {limit})",
                    q.z_t,
                    q.x_t
                );
            }
        }
    }
}

/// The limit load and whether every pair slips in the `+` direction, for a beam on bearings
/// pushed sideways (its sliding mechanism), traced to `target`.
fn sliding(
    b: &unilateral_oracle::fixtures::bearings::Bearings,
    target: f64,
) -> (f64, Vec<unilateral_contact::PairState>) {
    use unilateral_contact::{Outcome, SolveSettings};
    let model = crate::bearings_model(b);
    let settings = SolveSettings {
        target,
        ..SolveSettings::default()
    };
    let a = analyze(&model, &settings).unwrap();
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!(
            "expected the sliding mechanism, got {:?}",
            a.solution.outcome
        )
    };
    assert_eq!(a.solution.pairs.len(), b.m);
    (p_limit, a.solution.pairs.iter().map(|r| r.state).collect())
}

/// Every pair slides with the beam (`+`), but those the load has lifted off their bearings.
fn all_slide(states: &[unilateral_contact::PairState], open_allowed: bool) -> bool {
    use unilateral_contact::PairState;
    states.contains(&PairState::SlipPlus)
        && states
            .iter()
            .all(|&s| s == PairState::SlipPlus || (open_allowed && s == PairState::Open))
}

/// The sliding limit of the beam by hand: friction `f` against the sideways load `H`, the
/// dead load `V_c` and the variable load's mean `V_v` (down), per unit length: `p* = f·V_c /
/// (H − f·V_v)`, with the fixture's loads (10 kN/m dead, 40 kN/m down to 10 kN/m up) scaled.
fn sliding_limit_by_hand(b: &unilateral_oracle::fixtures::bearings::Bearings) -> f64 {
    let (vc, vv, h) = (
        1e4 * b.load_scale,
        1.5e4 * b.load_scale,
        b.sideways * b.load_scale,
    );
    b.friction * vc / (h - b.friction * vv)
}

/// The 80-bearing beam on 10 kN/m sideways springs (friction 0.2): `p* = 2/7` by hand.
fn soft_80(kn_mm: bool) -> unilateral_oracle::fixtures::bearings::Bearings {
    unilateral_oracle::fixtures::bearings::Bearings {
        m: 80,
        friction: 0.2,
        springs: [1e10, 1e4],
        load_scale: 3.0,
        sideways: 1e4,
        kn_mm,
    }
}

/// The stages of a load history on a fixture beam, each `(name, case, factor)` with the case
/// by its name in the model: `constant` (the dead load) or `variable` (the push).
fn stages(
    model: &unilateral_fem::Model,
    list: &[(&str, &str, f64)],
) -> Vec<unilateral_contact::Stage> {
    list.iter()
        .map(|&(name, case, factor)| {
            let mut factors = vec![None; model.cases().len()];
            factors[model.case(case).unwrap().0] = Some(factor);
            unilateral_contact::Stage {
                name: name.into(),
                factors,
            }
        })
        .collect()
}

/// The sliding beam's three stages: its dead load, then the push to 0.2, then to 1.
const DEAD_PUSH_TO_1: [(&str, &str, f64); 3] = [
    ("dead load", "constant", 1.0),
    ("push to 0.2", "variable", 0.2),
    ("push to 1", "variable", 1.0),
];

/// A beam on 600 bearings whose variable load pushes it sideways (10 kN/m, friction 0.1, stiff
/// springs): once friction can no longer hold it, every bearing slips and the beam slides as
/// a rigid body — by hand, at `p* = f·V_c / (H − f·V_v)` = 2/17. Until round 28 the
/// condensation zeroed `R`'s far-field couplings below 8 round-offs of their terms, and the
/// path went past `p*` to p = 508 and was refused as not resolvable in double precision (a
/// reviewer's sweep); now it ends in the mechanism at 2/17 with every pair slipping.
#[test]
fn a_beam_pushed_sideways_slides_at_the_limit_load_by_hand() {
    let b = unilateral_oracle::fixtures::bearings::Bearings {
        m: 600,
        friction: 0.1,
        springs: [1e8, 1e8],
        load_scale: 1.0,
        sideways: 1e4,
        kn_mm: false,
    };
    let by_hand = sliding_limit_by_hand(&b);
    assert!((by_hand - 2.0 / 17.0).abs() < 1e-15);
    let (p_limit, states) = sliding(&b, 30.0);
    assert!(
        (p_limit - by_hand).abs() <= 1e-9 * by_hand,
        "{p_limit} against {by_hand}"
    );
    assert!(all_slide(&states, false), "{states:?}");
}

/// Beams on bearings held sideways by soft springs (1 kN/m and 10 kN/m under a beam of 1.5e10
/// N): past the sliding limit by hand `p*` the beam slides on every bearing at constant load,
/// a mechanism. On the condensed data that mechanism keeps a residual stiffness of their
/// round-off (the load's rate 1e-10 of its column), and the path ran on with slips of 1e10
/// to the target, where the answer was refused as unresolvable in double precision (exit 2; a
/// reviewer's sweep of round 28). The structure's own equations give the load no rate there
/// (1e-54 to 1e-18 of their terms), and the path ends in the mechanism at `p*` — in N and m
/// and in kN and mm alike. The 300-bearing beam's exact direction also has a variable that
/// blocks at constant load before the mechanism (one pivot taken on the structure's
/// direction). The steel block on a genuine 300 N/m spring keeps its load rate
/// (`a_slow_load_rate_still_reaches_the_target`).
#[test]
fn a_beam_on_soft_sideways_springs_slides_at_the_limit_load_by_hand() {
    use unilateral_oracle::fixtures::bearings::Bearings;
    let cases = [
        // 80 bearings, friction 0.2, 10 kN/m springs: p* = 2/7.
        soft_80(false),
        // 300 bearings, friction 0.1, 1 kN/m springs: p* = 2/17.
        Bearings {
            m: 300,
            friction: 0.1,
            springs: [1e9, 1e3],
            load_scale: 10.0,
            sideways: 1e4,
            kn_mm: false,
        },
    ];
    for b in cases {
        let by_hand = sliding_limit_by_hand(&b);
        for kn_mm in [false, true] {
            let b = Bearings { kn_mm, ..b.clone() };
            // The file's target (1) lies beyond the limit.
            let (p_limit, states) = sliding(&b, 1.0);
            assert!(
                (p_limit - by_hand).abs() <= 1e-8 * by_hand,
                "{b:?}: {p_limit} against {by_hand}"
            );
            assert!(all_slide(&states, false), "{b:?}: {states:?}");
        }
    }
}

/// A beam on 600 bearings (friction 0.5, soles on 10 kN/m sideways springs, loads × 3): by
/// hand `p* = 0.5·30000 / (30000 − 0.5·45000)` = 2. Traced to its end the path went past `p*`
/// to a false mechanism at p = 412.7 (to a target of 200: exit 2): the sliding direction's
/// load rate there was 2.7e-11 of its column, below the tolerance, its step no runaway
/// (13 times the values), and its forces' rates 3200 times the load's. A direction that
/// moves only displacements and whose load changes that much more slowly than its forces is
/// judged on the structure's equations (`LOAD_BELOW_FORCES`), and the path ends in the
/// mechanism at `p*`.
#[test]
fn a_long_beam_traced_to_its_end_slides_at_the_limit_by_hand() {
    use unilateral_contact::{Follow, Outcome, SolveSettings};
    let b = unilateral_oracle::fixtures::bearings::Bearings {
        m: 600,
        friction: 0.5,
        springs: [1e10, 1e4],
        load_scale: 3.0,
        sideways: 1e4,
        kn_mm: false,
    };
    let by_hand = sliding_limit_by_hand(&b);
    assert!((by_hand - 2.0).abs() < 1e-15);
    let settings = SolveSettings {
        follow: Follow::ToEnd,
        ..SolveSettings::default()
    };
    let a = analyze(&crate::bearings_model(&b), &settings).unwrap();
    let Outcome::Mechanism { p_limit, mode } = &a.solution.outcome else {
        panic!("{:?}", a.solution.outcome);
    };
    assert!((p_limit - by_hand).abs() <= 1e-8 * by_hand, "{p_limit}");
    // The beam slides as a rigid body: every bearing's slip rate the same (to 3e-9 of it on
    // the condensed direction), none lifting (the far end, open, by 1e-9 of it).
    let rate = mode[0].1;
    assert!(rate.abs() > 0.0);
    let odd: Vec<_> = mode
        .iter()
        .enumerate()
        .filter(|(_, m)| (m.1 - rate).abs() > 1e-8 * rate.abs() || m.0.abs() > 1e-8 * rate.abs())
        .collect();
    assert!(odd.is_empty(), "{odd:?}");
}

/// A beam on 50 bearings (friction 0.5) whose soles are held sideways by springs of 100 N/m,
/// loads × 0.3: by hand `p* = 0.5·3000 / (3000 − 0.5·4500)` = 2. Past the last bearing's slip
/// the structure moves only sideways (the forces and the load hold): on the condensed data
/// the load's rate there passed the column's tolerance, and the path went on to a ray from p
/// = 81.75 (`--trace end`) or to an answer at the target refused as unresolvable in double
/// precision (exit 2, a reviewer's sweep). Such a direction, moving only displacements, is
/// now judged on the structure's equations where its step runs away (`docs/engine.md`,
/// "Near-mechanisms"), and the path ends in the mechanism at `p*`. The data's conditioning
/// (springs 1e-8 of the beam's axial stiffness) leaves 2.5e-7 of `p*`. Every pair slides,
/// but those the load lifts off at the far end.
#[test]
fn a_beam_on_sideways_springs_a_hundred_newtons_a_metre_slides_at_the_limit_by_hand() {
    let b = unilateral_oracle::fixtures::bearings::Bearings {
        m: 50,
        friction: 0.5,
        springs: [1e10, 1e2],
        load_scale: 0.3,
        sideways: 1e4,
        kn_mm: false,
    };
    let by_hand = sliding_limit_by_hand(&b);
    assert!((by_hand - 2.0).abs() < 1e-15);
    let (p_limit, states) = sliding(&b, 200.0);
    assert!(
        (p_limit - by_hand).abs() <= 1e-6 * by_hand,
        "{p_limit} against {by_hand}"
    );
    // The variable load lifts the far end (upwards there at p* = 2): those pairs are open.
    assert!(all_slide(&states, true), "{states:?}");
}

/// The same sliding beam (80 bearings on 10 kN/m springs, `p* = 2/7` by hand) under a load
/// history — its dead load, then the push to 0.2, then to 1 — in N and m and in kN and mm:
/// the last stage ends in the mechanism where the push's factor reaches `p*`, every pair
/// slipping. On the condensed data alone the stage's load rate there is 1e-10 of its column:
/// read as zero, yet applied with the whole column, it carried the stage past its end and the
/// results were out of balance (an internal failure, exit 1). Judged on the structure's
/// equations with the stage's increment as the load, the load holds there.
#[test]
fn a_beam_on_soft_sideways_springs_slides_in_a_load_history_at_the_limit_by_hand() {
    use unilateral_analysis::analyze_history;
    use unilateral_contact::{PairState, StageStatus};
    for kn_mm in [false, true] {
        let b = soft_80(kn_mm);
        let by_hand = sliding_limit_by_hand(&b);
        assert!((by_hand - 2.0 / 7.0).abs() < 1e-15);
        let model = crate::bearings_model(&b);
        let stages = stages(&model, &DEAD_PUSH_TO_1);
        let a = analyze_history(&model, &stages, &Default::default()).unwrap();
        let st = &a.history.stages;
        assert_eq!(st.len(), 3);
        assert_eq!(st[1].status, StageStatus::Completed);
        assert_eq!(st[2].status, StageStatus::Mechanism, "{:?}", st[2].reason);
        let factor = 0.2 + st[2].s_end * 0.8;
        assert!(
            (factor - by_hand).abs() <= 1e-8 * by_hand,
            "{factor} against {by_hand}"
        );
        let states: Vec<_> = st[2].pairs.iter().map(|r| r.state).collect();
        assert!(
            states.iter().all(|&s| s == PairState::SlipPlus),
            "{states:?}"
        );
    }
}

/// Two beams of a reviewer's sweep on stiffer springs (friction 0.5: `p* = 2` by hand) whose
/// paths reach the sliding limit after 629 and 909 pivots: there the structure's exact
/// direction has rates of its forces and gaps at round-off of its data (normal forces at 1e-17
/// of the direction's terms, gaps closing at 1e-9 of the slips), which, taken as decreases,
/// blocked the slide after slips of 1e13 to 1e14; the path then wandered down to a false
/// mechanism at p = 1.12 and 1.30 (the condensed data alone: a singular basis, exit 1). With
/// those rates judged as the round-off they are, both end in the mechanism at `p*`, every
/// bearing still pressed sliding with the beam.
#[test]
fn beams_reaching_the_sliding_limit_late_on_their_paths_stop_there() {
    use unilateral_oracle::fixtures::bearings::Bearings;
    let cases = [
        Bearings {
            m: 450,
            friction: 0.5,
            springs: [1e10, 1e8],
            load_scale: 3.0,
            sideways: 1e4,
            kn_mm: false,
        },
        Bearings {
            m: 700,
            friction: 0.5,
            springs: [1e9, 1e7],
            load_scale: 10.0,
            sideways: 1e4,
            kn_mm: false,
        },
        // Judged against the far target (200) instead of the load reached, its step at the
        // limit (the load falling by 3e-4 of it) was left to the condensed data, which took
        // the path down from the limit (exit 2) while `--trace end` found the mechanism.
        Bearings {
            m: 400,
            friction: 0.5,
            springs: [1e8, 1e5],
            load_scale: 0.3,
            sideways: 1e4,
            kn_mm: true,
        },
    ];
    for b in cases {
        let by_hand = sliding_limit_by_hand(&b);
        assert!((by_hand - 2.0).abs() < 1e-14);
        let (p_limit, states) = sliding(&b, 200.0);
        assert!(
            (p_limit - by_hand).abs() <= 1e-8 * by_hand,
            "{b:?}: {p_limit} against {by_hand}"
        );
        // Their right ends lift off (the variable load pulls up there at p = 2).
        assert!(all_slide(&states, true), "{b:?}: {states:?}");
    }
}

/// The sliding beam's history on its condensed zone alone (no structure to judge on, as a
/// zone file is solved): the last stage's `s` stays within the stage. Its load rate is below
/// the column's tolerance there and was read as zero, yet the pivot applied it with the whole
/// column: the stage ran on to s = 1.53 unnoticed. A rate that carries `s` a real way now
/// counts, as on the load path, and the stage's end is met (what the zone's round-off makes of
/// the state there is another matter: its check fails, as the sliding mechanism cannot be told
/// from the zone alone).
#[test]
fn a_stage_on_the_zone_alone_does_not_run_past_its_end() {
    use unilateral_contact::{follow_history, History};
    let model = crate::bearings_model(&soft_80(true));
    let (_, zone) = unilateral_analysis::contact_zone_of(&model).unwrap();
    let history = History {
        cases: zone.cases.clone(),
        stages: stages(&model, &DEAD_PUSH_TO_1),
    };
    let h = follow_history(&zone, &history, &Default::default()).unwrap();
    for st in &h.stages {
        assert!(
            (0.0..=1.0).contains(&st.s_end),
            "stage {} ends at s = {}",
            st.stage,
            st.s_end
        );
    }
}

/// A reviewer's beam (400 bearings, friction 0.5: `p* = 2` by hand) under its dead load and
/// then a push to 200 in one stage: the stage ends in the mechanism at a push of 2. Its step at
/// the limit moves `s` by 3e-6 — a real way from the `s` reached (0.01), not from the whole
/// stage — and was left to the condensed data when judged against the stage, which took the
/// path down from the limit (exit 2).
#[test]
fn a_long_stage_past_the_sliding_limit_ends_there() {
    use unilateral_analysis::analyze_history;
    use unilateral_contact::StageStatus;
    use unilateral_oracle::fixtures::bearings::Bearings;
    let b = Bearings {
        m: 400,
        friction: 0.5,
        springs: [1e8, 1e5],
        load_scale: 0.3,
        sideways: 1e4,
        kn_mm: true,
    };
    let by_hand = sliding_limit_by_hand(&b);
    let model = crate::bearings_model(&b);
    let stages = stages(
        &model,
        &[
            ("dead", "constant", 1.0),
            ("push to 200", "variable", 200.0),
        ],
    );
    let a = analyze_history(&model, &stages, &Default::default()).unwrap();
    let st = &a.history.stages[1];
    assert_eq!(st.status, StageStatus::Mechanism, "{:?}", st.reason);
    let factor = 200.0 * st.s_end;
    assert!(
        (factor - by_hand).abs() <= 1e-8 * by_hand,
        "{factor} against {by_hand}"
    );
}

/// A simply supported beam (4 m, E = 210 GPa, I = 1e-5 m⁴) on two frictional bearings, its
/// self-weight 100 N/m constant and an upward 1000 N at midspan times `p`: each bearing
/// carries `200 − 500·p` N, so both lift off together at `p = 0.4`, where every contact force
/// is zero — a mechanism whose state is the beam resting on its bearings with no force in them,
/// the midspan moment `qL²/8 − PL/4 = −200 N·m` (an independent tester's model, found by
/// enumerating every state of its pairs). The state's forces are the cancellation of terms of
/// 200 N: judged against themselves (zero) a round-off of 3e-14 N read as a negative force, no
/// state was reported and the run failed (exit 1) in N·m, not in kN·mm. Now in both: the
/// mechanism at 0.4 with its verified state.
#[test]
fn a_beam_lifted_off_both_bearings_at_once_reports_its_state_at_the_limit() {
    for kn_mm in [false, true] {
        assert_lifted_off(kn_mm, 1000.0, 0.4);
    }
}

/// The same beam lifted by 4e15 N: a real limit at `p = 1e-13` (400 N of the variable load),
/// not round-off of the start — a reviewer's model, which a first rule for a mechanism at the
/// start (`p_lim` within 1e-12 of `p = 1`) read as `p_lim = 0` with no state.
#[test]
fn a_beam_lifted_by_a_huge_load_has_its_limit_at_a_tiny_load_not_at_zero() {
    assert_lifted_off(false, 4e15, 1e-13);
}

/// The units line and the steel section `beam` (E = 2.1e11 Pa, A = 1e-2 m², I = 1e-5 m⁴) of
/// the beams and portals below, in N·m or kN·mm; with `member`, the 4 m beam `b` along x (two
/// elements).
fn steel_beam(kn_mm: bool, member: bool) -> String {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let mut text = format!(
        "units = \"{units}\"\n\
         [[sections]]\nname = \"beam\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n",
        units = if kn_mm { "kN, mm" } else { "N, m" },
        e = 2.1e11 * f / (l * l),
        a = 1e-2 * l * l,
        i = 1e-5 * l * l * l * l,
    );
    if member {
        text += &format!(
            "[[members]]\nname = \"b\"\nstart = [0.0, 0.0]\nend = [{:e}, 0.0]\n\
             divisions = 2\nsection = \"beam\"\n",
            4.0 * l
        );
    }
    text
}

/// The beam of [`a_beam_lifted_off_both_bearings_at_once_reports_its_state_at_the_limit`] lifted
/// by `load` N at midspan: the mechanism at `p_lim` (by hand `400/load`), every force zero there.
fn assert_lifted_off(kn_mm: bool, load: f64, p_lim: f64) {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let text = format!(
        "{head}\
         [[springs]]\nnodes = \"b.start\"\ndirection = [1.0, 0.0]\nstiffness = {k:e}\n\
         [[contact]]\nname = \"brg\"\nfrom = \"ground\"\nto = [\"b.start\", \"b.end\"]\n\
         normal = [0.0, 1.0]\nfriction = 0.3\n\
         [[loads.constant.distributed]]\nelements = \"b\"\nq = [0.0, {q:e}]\n\
         [[loads.variable.nodal]]\nnodes = \"b.1\"\nfy = {p:e}\n",
        head = steel_beam(kn_mm, true),
        k = 1e6 * f / l,
        q = -100.0 * f / l,
        p = load * f,
    );
    let what = format!("kN·mm {kn_mm}, load {load}");
    let (p_limit, s) = mechanism(&text, &what);
    assert!(
        (p_limit - p_lim).abs() < 1e-12 * p_lim,
        "{what}: p_lim = {p_limit}"
    );
    assert_eq!(s.p, Some(p_limit), "{what}: {:?}", s.notes);
    assert!(s.residual.is_some(), "{what}: a verified state");
    for r in &s.pairs {
        // Forces of round-off of 200 N, no opening: the beam rests on its bearings.
        assert!(r.x_n.abs() < 1e-9 * 200.0 * f, "{what}: {r:?}");
        assert!(r.x_t.abs() < 1e-9 * 200.0 * f, "{what}: {r:?}");
        assert!(r.z_n.abs() < 1e-12 * l, "{what}: {r:?}");
    }
}

/// A beam on four bearings that nothing holds sideways, pushed sideways by the variable load
/// (`tests/data/oracle/beam-pushed-sideways-at-rest.toml`, an independent tester's model): a
/// mechanism at `p_lim = 0` exactly, its state the constant load's, which the tester's own frame
/// solver gives by enumerating every state of the pairs (547.587523, 2317.093893, 0 and
/// 474.135096 N; no state at `p = 1e-6`). Read as `p_lim = 1.8e-15`, the point there failed its
/// verification (exit 1) in N·m, not in kN·mm. The same with the variable load written 1e-3,
/// 1e-5 and 1e-7 times as large (nothing holds any of them): a frictionless pair's tangential
/// row blocked at its round-off, so the limit was read at `p = 2.7e-12` (1e-3) and `2.3e-10`
/// (1e-5), where no state exists (exit 1); and the state came from a fresh solve, not from the
/// path's own scheme at `p = 0`.
#[test]
fn a_beam_pushed_sideways_with_nothing_to_hold_it_is_a_mechanism_at_zero() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/oracle/beam-pushed-sideways-at-rest.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let (head, variable) = text
        .split_once("[[loads.variable.nodal]]")
        .expect("the fixture's variable loads");
    for factor in [1.0, 1e-3, 1e-5, 1e-7] {
        // Every force and moment of the variable load times `factor`.
        let scaled: String = variable
            .lines()
            .map(|line| match line.split_once(" = ") {
                Some((key @ ("fx" | "fy" | "m"), v)) => {
                    let v: f64 = v.parse().expect("a number");
                    format!("{key} = {:e}\n", v * factor)
                }
                _ => format!("{line}\n"),
            })
            .collect();
        let text = format!("{head}[[loads.variable.nodal]]{scaled}");
        let (p_limit, s) = mechanism(&text, &format!("{factor}"));
        assert_eq!(p_limit, 0.0, "{factor}");
        assert_eq!(s.p, Some(0.0), "{factor}: {:?}", s.notes);
        assert!(s.residual.is_some(), "{factor}: a verified state");
        assert!(
            s.notes.iter().all(|n| !n.contains("fresh solve")),
            "{factor}: the path's own scheme at p = 0: {:?}",
            s.notes
        );
        // Every step at p = 0 (within round-off of p = 1) and settling the start.
        assert!(
            s.steps.iter().all(|st| st.p.abs() < 1e-12 && st.settling),
            "{factor}: {:?}",
            s.steps
        );
        let by_hand = [547.587523, 2317.093893, 0.0, 474.135096];
        for (r, want) in s.pairs.iter().zip(by_hand) {
            assert!(
                (r.x_n - want).abs() < 1e-6 * 2317.1,
                "{factor}: {r:?} against {want}"
            );
        }
        // The third pair open by the tester's 0.875902 mm.
        assert!(
            (s.pairs[2].z_n - 0.875902e-3).abs() < 1e-9,
            "{factor}: {:?}",
            s.pairs[2]
        );
    }
}

/// Two separate beams in one model (an independent reviewer's): beam `a` on two bearings of
/// friction 0.3 under 200 N/m, pushed sideways by 1000 N at midspan (alone it slides at
/// `p = 0.3·800/1000 = 0.24`), and beam `c` on two frictionless bearings under 200 N/m, pushed
/// sideways by `push` N. Nothing holds `c` sideways: by hand a mechanism as soon as the
/// variable load is applied, `p_lim = 0`, its state the constant load's (400 N on each of the
/// four bearings, by statics). Pushed by 3e-6…1e-4 N the path "returned to zero" at `p = 0`
/// instead: once both of `c`'s pairs slip, the load's rate along the slide (1.5e-3 at 1e-4 N)
/// was round-off of terms of 5e12, and the path left on it. N·m and kN·mm.
#[test]
fn a_frictionless_beam_pushed_by_a_small_force_beside_a_frictional_one_is_a_mechanism_at_zero() {
    for kn_mm in [false, true] {
        let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        for push in [1e-2, 1e-4, 1e-5, 3e-6] {
            let mut text = steel_beam(kn_mm, false);
            for (name, y, friction, fx) in [("a", 0.0, 0.3, 1000.0), ("c", 10.0, 0.0, push)] {
                text += &format!(
                    "[[members]]\nname = \"{name}\"\nstart = [0.0, {y:e}]\nend = [{x:e}, {y:e}]\n\
                     divisions = 2\nsection = \"beam\"\n\
                     [[contact]]\nname = \"{name}L\"\nfrom = \"ground\"\nto = \"{name}.start\"\n\
                     normal = [0.0, 1.0]\nfriction = {friction}\n\
                     [[contact]]\nname = \"{name}R\"\nfrom = \"ground\"\nto = \"{name}.end\"\n\
                     normal = [0.0, 1.0]\nfriction = {friction}\n\
                     [[loads.constant.distributed]]\nelements = \"{name}\"\nq = [0.0, {q:e}]\n\
                     [[loads.variable.nodal]]\nnodes = \"{name}.1\"\nfx = {fx:e}\n",
                    y = y * l,
                    x = 4.0 * l,
                    q = -200.0 * f / l,
                    fx = fx * f,
                );
            }
            let what = format!("kN·mm {kn_mm}, push {push} N");
            let (_, s) = state_at_limit(&text, 0.0, 0.0, &what);
            for r in &s.pairs {
                assert!(
                    (r.x_n - 400.0 * f).abs() < 1e-9 * 400.0 * f,
                    "{what}: {r:?}"
                );
            }
        }
    }
}

/// A beam (4 m, on two frictionless bearings, the left one with a gap `gap` m) pushed sideways
/// and down at midspan by the variable load (1000 N each way), its self-weight `q` N/m (none
/// when 0), in N·m or kN·mm.
fn sliding_beam(kn_mm: bool, q: f64, gap: f64) -> String {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let mut text = format!(
        "{head}\
         [[contact]]\nname = \"left\"\nfrom = \"ground\"\nto = \"b.start\"\n\
         normal = [0.0, 1.0]\nfriction = 0.0\ngap = {gap:e}\n\
         [[contact]]\nname = \"right\"\nfrom = \"ground\"\nto = \"b.end\"\n\
         normal = [0.0, 1.0]\nfriction = 0.0\n\
         [[loads.variable.nodal]]\nnodes = \"b.1\"\nfx = {p:e}\nfy = {mp:e}\n",
        head = steel_beam(kn_mm, true),
        gap = gap * l,
        p = 1000.0 * f,
        mp = -1000.0 * f,
    );
    if q != 0.0 {
        text += &format!(
            "[[loads.constant.distributed]]\nelements = \"b\"\nq = [0.0, {q:e}]\n",
            q = -q * f / l
        );
    }
    text
}

/// [`sliding_beam`] analysed: its limit (it must be a mechanism) and its solution.
fn slides(kn_mm: bool, q: f64, gap: f64) -> (f64, unilateral_contact::ContactSolution) {
    let what = format!("kN·mm {kn_mm}, q = {q}, gap {gap}");
    mechanism(&sliding_beam(kn_mm, q, gap), &what)
}

/// A model file's text analysed: its limit (it must be a mechanism) and its solution.
fn mechanism(text: &str, what: &str) -> (f64, unilateral_contact::ContactSolution) {
    use unilateral_contact::Outcome;
    let p = crate::surface::read("model.toml", text).unwrap_or_else(|e| panic!("{what}: {e}"));
    let a = analyze(&p.model, &p.settings).unwrap_or_else(|e| panic!("{what}: {e}"));
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!("{what}: {:?} {:?}", a.solution.outcome, a.solution.notes);
    };
    (p_limit, a.solution)
}

/// A model file's text analysed: a mechanism at `by_hand` (within `rel` of it: exactly at a
/// limit of zero), its state reported and verified there.
fn state_at_limit(
    text: &str,
    by_hand: f64,
    rel: f64,
    what: &str,
) -> (f64, unilateral_contact::ContactSolution) {
    let (p_limit, s) = mechanism(text, what);
    assert!(
        (p_limit - by_hand).abs() <= rel * by_hand.abs(),
        "{what}: p_lim = {p_limit}, by hand {by_hand}"
    );
    assert_eq!(s.p, Some(p_limit), "{what}: {:?}", s.notes);
    assert!(s.residual.is_some(), "{what}: a verified state");
    (p_limit, s)
}

/// A mechanism at `p = 0` that reports no state, with the note (containing `why`) the summary
/// points to.
fn assert_no_state_at_start(s: &unilateral_contact::ContactSolution, why: &str, what: &str) {
    assert_eq!(s.p, None, "{what}: {:?}", s.pairs);
    assert!(
        s.notes.iter().any(|n| n.contains(why)),
        "{what}: {:?}",
        s.notes
    );
    assert!(
        s.no_state_at_start(),
        "{what}: the summary points to the note"
    );
}

/// [`sliding_beam`] with a gap of 0.1 mm: nothing holds it sideways, a mechanism at
/// `p_lim = 0` (by hand: no horizontal restraint at all). With its self-weight (100 N/m over
/// 4 m) the state at `p = 0` is the constant load's, by statics 200 N on each bearing, the gap
/// closed by a rigid rotation (no force resists it); without a constant load no pair carries a
/// force there and the beam's position is not determined: no state, and a note that says why
/// (before, no note at all; the independent tester's beams of this kind were refused, exit 2,
/// or failed, exit 1, when their round-off state was reported). N·m and kN·mm.
#[test]
fn a_beam_that_slides_from_the_start_reports_the_constant_loads_state_or_says_why_not() {
    for kn_mm in [false, true] {
        let f = if kn_mm { 1e-3 } else { 1.0 };
        let what = format!("kN·mm {kn_mm}");
        let (p_limit, s) = slides(kn_mm, 100.0, 1e-4);
        assert_eq!(p_limit, 0.0, "{what}");
        assert_eq!(s.p, Some(0.0), "{what}: {:?}", s.notes);
        assert!(s.residual.is_some(), "{what}: a verified state");
        for r in &s.pairs {
            assert!(
                (r.x_n - 200.0 * f).abs() < 1e-9 * 200.0 * f,
                "{what}: {r:?}"
            );
            assert!(r.x_t.abs() < 1e-9 * 200.0 * f, "{what}: {r:?}");
            assert!(r.z_n.abs() < 1e-9 * 1e-4 / f, "{what}: {r:?}");
        }
        let (p_limit, s) = slides(kn_mm, 0.0, 1e-4);
        assert_eq!(p_limit, 0.0, "{what}");
        assert_no_state_at_start(&s, "nothing fixes the structure's position", &what);
    }
}

/// [`sliding_beam`] under 1e-6 N of weight (2.5e-7 N/m) over a gap of 0.1 m (a reviewer's
/// model had 1e-3 N on a stiffer beam): the mechanism at `p_lim = 0` stands; its state at
/// `p = 0` (5e-7 N on each bearing by statics) is far below the forces its gap makes term by
/// term, beyond double precision: it is not reported and a note says why. A first version of
/// the report at the start had the run refused (exit 2) after answering the limit.
#[test]
fn a_mechanism_at_the_start_whose_state_cannot_be_resolved_keeps_its_limit() {
    for kn_mm in [false, true] {
        let (p_limit, s) = slides(kn_mm, 2.5e-7, 0.1);
        assert_eq!(p_limit, 0.0, "kN·mm {kn_mm}");
        let why = "cannot be resolved in double precision";
        assert_no_state_at_start(&s, why, &format!("kN·mm {kn_mm}"));
    }
}

/// A portal frame (columns `h` m tall, 4 m apart, a 4 m beam under 250 N/m: W = 1000 N) on two
/// bearings of friction `mu`, pushed sideways at the top of its left column by 200·p N; with
/// `heavy`, a second, unrelated beam on two bearings far away under 2.5e17 N/m. In N·m or kN·mm.
fn portal(kn_mm: bool, mu: f64, h: f64, heavy: bool) -> String {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let member = |name: &str, start: String, end: String| {
        format!(
            "[[members]]\nname = \"{name}\"\nstart = {start}\nend = {end}\n\
             divisions = 2\nsection = \"beam\"\n"
        )
    };
    let point = |x: f64, y: f64| format!("[{:e}, {:e}]", x * l, y * l);
    let bearing = |name: &str, node: &str| {
        format!(
            "[[contact]]\nname = \"{name}\"\nfrom = \"ground\"\nto = \"{node}\"\n\
             normal = [0.0, 1.0]\nfriction = {mu}\n"
        )
    };
    let mut text = steel_beam(kn_mm, false);
    text += &member("cl", point(0.0, 0.0), point(0.0, h));
    text += &member("cr", point(4.0, 0.0), point(4.0, h));
    text += &member("bm", "\"cl.end\"".into(), "\"cr.end\"".into());
    text += &bearing("fl", "cl.start");
    text += &bearing("fr", "cr.start");
    text += &format!(
        "[[loads.constant.distributed]]\nelements = \"bm\"\nq = [0.0, {:e}]\n\
         [[loads.variable.nodal]]\nnodes = \"cl.end\"\nfx = {:e}\n",
        -250.0 * f / l,
        200.0 * f
    );
    if heavy {
        text += &member("hv", point(20.0, 30.0), point(24.0, 30.0));
        text += &bearing("hl", "hv.start");
        text += &bearing("hr", "hv.end");
        text += &format!(
            "[[loads.constant.distributed]]\nelements = \"hv\"\nq = [0.0, {:e}]\n",
            -2.5e17 * f / l
        );
    }
    text
}

/// A reviewer's portals. Frictionless and pushed sideways: nothing holds it, `p_lim = 0`, its
/// state at `p = 0` the weight's, 500 N on each bearing by statics; its limit read as
/// `p = −1.1e-12` in N·m (a state at a negative load) and `+1.4e-12` in kN·mm. With friction
/// 0.3, 12 m tall, beside an unrelated beam under 1e18 N: it tips at `p = W·L/(2·200·h) =
/// 0.8333` (sliding only at 1.5); a first version read that limit as round-off of the start
/// (its variable load is 1e-16 of the model's largest constant load) and moved it, with the
/// tipping's breakpoints, to `p = 0`.
#[test]
fn portals_pushed_sideways_have_their_limits_at_zero_or_where_they_tip() {
    for kn_mm in [false, true] {
        let f = if kn_mm { 1e-3 } else { 1.0 };
        let what = format!("kN·mm {kn_mm}");
        let (p_limit, s) = mechanism(&portal(kn_mm, 0.0, 3.0, false), &what);
        assert_eq!(p_limit, 0.0, "{what}");
        assert_eq!(s.p, Some(0.0), "{what}: {:?}", s.notes);
        for r in &s.pairs {
            assert!(
                (r.x_n - 500.0 * f).abs() < 1e-9 * 500.0 * f,
                "{what}: {r:?}"
            );
        }
        let (p_limit, _) = mechanism(&portal(kn_mm, 0.3, 12.0, true), &what);
        let by_hand = 1000.0 * 4.0 / (2.0 * 200.0 * 12.0);
        assert!(
            (p_limit - by_hand).abs() < 1e-9 * by_hand,
            "{what}: p_lim = {p_limit}"
        );
    }
}

/// A reviewer's portal, 10 m tall with friction 0.3, tips exactly at its target: by statics
/// `p_lim = W·L/(2·200·h) = 1000·4/(2·200·10) = 1`, where the left foot's normal force is zero
/// and the right foot carries the weight W = 1000 N and the push 200 N by friction (it sticks:
/// 0.3·1000 = 300 N available). In kN·mm the condensed data put that zero at −1.3e-11 of the
/// forces, beyond their round-off allowance, and the run failed (exit 1) where N·m answered;
/// the structure's own equations (double-double) judge such a basis now. Traced to the end and
/// to the target, in both units.
#[test]
fn a_portal_tipping_exactly_at_its_target_reports_its_state_there_in_any_units() {
    for kn_mm in [false, true] {
        for trace in ["end", "target"] {
            let f = if kn_mm { 1e-3 } else { 1.0 };
            let what = format!("kN·mm {kn_mm}, trace {trace}");
            let text = portal(kn_mm, 0.3, 10.0, false)
                + &format!("[solve]\ntarget = 1.0\ntrace = \"{trace}\"\n");
            let s = if trace == "end" {
                let (p_limit, s) = mechanism(&text, &what);
                assert!((p_limit - 1.0).abs() < 1e-9, "{what}: p_lim = {p_limit}");
                s
            } else {
                // stopped at the target, where the tipping's event is not yet passed
                let p = crate::surface::read("model.toml", &text).unwrap();
                let a = analyze(&p.model, &p.settings).unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(
                    a.solution.outcome,
                    unilateral_contact::Outcome::TargetReached,
                    "{what}"
                );
                a.solution
            };
            let p = s.p.unwrap_or_else(|| panic!("{what}: {:?}", s.notes));
            assert!((p - 1.0).abs() < 1e-9, "{what}: p = {p}");
            assert!(s.residual.is_some(), "{what}: a verified state");
            let (fl, fr) = (&s.pairs[0], &s.pairs[1]);
            assert!(fl.x_n.abs() < 1e-9 * 1000.0 * f, "{what}: {fl:?}");
            assert!(fl.x_t.abs() < 1e-9 * 1000.0 * f, "{what}: {fl:?}");
            assert!(
                (fr.x_n - 1000.0 * f).abs() < 1e-9 * 1000.0 * f,
                "{what}: {fr:?}"
            );
            assert!(
                (fr.x_t.abs() - 200.0 * f).abs() < 1e-9 * 1000.0 * f,
                "{what}: {fr:?}"
            );
            assert_eq!(fr.state, unilateral_contact::PairState::Stick, "{what}");
        }
    }
}

/// The structure check's round-off allowance ([`unilateral_fem::Equilibrium::dislocation_force`]
/// against the state's force scale) is a ratio of forces: the same in N·m and kN·mm. It took
/// each link's largest coupling, a rotation's (`6EI/L²`) among them, whose product with a gap
/// is a moment — the same number in both units against forces a thousand times smaller in
/// kN·mm (a reviewer: frames' internal failures read as round-off in kN·mm only). Checked on
/// [`sliding_beam`] with its weight, its left gap taken up at `p = 0`.
#[test]
fn the_check_allows_the_same_round_off_in_any_units() {
    let ratio = |kn_mm: bool| {
        let p = crate::surface::read("slide.toml", &sliding_beam(kn_mm, 100.0, 1e-4))
            .unwrap_or_else(|e| panic!("{e}"));
        let a = analyze(&p.model, &p.settings).unwrap_or_else(|e| panic!("{e}"));
        let r = a.results.expect("the state at p = 0");
        assert!(r.equilibrium.dislocation_force > 0.0, "{:?}", r.equilibrium);
        r.equilibrium.dislocation_force / r.equilibrium.scale
    };
    let (n_m, kn_mm) = (ratio(false), ratio(true));
    assert!((n_m - kn_mm).abs() < 1e-9 * n_m, "N·m {n_m}, kN·mm {kn_mm}");
}

/// A reviewer's model (r1592), in N·m or kN·mm: a 4 m beam on four bearings (two with gaps of
/// 2.2 and 1.3 mm), pressed down at its end by 977.9·p N, and apart from it a portal (3 m tall,
/// 4 m wide, under 2.944 N/m: W = 11.778 N) on feet of friction 9.86e-12 and 8.67e-8, pushed
/// sideways at the top of its left column by 1.2838e-4·p N.
fn reviewer_r1592(kn_mm: bool, trace: &str) -> String {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let mut text = format!(
        "units = \"{units}\"\n\
         [[sections]]\nname = \"beam\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n\
         [[members]]\nname = \"a\"\nstart = [0.0, 0.0]\nend = [{x:e}, 0.0]\n\
         divisions = 6\nsection = \"beam\"\n",
        units = if kn_mm { "kN, mm" } else { "N, m" },
        e = 2.1e11 * f / (l * l),
        a = 0.005524057662598866 * l * l,
        i = 6.419722259239307e-06 * l * l * l * l,
        x = 4.0 * l,
    );
    let pair = |name: &str, node: &str, mu: f64, gap: f64| {
        format!(
            "[[contact]]\nname = \"{name}\"\nfrom = \"ground\"\nto = \"{node}\"\n\
             normal = [0.0, 1.0]\nfriction = {mu:e}\ngap = {gap:e}\n",
            gap = gap * l
        )
    };
    text += &pair("ac0", "a.0", 8.620724921883926e-05, 0.002171203444068238);
    text += &pair("ac1", "a.3", 0.0, 0.0);
    text += &pair("ac2", "a.4", 0.111, 0.0013020917035061138);
    text += &pair("ac3", "a.6", 0.0, 0.0);
    text += &format!(
        "[[loads.variable.nodal]]\nnodes = \"a.0\"\nfy = {:e}\n",
        -977.9070944290523 * f
    );
    let point = |x: f64, y: f64| format!("[{:e}, {:e}]", x * l, y * l);
    for (name, start, end) in [
        ("zl", point(0.0, 20.0), point(0.0, 23.0)),
        ("zr", point(4.0, 20.0), point(4.0, 23.0)),
        ("zb", "\"zl.end\"".into(), "\"zr.end\"".into()),
    ] {
        text += &format!(
            "[[members]]\nname = \"{name}\"\nstart = {start}\nend = {end}\n\
             divisions = 2\nsection = \"beam\"\n"
        );
    }
    text += &pair("zf0", "zl.start", 9.860738551916568e-12, 0.0);
    text += &pair("zf1", "zr.start", 8.674288675989298e-08, 0.0);
    text += &format!(
        "[[loads.constant.distributed]]\nelements = \"zb\"\nq = [0.0, {:e}]\n\
         [[loads.variable.nodal]]\nnodes = \"zl.end\"\nfx = {:e}\n\
         [solve]\ntarget = 10.0\ntrace = \"{trace}\"\n",
        -2.9444557240279603 * f / l,
        0.00012838215995687266 * f
    );
    text
}

/// [`reviewer_r1592`]: the beam finds its supports (its end's gap closes at once) and carries
/// its load to any p; the portal slides when the push reaches its feet's friction, by statics
/// `p_lim = (μ0 + μ1)·(W/2) / 1.2838e-4 = 0.0039794` (the horizontal balance there is a
/// difference of forces 1e8 times the friction: the data fix it to about 1e-5). In N·m the
/// path "returned to zero" on a load rate of round-off (the driver leaving is now judged on its
/// terms); in kN·mm it read the slide as a ray to the target p = 10 with slips of 20 km, its
/// push balanced by round-off of the stiffness, on a load rate of 9.6e-7 of the column but
/// 1.2e-12 of its terms (traced to the target, the ray "reached" it: an independent
/// reviewer). Both units, both traces: the mechanism at the same limit, its state there.
#[test]
fn a_portal_on_nearly_frictionless_feet_slides_at_its_friction_limit_in_any_units() {
    let weight = 2.9444557240279603 * 4.0;
    let by_hand =
        (9.860738551916568e-12 + 8.674288675989298e-08) * weight / 2.0 / 0.00012838215995687266;
    for (kn_mm, trace) in [
        (false, "end"),
        (true, "end"),
        (false, "target"),
        (true, "target"),
    ] {
        let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let what = format!("kN·mm {kn_mm}, trace {trace}");
        let model = reviewer_r1592(kn_mm, trace);
        let (p_limit, s) = state_at_limit(&model, by_hand, 1e-5, &what);
        let pair = |name: &str| s.pairs.iter().find(|r| r.name == name).unwrap();
        // The portal's feet carry half its weight each and slip; the larger friction force is
        // at its limit (the smaller is 1e-11 of the forces, below their round-off), and the
        // two balance the push. The beam's load goes down through its end.
        for foot in ["zf0", "zf1"] {
            let r = pair(foot);
            assert!(
                (r.x_n - weight / 2.0 * f).abs() < 1e-5 * weight * f,
                "{what}: {r:?}"
            );
            assert!(
                matches!(
                    r.state,
                    unilateral_contact::PairState::SlipPlus
                        | unilateral_contact::PairState::SlipMinus
                ),
                "{what}: {r:?}"
            );
        }
        let (f0, f1) = (pair("zf0"), pair("zf1"));
        let mu = 8.674288675989298e-08;
        assert!(
            (f1.x_t.abs() - mu * f1.x_n).abs() < 1e-6 * mu * f1.x_n,
            "{what}: {f1:?}"
        );
        let push = 0.00012838215995687266 * p_limit * f;
        assert!(
            ((f0.x_t + f1.x_t).abs() - push).abs() < 1e-5 * push,
            "{what}: {f0:?} {f1:?} against {push}"
        );
        let end = pair("ac0");
        assert!(
            (end.x_n - 977.9070944290523 * p_limit * f).abs() < 1e-6 * end.x_n,
            "{what}: {end:?}"
        );
        // The slip at the limit: millimetres at most, not kilometres.
        assert!(
            pair("zf1").z_t.abs() < 1e-3 * l,
            "{what}: {:?}",
            pair("zf1")
        );
    }
}

/// A reviewer's beam (r1606), in N·m or kN·mm: 10 m in six elements, on a frictionless bearing
/// at its left end (over a pinned pad settled by 0.81 mm, with a gap of 0.39 mm) and a bearing
/// of friction 0.26 at node 5 (x = 25/3 m); under 1.1468 N/m and 1958.6 N at node 1, and
/// pushed at node 5 by 334.1·p N and a moment of −625.4·p N·m.
fn reviewer_r1606(kn_mm: bool) -> String {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    format!(
        "units = \"{units}\"\n\
         [[sections]]\nname = \"beam\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n\
         [[members]]\nname = \"a\"\nstart = [0.0, 0.0]\nend = [{x:e}, 0.0]\n\
         divisions = 6\nsection = \"beam\"\n\
         [[nodes]]\nid = \"apad0\"\nx = 0.0\ny = 0.0\n\
         [[supports]]\nnodes = \"apad0\"\npinned = true\n\
         [[loads.constant.settlement]]\nnodes = \"apad0\"\ndof = \"uy\"\nvalue = {s:e}\n\
         [[contact]]\nname = \"ac0\"\nfrom = \"apad0\"\nto = \"a.0\"\nnormal = [0.0, 1.0]\n\
         friction = 0.0\ngap = {gap:e}\n\
         [[contact]]\nname = \"ac1\"\nfrom = \"ground\"\nto = \"a.5\"\nnormal = [0.0, 1.0]\n\
         friction = 0.26\n\
         [[loads.constant.distributed]]\nelements = \"a\"\nq = [0.0, {q:e}]\n\
         [[loads.constant.nodal]]\nnodes = \"a.1\"\nfy = {fy:e}\n\
         [[loads.variable.nodal]]\nnodes = \"a.5\"\nfx = {fx:e}\nm = {m:e}\n\
         [solve]\ntarget = 0.5\ntrace = \"end\"\n",
        units = if kn_mm { "kN, mm" } else { "N, m" },
        e = 2.1e11 * f / (l * l),
        a = 0.010771046673067755 * l * l,
        i = 5.71406520555882e-05 * l * l * l * l,
        x = 10.0 * l,
        s = -0.0008124372722360949 * l,
        gap = 0.000394288999077698 * l,
        q = -1.1467857294642185 * f / l,
        fy = -1958.6223315688162 * f,
        fx = 334.10019952314565 * f,
        m = -625.4169298590359 * f * l,
    )
}

/// [`reviewer_r1606`] slides when the friction at node 5 is used up. By statics (the bearings'
/// normal forces do not depend on the pad's settlement or gap: two supports), node 5 carries
/// `N(p) = (1958.6·L/6 + 1.1468·L²/2 + 625.4·p) / (5L/6)`, and `0.26·N(p) = 334.1·p` at
/// `p_lim = 0.329439`. The path's point there failed its check on the frictionless pair's
/// empty friction rows, where the basis's solve left 1.4e-17 N (N·m; a fresh solve answered,
/// "may belong to another branch") or a slip read as 2.6e-17 mm put 1.4e-17 kN (kN·mm; the
/// fresh solve failed too, exit 1). Both units: the path's own state at the limit.
#[test]
fn a_beam_on_a_frictionless_and_a_frictional_bearing_reports_its_state_at_the_limit() {
    let (l, mu, push) = (10.0, 0.26, 334.10019952314565);
    let n5 = |p: f64| {
        (1958.6223315688162 * l / 6.0 + 1.1467857294642185 * l * l / 2.0 + 625.4169298590359 * p)
            / (5.0 * l / 6.0)
    };
    // 0.26·N(p) = push·p, linear in p
    let by_hand = mu * n5(0.0) / (push - mu * (n5(1.0) - n5(0.0)));
    for kn_mm in [false, true] {
        let f = if kn_mm { 1e-3 } else { 1.0 };
        let what = format!("kN·mm {kn_mm}");
        let (p_limit, s) = state_at_limit(&reviewer_r1606(kn_mm), by_hand, 1e-9, &what);
        assert!(
            s.notes.iter().all(|n| !n.contains("fresh solve")),
            "{what}: the path's own state: {:?}",
            s.notes
        );
        let (a0, a1) = (&s.pairs[0], &s.pairs[1]);
        let n = n5(p_limit) * f;
        assert!((a1.x_n - n).abs() < 1e-9 * n, "{what}: {a1:?} against {n}");
        assert!((a1.x_t.abs() - mu * n).abs() < 1e-9 * n, "{what}: {a1:?}");
        // The rest of the load on the left bearing; no friction there.
        let total = (1958.6223315688162 + 1.1467857294642185 * l) * f;
        assert!(
            (a0.x_n - (total - n)).abs() < 1e-9 * total,
            "{what}: {a0:?}"
        );
        assert_eq!(a0.x_t, 0.0, "{what}: {a0:?}");
    }
}

/// [`reviewer_r1606`] beside a bar that has nothing to do with it: 1 m long, pinned at one end,
/// its other end on a bearing of friction 0.5 and held up by a vertical spring of 1e-4 N/m,
/// weighed down by `W = p_lim − 1e-6` N and lifted by `p` N. By statics the bar's bearing
/// opens at `p = W` and its end then rises by `(p − W)/k` (10 mm at the beam's limit), and the
/// beam slides at the `p_lim` of the beam alone. Before, the soft spring's row — weighted by
/// `1/√k` to compare its terms with the beam's — gave the load's round-off on the sliding
/// beam's direction (1.4e-15, where the data's own round-off moves it by 8.8e-14) a share of
/// 5e-13 of the direction's terms, judged genuine: the path turned back to `p = 0` from the
/// limit (N·m) or ran on as a ray that no point verified (kN·mm, exit 1). Both units.
#[test]
fn a_bar_lifted_off_a_soft_spring_does_not_move_the_limit_of_a_beam_beside_it() {
    let (l, mu, push) = (10.0, 0.26, 334.10019952314565);
    let n5 = |p: f64| {
        (1958.6223315688162 * l / 6.0 + 1.1467857294642185 * l * l / 2.0 + 625.4169298590359 * p)
            / (5.0 * l / 6.0)
    };
    let by_hand = mu * n5(0.0) / (push - mu * (n5(1.0) - n5(0.0)));
    let (k, w) = (1e-4, by_hand - 1e-6);
    for kn_mm in [false, true] {
        let (f, len) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let what = format!("kN·mm {kn_mm}");
        let beam = reviewer_r1606(kn_mm);
        let at = beam.find("[solve]").expect("a [solve] table");
        let bar = format!(
            "[[sections]]\nname = \"bar\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n\
             [[nodes]]\nid = \"Bp\"\nx = {x0:e}\ny = {y:e}\n\
             [[nodes]]\nid = \"Bf\"\nx = {x1:e}\ny = {y:e}\n\
             [[elements]]\nid = \"Be\"\ntype = \"bar\"\nnodes = [\"Bp\", \"Bf\"]\n\
             section = \"bar\"\n\
             [[supports]]\nnodes = \"Bp\"\npinned = true\n\
             [[springs]]\nnodes = \"Bf\"\ndirection = [0.0, 1.0]\nstiffness = {k:e}\n\
             [[contact]]\nname = \"Bc\"\nfrom = \"ground\"\nto = \"Bf\"\n\
             normal = [0.0, 1.0]\nfriction = 0.5\n\
             [[loads.constant.nodal]]\nnodes = \"Bf\"\nfy = {wy:e}\n\
             [[loads.variable.nodal]]\nnodes = \"Bf\"\nfy = {u:e}\n",
            e = 1e6 * f / (len * len),
            a = len * len,
            i = 1e-5 * len * len * len * len,
            x0 = 20.0 * len,
            x1 = 21.0 * len,
            y = -20.0 * len,
            k = k * f / len,
            wy = -w * f,
            u = f,
        );
        let text = format!("{}{bar}{}", &beam[..at], &beam[at..]);
        let (p_limit, s) = state_at_limit(&text, by_hand, 1e-9, &what);
        let a1 = &s.pairs[1];
        let n = n5(p_limit) * f;
        assert!((a1.x_n - n).abs() < 1e-9 * n, "{what}: {a1:?} against {n}");
        assert!((a1.x_t.abs() - mu * n).abs() < 1e-9 * n, "{what}: {a1:?}");
        let b = &s.pairs[2];
        assert_eq!(
            b.state,
            unilateral_contact::PairState::Open,
            "{what}: {b:?}"
        );
        let lift = (p_limit - w) / k * len;
        assert!(
            (b.z_n - lift).abs() < 1e-6 * lift,
            "{what}: {b:?} against {lift}"
        );
    }
}

/// A reviewer's beam (r1052, N·m): 4 m under 2.0411 N/m, on a frictionless bearing under its
/// middle (x = 2 m) and two at x = 0 (friction 8.3e-8, a gap of 0.076 mm) and x = 2/3 m
/// (friction 0.319), pushed along its axis at its right end by 9.47e-6·p N. By statics it rests
/// on the middle bearing alone (its weight's centre is there: 8.1646 N) and nothing holds it
/// along its axis: a mechanism as soon as the load is applied, `p_lim = 0`. The path's loads
/// never rose above zero; round-off took them to `p = −3.1e-9`, where the limit was read — a
/// mechanism at a negative load. (Its kN·mm twin rose to `1.9e-7` first and still fails at
/// `−2.4e-7`: docs/engine.md.)
#[test]
fn a_limit_read_below_zero_on_a_path_that_never_rose_is_the_start() {
    let text = "units = \"N, m\"\n\
        [[sections]]\nname = \"beam\"\nE = 2.1e11\nA = 0.07527178255464861\n\
        I = 0.000353085657918322\n\
        [[members]]\nname = \"a\"\nstart = [0.0, 0.0]\nend = [4.0, 0.0]\ndivisions = 6\n\
        section = \"beam\"\n\
        [[contact]]\nname = \"ac0\"\nfrom = \"ground\"\nto = \"a.0\"\nnormal = [0.0, 1.0]\n\
        friction = 8.307338913864644e-08\ngap = 7.64093937310475e-05\n\
        [[contact]]\nname = \"ac1\"\nfrom = \"ground\"\nto = \"a.1\"\nnormal = [0.0, 1.0]\n\
        friction = 0.319\n\
        [[contact]]\nname = \"ac2\"\nfrom = \"ground\"\nto = \"a.3\"\nnormal = [0.0, 1.0]\n\
        friction = 0.0\n\
        [[loads.constant.distributed]]\nelements = \"a\"\nq = [0.0, -2.0411449811236935]\n\
        [[loads.variable.nodal]]\nnodes = \"a.6\"\nfx = -9.466101387246699e-06\n";
    let (_, s) = state_at_limit(text, 0.0, 0.0, "r1052");
    let weight = 2.0411449811236935 * 4.0;
    let (a0, a1, a2) = (&s.pairs[0], &s.pairs[1], &s.pairs[2]);
    assert!((a2.x_n - weight).abs() < 1e-9 * weight, "{a2:?}");
    for r in [a0, a1] {
        assert!(r.x_n.abs() < 1e-9 * weight, "{r:?}");
    }
    assert!(s.steps.iter().all(|st| st.p == 0.0), "{:?}", s.steps);
}

/// Two beams that share nothing but the model file, in N·m or kN·mm: beam `a` (4 m under
/// 25 kN/m, on two bearings of friction 0.4, pushed along its axis by 100 kN·p) and, 10 m above
/// it, beam `b` (4 m under 0.5 N/m, on two frictionless bearings, pushed along its axis by
/// `push`·p N).
pub(crate) fn two_beams(push: f64, kn_mm: bool) -> String {
    let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let beam = |name: &str, y: f64, friction: f64, q: f64, fx: f64| {
        format!(
            "[[members]]\nname = \"{name}\"\nstart = [0.0, {y:e}]\nend = [{x:e}, {y:e}]\n\
             divisions = 4\nsection = \"beam\"\n\
             [[contact]]\nname = \"{name}0\"\nfrom = \"ground\"\nto = \"{name}.0\"\n\
             normal = [0.0, 1.0]\nfriction = {friction}\n\
             [[contact]]\nname = \"{name}1\"\nfrom = \"ground\"\nto = \"{name}.4\"\n\
             normal = [0.0, 1.0]\nfriction = {friction}\n\
             [[loads.constant.distributed]]\nelements = \"{name}\"\nq = [0.0, {q:e}]\n\
             [[loads.variable.nodal]]\nnodes = \"{name}.2\"\nfx = {fx:e}\n",
            x = 4.0 * l,
            y = y * l,
            q = -q * f / l,
            fx = fx * f,
        )
    };
    format!(
        "units = \"{units}\"\n\
         [[sections]]\nname = \"beam\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n{}{}\
         [solve]\ntrace = \"end\"\n",
        beam("a", 0.0, 0.4, 25000.0, 100000.0),
        beam("b", 10.0, 0.0, 0.5, push),
        units = if kn_mm { "kN, mm" } else { "N, m" },
        e = 2.1e11 * f / (l * l),
        a = 0.01 * l * l,
        i = 0.0008 * l * l * l * l,
    )
}

/// [`two_beams`] with beam `b` pushed by 1e-6 N (5e-7 of its weight, 1e-11 of the push on
/// `a`): nothing holds `b` along its axis, a mechanism as soon as the load is applied
/// (`p_lim = 0`), and at `p = 0` each bearing carries half its beam's weight by statics
/// (50 kN and 1 N), without friction. Before, the engine's columns held both beams' loads at
/// the size of `a`'s, `b`'s push was below their pivot tolerance, and the path ran to `a`'s
/// sliding at `p = 0.4` (its friction 0.4 · 100 kN against 100 kN·p): a wrong limit, reported
/// as verified (exit 0). The friction rows of `b`'s frictionless pairs, which no row of `M`
/// and no friction relation ties to anything else, carry only the push: the engine now raises
/// them until it is as large as `a`'s (`Scaling::raise_parts`). Both units; pushes of 1e-7 N
/// (1e-12 of `a`'s) and 1e-3 N (answered before too).
#[test]
fn a_frictionless_beam_pushed_beside_a_heavy_one_slides_from_the_start() {
    for kn_mm in [false, true] {
        for push in [1e-3, 1e-6, 1e-7] {
            let f = if kn_mm { 1e-3 } else { 1.0 };
            let what = format!("kN·mm {kn_mm}, push {push}");
            let (_, s) = state_at_limit(&two_beams(push, kn_mm), 0.0, 0.0, &what);
            let halves = [50000.0, 50000.0, 1.0, 1.0];
            for (pair, half) in s.pairs.iter().zip(halves) {
                let n = half * f;
                assert!(
                    (pair.x_n - n).abs() <= 1e-9 * n,
                    "{what}: {pair:?} against {n}"
                );
                assert_eq!(pair.x_t, 0.0, "{what}: {pair:?}");
            }
        }
    }
}

/// A reviewer's portal (r1186, N·m): legs 8 m high 4 m apart on feet of friction 0.511 and
/// 0.513, its beam under 3.2004 N/m, pushed at the left leg's top by (−119.99, 18.98)·p N —
/// beside a beam 20 m above it on three bearings that carries 5.3e11 N·p and 7.8e11 N·m·p,
/// under 69.3 N/m (r1186's) or 6.9e10 N/m (its constant load a billion times heavier too).
/// By statics the portal tips about its left foot when the push's moment there,
/// `119.99·p · 8`, reaches its weight's, `3.2004 · 4 · 2` (the lift acts through the foot):
/// `p_lim = 0.026672`, before it could slide (`0.0504`, where `119.99·p` meets
/// `0.51·(12.8 − 18.98·p)`). The heavy beam does not tip (its loads lie between its
/// bearings). Before, the portal's loads were below the pivot tolerance of the columns the two
/// structures share: the path went on to the portal's sliding, whose point failed its check,
/// or stopped at a singular basis (exit 1 either way). Now the portal's part of the problem is
/// raised (`Scaling::raise_parts`). At the limit the right foot carries nothing and the left
/// one the weight less the lift and the whole push. Both units.
#[test]
fn a_portal_beside_a_beam_a_billion_times_heavier_tips_at_the_load_by_hand() {
    let (q, fx, fy, h, span) = (
        3.2003877157554554,
        119.99177709586304,
        18.98167211400592,
        8.0,
        4.0,
    );
    let by_hand = q * span * (span / 2.0) / (fx * h);
    for (kn_mm, heavy) in [(false, false), (true, false), (false, true), (true, true)] {
        let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let what = format!("kN·mm {kn_mm}, heavy {heavy}");
        let zq = if heavy {
            69289075446.48867
        } else {
            69.28907544648867
        };
        let leg = |name: &str, x: f64| {
            format!(
                "[[members]]\nname = \"{name}\"\nstart = [{x:e}, 0.0]\nend = [{x:e}, {h:e}]\n\
                 divisions = 2\nsection = \"beam\"\n",
                x = x * l,
                h = h * l,
            )
        };
        let foot = |name: &str, node: &str, friction: f64| {
            format!(
                "[[contact]]\nname = \"{name}\"\nfrom = \"ground\"\nto = \"{node}\"\n\
                 normal = [0.0, 1.0]\nfriction = {friction}\n"
            )
        };
        let pad = |id: &str, x: f64, settle: f64, node: &str, name: &str, friction: f64| {
            format!(
                "[[nodes]]\nid = \"{id}\"\nx = {x:e}\ny = {y:e}\n\
                 [[supports]]\nnodes = \"{id}\"\npinned = true\n\
                 [[loads.constant.settlement]]\nnodes = \"{id}\"\ndof = \"uy\"\n\
                 value = {s:e}\n{}",
                foot(name, node, friction).replace("\"ground\"", &format!("\"{id}\"")),
                x = x * l,
                y = 20.0 * l,
                s = settle * l,
            )
        };
        let text = format!(
            "units = \"{units}\"\n\
             [[sections]]\nname = \"beam\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n\
             {}{}\
             [[members]]\nname = \"ab\"\nstart = \"al.end\"\nend = \"ar.end\"\ndivisions = 2\n\
             section = \"beam\"\n{}{}\
             [[loads.constant.distributed]]\nelements = \"ab\"\nq = [0.0, {q:e}]\n\
             [[loads.variable.nodal]]\nnodes = \"al.end\"\nfx = {fx:e}\nfy = {fy:e}\n\
             [[members]]\nname = \"z\"\nstart = [0.0, {zy:e}]\nend = [{zx:e}, {zy:e}]\n\
             divisions = 6\nsection = \"beam\"\n{}{}{}\
             [[loads.constant.distributed]]\nelements = \"z\"\nq = [0.0, {zq:e}]\n\
             [[loads.variable.nodal]]\nnodes = \"z.2\"\nfy = {zf:e}\nm = {zm:e}\n\
             [solve]\ntarget = 0.5\n",
            leg("al", 0.0),
            leg("ar", span),
            foot("af0", "al.start", 0.511),
            foot("af1", "ar.start", 0.513),
            foot("zc0", "z.0", 1.0906483041406449e-10),
            pad(
                "zpad1",
                5.0,
                -6.439771413010225e-05,
                "z.5",
                "zc1",
                4.939280362207199e-11
            ),
            pad("zpad2", 6.0, -3.039781976825294e-05, "z.6", "zc2", 0.58),
            units = if kn_mm { "kN, mm" } else { "N, m" },
            e = 2.1e11 * f / (l * l),
            a = 0.0033676743541390555 * l * l,
            i = 0.00041153332398919816 * l * l * l * l,
            q = -q * f / l,
            fx = -fx * f,
            fy = fy * f,
            zy = 20.0 * l,
            zx = 6.0 * l,
            zq = -zq * f / l,
            zf = -531683148930.02405 * f,
            zm = -775498540334.4701 * f * l,
        );
        let (p, s) = state_at_limit(&text, by_hand, 1e-9, &what);
        let (left, right) = (&s.pairs[0], &s.pairs[1]);
        let weight = q * span * f;
        let n = weight - fy * p * f;
        assert!(
            (left.x_n - n).abs() <= 1e-9 * weight,
            "{what}: {left:?} against {n}"
        );
        let t = fx * p * f;
        assert!(
            (left.x_t.abs() - t).abs() <= 1e-9 * weight,
            "{what}: {left:?} against {t}"
        );
        assert!(right.x_n.abs() <= 1e-9 * weight, "{what}: {right:?}");
        assert!(right.x_t.abs() <= 1e-9 * weight, "{what}: {right:?}");
    }
}
