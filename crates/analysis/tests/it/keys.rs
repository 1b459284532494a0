//! A test for every documented model key (docs/model-format.md) with a non-default value.
//!
//! Each model of `tests/data/models/` is read from its file (some tests change a key or two
//! first), analysed, and its structural result — the load of an event, contact forces,
//! displacements, reactions, spring forces — compared with a value computed here by hand:
//! beam theory, statics, or a small stiffness solve assembled in the test. The derivation of
//! every value is in the comments; no expected value comes from the program itself.
//!
//! Tolerances are relative to the size of the quantity compared (`close`).

use std::path::{Path, PathBuf};

use unilateral_analysis::{analyze, Analysis, Outcome, PairState};
use unilateral_contact::{EventKind, PairResult};
use unilateral_fem::{Element, SupportDof};
use unilateral_io::{read_problem, Problem, StructuralProblem};
use unilateral_oracle::fixtures::example1 as ex1;

/// Relative tolerance of the comparisons with hand values (the hand values are exact for the
/// elements used: frames are exact for nodal loads, consistent loads and temperatures; plane
/// elements are exact for the uniform states and pure bending used here).
const REL: f64 = 1e-8;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/models")
        .join(name)
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// Reads a model file, applies `edit` to its TOML document, writes it to a temporary file and
/// analyses it. A missing data file is a failure, never a skip.
fn run_edited(path: &Path, edit: impl FnOnce(&mut toml::Table)) -> (StructuralProblem, Analysis) {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("the test data file {} is missing: {e}", path.display()));
    let mut doc: toml::Table = text
        .parse()
        .unwrap_or_else(|e| panic!("{} is not TOML: {e}", path.display()));
    edit(&mut doc);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(path.file_name().unwrap());
    std::fs::write(&file, toml::to_string(&doc).unwrap()).unwrap();
    let p = match read_problem(&file) {
        Ok(Problem::Structural(p)) => p,
        Ok(Problem::ContactZone(_)) => panic!("{} is not a structural model", path.display()),
        Err(e) => panic!("{}: {e}", path.display()),
    };
    let a = analyze(&p.model, &p.settings).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (p, a)
}

/// The model of `path` (in N·m) analysed as written (`force = 1`), or rewritten in kN·mm
/// (`force = 1e-3`, lengths × 1e3: `scale.rs`'s rewriting).
fn run_in_units(path: &Path, force: f64) -> (StructuralProblem, Analysis) {
    run_edited(path, |d| {
        if force != 1.0 {
            crate::scale::rescale_units(d, force, 1e3);
        }
    })
}

fn run(name: &str) -> (StructuralProblem, Analysis) {
    run_edited(&data(name), |_| {})
}

/// The table at a dotted path of tables (`solve`, `loads.variable`), created when missing.
fn table<'a>(doc: &'a mut toml::Table, path: &str) -> &'a mut toml::Table {
    let mut t = doc;
    for part in path.split('.') {
        let v = t
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        t = match v {
            toml::Value::Table(t) => t,
            other => panic!("{path}: {part} is not a table (use `entry` for arrays): {other:?}"),
        };
    }
    t
}

/// The `i`-th entry (0-based) of the array of tables `key`.
fn entry<'a>(doc: &'a mut toml::Table, key: &str, i: usize) -> &'a mut toml::Table {
    match doc.get_mut(key) {
        Some(toml::Value::Array(a)) => match &mut a[i] {
            toml::Value::Table(t) => t,
            other => panic!("{key}[{i}] is not a table: {other:?}"),
        },
        other => panic!("{key} is not an array: {other:?}"),
    }
}

fn set(t: &mut toml::Table, key: &str, v: impl Into<toml::Value>) {
    t.insert(key.to_string(), v.into());
}

fn close(got: f64, want: f64, scale: f64, what: &str) {
    assert!(
        got.is_finite() && (got - want).abs() <= REL * scale.abs().max(want.abs()),
        "{what}: got {got}, want {want} (scale {scale})"
    );
}

fn pair<'a>(a: &'a Analysis, name: &str) -> &'a PairResult {
    a.solution
        .pairs
        .iter()
        .find(|p| p.name == name)
        .unwrap_or_else(|| panic!("no pair {name} in {:?}", a.solution.pairs))
}

fn pair_at(pairs: &[PairResult], name: &str) -> PairResult {
    pairs.iter().find(|p| p.name == name).unwrap().clone()
}

fn node(p: &StructuralProblem, name: &str) -> usize {
    p.model
        .names()
        .node_id(name)
        .unwrap_or_else(|| panic!("no node {name}"))
        .0
}

/// The displacement `[ux, uy, rz]` of a node at the reported load.
fn disp(p: &StructuralProblem, a: &Analysis, name: &str) -> [f64; 3] {
    a.results.as_ref().expect("results").displacements[node(p, name)]
}

/// The reaction of a node in a DOF at the reported load.
fn reaction(p: &StructuralProblem, a: &Analysis, name: &str, dof: SupportDof) -> f64 {
    let n = node(p, name);
    a.results
        .as_ref()
        .expect("results")
        .reactions
        .iter()
        .find(|r| r.node.0 == n && r.dof == dof)
        .unwrap_or_else(|| panic!("no reaction {dof:?} at {name}"))
        .value
}

/// A change of a model document.
type Edit = Box<dyn Fn(&mut toml::Table)>;

/// The events of the path as (load, pair, kind), leaving out the friction events of open pairs
/// (they only use up the tightening's sideways capacity: no force is transmitted).
fn events(a: &Analysis) -> Vec<(f64, String, EventKind)> {
    a.solution
        .steps
        .iter()
        .flat_map(|s| {
            s.events
                .iter()
                .filter(|e| !e.while_open)
                .map(move |e| (s.p, e.name.clone(), e.kind))
        })
        .collect()
}

/// Solves a small dense system by Gaussian elimination with partial pivoting (the independent
/// stiffness solves of the hand computations).
fn solve_dense(mut k: Vec<Vec<f64>>, mut f: Vec<f64>) -> Vec<f64> {
    let n = f.len();
    for c in 0..n {
        let r = (c..n)
            .max_by(|&i, &j| k[i][c].abs().total_cmp(&k[j][c].abs()))
            .unwrap();
        k.swap(c, r);
        f.swap(c, r);
        for i in c + 1..n {
            let m = k[i][c] / k[c][c];
            let pivot_row = k[c].clone();
            for (kij, kcj) in k[i][c..].iter_mut().zip(&pivot_row[c..]) {
                *kij -= m * kcj;
            }
            f[i] -= m * f[c];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| k[i][j] * x[j]).sum();
        x[i] = (f[i] - s) / k[i][i];
    }
    x
}

// ---------------------------------------------------------------------------------------------
// gap

/// Simply supported beam of span `l`: deflection at `x` under a unit uniform load, times EI:
/// `x (l³ − 2 l x² + x³) / 24` (beam theory).
fn ss_udl(x: f64, l: f64) -> f64 {
    x * (l.powi(3) - 2.0 * l * x * x + x.powi(3)) / 24.0
}

/// Simply supported beam of span `l`: deflection at `x` under a unit point load at `a`, times
/// EI: `b x (l² − b² − x²) / (6 l)` for `x ≤ a`, `b = l − a` (and symmetric for `x > a`).
fn ss_point(x: f64, a: f64, l: f64) -> f64 {
    let (x, a) = if x <= a { (x, a) } else { (l - x, l - a) };
    let b = l - a;
    b * x * (l * l - b * b - x * x) / (6.0 * l)
}

#[test]
fn gap_to_ground_two_gaps_close_in_turn() {
    // The beam: L = 12, EI = 2.1e7, pinned ends, pairs at x = 4 (gap 0.01) and x = 8
    // (gap 0.02), q = 1e4·p. Open pairs: w(x) = q·p·ss_udl(x)/EI; the first closure (both
    // points deflect alike by symmetry, the smaller gap first) at q p ss_udl(4)/EI = 0.01.
    // Then x = 4 is a prop settled by 0.01 with force R1 = (q p ss_udl(4) − 0.01 EI)/ss_point(4,4)
    // and x = 8 closes when (q p ss_udl(8) − R1 ss_point(8,4))/EI = 0.02.
    let (l, ei, q, g1, g2) = (12.0, 2.1e7, 1e4, 0.01, 0.02);
    let p1 = g1 * ei / (q * ss_udl(4.0, l));
    let (f11, f21) = (ss_point(4.0, 4.0, l), ss_point(8.0, 4.0, l));
    // EI w8 = q p u8 − f21 (q p u4 − g1 EI)/f11 = g2 EI, solved for p.
    let (u4, u8) = (ss_udl(4.0, l), ss_udl(8.0, l));
    let p2 = (g2 * ei - f21 / f11 * g1 * ei) / (q * (u8 - f21 / f11 * u4));
    // The hand values.
    assert!((p1 - 0.089489).abs() < 1e-6 && (p2 - 0.805398).abs() < 1e-6);

    let (p, a) = run("gap-beam.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 2, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("g4", EventKind::Closes));
    assert_eq!((ev[1].1.as_str(), ev[1].2), ("g8", EventKind::Closes));
    close(ev[0].0, p1, 1.0, "first closure");
    close(ev[1].0, p2, 1.0, "second closure");
    assert_eq!(a.solution.outcome, Outcome::TargetReached);

    // At p = 1 both are props settled by their gaps: flexibility [[f11, f12], [f21, f22]]·R =
    // q·[u4, u8] − EI·[g1, g2].
    let f = vec![
        vec![f11, ss_point(4.0, 8.0, l)],
        vec![f21, ss_point(8.0, 8.0, l)],
    ];
    let r = solve_dense(f, vec![q * u4 - ei * g1, q * u8 - ei * g2]);
    close(pair(&a, "g4").x_n, r[0], q * l, "x_n at x = 4");
    close(pair(&a, "g8").x_n, r[1], q * l, "x_n at x = 8");
    close(pair(&a, "g4").z_n, 0.0, g1, "g4 closed");
    close(disp(&p, &a, "beam.4")[1], -g1, g1, "w(4) = gap");
    close(disp(&p, &a, "beam.8")[1], -g2, g2, "w(8) = gap");
    // The left support by moments about the right end: 12 R_A = 6·12 q − 8 R1 − 4 R2.
    let ra = (6.0 * l * q - 8.0 * r[0] - 4.0 * r[1]) / l;
    close(
        reaction(&p, &a, "beam.start", SupportDof::Uy),
        ra,
        q * l,
        "R_A",
    );
    for pr in &a.solution.pairs {
        close(pr.x_t, 0.0, q * l, "no friction force under vertical loads");
    }
}

#[test]
fn gap_to_ground_that_never_closes() {
    // The same beam with a 0.2 gap at x = 8: only x = 4 closes (at p1 as above); at p = 1 the
    // gap at x = 8 is what is left of 0.2 after EI w8 = q u8 − f21 R1, R1 = (q u4 − EI g1)/f11.
    let (l, ei, q, g1) = (12.0, 2.1e7, 1e4, 0.01);
    let (u4, u8) = (ss_udl(4.0, l), ss_udl(8.0, l));
    let (f11, f21) = (ss_point(4.0, 4.0, l), ss_point(8.0, 4.0, l));
    let r1 = (q * u4 - ei * g1) / f11;
    let w8 = (q * u8 - f21 * r1) / ei;

    let (p, a) = run_edited(&data("gap-beam.toml"), |d| {
        set(entry(d, "contact", 1), "gap", 0.2)
    });
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("g4", EventKind::Closes));
    close(ev[0].0, g1 * ei / (q * u4), 1.0, "closure at x = 4");
    let g8 = pair(&a, "g8");
    assert_eq!(g8.state, PairState::Open);
    close(g8.z_n, 0.2 - w8, 0.2, "the gap left at x = 8");
    close(g8.x_n, 0.0, q * l, "no force across an open gap");
    close(pair(&a, "g4").x_n, r1, q * l, "the prop force at x = 4");
    close(disp(&p, &a, "beam.8")[1], -w8, 0.2, "w(8)");
}

#[test]
fn gap_between_nodes_closes_and_never_closes() {
    // Two equal cantilevers, tip stiffness k = 3EI/L³ = 3·4e5/8 = 1.5e5, the upper tip pushed
    // down by P p = 1000 p across g = 0.005: the gap closes at p = g k/P = 0.75. Past it the
    // tips move together: P p − X = k uA, X = k uB, uA = uB + g → X = k (P p − k g)/(2k).
    let (k, pl, g) = (1.5e5, 1000.0, 0.005);
    let (p, a) = run("gap-tips.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("tips", EventKind::Closes));
    close(ev[0].0, g * k / pl, 1.0, "closure");
    let x = k * (pl - k * g) / (2.0 * k);
    close(pair(&a, "tips").x_n, x, pl, "contact force at p = 1");
    close(disp(&p, &a, "upper.end")[1], -(pl - x) / k, g, "upper tip");
    close(disp(&p, &a, "lower.end")[1], -x / k, g, "lower tip");

    // A gap of 0.05 never closes: at p = 1 it is 0.05 − P/k.
    let (_, a) = run_edited(&data("gap-tips.toml"), |d| {
        set(entry(d, "contact", 0), "gap", 0.05)
    });
    assert!(events(&a).is_empty(), "{:?}", events(&a));
    let t = pair(&a, "tips");
    assert_eq!(t.state, PairState::Open);
    close(t.z_n, 0.05 - pl / k, 0.05, "gap left");
}

// ---------------------------------------------------------------------------------------------
// friction per entry, target, trace = "end"

#[test]
fn friction_per_contact_entry() {
    // Bar on pairs a (f = 0.2) and b (f = 0.5), W = 10 per node, H p = p at node 2. Stuck, the
    // rigid pairs hold each node: b carries all of H p. b slips at p = 0.5·10 = 5 and keeps
    // 0.5·10; the bar passes H p − 5 to a, which slips at p = (0.2 + 0.5)·10 = 7: the bar then
    // slides (a mechanism). At the target p = 6: |x_t(b)| = 5, |x_t(a)| = 1, the bar's tension
    // 1 stretches it by 1·L/EA = 5e-10 — b's slip, a has not moved.
    check_slider(&run("friction-slider.toml").1);
}

#[test]
fn a_json_model_is_the_toml_model() {
    // The same slider written as JSON (docs/model-format.md: the same structure) gives the
    // same hand values.
    let text = std::fs::read_to_string(data("friction-slider.toml")).unwrap();
    let doc: toml::Table = text.parse().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("friction-slider.json");
    std::fs::write(&file, serde_json::to_string_pretty(&doc).unwrap()).unwrap();
    let Problem::Structural(p) = read_problem(&file).unwrap() else {
        panic!("not a structural model")
    };
    check_slider(&analyze(&p.model, &p.settings).unwrap());
}

fn check_slider(a: &Analysis) {
    let ev = events(a);
    assert_eq!(ev.len(), 2, "{ev:?}");
    assert_eq!(ev[0].1, "b");
    assert_eq!(ev[1].1, "a");
    assert!(matches!(
        ev[0].2,
        EventKind::StartsSlippingPlus | EventKind::StartsSlippingMinus
    ));
    close(ev[0].0, 5.0, 1.0, "b slips");
    close(ev[1].0, 7.0, 1.0, "a slips");
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!("expected a mechanism, got {:?}", a.solution.outcome)
    };
    close(p_limit, 7.0, 1.0, "limit load");

    assert_eq!(a.p(), Some(6.0));
    let (pa, pb) = (pair(a, "a"), pair(a, "b"));
    close(pa.x_n, 10.0, 10.0, "x_n a");
    close(pb.x_n, 10.0, 10.0, "x_n b");
    close(pb.x_t.abs(), 5.0, 10.0, "|x_t| b = f_b W");
    close(pa.x_t.abs(), 1.0, 10.0, "|x_t| a = H p − f_b W");
    assert_eq!(pa.state, PairState::Stick);
    assert_eq!(
        pb.state,
        PairState::SlipPlus,
        "node 2 moves along +x = the tangent"
    );
    close(pb.z_t, 1.0 / 2e9, 1.0 / 2e9, "slip of b = N L / EA");
    close(pa.z_t, 0.0, 1.0 / 2e9, "a has not moved");
}

// ---------------------------------------------------------------------------------------------
// settlement

#[test]
fn settlement_of_a_support_uy() {
    // A–B–C, spans a = 3, EI = 2.7e6, B settles by δ = 0.01. With C held, B pulls the beam down
    // like a point load F at the middle of a simply supported span 2a: δ = F (2a)³/(48 EI) →
    // F = 6 EI δ/a³ = 6000, A and C each push up F/2 = 3000. The lift 1000 p at C goes straight
    // into C's pair: x_n(C) = 3000 − 1000 p, open at p = 3, then a ray.
    let (p, a) = run("settlement.toml");
    let (ei, aa, d): (f64, f64, f64) = (2.7e6, 3.0, 0.01);
    let f = 6.0 * ei * d / aa.powi(3);
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("C", EventKind::Opens));
    close(ev[0].0, f / 2.0 / 1000.0, 1.0, "opening load");
    let Outcome::Ray { p_from } = a.solution.outcome else {
        panic!("expected a ray, got {:?}", a.solution.outcome)
    };
    close(p_from, 3.0, 1.0, "ray");
    // At p = 1.
    close(pair(&a, "C").x_n, f / 2.0 - 1000.0, f, "x_n(C)");
    close(reaction(&p, &a, "beam.1", SupportDof::Uy), -f, f, "R_B");
    close(
        reaction(&p, &a, "beam.0", SupportDof::Uy),
        f / 2.0,
        f,
        "R_A",
    );
    close(disp(&p, &a, "beam.1")[1], -d, d, "the settled node");
}

#[test]
fn settlement_of_a_support_rz() {
    // A clamp turning by θ = 1e-3 lifts the tip of a cantilever (L = 3, EI = 2.7e6) by θ L
    // against a stop: the prop force of a propped cantilever whose tip is held back by θ L is
    // 3 EI θ L/L³ = 3 EI θ/L² = 900. The pull 300 p on the tip opens it at p = 3.
    // The clamp written as `fixed`, and as `pinned` plus `rz` in two entries (merged).
    let pinned_and_rz = |d: &mut toml::Table| {
        let s = entry(d, "supports", 0);
        s.remove("fixed");
        set(s, "pinned", true);
        let mut rz = toml::Table::new();
        set(&mut rz, "nodes", "beam.start");
        set(&mut rz, "rz", true);
        match d.get_mut("supports") {
            Some(toml::Value::Array(a)) => a.push(rz.into()),
            _ => unreachable!(),
        }
    };
    settlement_rz(run("settlement-rz.toml"));
    settlement_rz(run_edited(&data("settlement-rz.toml"), pinned_and_rz));
}

fn settlement_rz((p, a): (StructuralProblem, Analysis)) {
    let x = 3.0 * 2.7e6 * 1e-3 / 9.0;
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("stop", EventKind::Opens));
    close(ev[0].0, x / 300.0, 1.0, "opening load");
    close(pair(&a, "stop").x_n, x - 300.0, x, "x_n at p = 1");
    close(
        disp(&p, &a, "beam.start")[2],
        1e-3,
        1e-3,
        "the clamp's rotation",
    );
    close(
        disp(&p, &a, "beam.end")[1],
        0.0,
        3e-3,
        "the tip stays at the stop",
    );
}

// ---------------------------------------------------------------------------------------------
// temperature

#[test]
fn uniform_temperature_alpha_on_the_section() {
    // Pinned at A, bearing at B (f = 0.25, W = 5e5), EA = 2e9, α = 1.2e-5, ΔT = 20 p, L = 10.
    // Stuck, B is held: the bearing takes EA α ΔT p = 4.8e5 p sideways; it slips at
    // p = f W/(4.8e5) = 0.260417, then a ray. At p = 2 the bearing has slid by the free
    // expansion less the shortening under the friction force: α ΔT p L − f W L/EA.
    let (ea, alpha, dt, l, f, w) = (2e9, 1.2e-5, 20.0, 10.0, 0.25, 5e5);
    let (p, a) = run("temperature-bearing.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!(
        (ev[0].1.as_str(), ev[0].2),
        ("bearing", EventKind::StartsSlippingPlus)
    );
    let p_slip = f * w / (ea * alpha * dt);
    close(ev[0].0, p_slip, 1.0, "slip load");
    assert!(matches!(a.solution.outcome, Outcome::Ray { .. }));
    assert_eq!(a.p(), Some(2.0));
    let b = pair(&a, "bearing");
    assert_eq!(b.state, PairState::SlipPlus);
    close(b.x_n, w, w, "x_n");
    close(b.x_t.abs(), f * w, w, "|x_t| = f W");
    let slide = alpha * dt * 2.0 * l - f * w * l / ea;
    close(b.z_t, slide, slide, "slip");
    close(disp(&p, &a, "beam.end")[0], slide, slide, "ux at B");
    // Tension positive: the bar is compressed by the friction force.
    let r = a.results.as_ref().unwrap();
    for line in &r.lines {
        close(line.end_forces[3], -f * w, f * w, "N");
    }
}

#[test]
fn temperature_gradient_through_the_depth() {
    // Top face 30 K warmer than the bottom, depth h = 0.3, α = 1e-5: curvature α ΔT/h = 1e-3
    // (the top lengthens: the beam bends down), free tip deflection κ L²/2 = 0.008 down, into
    // the prop. The prop force that pushes it back: 3 EI·0.008/L³ = 3·2e6·0.008/64 = 750.
    let (p, a) = run("temperature-gradient.toml");
    let x = 3.0 * 2e6 * (1e-5 * 30.0 / 0.3 * 16.0 / 2.0) / 64.0;
    assert_eq!(a.p(), Some(1.0));
    let pr = pair(&a, "prop");
    assert_eq!(pr.state, PairState::Stick);
    close(pr.x_n, x, x, "prop force");
    // The clamp's moment: the prop's 750 at 4 m (the temperature curvature alone makes no
    // reaction): M_A = −750·4 = −3000 (clockwise: the prop pushes up).
    close(
        reaction(&p, &a, "beam.start", SupportDof::Rz),
        -4.0 * x,
        4.0 * x,
        "M_A",
    );
}

#[test]
fn settlement_of_a_support_ux() {
    // The bearing beam without its temperature: its pinned end A moves left by δ p, δ = 1e-3.
    // Stuck, B is held: the beam is stretched by δ p, the bearing pulls with EA δ p/L = 2e5 p and
    // slips (B following A, along −x) at p = f W L/(EA δ) = 0.625. At p = 2 B has moved by
    // −(δ p − f W L/EA).
    let (ea, l, f, w, d) = (2e9, 10.0, 0.25, 5e5, 1e-3);
    let (p, a) = run_edited(&data("temperature-bearing.toml"), |doc| {
        let v = table(doc, "loads.variable");
        v.remove("temperature");
        let mut s = toml::Table::new();
        set(&mut s, "nodes", "beam.start");
        set(&mut s, "dof", "ux");
        set(&mut s, "value", -d);
        set(v, "settlement", toml::Value::Array(vec![s.into()]));
    });
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!(
        (ev[0].1.as_str(), ev[0].2),
        ("bearing", EventKind::StartsSlippingMinus)
    );
    close(ev[0].0, f * w * l / (ea * d), 1.0, "slip load");
    let b = pair(&a, "bearing");
    let slide = d * 2.0 - f * w * l / ea;
    close(b.z_t, -slide, slide, "slip");
    close(
        disp(&p, &a, "beam.start")[0],
        -2.0 * d,
        d,
        "the settled end",
    );
    close(disp(&p, &a, "beam.end")[0], -slide, slide, "ux at B");
}

/// The plane strip of `plane-thermal.toml` with its analysis, formulation and thickness.
fn plane_thermal(
    analysis: &str,
    formulation: &str,
    thickness: f64,
) -> (StructuralProblem, Analysis) {
    run_edited(&data("plane-thermal.toml"), |d| {
        for i in 0..2 {
            let b = entry(d, "blocks", i);
            set(b, "analysis", analysis);
            set(b, "formulation", formulation);
        }
        set(entry(d, "materials", 0), "thickness", thickness);
    })
}

#[test]
fn plane_temperature_stress_strain_q4_qm6_thickness() {
    // The strip (E = 1e9, ν = 0.25, α = 1e-5, ΔT = 50 p, height h = 0.5, thickness t) expands
    // freely in y and is held in x by ux at x = 0 and the wall at x = 2: a uniform state
    // (both elements pass the patch test) with ε_x = 0, σ_y = 0.
    //   plane stress: σ_x = −E α ΔT;
    //   plane strain (ε_z = 0): σ_z = ν σ_x − E α ΔT, σ_x = −E α ΔT/(1 − ν).
    // The wall carries −σ_x h t in all, split as a uniform traction: 1/4, 1/2, 1/4 over the
    // three nodes of the edge (two element edges of 0.25 each).
    // The two blocks are merged by connect_to (otherwise the right block would float); the
    // wall side is a node set from a box `within` the right block.
    let (e, nu, adt, h) = (1e9, 0.25, 1e-5 * 50.0, 0.5);
    for (analysis, t) in [("plane_stress", 0.5), ("plane_strain", 2.0)] {
        for formulation in ["Q4", "QM6"] {
            let (p, a) = plane_thermal(analysis, formulation, t);
            let sx = if analysis == "plane_stress" {
                e * adt
            } else {
                e * adt / (1.0 - nu)
            };
            let total = sx * h * t;
            let what = format!("{analysis} {formulation} t = {t}");
            assert_eq!(
                a.solution.pairs.len(),
                3,
                "{what}: the wall side has 3 nodes"
            );
            let mut by_y: Vec<(f64, f64)> = a
                .solution
                .pairs
                .iter()
                .zip(p.model.pairs())
                .map(|(pr, spec)| (p.model.nodes()[spec.b.0][1], pr.x_n))
                .collect();
            by_y.sort_by(|u, v| u.0.total_cmp(&v.0));
            for ((_, x), share) in by_y.iter().zip([0.25, 0.5, 0.25]) {
                close(*x, share * total, total, &what);
            }
            // The free expansion in y: ε_y = α ΔT − ν σ_x/E = (1 + ν) α ΔT (stress);
            // (1 + ν) α ΔT − ν (1 + ν) σ_x/E = (1 + ν) α ΔT/(1 − ν) (strain), σ_x < 0 as above.
            let ey = if analysis == "plane_stress" {
                (1.0 + nu) * adt
            } else {
                (1.0 + nu) * adt / (1.0 - nu)
            };
            close(disp(&p, &a, "right.top_right")[1], ey * h, ey * h, &what);
            close(disp(&p, &a, "right.top_right")[0], 0.0, ey * h, &what);
            let r = a.results.as_ref().unwrap();
            for pl in &r.planes {
                for s in &pl.stress {
                    close(s[0], -sx, sx, &format!("{what}: σ_x"));
                    close(s[1], 0.0, sx, &format!("{what}: σ_y"));
                    close(s[2], 0.0, sx, &format!("{what}: τ_xy"));
                    let sz = if analysis == "plane_stress" {
                        0.0
                    } else {
                        -nu * sx - e * adt
                    };
                    close(s[3], sz, sx, &format!("{what}: σ_z"));
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// plane formulations in bending

#[test]
fn plane_pure_bending_q4_locks_qm6_is_exact() {
    // One row of 4 elements (a = 0.5 half-length, b = 0.25 half-depth, t = 0.2), couple
    // M = F h = 100·0.5 = 50. Beam theory: ux at the top of the free end = M L (h/2)/(E' I),
    // I = t h³/12, E' = E (plane stress) or E/(1 − ν²) (plane strain). QM6 (incompatible
    // modes) reproduces pure bending on rectangles exactly. Q4 can only take the mode
    // u = α x y, v = 0 in each element (x, y from its centre): ε_x = α y, ε_y = 0 and a
    // parasitic γ = α x. Its energy per element over that of the exact bending is
    //   κ = [E_x ∫y² + G ∫x²]/(E' ∫y²) = E_x/E' + (G/E')(a/b)²,
    // E_x = E/(1 − ν²) (stress) or E(1 − ν)/((1 + ν)(1 − 2ν)) (strain), so ux_Q4 = ux/κ.
    // The ground pair at the top right corner opens (normal +x): z_n = ux there.
    let (e, nu, t, h, l, f): (f64, f64, f64, f64, f64, f64) = (1e7, 0.3, 0.2, 0.5, 4.0, 100.0);
    let (aa, b): (f64, f64) = (0.5, 0.25);
    let i = t * h.powi(3) / 12.0;
    let g = e / (2.0 * (1.0 + nu));
    for analysis in ["plane_stress", "plane_strain"] {
        let (e_exact, e_x) = if analysis == "plane_stress" {
            (e, e / (1.0 - nu * nu))
        } else {
            (
                e / (1.0 - nu * nu),
                e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            )
        };
        let exact = f * h * l * (h / 2.0) / (e_exact * i);
        let kappa = e_x / e_exact + g / e_exact * (aa / b).powi(2);
        for (formulation, want) in [("QM6", exact), ("Q4", exact / kappa)] {
            let (p, a) = run_edited(&data("plane-bending.toml"), |d| {
                let bl = entry(d, "blocks", 0);
                set(bl, "analysis", analysis);
                set(bl, "formulation", formulation);
            });
            let what = format!("{analysis} {formulation}");
            let tip = pair(&a, "tip");
            assert_eq!(tip.state, PairState::Open, "{what}");
            close(tip.z_n, want, exact, &what);
            close(disp(&p, &a, "beam.top_right")[0], want, exact, &what);
            close(disp(&p, &a, "beam.bottom_right")[0], -want, exact, &what);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// springs

#[test]
fn springs_to_the_ground_translational_and_rotational() {
    // Closed, the pair holds the tip: the springs are idle and x_n = 2000 − 1000 p: open at
    // p = 2, then a ray. Open at p = 4 the net lift 2000 meets the tip spring k = 5e5 and the
    // beam on its rotational root spring kr = 4e6, of tip flexibility L³/(3EI) + L²/kr.
    let (l, ei, k, kr): (f64, f64, f64, f64) = (2.0, 2e6, 5e5, 4e6);
    let (p, a) = run("springs-ground.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("tip", EventKind::Opens));
    close(ev[0].0, 2.0, 1.0, "opening");
    let kb = 1.0 / (l.powi(3) / (3.0 * ei) + l * l / kr);
    let z = 2000.0 / (k + kb);
    close(pair(&a, "tip").z_n, z, z, "uplift");
    close(disp(&p, &a, "beam.end")[1], z, z, "uy tip");
    // The root turns by the moment over kr: M = kb z L (counter-clockwise for an uplift).
    close(
        disp(&p, &a, "beam.start")[2],
        kb * z * l / kr,
        z / l,
        "root rotation",
    );
    let sf = &a.results.as_ref().unwrap().spring_forces;
    assert_eq!(sf.len(), 2);
    close(
        sf[0].abs(),
        kb * z * l,
        kb * z * l,
        "rotational spring moment",
    );
    close(sf[1].abs(), k * z, k * z, "tip spring force");
}

/// Tip block `[[v, θ]]` of the stiffness of a cantilever of length `l` clamped at its start:
/// `EI/L³ [[12, −6L], [−6L, 4L²]]` when it points along +x; `s = −1` when it points along −x
/// (local v = −global v).
fn cantilever_tip(ei: f64, l: f64, s: f64) -> [[f64; 2]; 2] {
    let c = ei / l.powi(3);
    [
        [12.0 * c, -6.0 * l * c * s],
        [-6.0 * l * c * s, 4.0 * l * l * c],
    ]
}

#[test]
fn springs_between_nodes_translational_and_rotational() {
    // Tip DOFs (vA, θA) of the upper cantilever (along +x), (vB, θB) of the lower (along −x);
    // a spring kt on vA − vB and kr on θA − θB; the pair acts on vA − vB. Assembled here:
    let (l, ei, kt, kr) = (2.0, 2e6, 3e5, 1e6);
    let (ka, kb) = (cantilever_tip(ei, l, 1.0), cantilever_tip(ei, l, -1.0));
    let open = |fa: f64| {
        let k = vec![
            vec![ka[0][0] + kt, ka[0][1], -kt, 0.0],
            vec![ka[1][0], ka[1][1] + kr, 0.0, -kr],
            vec![-kt, 0.0, kb[0][0] + kt, kb[0][1]],
            vec![0.0, -kr, kb[1][0], kb[1][1] + kr],
        ];
        solve_dense(k, vec![fa, 0.0, 0.0, 0.0])
    };
    // Closed (vA = vB = v, DOFs v, θA, θB): the pair's compression X is what the lower
    // cantilever receives downwards: X = −(kb00 v + kb01 θB).
    let closed = |fa: f64| {
        let k = vec![
            vec![ka[0][0] + kb[0][0], ka[0][1], kb[0][1]],
            vec![ka[1][0], ka[1][1] + kr, -kr],
            vec![kb[1][0], -kr, kb[1][1] + kr],
        ];
        let u = solve_dense(k, vec![fa, 0.0, 0.0]);
        -(kb[0][0] * u[0] + kb[0][1] * u[2])
    };
    // Both states are linear in the net load 500 p − 1000: the pair opens where it changes
    // sign, p = 2 (if the open solution at positive net load opens the pair, as checked).
    let (_, a) = run("springs-between.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!((ev[0].1.as_str(), ev[0].2), ("tips", EventKind::Opens));
    close(ev[0].0, 2.0, 1.0, "opening");
    let u = open(500.0);
    assert!(u[0] > u[2]);
    let t = pair(&a, "tips");
    close(t.z_n, u[0] - u[2], u[0], "opening at p = 3");
    let sf = &a.results.as_ref().unwrap().spring_forces;
    close(
        sf[0].abs(),
        kt * (u[0] - u[2]),
        kt * u[0],
        "translational spring",
    );
    close(
        sf[1].abs(),
        kr * (u[1] - u[3]).abs(),
        kr * u[1].abs(),
        "rotational spring",
    );
    // Before opening, at p = 1: net load −500.
    let x = closed(-500.0);
    assert!(x > 0.0);
    let (pairs, _) = a.results_at(1.0).unwrap();
    close(
        pair_at(&pairs, "tips").x_n,
        x,
        500.0,
        "compression at p = 1",
    );
}

// ---------------------------------------------------------------------------------------------
// releases

#[test]
fn releases_at_the_end_of_an_element_and_the_start_of_a_member() {
    // A hinge at B makes B–C a simply supported span on the tip of the cantilever A–B: the
    // middle load 1000 p splits in halves; C's pair gets 500 p + the 100 pressing it, and the
    // clamp at A holds the other half at 2 m: R_A = 500 p, M_A = +1000 p (counter-clockwise).
    // The same with the hinge written as a release at the start of the member instead.
    let variants: [(&str, Edit); 2] = [
        ("release at the end of AB", Box::new(|_| {})),
        (
            "release at the start of the member",
            Box::new(|d: &mut toml::Table| {
                entry(d, "elements", 0).remove("releases");
                set(
                    entry(d, "members", 0),
                    "releases",
                    toml::Value::Array(vec!["start".into()]),
                );
            }),
        ),
    ];
    let variants = variants.into_iter().chain([(
        "member sharing B through connect_to",
        Box::new(|d: &mut toml::Table| {
            let m = entry(d, "members", 0);
            set(m, "start", toml::Value::Array(vec![2.0.into(), 0.0.into()]));
            set(m, "connect_to", "B");
        }) as Edit,
    )]);
    for (what, edit) in variants {
        let (p, a) = run_edited(&data("releases.toml"), edit);
        close(pair(&a, "C").x_n, 600.0, 1000.0, what);
        close(reaction(&p, &a, "A", SupportDof::Uy), 500.0, 1000.0, what);
        close(reaction(&p, &a, "A", SupportDof::Rz), 1000.0, 1000.0, what);
        // No moment at the hinge: the end moment of AB and the start moment of the span.
        let r = a.results.as_ref().unwrap();
        for line in &r.lines {
            let Element::Frame { nodes, .. } = &p.model.elements()[line.element.0] else {
                panic!("only frames here")
            };
            let [x0, x1] = nodes.map(|n| p.model.nodes()[n.0][0]);
            if x1 == 2.0 {
                close(line.end_forces[5], 0.0, 1000.0, what);
            }
            if x0 == 2.0 {
                close(line.end_forces[2], 0.0, 1000.0, what);
            }
        }
    }
    // Without the hinge the structure is a propped cantilever and C carries less: the release
    // is what the answer above depends on. (Propped cantilever A–C, L = 6, load at a = 4:
    // R_C = P a²(3L − a)/(2 L³) = 1000·16·14/432 = 518.5.)
    let (_, a) = run_edited(&data("releases.toml"), |d| {
        entry(d, "elements", 0).remove("releases");
    });
    close(
        pair(&a, "C").x_n,
        100.0 + 1000.0 * 16.0 * 14.0 / 432.0,
        1000.0,
        "no hinge",
    );
}

// ---------------------------------------------------------------------------------------------
// inclined roller

#[test]
fn inclined_roller() {
    // The roller at B (4, 0) reacts along (1, 2): moments about A give its vertical part
    // P/2 (load P p at x = 2), so its horizontal part is P/4. A's pair then carries
    // x_n = W + P p/2 and |x_t| = P p/4, and slips when P p/4 = f (W + P p/2):
    // p = f W/(P (1/4 − f/2)) = 3 for W = P = 1000, f = 0.3; the beam becomes a mechanism.
    let (p, a) = run("inclined-roller.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    assert_eq!(ev[0].1, "A");
    close(ev[0].0, 3.0, 1.0, "slip");
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!("expected a mechanism, got {:?}", a.solution.outcome)
    };
    close(p_limit, 3.0, 1.0, "limit");
    let (pairs, r) = a.results_at(1.0).unwrap();
    let pa = pair_at(&pairs, "A");
    close(pa.x_n, 1500.0, 1000.0, "x_n at p = 1");
    close(pa.x_t.abs(), 250.0, 1000.0, "|x_t| at p = 1");
    let n = node(&p, "beam.end");
    let rb = r.reactions.iter().find(|x| x.node.0 == n).unwrap();
    assert!(matches!(rb.dof, SupportDof::Along(_)));
    close(
        rb.value.abs(),
        1000.0 * 5f64.sqrt() / 4.0,
        1000.0,
        "roller reaction",
    );
}

// ---------------------------------------------------------------------------------------------
// distributed loads, body forces, nodal moments

/// Vertical support at the start (0, 0), a sticking pair at the end (xb, yb): the statics of
/// a resultant (fx, fy) acting at (x, y) plus a moment m. Returns (R_A, x_n(B), x_t(B)) with
/// x_t the force the ground exerts on the beam along +x.
fn roller_and_pair(xb: f64, yb: f64, fx: f64, fy: f64, x: f64, y: f64, m: f64) -> [f64; 3] {
    // Σ Fx: T + fx = 0. Moments about B: R_A·(0 − xb) + (x − xb) fy − (y − yb) fx + m = 0.
    // Σ Fy: R_A + N + fy = 0.
    let t = -fx;
    let ra = ((x - xb) * fy - (y - yb) * fx + m) / xb;
    let n = -fy - ra;
    [ra, n, t]
}

#[test]
fn distributed_load_linearly_varying_along_a_member() {
    // q from (30, −100) at the start to (60, −400) at the end of the 4 m chain: resultant
    // (L (30 + 60)/2, −L (100 + 400)/2) = (180, −1000), the vertical part at the centroid of the
    // trapezoid x̄ = L (q1 + 2 q2)/(3 (q1 + q2)) = 4·900/1500 = 2.4 (horizontal parts on the
    // axis make no moment).
    let (p, a) = run("roller-pair.toml");
    let [ra, n, t] = roller_and_pair(4.0, 0.0, 180.0, -1000.0, 2.4, 0.0, 0.0);
    let b = pair(&a, "B");
    close(b.x_n, 1000.0 + n, 1000.0, "x_n");
    close(b.x_t.abs(), t.abs(), 1000.0, "|x_t|");
    close(
        reaction(&p, &a, "beam.start", SupportDof::Uy),
        ra,
        1000.0,
        "R_A",
    );
    close(ra, 400.0, 1.0, "R_A by hand: L (2 q1 + q2)/6");
}

/// The linearly varying load of `roller-pair.toml` on other listings of the same 4 m chain:
/// the variation follows the distance along the chain from its end at the first listed element,
/// whatever the order and direction in which the elements and members are drawn.
#[test]
fn distributed_load_linearly_varying_along_a_chain_however_drawn() {
    let load = |d: &mut toml::Table, elements: &[&str]| {
        let v = &mut table(d, "loads.variable")["distributed"];
        let toml::Value::Array(v) = v else {
            panic!("distributed")
        };
        let toml::Value::Table(t) = &mut v[0] else {
            panic!("distributed")
        };
        let list = elements.iter().map(|&e| toml::Value::from(e)).collect();
        set(t, "elements", toml::Value::Array(list));
    };
    // Listed from the end at x = 4: q = (30, −100) there and (60, −400) at x = 0. The vertical
    // resultant −1000 acts at 2.4 from x = 4, that is at x = 1.6; R_A = L (q1 + 2 q2)/6 with
    // q1 = 100 at x = 4 and q2 = 400 at A: 4·900/6 = 600.
    let (p, a) = run_edited(&data("roller-pair.toml"), |d| {
        load(d, &["beam.4", "beam.3", "beam.2", "beam.1"])
    });
    let [ra, n, t] = roller_and_pair(4.0, 0.0, 180.0, -1000.0, 1.6, 0.0, 0.0);
    close(ra, 600.0, 1.0, "R_A by hand");
    close(
        pair(&a, "B").x_n,
        1000.0 + n,
        1000.0,
        "x_n (listed backwards)",
    );
    close(
        pair(&a, "B").x_t.abs(),
        t.abs(),
        1000.0,
        "|x_t| (listed backwards)",
    );
    close(
        reaction(&p, &a, "beam.start", SupportDof::Uy),
        ra,
        1000.0,
        "R_A (listed backwards)",
    );
    // The same chain as two members (two elements each), their nodes named by the members:
    // `ends` gives each member's `start` and `end` (a point or a node's name), the support at
    // x = 0 and the pair (and its constant load) at x = 4 moved to those nodes.
    let point = |x: f64| toml::Value::Array(vec![x.into(), 0.0.into()]);
    let two_members = |d: &mut toml::Table,
                       ends: [(&str, toml::Value, toml::Value); 2],
                       support: &str,
                       tip: &str| {
        let members = ends
            .into_iter()
            .map(|(name, start, end)| {
                let mut m = toml::Table::new();
                set(&mut m, "name", name);
                set(&mut m, "start", start);
                set(&mut m, "end", end);
                set(&mut m, "divisions", 2);
                set(&mut m, "section", "beam");
                toml::Value::Table(m)
            })
            .collect();
        set(d, "members", toml::Value::Array(members));
        set(entry(d, "supports", 0), "nodes", support);
        set(entry(d, "contact", 0), "to", tip);
        let nodal = &mut table(d, "loads.constant")["nodal"];
        let toml::Value::Array(nodal) = nodal else {
            panic!("nodal")
        };
        let toml::Value::Table(nodal) = &mut nodal[0] else {
            panic!("nodal")
        };
        set(nodal, "nodes", tip);
        load(d, &["left", "right"]);
    };
    // Hand: the original load, R_A = 400 (above).
    let [ra, n, t] = roller_and_pair(4.0, 0.0, 180.0, -1000.0, 2.4, 0.0, 0.0);
    // Drawn towards each other, (0,0)→(2,0) and (4,0)→(2,0), listed from x = 0: a projection
    // on the line from the first element's start to the last element's end (both at x = 2)
    // lost this load. Drawn away from x = 2, (2,0)→(0,0) and (2,0)→(4,0), listed whole: the
    // first listed element (of `left`, at x = 2) is inside the chain, which starts at the free
    // end listed first, x = 0 (`left.end`).
    let towards = [
        ("left", point(0.0), point(2.0)),
        ("right", point(4.0), "left.end".into()),
    ];
    let away = [
        ("left", point(2.0), point(0.0)),
        ("right", "left.start".into(), point(4.0)),
    ];
    for (what, ends, support, tip) in [
        ("towards", towards, "left.start", "right.start"),
        ("away", away, "left.end", "right.end"),
    ] {
        let (p, a) = run_edited(&data("roller-pair.toml"), |d| {
            two_members(d, ends, support, tip)
        });
        close(pair(&a, "B").x_n, 1000.0 + n, 1000.0, what);
        close(pair(&a, "B").x_t.abs(), t.abs(), 1000.0, what);
        close(reaction(&p, &a, support, SupportDof::Uy), ra, 1000.0, what);
    }
}

#[test]
fn distributed_load_uniform_in_local_axes() {
    // Member (0,0)–(3,4), L = 5, axis e = (0.6, 0.8), normal n = (−0.8, 0.6) (e turned 90°
    // counter-clockwise, docs/fem.md). q = (100 axial, 200 normal): resultant
    // 5·(100 e + 200 n) = (−500, 1000) at the middle (1.5, 2). With W = 2000 pressing B, f = 0.5:
    // x_n(p) = W + p N1, |x_t(p)| = p |T1|; B slips at p = f W/(|T1| − f N1), a mechanism.
    let (fx, fy) = (
        5.0 * (100.0 * 0.6 - 200.0 * 0.8),
        5.0 * (100.0 * 0.8 + 200.0 * 0.6),
    );
    let [ra, n1, t1] = roller_and_pair(3.0, 4.0, fx, fy, 1.5, 2.0, 0.0);
    let (w, f) = (2000.0, 0.5);
    let p_slip = f * w / (t1.abs() - f * n1);
    let (_, a) = run("local-load.toml");
    let ev = events(&a);
    assert_eq!(ev.len(), 1, "{ev:?}");
    close(ev[0].0, p_slip, 1.0, "slip");
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!("expected a mechanism, got {:?}", a.solution.outcome)
    };
    close(p_limit, p_slip, 1.0, "limit");
    let (pairs, r) = a.results_at(1.0).unwrap();
    let b = pair_at(&pairs, "B");
    close(b.x_n, w + n1, w, "x_n at p = 1");
    close(b.x_t.abs(), t1.abs(), w, "|x_t| at p = 1");
    let ry = r
        .reactions
        .iter()
        .find(|x| x.node.0 == 0 && x.dof == SupportDof::Uy)
        .unwrap()
        .value;
    close(ry, ra, w, "R_A");
}

#[test]
fn body_force_on_frames_and_a_nodal_moment() {
    // Body force (20, −150) per unit length on the 4 m beam: resultant (80, −600) at x = 2:
    // R_A = 300, x_n = 1000 + 300, |x_t| = 80. A nodal moment −800 (clockwise) at x = 2 alone:
    // moments about A: 4 N + m = 0 → N = 200, R_A = −200.
    let body = |d: &mut toml::Table| {
        let v = table(d, "loads.variable");
        v.remove("distributed");
        let mut b = toml::Table::new();
        set(&mut b, "elements", "beam");
        set(
            &mut b,
            "force",
            toml::Value::Array(vec![20.0.into(), (-150.0).into()]),
        );
        set(v, "body", toml::Value::Array(vec![b.into()]));
    };
    let (p, a) = run_edited(&data("roller-pair.toml"), body);
    let [ra, n, t] = roller_and_pair(4.0, 0.0, 80.0, -600.0, 2.0, 0.0, 0.0);
    close(pair(&a, "B").x_n, 1000.0 + n, 1000.0, "x_n (body)");
    close(pair(&a, "B").x_t.abs(), t.abs(), 1000.0, "|x_t| (body)");
    close(
        reaction(&p, &a, "beam.start", SupportDof::Uy),
        ra,
        1000.0,
        "R_A (body)",
    );

    let moment = |d: &mut toml::Table| {
        let v = table(d, "loads.variable");
        v.remove("distributed");
        let mut b = toml::Table::new();
        set(&mut b, "nodes", "beam.2");
        set(&mut b, "m", -800.0);
        set(v, "nodal", toml::Value::Array(vec![b.into()]));
    };
    let (p, a) = run_edited(&data("roller-pair.toml"), moment);
    close(pair(&a, "B").x_n, 1200.0, 1000.0, "x_n (moment)");
    close(
        reaction(&p, &a, "beam.start", SupportDof::Uy),
        -200.0,
        1000.0,
        "R_A (moment)",
    );
}

#[test]
fn body_force_on_plane_elements_thickness_and_exclude() {
    // Block 2 × 1, t = 0.4, body (2000, −20000)·p: weight W = 20000·2·1·0.4 = 16000, push
    // B = 2000·0.8 = 1600 at the centroid (1, 0.5). The bottom-left node is pinned and left out
    // of the pairs (`exclude`): 4 pairs. Statics: Σ x_n + R_y = W, Σ x_t·t + R_x = −B along x
    // (t = (1, 0)), and moments about the pinned corner (the pairs at their x, friction on
    // the base makes none): Σ x_n x_i = W·1 + B·0.5.
    let (p, a) = run("body-block.toml");
    assert_eq!(a.solution.pairs.len(), 4, "exclude leaves out the corner");
    let (w, b) = (16000.0, 1600.0);
    let model = &p.model;
    let mut sum_n = 0.0;
    let mut sum_t = 0.0;
    let mut mom = 0.0;
    for (pr, spec) in a.solution.pairs.iter().zip(model.pairs()) {
        sum_n += pr.x_n;
        sum_t += pr.x_t;
        mom += pr.x_n * model.nodes()[spec.b.0][0];
    }
    let corner = node(&p, "blk.bottom_left");
    let rx = reaction(&p, &a, "blk.bottom_left", SupportDof::Ux);
    let ry = reaction(&p, &a, "blk.bottom_left", SupportDof::Uy);
    assert_eq!(model.nodes()[corner], [0.0, 0.0]);
    close(sum_n + ry, w, w, "Σ vertical");
    close(mom, w * 1.0 + b * 0.5, w, "moments");
    // x_t is the force on the structure along t or its opposite: either way it balances.
    assert!(
        (sum_t + rx + b).abs() <= REL * w || (-sum_t + rx + b).abs() <= REL * w,
        "Σ horizontal: x_t sum {sum_t}, R_x {rx}, B {b}"
    );
}

// ---------------------------------------------------------------------------------------------
// [solve]: tightening, max_pivots, pivot_tolerance (target and trace are used above)

#[test]
fn solve_tightening_moves_the_events_of_a_homogeneous_problem() {
    // Example 1: the tightening c presses every pair by c; pair 1 loses it to the load's
    // tension 0.09375 p (the paper's R_v) at p = c/0.09375: 26.667 for c = 2.5. The answer
    // at p = 1 does not depend on c: uplift P L³/(16 EI) = 0.5 at the left support.
    let (_, a) = run_edited(&example("example1-beam.toml"), |d| {
        set(table(d, "solve"), "tightening", 2.5)
    });
    let Outcome::Ray { p_from } = a.solution.outcome else {
        panic!("expected a ray, got {:?}", a.solution.outcome)
    };
    close(p_from, 2.5 / -ex1::RV_N[0], 1.0, "ray");
    close(a.solution.pairs[0].z_n, 0.5, 0.5, "uplift");
}

#[test]
fn solve_max_pivots_and_pivot_tolerance() {
    // The slider's path has two events, each at least one pivot, before its mechanism: with
    // max_pivots = 1 the cap is reached first. With a cap of 100 it ends as computed in
    // `friction_per_contact_entry`. A pivot tolerance of 1e-10 leaves example 1's ray at
    // 1/0.09375 (formulation: pair 1 loses the tightening c = 1 to the tension 0.09375 p).
    let (_, a) = run_edited(&data("friction-slider.toml"), |d| {
        set(table(d, "solve"), "max_pivots", 1)
    });
    assert_eq!(a.solution.outcome, Outcome::IterationLimit);
    let (_, a) = run_edited(&data("friction-slider.toml"), |d| {
        set(table(d, "solve"), "max_pivots", 100)
    });
    let Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
        panic!("expected a mechanism, got {:?}", a.solution.outcome)
    };
    close(p_limit, 7.0, 1.0, "limit load");
    let (_, a) = run_edited(&example("example1-beam.toml"), |d| {
        set(table(d, "solve"), "pivot_tolerance", 1e-10)
    });
    let Outcome::Ray { p_from } = a.solution.outcome else {
        panic!("expected a ray, got {:?}", a.solution.outcome)
    };
    close(p_from, ex1::FIRST_EVENT_P, 1.0, "ray");
}

/// `portal-sliding-feet.toml` (`friction = 0.05` on a portal that nothing else holds sideways),
/// in N·m and in kN·mm: by hand (statics of the three-hinged-free frame, its comment) the beam's
/// 160 kN split equally at the start, the push `H = 10 kN·p` leftwards at the right knee adds
/// `±H·h/L = ±6.25 kN·p` to the feet, the left foot slides out at its friction's capacity
/// (`x_t = f·x_n1`, state slip−) and the right one sticks with the rest of the push
/// (`x_t2 = H − f·x_n1`) until it too reaches its capacity: a mechanism at `p = f·W/H = 0.8`.
/// At the target 0.4: `x_n = 82.5, 77.5 kN`, `x_t = 4.125, −0.125 kN`. In kN·mm the start
/// (both feet at their capacity, one row zero by the statics) read that row as −1.4e-12 of the
/// largest value and was refused: "no solution at the start".
#[test]
fn a_portal_on_feet_with_little_friction_slides_at_the_load_by_hand_in_both_units() {
    for (units, force) in [("N·m", 1.0), ("kN·mm", 1e-3)] {
        let (_, a) = run_in_units(&data("portal-sliding-feet.toml"), force);
        match a.solution.outcome {
            Outcome::Mechanism { p_limit, .. } => close(p_limit, 0.8, 1.0, units),
            ref other => panic!("{units}: {other:?}"),
        }
        let w = 160_000.0 * force;
        let (left, right) = (pair(&a, "foot.1"), pair(&a, "foot.2"));
        close(left.x_n, 82_500.0 * force, w, units);
        close(right.x_n, 77_500.0 * force, w, units);
        close(left.x_t, 4_125.0 * force, w, units);
        close(right.x_t, -125.0 * force, w, units);
        assert_eq!(left.state, PairState::SlipMinus, "{units}");
        assert_eq!(right.state, PairState::Stick, "{units}");
    }
}

/// `tests/data/free-modes/beam-on-block-frictionless.toml` and its `-kn-mm` twin (the same
/// model as an engineer types it in kN·mm; `friction = 0` on node-to-surface pairs, a 100 N/m
/// spring the only sideways support): by hand each of the beam's two pairs carries half of
/// `(4 + 5·6) kN/m × 2 m` at the target `p = 5`, 34 kN, and no tangential force (nothing loads
/// the beam sideways). In kN·mm the start read a row that is zero by the statics as −1e-12 of
/// the largest value: "no solution at the start".
#[test]
fn a_beam_lying_without_friction_on_a_block_carries_its_load_in_both_units() {
    for (file, force) in [
        ("beam-on-block-frictionless.toml", 1.0),
        ("beam-on-block-frictionless-kn-mm.toml", 1e-3),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/free-modes")
            .join(file);
        let (_, a) = run_edited(&path, |_| {});
        assert_eq!(a.solution.outcome, Outcome::TargetReached, "{file}");
        let load = 68_000.0 * force;
        for name in ["seat.1", "seat.2"] {
            let pr = pair(&a, name);
            close(pr.x_n, 34_000.0 * force, load, file);
            close(pr.x_t, 0.0, load, file);
        }
    }
}

/// `tests/data/free-modes/block-on-foundation-soft-spring.toml` (`friction = 0` between two
/// blocks, a 133 N/m spring at the top the only sideways support), in N·m and in kN·mm: by
/// statics the spring carries the whole push `P = 23.54 kN·p` (no friction), and the couple
/// `P·h` of the push at the toe and the spring at the top tips the block about its toe where
/// `P·h = W·b/2`: `p = W·b/(2·h·P)`, `W` the body force times the block's volume. Within 1e-5:
/// the spring is 1e-9 of the block's stiffness, and the traced limit carries its round-off
/// (5e-7). In N·m the start's friction rows, zero by the statics, read −2.7e-9 of the largest
/// value on the condensed data: "no solution at the start".
#[test]
fn a_block_on_a_soft_spring_without_friction_tips_at_the_load_by_statics_in_both_units() {
    let (b, h, t) = (2.871111111111111, 2.789, 0.591);
    let w = 18551.016961664885 * b * h * t;
    let tip = w * b / (2.0 * h * 23539.81956369561);
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/free-modes/block-on-foundation-soft-spring.toml");
    for (units, force) in [("N·m", 1.0), ("kN·mm", 1e-3)] {
        let (_, a) = run_in_units(&path, force);
        match a.solution.outcome {
            Outcome::Mechanism { p_limit, .. } => assert!(
                (p_limit - tip).abs() <= 1e-5 * tip,
                "{units}: a mechanism at {p_limit}, by statics {tip}"
            ),
            ref other => panic!("{units}: {other:?}"),
        }
    }
}
