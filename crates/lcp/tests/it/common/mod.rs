//! Helpers shared by the engine's verification tests: conversions between the engine's
//! `faer` data and the oracle's row-major `f64` data, tolerance checks and variable mapping.

#![allow(dead_code)]

use faer::Mat;
use unilateral_lcp::{LcpPoint, PathPoint, PathStatus, Var};
use unilateral_oracle as oracle;

/// Row-major `Vec<Vec<f64>>` to a dense `faer` matrix.
pub fn to_mat(m: &[Vec<f64>]) -> Mat<f64> {
    let n = m.len();
    Mat::<f64>::from_fn(n, n, |i, j| m[i][j])
}

/// Row-major `Vec<Vec<i64>>` to `Vec<Vec<f64>>`.
pub fn to_f64_matrix(m: &[Vec<i64>]) -> Vec<Vec<f64>> {
    m.iter()
        .map(|r| r.iter().map(|&v| v as f64).collect())
        .collect()
}

/// `Aᵀ A + s·I + (B − Bᵀ)`: the oracle's shared construction of (semi)definite test matrices.
pub use oracle::fixtures::random::psd_plus_skew;

/// `|a − b| ≤ tol · max(1, scale)` entrywise, with a readable error.
pub fn assert_close(what: &str, got: &[f64], want: &[f64], tol: f64) -> Result<(), String> {
    if got.len() != want.len() {
        return Err(format!("{what}: length {} vs {}", got.len(), want.len()));
    }
    let scale = want.iter().fold(1.0f64, |a, b| a.max(b.abs()));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        if (g - w).abs() > tol * scale {
            return Err(format!(
                "{what}[{i}]: got {g:e}, expected {w:e} (|diff| = {:e}, tol {:e})\n  got  {got:?}\n  want {want:?}",
                (g - w).abs(),
                tol * scale
            ));
        }
    }
    Ok(())
}

/// An independent tolerance check that `(z, w)` solves `w = M z + q ≥ 0, z ≥ 0, wᵀz = 0`,
/// relative to the scale of the data.
pub fn check_solution(
    m: &[Vec<f64>],
    q: &[f64],
    z: &[f64],
    w: &[f64],
    tol: f64,
) -> Result<(), String> {
    let n = q.len();
    if z.len() != n || w.len() != n {
        return Err("wrong lengths".into());
    }
    let mut scale = q.iter().fold(1.0f64, |a, b| a.max(b.abs()));
    let mut r = q.to_vec();
    for i in 0..n {
        let mut mag = q[i].abs();
        for j in 0..n {
            r[i] += m[i][j] * z[j];
            mag += (m[i][j] * z[j]).abs();
        }
        scale = scale.max(mag).max(w[i].abs());
    }
    let zscale = z.iter().fold(1.0f64, |a, b| a.max(b.abs()));
    for i in 0..n {
        if (w[i] - r[i]).abs() > tol * scale {
            return Err(format!("equation {i}: w = {} but Mz + q = {}", w[i], r[i]));
        }
        if w[i] < -tol * scale {
            return Err(format!("w[{i}] = {} < 0", w[i]));
        }
        if z[i] < -tol * zscale {
            return Err(format!("z[{i}] = {} < 0", z[i]));
        }
        if (w[i] * z[i]).abs() > tol * scale * zscale {
            return Err(format!("w[{i}]·z[{i}] = {}·{} ≠ 0", w[i], z[i]));
        }
    }
    Ok(())
}

/// Checks an engine point of a standard LCP: reported residual and an independent check.
pub fn check_point(m: &[Vec<f64>], q: &[f64], pt: &LcpPoint, tol: f64) -> Result<(), String> {
    if pt.residual.max() > tol {
        return Err(format!("reported residual {:?} above {tol:e}", pt.residual));
    }
    check_solution(m, q, &pt.z, &pt.w, tol)
}

/// Checks an engine path point: reported residual and an independent check at its `p`.
pub fn check_path_point(
    m: &[Vec<f64>],
    q0: &[f64],
    d: &[f64],
    pt: &PathPoint,
    tol: f64,
) -> Result<(), String> {
    let q: Vec<f64> = q0.iter().zip(d).map(|(a, b)| a + pt.p * b).collect();
    if pt.residual.max() > tol {
        return Err(format!(
            "reported residual {:?} above {tol:e} at p = {}",
            pt.residual, pt.p
        ));
    }
    check_solution(m, &q, &pt.z, &pt.x, tol)
}

/// The oracle's name of an engine variable (the driver of a path is the load `p`).
pub fn oracle_var(v: Var) -> oracle::Var {
    match v {
        Var::X(i) => oracle::Var::X(i),
        Var::Z(i) => oracle::Var::Z(i),
        Var::Driver => oracle::Var::P,
    }
}

/// Whether an engine path status means the same as an oracle path status.
pub fn same_status(e: PathStatus, o: oracle::PathStatus) -> bool {
    matches!(
        (e, o),
        (PathStatus::TargetReached, oracle::PathStatus::TargetReached)
            | (PathStatus::Ray, oracle::PathStatus::Ray)
            | (PathStatus::Mechanism, oracle::PathStatus::Mechanism)
            | (
                PathStatus::ReturnedToZero,
                oracle::PathStatus::ReturnedToZero
            )
            | (PathStatus::IterationLimit, oracle::PathStatus::IterationCap)
    )
}

/// `q0 + p·d` in `f64`.
pub fn q_at(q0: &[f64], d: &[f64], p: f64) -> Vec<f64> {
    q0.iter().zip(d).map(|(a, b)| a + p * b).collect()
}

/// Whether an oracle path is nondegenerate: at every breakpoint after a pivot (and at the start)
/// exactly `n + 1` of the `2n + 1` variables `(x, z, p)` are zero, i.e. no basic variable
/// vanishes, so every ratio test had a unique minimiser.
pub fn oracle_path_nondegenerate(path: &oracle::Path, n: usize) -> bool {
    let zero = oracle::frac(0, 1);
    let pivots = path.steps.len();
    path.points.iter().take(pivots + 1).all(|pt| {
        let zeros =
            pt.x.iter().chain(&pt.z).filter(|v| **v == zero).count() + usize::from(pt.p == zero);
        zeros == n + 1
    })
}

/// The engine's path has the oracle's steps (entering, leaving, `p` to 1e-9 relative) and
/// status; otherwise both lists, for the failure message.
pub fn same_events(path: &unilateral_lcp::LoadPath, exact: &oracle::Path) -> Result<(), String> {
    let e: Vec<_> = path
        .steps
        .iter()
        .map(|s| (oracle_var(s.entering), oracle_var(s.leaving), s.p))
        .collect();
    let o: Vec<_> = exact
        .steps
        .iter()
        .map(|s| (s.entering, s.leaving, s.p_f64()))
        .collect();
    let same = e.len() == o.len()
        && e.iter().zip(&o).all(|(a, b)| {
            a.0 == b.0 && a.1 == b.1 && (a.2 - b.2).abs() <= 1e-9 * b.2.abs().max(1.0)
        });
    if same && same_status(path.status, exact.status) {
        Ok(())
    } else {
        Err(format!(
            "engine {:?} {e:?}\n  oracle {:?} {o:?}",
            path.status, exact.status
        ))
    }
}
