//! Cattaneo–Mindlin and Mindlin–Deresiewicz on a finite-element mesh: two identical elastic
//! blocks standing for two identical cylinders (plane strain), pressed together, sheared,
//! partly unsheared and sheared again, followed exactly by `follow_history` with incremental
//! friction.
//!
//! References (closed forms for two identical elastic cylinders of radius `R`, 2D, contact
//! force `P` per unit length, tangential force `Q`, friction `f`; Johnson, *Contact
//! Mechanics*, §4.2 and §7.2–7.3), with `E* = E/(2(1−ν²))` and `R* = R/2`:
//!
//! * Hertz: half-width `a² = 4·P·R*/(π·E*)`;
//! * Cattaneo–Mindlin, loading to `Q*`: stick zone `|x| < c`, `c/a = sqrt(1 − Q*/(f·P))`,
//!   slip in `c < |x| < a`;
//! * Mindlin–Deresiewicz, unloading from `Q*` to `Q`: stick zone `|x| < c'`,
//!   `c'/a = sqrt(1 − (Q* − Q)/(2·f·P))`, the ring `c' < |x| < a` slipping back;
//! * the unloading curve is the loading curve scaled by two about the turning point
//!   (Masing's rule, which the Mindlin–Deresiewicz solution obeys): `d* − d(Q) =
//!   2·d_load((Q* − Q)/2)`;
//! * reloading to `Q*` restores the state of the first loading: the loop closes;
//! * the traction profiles: Hertz's pressure, Cattaneo–Mindlin's shear at `Q*` and
//!   Mindlin–Deresiewicz's after unloading (formulas where they are checked).
//!
//! Masing's rule holds exactly for the discrete model too once the normal problem is
//! uncoupled: the friction limits `f·x_n` are then fixed, and the loading state minus twice the
//! loading state at `(Q* − Q)/2` satisfies the incremental law on the whole unloading branch
//! (the loading slips only grow and their zones are nested), so the measured `Q` must equal
//! the one the rule aims at to round-off.
//!
//! Identical bodies make normal and tangential contact uncoupled (Dundurs' β = 0), which the
//! closed forms assume. The mesh keeps that exactly: the upper block is the mirror image of the
//! lower one about the contact plane, and its top edge is held like the lower block's bottom
//! (both in `x` and `y`). The loads are applied through that edge as prescribed displacements
//! (support settlements): a uniform vertical approach `δ` (the constant group) and a uniform
//! horizontal displacement `d` (the variable group). The top edge thus moves as a rigid loading
//! plate that cannot rotate — the moment `Q·H` of the shear about the contact is taken by the
//! plate, not by a tilt of the contact pressure — and the structure stays symmetric under the
//! reflection `y → −y`, so that `Rnt = Rtn = 0`, the tangential link forces under `δ` and the
//! normal ones under `d` vanish to round-off (asserted below). With the normal problem
//! uncoupled, the contact force `P` does not change while the plate is moved sideways; the
//! transmitted force `Q = −Σ x_t` is measured, and the closed forms are evaluated at the
//! measured `P`, `Q*`, `Q`. (Displacement control and force control through a rigid plate
//! follow the same states: the tangential force grows with `d` on every branch.)
#![allow(clippy::needless_range_loop)]

use unilateral_analysis::zone_of;
use unilateral_contact::{
    follow_history, ContactLoad, ContactZone, History, HistorySolution, LoadCase, PairResult,
    PairState, Stage, StageStatus,
};
use unilateral_fem::{
    ContactPairSpec, Load, LoadGroup, Model, NodeId, PlaneAnalysis, PlaneFormulation,
    PlaneMaterial, SupportDof,
};

/// Young's modulus (MPa), Poisson's ratio, cylinder radius (mm), friction coefficient.
const E: f64 = 2.0e5;
const NU: f64 = 0.3;
const RADIUS: f64 = 100.0;
const FRICTION: f64 = 0.3;
/// The element size over the contact zone (mm): a/90 for the half-width `a ≈ 1.12 mm` that
/// the approach `DELTA` produces (the test checks `h ≤ a/12` with the measured `a`). The
/// measured zones converge as `h` shrinks (a/22: off by ≤ 0.5·h; a/45 and a/90: ≤ 0.7·h and
/// ≤ 0.4·h); a/90 is the finest that keeps the test near a second.
const H: f64 = 0.0125;
/// Pairs on each side of the centre (the paired face reaches `FINE·H = 1.4 mm ≈ 1.25·a`).
const FINE: usize = 112;
/// Half-width and depth of each block (mm): about 18 contact half-widths each. Doubling both
/// (at the same approach, hence a smaller `P` and `a`) moves every measured zone by less than
/// one element of a/22 against its closed form at the new `P`: the blocks stand for half-spaces.
const HALF_WIDTH: f64 = 20.0;
const DEPTH: f64 = 20.0;
/// Away from the contact the cells grow by this factor up to this size (mm).
const GROWTH: f64 = 1.3;
const CAP: f64 = 2.0;
/// The vertical approach of the plates (mm, constant group) and the horizontal plate
/// displacement per unit factor (mm, variable group).
const DELTA: f64 = 0.045;
const D_UNIT: f64 = 0.02;

/// Graded coordinates from 0 to `length`: `fine` cells of size `h`, then cells growing by the
/// factor `ratio` up to the size `cap`, the last one ending at `length`.
fn graded(h: f64, fine: usize, ratio: f64, cap: f64, length: f64) -> Vec<f64> {
    let mut v: Vec<f64> = (0..=fine).map(|k| k as f64 * h).collect();
    let mut size = h;
    loop {
        size = (size * ratio).min(cap);
        let last = *v.last().unwrap();
        if last + 1.5 * size >= length {
            v.push(length);
            return v;
        }
        v.push(last + size);
    }
}

/// The two blocks with the element size `h` and `fine` pairs each side of the centre, condensed
/// to their contact zone, in units whose length is `length` mm and whose force is `force` N;
/// returns the zone and the pairs' `x` (in those units).
fn two_cylinders(h: f64, fine: usize, length: f64, force: f64) -> (ContactZone, Vec<f64>) {
    let l = |v: f64| v / length;
    let half = graded(h, fine, GROWTH, CAP, HALF_WIDTH);
    let mut xs: Vec<f64> = half.iter().skip(1).rev().map(|&x| -l(x)).collect();
    xs.extend(half.iter().map(|&x| l(x)));
    // Depth coordinates from the contact plane, fine at the contact.
    let ys: Vec<f64> = graded(h, 0, GROWTH, CAP, DEPTH)
        .into_iter()
        .map(l)
        .collect();
    let (nx, ny) = (xs.len(), ys.len());
    let mut model = Model::new();
    // Plane strain per unit thickness of 1 mm (a length too).
    let material = PlaneMaterial::new(E * length * length / force, NU).with_thickness(l(1.0));
    let mut blocks: Vec<Vec<Vec<NodeId>>> = Vec::new();
    for upper in [false, true] {
        // Rows bottom to top; the upper block is the lower one reflected (y → −y).
        let rows: Vec<f64> = if upper {
            ys.clone()
        } else {
            ys.iter().rev().map(|y| -y).collect()
        };
        let ids: Vec<Vec<NodeId>> = rows
            .iter()
            .map(|&y| xs.iter().map(|&x| model.add_node(x, y)).collect())
            .collect();
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                model.add_plane(
                    [ids[j][i], ids[j][i + 1], ids[j + 1][i + 1], ids[j + 1][i]],
                    material,
                    PlaneAnalysis::PlaneStrain,
                    PlaneFormulation::QM6,
                );
            }
        }
        blocks.push(ids);
    }
    let (lower, upper) = (&blocks[0], &blocks[1]);
    for &n in &lower[0] {
        model.fix(n);
    }
    for &n in &upper[ny - 1] {
        model.add_support(n, SupportDof::Ux);
        model.add_support(n, SupportDof::Uy);
        let settle = |dof, value| Load::Settlement {
            node: n,
            dof,
            value,
        };
        model.add_load(LoadGroup::Constant, settle(SupportDof::Uy, -l(DELTA)));
        model.add_load(LoadGroup::Variable, settle(SupportDof::Ux, l(D_UNIT)));
    }
    // Coincident node pairs on the touching faces, normal from the lower block into the
    // upper one, gap x²/(2R) from each cylinder.
    let centre = nx / 2;
    let mut px = Vec::new();
    for i in centre - fine..=centre + fine {
        let x = xs[i];
        px.push(x);
        model.add_contact_pair(
            ContactPairSpec::between(lower[ny - 1][i], upper[0][i], [0.0, 1.0])
                .friction(FRICTION)
                .gap(x * x / l(RADIUS)),
        );
    }
    let condensed = model.condense().unwrap();
    (zone_of(&condensed), px)
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, b| a.max(b.abs()))
}

/// The history: the plates pressed together, then moved sideways through the factors given.
fn run(zone: &ContactZone, shear: &[f64]) -> HistorySolution {
    let case = |name: &str, l: &ContactLoad| LoadCase {
        name: name.into(),
        load: l.clone(),
    };
    let mut stages = vec![Stage {
        name: "press".into(),
        factors: vec![Some(1.0), None],
    }];
    for (k, &d) in shear.iter().enumerate() {
        stages.push(Stage {
            name: format!("shear {}", k + 1),
            factors: vec![None, Some(d)],
        });
    }
    let history = History {
        cases: vec![
            case("constant", &zone.constant),
            case("variable", &zone.variable),
        ],
        stages,
    };
    let h = follow_history(zone, &history, &Default::default()).unwrap();
    for s in &h.stages {
        assert_eq!(
            s.status,
            StageStatus::Completed,
            "{}: {:?}",
            s.name,
            s.reason
        );
        // Reference: the stage's own equations, checked from the original data.
        assert!(s.residual.max() < 1e-9, "{}: {:?}", s.name, s.residual);
    }
    h
}

/// The transmitted tangential force `Q = −Σ x_t` (positive along the plate's motion).
fn q_of(pairs: &[PairResult]) -> f64 {
    -pairs.iter().map(|p| p.x_t).sum::<f64>()
}

/// The loading curve of a stage that only moves the plate: (plate factor, Q) at the start, at
/// every change of the working scheme and at the end (the path is linear between them, so
/// interpolating between these points is exact).
fn curve(h: &HistorySolution, stage: usize) -> Vec<(f64, f64)> {
    let s = &h.stages[stage];
    let (f0, f1) = (s.factors_start[1], s.factors_end[1]);
    let at = |t: f64| f0 + t * (f1 - f0);
    let mut points = vec![(at(0.0), 0.0)];
    points.extend(s.steps.iter().map(|st| (at(st.s), q_of(&st.pairs))));
    points.push((at(1.0), q_of(&s.pairs)));
    points
}

/// The plate factor at which a rising curve first transmits `q`.
fn factor_at(curve: &[(f64, f64)], q: f64) -> f64 {
    for w in curve.windows(2) {
        let ((d0, q0), (d1, q1)) = (w[0], w[1]);
        if q0 <= q && q <= q1 && q1 > q0 {
            return d0 + (d1 - d0) * (q - q0) / (q1 - q0);
        }
    }
    panic!("the loading stage never transmits Q = {q}");
}

/// The force a curve transmits at the plate factor `d`.
fn q_at(curve: &[(f64, f64)], d: f64) -> f64 {
    for w in curve.windows(2) {
        let ((d0, q0), (d1, q1)) = (w[0], w[1]);
        if d0 <= d && d <= d1 && d1 > d0 {
            return q0 + (q1 - q0) * (d - d0) / (d1 - d0);
        }
    }
    panic!("the loading stage never reaches the plate factor {d}");
}

/// The half-width of the zone of pairs that `inside` accepts, which must be contiguous about
/// the centre: on each side the midpoint between the outermost accepted pair and the next one
/// out, then the mean of the two sides (the sides may differ by one element).
fn half_width(px: &[f64], pairs: &[PairResult], inside: impl Fn(&PairResult) -> bool) -> f64 {
    let c = px.len() / 2;
    assert!(inside(&pairs[c]), "the centre pair is not in the zone");
    let mut sides = [0.0; 2];
    for (k, dir) in [(0, 1isize), (1, -1isize)] {
        let mut i = c as isize;
        while inside(&pairs[(i + dir) as usize]) {
            i += dir;
            assert!(
                i > 0 && i < px.len() as isize - 1,
                "the zone reaches the end of the paired face"
            );
        }
        let out = (i + dir) as usize;
        // Contiguous: nothing further out is in the zone.
        let mut j = out as isize;
        while j >= 0 && j < px.len() as isize {
            assert!(!inside(&pairs[j as usize]), "the zone is not contiguous");
            j += dir;
        }
        sides[k] = (px[i as usize].abs() + px[out].abs()) / 2.0;
    }
    (sides[0] + sides[1]) / 2.0
}

fn closed(p: &PairResult) -> bool {
    p.state != PairState::Open && p.x_n > 0.0
}

fn sticking(p: &PairResult) -> bool {
    closed(p) && p.state == PairState::Stick
}

#[test]
fn mindlin_deresiewicz_on_two_identical_blocks() {
    let (zone, px) = two_cylinders(H, FINE, 1.0, 1.0);
    // The premise of the closed forms: uncoupled normal and tangential contact (β = 0), here
    // by the mirror symmetry of the mesh and of its supports.
    let rnn = zone.rnn.norm_max();
    assert!(zone.rnt.norm_max() <= 1e-9 * rnn && zone.rtn.norm_max() <= 1e-9 * rnn);
    assert!(max_abs(&zone.constant.tangential) <= 1e-9 * max_abs(&zone.constant.normal));
    assert!(max_abs(&zone.variable.normal) <= 1e-9 * max_abs(&zone.variable.tangential));

    // The loading curve: pressed, then sheared until the whole contact slides (factor 2 is
    // well beyond; the tangential force saturates at f·P).
    let probe = run(&zone, &[2.0]);
    let press = &probe.stages[0].pairs;
    let p: f64 = press.iter().map(|q| q.x_n).sum();
    let fp = FRICTION * p;
    assert!(
        (q_of(&probe.stages[1].pairs) - fp).abs() <= 1e-9 * fp,
        "no full sliding"
    );

    // (1) Hertz: the contact half-width within one element.
    let a =
        (4.0 * p * (RADIUS / 2.0) / (std::f64::consts::PI * E / (2.0 * (1.0 - NU * NU)))).sqrt();
    let a_fe = half_width(&px, press, closed);
    println!(
        "Hertz: P = {p:.6e}, a = {a:.5}, measured {a_fe:.5}, h = {H} = a/{:.1}",
        a / H
    );
    assert!(
        H <= a / 12.0,
        "the mesh is too coarse for the contact: a/h = {}",
        a / H
    );
    assert!((a_fe - a).abs() <= H, "a = {a_fe}, Hertz {a}");

    // Loading to Q* = 0.8·f·P, unloading to Q = 0.1·f·P, reloading to Q* (rather than 0.6 and
    // 0.2: the ring c' < |x| < a that slips back is then 0.19·a wide, 17 elements, and
    // c = 0.45·a, c' = 0.81·a lie far apart and far from a). The factors come from the loading
    // curve: d* where it transmits Q*, and the end of the unloading branch by Masing's rule,
    // d* − 2·d_load((Q* − Q)/2).
    let (q_star_target, q_target) = (0.8 * fp, 0.1 * fp);
    let loading = curve(&probe, 1);
    let d_star = factor_at(&loading, q_star_target);
    let d_half = factor_at(&loading, (q_star_target - q_target) / 2.0);
    let d_back = d_star - 2.0 * d_half;
    let h = run(&zone, &[d_star, d_back, d_star]);
    let (loaded, unloaded, reloaded) = (&h.stages[1].pairs, &h.stages[2].pairs, &h.stages[3].pairs);

    // The normal problem is untouched by the shear: every x_n stays as pressed (β = 0).
    let xn_scale = max_abs(&press.iter().map(|q| q.x_n).collect::<Vec<_>>());
    for s in &h.stages {
        for (i, q) in s.pairs.iter().enumerate() {
            assert!(
                (q.x_n - press[i].x_n).abs() <= 1e-9 * xn_scale,
                "{}: {}",
                s.name,
                q.name
            );
        }
    }

    // (2) Cattaneo–Mindlin at Q*: the stick zone within one element of c; the rest of the
    // contact slips, all in one direction.
    let q_star = q_of(loaded);
    assert!((q_star - q_star_target).abs() <= 1e-9 * fp);
    let c = a * (1.0 - q_star / fp).sqrt();
    let c_fe = half_width(&px, loaded, sticking);
    println!(
        "Cattaneo–Mindlin: Q*/fP = {:.6}, c = {c:.5}, measured {c_fe:.5}",
        q_star / fp
    );
    assert!((c_fe - c).abs() <= H, "c = {c_fe}, closed form {c}");
    let forward: Vec<PairState> = loaded
        .iter()
        .filter(|q| closed(q) && q.state != PairState::Stick)
        .map(|q| q.state)
        .collect();
    assert!(!forward.is_empty());
    let forward = forward[0];
    assert!(loaded
        .iter()
        .all(|q| !closed(q) || q.state == PairState::Stick || q.state == forward));

    // (3) Mindlin–Deresiewicz after unloading to Q: the stick zone within one element of c';
    // the pairs that slip are those slipping back, outside it.
    let q_back = q_of(unloaded);
    // Masing's rule: the unloading branch is the loading curve doubled about the turning point.
    println!("Masing: Q/fP = {:.12} (rule: 0.1)", q_back / fp);
    assert!(
        (q_back - q_target).abs() <= 1e-9 * fp,
        "Q = {q_back}, Masing {q_target}"
    );
    let c2 = a * (1.0 - (q_star - q_back) / (2.0 * fp)).sqrt();
    let c2_fe = half_width(&px, unloaded, sticking);
    println!(
        "Mindlin–Deresiewicz: Q/fP = {:.6}, c' = {c2:.5}, measured {c2_fe:.5}",
        q_back / fp
    );
    assert!((c2_fe - c2).abs() <= H, "c' = {c2_fe}, closed form {c2}");
    let backward = if forward == PairState::SlipPlus {
        PairState::SlipMinus
    } else {
        PairState::SlipPlus
    };
    let mut back = 0;
    for (i, q) in unloaded.iter().enumerate() {
        if closed(q) && q.state != PairState::Stick {
            assert_eq!(
                q.state, backward,
                "{} slips forward while unloading",
                q.name
            );
            assert!(
                px[i].abs() > c2_fe,
                "{} slips back inside the stick zone",
                q.name
            );
            back += 1;
        }
    }
    assert!(back >= 4, "only {back} pairs slip back");
    // The loop is open at Q: the unloading branch transmits less than the loading curve at the
    // same plate displacement (Q_load(d_back) is read off the loading curve; a friction law
    // tying the total slip to the total force, as the paper's, would retrace it: width 0).
    let q_load_at_back = q_at(&loading, d_back);
    println!("loop width at d: {:.4} f·P", (q_load_at_back - q_back) / fp);
    assert!(q_load_at_back - q_back > 0.01 * fp);

    // The traction profiles: the pressure against Hertz, `p(x) = p0·sqrt(1 − x²/a²)` with
    // `p0 = 2P/(πa)`; the shear at Q* against Cattaneo–Mindlin, `q(x) = f·p(x) − f·p0·(c/a)·
    // sqrt(1 − x²/c²)` (the second term inside the stick zone only); after unloading against
    // Mindlin–Deresiewicz, `q(x) − 2·(f·p(x) − f·p0·(c'/a)·sqrt(1 − x²/c'²))`. A pair carries
    // the traction over its element: `x_n/h`, `−x_t/h`. Next to a square-root edge a nodal value is off by
    // the order of `p0·sqrt(h/a)` (0.106·p0 here); half of that is required of the pressure
    // and of the shear at Q* (measured: 0.024·p0 and 0.024·f·p0, both at the contact edge),
    // all of it of the shear after unloading, which carries the doubled correction with its
    // edge at c' (measured 0.061·f·p0).
    let p0 = 2.0 * p / (std::f64::consts::PI * a);
    let root = |x: f64, r: f64| (1.0 - (x / r).powi(2)).max(0.0).sqrt();
    let hertz = |x: f64| p0 * root(x, a);
    let shear_at = |x: f64, c: f64| FRICTION * (hertz(x) - p0 * (c / a) * root(x, c));
    let edge = (H / a).sqrt();
    let profile = |values: &dyn Fn(usize) -> f64, closed: &dyn Fn(f64) -> f64| {
        px.iter().enumerate().fold(0.0f64, |e, (i, &x)| {
            e.max((values(i) / H - closed(x)).abs())
        })
    };
    let e_n = profile(&|i| press[i].x_n, &hertz) / p0;
    let e_t = profile(&|i| -loaded[i].x_t, &|x| shear_at(x, c)) / (FRICTION * p0);
    let e_u = profile(&|i| -unloaded[i].x_t, &|x| {
        shear_at(x, c) - 2.0 * shear_at(x, c2)
    }) / (FRICTION * p0);
    println!(
        "profiles: pressure {e_n:.4}·p0, shear at Q* {e_t:.4}·f·p0, at Q {e_u:.4}·f·p0 \
         (edge order sqrt(h/a) = {edge:.4})"
    );
    assert!(e_n <= edge / 2.0, "pressure off Hertz by {e_n}·p0");
    assert!(
        e_t <= edge / 2.0,
        "shear off Cattaneo–Mindlin by {e_t}·f·p0"
    );
    assert!(e_u <= edge, "shear off Mindlin–Deresiewicz by {e_u}·f·p0");

    // (4) Reloading to the same plate displacement closes the loop: the same force and the
    // same slip at every pair as at the end of the first loading.
    let q_again = q_of(reloaded);
    assert!(
        (q_again - q_star).abs() <= 1e-9 * q_star,
        "{q_again} vs {q_star}"
    );
    let zt_scale = max_abs(&loaded.iter().map(|q| q.z_t).collect::<Vec<_>>());
    let xt_scale = max_abs(&loaded.iter().map(|q| q.x_t).collect::<Vec<_>>());
    for (r, l) in reloaded.iter().zip(loaded) {
        assert!((r.z_t - l.z_t).abs() <= 1e-9 * zt_scale, "{}", r.name);
        assert!((r.x_t - l.x_t).abs() <= 1e-9 * xt_scale, "{}", r.name);
    }
}

/// The same history in other units: every force, slip and event the same, scaled. Reference:
/// the history in N and mm (on the coarser mesh h = a/22, to keep it quick), against the same
/// model typed in kN and m and in units 10⁴ mm and 10⁻⁵ N; factors are dimensionless, so the
/// same stages apply: pressed, sheared, partly unsheared, resheared, sheared the other way.
#[test]
fn the_history_does_not_depend_on_the_units() {
    let shear = [0.3, 0.05, 0.3, -0.3];
    let (zone, _) = two_cylinders(0.05, 28, 1.0, 1.0);
    let reference = run(&zone, &shear);
    // Every stage of shear changes the working scheme: partial slip, forward or back.
    for r in &reference.stages[1..] {
        let slipping = r
            .pairs
            .iter()
            .filter(|p| matches!(p.state, PairState::SlipPlus | PairState::SlipMinus))
            .count();
        let stuck = r.pairs.iter().filter(|p| sticking(p)).count();
        assert!(
            slipping > 0 && stuck > 0,
            "{}: {slipping} slip, {stuck} stick",
            r.name
        );
    }
    for (length, force) in [(1e3, 1e3), (1e4, 1e-5)] {
        let (zone, _) = two_cylinders(0.05, 28, length, force);
        let h = run(&zone, &shear);
        assert_eq!(h.stages.len(), reference.stages.len());
        for (s, r) in h.stages.iter().zip(&reference.stages) {
            let fs = r
                .pairs
                .iter()
                .fold(0.0f64, |a, p| a.max(p.x_n.abs()).max(p.x_t.abs()));
            let zs = r
                .pairs
                .iter()
                .fold(0.0f64, |a, p| a.max(p.z_n.abs()).max(p.z_t.abs()));
            for (p, q) in s.pairs.iter().zip(&r.pairs) {
                assert_eq!(
                    p.state, q.state,
                    "{}: {} in units ({length}, {force})",
                    s.name, p.name
                );
                for (v, w, scale, unit) in [
                    (p.x_n, q.x_n, fs, force),
                    (p.x_t, q.x_t, fs, force),
                    (p.z_n, q.z_n, zs, length),
                    (p.z_t, q.z_t, zs, length),
                ] {
                    assert!(
                        (v * unit - w).abs() <= 1e-9 * scale,
                        "{}: {}",
                        s.name,
                        p.name
                    );
                }
            }
            // The changes of the working scheme strictly inside the stage: the same events at
            // the same s.
            let inside = |h: &unilateral_contact::StageSolution| -> Vec<(f64, Vec<String>)> {
                h.steps
                    .iter()
                    .filter(|st| st.s > 1e-9 && !st.events.is_empty())
                    .map(|st| {
                        (
                            st.s,
                            st.events
                                .iter()
                                .map(|e| format!("{}:{:?}", e.pair, e.kind))
                                .collect(),
                        )
                    })
                    .collect()
            };
            let (a, b) = (inside(s), inside(r));
            assert_eq!(a.len(), b.len(), "{}", s.name);
            for ((sa, ea), (sb, eb)) in a.iter().zip(&b) {
                assert_eq!(ea, eb, "{}", s.name);
                assert!((sa - sb).abs() <= 1e-9, "{}: s = {sa} vs {sb}", s.name);
            }
        }
    }
}
