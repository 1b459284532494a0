//! The paper's Example 1 (formulation.md §5), built as in §3, through the exact oracle.

#![allow(clippy::needless_range_loop)] // index notation mirrors the formulas

use unilateral_oracle::{
    enumerate_parametric_exact, frac, is_lcp_solution, mz_plus_q, parametric_path,
    parametric_path_exact, PathStatus, Rat, Step, Var, DEFAULT_MAX_STEPS,
};

const N: usize = 3;

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

/// M and d of formulation.md §3 with Rnt = Rtn = 0, in any number type.
fn assemble<T: Clone>(
    rnn: &[[T; N]; N],
    rtt_half: &[[T; N]; N],
    rv_n: &[T; N],
    f: &T,
    zero: T,
    mul: impl Fn(&T, &T) -> T,
    neg: impl Fn(&T) -> T,
) -> (Vec<Vec<T>>, Vec<T>) {
    let mut m = vec![vec![zero.clone(); 3 * N]; 3 * N];
    let mut d = vec![zero; 3 * N];
    for i in 0..N {
        for j in 0..N {
            let fr = mul(f, &rnn[i][j]);
            m[i][j] = rnn[i][j].clone();
            m[N + i][j] = fr.clone();
            m[2 * N + i][j] = fr;
            let t = &rtt_half[i][j];
            m[N + i][N + j] = t.clone();
            m[N + i][2 * N + j] = neg(t);
            m[2 * N + i][N + j] = neg(t);
            m[2 * N + i][2 * N + j] = t.clone();
        }
        d[i] = rv_n[i].clone();
        d[N + i] = mul(f, &rv_n[i]);
        d[2 * N + i] = mul(f, &rv_n[i]);
    }
    (m, d)
}

/// Example 1 exactly: f = 3/5, c = 1 (so q0 = e, as max(1, f)·c = 1).
fn exact() -> (Vec<Vec<Rat>>, Vec<Rat>, Vec<Rat>) {
    let r = |a: i64, b: i64| frac(a, b);
    let rnn = [
        [r(3, 16), r(-3, 8), r(3, 16)],
        [r(-3, 8), r(3, 4), r(-3, 8)],
        [r(3, 16), r(-3, 8), r(3, 16)],
    ];
    let rtt_half = [
        [r(1, 2), r(-1, 2), r(0, 1)],
        [r(-1, 2), r(1, 1), r(-1, 2)],
        [r(0, 1), r(-1, 2), r(1, 2)],
    ];
    let rv_n = [r(-3, 32), r(11, 16), r(13, 32)];
    let (m, d) = assemble(
        &rnn,
        &rtt_half,
        &rv_n,
        &r(3, 5),
        r(0, 1),
        |a, b| a * b,
        |a| -a,
    );
    (m, vec![r(1, 1); 3 * N], d)
}

/// Example 1 from the `f64` data as a user would type it.
fn floating() -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let rnn = [
        [0.1875, -0.375, 0.1875],
        [-0.375, 0.75, -0.375],
        [0.1875, -0.375, 0.1875],
    ];
    let rtt = [[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]];
    let rtt_half = rtt.map(|row| row.map(|v| v / 2.0));
    let rv_n = [-0.09375, 0.6875, 0.40625];
    let (m, d) = assemble(&rnn, &rtt_half, &rv_n, &0.6, 0.0, |a, b| a * b, |a| -a);
    (m, vec![1.0; 3 * N], d)
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
            p: frac(32, 3),
            p_decreased: false,
        }]
    );
    assert_eq!(path.status, PathStatus::Ray);
    assert_eq!(path.final_entering, Some(zn(0)));
    let ray = path.ray.as_ref().expect("a ray");
    assert_eq!(ray.entering, zn(0));
    assert_eq!(ray.p_entry, frac(-2, 1));
    assert_eq!(ray.dp, frac(1, 1));

    // Per unit of p along the ray = the c = 0 solution at p = 1 (Table 3's p column, negated).
    let h = frac(1, 2);
    let t = frac(3, 10);
    let o = frac(0, 1);
    assert_eq!(
        ray.dz,
        vec![
            h.clone(),
            o.clone(),
            o.clone(),
            o.clone(),
            o.clone(),
            o.clone(),
            o.clone(),
            o.clone(),
            o.clone()
        ]
    );
    assert_eq!(
        ray.dx,
        vec![
            o.clone(),
            h.clone(),
            h.clone(),
            o.clone(),
            t.clone(),
            t.clone(),
            o.clone(),
            t.clone(),
            t.clone()
        ]
    );
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
    let table3_rhs = [
        (zn(0), frac(-16, 3)),
        (xn(1), frac(3, 1)),
        (xn(2), frac(0, 1)),
        (xtp(0), frac(2, 5)),
        (xtp(1), frac(11, 5)),
        (xtp(2), frac(2, 5)),
        (xtm(0), frac(2, 5)),
        (xtm(1), frac(11, 5)),
        (xtm(2), frac(2, 5)),
    ];
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
    let expected = [0.0, 0.5, 0.5, 0.0, 0.3, 0.3, 0.0, 0.3, 0.3];
    for (a, b) in ray.dx_f64().iter().zip(expected) {
        assert!((a - b).abs() < 1e-15, "{a} vs {b}");
    }
    assert_eq!(ray.dz_f64()[0], 0.5);
    // At p = 1 (target): x = e + d, z = 0.
    let s = path.solution_at_f64(1.0).unwrap();
    assert_eq!(s.x_f64()[0], 1.0 - 0.09375);
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
    let (h, t, o) = (frac(1, 2), frac(3, 10), frac(0, 1));
    let mut z = vec![o.clone(); 3 * N];
    z[0] = h.clone();
    assert_eq!(sols[0].z, z);
    assert_eq!(
        sols[0].w,
        vec![
            o.clone(),
            h.clone(),
            h,
            o.clone(),
            t.clone(),
            t.clone(),
            o,
            t.clone(),
            t
        ]
    );
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
