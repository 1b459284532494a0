//! Small cases checked by hand, and degenerate cases that must terminate cleanly.

use unilateral_oracle::fixtures::random::Lcg;
use unilateral_oracle::{
    enumerate, enumerate_exact, frac, has_solution, is_lcp_solution, lemke, lemke_exact,
    parametric_path, parametric_path_exact, LemkeStatus, PathStatus, Rat, Step, Var,
};

fn ints(rows: &[&[i64]]) -> Vec<Vec<Rat>> {
    rows.iter()
        .map(|r| r.iter().map(|&v| frac(v, 1)).collect())
        .collect()
}

fn iv(v: &[i64]) -> Vec<Rat> {
    v.iter().map(|&x| frac(x, 1)).collect()
}

// ---------- standard LCP ----------

#[test]
fn p_matrix_2x2_interior() {
    // M = [[2,1],[1,2]], q = (−5,−6): both z positive, 2z1 + z2 = 5, z1 + 2z2 = 6
    // → z = (4/3, 7/3), w = 0.
    let m = vec![vec![2.0, 1.0], vec![1.0, 2.0]];
    let q = [-5.0, -6.0];
    let sols = enumerate(&m, &q);
    assert_eq!(sols.len(), 1);
    assert_eq!(sols[0].z, vec![frac(4, 3), frac(7, 3)]);
    assert_eq!(sols[0].w, vec![frac(0, 1), frac(0, 1)]);
    assert_eq!(sols[0].set, vec![0, 1]);
    assert!(sols[0].singular_sets.is_empty());
    let r = lemke(&m, &q, &[1.0, 1.0]);
    assert_eq!(r.status, LemkeStatus::Solved);
    assert_eq!(r.z, sols[0].z);
    assert_eq!(r.w, sols[0].w);
}

#[test]
fn p_matrix_2x2_one_active() {
    // q = (−1, 2): S = {0}: z1 = 1/2, w2 = 1/2 + 2 = 5/2. The other three sets fail:
    // S = {} (w1 = −1), S = {1} (z2 = −2/... < 0), S = {0,1} (z2 = −5/3).
    let m = vec![vec![2.0, 1.0], vec![1.0, 2.0]];
    let q = [-1.0, 2.0];
    let sols = enumerate(&m, &q);
    assert_eq!(sols.len(), 1);
    assert_eq!(sols[0].z, vec![frac(1, 2), frac(0, 1)]);
    assert_eq!(sols[0].w, vec![frac(0, 1), frac(5, 2)]);
    assert_eq!(sols[0].z_f64(), vec![0.5, 0.0]);
    // Lemke: z0 enters (w1 leaves, z0 = 1), then z1 enters and z0 leaves at z1 = 1/2.
    let r = lemke(&m, &q, &[1.0, 1.0]);
    assert_eq!(r.status, LemkeStatus::Solved);
    assert_eq!(r.pivots, 2);
    assert_eq!(r.z, sols[0].z);
    assert_eq!(r.z0, frac(0, 1));
    // q ≥ 0: z = 0 with no pivot.
    let r = lemke(&m, &[0.0, 3.0], &[1.0, 1.0]);
    assert_eq!((r.status, r.pivots), (LemkeStatus::Solved, 0));
    assert_eq!(r.w, vec![frac(0, 1), frac(3, 1)]);
}

#[test]
fn several_solutions_and_none() {
    // M = [[0,1],[1,0]], q = (−1,−1): z = (1,1) is the only one (w = 0).
    let sols = enumerate(&[vec![0.0, 1.0], vec![1.0, 0.0]], &[-1.0, -1.0]);
    assert_eq!(sols.len(), 1);
    assert_eq!(sols[0].z, iv(&[1, 1]));
    // M = −I, q = (1, 1): z = 0, or z_i = 1 for any subset: four solutions.
    let m = vec![vec![-1.0, 0.0], vec![0.0, -1.0]];
    let sols = enumerate(&m, &[1.0, 1.0]);
    assert_eq!(sols.len(), 4);
    for s in &sols {
        assert!(is_lcp_solution(
            &ints(&[&[-1, 0], &[0, -1]]),
            &iv(&[1, 1]),
            &s.z,
            &s.w
        ));
    }
    // M = −1, q = −1: w = −z − 1 < 0 always: no solution; Lemke ends on a ray.
    assert!(!has_solution(&[vec![-1.0]], &[-1.0]));
    let r = lemke(&[vec![-1.0]], &[-1.0], &[1.0]);
    assert_eq!(r.status, LemkeStatus::Ray);
    let ray = r.ray.unwrap();
    assert_eq!(ray.entering, Var::Z(0));
}

#[test]
fn singular_and_degenerate_standard_lcps() {
    // Duplicate rows, M = [[1,1],[1,1]], q = (−1,−1): every z ≥ 0 with z1 + z2 = 1 solves.
    // The vertices (1,0) and (0,1) are found; {0,1} is singular and feasible, so flagged.
    let m = ints(&[&[1, 1], &[1, 1]]);
    let q = iv(&[-1, -1]);
    let sols = enumerate_exact(&m, &q);
    assert_eq!(sols.len(), 2);
    assert!(sols.iter().any(|s| s.singular_sets == vec![vec![0, 1]]));
    assert!(sols.iter().all(|s| is_lcp_solution(&m, &q, &s.z, &s.w)));
    let r = lemke_exact(&m, &q, &iv(&[1, 1]), 100);
    assert_eq!(r.status, LemkeStatus::Solved);
    assert!(is_lcp_solution(&m, &q, &r.z, &r.w));

    // Zero matrix: q = (0, 1) → z1 arbitrary ≥ 0 (a continuum, flagged); q = (−1, 0) → none.
    let zero = ints(&[&[0, 0], &[0, 0]]);
    let sols = enumerate_exact(&zero, &iv(&[0, 1]));
    assert_eq!(sols.len(), 1);
    assert_eq!(sols[0].z, iv(&[0, 0]));
    assert!(!sols[0].singular_sets.is_empty());
    assert!(enumerate_exact(&zero, &iv(&[-1, 0])).is_empty());
    let r = lemke_exact(&zero, &iv(&[-1, 0]), &iv(&[1, 1]), 100);
    assert_eq!(r.status, LemkeStatus::Ray);

    // A zero row and a duplicate row with a degenerate q (ties in every ratio test).
    let m = ints(&[&[1, 2, 0], &[0, 0, 0], &[1, 2, 0]]);
    let q = iv(&[-1, 0, -1]);
    // Solutions exist (e.g. z = (1, 0, 0)), but M is not copositive-plus and Lemke ends on a
    // ray (traced by hand): z0 = 1 enters, rows 0 and 2 tie, (−1 | 0 0 1) < (−1 | 1 0 0) so
    // w2 leaves; z2 enters, its column is −M e2 = 0: no positive entry.
    let r = lemke_exact(&m, &q, &iv(&[1, 1, 1]), 1000);
    assert_eq!(r.status, LemkeStatus::Ray);
    assert_eq!(r.pivots, 1);
    assert_eq!(r.ray.unwrap().entering, Var::Z(2));
    let sols = enumerate_exact(&m, &q);
    assert!(sols.iter().any(|s| s.z == iv(&[1, 0, 0])));
    // Solvable with a different covering vector: (1, 1, 2) makes w0 leave first.
    // Then z_0 enters and all three rows tie at ratio 1: z0 is preferred and leaves.
    let r = lemke_exact(&m, &q, &iv(&[1, 1, 2]), 1000);
    assert_eq!(r.status, LemkeStatus::Solved);
    assert_eq!((r.z.clone(), r.pivots), (iv(&[1, 0, 0]), 2));
    assert!(is_lcp_solution(&m, &q, &r.z, &r.w));

    // q = 0 with a non-trivial M: z = 0 at once.
    let r = lemke_exact(&ints(&[&[-1, 2], &[3, -4]]), &iv(&[0, 0]), &iv(&[1, 1]), 10);
    assert_eq!((r.status, r.pivots), (LemkeStatus::Solved, 0));
}

/// Murty's matrix: upper triangular, 1 on the diagonal, 2 above. A P-matrix (unique solution)
/// on which pivoting methods make many steps.
fn murty(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| match j.cmp(&i) {
                    std::cmp::Ordering::Less => 0.0,
                    std::cmp::Ordering::Equal => 1.0,
                    std::cmp::Ordering::Greater => 2.0,
                })
                .collect()
        })
        .collect()
}

#[test]
fn murty_matrix_terminates_and_agrees() {
    for n in [3, 6, 8] {
        let m = murty(n);
        for q in [vec![-1.0; n], (0..n).map(|i| -((i + 1) as f64)).collect()] {
            let sols = enumerate(&m, &q);
            assert_eq!(sols.len(), 1, "P-matrix: unique solution");
            let r = lemke(&m, &q, &vec![1.0; n]);
            assert_eq!(r.status, LemkeStatus::Solved);
            assert_eq!(r.z, sols[0].z);
        }
    }
}

#[test]
fn lemke_iteration_cap() {
    let m = murty(4);
    let r = lemke(&m, &[-1.0; 4], &[1.0; 4]);
    assert!(r.pivots > 1);
    let capped = lemke_exact(
        &unilateral_oracle::rat_matrix(&m),
        &iv(&[-1, -1, -1, -1]),
        &iv(&[1, 1, 1, 1]),
        1,
    );
    assert_eq!(capped.status, LemkeStatus::IterationCap);
    assert_eq!(capped.pivots, 1);
}

// ---------- parametric ----------

#[test]
fn parametric_one_variable_ray() {
    // x = 1 − p + z: p enters, x leaves at p = 1; z enters, p's row entry −1: ray, z = p − 1.
    let path = parametric_path(&[vec![1.0]], &[1.0], &[-1.0], None, None);
    assert_eq!(
        path.steps,
        vec![Step {
            entering: Var::P,
            leaving: Var::X(0),
            p: frac(1, 1),
            p_decreased: false
        }]
    );
    assert_eq!(path.status, PathStatus::Ray);
    let ray = path.ray.as_ref().unwrap();
    assert_eq!(
        (ray.entering, ray.p_entry.clone()),
        (Var::Z(0), frac(-1, 1))
    );
    assert_eq!((ray.dx.clone(), ray.dz.clone()), (iv(&[0]), iv(&[1])));
    let s = path.solution_at(&frac(3, 1)).unwrap();
    assert_eq!((s.x, s.z), (iv(&[0]), iv(&[2])));
    let s = path.solution_at(&frac(1, 2)).unwrap();
    assert_eq!((s.x, s.z), (vec![frac(1, 2)], iv(&[0])));
}

#[test]
fn parametric_mechanism() {
    // x = 1 − p + 0·z: at p = 1 the column of z is zero: mechanism, p_lim = 1.
    let path = parametric_path(&[vec![0.0]], &[1.0], &[-1.0], Some(5.0), None);
    assert_eq!(path.status, PathStatus::Mechanism);
    assert_eq!(path.last_p(), Some(&frac(1, 1)));
    let ray = path.ray.as_ref().unwrap();
    assert_eq!(ray.p_entry, frac(0, 1));
    assert_eq!(ray.dp, frac(0, 1));
    assert_eq!(ray.dz, iv(&[1]));
    assert!(path.solution_at(&frac(2, 1)).is_none());
}

#[test]
fn parametric_returns_to_zero() {
    // x = 1 − p − z: p enters (x leaves at p = 1), z enters and p leaves at z = 1, p = 0.
    let path = parametric_path(&[vec![-1.0]], &[1.0], &[-1.0], None, None);
    assert_eq!(path.status, PathStatus::ReturnedToZero);
    assert_eq!(path.steps.len(), 2);
    assert_eq!(path.steps[1].entering, Var::Z(0));
    assert_eq!(path.steps[1].leaving, Var::P);
    assert_eq!(path.steps[1].p, frac(0, 1));
    assert!(path.steps[1].p_decreased);
    assert_eq!(path.final_entering, None);
    // The first point at p = 1/2 is on the way up (z = 0).
    let s = path.solution_at(&frac(1, 2)).unwrap();
    assert_eq!(s.z, iv(&[0]));
}

#[test]
fn parametric_start_cases() {
    // q0 has a negative entry.
    let path = parametric_path(&[vec![1.0]], &[-1.0], &[1.0], None, None);
    assert_eq!(path.status, PathStatus::InfeasibleStart);
    assert!(path.steps.is_empty() && path.points.is_empty());
    // d ≥ 0: the start scheme never changes (ray at the first step, entering p).
    let path = parametric_path(
        &[vec![1.0, 0.0], vec![0.0, 1.0]],
        &[1.0, 0.0],
        &[2.0, 0.0],
        None,
        None,
    );
    assert_eq!(path.status, PathStatus::Ray);
    let ray = path.ray.as_ref().unwrap();
    assert_eq!((ray.entering, ray.p_entry.clone()), (Var::P, frac(-1, 1)));
    assert_eq!(ray.dx, iv(&[2, 0]));
    assert_eq!(path.solution_at(&frac(10, 1)).unwrap().x, iv(&[21, 0]));
    // Target inside the first segment; target exactly at the first breakpoint.
    let path = parametric_path(&[vec![1.0]], &[1.0], &[-1.0], Some(0.5), None);
    assert_eq!(path.status, PathStatus::TargetReached);
    assert!(path.steps.is_empty());
    assert_eq!(path.points.last().unwrap().x, vec![frac(1, 2)]);
    let path = parametric_path(&[vec![1.0]], &[1.0], &[-1.0], Some(1.0), None);
    assert_eq!(path.status, PathStatus::TargetReached);
    assert_eq!(path.steps.len(), 1);
    assert_eq!(path.final_entering, Some(Var::Z(0)));
    // Target 0 with a positive first ratio: the start is the answer.
    let path = parametric_path(&[vec![1.0]], &[1.0], &[-1.0], Some(0.0), None);
    assert_eq!(path.status, PathStatus::TargetReached);
    assert_eq!(path.points.last().unwrap().x, iv(&[1]));
}

#[test]
fn parametric_degenerate_tie_and_priority() {
    // M = I, q0 = (1,1), d = (−1,−1): both rows tie at p = 1. Rows of [rhs | B⁻¹]/col:
    // (1 | 1 0) and (1 | 0 1): the second is lexicographically smaller, so x1 leaves first;
    // then z1 enters and x0 leaves at once (degenerate: p stays 1); then z0's column has no
    // positive entry: ray with dz = (1, 1) per unit p.
    let m = ints(&[&[1, 0], &[0, 1]]);
    let (q0, d) = (iv(&[1, 1]), iv(&[-1, -1]));
    let path = parametric_path_exact(&m, &q0, &d, None, None, 100);
    let seq: Vec<(Var, Var, Rat)> = path
        .steps
        .iter()
        .map(|s| (s.entering, s.leaving, s.p.clone()))
        .collect();
    assert_eq!(
        seq,
        vec![
            (Var::P, Var::X(1), frac(1, 1)),
            (Var::Z(1), Var::X(0), frac(1, 1)),
        ]
    );
    assert_eq!(path.status, PathStatus::Ray);
    let ray = path.ray.as_ref().unwrap();
    assert_eq!((ray.entering, ray.dz.clone()), (Var::Z(0), iv(&[1, 1])));
    // With the priority (1, 0) the B⁻¹ columns are compared in the other order: x0 first.
    let path = parametric_path_exact(&m, &q0, &d, None, Some(&[1, 0]), 100);
    assert_eq!(path.steps[0].leaving, Var::X(0));
    assert_eq!(path.steps[1].entering, Var::Z(0));
    assert_eq!(path.steps[1].leaving, Var::X(1));
    assert_eq!(path.status, PathStatus::Ray);
    // The step cap.
    let path = parametric_path_exact(&m, &q0, &d, None, None, 1);
    assert_eq!(path.status, PathStatus::IterationCap);
    assert_eq!(path.steps.len(), 1);
}

#[test]
fn parametric_degenerate_zero_rows_terminate() {
    // Zero rows, duplicate rows, q0 with zeros: every ratio test has ties.
    let m = ints(&[&[0, 0, 0], &[1, 1, 0], &[1, 1, 0]]);
    let q0 = iv(&[0, 0, 1]);
    for d in [
        iv(&[-1, -1, -1]),
        iv(&[0, -1, -1]),
        iv(&[-1, 0, 0]),
        iv(&[0, 0, 0]),
    ] {
        let path = parametric_path_exact(&m, &q0, &d, Some(&frac(3, 1)), None, 1000);
        assert_ne!(path.status, PathStatus::IterationCap);
        for pt in &path.points {
            let q = unilateral_oracle::parametric_q(&q0, &d, &pt.p);
            assert!(is_lcp_solution(&m, &q, &pt.z, &pt.x), "{:?}", path.status);
        }
    }
}

/// n = 10 with non-dyadic f64 data (large exact denominators): 1024 index sets, and Lemke
/// agrees. Kept as a smoke test of speed (well under a second in release builds).
#[test]
fn size_ten_with_f64_data() {
    let n = 10;
    let mut g = Lcg::new(12345);
    let mut next = || g.uniform(-0.5, 0.5);
    // Strictly diagonally dominant with a positive diagonal: a P-matrix.
    let mut m: Vec<Vec<f64>> = (0..n)
        .map(|_| (0..n).map(|_| next() * 0.3).collect())
        .collect();
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 2.0 + next();
    }
    let q: Vec<f64> = (0..n).map(|_| next() * 3.0).collect();
    let start = std::time::Instant::now();
    let sols = enumerate(&m, &q);
    let elapsed = start.elapsed();
    assert_eq!(sols.len(), 1);
    let r = lemke(&m, &q, &vec![1.0; n]);
    assert_eq!(r.status, LemkeStatus::Solved);
    assert_eq!(r.z, sols[0].z);
    eprintln!("enumeration of 2^10 sets with f64 data: {elapsed:?}");
}
