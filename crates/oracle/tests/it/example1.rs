//! The paper's Example 1 (formulation.md §5), built as in §3, through the exact oracle.

#![allow(clippy::needless_range_loop)] // index notation mirrors the formulas

use unilateral_oracle::fixtures::example1;
use unilateral_oracle::{
    enumerate_parametric_exact, frac, is_lcp_solution, mz_plus_q, parametric_path,
    parametric_path_exact, PathStatus, Rat, Step, Var, DEFAULT_MAX_STEPS,
};

const N: usize = example1::PAIRS;

/// Labels of Example 1 (0-based pair `i`).
fn xn(i: usize) -> Var {
    Var::X(i)
}
fn xtp(i: usize) -> Var {
    Var::X(N + i)
}
fn xtm(i: usize) -> Var {
    Var::X(2 * N + i)
}
fn zn(i: usize) -> Var {
    Var::Z(i)
}

/// Example 1 exactly: f = 3/5, c = 1 (so q0 = e, as max(1, f)·c = 1); M and d of
/// formulation.md §3 with Rnt = Rtn = 0, from the shared fixture.
fn exact() -> (Vec<Vec<Rat>>, Vec<Rat>, Vec<Rat>) {
    let lcp = example1::lcp_exact();
    (lcp.m, vec![frac(1, 1); 3 * N], lcp.d)
}

/// Example 1 from the `f64` data as a user would type it.
fn floating() -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let lcp = example1::lcp();
    (lcp.m, vec![1.0; 3 * N], lcp.d)
}

#[test]
fn m_is_singular_as_the_spec_says() {
    // Rows of the ± blocks add up to 2F times the normal rows.
    let (m, _, _) = exact();
    for i in 0..N {
        for j in 0..3 * N {
            assert_eq!(&m[N + i][j] + &m[2 * N + i][j], frac(6, 5) * &m[i][j]);
        }
    }
}

#[test]
fn path_is_one_step_then_criterion_2a() {
    let (m, q0, d) = exact();
    let path = parametric_path_exact(&m, &q0, &d, None, None, DEFAULT_MAX_STEPS);
    assert_eq!(
        path.steps,
        vec![Step {
            entering: Var::P,
            leaving: xn(0),
            p: example1::first_event_p_exact(),
            p_decreased: false,
        }]
    );
    assert_eq!(path.status, PathStatus::Ray);
    assert_eq!(path.final_entering, Some(zn(0)));
    let ray = path.ray.as_ref().expect("a ray");
    assert_eq!(ray.entering, zn(0));
    assert_eq!(ray.p_entry, frac(-2, 1)); // Table 2: p's entry in z_n1's column
    assert_eq!(ray.dp, frac(1, 1));

    // Per unit of p along the ray = the c = 0 solution at p = 1 (Table 3's p column, negated).
    let o = frac(0, 1);
    assert_eq!(ray.dz, example1::z_at_target_exact());
    assert_eq!(ray.dx, example1::x_at_target_exact());
    // The c = 0 solution at p = 1 solves the real (homogeneous) problem exactly.
    let zero_q: Vec<Rat> = d.clone();
    assert!(is_lcp_solution(&m, &zero_q, &ray.dz, &ray.dx));

    // Breakpoints: p = 0 (x = e), p = 32/3 (x = e + 32/3·d, x_n1 = 0).
    assert_eq!(path.points.len(), 2);
    let b = &path.points[1];
    assert_eq!(b.p, frac(32, 3));
    assert_eq!(b.x[0], frac(0, 1));
    assert!(b.z.iter().all(|v| *v == o));

    // Table 3's rhs column: the basic values extrapolated to p = 0 along the final basis.
    let basis = [
        zn(0),
        xn(1),
        xn(2),
        xtp(0),
        xtp(1),
        xtp(2),
        xtm(0),
        xtm(1),
        xtm(2),
    ];
    let table3_rhs: Vec<(Var, Rat)> = basis
        .into_iter()
        .zip(example1::table3_rhs_exact())
        .collect();
    for p in [frac(32, 3), frac(12, 1), frac(100, 1)] {
        let s = path.solution_at(&p).expect("on the ray");
        for (v, rhs) in &table3_rhs {
            let (value, slope) = match v {
                Var::X(i) => (&s.x[*i], &ray.dx[*i]),
                Var::Z(i) => (&s.z[*i], &ray.dz[*i]),
                _ => unreachable!(),
            };
            assert_eq!(*value, rhs + slope * &p, "{v} at p = {p}");
        }
        // And it is an exact solution of x = q0 + p d + M z.
        let q = unilateral_oracle::parametric_q(&q0, &d, &p);
        assert_eq!(mz_plus_q(&m, &s.z, &q), s.x);
        assert!(is_lcp_solution(&m, &q, &s.z, &s.x));
    }
    // Between 0 and 32/3 the path is z = 0, x = e + p d.
    let s = path.solution_at(&frac(1, 1)).unwrap();
    assert!(s.z.iter().all(|v| *v == o));
    assert_eq!(s.x, unilateral_oracle::parametric_q(&q0, &d, &frac(1, 1)));
}

#[test]
fn target_one_stops_on_the_first_segment() {
    let (m, q0, d) = exact();
    let path = parametric_path_exact(&m, &q0, &d, Some(&frac(1, 1)), None, DEFAULT_MAX_STEPS);
    assert_eq!(path.status, PathStatus::TargetReached);
    assert!(path.steps.is_empty());
    assert_eq!(path.final_entering, Some(Var::P));
    let last = path.points.last().unwrap();
    assert_eq!(last.p, frac(1, 1));
    assert_eq!(
        last.x,
        unilateral_oracle::parametric_q(&q0, &d, &frac(1, 1))
    );
    // Target 32/3 exactly: the step is taken and the path stops there.
    let path = parametric_path_exact(&m, &q0, &d, Some(&frac(32, 3)), None, DEFAULT_MAX_STEPS);
    assert_eq!(path.status, PathStatus::TargetReached);
    assert_eq!(path.steps.len(), 1);
    assert_eq!(path.final_entering, Some(zn(0)));
}

#[test]
fn the_same_from_f64_data() {
    let (m, q0, d) = floating();
    let path = parametric_path(&m, &q0, &d, None, None);
    assert_eq!(path.steps.len(), 1);
    assert_eq!(path.steps[0].entering, Var::P);
    assert_eq!(path.steps[0].leaving, xn(0));
    assert_eq!(path.steps[0].p, frac(32, 3)); // 1/0.09375 is exact in f64 data too
    assert_eq!(path.status, PathStatus::Ray);
    let ray = path.ray.as_ref().unwrap();
    assert_eq!(ray.entering, zn(0));
    assert_eq!(ray.p_entry, frac(-2, 1));
    for (a, b) in ray.dx_f64().iter().zip(example1::X_AT_TARGET) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
    assert_eq!(ray.dz_f64()[0], 0.5);
    // At p = 1 (target): x = e + d, z = 0.
    let s = path.solution_at_f64(1.0).unwrap();
    assert_eq!(s.x_f64()[0], 1.0 + example1::RV_N[0]);
    assert!(s.z_f64().iter().all(|&v| v == 0.0));
}

#[test]
fn without_tightening_enumeration_gives_the_papers_answer() {
    // c = 0: the real problem x = p·d + M z at p = 1. The enumeration (M is singular, so the
    // singular patterns go through the phase-1 LP) finds exactly one solution, the paper's.
    let (m, _, d) = exact();
    let zero = vec![frac(0, 1); 3 * N];
    let start = std::time::Instant::now();
    let sols = enumerate_parametric_exact(&m, &zero, &d, &frac(1, 1));
    eprintln!(
        "enumeration of 2^9 sets of Example 1: {:?}",
        start.elapsed()
    );
    assert_eq!(sols.len(), 1);
    assert_eq!(sols[0].z, example1::z_at_target_exact());
    assert_eq!(sols[0].w, example1::x_at_target_exact());
}

#[test]
fn without_tightening_the_path_ends_in_a_false_mechanism() {
    // formulation.md §3: the tightening c is what keeps the start away from this. With
    // q0 = 0 every ratio is 0; p enters and x_t1- leaves (lexicographic), z_t1- enters and
    // x_t1+ leaves, then z_t1+ has a zero column: "mechanism" at p = 0 (pair 1 slipping
    // both ways at once, no force).
    let (m, _, d) = exact();
    let zero = vec![frac(0, 1); 3 * N];
    let path = parametric_path_exact(&m, &zero, &d, None, None, DEFAULT_MAX_STEPS);
    let seq: Vec<(Var, Var)> = path.steps.iter().map(|s| (s.entering, s.leaving)).collect();
    assert_eq!(seq, vec![(Var::P, xtm(0)), (Var::Z(2 * N), xtp(0))]);
    assert!(path.steps.iter().all(|s| s.p == frac(0, 1)));
    assert_eq!(path.status, PathStatus::Mechanism);
    let ray = path.ray.as_ref().unwrap();
    assert_eq!(ray.entering, Var::Z(N));
    let mut dz = vec![frac(0, 1); 3 * N];
    dz[N] = frac(1, 1);
    dz[2 * N] = frac(1, 1);
    assert_eq!(ray.dz, dz);
}
