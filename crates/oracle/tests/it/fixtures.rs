//! The shared fixtures checked against their own references: Example 1's two number forms
//! against each other, its data against the hand derivation from the beam, its answers against
//! the exact definition of a solution, the hand-built `3m` LCP against the formulas of
//! formulation.md §3, and the generator against the recurrence computed apart.

use unilateral_oracle::fixtures::example1::{self, beam};
use unilateral_oracle::fixtures::frictional_lcp;
use unilateral_oracle::fixtures::random::{psd_plus_skew, Lcg};
use unilateral_oracle::{frac, is_lcp_solution, mz_plus_q, rat, rat_matrix, rat_vec, to_f64};

#[test]
fn example1_f64_and_exact_forms_agree() {
    // Every entry of Rnn, Rtt, Rv_n is dyadic: the f64 constants are the exact rationals.
    assert_eq!(
        rat_matrix(&example1::rows(&example1::RNN)),
        example1::rnn_exact()
    );
    assert_eq!(
        rat_matrix(&example1::rows(&example1::RTT)),
        example1::rtt_exact()
    );
    assert_eq!(rat_vec(&example1::RV_N), example1::rv_n_exact());
    // 0.6 is not 3/5, only its nearest f64.
    assert_ne!(rat(example1::FRICTION), example1::friction_exact());
    assert_eq!(to_f64(&example1::friction_exact()), example1::FRICTION);
    // The answers: each f64 constant is the f64 nearest to the exact value.
    let near = |exact: &[unilateral_oracle::Rat], f: &[f64]| {
        exact.iter().map(to_f64).collect::<Vec<_>>() == f
    };
    assert!(near(&example1::z_at_target_exact(), &example1::Z_AT_TARGET));
    assert!(near(&example1::x_at_target_exact(), &example1::X_AT_TARGET));
    assert!(near(&example1::table3_rhs_exact(), &example1::TABLE3_RHS));
    assert_eq!(
        to_f64(&example1::first_event_p_exact()),
        example1::FIRST_EVENT_P
    );
}

#[test]
fn example1_data_follow_from_the_beam() {
    // Hand derivation (fixtures::example1's documentation): Rnn = k·aaᵀ, a = (1, −2, 1), with
    // 4k the force that pushes the middle support of a simply supported span 2L down by one.
    let span2 = beam::NODE_X[3] - beam::NODE_X[0];
    let k = 48.0 * beam::E * beam::INERTIA / span2.powi(3) / 4.0;
    let a = [1.0, -2.0, 1.0];
    for i in 0..3 {
        for j in 0..3 {
            assert_eq!(example1::RNN[i][j], k * a[i] * a[j], "Rnn[{i}][{j}]");
        }
    }
    // Rtt: a chain of axial links EA/L between the supports (the right span is two elements of
    // length 1 in series).
    let link = beam::E * beam::AREA / (beam::NODE_X[1] - beam::NODE_X[0]);
    let right = 1.0 / (2.0 / (beam::E * beam::AREA / 1.0));
    assert_eq!(link, right);
    let rtt = [
        [link, -link, 0.0],
        [-link, link + right, -right],
        [0.0, -right, right],
    ];
    assert_eq!(example1::RTT, rtt);
    // Rv_n: the bonded beam's reactions balance the unit load in force and in moment about
    // x = 0 (compression positive, the load pointing down).
    let xs = beam::SUPPORTED_NODES.map(|n| beam::NODE_X[n]);
    let force: f64 = example1::RV_N.iter().sum();
    let moment: f64 = example1::RV_N.iter().zip(xs).map(|(r, x)| r * x).sum();
    assert_eq!(force, -beam::LOAD_FY);
    assert_eq!(moment, -beam::LOAD_FY * beam::NODE_X[beam::LOADED_NODE]);
    // Three-moment equation: |M_B| = 3PL/32, R_A = −|M_B|/L.
    let l = beam::NODE_X[1];
    assert_eq!(example1::RV_N[0], -(3.0 * l / 32.0) / l);
}

#[test]
fn example1_answers_solve_its_lcp() {
    // The c = 0 problem x = p·d + M z at p = 1: the fixture's answer is an exact solution.
    let lcp = example1::lcp_exact();
    let (z, x) = (example1::z_at_target_exact(), example1::x_at_target_exact());
    assert_eq!(mz_plus_q(&lcp.m, &z, &lcp.d), x);
    assert!(is_lcp_solution(&lcp.m, &lcp.d, &z, &x));
    // The first event: x_n1 = c + p·Rv_n1 with c = 1 reaches zero at p = −1/Rv_n1.
    let p = example1::first_event_p_exact();
    assert_eq!(frac(1, 1) + &p * &example1::rv_n_exact()[0], frac(0, 1));
    // Table 3's p column is minus the p = 1 answer of its basic variables (z_n1, then x).
    let basic: Vec<f64> = (0..9)
        .map(|i| {
            if i == 0 {
                example1::Z_AT_TARGET[0]
            } else {
                example1::X_AT_TARGET[i]
            }
        })
        .collect();
    for (i, (col, v)) in example1::TABLE3_P_COLUMN.iter().zip(&basic).enumerate() {
        assert_eq!(*col, -v, "row {i}");
    }
    // Exact and f64 assemblies describe the same problem: the f64 one is within round-off of
    // the exact one (0.6·r is rounded), the friction-free parts equal.
    let f = example1::lcp();
    for (i, (row_f, row_e)) in f.m.iter().zip(&lcp.m).enumerate() {
        for (j, (a, b)) in row_f.iter().zip(row_e).enumerate() {
            assert!((a - to_f64(b)).abs() <= 1e-15, "M[{i}][{j}]: {a} vs {b}");
        }
    }
    assert_eq!(f.direction, vec![1.0; 9], "f ≤ 1: the uniform tightening");
}

#[test]
fn frictional_lcp_has_the_entries_of_formulation_section_3() {
    // One pair by hand: Rnn = 2, Rtt = 4, f = 3/2, Rv_n = −1, Rv_t = 1/2.
    let lcp = frictional_lcp(&[vec![2.0]], &[vec![4.0]], &[1.5], &[-1.0], &[0.5]);
    assert_eq!(
        lcp.m,
        vec![
            vec![2.0, 0.0, 0.0],
            vec![3.0, 2.0, -2.0],
            vec![3.0, -2.0, 2.0]
        ]
    );
    assert_eq!(lcp.d, vec![-1.0, -1.0, -2.0]);
    assert_eq!(
        lcp.direction,
        vec![1.0, 1.5, 1.5],
        "max(1, f) on the tangential rows"
    );
    // Two pairs: block positions (row block, column block) of formulation.md §3.
    let r = |v: i64| frac(v, 1);
    let rnn = vec![vec![r(1), r(2)], vec![r(3), r(4)]];
    let rtt = vec![vec![r(6), r(8)], vec![r(10), r(12)]];
    let lcp = frictional_lcp(
        &rnn,
        &rtt,
        &[r(2), frac(1, 2)],
        &[r(1), r(-1)],
        &[r(5), r(7)],
    );
    assert_eq!(lcp.m[1][0], r(3)); // Rnn
    assert_eq!(lcp.m[2][1], r(4)); // F·Rnn, pair 1 (f = 2), Rnn₁₂ = 2
    assert_eq!(lcp.m[5][1], r(2)); // F·Rnn, pair 2 (f = 1/2), Rnn₂₂ = 4
    assert_eq!(lcp.m[2][3], r(4)); // Rtt/2, Rtt₁₂ = 8
    assert_eq!(lcp.m[3][4], r(-5)); // −Rtt/2, Rtt₂₁ = 10
    assert_eq!(lcp.m[5][3], r(-6)); // −Rtt/2, Rtt₂₂ = 12
    assert_eq!(lcp.m[4][4], r(3)); // Rtt/2, Rtt₁₁ = 6
    assert_eq!(lcp.m[0][2], r(0)); // Rnt = 0
    assert_eq!(
        lcp.d,
        vec![r(1), r(-1), r(7), frac(13, 2), r(-3), frac(-15, 2)]
    );
    assert_eq!(lcp.direction, vec![r(1), r(1), r(2), r(1), r(2), r(1)]);
}

#[test]
fn lcg_follows_its_recurrence() {
    // Known answers of s ← 6364136223846793005·s + 1442695040888963407 (mod 2⁶⁴), draws from
    // s >> 33, computed apart (in Python's arbitrary-precision integers).
    let mut g = Lcg::new(5);
    let ints: Vec<i64> = (0..6).map(|_| g.int(-2, 2)).collect();
    assert_eq!(ints, [0, 1, 2, -2, -2, -1]);
    let mut g = Lcg::new(12345);
    let u: Vec<f64> = (0..3).map(|_| g.uniform(-0.5, 0.5)).collect();
    assert_eq!(
        u,
        [
            -0.39042139425873756,
            -0.23461470426991582,
            0.385623992420733
        ]
    );
    // The same seed, the same stream.
    let (mut a, mut b) = (Lcg::new(99), Lcg::new(99));
    assert_eq!(a.square(4, -3, 3), b.square(4, -3, 3));
}

#[test]
fn psd_plus_skew_has_the_quadratic_form_of_its_factors() {
    // zᵀ(AᵀA + sI + B − Bᵀ)z = |Az|² + s|z|² (the skew part adds nothing), exactly in integers.
    let mut g = Lcg::new(3);
    for case in 0..50 {
        let n = 1 + case % 5;
        let int = |m: Vec<Vec<f64>>| -> Vec<Vec<i64>> {
            m.into_iter()
                .map(|r| r.into_iter().map(|v| v as i64).collect())
                .collect()
        };
        let a = int(g.square(n, -3, 3));
        let b = int(g.square(n, -3, 3));
        let s = g.int(0, 2);
        let z: Vec<i64> = g.vector(n, -4, 4).into_iter().map(|v| v as i64).collect();
        let m = psd_plus_skew(&a, &b, s);
        let quad: i64 = (0..n)
            .map(|i| (0..n).map(|j| z[i] * m[i][j] * z[j]).sum::<i64>())
            .sum();
        let az: i64 = a
            .iter()
            .map(|row| row.iter().zip(&z).map(|(x, y)| x * y).sum::<i64>().pow(2))
            .sum();
        let zz: i64 = z.iter().map(|v| v * v).sum();
        assert_eq!(quad, az + s * zz, "case {case}");
    }
    // And p_matrix is A, B from square(−2, 2), s = 1.
    let (mut g1, mut g2) = (Lcg::new(8), Lcg::new(8));
    let (a, b) = (g2.square(3, -2, 2), g2.square(3, -2, 2));
    assert_eq!(g1.p_matrix(3), psd_plus_skew(&a, &b, 1.0));
}
