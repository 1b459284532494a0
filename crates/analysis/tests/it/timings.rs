//! `Analysis::timings`: the analysis times its three steps (condense, solve, recover), leaves
//! reading and writing to the front end, and never counts more than the call took. Reference: the wall-clock time
//! measured by the test around `analyze` (the steps do not overlap and all lie inside the call).

use std::time::{Duration, Instant};

use unilateral_analysis::{analyze, Analysis};
use unilateral_contact::{Follow, SolveSettings};
use unilateral_fem::{ContactPairSpec, FrameSection, LoadGroup, Model};

use crate::fixes::nodal;

/// `analyze` and the wall-clock time around it.
fn timed(model: &Model, settings: &SolveSettings) -> (Analysis, Duration) {
    let start = Instant::now();
    let a = analyze(model, settings).unwrap();
    (a, start.elapsed())
}

fn sum(a: &Analysis) -> Duration {
    a.timings.present().map(|(_, d)| d).sum()
}

/// The paper's Example 1 as a structure (two spans of 2, EI = 1, three frictional supports, a
/// unit load in the middle of the right span): the path reports a solution at p = 1, so all
/// three steps happen.
#[test]
fn the_three_steps_of_an_analysis_are_timed() {
    let mut model = Model::new();
    let n: Vec<_> = [0.0, 2.0, 3.0, 4.0]
        .iter()
        .map(|&x| model.add_node(x, 0.0))
        .collect();
    for w in n.windows(2) {
        model.add_frame(w[0], w[1], FrameSection::new(1.0, 2.0, 1.0));
    }
    for &i in &[n[0], n[1], n[3]] {
        model.add_contact_pair(ContactPairSpec::to_ground(i, [0.0, 1.0]).friction(0.6));
    }
    model.add_load(LoadGroup::Variable, nodal(n[2], 0.0, -1.0));
    let settings = SolveSettings {
        tightening: 1.0,
        follow: Follow::ToEnd,
        ..Default::default()
    };
    let (a, wall) = timed(&model, &settings);
    assert!(a.results.is_some());
    let t = a.timings;
    assert!(t.condense.is_some() && t.solve.is_some() && t.recover.is_some());
    // The analysis reads and writes nothing.
    assert_eq!((t.read, t.write), (None, None));
    let names: Vec<&str> = t.present().map(|(n, _)| n).collect();
    assert_eq!(names, ["condense", "solve", "recover"]);
    assert!(sum(&a) <= wall, "{t:?} in {wall:?}");
}
