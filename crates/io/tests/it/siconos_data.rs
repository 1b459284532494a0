//! Every Siconos LCP test problem of `tests/data/siconos/lcp/` is read with `read_lcp` and solved with
//! `solve_lcp`; the answer is checked independently of the engine (`w = Mz + q` recomputed here,
//! signs, complementarity, and a brute-force enumeration of all complementary bases written in
//! this file). The FC2D problem of `tests/data/siconos/fc2d/` is solved through the classical
//! flexibility-form LCP and checked against the Coulomb conditions of the FC2D problem itself.
//!
//! The files are part of the repository (Apache-2.0, attribution in
//! `tests/data/siconos/README.md`); a missing or an unlisted file is a test failure, never a skip.
//!
//! # How each file ends, and why
//!
//! | file                        | n  | status | strategy               | pivots | why |
//! |-----------------------------|----|--------|------------------------|--------|-----|
//! | `lcp_CPS_1`                 | 2  | Solved | Lemke, covering ones   | 2      | `M = [[1,1],[1,1]]`, `q = −e`: the solutions are the segment `z1 + z2 = 1`; Lemke ends at `z = (0, 1)`. |
//! | `lcp_CPS_2`                 | 3  | Solved | Lemke, covering ones   | 5      | CPS Example 4.4.7; `z = (0, 1, 3)`, `w = 0` (fully degenerate solution). |
//! | `lcp_CPS_3`                 | 4  | Solved | Enumeration            | 3      | A bimatrix game `M = [[0, A], [Bᵀ, 0]]`, `A, B > 0`, `q = −e`. Lemke with *any* positive covering vector `d` ends on a secondary ray after one pivot (proof below), so all three covering vectors fail (1 pivot each) and the engine's enumeration fallback (`n ≤ 16`) finds the pure equilibrium `z = (0.1, 0, 0.1, 0)`, `w = (0, 2, 0, 2)`. |
//! | `lcp_Pang_isolated_sol`     | 3  | Solved | Lemke, covering ones   | 3      | `z = (1, 0, 0)` with `w = 0`: an isolated, fully degenerate solution; the lexicographic ratio test reaches it. |
//! | `lcp_deudeu`                | 2  | Solved | Lemke, covering ones   | 3      | Symmetric positive definite: `z = (4/3, 7/3)`. |
//! | `lcp_enum_fails`            | 9  | Solved | Lemke, covering ones   | 8      | Named for Siconos' enumerative solver failing on it; Lemke solves it directly (all `z` of order `1e-4`, residual ~1e-16). |
//! | `lcp_exp_murty`             | 6  | Solved | Lemke, covering ones   | 2      | Murty's triangular matrix (1 on the diagonal, 2 above). Exponential pivot counts on this matrix are for other methods / other `q`; with `q = −e` and covering `e` the first ratio test is a six-way tie, the lexicographic rule picks row 6, `z6` enters and drives `z0` out: `z = e6`, `w = (1,1,1,1,1,0)`. |
//! | `lcp_mmc`                   | 26 | Solved | Lemke, covering ones   | 23     | Entries up to 1.5e5, `q` ~1: the power-of-two equilibration keeps the residual at ~2e-16. Too large for the enumeration cross-check. |
//! | `lcp_ortiz`                 | 4  | Solved | Lemke, covering ones   | 3      | `z = (2/3, 0, 1/3, 0)`. |
//! | `lcp_trivial`               | 9  | Solved | Lemke, covering ones   | 10     | Diagonal `M = diag(1..9)`, `q = −e`: `z_i = 1/i`; one pivot per row plus the first. |
//!
//! No file ends with `Ray`: every one has a solution (the enumeration below finds one for each
//! `n ≤ 16`), and the engine finds it. The test still knows the `Ray` case: it is accepted only
//! where the table says so and the enumeration here finds no solution either.
//!
//! **Why Lemke cannot solve `lcp_CPS_3`.** Let `d > 0` be the covering vector. The first pivot
//! brings `z0` in at `z0 = max_i(−q_i/d_i)` and row `r` leaves; then `z_r` enters. Its updated
//! column changes `z0` by `−M_rr/d_r = 0` and each other basic `w_i` by `M_ir ≥ 0`, so no basic
//! variable decreases as `z_r` grows: a secondary ray after one pivot, for every `d > 0`. (This is
//! why bimatrix games are solved by Lemke–Howson, not by Lemke with a covering vector.)
//!
//! # The FC2D file
//!
//! `FC2D_SliderCrankLagrangian00000` is `u = W r + q` with `r = (r_n, r_t)` per contact and the
//! Coulomb law `0 ≤ u_n ⊥ r_n ≥ 0`, `−u_t ∈ ∂ψ_[−μ r_n, μ r_n](r_t)`. It is written as the
//! classical `4·nc` flexibility LCP (`r_t = r_t+ − r_t-`, `λ` the sliding speed):
//!
//! ```text
//! u_n            = W_nn r_n + W_nt (r_t+ − r_t-) + q_n  ≥ 0  ⊥ r_n  ≥ 0
//! λ + u_t        = …                                    ≥ 0  ⊥ r_t+ ≥ 0
//! λ − u_t        = …                                    ≥ 0  ⊥ r_t- ≥ 0
//! μ r_n − r_t+ − r_t-                                   ≥ 0  ⊥ λ    ≥ 0
//! ```
//!
//! solved with `solve_lcp`, and the result is checked against the FC2D conditions directly.
//! The conversion to the `3m` stiffness LCP of `unilateral-contact` (`R = W⁻¹`) is **not** done:
//! `W` of this file is singular (its columns 2 and 4, the tangential directions of the two
//! contacts, are identical), so no contact stiffness matrix exists; the test asserts that.

use crate::common;

use common::{siconos, siconos_files};

use faer::Mat;
use unilateral_io::{read_fc2d, read_lcp};
use unilateral_lcp::{solve_lcp, Lcp, LcpStatus, Settings, Strategy};

/// Expected outcome of each file: status, strategy (as `Strategy`'s `Debug`), pivots.
const EXPECTED: &[(&str, LcpStatus, &str, usize)] = &[
    ("lcp_CPS_1", LcpStatus::Solved, "ones", 2),
    ("lcp_CPS_2", LcpStatus::Solved, "ones", 5),
    ("lcp_CPS_3", LcpStatus::Solved, "enumeration", 3),
    ("lcp_Pang_isolated_sol", LcpStatus::Solved, "ones", 3),
    ("lcp_deudeu", LcpStatus::Solved, "ones", 3),
    ("lcp_enum_fails", LcpStatus::Solved, "ones", 8),
    ("lcp_exp_murty", LcpStatus::Solved, "ones", 2),
    ("lcp_mmc", LcpStatus::Solved, "ones", 23),
    ("lcp_ortiz", LcpStatus::Solved, "ones", 3),
    ("lcp_trivial", LcpStatus::Solved, "ones", 10),
];

fn strategy_name(s: &Strategy) -> &'static str {
    match s {
        Strategy::Trivial => "trivial",
        Strategy::Lemke { covering } => covering,
        Strategy::Enumeration => "enumeration",
    }
}

/// `q + M z`, and the magnitude `|q| + |M||z|` row by row.
fn w_of(m: &Mat<f64>, q: &[f64], z: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = q.len();
    let mut w = q.to_vec();
    let mut mag: Vec<f64> = q.iter().map(|v| v.abs()).collect();
    for i in 0..n {
        for (j, &zj) in z.iter().enumerate() {
            w[i] += m[(i, j)] * zj;
            mag[i] += (m[(i, j)] * zj).abs();
        }
    }
    (w, mag)
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, b| a.max(b.abs()))
}

/// Checks `(z, w)` against `w = Mz + q ≥ 0`, `z ≥ 0`, `w_i z_i = 0` with relative tolerance
/// `tol`, from the data alone. Returns a description of the first violation.
fn verify(m: &Mat<f64>, q: &[f64], z: &[f64], w_reported: &[f64], tol: f64) -> Result<(), String> {
    let (w, mag) = w_of(m, q, z);
    let sw = max_abs(&mag).max(f64::MIN_POSITIVE);
    let sz = max_abs(z).max(f64::MIN_POSITIVE);
    for i in 0..q.len() {
        if (w[i] - w_reported[i]).abs() > tol * sw {
            return Err(format!(
                "w[{i}] reported {} but Mz + q = {}",
                w_reported[i], w[i]
            ));
        }
        if w[i] < -tol * sw {
            return Err(format!("w[{i}] = {} < 0 (scale {sw})", w[i]));
        }
        if z[i] < -tol * sz {
            return Err(format!("z[{i}] = {} < 0", z[i]));
        }
        if (w[i] * z[i]).abs() > tol * sw * sz {
            return Err(format!("w[{i}] z[{i}] = {} ≠ 0", w[i] * z[i]));
        }
    }
    Ok(())
}

/// Solves `A x = b` by Gaussian elimination with partial pivoting; `None` if (nearly) singular.
fn gauss(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let k = b.len();
    let scale = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..k {
        let p = (c..k).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs() <= 1e-12 * scale {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        let (top, rest) = a.split_at_mut(c + 1);
        let pivot_row = &top[c];
        for (r, row) in rest.iter_mut().enumerate() {
            let f = row[c] / pivot_row[c];
            for (x, p) in row[c..].iter_mut().zip(&pivot_row[c..]) {
                *x -= f * p;
            }
            b[c + 1 + r] -= f * b[c];
        }
    }
    let mut x = vec![0.0; k];
    for r in (0..k).rev() {
        let s: f64 = (r + 1..k).map(|c| a[r][c] * x[c]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}

/// Every complementary basis with a nonsingular `M[S, S]` whose solution verifies: an
/// enumeration independent of the engine's.
fn enumerate_all(m: &Mat<f64>, q: &[f64]) -> Vec<Vec<f64>> {
    let n = q.len();
    assert!(n <= 16);
    let mut out = Vec::new();
    for s in 0u32..(1 << n) {
        let idx: Vec<usize> = (0..n).filter(|&i| s >> i & 1 == 1).collect();
        let a: Vec<Vec<f64>> = idx
            .iter()
            .map(|&r| idx.iter().map(|&c| m[(r, c)]).collect())
            .collect();
        let b: Vec<f64> = idx.iter().map(|&r| -q[r]).collect();
        let Some(x) = gauss(a, b) else { continue };
        let mut z = vec![0.0; n];
        for (r, &i) in idx.iter().enumerate() {
            z[i] = x[r];
        }
        let (w, _) = w_of(m, q, &z);
        if verify(m, q, &z, &w, 1e-10).is_ok() {
            out.push(z);
        }
    }
    out
}

#[test]
fn every_siconos_lcp_ends_as_expected() {
    let files = siconos_files("lcp");
    assert_eq!(files.len(), EXPECTED.len(), "{files:?}");
    let mut failures = Vec::new();
    for path in &files {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let lcp = read_lcp(path).unwrap_or_else(|e| panic!("{e}"));
        let n = lcp.q.len();
        let sol = solve_lcp(&lcp, &Settings::default()).unwrap();
        println!(
            "{stem:24} n = {n:2}: {:?} by {:?} in {} pivots; {:?}",
            sol.status, sol.strategy, sol.pivots, sol.attempts
        );
        let Some(&(_, status, strategy, pivots)) = EXPECTED.iter().find(|e| e.0 == stem) else {
            failures.push(format!(
                "{stem}: not in the table of expected outcomes (got {:?} by {:?})",
                sol.status, sol.strategy
            ));
            continue;
        };
        if sol.status != status {
            failures.push(format!("{stem}: {:?}, expected {status:?}", sol.status));
            continue;
        }
        if strategy_name(&sol.strategy) != strategy || sol.pivots != pivots {
            failures.push(format!(
                "{stem}: {:?} in {} pivots, expected {strategy} in {pivots}",
                sol.strategy, sol.pivots
            ));
        }
        let solutions = (n <= 16).then(|| enumerate_all(&lcp.m, &lcp.q));
        match status {
            LcpStatus::Solved => {
                let p = sol.point.as_ref().expect("a solved LCP has a point");
                if p.residual.max() > 1e-10 {
                    failures.push(format!("{stem}: residual {:?}", p.residual));
                }
                if let Err(e) = verify(&lcp.m, &lcp.q, &p.z, &p.w, 1e-10) {
                    failures.push(format!("{stem}: {e}"));
                }
                if solutions.as_ref().is_some_and(|s| s.is_empty()) {
                    failures.push(format!("{stem}: solved, but the enumeration finds nothing"));
                }
            }
            LcpStatus::Ray => {
                assert!(sol.point.is_none());
                match &solutions {
                    Some(s) if s.is_empty() => {}
                    Some(s) => failures.push(format!(
                        "{stem}: Ray, but the enumeration finds {} solutions, e.g. {:?}",
                        s.len(),
                        s[0]
                    )),
                    None => failures.push(format!("{stem}: Ray on n = {n} > 16 is unproven")),
                }
            }
            LcpStatus::IterationLimit => failures.push(format!("{stem}: pivot cap")),
            LcpStatus::NumericalFailure => failures.push(format!("{stem}: numerical failure")),
        }
    }
    for (name, ..) in EXPECTED {
        if !files.iter().any(|p| p.file_stem().unwrap() == *name) {
            failures.push(format!("{name}.dat is listed but missing"));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

/// The secondary ray of `lcp_CPS_3` does not depend on the covering vector (see the module
/// documentation): a user covering vector fails as well, and enumeration answers.
#[test]
fn cps_3_defeats_every_covering_vector() {
    let lcp = read_lcp(&siconos("lcp").join("lcp_CPS_3.dat")).unwrap();
    for cov in [vec![1.0, 2.0, 3.0, 4.0], vec![5.0, 1.0, 0.5, 2.0]] {
        let sol = solve_lcp(
            &lcp,
            &Settings {
                covering: Some(cov.clone()),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(
            sol.strategy,
            Strategy::Enumeration,
            "{cov:?}: {:?}",
            sol.attempts
        );
        assert!(
            sol.attempts[0].contains("secondary ray after 1 pivots"),
            "{:?}",
            sol.attempts
        );
        let p = sol.point.unwrap();
        verify(&lcp.m, &lcp.q, &p.z, &p.w, 1e-10).unwrap();
    }
    // The pure equilibrium (row 1, column 1 of the game).
    let all = enumerate_all(&lcp.m, &lcp.q);
    assert!(all.iter().any(|z| z
        .iter()
        .zip([0.1, 0.0, 0.1, 0.0])
        .all(|(a, b)| (a - b).abs() < 1e-12)));
}

#[test]
fn fc2d_slider_crank_through_the_flexibility_lcp() {
    let p = read_fc2d(&siconos("fc2d").join("FC2D_SliderCrankLagrangian00000.dat")).unwrap();
    let nc = p.contacts();
    let w = &p.w;
    // W is singular: the stiffness form R = W⁻¹ of the 3m contact LCP does not exist.
    for i in 0..2 * nc {
        assert_eq!(
            w[(i, 1)],
            w[(i, 3)],
            "columns 2 and 4 of W differ in row {i}"
        );
    }

    // Unknowns per contact c: r_n(c), r_t+(c), r_t-(c), λ(c) at 4c .. 4c + 3.
    let n = 4 * nc;
    let mut m = Mat::<f64>::zeros(n, n);
    let mut q = vec![0.0; n];
    for a in 0..nc {
        let (na, ta) = (2 * a, 2 * a + 1);
        for b in 0..nc {
            let (nb, tb) = (2 * b, 2 * b + 1);
            // u_n(a) row.
            m[(4 * a, 4 * b)] = w[(na, nb)];
            m[(4 * a, 4 * b + 1)] = w[(na, tb)];
            m[(4 * a, 4 * b + 2)] = -w[(na, tb)];
            // λ + u_t(a) and λ − u_t(a) rows.
            for (row, s) in [(4 * a + 1, 1.0), (4 * a + 2, -1.0)] {
                m[(row, 4 * b)] = s * w[(ta, nb)];
                m[(row, 4 * b + 1)] = s * w[(ta, tb)];
                m[(row, 4 * b + 2)] = -s * w[(ta, tb)];
            }
        }
        m[(4 * a + 1, 4 * a + 3)] = 1.0;
        m[(4 * a + 2, 4 * a + 3)] = 1.0;
        // μ r_n − r_t+ − r_t- row.
        m[(4 * a + 3, 4 * a)] = p.mu[a];
        m[(4 * a + 3, 4 * a + 1)] = -1.0;
        m[(4 * a + 3, 4 * a + 2)] = -1.0;
        q[4 * a] = p.q[na];
        q[4 * a + 1] = p.q[ta];
        q[4 * a + 2] = -p.q[ta];
    }
    let lcp = Lcp { m, q };
    let sol = solve_lcp(&lcp, &Settings::default()).unwrap();
    println!(
        "FC2D slider crank as a {n}-LCP: {:?} by {:?} in {} pivots",
        sol.status, sol.strategy, sol.pivots
    );
    assert_eq!(sol.status, LcpStatus::Solved, "{:?}", sol.attempts);
    let pt = sol.point.unwrap();
    assert!(pt.residual.max() <= 1e-10, "{:?}", pt.residual);
    verify(&lcp.m, &lcp.q, &pt.z, &pt.w, 1e-10).unwrap();

    // The Coulomb conditions of the FC2D problem itself, from u = W r + q.
    let mut r = vec![0.0; 2 * nc];
    for c in 0..nc {
        r[2 * c] = pt.z[4 * c];
        r[2 * c + 1] = pt.z[4 * c + 1] - pt.z[4 * c + 2];
    }
    let (u, mag) = w_of(w, &p.q, &r);
    let su = max_abs(&mag);
    let sr = max_abs(&r);
    let tol = 1e-10;
    println!("r = {r:?}, u = {u:?}");
    for c in 0..nc {
        let (rn, rt, un, ut) = (r[2 * c], r[2 * c + 1], u[2 * c], u[2 * c + 1]);
        let bound = p.mu[c] * rn;
        assert!(
            rn >= -tol * sr && un >= -tol * su,
            "contact {c}: r_n {rn}, u_n {un}"
        );
        assert!(
            (rn * un).abs() <= tol * sr * su,
            "contact {c}: r_n u_n = {}",
            rn * un
        );
        assert!(
            rt.abs() <= bound + tol * sr,
            "contact {c}: |r_t| {rt} > μ r_n {bound}"
        );
        if ut.abs() > tol * su {
            // Sliding: the friction force is at the bound and opposes the velocity.
            assert!(
                (rt + ut.signum() * bound).abs() <= tol * sr,
                "contact {c}: sliding with u_t {ut} but r_t {rt}, μ r_n {bound}"
            );
        } else {
            assert!(ut.abs() <= tol * su);
        }
    }
    // The slider crank is pressed: both contacts carry a normal force.
    assert!(r[0] > 0.0 || r[2] > 0.0);
}
