//! The solution without tightening at many loads of a traced path in one walk along it
//! ([`crate::PathSolver::points_at`]).
//!
//! [`crate::PathSolver::solution_at`] rebuilds the basis of the load's segment from the path's
//! records and factorises it afresh, `O(k³)` per load. The sweep instead keeps one basis of
//! the path (with the load `p` as a basic column) and updates it by the path's own pivots, so
//! that moving from one segment to the next costs one column solve and a rank-one update of the
//! kernel inverse, `O(n·k + k²)`, as tracing did. At a requested load on segment `j` the
//! complementary basis of the segment (the driver's column replaced by the segment's entering
//! column) is evaluated at `q0 + p·d` by one solve and a rank-one correction of it, with no
//! basis of its own. Only when that basis is infeasible without the tightening is the
//! tightening driven out, on a copy, for at most [`TIGHTENING_PIVOTS`] pivots. Every point is
//! verified from the original data; anything the sweep cannot settle cheaply (a singular or
//! inaccurate update, a longer removal of the tightening, a residual that does not verify) is
//! answered by `solution_at`'s own procedure, so the answers are those of `solution_at` (the
//! same scheme and verified residuals; not the same last bits: `solution_at` refines its
//! kernel values from a fresh factorisation, `Basis::solve_refined`, and the sweep's quick
//! points come from the updated inverse).

use crate::parametric::{clamp, solution_on_segment};
use crate::pivoting::basis::Basis;
use crate::pivoting::columns::Columns;
use crate::pivoting::pivot::{max_abs, Ending, Pivoter, Tolerances};
use crate::{LoadPath, PathPoint, PathSolver, PathStatus};

/// The least number of pivots allowed for removing the tightening at one load within the
/// sweep. The bound grows with the basis (see [`removal_cap`]); a point that needs more is
/// computed as [`crate::PathSolver::solution_at`] computes it.
pub(crate) const TIGHTENING_PIVOTS: usize = 12;

/// Pivots allowed for removing the tightening on a copy of a basis with a kernel of order `k`
/// in a problem of order `n`: a pivot costs about `n·k`, the fresh factorisation that
/// `solution_at` starts from about `k³`, so up to `k²/n` pivots cost no more than that
/// factorisation (at least [`TIGHTENING_PIVOTS`]). A point that needs more falls back.
fn removal_cap(k: usize, n: usize) -> usize {
    (k * k / n.max(1)).max(TIGHTENING_PIVOTS)
}

/// Relative kernel residual of a column solve above which the sweep's basis is refactorised
/// (the engine's own threshold).
const DRIFT: f64 = 1e-9;

/// The solutions at `loads` (in any order) on `path`, one per load, `None` off the path.
pub(crate) fn points_at(
    solver: &PathSolver,
    path: &LoadPath,
    loads: &[f64],
) -> Vec<Option<PathPoint>> {
    let mut out: Vec<Option<PathPoint>> = vec![None; loads.len()];
    // (segment, request index), walked in the order of the segments.
    let mut todo: Vec<(usize, usize)> = loads
        .iter()
        .enumerate()
        .filter_map(|(i, &p)| segment_of(path, p).map(|j| (j, i)))
        .collect();
    todo.sort_unstable();
    if todo.is_empty() {
        return out;
    }
    let prep = &solver.prep;
    // The path's own columns: the basis depends on `M` and the driver's direction `d` only.
    let cols_path = prep.columns(solver.q0(), solver.d());
    let mut walk = Basis::from_slots(&cols_path, path.start_slots.clone()).ok();
    let mut at = 0usize; // pivots applied to `walk`
    let mut since_refactor = 0usize;
    let interval = solver.settings().refactor_interval.max(1);
    for (seg, i) in todo {
        let p = loads[i];
        // Bring the walk to segment `seg`.
        while walk.is_some() && at < seg {
            let b = walk.as_mut().expect("checked");
            let (entering, leaving) = path.records[at];
            let (alpha, drift) = b.ftran_checked(&cols_path, entering);
            let slot = b.var_slot[leaving];
            if slot == usize::MAX || alpha[slot].abs() <= 1e-14 * max_abs(&alpha) || drift > DRIFT {
                // Refactorise and try again once; give the walk up if the basis is singular.
                if since_refactor > 0 && b.refactor(&cols_path).is_ok() {
                    since_refactor = 0;
                    continue;
                }
                walk = None;
                break;
            }
            b.pivot(&cols_path, entering, slot, &alpha);
            at += 1;
            since_refactor += 1;
            if since_refactor >= interval.max(b.kernel_size() / 4) {
                if b.refactor(&cols_path).is_err() {
                    walk = None;
                    break;
                }
                since_refactor = 0;
            }
        }
        let quick = walk
            .as_ref()
            .and_then(|b| evaluate(solver, path, b, seg, p));
        out[i] = match quick {
            Some(pt) => Some(pt),
            None => solution_on_segment(solver, path, seg, p).ok(),
        };
    }
    out
}

/// The segment on which [`crate::PathSolver::solution_at`] evaluates load `p` (the last one
/// whose loads contain it; for a ray, the last one beyond the last event).
fn segment_of(path: &LoadPath, p: f64) -> Option<usize> {
    let seg = match path.last_segment_containing(p) {
        Some(j) if path.records.get(j).is_some() || j + 1 < path.breakpoints.len() => Some(j),
        _ => None,
    };
    seg.or_else(|| {
        let last = path.breakpoints.last().map_or(0.0, |b| b.p);
        // beyond the last event: the ray, or the segment a path stopped at its target ends on
        // (up to the target; from p = 0 itself on a path without an event before it)
        let on_last = match path.status {
            PathStatus::Ray => p >= last,
            PathStatus::TargetReached => p >= last && p <= path.p_max,
            _ => false,
        };
        on_last.then_some(path.records.len())
    })
}

/// The point at `p` on segment `seg` from the walk's basis `b` of that segment, or `None` when
/// the sweep cannot settle it cheaply (the caller then computes it as `solution_at` does).
fn evaluate(
    solver: &PathSolver,
    path: &LoadPath,
    b: &Basis,
    seg: usize,
    p: f64,
) -> Option<PathPoint> {
    let prep = &solver.prep;
    let n = prep.n;
    let driver = 2 * n;
    let q_real: Vec<f64> = solver.q_at(p);
    // Same `M` and driver direction as the path's columns, so the walk's basis serves.
    let cols = prep.columns(&q_real, solver.d());
    let mut slots = b.slot_var.clone();
    let mut beta = b.solve(&cols, &cols.h);
    let mut replaced: Option<(usize, usize, Vec<f64>)> = None;
    if let Some(ds) = slots.iter().position(|&v| v == driver) {
        // The driver's column gives way to the segment's entering column `e`:
        // with `α = B⁻¹ A_e`, `β' = β − α·β_ds/α_ds` and `β'_ds = β_ds/α_ds`.
        let e = path.segment_entering(seg, n)?;
        let (alpha, drift) = b.ftran_checked(&cols, e);
        if drift > DRIFT || alpha[ds].abs() <= 1e-12 * max_abs(&alpha) {
            return None;
        }
        let r = beta[ds] / alpha[ds];
        for (v, a) in beta.iter_mut().zip(&alpha) {
            *v -= r * a;
        }
        beta[ds] = r;
        slots[ds] = e;
        replaced = Some((ds, e, alpha));
    }
    let hmax = max_abs(&cols.h).max(max_abs(&beta)).max(f64::MIN_POSITIVE);
    if beta.iter().all(|&v| v.is_finite() && v >= -1e-12 * hmax) {
        let (x, z) = prep.unscale(&slots, &cols.values(&clamp(&beta)));
        return verified(solver, p, x, z, 0);
    }
    if solver.c0 <= 0.0 {
        return None;
    }
    // Remove the tightening on a copy of the complementary basis, for a few pivots at most.
    let mut basis = b.clone();
    if let Some((ds, e, alpha)) = &replaced {
        basis.pivot(&cols, *e, *ds, alpha);
    }
    let h: Vec<f64> = q_real
        .iter()
        .zip(&solver.cov)
        .map(|(a, c)| a + solver.c0 * c)
        .collect();
    let g: Vec<f64> = solver.cov.iter().map(|c| -c).collect();
    let cols_c = prep.columns(&h, &g);
    let settings = solver.settings();
    let tol = Tolerances {
        pivot: settings.pivot_tol(),
        value: 1e-13,
    };
    let mut piv = Pivoter::new(
        &cols_c,
        basis,
        tol,
        settings.priority(n),
        settings.refactor_interval,
    );
    let (mut records, mut crossed) = (Vec::new(), None);
    let (ending, entering) = piv.run(
        driver,
        Some((solver.c0, true)),
        removal_cap(piv.basis.kernel_size(), n).min(settings.cap(n)),
        &mut records,
        &mut crossed,
    );
    let Ending::TargetReached = ending else {
        return None;
    };
    let spent = piv.pivots;
    let mut last = piv.basis;
    if let Some(ds) = last.slot_var.iter().position(|&v| v == driver) {
        let (alpha, drift) = last.ftran_checked(&cols_c, entering);
        if drift > DRIFT || alpha[ds].abs() <= 1e-12 * max_abs(&alpha) {
            return None;
        }
        last.pivot(&cols_c, entering, ds, &alpha);
    }
    let cols_real: Columns = prep.columns(&q_real, &vec![0.0; n]);
    let beta = last.solve(&cols_real, &cols_real.h);
    let hmax = max_abs(&cols_real.h)
        .max(max_abs(&beta))
        .max(f64::MIN_POSITIVE);
    if !beta.iter().all(|&v| v.is_finite() && v >= -1e-12 * hmax) {
        return None;
    }
    let (x, z) = prep.unscale(&last.slot_var, &cols_real.values(&clamp(&beta)));
    verified(solver, p, x, z, spent)
}

/// The point when it is finite, non-negative and its residuals from the original data verify.
fn verified(
    solver: &PathSolver,
    p: f64,
    x: Vec<f64>,
    z: Vec<f64>,
    pivots: usize,
) -> Option<PathPoint> {
    if x.iter().chain(&z).any(|&v| !v.is_finite() || v < 0.0) {
        return None;
    }
    let residual = solver.residual(p, &x, &z);
    if !residual.accepts(&x, &z) {
        return None;
    }
    Some(PathPoint {
        p,
        x,
        z,
        residual,
        tightening_pivots: pivots,
        fallback: false,
    })
}
