//! Property tests on random small problems: the three methods must agree with each other and
//! with the exact definition of a solution.

use proptest::prelude::*;
use unilateral_oracle::fixtures::random::psd_plus_skew;
use unilateral_oracle::{
    enumerate_exact, enumerate_parametric_exact, frac, has_solution_exact, is_lcp_solution,
    lemke_exact, parametric_path_exact, parametric_q, LemkeStatus, PathStatus, Rat,
};

fn to_rat(m: &[Vec<i64>]) -> Vec<Vec<Rat>> {
    m.iter()
        .map(|r| r.iter().map(|&v| frac(v, 1)).collect())
        .collect()
}

fn iv(v: &[i64]) -> Vec<Rat> {
    v.iter().map(|&x| frac(x, 1)).collect()
}

fn square(n: usize, lo: i64, hi: i64) -> impl Strategy<Value = Vec<Vec<i64>>> {
    prop::collection::vec(prop::collection::vec(lo..=hi, n), n)
}

/// (A, B, q, cover).
type Problem = (Vec<Vec<i64>>, Vec<Vec<i64>>, Vec<i64>, Vec<i64>);

/// A [`Problem`] of size 1..=max_n.
fn problem(max_n: usize) -> impl Strategy<Value = Problem> {
    (1..=max_n).prop_flat_map(|n| {
        (
            square(n, -2, 2),
            square(n, -2, 2),
            prop::collection::vec(-6i64..=6, n),
            prop::collection::vec(1i64..=3, n),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// P-matrix: exactly one solution; Lemke finds it with any covering vector.
    #[test]
    fn p_matrix_enumeration_and_lemke_agree((a, b, q, cover) in problem(6)) {
        let m = to_rat(&psd_plus_skew(&a, &b, 1));
        let q = iv(&q);
        let sols = enumerate_exact(&m, &q);
        prop_assert_eq!(sols.len(), 1);
        prop_assert!(sols[0].singular_sets.is_empty());
        prop_assert!(is_lcp_solution(&m, &q, &sols[0].z, &sols[0].w));
        let r = lemke_exact(&m, &q, &iv(&cover), 10_000);
        prop_assert_eq!(r.status, LemkeStatus::Solved);
        prop_assert_eq!(&r.z, &sols[0].z);
        prop_assert_eq!(&r.w, &sols[0].w);
    }

    /// Positive semidefinite (copositive-plus, often singular): Lemke ends on a ray exactly
    /// when there is no solution, which the enumeration (with its singular-set LPs) decides.
    #[test]
    fn psd_lemke_ray_iff_no_solution((a, b, q, cover) in problem(5)) {
        let m = to_rat(&psd_plus_skew(&a, &b, 0));
        let q = iv(&q);
        let r = lemke_exact(&m, &q, &iv(&cover), 10_000);
        prop_assert_ne!(r.status, LemkeStatus::IterationCap);
        let exists = has_solution_exact(&m, &q);
        prop_assert_eq!(r.status == LemkeStatus::Solved, exists);
        if r.status == LemkeStatus::Solved {
            prop_assert!(is_lcp_solution(&m, &q, &r.z, &r.w));
        }
        for s in enumerate_exact(&m, &q) {
            prop_assert!(is_lcp_solution(&m, &q, &s.z, &s.w));
        }
    }

    /// Any matrix: whatever Lemke and the enumeration return is a solution; Lemke terminates.
    #[test]
    fn general_matrices_are_consistent(
        (m, q, cover) in (1usize..=4).prop_flat_map(|n| (
            square(n, -3, 3),
            prop::collection::vec(-4i64..=4, n),
            prop::collection::vec(1i64..=2, n),
        ))
    ) {
        let m = to_rat(&m);
        let q = iv(&q);
        let r = lemke_exact(&m, &q, &iv(&cover), 10_000);
        prop_assert_ne!(r.status, LemkeStatus::IterationCap);
        let sols = enumerate_exact(&m, &q);
        if r.status == LemkeStatus::Solved {
            prop_assert!(is_lcp_solution(&m, &q, &r.z, &r.w));
            prop_assert!(!sols.is_empty());
            // When the list is complete, Lemke's solution is on it.
            if sols.iter().all(|s| s.singular_sets.is_empty()) {
                prop_assert!(sols.iter().any(|s| s.z == r.z));
            }
        }
        for s in &sols {
            prop_assert!(is_lcp_solution(&m, &q, &s.z, &s.w));
        }
    }

    /// P-matrix parametric path: p never decreases, never a mechanism, every breakpoint solves
    /// the LCP at its p, and the solution at the target is the unique enumerated one.
    #[test]
    fn p_matrix_path_matches_enumeration(
        (a, b, q0, d, target) in (1usize..=5).prop_flat_map(|n| (
            square(n, -2, 2),
            square(n, -2, 2),
            prop::collection::vec(0i64..=4, n),
            prop::collection::vec(-5i64..=5, n),
            0i64..=20,
        ))
    ) {
        let m = to_rat(&psd_plus_skew(&a, &b, 1));
        let (q0, d) = (iv(&q0), iv(&d));
        let target = frac(target, 2);
        let path = parametric_path_exact(&m, &q0, &d, Some(&target), None, 10_000);
        prop_assert!(matches!(path.status, PathStatus::TargetReached | PathStatus::Ray));
        prop_assert!(path.steps.iter().all(|s| !s.p_decreased));
        for pt in &path.points {
            let q = parametric_q(&q0, &d, &pt.p);
            prop_assert!(is_lcp_solution(&m, &q, &pt.z, &pt.x));
        }
        let at = path.solution_at(&target).expect("the target is on the path");
        let sols = enumerate_parametric_exact(&m, &q0, &d, &target);
        prop_assert_eq!(sols.len(), 1);
        prop_assert_eq!(&at.z, &sols[0].z);
        prop_assert_eq!(&at.x, &sols[0].w);
        // Without a target the path ends on a ray, and agrees at every breakpoint.
        let full = parametric_path_exact(&m, &q0, &d, None, None, 10_000);
        prop_assert_eq!(full.status, PathStatus::Ray);
        let beyond = full.last_p().unwrap() + frac(1, 1);
        let s = full.solution_at(&beyond).unwrap();
        let q = parametric_q(&q0, &d, &beyond);
        prop_assert!(is_lcp_solution(&m, &q, &s.z, &s.x));
    }

    /// Any matrix, any priority: the path terminates, every breakpoint and every point on a
    /// final ray or at the target solves the LCP at its p, and p is exact at each step.
    #[test]
    fn general_paths_are_solutions(
        (m, q0, d, perm) in (1usize..=4).prop_flat_map(|n| (
            square(n, -3, 3),
            prop::collection::vec(0i64..=3, n),
            prop::collection::vec(-3i64..=3, n),
            Just((0..n).collect::<Vec<usize>>()).prop_shuffle(),
        ))
    ) {
        let m = to_rat(&m);
        let (q0, d) = (iv(&q0), iv(&d));
        let path = parametric_path_exact(&m, &q0, &d, Some(&frac(5, 1)), Some(&perm), 10_000);
        prop_assert_ne!(path.status, PathStatus::IterationCap);
        prop_assert_ne!(path.status, PathStatus::InfeasibleStart);
        prop_assert!(path.points.len() > path.steps.len());
        for (st, pt) in path.steps.iter().zip(&path.points[1..]) {
            prop_assert_eq!(&st.p, &pt.p);
        }
        for pt in &path.points {
            let q = parametric_q(&q0, &d, &pt.p);
            prop_assert!(is_lcp_solution(&m, &q, &pt.z, &pt.x));
        }
        if let Some(ray) = &path.ray {
            let last = path.points.last().unwrap();
            let t = frac(7, 3);
            let p = &last.p + &t * &ray.dp;
            let z: Vec<Rat> = last.z.iter().zip(&ray.dz).map(|(a, b)| a + &t * b).collect();
            let x: Vec<Rat> = last.x.iter().zip(&ray.dx).map(|(a, b)| a + &t * b).collect();
            prop_assert!(is_lcp_solution(&m, &parametric_q(&q0, &d, &p), &z, &x));
        }
        if path.status == PathStatus::TargetReached {
            prop_assert_eq!(&path.points.last().unwrap().p, &frac(5, 1));
        }
    }
}
