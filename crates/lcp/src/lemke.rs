//! The standard LCP `w = M z + q` by Lemke's method with a covering vector, with fallbacks.

use crate::pivoting::basis::Basis;
use crate::pivoting::columns::Columns;
use crate::pivoting::enumerate::enumerate_first;
use crate::pivoting::pivot::{max_abs, Ending, Pivoter, Tolerances};
use crate::pivoting::prepare::{check_matrix, check_vector, Prepared};
use crate::{Lcp, LcpError, LcpPoint, LcpSolution, LcpStatus, Residual, Settings, Strategy};

/// Solves `w = M z + q, w ≥ 0, z ≥ 0, wᵀz = 0`.
///
/// Lemke's method with the covering vector of `settings` (default all ones) and the
/// lexicographic ratio test. A secondary ray of Lemke's method does not prove that no solution
/// exists, so before answering [`LcpStatus::Ray`] other covering vectors are tried and, for
/// `n ≤ 16`, all complementary bases are enumerated. A solution is reported only with residuals
/// verified from the original data (at most [`crate::ACCEPT_RESIDUAL`], every number finite).
///
/// ```
/// use faer::mat;
/// use unilateral_lcp::{solve_lcp, Lcp, LcpStatus, Settings};
///
/// // w1 = 2 z1 + z2 − 5, w2 = z1 + 2 z2 − 6
/// let lcp = Lcp { m: mat![[2.0, 1.0], [1.0, 2.0]], q: vec![-5.0, -6.0] };
/// let sol = solve_lcp(&lcp, &Settings::default()).unwrap();
/// assert_eq!(sol.status, LcpStatus::Solved);
/// let p = sol.point.unwrap();
/// assert!((p.z[0] - 4.0 / 3.0).abs() < 1e-12 && (p.z[1] - 7.0 / 3.0).abs() < 1e-12);
/// assert!(p.residual.max() < 1e-12);
/// ```
pub fn solve_lcp(lcp: &Lcp, settings: &Settings) -> Result<LcpSolution, LcpError> {
    let n = check_matrix(&lcp.m)?;
    check_vector("q", &lcp.q, n)?;
    settings.validate(n)?;
    if lcp.q.iter().all(|&v| v >= 0.0) {
        let z = vec![0.0; n];
        let w = lcp.q.clone();
        let residual = Residual::of(&lcp.m, &lcp.q, &w, &z);
        return Ok(LcpSolution {
            status: LcpStatus::Solved,
            point: Some(LcpPoint { z, w, residual }),
            pivots: 0,
            strategy: Strategy::Trivial,
            attempts: vec!["q ≥ 0: z = 0".into()],
        });
    }
    // Equilibrated whatever the units of rows and unknowns, each block that M couples brought
    // to the size of its q, so that a block whose data are all tiny is as visible to the
    // pivoting as any other; the built-in covering vectors are chosen in the equilibrated
    // problem, where every row has entries of order one (a covering vector of ones in the
    // original units would be `E·1` there, as lopsided as the units).
    let prep = Prepared::for_lcp(&lcp.m, &lcp.q);
    let qhat = prep.scaling.scale_rows(&lcp.q);
    let original = |v: Vec<f64>| prep.scaling.unscale_x(&v);
    let mut coverings: Vec<(&'static str, Vec<f64>)> = Vec::new();
    match &settings.covering {
        Some(c) => coverings.push(("user", c.clone())),
        None => coverings.push(("ones", original(vec![1.0; n]))),
    }
    coverings.push((
        "graded",
        original((0..n).map(|i| 1.0 + i as f64 / n as f64).collect()),
    ));
    let qmean = qhat.iter().map(|v| v.abs()).sum::<f64>() / n as f64;
    coverings.push((
        "|q|",
        original(qhat.iter().map(|v| v.abs() + qmean).collect()),
    ));
    let mut attempts = Vec::new();
    let mut pivots = 0;
    let mut last_status = LcpStatus::Ray;
    let mut last_strategy = Strategy::Lemke { covering: "ones" };
    let mut unverified = false;
    settings.progress.phase(crate::Phase::Lemke);
    for (name, cov) in &coverings {
        let run = lemke_run(&prep, &lcp.q, cov, settings);
        settings.progress.pivots(run.pivots);
        pivots += run.pivots;
        last_strategy = Strategy::Lemke { covering: name };
        match run.outcome {
            LemkeOutcome::Solved(slots, beta) => {
                let (w, z) = prep.unscale(&slots, &beta);
                let residual = Residual::of(&lcp.m, &lcp.q, &w, &z);
                if residual.accepts(&w, &z) {
                    attempts.push(format!(
                        "Lemke, covering '{name}': solved in {} pivots",
                        run.pivots
                    ));
                    return Ok(LcpSolution {
                        status: LcpStatus::Solved,
                        point: Some(LcpPoint { z, w, residual }),
                        pivots,
                        strategy: last_strategy,
                        attempts,
                    });
                }
                attempts.push(format!(
                    "Lemke, covering '{name}': basis found but its point does not verify \
                     (residual {:.1e}{})",
                    residual.max(),
                    if w.iter().chain(&z).all(|v| v.is_finite()) {
                        ""
                    } else {
                        ", numbers beyond the floating-point range"
                    }
                ));
                unverified = true;
            }
            LemkeOutcome::Ray => {
                attempts.push(format!(
                    "Lemke, covering '{name}': secondary ray after {} pivots",
                    run.pivots
                ));
                last_status = LcpStatus::Ray;
            }
            LemkeOutcome::IterationLimit => {
                attempts.push(format!(
                    "Lemke, covering '{name}': pivot cap reached ({} pivots)",
                    run.pivots
                ));
                last_status = LcpStatus::IterationLimit;
            }
            LemkeOutcome::Singular => {
                attempts.push(format!(
                    "Lemke, covering '{name}': numerically singular basis after {} pivots",
                    run.pivots
                ));
            }
        }
    }
    if n <= 16 {
        // On the equilibrated problem, so that its tolerances too meet data of order one.
        if let Some((zhat, what, _)) = enumerate_first(&prep.matrix(), &qhat) {
            let z = prep.scaling.unscale_z(&zhat);
            let w = prep.scaling.unscale_x(&what);
            let residual = Residual::of(&lcp.m, &lcp.q, &w, &z);
            if residual.accepts(&w, &z) {
                attempts.push("enumeration of complementary bases: solved".into());
                return Ok(LcpSolution {
                    status: LcpStatus::Solved,
                    point: Some(LcpPoint { z, w, residual }),
                    pivots,
                    strategy: Strategy::Enumeration,
                    attempts,
                });
            }
            attempts.push(format!(
                "enumeration of complementary bases: a basis found but its point does not \
                 verify in the original units (residual {:.1e})",
                residual.max()
            ));
            unverified = true;
        } else {
            attempts.push("enumeration of complementary bases: no solution".into());
        }
        last_status = LcpStatus::Ray;
        last_strategy = Strategy::Enumeration;
    }
    if unverified && last_status == LcpStatus::Ray {
        // A basis was found whose point could not be verified: that is the engine's failure,
        // not evidence that the problem has no solution.
        last_status = LcpStatus::NumericalFailure;
    }
    Ok(LcpSolution {
        status: last_status,
        point: None,
        pivots,
        strategy: last_strategy,
        attempts,
    })
}

pub(crate) enum LemkeOutcome {
    /// Final complementary basis (slot → column) and its basic values (equilibrated units).
    Solved(Vec<usize>, Vec<f64>),
    Ray,
    IterationLimit,
    Singular,
}

pub(crate) struct LemkeRun {
    pub outcome: LemkeOutcome,
    pub pivots: usize,
}

/// One run of Lemke's method on `w = q + cov·z0 + M z` (original units in `q`, `cov`).
pub(crate) fn lemke_run(prep: &Prepared, q: &[f64], cov: &[f64], settings: &Settings) -> LemkeRun {
    let n = prep.n;
    let cols: Columns = prep.columns(q, cov);
    let tol = Tolerances {
        pivot: settings.pivot_tol(),
        value: 1e-13,
    };
    let mut piv = Pivoter::new(
        &cols,
        Basis::slack(n),
        tol,
        settings.priority(n),
        settings.refactor_interval,
    );
    let driver = cols.driver();
    let alpha = piv.basis.ftran(&cols, driver);
    let Some(slot) = piv.lemke_first_slot(&alpha) else {
        let beta = cols.values(&piv.beta);
        return LemkeRun {
            outcome: LemkeOutcome::Solved(piv.basis.slot_var.clone(), beta),
            pivots: 0,
        };
    };
    let theta = piv.beta[slot] / alpha[slot];
    let leaving = match piv.pivot(driver, slot, theta, &alpha) {
        Ok(l) => l,
        Err(_) => {
            return LemkeRun {
                outcome: LemkeOutcome::Singular,
                pivots: piv.pivots,
            }
        }
    };
    let entering = cols.complement(leaving).expect("a slack left");
    let mut records = Vec::new();
    let mut crossed = None;
    let (ending, _) = piv.run(entering, None, settings.cap(n), &mut records, &mut crossed);
    let outcome = match ending {
        Ending::DriverLeft => {
            // Fresh factorisation of the final basis from the data.
            match piv.refactor() {
                Ok(()) => LemkeOutcome::Solved(piv.basis.slot_var.clone(), cols.values(&piv.beta)),
                Err(_) => LemkeOutcome::Singular,
            }
        }
        // A ray with the artificial variable already at zero is a solution, not a ray.
        // Judged relative to the data it meets: the driver's contribution `z0·g` against `h`.
        Ending::Ray { .. }
            if piv.driver_value_scaled() * max_abs(&cols.g) <= 1e-12 * max_abs(&cols.h) =>
        {
            LemkeOutcome::Solved(piv.basis.slot_var.clone(), cols.values(&piv.beta))
        }
        Ending::Ray { .. } => LemkeOutcome::Ray,
        Ending::TargetReached => unreachable!("no target in Lemke's method"),
        Ending::IterationLimit => LemkeOutcome::IterationLimit,
        Ending::Singular => LemkeOutcome::Singular,
    };
    LemkeRun {
        outcome,
        pivots: piv.pivots,
    }
}
