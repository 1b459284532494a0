//! The tableau of the parametric method in the paper's layout, for display and teaching.

use faer::linalg::solvers::Solve;
use faer::Mat;

use crate::{LoadPath, PathSolver, PathStatus, Var};

/// One tableau: rows labelled by the basic variables, columns `x1…xn, z1…zn, p`, the
/// right-hand side, and the minimum-ratio column of the variable entering next.
///
/// Entries are computed afresh from the original data (`B⁻¹ [E | −M | −d]` and
/// `B⁻¹ (q0 + c·e)`), so they show the exact tableau up to round-off of one factorisation.
#[derive(Debug, Clone, PartialEq)]
pub struct Tableau {
    /// `"initial"`, `"after step k"`, or `"after step k, p out of the basis"`.
    pub title: String,
    /// Number of pivots made before this tableau.
    pub after_steps: usize,
    /// The basic variable of each row.
    pub basis: Vec<Var>,
    /// The column labels: `x1…xn, z1…zn, p`.
    pub columns: Vec<Var>,
    /// `entries[row][col]`.
    pub entries: Vec<Vec<f64>>,
    /// The right-hand side by row.
    pub rhs: Vec<f64>,
    /// The leading (entering) column, if any.
    pub entering: Option<Var>,
    /// `rhs / entry` of the leading column where the entry is positive.
    pub ratios: Vec<Option<f64>>,
    /// The leading row (the one that leaves), if any.
    pub leaving_row: Option<usize>,
}

/// All tableaux of a traced path (see [`PathSolver::tableaux`]).
pub(crate) fn tableaux_of(
    solver: &PathSolver,
    path: &LoadPath,
    max_steps: Option<usize>,
) -> Vec<Tableau> {
    let n = solver.order();
    let (c0, cov) = (solver.c0, &solver.cov);
    let ncol = 2 * n + 1;
    let a = Mat::<f64>::from_fn(n, ncol, |i, j| {
        if j < n {
            if i == j {
                1.0
            } else {
                0.0
            }
        } else if j < 2 * n {
            -solver.prep.original_entry(i, j - n)
        } else {
            -solver.d()[i]
        }
    });
    let h: Vec<f64> = (0..n).map(|i| solver.q0()[i] + c0 * cov[i]).collect();
    let columns: Vec<Var> = (0..ncol).map(|j| Var::from_col(j, n)).collect();
    let k_total = path.records.len();
    let last = max_steps.map_or(k_total, |m| m.min(k_total));
    let mut out = Vec::new();
    let build = |slots: &[usize],
                 title: String,
                 after: usize,
                 entering: Option<usize>,
                 leaving: Option<usize>| {
        let b = Mat::<f64>::from_fn(n, n, |i, s| a[(i, slots[s])]);
        let lu = b.partial_piv_lu();
        let mut rhs_mat = Mat::<f64>::zeros(n, ncol + 1);
        for i in 0..n {
            for j in 0..ncol {
                rhs_mat[(i, j)] = a[(i, j)];
            }
            rhs_mat[(i, ncol)] = h[i];
        }
        let y = lu.solve(&rhs_mat);
        let entries: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..ncol).map(|j| y[(i, j)]).collect())
            .collect();
        let rhs: Vec<f64> = (0..n).map(|i| y[(i, ncol)]).collect();
        let ratios = match entering {
            Some(e) => {
                let cmax = (0..n).fold(0.0f64, |m, i| m.max(entries[i][e].abs()));
                (0..n)
                    .map(|i| {
                        let v = entries[i][e];
                        (v > 1e-9 * cmax).then(|| rhs[i] / v)
                    })
                    .collect()
            }
            None => vec![None; n],
        };
        Tableau {
            title,
            after_steps: after,
            basis: slots.iter().map(|&v| Var::from_col(v, n)).collect(),
            columns: columns.clone(),
            entries,
            rhs,
            entering: entering.map(|e| Var::from_col(e, n)),
            ratios,
            leaving_row: leaving.and_then(|l| slots.iter().position(|&v| v == l)),
        }
    };
    for k in 0..=last {
        let slots = path.slots_after(k);
        let (entering, leaving) = if k < k_total {
            (Some(path.records[k].0), Some(path.records[k].1))
        } else {
            (path.segment_entering(k, n), None)
        };
        let title = if k == 0 {
            "initial".to_string()
        } else {
            format!("after step {k}")
        };
        out.push(build(&slots, title, k, entering, leaving));
    }
    if last == k_total && matches!(path.status, PathStatus::Ray | PathStatus::TargetReached) {
        let mut slots = path.final_slots();
        if let (Some(ds), Some(e)) = (
            slots.iter().position(|&v| v == 2 * n),
            path.segment_entering(k_total, n),
        ) {
            slots[ds] = e;
            out.push(build(
                &slots,
                format!("after step {k_total}, p out of the basis"),
                k_total,
                None,
                None,
            ));
        }
    }
    out
}
