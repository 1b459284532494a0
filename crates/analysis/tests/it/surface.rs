//! Contact on surfaces through the model file: `match = "nearest"` and `"surface"`
//! (node-to-segment), gaps and friction per pair, gaps from the geometry, normals from the
//! surface, and their errors. Each test names its reference.

use std::path::PathBuf;

use unilateral_analysis::analyze;
use unilateral_contact::{EventKind, Follow, PairState, SolveSettings};
use unilateral_fem::{Endpoint, Model};
use unilateral_io::read_model;

/// Writes `text` as `name` in a fresh directory and reads it as a model file.
pub(crate) fn read(name: &str, text: &str) -> Result<unilateral_io::StructuralProblem, String> {
    let dir = tempfile::tempdir().unwrap();
    let path: PathBuf = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    read_model(&path).map_err(|e| e.to_string())
}

fn settings() -> SolveSettings {
    SolveSettings {
        tightening: 0.0,
        target: 1.0,
        follow: Follow::ToTarget,
        ..Default::default()
    }
}

/// A soft base block (`nb` elements along its top) and a block of the same width on it (`nt`
/// along its bottom), the base pinned at its bottom; the upper block carries `fy` at every
/// node of its top (constant) and `h` at its top-left corner (variable). `contact` is the
/// `[[contact]]` entry.
fn two_blocks(nb: usize, nt: usize, fy: f64, h: f64, contact: &str) -> String {
    format!(
        r#"units = "N, m"
[[materials]]
name = "soft"
E = 2.0e7
nu = 0.3

[[blocks]]
name = "base"
origin = [0.0, 0.0]
width = 2.0
height = 1.0
nx = {nb}
ny = 2
material = "soft"
analysis = "plane_strain"

[[blocks]]
name = "top"
origin = [0.0, 1.0]
width = 2.0
height = 0.5
nx = {nt}
ny = 1
material = "soft"
analysis = "plane_strain"

[[supports]]
nodes = "base.bottom"
pinned = true

[[loads.constant.nodal]]
nodes = "top.top"
fy = {fy}

[[loads.constant.nodal]]
nodes = ["top.top_left", "top.top_right"]
fy = {half}

[[loads.variable.nodal]]
nodes = "top.top_left"
fx = {h}

{contact}
"#,
        half = -0.5 * fy
    )
}

/// The pair results and the full results at the target p = 1.
fn at_target(
    a: &unilateral_analysis::Analysis,
) -> (Vec<unilateral_contact::PairResult>, unilateral_fem::Results) {
    assert_eq!(a.solution.p, Some(1.0), "{:?}", a.solution.outcome);
    (a.solution.pairs.clone(), a.results.clone().unwrap())
}

/// The pair forces at p = 1 (names, x_n, x_t) and the sum of the base's vertical reactions.
fn forces(model: &Model) -> (Vec<(String, f64, f64)>, f64, f64) {
    let a = analyze(model, &settings()).unwrap();
    let (pairs, res) = at_target(&a);
    let ry: f64 = res
        .reactions
        .iter()
        .filter(|r| r.dof == unilateral_fem::SupportDof::Uy)
        .map(|r| r.value)
        .sum();
    // the work of the constant load: a uniform pressure on the top, its nodal loads
    // consistent (half at the corners)
    let names = model.names();
    let top = &names.node_sets["top.top"];
    let ends = [top[0], top[top.len() - 1]];
    let per_node = -3.0e3 / (top.len() - 1) as f64;
    let uy: f64 = top
        .iter()
        .map(|n| {
            let f = if ends.contains(n) {
                0.5 * per_node
            } else {
                per_node
            };
            f * res.displacements[n.0][1]
        })
        .sum();
    (
        pairs
            .iter()
            .map(|p| (p.name.clone(), p.x_n, p.x_t))
            .collect(),
        ry,
        uy,
    )
}

/// Matching meshes: `match = "coincident"` and `match = "surface"` pair the same nodes and
/// give the same contact forces (reference: the coincident pairing, today's, whose results
/// the bundled examples check against hand calculations).
#[test]
fn coincident_and_surface_agree_on_matching_meshes() {
    let coincident = two_blocks(
        4,
        4,
        -1.0e3,
        500.0,
        "[[contact]]\nname = \"c\"\nfrom = \"base.top\"\nto = \"top.bottom\"\nnormal = [0.0, 1.0]\nfriction = 0.5\n",
    );
    let surface = two_blocks(
        4,
        4,
        -1.0e3,
        500.0,
        "[[contact]]\nname = \"c\"\nmatch = \"surface\"\nsearch = 0.01\nfrom = \"base.top\"\nto = \"top.bottom\"\nnormal = \"surface\"\nfriction = 0.5\n",
    );
    let c = read("c.toml", &coincident).unwrap();
    let s = read("s.toml", &surface).unwrap();
    assert_eq!(c.model.pairs().len(), 5);
    assert_eq!(s.model.pairs().len(), 5);
    let (fc, _, _) = forces(&c.model);
    let (fs, _, _) = forces(&s.model);
    let scale = fc.iter().fold(0.0f64, |m, f| m.max(f.1.abs()));
    for (a, b) in fc.iter().zip(&fs) {
        assert_eq!(a.0, b.0);
        assert!((a.1 - b.1).abs() <= 1e-9 * scale, "{a:?} vs {b:?}");
        assert!((a.2 - b.2).abs() <= 1e-9 * scale, "{a:?} vs {b:?}");
    }
}

/// Non-matching meshes (3·k elements above, 5·k below): the contact normal forces carry the
/// applied weight and the tangential ones the push, to round-off (statics of the upper
/// block), and the base's supports carry the weight too (the link forces reach the segment
/// nodes with their weights). The work of the weight (a uniform pressure on the upper block)
/// converges under refinement to that of a fine matching mesh (reference: 80 × 80 elements
/// along the interface, node-to-node, whose own error is about 5e-5 of the value, as its
/// difference from 40 × 40 shows): the error must shrink at each halving of the elements and
/// end below 1 %. (Measured: 5.0 %, 2.1 %, 0.55 %, 0.34 %.)
#[test]
fn non_matching_meshes_balance_and_converge() {
    let (w, h) = (3.0e3, 600.0); // h below f·W = 1500: no slip
    let matching = "[[contact]]\nname = \"c\"\nfrom = \"top.bottom\"\nto = \"base.top\"\nnormal = [0.0, -1.0]\nfriction = 0.5\n";
    let r = read("m.toml", &two_blocks(80, 80, -w / 80.0, h, matching)).unwrap();
    let (_, _, work_ref) = forces(&r.model);
    let mut errors = Vec::new();
    for k in [1usize, 2, 4, 8] {
        let (nt, nb) = (3 * k, 5 * k);
        let entry = "[[contact]]\nname = \"c\"\nmatch = \"surface\"\nsearch = 0.05\nfrom = \"base.top\"\nto = \"top.bottom\"\nnormal = \"surface\"\nfriction = 0.5\n";
        let p = read("n.toml", &two_blocks(nb, nt, -w / nt as f64, h, entry)).unwrap();
        // every inner node of top.bottom but every third falls inside a segment of base.top
        let on_segment = p
            .model
            .pairs()
            .iter()
            .filter(|s| s.segment.is_some())
            .count();
        assert_eq!(on_segment, 2 * k, "k {k}");
        let (f, ry, work) = forces(&p.model);
        assert_eq!(f.len(), nt + 1);
        let sum_n: f64 = f.iter().map(|x| x.1).sum();
        let sum_t: f64 = f.iter().map(|x| x.2).sum();
        assert!((sum_n - w).abs() <= 1e-10 * w, "k {k}: Σ x_n = {sum_n}");
        assert!(
            (sum_t.abs() - h).abs() <= 1e-10 * w,
            "k {k}: Σ x_t = {sum_t}"
        );
        assert!((ry - w).abs() <= 1e-10 * w, "k {k}: Σ R_y = {ry}");
        errors.push(((work - work_ref) / work_ref).abs());
    }
    println!("relative errors of the work of the weight: {errors:?}");
    assert!(errors.windows(2).all(|e| e[1] < e[0]), "{errors:?}");
    assert!(errors[3] < 0.01, "{errors:?}");
}

/// A base block (3 elements along its top, y = 1) and a member from (0, `start_y`) to (2, 1.1)
/// in 4 elements, paired node-to-segment with gaps from the geometry.
fn beam_above_base(start_y: f64) -> String {
    format!(
        r#"units = "N, m"
[[materials]]
name = "soft"
E = 2.0e7
nu = 0.3

[[sections]]
name = "beam"
E = 2.0e11
A = 1.0e-2
I = 1.0e-5

[[blocks]]
name = "base"
origin = [0.0, 0.0]
width = 2.0
height = 1.0
nx = 3
ny = 1
material = "soft"
analysis = "plane_strain"

[[members]]
name = "beam"
start = [0.0, {start_y}]
end = [2.0, 1.1]
divisions = 4
section = "beam"

[[supports]]
nodes = "base.bottom"
pinned = true

[[supports]]
nodes = "beam.start"
fixed = true

[[loads.variable.nodal]]
nodes = "beam.end"
fy = -1.0

[[contact]]
name = "g"
match = "surface"
search = 1.0
from = "base.top"
to = "beam.nodes"
normal = "surface"
friction = 0.3
gap = "geometry"
"#
    )
}

/// `gap = "geometry"`: a member above the base block, its nodes at heights 1.5 − 0.2·x above
/// the base's top (y = 1): gaps 0.5, 0.4, 0.3, 0.2, 0.1 by hand, the projections at x = 0,
/// 0.5, 1, 1.5, 2 on the base's segments of length 2/3 (weights 0, 0.75, 0.5, 0.25, 1), and
/// the surface normal (0, 1) (the outward normal of the base's top edge).
#[test]
fn gaps_from_the_geometry_by_hand() {
    let p = read("g.toml", &beam_above_base(1.5)).unwrap();
    let pairs = p.model.pairs();
    assert_eq!(pairs.len(), 5);
    let gaps = [0.5, 0.4, 0.3, 0.2, 0.1];
    let xis = [None, Some(0.75), Some(0.5), Some(0.25), None];
    for (k, s) in pairs.iter().enumerate() {
        assert!((s.gap - gaps[k]).abs() < 1e-12, "pair {k}: gap {}", s.gap);
        assert!((s.normal[0]).abs() < 1e-15 && (s.normal[1] - 1.0).abs() < 1e-15);
        match (xis[k], s.segment) {
            (None, None) => {}
            (Some(x), Some((_, xi))) => assert!((xi - x).abs() < 1e-12, "pair {k}: ξ {xi}"),
            other => panic!("pair {k}: {other:?}"),
        }
        assert!(matches!(s.a, Endpoint::Node(_)));
    }
}

/// The gaps of `gap = "geometry"` do not depend on where the model is drawn: the base block
/// and a member 1 mm above its top, at the origin and at a site's grid coordinates
/// (5e5, 4e6) m. By hand every gap is 0.001 (up to the round-off of coordinates of 4e6,
/// about 1e-9). The coincidence tolerance was 1e-9 of the largest coordinate, 4 mm there:
/// every gap read 0.
#[test]
fn gaps_from_the_geometry_wherever_the_model_is_drawn() {
    for (x0, y0) in [(0.0, 0.0), (5e5, 4e6)] {
        let text = beam_above_base(1.5)
            .replace(
                "origin = [0.0, 0.0]",
                &format!("origin = [{x0:.1}, {y0:.1}]"),
            )
            .replace(
                "start = [0.0, 1.5]",
                &format!("start = [{x0:.1}, {:.3}]", y0 + 1.001),
            )
            .replace(
                "end = [2.0, 1.1]",
                &format!("end = [{:.1}, {:.3}]", x0 + 2.0, y0 + 1.001),
            );
        assert!(text.contains(&format!("{:.3}", y0 + 1.001)), "{text}");
        let p = read("g.toml", &text).unwrap();
        let pairs = p.model.pairs();
        assert_eq!(pairs.len(), 5, "at ({x0}, {y0})");
        for (k, s) in pairs.iter().enumerate() {
            assert!(
                (s.gap - 0.001).abs() < 1e-8,
                "at ({x0}, {y0}), pair {k}: gap {}",
                s.gap
            );
        }
    }
}

/// A block held only by its pairs, over a base with the same 1 mm gap at every pair, no
/// constant load (`tests/data/models/block-over-gap.toml`; with `gap = "geometry"` and the
/// block drawn 1 mm higher, the reviewer's case, in the second half). The gaps close by a rigid
/// motion of the block, which costs no force. Reference: the same blocks touching (gap 0): the
/// same pair forces, and the block's displacements 1 mm lower. The gap forces R·η cancel to
/// round-off (−3e-16), which read as tension made "no equilibrium at p = 0" of it.
#[test]
fn a_gap_closed_by_a_rigid_motion_costs_no_force() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/models/block-over-gap.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let touching = text.replace("gap = 0.001", "gap = 0.0");
    assert_ne!(text, touching);
    let run = |t: &str| {
        let p = read("b.toml", t).unwrap();
        let a = analyze(&p.model, &settings()).unwrap_or_else(|e| panic!("{e}"));
        let (pairs, res) = at_target(&a);
        (p.model, pairs, res)
    };
    let (mg, gap, rg) = run(&text);
    let (m0, zero, r0) = run(&touching);
    assert_eq!(gap.len(), 5);
    let top = zero.iter().fold(0.0f64, |a, p| a.max(p.x_n.abs()));
    for (a, b) in gap.iter().zip(&zero) {
        assert_eq!(a.state, b.state, "{a:?} {b:?}");
        assert!((a.x_n - b.x_n).abs() < 1e-9 * top, "{a:?} {b:?}");
        assert!((a.x_t - b.x_t).abs() < 1e-9 * top, "{a:?} {b:?}");
        assert!(a.z_n.abs() < 1e-12 && a.z_t.abs() < 1e-12, "{a:?}");
    }
    let sum: f64 = gap.iter().map(|p| p.x_n).sum();
    assert!((sum - 50.0).abs() < 1e-9 * 50.0, "Σ x_n = {sum}");
    let (ng, n0) = (mg.names(), m0.names());
    let mut checked = 0;
    for (i, name) in n0.nodes.iter().enumerate() {
        let j = ng.node_id(name).unwrap().0;
        let (ug, u0) = (rg.displacements[j], r0.displacements[i]);
        let shift = if name.starts_with("up.") { -0.001 } else { 0.0 };
        assert!((ug[0] - u0[0]).abs() < 1e-9, "{name}: {ug:?} {u0:?}");
        assert!(
            (ug[1] - (u0[1] + shift)).abs() < 1e-9,
            "{name}: {ug:?} {u0:?}"
        );
        checked += 1;
    }
    assert_eq!(checked, 25);
    // The gap from the geometry: the block drawn 1 mm above the base, the same answer.
    let drawn = text
        .replace("origin = [0.0, 1.0]", "origin = [0.0, 1.001]")
        .replace("gap = 0.001", "gap = \"geometry\"");
    assert!(drawn.contains("1.001") && drawn.contains("geometry"));
    let (_, geo, _) = run(&drawn);
    for (a, b) in geo.iter().zip(&gap) {
        assert_eq!(a.state, b.state, "{a:?} {b:?}");
        assert!((a.x_n - b.x_n).abs() < 1e-9 * top, "{a:?} {b:?}");
        assert!((a.x_t - b.x_t).abs() < 1e-9 * top, "{a:?} {b:?}");
    }
}

/// The same block over its 1 mm gap under 1e-11 of the test's load (target 1e-11): the gap's
/// dislocations make forces of about 1 N term by term (E = 1000 N/m² over 1 mm), whose
/// round-off (1e-16 of them, amplified by the solve) is beyond 1e-6 of the state's forces
/// (5e-10 N). The state cannot
/// be resolved in double precision: that is said as the data's conditioning (exit 2), not as
/// an internal failure (exit 1); at the test's load (above) the same model is resolved.
#[test]
fn a_state_the_gaps_round_off_swamps_is_the_datas_conditioning() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/models/block-over-gap.toml");
    let p = read("b.toml", &std::fs::read_to_string(path).unwrap()).unwrap();
    let s = SolveSettings {
        target: 1e-11,
        ..settings()
    };
    let e = analyze(&p.model, &s).unwrap_err();
    assert!(!e.is_internal(), "{e}");
    assert!(
        matches!(e, unilateral_analysis::AnalysisError::Unresolved { .. }),
        "{e}"
    );
    assert!(
        e.to_string()
            .contains("cannot be resolved in double precision"),
        "{e}"
    );
    // The model has a gap: the advice names it.
    assert!(e.to_string().contains("(gaps and slips)"), "{e}");
    assert!(e.to_string().contains("smaller gaps"), "{e}");
}

/// A block on the ground (f = 0.4, weight W = 2000 N) pushed sideways by 100 N·p slides as a
/// whole at p_lim = f·W/100 = 8 (`tests/data/models/block-sliding.toml`). At p_lim every pair
/// in contact is at its friction limit and slides in the mechanism: `slip-` (the push is in
/// −x), Σ x_n = W, Σ x_t = 100·p_lim. The pair whose slip starts at p_lim itself read "stick"
/// (its accumulated slip is zero there) while the mode slid it with the others.
#[test]
fn every_pair_of_a_sliding_mechanism_slips_at_the_limit_load() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/models/block-sliding.toml");
    let p = read("s.toml", &std::fs::read_to_string(path).unwrap()).unwrap();
    // traced beyond it, and with the target at the hand value of p_lim itself (the computed
    // p_lim is 8 to round-off: the state must not depend on which side of 8 it falls)
    for target in [20.0, 8.0] {
        let s = SolveSettings {
            tightening: 0.0,
            target,
            follow: Follow::ToEnd,
            ..Default::default()
        };
        let a = analyze(&p.model, &s).unwrap();
        let unilateral_analysis::Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
            panic!("{:?}", a.solution.outcome)
        };
        assert!((p_limit - 8.0).abs() < 1e-12 * 8.0, "{p_limit}");
        let reported = a.solution.p.unwrap();
        assert!((reported - 8.0).abs() < 1e-12 * 8.0, "{reported}");
        let pairs = &a.solution.pairs;
        let closed: Vec<_> = pairs
            .iter()
            .filter(|r| r.state != PairState::Open)
            .collect();
        assert!(closed.len() >= 3, "{pairs:?}");
        for r in &closed {
            assert_eq!(r.state, PairState::SlipMinus, "p* = {target}: {r:?}");
            assert!((r.x_t - 0.4 * r.x_n).abs() < 1e-9 * 2000.0, "{r:?}");
        }
        let (sn, st): (f64, f64) = pairs
            .iter()
            .fold((0.0, 0.0), |(a, b), r| (a + r.x_n, b + r.x_t));
        assert!((sn - 2000.0).abs() < 1e-9 * 2000.0, "Σ x_n = {sn}");
        assert!((st - 800.0).abs() < 1e-9 * 2000.0, "Σ x_t = {st}");
    }
}

/// A steel block 1 m × 0.5 m (E = 2e11, plane stress, 4 × 2 elements) on frictional ground
/// (pairs `g.*`, f = 0.3) under 5 × 2000 N on its top, pushed at its top right corner by
/// 5000 N·p, with `extra` (a spring, a stopper) added to the model.
fn steel_block_pushed(extra: &str) -> String {
    format!(
        r#"units = "N, m"
[[materials]]
name = "steel"
E = 2.0e11
nu = 0.3
thickness = 1.0

[[blocks]]
name = "blk"
origin = [0.0, 0.0]
width = 1.0
height = 0.5
nx = 4
ny = 2
material = "steel"
analysis = "plane_stress"

[[contact]]
name = "g"
from = "ground"
to = "blk.bottom"
normal = [0.0, 1.0]
friction = 0.3
{extra}
[[loads.constant.nodal]]
nodes = "blk.top"
fy = -2000.0

[[loads.variable.nodal]]
nodes = "blk.top_right"
fx = 5000.0
"#
    )
}

/// A spring of 300 N/m holding the block's heel sideways.
const SPRING_AT_THE_HEEL: &str = r#"
[[springs]]
nodes = "blk.bottom_left"
direction = [1.0, 0.0]
stiffness = 300.0
"#;

/// A frictionless stopper at the block's right face, 1 mm away (pairs `s.*`).
const STOPPER_1_MM_AWAY: &str = r#"
[[contact]]
name = "s"
from = "ground"
to = "blk.right"
normal = [-1.0, 0.0]
friction = 0.0
gap = 0.001
exclude = "blk.bottom_right"
"#;

/// A steel block (1 m × 0.5 m) on frictional ground (f = 0.3) under 5 × 2000 N, held
/// sideways by a soft spring (300 N/m) at its heel and pushed at its top right corner by
/// 5000 N·p. By hand: it slides when 5000·p = f·W = 3000 (p = 0.6), then the spring alone adds
/// resistance: at p = 1 the slip is (5000 − 3000)/300 = 6.6667 m. On the segment that carries
/// the load over the target (0.998 → 1.56, the heel lifting), the load's rate is 1e-6 of the
/// slips' — below the pivot tolerance of that column, which hid the target: the path ran on
/// past it to p = 2 and back to p = 0 ("returned to zero", the solution at p = 0).
#[test]
fn a_slow_load_rate_still_reaches_the_target() {
    let text = steel_block_pushed(SPRING_AT_THE_HEEL);
    let p = read("s.toml", &text).unwrap();
    let a = analyze(&p.model, &settings()).unwrap();
    assert_eq!(
        a.solution.outcome,
        unilateral_analysis::Outcome::TargetReached
    );
    assert_eq!(a.solution.p, Some(1.0));
    let slip = 2000.0 / 300.0;
    let mut sliding = 0;
    for r in &a.solution.pairs {
        // every pair has slid by the spring's share to the block's elastic strains (about
        // 1e-8 m; the lifted heel by its rotation too)
        assert!((r.z_t - slip).abs() < 1e-5 * slip, "{r:?}");
        if r.state == PairState::SlipPlus {
            sliding += 1;
            // to the round-off of the slips' terms (6.7 m times the links' stiffness, 1e11:
            // about 1e-4 N of forces of 1e4)
            assert!((r.x_t + 0.3 * r.x_n).abs() < 1e-6 * 10000.0, "{r:?}");
        }
    }
    assert!(sliding >= 4, "{:?}", a.solution.pairs);
    let fx: f64 = a.solution.pairs.iter().map(|r| r.x_t).sum();
    assert!((fx + 3000.0).abs() < 1e-6 * 3000.0, "friction {fx}");
    // Traced on, the block tips about its toe at p = 2 (the test after this one); none of the
    // steps after the start is one of the pivots that settle it. (The path came back to p = 0 after the tipping, on a load rate that was the
    // condensation's round-off.)
    let end = SolveSettings {
        follow: Follow::ToEnd,
        ..settings()
    };
    let a = analyze(&p.model, &end).unwrap();
    let steps = &a.solution.steps;
    let first_moving = steps.iter().position(|s| s.p != 0.0).unwrap();
    assert!(
        steps[first_moving..]
            .iter()
            .all(|s| !s.settling && s.p > 0.0),
        "{:?}",
        steps.iter().map(|s| (s.p, s.settling)).collect::<Vec<_>>()
    );
    assert!(
        matches!(a.solution.outcome, unilateral_analysis::Outcome::Mechanism { p_limit, .. }
            if (p_limit - 2.0).abs() < 1e-5),
        "{:?}",
        a.solution.outcome
    );
}

/// The block of [`a_slow_load_rate_still_reaches_the_target`] traced to its end on soft
/// springs: it tips about its toe. By hand: with the toe alone on the ground, moments about
/// it give 5000·p·0.5 = 2000·(1 + 0.75 + 0.5 + 0.25 + 0) N·m (the heel's spring acts at the
/// toe's height), so p = 2 whatever the spring, and the mechanism is a rotation about the
/// toe: each pair lifts in proportion to its distance from it (1, 0.75, 0.5, 0.25, 0). On
/// the condensed data the tipping direction's load rate is round-off of the spring's
/// stiffness contrast (1.7e-8 of the column at 300 N/m): the path stepped back to p = 0 (a
/// "return to zero", 300 and 178 N/m) or on into a singular basis (exit 1: 100 N/m, and in
/// kN·mm); now that direction, which moves only displacements, is judged on the structure's
/// equations (`docs/engine.md`, "Near-mechanisms").
#[test]
fn a_block_on_a_soft_spring_tips_at_the_load_by_hand() {
    let end = SolveSettings {
        follow: Follow::ToEnd,
        ..settings()
    };
    for (k, kn_mm) in [
        (300.0, false),
        (178.0, false),
        (100.0, false),
        (100.0, true),
    ] {
        let p = read("s.toml", &steel_block_on_a_spring(k, kn_mm)).unwrap();
        let a = analyze(&p.model, &end).unwrap();
        let unilateral_analysis::Outcome::Mechanism { p_limit, mode } = &a.solution.outcome else {
            panic!("k = {k}, kN·mm {kn_mm}: {:?}", a.solution.outcome);
        };
        // The data's conditioning (a stiffness contrast of 1e9) leaves 2e-6 at 100 N/m.
        assert!(
            (p_limit - 2.0).abs() < 1e-5 * 2.0,
            "k = {k}, kN·mm {kn_mm}: {p_limit}"
        );
        let lift: Vec<f64> = mode.iter().map(|m| m.0).collect();
        for (i, d) in [1.0, 0.75, 0.5, 0.25, 0.0].iter().enumerate() {
            assert!(
                (lift[i] / lift[0] - d).abs() < 1e-6,
                "k = {k}, kN·mm {kn_mm}: {lift:?}"
            );
        }
    }
    // Asked for a target beyond the tipping, the answer is the state at the limit load. On
    // 150 and 200 N/m its point formed on the condensed data left the structure out of
    // balance beyond the data's round-off (refused as unresolvable, exit 2); formed again on
    // the structure's equations, the toe carries the weight to 2e-8 of it.
    for k in [150.0, 200.0] {
        let p = read("s.toml", &steel_block_on_a_spring(k, false)).unwrap();
        let beyond = SolveSettings {
            target: 2.5,
            ..settings()
        };
        let a = analyze(&p.model, &beyond).unwrap_or_else(|e| panic!("k = {k}: {e}"));
        let unilateral_analysis::Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
            panic!("k = {k}: {:?}", a.solution.outcome);
        };
        assert!((p_limit - 2.0).abs() < 1e-5 * 2.0, "k = {k}: {p_limit}");
        assert_eq!(a.solution.p, Some(p_limit));
        let weight: f64 = a.solution.pairs.iter().map(|r| r.x_n).sum();
        assert!(
            (weight - 10000.0).abs() < 1e-7 * 10000.0,
            "k = {k}: {weight}"
        );
        assert!(a.results.is_some());
    }
}

/// [`steel_block_pushed`] held by a spring of `k` N/m at its heel, in N and m or in kN and mm
/// (the same block: E = 2e11 Pa = 200 kN/mm², 1 m = 1000 mm, 2000 N = 2 kN, k N/m =
/// k·1e-6 kN/mm).
fn steel_block_on_a_spring(k: f64, kn_mm: bool) -> String {
    let spring = format!(
        "\n[[springs]]\nnodes = \"blk.bottom_left\"\ndirection = [1.0, 0.0]\nstiffness = {k:e}\n"
    );
    let text = steel_block_pushed(&spring);
    if !kn_mm {
        return text;
    }
    text.replace("units = \"N, m\"", "units = \"kN, mm\"")
        .replace("E = 2.0e11", "E = 200.0")
        .replace("thickness = 1.0", "thickness = 1000.0")
        .replace("width = 1.0", "width = 1000.0")
        .replace("height = 0.5", "height = 500.0")
        .replace("fy = -2000.0", "fy = -2.0")
        .replace("fx = 5000.0", "fx = 5.0")
        .replace(
            &format!("stiffness = {k:e}"),
            &format!("stiffness = {:e}", k * 1e-6),
        )
}

/// The pairs that open along a path or a history's stage, in order, each with the load at its
/// step (`(load, events)` a step).
fn openings<'a>(
    steps: impl Iterator<Item = (f64, &'a [unilateral_contact::Event])>,
) -> Vec<(String, f64)> {
    steps
        .flat_map(|(p, events)| {
            events
                .iter()
                .filter(|e| e.kind == EventKind::Opens)
                .map(move |e| (e.name.clone(), p))
        })
        .collect()
}

/// The steel block pushed past its heel's opening opens `g.1`, `g.3` and `g.2` at these loads
/// of the push by statics, whatever the spring once every pair slides (the load path on a
/// spring of 1e5 N/m, slips of a few centimetres).
const TOE_OPENINGS: [(&str, f64); 3] = [("g.1", 0.998489), ("g.3", 1.550983), ("g.2", 1.561481)];

/// `opens` are [`TOE_OPENINGS`], in order, each load within `tol`.
fn assert_toe_openings(opens: &[(String, f64)], tol: f64, what: &str) {
    let names: Vec<&str> = opens.iter().map(|(n, _)| n.as_str()).collect();
    let want: Vec<&str> = TOE_OPENINGS.iter().map(|(n, _)| *n).collect();
    assert_eq!(names, want, "{what}: {opens:?}");
    for ((_, p), (_, by_hand)) in opens.iter().zip(TOE_OPENINGS) {
        assert!((p - by_hand).abs() < tol, "{what}: {opens:?}");
    }
}

/// The steel block on a soft spring pushed on past its heel's opening (target 1.8): its toe
/// pairs open where they open on a stiff spring. Reference: by statics the forces do not depend
/// on the spring once every pair slides (the spring carries `5000·p − 3000`), so the loads at
/// which the pairs open are those of the same block on a spring of 1e5 N/m (slips of a few
/// centimetres, a well-conditioned path): `g.1` at 0.998489, `g.3` at 1.550983, `g.2` at
/// 1.561481. On 300 and 500 N/m (slips of 15 m, 1e9 times the block's strains) `g.3`'s normal
/// force fell at a quarter of the largest force rate, which the condensed data read as
/// round-off beside the slips' rates: the path passed its opening and opened `g.2` and `g.3`
/// together at 1.56403, a turning point between them.
#[test]
fn a_block_on_a_soft_spring_opens_its_toe_pairs_where_a_stiff_one_does() {
    let settings = SolveSettings {
        target: 1.8,
        ..settings()
    };
    let openings = |a: &unilateral_analysis::Analysis| {
        openings(a.solution.steps.iter().map(|s| (s.p, s.events.as_slice())))
    };
    let stiff = read("s.toml", &steel_block_on_a_spring(1e5, false)).unwrap();
    let reference = openings(&analyze(&stiff.model, &settings).unwrap());
    assert_toe_openings(&reference, 1e-6, "the stiff spring");
    for k in [300.0, 500.0] {
        for kn_mm in [false, true] {
            let p = read("s.toml", &steel_block_on_a_spring(k, kn_mm)).unwrap();
            let a = analyze(&p.model, &settings).unwrap_or_else(|e| panic!("k = {k}: {e}"));
            let got = openings(&a);
            assert_eq!(got.len(), 3, "k = {k}, kN·mm {kn_mm}: {got:?}");
            for ((name, p), (want, p_ref)) in got.iter().zip(&reference) {
                assert_eq!(name, want, "k = {k}, kN·mm {kn_mm}: {got:?}");
                // the conditioning of slips 1e9 times the strains (measured in N·m: 5.5e-7 at
                // most, the heel's opening 4.3e-7)
                assert!(
                    (p - p_ref).abs() < 3e-6 * p_ref,
                    "k = {k}, kN·mm {kn_mm}: {got:?} against {reference:?}"
                );
            }
            assert!(
                a.solution.steps.iter().all(|s| !s.turning),
                "k = {k}, kN·mm {kn_mm}: no turning point"
            );
        }
    }
}

/// The steel block on its heel's spring pushed past its tipping load: by hand it tips about
/// its toe where the push's moment about the toe equals the weight's, 5000·p·0.5 = 10 000·0.5,
/// at p = 2 (once the last pair but the toe has opened there, rotation about the toe moves the
/// heel's spring only to second order: a mechanism). On 1000 N/m the step after the last
/// opening had a load rate of 1.4e-9 of the column's largest (below its tolerance) that would
/// carry the load from 2 to 4 while moving the values 9 times their size, below the 100 that
/// made a step "runaway" and judged on the structure's equations: the path went on to the
/// toe's opening at p = 4.01 and then to a singular basis (exit 1). A step is now judged from
/// a runaway of 1 (`RUNAWAY`), and the path ends in the mechanism at 2 on every spring.
#[test]
fn a_block_pushed_past_its_tipping_load_is_a_mechanism_there_on_every_spring() {
    let settings = SolveSettings {
        target: 2.5,
        ..settings()
    };
    for k in [300.0, 1000.0, 1e5] {
        for kn_mm in [false, true] {
            let p = read("s.toml", &steel_block_on_a_spring(k, kn_mm)).unwrap();
            let a = analyze(&p.model, &settings)
                .unwrap_or_else(|e| panic!("k = {k}, kN·mm {kn_mm}: {e}"));
            let unilateral_analysis::Outcome::Mechanism { p_limit, .. } = a.solution.outcome else {
                panic!("k = {k}, kN·mm {kn_mm}: {:?}", a.solution.outcome);
            };
            assert!(
                (p_limit - 2.0).abs() < 2e-6,
                "k = {k}, kN·mm {kn_mm}: p_lim = {p_limit}"
            );
        }
    }
}

/// The steel block of [`a_slow_load_rate_still_reaches_the_target`] on springs of 178 and 100
/// N/m (in N·m and in kN·mm): 10⁻⁹ of the block's own stiffness, so that the load's rate
/// while every pair slides is below what the condensed data can tell from round-off. It was
/// read as a mechanism at p = 0.6 (the friction limit f·W = 3000 N). By hand: once every
/// pair slides (p ≥ 0.6) the spring carries 5000·p − 3000, so at p = 1 the block has slid
/// (5000 − 3000)/k (11.2 m, 20 m), the friction is f·W and the normal forces carry W. The
/// heel opens where it opens on a stiff spring (k = 1e5 N/m, slips of 2 cm): the spring
/// force at p does not depend on k, only the slip does.
#[test]
fn a_block_on_a_spring_a_billionth_of_its_stiffness_slides_to_the_target() {
    let heel_opens = |a: &unilateral_analysis::Analysis| -> f64 {
        a.solution
            .steps
            .iter()
            .find(|s| s.events.iter().any(|e| e.kind == EventKind::Opens))
            .map(|s| s.p)
            .expect("the heel opens")
    };
    let stiff = read("s.toml", &steel_block_on_a_spring(1e5, false)).unwrap();
    let reference = heel_opens(&analyze(&stiff.model, &settings()).unwrap());
    assert!((reference - 0.998489).abs() < 1e-6, "{reference}");
    for k in [178.0, 100.0] {
        for kn_mm in [false, true] {
            let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
            let p = read("s.toml", &steel_block_on_a_spring(k, kn_mm)).unwrap();
            let a = analyze(&p.model, &settings()).unwrap_or_else(|e| panic!("k = {k}: {e}"));
            assert_eq!(
                a.solution.outcome,
                unilateral_analysis::Outcome::TargetReached,
                "k = {k}, kN·mm {kn_mm}"
            );
            assert_eq!(a.solution.p, Some(1.0));
            let slip = 2000.0 / k * length;
            let pairs = &a.solution.pairs;
            for r in pairs {
                assert!((r.z_t - slip).abs() < 1e-5 * slip, "k = {k}: {r:?}");
                if r.name == "g.1" {
                    assert_eq!(r.state, PairState::Open, "the heel: {r:?}");
                } else {
                    assert_eq!(r.state, PairState::SlipPlus, "{r:?}");
                    assert!(
                        (r.x_t + 0.3 * r.x_n).abs() < 1e-6 * 10000.0 * force,
                        "{r:?}"
                    );
                }
            }
            let sn: f64 = pairs.iter().map(|r| r.x_n).sum();
            let st: f64 = pairs.iter().map(|r| r.x_t).sum();
            assert!(
                (sn - 10000.0 * force).abs() < 1e-6 * 10000.0 * force,
                "Σ x_n = {sn}"
            );
            assert!(
                (st + 3000.0 * force).abs() < 1e-6 * 10000.0 * force,
                "Σ x_t = {st}"
            );
            // The path's states are the stiff spring's; the heel's opening load to the
            // conditioning of slips 1e9 times the block's strains (measured: 1.7e-6 at most).
            let opens = heel_opens(&a);
            assert!(
                (opens - reference).abs() < 3e-6 * reference,
                "k = {k}, kN·mm {kn_mm}: the heel opens at {opens}, {reference} on a stiff spring"
            );
            let r = a.results.as_ref().expect("the structure at p = 1");
            assert!(r.equilibrium.relative() <= 1e-6, "{:?}", r.equilibrium);
        }
    }
    // On 10 N/m the slips (200 m) make forces 2.3e9 times the state's: the state at p = 1
    // cannot be resolved in double precision, and is refused as such (the model's limit, not
    // a mechanism nor the program's failure).
    let p = read("s.toml", &steel_block_on_a_spring(10.0, false)).unwrap();
    let e = analyze(&p.model, &settings()).unwrap_err();
    assert!(
        matches!(e, unilateral_analysis::AnalysisError::Unresolved { .. }),
        "{e}"
    );
}

/// [`steel_block_on_a_spring`] with its weight and push as load cases `weight` and `push`, in
/// a history of the weight and then the pushes `pushes` (`(stage name, factor)`), analysed.
fn analyze_block_history(
    k: f64,
    kn_mm: bool,
    pushes: &[(&str, f64)],
) -> Result<unilateral_analysis::HistoryAnalysis, unilateral_analysis::AnalysisError> {
    let text = steel_block_on_a_spring(k, kn_mm)
        .replace("[[loads.constant.nodal]]", "[[loads.weight.nodal]]")
        .replace("[[loads.variable.nodal]]", "[[loads.push.nodal]]");
    analyze_with_history(&text, ("weight", "weight"), "push", pushes)
}

/// The model `model` (a model file's text) with a history, analysed: a first stage
/// `first.0` of its load group `first.1` at 1, then the stages `pushes` (`(stage name,
/// factor)`) of the load group `group`.
fn analyze_with_history(
    model: &str,
    first: (&str, &str),
    group: &str,
    pushes: &[(&str, f64)],
) -> Result<unilateral_analysis::HistoryAnalysis, unilateral_analysis::AnalysisError> {
    let (stage, loads) = first;
    let mut text = model.to_string();
    text.push_str(&format!(
        "\n[[history]]\nname = \"{stage}\"\nfactors = {{ {loads} = 1.0 }}\n"
    ));
    for (name, f) in pushes {
        text.push_str(&format!(
            "\n[[history]]\nname = \"{name}\"\nfactors = {{ {group} = {f} }}\n"
        ));
    }
    analyze_history_text(&text)
}

/// The steel block's history — its weight, then a push to 1.7 or 1.9 — on a stiff spring and on
/// 1000 N/m: the push stage opens the heel and then the two toe pairs at the loads statics give
/// the load path (`g.1` at 0.998489, `g.3` at 1.550983, `g.2` at 1.561481 of the push:
/// [`a_block_on_a_soft_spring_opens_its_toe_pairs_where_a_stiff_one_does`], whatever the spring
/// once every pair slides), and ends with the open pairs free of friction. The stage's values,
/// formed at each breakpoint with the updated inverse alone, broke the friction relations by
/// 1e-4 of the forces after the third opening: `g.2` ended open carrying 0.06 N of friction
/// and the stage failed its check (a numerical failure). They are now refined once from the
/// data at each breakpoint (`Pivoter::rebase`).
#[test]
fn a_block_pushed_past_its_toe_openings_in_a_history_opens_them_where_the_path_does() {
    for k in [1e5, 1000.0] {
        for f in [1.7, 1.9] {
            let a = block_history(k, false, &[("push", f)]);
            let st = &a.history.stages[1];
            let opens = openings(st.steps.iter().map(|s| (s.s * f, s.events.as_slice())));
            assert_toe_openings(&opens, 2e-6, &format!("k = {k}, push {f}"));
            for r in &st.pairs {
                if r.state == PairState::Open {
                    assert!(
                        r.x_n == 0.0 && r.x_t.abs() < 1e-6 * 2000.0,
                        "k = {k}, push {f}: {r:?}"
                    );
                }
            }
            assert!(
                st.residual.max() <= 1e-8,
                "k = {k}, push {f}: {:?}",
                st.residual
            );
        }
    }
}

/// An 8×4 steel block (1 m × 0.5 m, 2000 N down at each of its 9 top nodes, W = 18 kN; f =
/// 0.3) held by a 1000 N/m spring, in five stages: its weight, a push of 6 kN at the top right
/// corner, back to 5 and to 1.5 kN, then on to 12.5 kN. By hand (a rigid block on a friction
/// slider and the spring): the block slides once the push less the spring's force exceeds
/// f·W = 5400 N, so the first push leaves a slip of 0.6 m, the unloading stages stick, and the
/// last push slides it on from 6 kN to a slip of 7.1 m; the friction force at each stage's end
/// is the push less the spring's force. Once every pair slides the normal forces depend on the
/// load alone, so the last stage opens the heel pairs where the monotone load path does
/// (`g.1` at 1.31398, `g.2` at 2.13128 of the push). At `g.2`'s opening its normal row and its
/// friction part reach zero together; the stage's own tie-breaking let the friction part leave
/// and the basis turned singular (a numerical failure): the stage is now traced again with the
/// friction relations deciding its ties (`EvolutionSolver::stage_judged`).
#[test]
fn a_history_that_meets_a_singular_basis_at_a_tie_is_traced_again_by_the_relations() {
    let model = "units = \"N, m\"\n\
        [[materials]]\nname = \"steel\"\nE = 2.0e11\nnu = 0.3\nthickness = 1.0\n\
        [[blocks]]\nname = \"blk\"\norigin = [0.0, 0.0]\nwidth = 1.0\nheight = 0.5\n\
        nx = 8\nny = 4\nmaterial = \"steel\"\nanalysis = \"plane_stress\"\n\
        [[contact]]\nname = \"g\"\nfrom = \"ground\"\nto = \"blk.bottom\"\n\
        normal = [0.0, 1.0]\nfriction = 0.3\n\
        [[springs]]\nnodes = \"blk.bottom_left\"\ndirection = [1.0, 0.0]\nstiffness = 1000\n\
        [[loads.constant.nodal]]\nnodes = \"blk.top\"\nfy = -2000.0\n\
        [[loads.variable.nodal]]\nnodes = \"blk.top_right\"\nfx = 5000.0\n";
    let path = read("p.toml", model).unwrap();
    let end = SolveSettings {
        target: 2.5,
        ..settings()
    };
    let a = analyze(&path.model, &end).unwrap();
    let reference = openings(a.solution.steps.iter().map(|s| (s.p, s.events.as_slice())));
    let names: Vec<&str> = reference.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["g.1", "g.2"], "{reference:?}");
    assert!((reference[0].1 - 1.31398).abs() < 1e-5, "{reference:?}");
    assert!((reference[1].1 - 2.13128).abs() < 1e-5, "{reference:?}");

    let pushes = [
        ("push 1.2", 1.2),
        ("push 1", 1.0),
        ("back 0.3", 0.3),
        ("push 2.5", 2.5),
    ];
    let h = analyze_with_history(model, ("dead", "constant"), "variable", &pushes)
        .unwrap_or_else(|e| panic!("{e}"));
    let st = &h.history.stages;
    assert_eq!(st.len(), 5);
    let (w, cap, k) = (18000.0, 5400.0, 1000.0);
    let (mut slip, mut from) = (0.0f64, 0.0);
    for (stage, (_, push)) in st[1..].iter().zip(pushes) {
        assert_eq!(
            stage.status,
            unilateral_contact::StageStatus::Completed,
            "{}: {:?}",
            stage.name,
            stage.reason
        );
        // the slider by hand: the spring's force k·slip, the friction within ±cap
        let demand = 5000.0 * push - k * slip;
        if demand > cap {
            slip = (5000.0 * push - cap) / k;
        }
        let friction = -(5000.0 * push - k * slip);
        let sn: f64 = stage.pairs.iter().map(|r| r.x_n).sum();
        let st_: f64 = stage.pairs.iter().map(|r| r.x_t).sum();
        assert!((sn - w).abs() < 1e-6 * w, "{}: Σ x_n = {sn}", stage.name);
        assert!(
            (st_ - friction).abs() < 1e-6 * w,
            "{}: Σ x_t = {st_}, by hand {friction}",
            stage.name
        );
        for r in &stage.pairs {
            assert!((r.z_t - slip).abs() < 1e-5 * slip, "{}: {r:?}", stage.name);
        }
        if push > from {
            // the pushes: where the stage's pairs open, on the push's scale
            let opens = openings(
                stage
                    .steps
                    .iter()
                    .map(|s| (from + s.s * (push - from), s.events.as_slice())),
            );
            if push == 2.5 {
                assert_eq!(opens.len(), 2, "{opens:?}");
                for ((name, p), (want, p_ref)) in opens.iter().zip(&reference) {
                    assert_eq!(name, want, "{opens:?}");
                    assert!(
                        (p - p_ref).abs() < 1e-6 * p_ref,
                        "{opens:?} against {reference:?}"
                    );
                }
            } else {
                assert!(opens.is_empty(), "{}: {opens:?}", stage.name);
            }
        }
        from = push;
    }
}

/// The pairs of a block tipped about its toe, by hand: every pair slid `slip`; the toe `toe`
/// carries the weight `w` and the friction limit `f·w`; every other pair carries nothing — and,
/// with `open`, reads open with no normal force at all (a mechanism's state; at the end of a
/// completed stage the forces alone are checked).
fn assert_tipped(
    pairs: &[unilateral_contact::PairResult],
    toe: &str,
    (w, f, slip): (f64, f64, f64),
    open: bool,
    what: &str,
) {
    for r in pairs {
        assert!((r.z_t - slip).abs() < 1e-5 * slip, "{what}: {r:?}");
        if r.name == toe {
            assert!((r.x_n - w).abs() < 1e-6 * w, "{what}: the toe {r:?}");
            assert!((r.x_t + f * w).abs() < 1e-6 * w, "{what}: the toe {r:?}");
        } else if open {
            assert_eq!(r.state, PairState::Open, "{what}: {r:?}");
            assert!(r.x_n == 0.0 && r.x_t.abs() < 1e-6 * w, "{what}: {r:?}");
        } else {
            assert!(
                r.x_n.abs() < 1e-6 * w && r.x_t.abs() < 1e-6 * w,
                "{what}: {r:?}"
            );
        }
    }
}

/// The steel block on a 1e5 N/m spring, its weight and then a push to 2.5 in a history: by
/// hand (as on the load path, `a_block_pushed_past_its_tipping_load_is_a_mechanism_there_on_every_spring`)
/// it tips about its toe at a push of 2, the toe carrying the weight and the friction limit
/// f·W = 3000 N, the spring the rest of the 10 kN push (a slip of 7 cm). The stage's trace
/// found the mechanism after a pivot of no step (the toe's slip increment, zero since the last
/// breakpoint, stopped at a rate of round-off in the rotation) whose basis is singular in the
/// rotation: its values had the block rotated by 8 mm and the stage failed its check (3.5e-3).
/// A stage's mechanism now holds the state of the last step that moved, as that step formed
/// it. In kN·mm there was no such pivot, but the values formed afresh for the ray's judgement
/// failed the check too (a singular basis with the stage's own ties).
#[test]
fn a_block_pushed_past_its_tipping_load_in_a_history_is_a_mechanism_there() {
    use unilateral_contact::StageStatus;
    for kn_mm in [false, true] {
        let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let a = analyze_block_history(1e5, kn_mm, &[("push", 2.5)])
            .unwrap_or_else(|e| panic!("kN·mm {kn_mm}: {e}"));
        let st = &a.history.stages[1];
        assert_eq!(
            st.status,
            StageStatus::Mechanism,
            "kN·mm {kn_mm}: {:?}",
            st.reason
        );
        let push = 2.5 * st.s_end;
        assert!((push - 2.0).abs() < 1e-6, "kN·mm {kn_mm}: tips at {push}");
        assert!(
            st.residual.max() <= 1e-8,
            "kN·mm {kn_mm}: {:?}",
            st.residual
        );
        let w = 10000.0 * force;
        let what = format!("kN·mm {kn_mm}");
        assert_tipped(&st.pairs, "g.5", (w, 0.3, 0.07 * length), true, &what);
    }
}

/// Two blocks of a reviewer's sweep (3 × 4 elements, 1 m × 0.5 m, 2000 N down at each of the
/// 4 top nodes, W = 8 kN; a heel spring of 562 N/m; 5000 N·P at the top right corner), their
/// weight and then a push past tipping, P_tip = W·b / (2·h·5000) = 1.6: friction 0.34 in
/// N·m, 0.48 in kN·mm. By hand the stage ends in the mechanism at 1.6, the toe `g.4` carrying
/// W and the friction limit f·W, the spring the rest (the block slid (8000 − f·W)/562 m).
/// In N·m the stage met a singular basis at P = 0.95, in kN·mm at 1.13: on a direction that
/// moved only displacements and took the load back, which the load path judges on the
/// structure's equations and a stage now does too
/// (`Pivoter::near_mechanism_taking_load_back`).
#[test]
fn a_block_tipping_in_a_history_on_a_soft_spring_is_the_mechanism_by_hand() {
    use unilateral_contact::StageStatus;
    for (f, push, kn_mm) in [(0.34, 2.1456, false), (0.48, 2.2208, true)] {
        let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let text = format!(
            "units = \"{units}\"\n\
             [[materials]]\nname = \"steel\"\nE = {e:e}\nnu = 0.3\nthickness = {l:e}\n\
             [[blocks]]\nname = \"blk\"\norigin = [0.0, 0.0]\nwidth = {l:e}\n\
             height = {h:e}\nnx = 3\nny = 4\nmaterial = \"steel\"\n\
             analysis = \"plane_stress\"\n\
             [[contact]]\nname = \"g\"\nfrom = \"ground\"\nto = \"blk.bottom\"\n\
             normal = [0.0, 1.0]\nfriction = {f}\n\
             [[springs]]\nnodes = \"blk.bottom_left\"\ndirection = [1.0, 0.0]\n\
             stiffness = {k:e}\n\
             [[loads.weight.nodal]]\nnodes = \"blk.top\"\nfy = {fy:e}\n\
             [[loads.push.nodal]]\nnodes = \"blk.top_right\"\nfx = {fx:e}\n\
             [[history]]\nname = \"weight\"\nfactors = {{ weight = 1.0 }}\n\
             [[history]]\nname = \"push\"\nfactors = {{ push = {push} }}\n",
            units = if kn_mm { "kN, mm" } else { "N, m" },
            e = 2e11 * force / (length * length),
            l = length,
            h = 0.5 * length,
            k = 562.0 * force / length,
            fy = -2000.0 * force,
            fx = 5000.0 * force,
        );
        let p = read("h.toml", &text).unwrap();
        let stages = p.history.clone().expect("a history");
        let a = unilateral_analysis::analyze_history(&p.model, &stages, &p.settings.engine)
            .unwrap_or_else(|e| panic!("kN·mm {kn_mm}: {e}"));
        let st = &a.history.stages[1];
        assert_eq!(
            st.status,
            StageStatus::Mechanism,
            "kN·mm {kn_mm}: {:?}",
            st.reason
        );
        let tips = push * st.s_end;
        assert!(
            (tips - 1.6).abs() < 1e-6 * 1.6,
            "kN·mm {kn_mm}: tips at {tips}"
        );
        let w = 8000.0 * force;
        let slip = (8000.0 - f * 8000.0) / 562.0 * length;
        let what = format!("kN·mm {kn_mm}");
        assert_tipped(&st.pairs, "g.4", (w, f, slip), true, &what);
    }
}

/// The steel block (4 × 2 elements, W = 10 kN, f = 0.3) on 1000 and 1e5 N/m, its weight and
/// then a push to exactly its tipping load, 2 (N·m and kN·mm). By hand, at 2 the toe carries W
/// and f·W, the spring the rest of the 10 kN push (slips of 7 m and 7 cm), every other pair
/// open: the stage's end (completed) or its mechanism there are the same state. At the tipping
/// the last pair but the toe opens at constant load, and the toe's slip increment, zero since
/// the breakpoint, read a rate of round-off in the rotation: the pivot took it and the next
/// basis was singular (a numerical failure in N·m). Such a step is now judged on the
/// structure's equations, where the rotation is the mechanism.
#[test]
fn a_block_pushed_to_its_tipping_load_in_a_history_ends_there_by_hand() {
    use unilateral_contact::StageStatus;
    for k in [1000.0, 1e5] {
        for kn_mm in [false, true] {
            let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
            let a = analyze_block_history(k, kn_mm, &[("push", 2.0)])
                .unwrap_or_else(|e| panic!("k = {k}, kN·mm {kn_mm}: {e}"));
            let st = &a.history.stages[1];
            assert!(
                matches!(st.status, StageStatus::Completed | StageStatus::Mechanism),
                "k = {k}, kN·mm {kn_mm}: {:?}",
                st.reason
            );
            let reached = 2.0 * st.s_end;
            assert!((reached - 2.0).abs() < 1e-6 * 2.0, "k = {k}: {reached}");
            let w = 10000.0 * force;
            let slip = 7000.0 / k * length;
            let what = format!("k = {k}, kN·mm {kn_mm}");
            assert_tipped(&st.pairs, "g.5", (w, 0.3, slip), false, &what);
        }
    }
}

/// [`analyze_block_history`]; every stage must complete.
fn block_history(
    k: f64,
    kn_mm: bool,
    pushes: &[(&str, f64)],
) -> unilateral_analysis::HistoryAnalysis {
    use unilateral_contact::StageStatus;
    let a = analyze_block_history(k, kn_mm, pushes)
        .unwrap_or_else(|e| panic!("k = {k}, kN·mm {kn_mm}: {e}"));
    let st = &a.history.stages;
    assert!(
        st.iter().all(|s| s.status == StageStatus::Completed),
        "k = {k}, kN·mm {kn_mm}: {:?}",
        st.iter()
            .map(|s| (&s.status, &s.reason))
            .collect::<Vec<_>>()
    );
    a
}

/// A T-footing (a frame: a 2 m foot on three frictional supports, f = 0.3, a 1 m column) under
/// 100 kN down and 10 kN·p sideways at the column's top, held there by a spring of 1 N/m. By
/// hand every support slides at `p = f·W/H = 3`; past it the spring holds the frame, the load
/// growing with the slide (a ray, not a mechanism). In kN·mm the path read a mechanism at 3:
/// the structure's equations judged the spring's load rate against their largest terms, and in
/// mm the column's moment equations outweigh its force equations a thousand times more than
/// in m. The equations are now weighted to common units (`schur/judge.rs`, `row_weights`):
/// both units give the ray from 3 (a reviewer's sweep: nine runs of T-footings on 1 N/m
/// springs in kN·mm agree with N·m now).
#[test]
fn a_frame_on_a_soft_spring_slides_alike_in_newtons_and_metres_and_in_kilonewtons_and_millimetres()
{
    let frame = |kn_mm: bool| {
        let (l, f, k, e, a, i) = if kn_mm {
            (1000.0, 1e-3, 1e-6, 210.0, 5e4, 1e9)
        } else {
            (1.0, 1.0, 1.0, 2.1e11, 0.05, 1e-3)
        };
        let units = if kn_mm { "kN, mm" } else { "N, m" };
        format!(
            "units = \"{units}\"\n\
             [[sections]]\nname = \"s\"\nE = {e:e}\nA = {a:e}\nI = {i:e}\n\
             [[members]]\nname = \"foot\"\nstart = [{m:e}, 0.0]\nend = [{l:e}, 0.0]\n\
             divisions = 2\nsection = \"s\"\n\
             [[members]]\nname = \"col\"\nstart = \"foot.1\"\nend = [0.0, {l:e}]\n\
             divisions = 2\nsection = \"s\"\n\
             [[contact]]\nname = \"base\"\nfrom = \"ground\"\nto = \"foot.nodes\"\n\
             normal = [0.0, 1.0]\nfriction = 0.3\n\
             [[springs]]\nnodes = \"col.end\"\ndirection = [1.0, 0.0]\nstiffness = {k:e}\n\
             [[loads.constant.nodal]]\nnodes = \"col.end\"\nfy = {fy:e}\n\
             [[loads.variable.nodal]]\nnodes = \"col.end\"\nfx = {fx:e}\n",
            m = -l,
            fy = -1e5 * f,
            fx = 1e4 * f,
        )
    };
    let end = SolveSettings {
        follow: Follow::ToEnd,
        ..settings()
    };
    for kn_mm in [false, true] {
        let p = read("t.toml", &frame(kn_mm)).unwrap();
        let a = analyze(&p.model, &end).unwrap_or_else(|e| panic!("kN·mm {kn_mm}: {e}"));
        let unilateral_analysis::Outcome::Ray { p_from } = a.solution.outcome else {
            panic!("kN·mm {kn_mm}: {:?}", a.solution.outcome);
        };
        assert!((p_from - 3.0).abs() < 1e-6 * 3.0, "kN·mm {kn_mm}: {p_from}");
    }
}

/// A stage the engine fails in (a singular basis, or an end state that fails its check) has
/// no state of the structure to recover: its results are left out and the history is reported
/// with the stage's own reason. They were recovered and refused as "out of balance", an error
/// in place of the history that hid the reason. The steel block on 300 N/m, its weight and then
/// a push to 1.6 (past the opening of three of its pairs), is such a history in this version
/// (its second stage's end fails its check; `docs/history.md`); whatever the stages' statuses,
/// the stages recovered are those before the first that failed.
#[test]
fn a_stage_the_engine_failed_in_is_not_recovered() {
    let a = analyze_block_history(300.0, false, &[("push", 1.6)]).unwrap_or_else(|e| panic!("{e}"));
    let sound = a
        .history
        .stages
        .iter()
        .take_while(|s| s.status != unilateral_contact::StageStatus::NumericalFailure)
        .count();
    assert_eq!(a.stage_results.len(), sound);
    assert!(sound >= 1, "{:?}", a.history.stages[0].status);
}

/// A history whose end cannot be resolved in double precision names the point by its stage
/// and the stage's parameter: the block on a 10 N/m spring (slips of 200 m, forces of 1e13 N
/// term by term against 5000 N) pushed to 1 in its second stage. Errors called it "p = 2",
/// the stage's pseudo-time, which the user never wrote.
#[test]
fn a_history_that_cannot_be_resolved_names_the_stage() {
    let e = analyze_block_history(10.0, false, &[("push", 1.0)]).expect_err("slips of 200 m");
    let unilateral_analysis::AnalysisError::Unresolved { at, .. } = &e else {
        panic!("{e}");
    };
    assert_eq!(*at, unilateral_analysis::Place::Stage { stage: 2, s: 1.0 });
    assert!(
        e.to_string()
            .starts_with("the results at s = 1 of stage 2 cannot"),
        "{e}"
    );
    // The block has no gap: the advice is about the slips alone (it named gaps the model
    // does not have).
    assert!(e.to_string().contains("dislocations (slips)"), "{e}");
    assert!(!e.to_string().contains("gap"), "{e}");
}

/// A steel block (2 m × 1 m, 8 × 3 elements, friction 0.38, weight 9271 N) held sideways by a
/// 1 N/m spring and pushed by 8622.03 N in a history's second stage: by hand it slides
/// (8622.03 − 0.38·9271)/1 = 5099.05 m, slips that make forces of 1e15 N term by term
/// against loads of 3e3 N — their round-off alone (64 ε of them) is 1e-3 of the loads, and no
/// state can pass the stage's check (1e-8). The trace reached the slip (every pair within
/// 1e-4 of it) but its state failed the check, and the stage read "numerical failure, the
/// program's fault" (exit 1): it is now `unresolved`, the data's conditioning, with the sizes
/// and the advice. N·m and kN·mm.
#[test]
fn a_block_sliding_kilometres_in_a_history_stage_is_unresolved_at_its_slip_by_hand() {
    let slip = (8622.03 - 0.38 * 9271.0) / 1.0;
    for kn_mm in [false, true] {
        let text = block_history_text((8, 3, 2.0, 1.0), (0.38, 1.0, 9271.0), &[0.862203], kn_mm);
        let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("kN·mm {kn_mm}: {e}"));
        let last = last_stage_unresolved(&a, &format!("kN·mm {kn_mm}"));
        let reason = last.reason.as_deref().unwrap_or_default();
        assert!(
            reason.contains("cannot be resolved in double precision")
                && reason.contains("keep the slips short")
                && !reason.contains("program's fault"),
            "kN·mm {kn_mm}: {reason}"
        );
        let unit = if kn_mm { 1e3 } else { 1.0 };
        for p in &last.pairs {
            assert!(
                (p.z_t - slip * unit).abs() <= 1e-4 * slip * unit,
                "kN·mm {kn_mm}, {}: z_t = {} against {}",
                p.name,
                p.z_t,
                slip * unit
            );
        }
        // No state of the failed stage is recovered.
        assert_eq!(a.stage_results.len(), 1, "kN·mm {kn_mm}");
    }
}

/// The last stage of `a`, which must have ended `unresolved`.
fn last_stage_unresolved<'a>(
    a: &'a unilateral_analysis::HistoryAnalysis,
    what: &str,
) -> &'a unilateral_contact::StageSolution {
    let last = a.history.stages.last().expect("a stage");
    assert_eq!(
        last.status,
        unilateral_contact::StageStatus::Unresolved,
        "{what}: {:?}",
        last.reason
    );
    last
}

/// The 40 histories of a generated sweep of 100 (blocks of 2–8 × 1–4 elements, three
/// proportions, friction 0.2–0.5, weights of 8–10 kN, heel springs of 0.1–10 N/m, pushed to
/// 0.5–1.5 of the tipping load, then perhaps pulled back; half in kN·mm) that failed as the
/// program's fault (exit 1): slips of kilometres, states beyond double precision. Each now
/// ends `unresolved` in the stage where the check or the trace failed, or is refused as
/// unresolvable where its last state is recovered — never a numerical failure or an internal
/// error.
#[test]
fn blocks_sliding_kilometres_on_soft_springs_in_histories_are_unresolved_not_failed() {
    // ((nx, ny, B, H), (f, k, W), pushes, kN·mm): one case a line.
    #[allow(clippy::type_complexity)]
    #[rustfmt::skip]
    let cases: &[((usize, usize, f64, f64), (f64, f64, f64), &[f64], bool)] = &[
        ((3, 3, 1.0, 0.5), (0.42, 10.0, 9873.0), &[1.48095], true),
        ((4, 3, 2.0, 1.0), (0.47, 10.0, 9218.0), &[0.9218, -0.4609], false),
        ((6, 2, 1.0, 1.0), (0.32, 2.0, 8829.0), &[0.52974, -0.220725], true),
        ((8, 3, 2.0, 1.0), (0.38, 1.0, 9271.0), &[0.862203], false),
        ((6, 2, 1.0, 1.0), (0.28, 2.0, 8909.0), &[0.44545], true),
        ((2, 3, 2.0, 1.0), (0.3, 1.0, 8517.0), &[1.27755, -0.42585], true),
        ((4, 1, 1.0, 0.5), (0.29, 2.0, 9488.0), &[0.939312], true),
        ((8, 4, 2.0, 1.0), (0.21, 1.0, 9715.0), &[1.1658], false),
        ((4, 4, 1.0, 0.5), (0.28, 0.1, 9675.0), &[0.957825, -0.48375], false),
        ((8, 2, 2.0, 1.0), (0.23, 10.0, 9564.0), &[1.14768, -0.4782], true),
        ((4, 4, 1.0, 0.5), (0.28, 10.0, 9556.0), &[1.4334, 0.0], false),
        ((6, 3, 1.0, 0.5), (0.35, 1.0, 8359.0), &[0.777387, 0.0], true),
        ((7, 1, 2.0, 1.0), (0.45, 10.0, 9608.0), &[1.4412, -0.4804], false),
        ((6, 4, 1.0, 0.5), (0.38, 1.0, 8972.0), &[0.888228, -0.4486], true),
        ((7, 4, 1.0, 1.0), (0.39, 1.0, 8477.0), &[0.42385], true),
        ((7, 3, 1.0, 0.5), (0.35, 1.0, 8624.0), &[1.03488, 0.0], false),
        ((3, 4, 1.0, 1.0), (0.23, 0.1, 9793.0), &[0.58758, 0.0], false),
        ((5, 3, 2.0, 1.0), (0.35, 1.0, 9088.0), &[1.09056], false),
        ((7, 1, 2.0, 1.0), (0.46, 1.0, 9942.0), &[0.9942, 0.0], true),
        ((3, 3, 2.0, 1.0), (0.24, 5.0, 9919.0), &[1.19028, -0.49595], true),
        ((5, 1, 1.0, 1.0), (0.29, 1.0, 8758.0), &[0.407247, -0.21895], false),
        ((5, 1, 1.0, 0.5), (0.39, 10.0, 8484.0), &[0.789012, 0.0], true),
        ((4, 4, 2.0, 1.0), (0.46, 1.0, 9141.0), &[0.904959], true),
        ((3, 1, 1.0, 1.0), (0.31, 2.0, 8874.0), &[0.53244, 0.0], false),
        ((2, 1, 2.0, 1.0), (0.42, 2.0, 8610.0), &[1.2915, -0.4305], true),
        ((5, 4, 2.0, 1.0), (0.46, 10.0, 9949.0), &[1.49235], false),
        ((7, 4, 2.0, 1.0), (0.45, 0.1, 9631.0), &[0.953469, 0.0], false),
        ((8, 4, 1.0, 1.0), (0.36, 1.0, 8924.0), &[0.414966, 0.0], true),
        ((6, 1, 2.0, 1.0), (0.35, 10.0, 8845.0), &[1.32675, 0.0], true),
        ((4, 2, 2.0, 1.0), (0.49, 1.0, 9688.0), &[1.16256, 0.0], true),
        ((4, 4, 1.0, 0.5), (0.44, 1.0, 8145.0), &[0.9774, 0.0], false),
        ((5, 3, 2.0, 1.0), (0.43, 1.0, 8232.0), &[1.2348, 0.0], true),
        ((8, 1, 1.0, 0.5), (0.4, 5.0, 9408.0), &[1.12896, 0.0], false),
        ((5, 2, 1.0, 0.5), (0.27, 2.0, 8925.0), &[0.830025, 0.0], false),
        ((8, 1, 2.0, 1.0), (0.3, 5.0, 9696.0), &[0.901728, 0.0], true),
        ((3, 2, 1.0, 0.5), (0.2, 1.0, 9753.0), &[1.17036, 0.0], false),
        ((4, 2, 1.0, 0.5), (0.22, 10.0, 8351.0), &[1.25265, -0.41755], true),
        ((7, 1, 2.0, 1.0), (0.36, 10.0, 8399.0), &[0.8399, -0.41995], false),
        ((3, 4, 1.0, 0.5), (0.22, 0.1, 9825.0), &[1.179, 0.0], false),
        ((8, 4, 1.0, 0.5), (0.42, 2.0, 9470.0), &[0.947], true),
    ];
    let (mut stages, mut recoveries) = (0, 0);
    for (i, &(mesh, block, pushes, kn_mm)) in cases.iter().enumerate() {
        let text = block_history_text(mesh, block, pushes, kn_mm);
        match analyze_history_text(&text) {
            Ok(a) => {
                last_stage_unresolved(&a, &format!("case {i}"));
                stages += 1;
            }
            Err(e) => {
                assert!(
                    matches!(e, unilateral_analysis::AnalysisError::Unresolved { .. }),
                    "case {i}: {e}"
                );
                assert!(!e.is_internal(), "case {i}: {e}");
                recoveries += 1;
            }
        }
    }
    // Both routes are met: the stage's own check (30 of the sweep's) and the recovery's (10).
    assert!(
        stages > 0 && recoveries > 0,
        "{stages} stages, {recoveries} recoveries"
    );
}

/// A steel block (1 m × 0.5 m, 7 × 4 elements, friction 0.45) held sideways only by a
/// 178 N/m spring, its weight (8000 N) and then a push of 7440 N (below tipping, 8000 N): by
/// hand it slides (7440 − 0.45·8000)/178 = 21.6 m over eight pairs, slips that make forces of
/// 1e12 N a pair term by term against the state's 7440 N. Its link forces carry the round-off
/// of those terms summed over the pairs (0.03 N, 5e-6 of the forces): the check judged the
/// round-off by the largest pair's terms alone and called it the program's failure (exit 1);
/// the data's conditioning is the sum over the pairs, and the state is refused as
/// unresolvable (exit 2, the advice about the spring). N·m and kN·mm (a generated sweep's
/// model, one of 163 such failures on springs of 100 to 1000 N/m).
#[test]
fn a_block_sliding_metres_on_a_soft_spring_in_a_history_is_refused_as_unresolvable() {
    for kn_mm in [false, true] {
        // 7440 N: 0.744 of the block's 10 kN push.
        let text = block_history_text((7, 4, 1.0, 0.5), (0.45, 178.0, 8000.0), &[0.744], kn_mm);
        let e = analyze_history_text(&text).expect_err("slips of 21.6 m");
        assert!(
            matches!(e, unilateral_analysis::AnalysisError::Unresolved { .. }),
            "kN·mm {kn_mm}: {e}"
        );
        assert!(!e.is_internal(), "kN·mm {kn_mm}: {e}");
    }
}

/// The block of [`a_slow_load_rate_still_reaches_the_target`] on springs of 300 and 178 N/m
/// at its heel in a load history, its weight and then the push to 1 (in N·m and kN·mm). By
/// hand as on the path: every pair slides from 0.6, and at the end the block has slid
/// 2000/k m (6.67 m, 11.2 m), the heel open.
///
/// * 300 N/m: the open heel's tangential force is the round-off of terms of 7e11 N (metres of
///   slip times the links' stiffness), 6e-5 N. Against the largest force (4100 N) the final
///   state's check read it as a violation of 1.9e-8 of the signs and of complementarity,
///   above the 1e-8 allowed, and refused the stage as the program's failure (exit 1). A force
///   is now judged against its terms' round-off too.
/// * 178 N/m: the stage read a mechanism at the friction limit (s = 0.6), as the path did
///   before round 30; the structure's equations now drive the segment, with the rows that
///   the friction relations tie decided by them (as on the path).
#[test]
fn a_block_sliding_metres_in_a_load_history_passes_its_check() {
    for (k, kn_mm) in [(300.0, false), (300.0, true), (178.0, false), (178.0, true)] {
        let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let a = block_history(k, kn_mm, &[("push", 1.0)]);
        let st = &a.history.stages;
        let end = &st[1];
        assert!(end.residual.max() <= 1e-8, "{:?}", end.residual);
        let slip = 2000.0 / k * length;
        for r in &end.pairs {
            assert!((r.z_t - slip).abs() < 1e-5 * slip, "{r:?}");
            let expected = if r.name == "g.1" {
                PairState::Open
            } else {
                PairState::SlipPlus
            };
            assert_eq!(r.state, expected, "{r:?}");
        }
        let sn: f64 = end.pairs.iter().map(|r| r.x_n).sum();
        let st: f64 = end.pairs.iter().map(|r| r.x_t).sum();
        assert!(
            (sn - 10000.0 * force).abs() < 1e-6 * 10000.0 * force,
            "{sn}"
        );
        assert!((st + 3000.0 * force).abs() < 1e-6 * 10000.0 * force, "{st}");
    }
}

/// The block on 178 N/m pushed to 0.8, to 1, back to 0.3 and on to 1.5 (a reviewer's
/// history; N·m and kN·mm). By hand, a rigid block on its spring with the friction limit
/// f·W = 3000 N: it slides from the push 3000 N on, the spring carrying the push less 3000;
/// back at 0.3 (1500 N) it sticks, the ground holding it against the spring's 2000 N with
/// +500 N; pushed again it sticks until the push is 5000 N and slides on to a spring force of
/// 4500 N. The later stages slide on from metres of slip: their load rate is clear on the
/// condensed data, but the heel's unloading (3e-10 of the slips' terms) is not, and the stage
/// ran past the heel's opening into a structure out of balance (exit 1; a false mechanism at
/// the friction limit before round 30). Rows that the ratio test passes over and that would
/// reach zero within the segment are now judged on the structure's equations.
///
/// In kN·mm the last stage read a false mechanism where the heel opens again (s = 0.572 of
/// the push to 1.5), its normal force and its friction part reaching zero together on a step
/// of the condensed data, which a stage's pivoting (without the friction relations, which
/// made stiff-spring histories of a reviewer's sweep fail) splits by their round-off. A stage
/// that ends in a mechanism is now traced again with the relations deciding its ties, and
/// that trace is kept where it completes the stage and passes its check
/// (`unilateral_contact`'s history; genuine mechanisms: `beam_bearings.rs`, `history.rs`).
#[test]
fn a_block_on_a_soft_spring_pushed_back_and_forth_in_a_history_by_hand() {
    let k = 178.0;
    let pushes = [("0.8", 0.8), ("1", 1.0), ("back", 0.3), ("1.5", 1.5)];
    for kn_mm in [false, true] {
        let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let a = block_history(k, kn_mm, &pushes);
        let st = &a.history.stages;
        // (stage, spring force, Σ x_t): the slip is the spring's force over k.
        for (i, spring, friction) in [
            (1, 1000.0, -3000.0),
            (2, 2000.0, -3000.0),
            (3, 2000.0, 500.0),
            (4, 4500.0, -3000.0),
        ] {
            let pairs = &st[i].pairs;
            let slip = spring / k * length;
            for r in pairs {
                assert!(
                    (r.z_t - slip).abs() < 1e-5 * slip,
                    "kN·mm {kn_mm}, stage {i}: {r:?}"
                );
            }
            let sn: f64 = pairs.iter().map(|r| r.x_n).sum();
            let sx: f64 = pairs.iter().map(|r| r.x_t).sum();
            let w = 10000.0 * force;
            assert!((sn - w).abs() < 1e-6 * w, "kN·mm {kn_mm}, stage {i}: {sn}");
            assert!(
                (sx - friction * force).abs() < 1e-6 * w,
                "kN·mm {kn_mm}, stage {i}: {sx}"
            );
        }
        let heel = st[4].pairs.iter().find(|r| r.name == "g.1").unwrap();
        assert_eq!(heel.state, PairState::Open, "kN·mm {kn_mm}: {heel:?}");
    }
}

/// A steel block sliding on the ground (f = 0.3, W = 10 kN) into a stopper 1 mm away, pushed
/// at its top by 5000 N·p: it slides at p = 0.6, closes the gap at once (it moves freely), and
/// at p = 0.600006 the stopper carries the rest of the push, 5000·0.000006 = 0.03 N by hand.
/// That force is small beside the stopper's gap forces (1e11 N·m⁻¹ × 1 mm): the pair read
/// open with it, and its force was set to 0 — the structure then out of balance by it (exit 1).
/// The force stays, and the state with it (below).
#[test]
fn a_small_force_beside_large_gap_forces_is_kept() {
    let text = steel_block_pushed(STOPPER_1_MM_AWAY);
    let p = read("s.toml", &text).unwrap();
    let s = SolveSettings {
        target: 0.600006,
        ..settings()
    };
    let a = analyze(&p.model, &s).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.solution.p, Some(0.600006));
    let stopper: f64 = a
        .solution
        .pairs
        .iter()
        .filter(|r| r.name.starts_with("s."))
        .map(|r| r.x_n)
        .sum();
    assert!((stopper - 0.03).abs() < 1e-6, "stopper {stopper}");
    let friction: f64 = a
        .solution
        .pairs
        .iter()
        .filter(|r| r.name.starts_with("g."))
        .map(|r| r.x_t)
        .sum();
    assert!(
        (friction + 3000.0).abs() < 1e-6 * 3000.0,
        "friction {friction}"
    );

    // A softer block (E = 1e7) against a stopper 1000 m away, coarsely meshed (one stopper
    // pair): at p = 0.6006 the stopper carries 5000·0.0006 = 3 N by hand and is closed
    // (frictionless: slip−). Judged against a full share of its gap forces (1e7 N/m × 1000 m)
    // its 3 N read as round-off: "open" while it carries the push.
    let soft = text
        .replace("E = 2.0e11", "E = 1.0e7")
        .replace("nx = 4\nny = 2", "nx = 2\nny = 1")
        .replace("gap = 0.001", "gap = 1000.0")
        .replace("fy = -2000.0", "fy = -3333.3333333333335");
    assert!(soft.contains("gap = 1000.0") && soft.contains("ny = 1"));
    let p = read("soft.toml", &soft).unwrap();
    let s = SolveSettings {
        target: 0.6006,
        ..settings()
    };
    let a = analyze(&p.model, &s).unwrap_or_else(|e| panic!("{e}"));
    let stopper: Vec<_> = a
        .solution
        .pairs
        .iter()
        .filter(|r| r.name.starts_with('s'))
        .collect();
    assert_eq!(stopper.len(), 1, "{stopper:?}");
    assert!((stopper[0].x_n - 3.0).abs() < 1e-3, "{:?}", stopper[0]);
    assert_eq!(stopper[0].state, PairState::SlipMinus, "{:?}", stopper[0]);
}

/// A beam of span 2L = 4 m on three ground pairs (ends with gap 0, the middle with gap g),
/// loaded at mid-span by P: with the middle pair open the mid-span deflection is
/// δ = P(2L)³/(48EI) (simply supported); with g < δ the middle pair closes and carries
/// R = P − 48EI·g/(2L)³ (compatibility: (P − R)(2L)³/(48EI) = g); with g > δ it stays open.
/// Frictions per pair are read in the order of `to`.
#[test]
fn gap_and_friction_lists_per_pair_by_hand() {
    let (e, i, l, p): (f64, f64, f64, f64) = (2.0e11, 1.0e-5, 2.0, 1.0e4);
    let delta = p * (2.0 * l).powi(3) / (48.0 * e * i);
    for (g, touches) in [(0.4 * delta, true), (1.5 * delta, false)] {
        let text = format!(
            r#"units = "N, m"
[[sections]]
name = "beam"
E = {e}
A = 1.0e-2
I = {i}

[[members]]
name = "beam"
start = [0.0, 0.0]
end = [{span}, 0.0]
divisions = 2
section = "beam"

[[loads.variable.nodal]]
nodes = "beam.1"
fy = -{p}

[[contact]]
name = "s"
from = "ground"
to = ["beam.0", "beam.1", "beam.2"]
normal = [0.0, 1.0]
friction = [0.1, 0.2, 0.3]
gap = [0.0, {g}, 0.0]
"#,
            span = 2.0 * l
        );
        let prob = read("b.toml", &text).unwrap();
        let fr: Vec<f64> = prob.model.pairs().iter().map(|s| s.friction).collect();
        assert_eq!(fr, [0.1, 0.2, 0.3]);
        let a = analyze(&prob.model, &settings()).unwrap();
        let (pairs, _) = at_target(&a);
        let r_mid = if touches {
            p - 48.0 * e * i * g / (2.0 * l).powi(3)
        } else {
            0.0
        };
        assert!(
            (pairs[1].x_n - r_mid).abs() < 1e-9 * p,
            "g {g}: {:?}",
            pairs[1]
        );
        assert_eq!(
            pairs[1].state == PairState::Open,
            !touches,
            "{:?}",
            pairs[1]
        );
        for k in [0, 2] {
            assert!(
                (pairs[k].x_n - (p - r_mid) / 2.0).abs() < 1e-9 * p,
                "{:?}",
                pairs[k]
            );
        }
    }
}

/// `match = "nearest"`: each node of `to` with the nearest node of `from` within `search`
/// (reference: the positions, by hand: the top block's bottom nodes at x = 0, 1, 2 and the
/// base's top nodes at x = 0, 0.5, …, 2; the nearest of x = 1 is x = 1, and so on). A node of
/// `from` may take part in several pairs; the pairs carry the weight (statics).
#[test]
fn nearest_pairs_by_hand() {
    let entry = "[[contact]]\nname = \"n\"\nmatch = \"nearest\"\nsearch = 0.3\nfrom = \"top.bottom\"\nto = \"base.top\"\nnormal = [0.0, -1.0]\nfriction = 0.5\n";
    let p = read("n.toml", &two_blocks(4, 2, -100.0, 10.0, entry)).unwrap();
    let names = p.model.names();
    let pairs = p.model.pairs();
    // base.top x = 0, 0.5, 1, 1.5, 2 → top.bottom x = 0, (0 or 1: 0.5 is 0.5 away from both,
    // beyond search 0.3), 1, (beyond), 2
    let got: Vec<(String, String)> = pairs
        .iter()
        .map(|s| {
            let Endpoint::Node(a) = s.a else { panic!() };
            (names.nodes[a.0].clone(), names.nodes[s.b.0].clone())
        })
        .collect();
    assert_eq!(
        got,
        [
            ("top.0.0".to_string(), "base.0.2".to_string()),
            ("top.1.0".to_string(), "base.2.2".to_string()),
            ("top.2.0".to_string(), "base.4.2".to_string()),
        ]
    );
    // with a wider search, x = 0.5 and 1.5 find a partner too, 0.5 away from two nodes: the
    // tie goes to the node of `from` created first (top.0.0, top.1.0), which is then in two
    // pairs
    let entry = entry.replace("search = 0.3", "search = 0.6");
    let p = read("n.toml", &two_blocks(4, 2, -100.0, 10.0, &entry)).unwrap();
    let a_names: Vec<String> = p
        .model
        .pairs()
        .iter()
        .map(|s| {
            let Endpoint::Node(a) = s.a else { panic!() };
            names.nodes[a.0].clone()
        })
        .collect();
    assert_eq!(
        a_names,
        ["top.0.0", "top.0.0", "top.1.0", "top.1.0", "top.2.0"]
    );
    let a = analyze(&p.model, &settings()).unwrap();
    let (f, _) = at_target(&a);
    let sum: f64 = f.iter().map(|x| x.x_n).sum();
    // the weight: 100 at each of the 3 top nodes less the half at the 2 corners
    assert!((sum - 200.0).abs() < 1e-9 * 200.0, "Σ x_n = {sum}");
}

/// Every new error of `[[contact]]`, read through `read_model`: the file, line and key, and
/// the words that say what is wrong.
#[test]
fn contact_surface_errors_are_located() {
    let ok = "[[contact]]\nname = \"c\"\nmatch = \"surface\"\nsearch = 0.05\nfrom = \"base.top\"\nto = \"top.bottom\"\nnormal = \"surface\"\nfriction = 0.5\n";
    let cases: Vec<(String, &str, &str)> = vec![
        (
            ok.replace("match = \"surface\"", "match = \"surfce\""),
            ":45:9: contact[1].match",
            "unknown pair matching \"surfce\" (did you mean \"surface\"?)",
        ),
        (
            ok.replace("search = 0.05\n", ""),
            "contact[1].search",
            "missing key `search`",
        ),
        (
            ok.replace("match = \"surface\"\n", "").replace("normal = \"surface\"", "normal = [0.0, 1.0]"),
            ":45:10: contact[1].search",
            "`search` is for `match = \"nearest\"`",
        ),
        (
            ok.replace("match = \"surface\"", "match = \"nearest\""),
            "contact[1].normal",
            "`normal = \"surface\"` needs `match = \"surface\"`",
        ),
        (
            ok.replace("friction = 0.5", "friction = [0.5, 0.5]"),
            "contact[1].friction",
            "`friction` lists 2 values, but [contact[1]] makes 5 pairs",
        ),
        (
            ok.replace("friction = 0.5", "friction = [0.5, 0.5, -0.1, 0.5, 0.5]"),
            "contact[1].friction[3]",
            "the friction coefficient must be ≥ 0, got -0.1",
        ),
        (
            ok.replace("search = 0.05", "search = 0.05\ngap = \"geometric\""),
            "contact[1].gap",
            "(did you mean \"geometry\"?)",
        ),
        (
            ok.replace("to = \"top.bottom\"", "to = \"top.top\""),
            "contact[1]",
            "makes no pairs (no node of `to` has a partner in `from` within `search` = 0.05)",
        ),
        (
            ok.replace("from = \"base.top\"", "from = [\"base.0.0\", \"base.4.2\"]"),
            "contact[1].from",
            "`from` is not a surface",
        ),
        (
            ok.replace("from = \"base.top\"", "from = \"ground\""),
            "contact[1].match",
            "the rigid ground has no position to match",
        ),
        (
            "[[contact]]\nfrom = \"ground\"\nto = \"top.bottom\"\nnormal = [0.0, 1.0]\nfriction = 0.5\ngap = \"geometry\"\n".to_string(),
            "contact[1].gap",
            "with `from = \"ground\"` give the gap as a number or a list",
        ),
    ];
    for (entry, place, words) in cases {
        let text = two_blocks(4, 4, -100.0, 10.0, &entry);
        let e = read("bad.toml", &text).expect_err(words);
        println!("{e}");
        assert!(e.contains("bad.toml"), "{e}");
        assert!(e.contains(place), "{e}\n lacks {place}");
        assert!(e.contains(words), "{e}\n lacks {words}");
    }
    // the member's first node 0.5 below the base's top: the bodies overlap
    let e = read("bad.toml", &beam_above_base(0.5)).unwrap_err();
    println!("{e}");
    assert!(
        e.contains(
            "bad.toml:50:7: contact[1].gap: contact pair `g.1`: node `beam.0` is 0.5 inside"
        ),
        "{e}"
    );
}

/// `normal = "surface"` at a corner of a surface: the surface `base.left` then `base.top`
/// (bottom to top, then left to right; the corner once) has at the corner (0, 1) the average
/// of the outward normals (−1, 0) and (0, 1), i.e. (−1, 1)/√2; a node at (−0.1, 1.1) projects
/// on the corner, and its gap from the geometry is n·(x_B − x_A) = 0.2/√2 (by hand). A node
/// at (0.5, 1.3) projects inside the top's first segment (ξ = 0.5 of [0, 1]), normal (0, 1),
/// gap 0.3. A node beyond `search` makes no pair.
#[test]
fn surface_normal_at_a_corner_by_hand() {
    let text = r#"units = "N, m"
[[materials]]
name = "soft"
E = 2.0e7
nu = 0.3

[[blocks]]
name = "base"
origin = [0.0, 0.0]
width = 2.0
height = 1.0
nx = 2
ny = 1
material = "soft"
analysis = "plane_strain"

[[nodes]]
id = "p"
x = -0.1
y = 1.1

[[nodes]]
id = "q"
x = 0.5
y = 1.3

[[nodes]]
id = "far"
x = 5.0
y = 5.0

[[loads.variable.nodal]]
nodes = "q"
fy = -1.0

[[contact]]
name = "c"
match = "surface"
search = 0.5
from = ["base.left", "base.top"]
to = ["p", "q", "far"]
normal = "surface"
friction = 0.3
gap = "geometry"
"#;
    let p = read("corner.toml", text).unwrap();
    let pairs = p.model.pairs();
    assert_eq!(pairs.len(), 2);
    let names = p.model.names();
    let Endpoint::Node(a) = pairs[0].a else {
        panic!()
    };
    assert_eq!(names.nodes[a.0], "base.0.1");
    assert!(pairs[0].segment.is_none());
    let r = std::f64::consts::FRAC_1_SQRT_2;
    let n = pairs[0].normal;
    assert!(
        (n[0] + r).abs() < 1e-15 && (n[1] - r).abs() < 1e-15,
        "{n:?}"
    );
    assert!((pairs[0].gap - 0.2 * r).abs() < 1e-15, "{}", pairs[0].gap);
    let n = pairs[1].normal;
    assert!(n[0].abs() < 1e-15 && (n[1] - 1.0).abs() < 1e-15, "{n:?}");
    let Some((_, xi)) = pairs[1].segment else {
        panic!()
    };
    assert!((xi - 0.5).abs() < 1e-15);
    assert!((pairs[1].gap - 0.3).abs() < 1e-15);
}

/// A steel block (`nx × ny` elements, `b` wide and `h` high in metres, E = 200 GPa, 1 m thick)
/// on the ground with friction `f`, a spring of `k` N/m at its heel, its weight `w` N on its
/// top nodes and a push of 10 kN at its top right corner: the model's text with its history
/// (the weight, then stages `push1`, `push2`, … taking the push's factor to each of `pushes`
/// in turn), in N·m or kN·mm. By hand it tips about its toe at `P = w·b/(2h)` (the spring acts
/// at the base, with no moment about the toe), and pushed back about its heel at `−P`.
pub(crate) fn block_history_text(
    (nx, ny, b, h): (usize, usize, f64, f64),
    (f, k, w): (f64, f64, f64),
    pushes: &[f64],
    kn_mm: bool,
) -> String {
    let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    format!(
        "units = \"{units}\"\n\
         [[materials]]\nname = \"steel\"\nE = {e:e}\nnu = 0.3\nthickness = {l:e}\n\
         [[blocks]]\nname = \"blk\"\norigin = [0.0, 0.0]\nwidth = {b:e}\nheight = {h:e}\n\
         nx = {nx}\nny = {ny}\nmaterial = \"steel\"\nanalysis = \"plane_stress\"\n\
         [[contact]]\nname = \"g\"\nfrom = \"ground\"\nto = \"blk.bottom\"\n\
         normal = [0.0, 1.0]\nfriction = {f}\n\
         [[springs]]\nnodes = \"blk.bottom_left\"\ndirection = [1.0, 0.0]\nstiffness = {k:e}\n\
         [[loads.weight.nodal]]\nnodes = \"blk.top\"\nfy = {fy:e}\n\
         [[loads.push.nodal]]\nnodes = \"blk.top_right\"\nfx = {fx:e}\n\
         [[history]]\nname = \"weight\"\nfactors = {{ weight = 1.0 }}\n{stages}",
        units = if kn_mm { "kN, mm" } else { "N, m" },
        e = 2e11 * force / (length * length),
        l = length,
        b = b * length,
        h = h * length,
        k = k * force / length,
        fy = -w / (nx + 1) as f64 * force,
        fx = 10_000.0 * force,
        stages = pushes
            .iter()
            .enumerate()
            .map(|(i, p)| {
                format!(
                    "[[history]]\nname = \"push{}\"\nfactors = {{ push = {p} }}\n",
                    i + 1
                )
            })
            .collect::<String>(),
    )
}

/// A model file's text with its history, read and analysed.
pub(crate) fn analyze_history_text(
    text: &str,
) -> Result<unilateral_analysis::HistoryAnalysis, unilateral_analysis::AnalysisError> {
    let p = read("h.toml", text).unwrap_or_else(|e| panic!("{e}"));
    let stages = p.history.clone().expect("a history");
    unilateral_analysis::analyze_history(&p.model, &stages, &p.settings.engine)
}

/// A block's stage that pushed it back completed with its pairs carrying the weight `w` and,
/// slipping back, the friction `fw` in all.
fn assert_slid_back(st: &unilateral_contact::StageSolution, (w, fw): (f64, f64), what: &str) {
    assert_eq!(
        st.status,
        unilateral_contact::StageStatus::Completed,
        "{what}: {:?}",
        st.reason
    );
    let n: f64 = st.pairs.iter().map(|r| r.x_n).sum();
    let t: f64 = st.pairs.iter().map(|r| r.x_t).sum();
    assert!((n - w).abs() < 1e-6 * w, "{what}: ΣN = {n}");
    assert!((t - fw).abs() < 1e-6 * w, "{what}: Σx_t = {t}");
}

/// Blocks of a generated sweep of histories (2896 runs) that slide, the heel carrying the
/// spring, until the heel opens and then tip about the toe. Where the heel opened, the
/// stage's trace let the heel's friction part leave before its normal force and read a
/// mechanism whose mode moved nothing (the heel's two friction parts growing together): the
/// stage ended there as a mechanism at 0.34–0.65 of the tipping load, exit 0. Such a mode is
/// now no mechanism: the stage is traced again with the friction relations deciding the ties
/// (for the 4 × 4 block, whose second trace turned back out of balance at the tipping, a third
/// time with them only up to the heel's opening) and ends in the mechanism at the tipping load
/// by hand — the toe carrying the weight and `f·W`, the spring the rest, every pair slid
/// `(P − f·W)/k` and every other pair open — in N·m and in kN·mm.
#[test]
fn a_block_whose_heel_opens_as_it_slides_in_a_history_tips_where_statics_say() {
    // (mesh and size, friction, spring, weight, push, units): x1009, x0767, x1226k, x0869k,
    // x0789 (its second trace turned back out of balance at the tipping: the third, with the
    // relations only up to the heel's opening, tips), x0724k (its first trace met a singular
    // basis, its second failed: the third tips)
    let cases = [
        ((7, 3, 1.0, 0.5), (0.25, 1e4, 8000.0), 0.96, false),
        ((4, 4, 1.0, 1.0), (0.2, 1000.0, 9000.0), 0.54, false),
        ((7, 3, 2.0, 1.0), (0.34, 562.0, 10_000.0), 1.2, true),
        ((3, 1, 2.0, 1.0), (0.34, 1e4, 9000.0), 1.35, false),
        ((5, 1, 1.0, 1.0), (0.3, 1e4, 10_000.0), 0.75, true),
        ((6, 2, 1.0, 0.5), (0.2, 1e5, 8000.0), 1.2, true),
    ];
    for (mesh, (f, k, w), push, kn_mm) in cases {
        assert_push_tips_at_the_toe(mesh, (f, k, w), push, kn_mm);
    }
}

/// The block of [`block_history_text`] pushed to `push` in one stage after its weight: the
/// stage ends in the mechanism at the tipping load `w·b/(2h)` by hand, the toe carrying the
/// weight and `f·w`, every pair slid `(P − f·w)/k` and every other pair open, the mode the
/// rotation about the toe.
fn assert_push_tips_at_the_toe(
    mesh: (usize, usize, f64, f64),
    (f, k, w): (f64, f64, f64),
    push: f64,
    kn_mm: bool,
) {
    use unilateral_contact::StageStatus;
    let what = format!("{mesh:?}, f = {f}, k = {k}, push {push}, kN·mm {kn_mm}");
    let text = block_history_text(mesh, (f, k, w), &[push], kn_mm);
    let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("{what}: {e}"));
    let st = &a.history.stages[1];
    assert_eq!(st.status, StageStatus::Mechanism, "{what}: {:?}", st.reason);
    let (nx, _, b, h) = mesh;
    let tipping = w * b / (2.0 * h);
    let load = 10_000.0 * push * st.s_end;
    assert!(
        (load - tipping).abs() < 1e-6 * tipping,
        "{what}: the mechanism at {load}, by hand {tipping}"
    );
    let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
    let slip = (tipping - f * w) / k * length;
    let toe = format!("g.{}", nx + 1);
    assert_tipped(&st.pairs, &toe, (w * force, f, slip), true, &what);
    assert_rotation_about_the_toe(st.mechanism.as_deref().unwrap_or_default(), nx, &what);
}

/// Blocks of the generated sweep pushed past their tipping load in a history, on springs of
/// 1e4 and 1e5 N/m: where the last pair but the toe opened, the rotation about the toe entered
/// with the load held, and the toe's slip increment, falling at a rate of round-off (2e-12 of
/// the rotation's), blocked it after a step that moved the load by 5e-8 of itself; the next
/// basis was singular (a numerical failure, exit 1, at the tipping load). Judged on the
/// structure's equations, the rotation is the mechanism: the stage ends at the tipping load by
/// hand, the toe carrying the weight and `f·W`, every pair slid `(P − f·W)/k`, the mode the
/// rotation about the toe — in N·m and in kN·mm.
#[test]
fn a_block_pushed_past_its_tipping_load_in_a_history_tips_there() {
    // x1166, x1226, x1369, x0467, x1125, x0650k (the loads as the helper writes them)
    let cases = [
        ((7, 2, 2.0, 1.0), (0.3, 1e5, 9000.0), 1.08, false),
        ((5, 1, 1.0, 1.0), (0.3, 1e4, 10_000.0), 0.75, false),
        ((4, 1, 1.0, 0.5), (0.4, 1e5, 8000.0), 0.96, false),
        ((2, 2, 2.0, 1.0), (0.5, 1e4, 10_000.0), 1.5, false),
        ((3, 3, 1.0, 1.0), (0.3, 1e4, 9000.0), 0.54, false),
        ((3, 3, 1.0, 1.0), (0.25, 1e4, 10_000.0), 0.6, true),
    ];
    for (mesh, (f, k, w), push, kn_mm) in cases {
        for kn_mm in [kn_mm, !kn_mm] {
            assert_push_tips_at_the_toe(mesh, (f, k, w), push, kn_mm);
        }
    }
}

/// A reviewer's block (1 × 0.5 m, 4 × 1 elements, a heel spring of 1e6 N/m) pushed until it
/// tips against a wall 1 cm from its right face, unloaded, pushed again and back: as it
/// rotates, its corner's gap to the wall closes, a gap blocking a rotation that moves only
/// displacements. Judged on the structure's equations (as a slip increment blocking such a
/// rotation is), the same block came out with its state out of balance by 2.1e-6 (exit 1)
/// where the data's own pivot completes every stage; only slip increments are judged.
#[test]
fn a_block_that_tips_against_a_wall_and_is_unloaded_completes_every_stage() {
    use unilateral_contact::StageStatus;
    let a = analyze_history_text(WALL_BLOCK).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.history.stages.len(), 5);
    for st in &a.history.stages {
        assert_eq!(
            st.status,
            StageStatus::Completed,
            "{}: {:?}",
            st.name,
            st.reason
        );
    }
}

/// The model of [`a_block_that_tips_against_a_wall_and_is_unloaded_completes_every_stage`].
const WALL_BLOCK: &str = r#"units = "N, m"
[[materials]]
name = "steel"
E = 200000000000.0
nu = 0.3
thickness = 1.0
[[blocks]]
name = "blk"
origin = [0.0, 0.0]
width = 1.0
height = 0.5
nx = 4
ny = 1
material = "steel"
analysis = "plane_stress"
[[contact]]
name = "g"
from = "ground"
to = "blk.bottom"
normal = [0.0, 1.0]
friction = 0.5
gap = [0.0, 0.0, 0.0, 0.0, 0.0]
[[springs]]
nodes = "blk.bottom_left"
direction = [1.0, 0.0]
stiffness = 1000000.0
[[contact]]
name = "wall"
from = "ground"
to = "blk.right"
exclude = "blk.bottom_right"
normal = [-1.0, 0.0]
friction = 0.3
gap = 0.01
[[loads.push.nodal]]
nodes = "blk.top_right"
fx = 5000.0
[[loads.weight.nodal]]
nodes = "blk.top"
fy = -1600.0
[[history]]
name = "weight"
factors = { weight = 1.0 }
[[history]]
name = "push"
factors = { push = 3.2 }
[[history]]
name = "unload"
factors = { push = 0.8 }
[[history]]
name = "again"
factors = { push = 1.92 }
[[history]]
name = "reverse"
factors = { push = -0.48 }
"#;

/// A mechanism's mode (`(dz_n, dz_t)` a pair, heel to toe, normalised to a largest rate of 1)
/// is the rigid rotation about the toe of a block of `nx` elements along its base: each pair
/// opens at a rate proportional to its distance from the toe, `(nx − i)/nx` of the heel's, and
/// slides not at all.
fn assert_rotation_about_the_toe(mode: &[(f64, f64)], nx: usize, what: &str) {
    assert_eq!(mode.len(), nx + 1, "{what}: {mode:?}");
    for (i, &(n, t)) in mode.iter().enumerate() {
        let by_hand = (nx - i) as f64 / nx as f64;
        assert!(
            (n - by_hand).abs() < 1e-4 && t.abs() < 1e-4,
            "{what}: pair {} moves ({n}, {t}) in the mode, by hand ({by_hand}, 0)",
            i + 1
        );
    }
}

/// Blocks of the same sweep whose stage read a mechanism that moved nothing where the heel
/// opens, and whose second and third traces (the relations deciding the ties throughout, and
/// only up to the heel's opening) fail their checks at the tipping load: such a stage ended
/// as a mechanism at 0.31 and 0.65 of the tipping load (exit 0, a wrong answer), both pushed
/// exactly to it. It is now a numerical failure (the program's fault, exit 1) — or, once a
/// trace is right, the stage completed or the mechanism at the tipping load by hand; never a
/// mechanism short of it.
#[test]
fn a_mechanism_that_moves_nothing_is_never_a_stages_answer() {
    use unilateral_contact::StageStatus;
    // x1413 (a push exactly to tipping), x0527
    let cases = [
        ((7, 1, 2.0, 1.0), (0.2, 1e4, 8000.0), 0.8),
        ((3, 3, 2.0, 1.0), (0.4, 1e4, 8000.0), 0.8),
    ];
    for (mesh, (f, k, w), push) in cases {
        let what = format!("{mesh:?}, f = {f}, k = {k}, push {push}");
        let text = block_history_text(mesh, (f, k, w), &[push], false);
        let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("{what}: {e}"));
        let st = &a.history.stages[1];
        let (_, _, b, h) = mesh;
        let tipping = w * b / (2.0 * h);
        let load = 10_000.0 * push * st.s_end;
        assert!(
            st.status != StageStatus::NumericalFailure || st.mechanism.is_none(),
            "{what}: a failed stage with a mechanism's mode {:?}",
            st.mechanism
        );
        match st.status {
            StageStatus::Mechanism => {
                assert!(
                    (load - tipping).abs() < 1e-6 * tipping,
                    "{what}: a mechanism at {load}, by hand {tipping}"
                );
                let mode = st.mechanism.as_deref().unwrap_or_default();
                assert_rotation_about_the_toe(mode, mesh.0, &what);
            }
            StageStatus::Completed => assert!(
                (load - tipping).abs() < 1e-6 * tipping
                    && push * 10_000.0 <= tipping * (1.0 + 1e-9),
                "{what}: completed at {load}, tipping by hand at {tipping}"
            ),
            StageStatus::NumericalFailure => {}
            ref other => panic!("{what}: {other:?} {:?}", st.reason),
        }
    }
}

/// A 2 × 1 block (2 m wide, 1 m high, W = 8 kN, friction 0.5) on a 1e5 N/m spring, pushed to
/// 6.96 kN (it slides (6960 − 4000)/1e5 = 2.96 cm) and then back to −4 kN, where by hand it
/// has slid back to where it started: the spring's force `P + f·W` is zero, and the pairs
/// in contact carry W and slip back with their friction f·W = 4 kN in all. The stage's check
/// judged the last segment's slips (2.96 cm) against the state's mutual displacements (1e-8
/// m, the round-off of those centimetres) and failed it by 1.4e-6 (exit 1; 68 runs of a sweep
/// of 2896 failed so, on stiff springs): the scale is now the larger of the two. In N·m and
/// kN·mm.
#[test]
fn a_block_slid_back_to_where_it_started_passes_its_check() {
    use unilateral_contact::StageStatus;
    for kn_mm in [false, true] {
        let what = format!("kN·mm {kn_mm}");
        let text = block_history_text((2, 1, 2.0, 1.0), (0.5, 1e5, 8000.0), &[0.696, -0.4], kn_mm);
        let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("{what}: {e}"));
        let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let pushed = &a.history.stages[1];
        assert_eq!(
            pushed.status,
            StageStatus::Completed,
            "{what}: {:?}",
            pushed.reason
        );
        // The heel, which carries the spring, by balance; the other pairs within the block's
        // strain of it.
        let slid = 0.0296 * length;
        for r in &pushed.pairs {
            let within = if r.name == "g.1" { 1e-6 } else { 1e-4 };
            assert!((r.z_t - slid).abs() < within * slid, "{what}: {r:?}");
        }
        let back = &a.history.stages[2];
        let w = 8000.0 * force;
        assert_slid_back(back, (w, 4000.0 * force), &what);
        for r in &back.pairs {
            assert!(r.z_t.abs() < 1e-6 * slid, "{what}: {r:?}");
            assert!(
                r.x_t <= 0.5 * r.x_n * (1.0 + 1e-9) + 1e-9 * w,
                "{what}: {r:?}"
            );
        }
    }
}

/// A 2 × 3 block (2 m wide, 1 m high, W = 8 kN, friction 0.2) on a 1e5 N/m spring, pushed to
/// 6.88 kN (it slides (6880 − 1600)/1e5 = 5.28 cm) and then back to −4 kN: by hand it slides
/// back past its start to `(−4000 + 1600)/1e5` = −2.4 cm, every pair in contact slipping back
/// with the friction f·W = 1.6 kN in all. The last stage's end, its values moved there by hand
/// along the last column, failed its check by 1.2e-8 (exit 1; 24 runs of a sweep of 2896
/// failed so); refined once from the data it passes, and a completed stage that fails its
/// check is now checked again so (in N·m; in kN·mm the end passed as it was).
#[test]
fn a_block_pushed_back_past_its_start_ends_its_stage_by_hand() {
    for kn_mm in [false, true] {
        let what = format!("kN·mm {kn_mm}");
        let text = block_history_text((2, 3, 2.0, 1.0), (0.2, 1e5, 8000.0), &[0.688, -0.4], kn_mm);
        let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("{what}: {e}"));
        let (force, length) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        let back = &a.history.stages[2];
        let w = 8000.0 * force;
        assert_slid_back(back, (w, 1600.0 * force), &what);
        let slid = -0.024 * length;
        for r in &back.pairs {
            let within = if r.name == "g.1" { 1e-6 } else { 1e-4 };
            assert!((r.z_t - slid).abs() < within * slid.abs(), "{what}: {r:?}");
            assert!(r.x_t.abs() <= 0.2 * r.x_n + 1e-9 * w, "{what}: {r:?}");
        }
    }
}

/// A steel block (`b` × `h` m, `nx` × 1 elements, friction `mu`) on a horizontal spring `k`
/// N/m at its heel, its weight `w` N on its top nodes and then a push `push` N at its top
/// corner to the right and back to `back` N, as a load history, in N·m or kN·mm: by hand
/// (statics, the incremental law) it slides `u2 = (push − μw)/k` and, pushed back past the
/// spring's pull less the friction, to `u3 = (back + μw)/k` — checked at each stage's end:
/// the pairs carry `w`, their friction `∓μw`, the heel's slip is `u`.
fn assert_block_slides_out_and_back(
    (b, h, nx, mu, k): (f64, f64, usize, f64, f64),
    (w, push, back): (f64, f64, f64),
) {
    for kn_mm in [false, true] {
        let (f, l) = if kn_mm { (1e-3, 1e3) } else { (1.0, 1.0) };
        // The pushes as factors of the block's 10 kN push.
        let pushes = [push / 10_000.0, back / 10_000.0];
        let text = block_history_text((nx, 1, b, h), (mu, k, w), &pushes, kn_mm);
        let what = format!("k = {k}, kN·mm {kn_mm}");
        let a = analyze_history_text(&text).unwrap_or_else(|e| panic!("{what}: {e}"));
        let stages = &a.history.stages;
        assert_eq!(stages.len(), 3, "{what}");
        for (st, (sign, u)) in stages[1..]
            .iter()
            .zip([(-1.0, (push - mu * w) / k), (1.0, (back + mu * w) / k)])
        {
            assert_eq!(
                st.status,
                unilateral_contact::StageStatus::Completed,
                "{what}: stage {} {:?}",
                st.stage,
                st.status
            );
            let sn: f64 = st.pairs.iter().map(|r| r.x_n).sum::<f64>() / f;
            let sx: f64 = st.pairs.iter().map(|r| r.x_t).sum::<f64>() / f;
            assert!(
                (sn - w).abs() < 1e-6 * w,
                "{what}: stage {} Σ x_n = {sn}",
                st.stage
            );
            assert!(
                (sx - sign * mu * w).abs() < 1e-6 * w,
                "{what}: stage {} Σ x_t = {sx}",
                st.stage
            );
            let slip = st.pairs[0].z_t / l;
            assert!(
                (slip - u).abs() < (1e-5 * u.abs()).max(1e-5 * w / k),
                "{what}: stage {} slip {slip}, by hand {u}",
                st.stage
            );
        }
    }
}

/// Blocks pushed far along a spring and back in a load history (a generated sweep's models):
/// a 2 m block on 1e5 N/m (slides 42.4 mm, then back to −8 mm) and a 1 m block on 1e4 N/m
/// (slides 441 mm, then back exactly to where it started). In the sweep both failed in their
/// last stage (exit 1: a singular basis, or an end "failing its check" by 2.5e-8 in kN·mm;
/// written here, the second still does before this change): the forces carry the round-off of
/// the slide, which the check measured against the final state's slips alone. A stage whose
/// traces all fail the check is now checked once more against each pair's largest slip over
/// the stage (the strict check still chooses among traces that pass it).
#[test]
fn blocks_pushed_far_along_a_spring_and_back_end_where_statics_puts_them() {
    assert_block_slides_out_and_back((2.0, 1.0, 5, 0.4, 1e5), (8000.0, 7440.0, -4000.0));
    assert_block_slides_out_and_back((1.0, 0.5, 7, 0.5, 1e4), (9000.0, 8910.0, -4500.0));
}
