//! Solver settings. None needs tuning: defaults scale with the data.

use crate::{LcpError, SettingsError};

/// Settings of the pivoting methods.
///
/// Every tolerance is relative to the data after equilibration, so the defaults serve problems
/// in any units. They exist for experts who study round-off (the paper's single "accuracy"
/// parameter); a wrong answer is never the cure for a wrong tolerance, because every reported
/// solution is verified from the original data.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// An entry of the entering column counts as positive only above `pivot_tolerance · ‖α‖∞`.
    /// Default `1e-9`.
    pub pivot_tolerance: Option<f64>,
    /// Maximum number of pivots; default `20·n + 100`.
    pub max_pivots: Option<usize>,
    /// Pivots between fresh factorisations of the basis (default 50). A refactorisation also
    /// happens at once when the updated inverse loses accuracy.
    pub refactor_interval: usize,
    /// Lexicographic priority of the rows (a permutation of `0..n`): ties in the ratio test are
    /// broken as if the right-hand side of row `order[0]` were perturbed by `ε`, row `order[1]`
    /// by `ε²`, … Default: `0, 1, …, n−1`.
    pub lexicographic_order: Option<Vec<usize>>,
    /// Covering vector of the standard Lemke method (all entries `> 0`); default all ones.
    pub covering: Option<Vec<f64>>,
    /// Rows that the problem's formulation ties exactly (see [`RowRelation`]): ties in the
    /// ratio test between them are then decided from the relation, not from round-off of the
    /// basic values. Default: none.
    pub row_relations: Vec<RowRelation>,
    /// Where the methods report what they are doing (default: nowhere). Not a setting of the
    /// computation: it is never validated, two handles compare equal, and the answer is the
    /// same with or without one.
    pub progress: crate::Progress,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            pivot_tolerance: None,
            max_pivots: None,
            refactor_interval: 50,
            lexicographic_order: None,
            covering: None,
            row_relations: Vec::new(),
            progress: crate::Progress::default(),
        }
    }
}

/// A linear relation `Σ λ_i x_i = λᵀ(q0 + t·cov)` that the formulation guarantees between rows of
/// the problem: `λᵀM = 0` and `λᵀd = 0` hold in exact arithmetic (and in the floating-point data
/// to round-off of their terms). In the contact LCP each pair's friction rows satisfy
/// `x_t+ + x_t- − 2f·x_n = (2·max(1, f) − 2f)·c`.
///
/// On a basis where two of its rows are basic and the others not, the two rows' ratios differ by
/// an amount the relation fixes exactly (zero, or of the sign of the right-hand side's
/// combination); computed from the basic values they differ by round-off, which can let the
/// wrong row leave. With the relation given, the engine decides such ties from it (and
/// lexicographically when it is zero), and a row alone among its relation's basic rows never
/// moves. A relation the data do not satisfy to round-off of the terms is not used.
#[derive(Debug, Clone, PartialEq)]
pub struct RowRelation {
    /// `(row i, λ_i)` with `λ_i ≠ 0`.
    pub terms: Vec<(usize, f64)>,
}

/// Residual above which a solution is not reported as solved.
pub const ACCEPT_RESIDUAL: f64 = 1e-9;

impl Settings {
    /// Checks the settings against a problem of order `n`: those of
    /// [`Settings::validate_values`], then the lexicographic order and the covering vector.
    pub fn validate(&self, n: usize) -> Result<(), LcpError> {
        self.validate_values()?;
        if let Some(order) = &self.lexicographic_order {
            let mut seen = vec![false; n];
            if order.len() != n
                || order
                    .iter()
                    .any(|&i| i >= n || std::mem::replace(&mut seen[i], true))
            {
                return Err(SettingsError::LexicographicOrder(n).into());
            }
        }
        if let Some(i) = self
            .row_relations
            .iter()
            .flat_map(|r| &r.terms)
            .map(|&(i, _)| i)
            .find(|&i| i >= n)
        {
            return Err(LcpError::Dimension(format!(
                "a row relation names row {}, the problem has {n}",
                i + 1
            )));
        }
        if let Some(c) = &self.covering {
            if c.len() != n {
                return Err(LcpError::Dimension(format!(
                    "covering vector has {} entries, expected {n}",
                    c.len()
                )));
            }
            if let Some(i) = c.iter().position(|&v| !(v.is_finite() && v > 0.0)) {
                return Err(SettingsError::Covering {
                    entry: i,
                    value: c[i],
                }
                .into());
            }
        }
        Ok(())
    }

    /// Checks the settings that do not depend on the problem (`pivot_tolerance`, `max_pivots`,
    /// `refactor_interval`), in that order: what a caller that supplies the order and the
    /// covering itself (the contact solve) checks before it has a problem.
    pub fn validate_values(&self) -> Result<(), SettingsError> {
        if let Some(t) = self.pivot_tolerance {
            if !(t.is_finite() && t > 0.0 && t < 1e-2) {
                return Err(SettingsError::PivotTolerance(t));
            }
        }
        if self.max_pivots == Some(0) {
            return Err(SettingsError::MaxPivots);
        }
        if self.refactor_interval == 0 {
            return Err(SettingsError::RefactorInterval);
        }
        Ok(())
    }

    pub(crate) fn pivot_tol(&self) -> f64 {
        self.pivot_tolerance.unwrap_or(1e-9)
    }

    /// The rows of each row relation (the rows a relation ties belong to one part of the
    /// problem: `Scaling::raise_parts`).
    pub(crate) fn relation_rows(&self) -> Vec<Vec<usize>> {
        self.row_relations
            .iter()
            .map(|r| r.terms.iter().map(|&(i, _)| i).collect())
            .collect()
    }

    pub(crate) fn cap(&self, n: usize) -> usize {
        self.max_pivots.unwrap_or(20 * n + 100)
    }

    pub(crate) fn priority(&self, n: usize) -> Vec<usize> {
        self.lexicographic_order
            .clone()
            .unwrap_or_else(|| (0..n).collect())
    }
}
