//! Independent exact-arithmetic reference solvers for small linear complementarity problems.
//!
//! This crate is **test support only** (`publish = false`). It re-implements, in exact rational
//! arithmetic ([`BigRational`]), the algorithms that the engine crate implements in `f64`, so that
//! the engine's tests can compare against answers that carry no round-off at all: every zero test
//! here is exact.
//!
//! Notation (see `docs/formulation.md`, §3–§5):
//!
//! * the standard LCP: find `z ≥ 0`, `w = M z + q ≥ 0` with `wᵀz = 0`;
//! * the parametric LCP: `x = q0 + p·d + M z`, `x ≥ 0`, `z ≥ 0`, `xᵀz = 0`, load parameter `p ≥ 0`.
//!   Here `x` plays the part of `w` (the same [`Var::X`] labels are used for both).
//!
//! What is provided:
//!
//! * [`enumerate`] / [`has_solution`]: exhaustive enumeration of all `2ⁿ` complementary index
//!   sets (n ≤ 12), also for the parametric problem at a given `p` ([`enumerate_parametric`]);
//! * [`lemke()`]: Lemke's method with a covering vector on a full rational tableau with the
//!   lexicographic ratio test;
//! * [`parametric_path`]: the parametric Lemke method of `docs/formulation.md` §4 on a full rational
//!   tableau `[E | −M | −d | q0]`, with the events (steps), the final status, the breakpoint
//!   solutions and [`Path::solution_at`] to evaluate the piecewise-linear path at any `p`;
//! * [`fixtures`]: the test data the workspace's tests share — the paper's Example 1 with its
//!   derivation and answers, the frictional `3m` LCP built by hand, one seeded generator.
//!
//! Inputs given as `f64` are converted **exactly** to rationals ([`rat`]): `0.6_f64` is the
//! rational `5404319552844595/9007199254740992`, not `3/5`. Every function also has an `_exact`
//! variant that takes rationals directly (use [`frac`] to write `3/5`). Outputs are rationals,
//! with `*_f64` helper methods that round them to the nearest `f64`.
//!
//! # Example
//!
//! ```
//! use unilateral_oracle::{enumerate, lemke, LemkeStatus};
//!
//! // w = M z + q with a P-matrix: a unique solution.
//! let m = vec![vec![2.0, 1.0], vec![1.0, 2.0]];
//! let q = vec![-5.0, -6.0];
//! let all = enumerate(&m, &q);
//! assert_eq!(all.len(), 1);
//! assert_eq!(all[0].z_f64(), vec![4.0 / 3.0, 7.0 / 3.0]);
//!
//! let r = lemke(&m, &q, &[1.0, 1.0]);
//! assert_eq!(r.status, LemkeStatus::Solved);
//! assert_eq!(r.z, all[0].z);
//! ```

#![warn(missing_docs)]

mod enumerate;
pub mod fixtures;
pub mod history;
mod lemke;
mod linalg;
mod parametric;
mod tableau;

pub use enumerate::{
    enumerate, enumerate_exact, enumerate_parametric, enumerate_parametric_exact, has_solution,
    has_solution_exact, Solution, MAX_ENUMERATION_SIZE,
};
pub use lemke::{lemke, lemke_exact, LemkeRay, LemkeResult, LemkeStatus, DEFAULT_MAX_PIVOTS};
pub use linalg::solve;
pub use parametric::{
    parametric_path, parametric_path_exact, Path, PathPoint, PathRay, PathStatus, Step,
    DEFAULT_MAX_STEPS,
};

pub use num_bigint::BigInt;
pub use num_rational::BigRational;

use num_traits::{Signed, ToPrimitive, Zero};

/// Shorthand for the exact rational type used everywhere in this crate.
pub type Rat = BigRational;

/// A variable of the (parametric) LCP, as a label for tableau columns and pivot steps.
///
/// Indices are 0-based. In the standard LCP `w = M z + q` the `w` variables are labelled
/// [`Var::X`] too.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Var {
    /// `x_i` (in the standard LCP: `w_i`), the "force" side.
    X(usize),
    /// `z_i`, the "displacement" side.
    Z(usize),
    /// The load parameter `p` of the parametric LCP.
    P,
    /// The artificial variable `z0` of Lemke's method (standard LCP only).
    Z0,
}

impl Var {
    /// The complementary variable (`X(i) ↔ Z(i)`); `None` for `P` and `Z0`.
    pub fn complement(self) -> Option<Var> {
        match self {
            Var::X(i) => Some(Var::Z(i)),
            Var::Z(i) => Some(Var::X(i)),
            Var::P | Var::Z0 => None,
        }
    }
}

impl std::fmt::Display for Var {
    /// `x0`, `z3`, `p`, `z0*` (0-based; the artificial variable is `z0*` to avoid a clash).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Var::X(i) => write!(f, "x{i}"),
            Var::Z(i) => write!(f, "z{i}"),
            Var::P => write!(f, "p"),
            Var::Z0 => write!(f, "z0*"),
        }
    }
}

/// Converts an `f64` to the rational with exactly the same value.
///
/// # Panics
/// If `v` is NaN or infinite.
pub fn rat(v: f64) -> Rat {
    BigRational::from_float(v).unwrap_or_else(|| panic!("non-finite input value {v}"))
}

/// The rational `num/den`, reduced.
///
/// # Panics
/// If `den == 0`.
pub fn frac(num: i64, den: i64) -> Rat {
    assert!(den != 0, "zero denominator");
    BigRational::new(BigInt::from(num), BigInt::from(den))
}

/// Converts a slice of `f64` exactly ([`rat`] on each entry).
pub fn rat_vec(v: &[f64]) -> Vec<Rat> {
    v.iter().map(|&x| rat(x)).collect()
}

/// Converts a row-major `f64` matrix exactly ([`rat`] on each entry).
pub fn rat_matrix(m: &[Vec<f64>]) -> Vec<Vec<Rat>> {
    m.iter().map(|row| rat_vec(row)).collect()
}

/// The `f64` nearest to a rational (correctly rounded; ±∞ beyond the `f64` range).
pub fn to_f64(r: &Rat) -> f64 {
    match r.to_f64() {
        Some(v) => v,
        None if r.is_negative() => f64::NEG_INFINITY,
        None if r.is_zero() => 0.0,
        None => f64::INFINITY,
    }
}

/// [`to_f64`] on each entry.
pub fn to_f64_vec(v: &[Rat]) -> Vec<f64> {
    v.iter().map(to_f64).collect()
}

/// `q0 + p·d`, exactly.
///
/// # Panics
/// If the lengths differ.
pub fn parametric_q(q0: &[Rat], d: &[Rat], p: &Rat) -> Vec<Rat> {
    assert_eq!(q0.len(), d.len(), "q0 and d must have the same length");
    q0.iter().zip(d).map(|(a, b)| a + p * b).collect()
}

/// `M z + q`, exactly.
///
/// # Panics
/// If the sizes do not match.
pub fn mz_plus_q(m: &[Vec<Rat>], z: &[Rat], q: &[Rat]) -> Vec<Rat> {
    check_square(m, q.len());
    assert_eq!(z.len(), q.len(), "z has the wrong length");
    m.iter()
        .zip(q)
        .map(|(row, qi)| {
            row.iter()
                .zip(z)
                .filter(|(_, zj)| !zj.is_zero())
                .fold(qi.clone(), |acc, (a, zj)| acc + a * zj)
        })
        .collect()
}

/// Checks exactly that `(z, w)` solves the LCP `w = M z + q ≥ 0, z ≥ 0, wᵀz = 0`
/// (every product `w_i z_i` must be zero).
pub fn is_lcp_solution(m: &[Vec<Rat>], q: &[Rat], z: &[Rat], w: &[Rat]) -> bool {
    if z.len() != q.len() || w.len() != q.len() {
        return false;
    }
    mz_plus_q(m, z, q) == w
        && z.iter().all(|v| !v.is_negative())
        && w.iter().all(|v| !v.is_negative())
        && z.iter().zip(w).all(|(a, b)| a.is_zero() || b.is_zero())
}

/// Panics unless `m` is `n × n`.
pub(crate) fn check_square(m: &[Vec<Rat>], n: usize) {
    assert_eq!(m.len(), n, "M must have {n} rows");
    for (i, row) in m.iter().enumerate() {
        assert_eq!(row.len(), n, "row {i} of M must have {n} entries");
    }
}
