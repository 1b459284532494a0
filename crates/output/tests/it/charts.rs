//! The load-path charts and the working-scheme map: a tightened run draws the path as traced
//! (with its tightening), a run without one the solution itself; the map's states change
//! exactly where the path's events say.

use std::path::{Path, PathBuf};

use unilateral_contact::{ContactSolution, PairResult};
use unilateral_io::Problem;
use unilateral_lcp::{solve_lcp, Lcp, Settings};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn solve(file: &str, tightening: Option<f64>) -> ContactSolution {
    match unilateral_io::read_problem(&examples().join(file)).unwrap() {
        Problem::Structural(pb) => {
            let mut settings = pb.settings.clone();
            if let Some(c) = tightening {
                settings.tightening = c;
            }
            unilateral_analysis::analyze(&pb.model, &settings)
                .unwrap()
                .solution
        }
        Problem::ContactZone(pb) => {
            let mut settings = pb.settings.clone();
            if let Some(c) = tightening {
                settings.tightening = c;
            }
            unilateral_contact::solve(&pb.zone, &settings).unwrap()
        }
    }
}

fn largest(pairs: &[PairResult]) -> (f64, f64) {
    pairs.iter().fold((0.0f64, 0.0f64), |(f, d), r| {
        (
            f.max(r.x_n.abs()).max(r.x_t.abs()),
            d.max(r.z_n.abs()).max(r.z_t.abs()),
        )
    })
}

/// The paper's Example 3 (the sheet pile, c = 1000 N): every charted sample is the traced path
/// at one of its breakpoints, and it solves the tightened LCP there. Reference: an independent
/// standard Lemke solve (`unilateral_lcp::solve_lcp`, not the path) of
/// `x = (q_c + c·t + p·d) + M z` at the sample's load, in the user's units, compared pair by
/// pair relative to the largest force and displacement. The charted values are not those of
/// the problem without the tightening (which the report's table of pairs shows).
#[test]
fn tightened_charts_are_the_traced_path() {
    let sol = solve("example3-sheet-pile.toml", None);
    let c = sol.tightening;
    assert_eq!(c, 1000.0);
    let s = unilateral_output::samples(&sol).unwrap();
    let bp_loads: Vec<f64> = sol.path.breakpoints.iter().map(|b| b.p).collect();
    assert!(s.loads.len() >= 30, "{} samples", s.loads.len());
    assert!(
        s.loads.iter().all(|p| bp_loads.contains(p)),
        "breakpoint loads only"
    );
    let lcp = &sol.lcp().problem;
    let n = lcp.q0.len();
    let names: Vec<String> = sol.pairs.iter().map(|r| r.name.clone()).collect();
    let mut differs = false;
    for (p, pairs) in s.loads.iter().zip(&s.pairs).step_by(4) {
        let q: Vec<f64> = (0..n)
            .map(|i| lcp.q0[i] + c * sol.lcp().tightening_direction[i] + p * lcp.d[i])
            .collect();
        let std = solve_lcp(
            &Lcp {
                m: lcp.m.clone(),
                q,
            },
            &Settings::default(),
        )
        .unwrap();
        let pt = std.point.expect("the tightened LCP is solved");
        let want = unilateral_contact::pair_results(&pt.w, &pt.z, &names);
        let (fmax, dmax) = largest(&want);
        for (a, b) in want.iter().zip(pairs) {
            assert!(
                (a.x_n - b.x_n).abs() <= 1e-7 * fmax
                    && (a.x_t - b.x_t).abs() <= 1e-7 * fmax
                    && (a.z_n - b.z_n).abs() <= 1e-7 * dmax
                    && (a.z_t - b.z_t).abs() <= 1e-7 * dmax,
                "p = {p}, pair {}: charted {b:?}, tightened LCP {a:?}",
                a.name
            );
        }
        // the tightening presses the pairs: x_n + ... differs from the untightened answer
        if let Some((free, _)) = sol.at(*p).unwrap() {
            if free
                .iter()
                .zip(pairs)
                .any(|(a, b)| (a.x_n - b.x_n).abs() > 1e-3 * fmax)
            {
                differs = true;
            }
        }
    }
    assert!(
        differs,
        "the traced values are not those without the tightening"
    );
    // the captions say so, with c's value
    let (forces, _) = unilateral_output::load_path_svgs(&sol, &Default::default()).unwrap();
    assert!(forces.contains("traced with the tightening c = 1000"));
    assert!(!forces.contains("solution without tightening"));
}

/// Without a tightening the charts draw the solution of the problem itself: the samples are
/// the solution at each load ([`ContactSolution::at`], evaluated afresh per load, a
/// reference independent of the one-walk sweep the charts use).
#[test]
fn untightened_charts_are_the_solution() {
    let sol = solve("example1-contact-zone.toml", Some(0.0));
    let s = unilateral_output::samples(&sol).unwrap();
    assert!(s.loads.len() >= 2);
    for (p, pairs) in s.loads.iter().zip(&s.pairs) {
        let (want, _) = sol.at(*p).unwrap().expect("on the path");
        let (fmax, dmax) = largest(&want);
        for (a, b) in want.iter().zip(pairs) {
            assert!((a.x_n - b.x_n).abs() <= 1e-9 * fmax.max(1e-300));
            assert!((a.z_n - b.z_n).abs() <= 1e-9 * dmax.max(1e-300));
        }
    }
}

/// Beyond the last event of a ray the charts end a quarter further on, where the last scheme
/// still holds: that point is on the straight line through the last breakpoint and the
/// reported solution when the target lies between them (here the cantilever's ray from
/// p = 1.2402, the target moved to 1.3, the end at 1.25·1.2402). Reference: the engine's
/// solution at that load (`ContactSolution::at`, a fresh basis there).
#[test]
fn untightened_charts_end_on_the_ray() {
    let pb =
        match unilateral_io::read_problem(&examples().join("example2-cantilever.toml")).unwrap() {
            Problem::Structural(pb) => pb,
            Problem::ContactZone(_) => panic!("a structural model"),
        };
    let mut settings = pb.settings.clone();
    settings.target = 1.3;
    settings.follow = unilateral_contact::Follow::ToEnd;
    let sol = unilateral_analysis::analyze(&pb.model, &settings)
        .unwrap()
        .solution;
    let unilateral_contact::Outcome::Ray { p_from } = sol.outcome else {
        panic!("a ray: {:?}", sol.outcome)
    };
    assert!(p_from < 1.3 && 1.3 < 1.25 * p_from, "p_from = {p_from}");
    let s = unilateral_output::samples(&sol).unwrap();
    let (&e, pairs) = (s.loads.last().unwrap(), s.pairs.last().unwrap());
    assert_eq!(e, 1.25 * p_from);
    let (want, _) = sol.at(e).unwrap().expect("on the ray");
    let (fmax, dmax) = largest(&want);
    for (a, b) in want.iter().zip(pairs) {
        assert_eq!(a.state, b.state, "{}", a.name);
        for (u, v, scale) in [
            (a.x_n, b.x_n, fmax),
            (a.x_t, b.x_t, fmax),
            (a.z_n, b.z_n, dmax),
            (a.z_t, b.z_t, dmax),
        ] {
            assert!((u - v).abs() <= 1e-9 * scale, "{}: {u} vs {v}", a.name);
        }
    }
}

/// A tightened path stopped at its target before its first event (Example 1's beam, c = 1, the
/// event at p = 32/3 beyond the target 1) records its values at its start only: its charts
/// say so, not "no solution along the path" (the solution at the target is verified and
/// reported).
#[test]
fn a_tightened_path_without_an_event_says_why_it_draws_no_curve() {
    let Problem::Structural(pb) =
        unilateral_io::read_problem(&examples().join("example1-beam.toml")).unwrap()
    else {
        panic!("a structural model");
    };
    let mut settings = pb.settings.clone();
    settings.follow = unilateral_contact::Follow::ToTarget;
    let a = unilateral_analysis::analyze(&pb.model, &settings).unwrap();
    assert!(a.solution.tightening > 0.0 && a.solution.steps.is_empty());
    assert_eq!(a.solution.p, Some(1.0));
    let dir = tempfile::tempdir().unwrap();
    unilateral_output::write_structural_report(&a, dir.path(), &Default::default()).unwrap();
    for f in ["load-path-forces.svg", "load-path-displacements.svg"] {
        let svg = std::fs::read_to_string(dir.path().join(f)).unwrap();
        assert!(svg.contains("no curve to draw"), "{f}");
        assert!(!svg.contains("no solution along the path"), "{f}");
    }
}

/// The pivots that settle the start at p = 0 are no events: Example 1's beam without the
/// tightening settles its start by one pivot (support.1 lifts at p = 0: the problem is
/// homogeneous). The charts listed and marked it as an event of support.1 (while leaving out
/// its tick); the HTML's events table now marks it as no event.
#[test]
fn settling_pivots_are_no_events_in_the_report() {
    let Problem::Structural(pb) =
        unilateral_io::read_problem(&examples().join("example1-beam.toml")).unwrap()
    else {
        panic!("a structural model");
    };
    let mut settings = pb.settings.clone();
    settings.tightening = 0.0;
    let a = unilateral_analysis::analyze(&pb.model, &settings).unwrap();
    let settling: Vec<_> = a.solution.steps.iter().filter(|s| s.settling).collect();
    assert_eq!(settling.len(), 1, "{:?}", a.solution.steps);
    // as the charts' event list names a step
    let word = unilateral_output::step_label(settling[0]);
    assert!(word.contains("support.1"), "{word}");
    let dir = tempfile::tempdir().unwrap();
    unilateral_output::write_structural_report(&a, dir.path(), &Default::default()).unwrap();
    for f in ["load-path-forces.svg", "load-path-displacements.svg"] {
        let svg = std::fs::read_to_string(dir.path().join(f)).unwrap();
        assert!(
            !svg.contains(&word),
            "{f} lists the settling pivot as an event"
        );
    }
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(html.contains("settles the start at p = 0: not an event"));
}
