//! The answer of a standard LCP solve: its status, the verified point and how it was found.

use crate::Residual;

/// How a standard LCP solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LcpStatus {
    /// A solution, verified from the original data.
    Solved,
    /// Lemke's method ended on a secondary ray with every covering vector tried, and exhaustive
    /// enumeration (for `n ≤ 16`) found no solution either.
    Ray,
    /// The pivot cap was reached.
    IterationLimit,
    /// A complementary basis was found but no point of it could be verified from the data
    /// (its numbers overflow the floating-point range or its residuals are too large): an
    /// internal failure of the engine, never a claim that no solution exists.
    NumericalFailure,
}

impl LcpStatus {
    /// The status as written in result files (`"solved"`, `"ray"`, `"iteration_limit"`).
    pub fn as_str(&self) -> &'static str {
        match self {
            LcpStatus::Solved => "solved",
            LcpStatus::Ray => "ray",
            LcpStatus::IterationLimit => "iteration_limit",
            LcpStatus::NumericalFailure => "numerical_failure",
        }
    }
}

/// Which strategy produced the answer.
#[derive(Debug, Clone, PartialEq)]
pub enum Strategy {
    /// `q ≥ 0`: `z = 0` solves the problem.
    Trivial,
    /// Lemke's method with the named covering vector.
    Lemke {
        /// `"ones"`, `"user"`, `"graded"` or `"|q|"`.
        covering: &'static str,
    },
    /// Exhaustive enumeration of complementary bases.
    Enumeration,
}

/// A verified solution `(z, w)`.
#[derive(Debug, Clone, PartialEq)]
pub struct LcpPoint {
    /// The unknown `z ≥ 0`.
    pub z: Vec<f64>,
    /// `w = M z + q ≥ 0`.
    pub w: Vec<f64>,
    /// Residuals computed from the original data.
    pub residual: Residual,
}

/// The answer of [`crate::solve_lcp`].
#[derive(Debug, Clone, PartialEq)]
pub struct LcpSolution {
    /// How the solve ended.
    pub status: LcpStatus,
    /// The solution when `status` is [`LcpStatus::Solved`].
    pub point: Option<LcpPoint>,
    /// Pivots over all attempts.
    pub pivots: usize,
    /// The strategy that produced the solution (or the last one tried).
    pub strategy: Strategy,
    /// What was tried, in order, and how each attempt ended.
    pub attempts: Vec<String>,
}
