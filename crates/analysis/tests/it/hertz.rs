//! Hertz's line contact on Gmsh meshes of the real curved body, and the bundled Gmsh examples.
//!
//! `examples/cylinder-on-foundation.toml`: a steel disc of radius `R` (triangles refined near
//! its lowest point) pressed by `P` per unit length at its centre onto a steel block whose
//! own mesh does not match the disc's; node-to-segment pairs from the block's top to the
//! disc's lower arc, gaps and normals from the geometry, no friction (Hertz's assumption; with
//! identical materials friction would not change the pressure anyway).
//!
//! Reference (Hertz, 2D; Johnson, *Contact Mechanics*, §4.2): `1/E* = (1−ν1²)/E1 +
//! (1−ν2²)/E2`, half-width `a = sqrt(4·P·R/(π·E*))`, pressure `p(x) = p0·sqrt(1 − x²/a²)`
//! with `p0 = 2P/(π·a)`. The block is 85a wide and 42a deep, its bottom pinned: it stands for
//! the half-space (a finite depth `d` changes `a` by a relative amount of order `(a/d)²`,
//! here below 1e-3, far below the mesh's error).
//!
//! What the mesh allows (and so the tolerances): the contact edge lies somewhere between two
//! nodes, so the half-width is known to one element size `h` along the surface; and near a
//! square-root edge a nodal force spread over its tributary length misses the pressure by up
//! to `p0·sqrt(h/a)` (the pressure changes by that much over the last element). The test
//! asserts those bounds on the coarse (`h = 0.3 mm`, `a/h ≈ 8`) and the fine (`h = 0.15 mm`)
//! meshes, and that the fine mesh's errors are smaller (convergence).

use std::path::{Path, PathBuf};

use unilateral_analysis::analyze;
use unilateral_io::{read_model, StructuralProblem};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Reads a bundled example and analyses it; the LCP's residual and the structure's
/// equilibrium must be at round-off (the program's own verification, here checked for a pass).
fn run_example(name: &str) -> (StructuralProblem, unilateral_analysis::Analysis) {
    let problem = read_model(&examples().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let a = analyze(&problem.model, &problem.settings).unwrap();
    assert_eq!(a.solution.p, Some(1.0), "{name}: {:?}", a.solution.outcome);
    let r = a.solution.residual.as_ref().unwrap();
    assert!(r.max() < 1e-9, "{name}: {r:?}");
    let eq = &a.results.as_ref().unwrap().equilibrium;
    let res = eq.resultant.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(res <= 1e-9 * eq.scale, "{name}: {eq:?}");
    (problem, a)
}

/// The cylinder example on the mesh pair `tag` ("coarse" or "fine"): the example's file with
/// its mesh names changed, written next to the meshes (absolute paths).
fn cylinder(tag: &str) -> (StructuralProblem, unilateral_analysis::Analysis) {
    if tag == "coarse" {
        return run_example("cylinder-on-foundation.toml");
    }
    let text = std::fs::read_to_string(examples().join("cylinder-on-foundation.toml")).unwrap();
    let meshes = examples().join("meshes");
    let text = text
        .replace(
            "\"meshes/disc-coarse.msh\"",
            &format!("{:?}", meshes.join(format!("disc-{tag}.msh"))),
        )
        .replace(
            "\"meshes/block-coarse.msh\"",
            &format!("{:?}", meshes.join(format!("block-{tag}.msh"))),
        );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cylinder.toml");
    std::fs::write(&path, text).unwrap();
    let problem = read_model(&path).unwrap();
    let a = analyze(&problem.model, &problem.settings).unwrap();
    assert_eq!(a.solution.p, Some(1.0));
    assert!(a.solution.residual.as_ref().unwrap().max() < 1e-9);
    (problem, a)
}

/// The example's data: P (N/mm), R (mm), E (MPa), ν.
const P: f64 = 1.0e4;
const R: f64 = 50.0;
const E: f64 = 2.1e5;
const NU: f64 = 0.3;

/// What one mesh gives against Hertz.
#[derive(Debug, Clone, Copy)]
struct HertzErrors {
    /// |a_mesh − a| (mm), the worse side.
    half_width: f64,
    /// The same over the element length at the edge.
    a_over_h: f64,
    /// The largest nodal pressure error, over p0.
    pressure: f64,
    /// The largest error of the force carried left of a point, over P.
    force: f64,
    /// The element length along the surface at the contact's edge (mm).
    h: f64,
}

fn hertz_errors(tag: &str) -> HertzErrors {
    let (problem, a) = cylinder(tag);
    let e_star = 1.0 / (2.0 * (1.0 - NU * NU) / E);
    let half = (4.0 * P * R / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * P / (std::f64::consts::PI * half);
    let model = &problem.model;
    let arc = &model.names().node_sets["disc.arc"];
    let pairs = &a.solution.pairs;
    // the block stands for Hertz's half-space: its width and depth at least 20a
    let block = &model.names().node_sets["block.nodes"];
    let extent = |k: usize| {
        let v = block.iter().map(|n| model.nodes()[n.0][k]);
        v.clone().fold(f64::MIN, f64::max) - v.fold(f64::MAX, f64::min)
    };
    assert!(extent(0).min(extent(1)) >= 20.0 * half, "{tag}");
    // one pair per node of the arc, in the arc's order (its largest gap is within `search`)
    assert_eq!(pairs.len(), arc.len());
    let xy: Vec<[f64; 2]> = arc.iter().map(|n| model.nodes()[n.0]).collect();
    // Σ x_n = P: the disc's only vertical support is the contact
    let sum: f64 = pairs.iter().map(|p| p.x_n).sum();
    assert!((sum - P).abs() <= 1e-9 * P, "{tag}: Σ x_n = {sum}");
    let pressed: Vec<usize> = (0..pairs.len()).filter(|&i| pairs[i].x_n > 0.0).collect();
    let (first, last) = (pressed[0], *pressed.last().unwrap());
    // a contiguous contact zone, not touching the arc's ends
    assert_eq!(last - first + 1, pressed.len(), "{tag}");
    assert!(first > 0 && last + 1 < pairs.len(), "{tag}");
    // the meshes do not match: most pressed pairs end inside a segment of the block's top
    let on_segment = pressed
        .iter()
        .filter(|&&i| model.pairs()[i].segment.is_some())
        .count();
    assert!(
        2 * on_segment > pressed.len(),
        "{tag}: {on_segment} of {}",
        pressed.len()
    );
    // the half-width: midway between the outermost pressed nodes and the next ones out,
    // each side; h the element length there
    let mid = |i: usize, j: usize| 0.5 * (xy[i][0] + xy[j][0]);
    let a_left = -mid(first, first - 1);
    let a_right = mid(last, last + 1);
    let h = (xy[first][0] - xy[first - 1][0])
        .abs()
        .max((xy[last + 1][0] - xy[last][0]).abs());
    let a_err = (a_left - half).abs().max((a_right - half).abs()) / h;
    // the pressure: each pair's force over its tributary length along the arc
    let len = |i: usize, j: usize| (xy[i][0] - xy[j][0]).hypot(xy[i][1] - xy[j][1]);
    let (mut worst, mut sq) = (0.0f64, 0.0);
    for &i in &pressed {
        let trib = 0.5 * (len(i, i - 1) + len(i, i + 1));
        let p = pairs[i].x_n / trib;
        let x = xy[i][0];
        let exact = p0 * (1.0 - (x / half).powi(2)).max(0.0).sqrt();
        worst = worst.max((p - exact).abs() / p0);
        sq += ((p - exact) / p0).powi(2);
    }
    let rms = (sq / pressed.len() as f64).sqrt();
    // the force carried left of x, Σ x_n over the nodes left of x, against Hertz's
    // F(x) = P/2 + (P/π)·(asin(x/a) + (x/a)·sqrt(1 − x²/a²)), at the midpoints between nodes
    let hertz_force = |x: f64| {
        let s = (x / half).clamp(-1.0, 1.0);
        P * (0.5 + (s.asin() + s * (1.0 - s * s).sqrt()) / std::f64::consts::PI)
    };
    let (mut carried, mut force_err) = (0.0, 0.0f64);
    for (i, pair) in pairs.iter().enumerate().take(last + 1).skip(first) {
        carried += pair.x_n;
        force_err = force_err.max((carried - hertz_force(mid(i, i + 1))).abs() / P);
    }
    println!(
        "{tag}: a = {half:.4}, numerical {a_left:.4} / {a_right:.4}, h = {h:.3}, \
         pressure error max {worst:.3} rms {rms:.3} (of p0 = {p0:.1}), \
         force left of x: error {force_err:.4} (of P)"
    );
    HertzErrors {
        half_width: (a_left - half).abs().max((a_right - half).abs()),
        a_over_h: a_err,
        pressure: worst,
        force: force_err,
        h,
    }
}

/// Hertz on the coarse and the fine Gmsh meshes: the half-width within one element size,
/// Σ x_n = P to round-off, the nodal pressure within `p0·sqrt(h/a)` at every pressed node, the
/// force carried left of any point between nodes within one nodal force of the peak, `p0·h`
/// (the discrete sum jumps by about that at each node); and the fine mesh closer to Hertz in
/// the half-width, the largest pressure error and the carried force (convergence).
///
/// Measured (gmsh 4.15.2 meshes): a = 2.349 mm; coarse (h = 0.30 mm) a_mesh = 2.538, pressure
/// error 0.15 p0, force error 0.0063 P; fine (h = 0.15 mm) a_mesh = 2.313, 0.12 p0, 0.0030 P.
/// The root-mean-square nodal pressure error stays near 0.07 p0 on both meshes: it is the
/// scatter of the nodal forces of an unstructured triangle mesh about the smooth pressure
/// (each node's share depends on its triangles), which refinement does not remove; the
/// carried force, which sums it out, converges.
#[test]
fn hertz_on_gmsh_meshes_of_a_disc_and_a_block() {
    let e_star = 1.0 / (2.0 * (1.0 - NU * NU) / E);
    let half = (4.0 * P * R / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * P / (std::f64::consts::PI * half);
    let coarse = hertz_errors("coarse");
    let fine = hertz_errors("fine");
    for (tag, e) in [("coarse", coarse), ("fine", fine)] {
        assert!(e.a_over_h <= 1.0, "{tag}: {e:?}");
        let bound = (e.h / half).sqrt();
        assert!(
            e.pressure <= bound,
            "{tag}: {e:?}, bound sqrt(h/a) = {bound}"
        );
        assert!(
            e.force <= p0 * e.h / P,
            "{tag}: {e:?}, bound p0·h/P = {}",
            p0 * e.h / P
        );
    }
    assert!(fine.half_width < coarse.half_width, "{fine:?} {coarse:?}");
    assert!(fine.pressure < coarse.pressure, "{fine:?} {coarse:?}");
    assert!(fine.force < coarse.force, "{fine:?} {coarse:?}");
}

/// The footing on the non-matching soil mesh reads and analyses with a verified residual; the
/// contact normal forces carry the footing's load and weight (statics of the footing: its only
/// support is the contact).
#[test]
fn footing_on_soil_example_is_verified() {
    let (_problem, a) = run_example("footing-on-soil.toml");
    // V = 500 kN/m and the weight 25 kN/m³ × (2 × 0.8 − 2 × 0.2²/2) m² = 39 kN/m; H = 150 kN/m
    let (w, h) = (500.0 + 25.0 * 1.56, 150.0);
    let pairs = &a.solution.pairs;
    assert_eq!(pairs.len(), 21); // the base's 21 nodes (Gmsh: 20 segments of 0.1 m)
    let sum_n: f64 = pairs.iter().map(|p| p.x_n).sum();
    let sum_t: f64 = pairs.iter().map(|p| p.x_t).sum();
    assert!((sum_n - w).abs() <= 1e-9 * w, "Σ x_n = {sum_n}");
    assert!((sum_t.abs() - h).abs() <= 1e-9 * w, "Σ x_t = {sum_t}");
    // below the sliding load: the footing does not slide (some pairs slip, not all)
    assert!(h < 0.5 * w);
    assert!(pairs
        .iter()
        .any(|p| p.x_t.abs() < 0.5 * p.x_n * (1.0 - 1e-9)));
}

/// The pivots that settle the cylinder's start (at loads of round-off, p ≲ 1e-12) are the same
/// whatever the target: with p* = 0.01 the path reaches less far, and a threshold relative to
/// the loads reached alone turned two of them into listed "events" (a turning point at
/// p = −7.7e-14, a slip at 2.4e-13). Reference: the run to p* = 1, whose settling pivots
/// docs/examples.md lists.
#[test]
fn the_cylinders_settling_pivots_do_not_depend_on_the_target() {
    let problem = read_model(&examples().join("cylinder-on-foundation.toml")).unwrap();
    let settling = |target: f64| {
        let settings = unilateral_contact::SolveSettings {
            target,
            ..problem.settings.clone()
        };
        let a = analyze(&problem.model, &settings).unwrap();
        a.solution
            .steps
            .iter()
            .filter(|s| s.settling)
            .map(|s| s.index)
            .collect::<Vec<_>>()
    };
    let at_one = settling(1.0);
    assert!(!at_one.is_empty());
    for target in [0.01, 0.2] {
        assert_eq!(settling(target), at_one, "target {target}");
    }
}
