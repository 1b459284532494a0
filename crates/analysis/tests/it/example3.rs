//! Example 3 (examples/example3-sheet-pile.toml): the sheet pile wall reconstruction shows the
//! pattern the paper reports — detachment at the top on the left and at the bottom on the
//! right, contact at the top on the right and at the bottom on the left, stick on the left side
//! only in a couple of nodes, sliding along the right side, and a ray.

use std::path::Path;

use unilateral_analysis::{analyze, Analysis, Outcome, PairState};
use unilateral_io::{read_model, StructuralProblem};

fn problem() -> StructuralProblem {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/example3-sheet-pile.toml");
    read_model(&src).unwrap()
}

fn run(p: &StructuralProblem) -> Analysis {
    analyze(&p.model, &p.settings).unwrap()
}

#[test]
fn example3_pattern() {
    let p = problem();
    assert_eq!(p.model.pairs().len(), 24);
    // 13 wall nodes + 2 × 13 × 13 soil nodes, no sharing.
    assert_eq!(p.model.nodes().len(), 13 + 2 * 169);
    let a = run(&p);
    let Outcome::Ray { p_from } = a.solution.outcome else {
        panic!("expected a ray, got {:?}", a.solution.outcome)
    };
    let pairs = &a.solution.pairs;
    let state = |name: &str| pairs.iter().find(|r| r.name == name).unwrap().state;
    let side =
        |s: &str| -> Vec<PairState> { (1..=12).map(|k| state(&format!("{s}.{k}"))).collect() };
    let (left, right) = (side("left"), side("right"));
    println!("ray from p = {p_from}");
    for pr in pairs {
        println!(
            "{:9} {:6} x_n = {:10.1} x_t = {:10.1} z_n = {:.3e} z_t = {:.3e}",
            pr.name, pr.state, pr.x_n, pr.x_t, pr.z_n, pr.z_t
        );
    }
    let open = |s: &PairState| *s == PairState::Open;
    // Left: detached at the top, in contact at the bottom.
    assert!(open(&left[11]) && open(&left[10]), "{left:?}");
    assert!(!open(&left[0]), "{left:?}");
    // Right: in contact at the top, detached at the bottom.
    assert!(!open(&right[11]) && !open(&right[10]), "{right:?}");
    assert!(open(&right[0]) && open(&right[1]), "{right:?}");
    // Each side has one contact zone: closed pairs form one run.
    for s in [&left, &right] {
        let closed: Vec<usize> = (0..12).filter(|&k| !open(&s[k])).collect();
        assert!(closed.windows(2).all(|w| w[1] == w[0] + 1), "{s:?}");
    }
    // Stick only on the left, in a couple of nodes; every closed pair on the right slides.
    let left_stick = left.iter().filter(|s| **s == PairState::Stick).count();
    assert!((1..=3).contains(&left_stick), "{left:?}");
    assert!(right.iter().all(|s| matches!(
        s,
        PairState::Open | PairState::SlipMinus | PairState::SlipPlus
    )));
    assert!(right.iter().filter(|s| !open(s)).count() >= 2);

    // The results balance, and the wall's top moves towards the right soil.
    let r = a.results.as_ref().unwrap();
    assert!(r.equilibrium.relative() < 1e-8);
    let top = p.model.names().node_id("wall.end").unwrap();
    assert!(r.displacements[top.0][0] > 0.0);

    // Results at every event load up to the ray (for pictures) are available and balance.
    for &pe in a.event_loads().iter().step_by(8) {
        let (_, re) = a.results_at(pe).unwrap();
        assert!(re.equilibrium.relative() < 1e-8);
    }

    // Without a physical constant load the final scheme does not depend on c, the ray's load
    // scales with it.
    let mut p2 = problem();
    p2.settings.tightening *= 2.0;
    let a2 = run(&p2);
    let Outcome::Ray { p_from: p2_from } = a2.solution.outcome else {
        panic!()
    };
    assert!((p2_from - 2.0 * p_from).abs() < 1e-6 * p_from);
    for (x, y) in a.solution.pairs.iter().zip(&a2.solution.pairs) {
        assert_eq!(x.state, y.state);
        assert!((x.x_n - y.x_n).abs() < 1e-6 * 1e5);
    }
}
