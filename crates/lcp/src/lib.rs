//! # unilateral-lcp — the complementarity engine
//!
//! Knows nothing of mechanics. It solves
//!
//! * the **standard LCP** `w = M z + q, w ≥ 0, z ≥ 0, wᵀz = 0` by Lemke's method with a covering
//!   vector ([`solve_lcp`]), and
//! * the **parametric LCP** `x = q0 + p·d + M z` followed from `p = 0` with the load parameter
//!   `p` as the driving variable ([`PathSolver`], built once from the problem, its options and
//!   settings, which it validates and equilibrates): every pivot is one change of the basis,
//!   the result is the whole [`LoadPath`], and the solver answers for any load on it
//!   ([`PathSolver::solution_at`]) and shows its tableaux ([`PathSolver::tableaux`]).
//!
//! Files: the public types in `problem.rs`, `settings.rs`, `error.rs`, `solution.rs` (standard
//! LCP) and `path.rs` (load path); the algorithms in `lemke.rs` and `parametric.rs` behind
//! `solver.rs`; the crate-private pivoting machinery (equilibration, revised basis, ratio test,
//! enumeration) in `pivoting/`.
//!
//! Ties in every ratio test are broken lexicographically, so degenerate problems do not cycle.
//! The basis is kept in revised form: only the `k × k` kernel of non-slack basic columns is
//! inverted, so a pivot costs `O(n·k + k²)`, and the kernel is refactorised from the data
//! (`faer` LU) periodically and whenever its accuracy degrades. Every reported solution carries
//! its [`Residual`] computed from the original data.
//!
//! **Units.** The answer may not depend on the units of the data. `M` is equilibrated by powers
//! of two (rows and columns, computed on binary exponents so that no scale overflows); for the
//! standard LCP the equilibration is itself independent of the units of rows and unknowns
//! (rows divided by the diagonal, the remaining similarity max-balanced, each block that `M`
//! couples brought to the size of its `q`), and the covering vectors and the enumeration work
//! in the equilibrated problem. The right-hand side `q0` and the direction `d` are each
//! divided by a power of two near their own largest entry, the driver rescaled to match (see
//! the `columns` module): every tolerance then compares quantities of one kind and one size, so
//! a `q0` of `1e-150` against an `M` of `1e9` is never read as round-off, and a change of units
//! by `2^k` changes no bit of what the pivoting sees. A solution is reported only when every one
//! of its numbers is finite and its residuals, formed overflow-free from the original data and
//! measured row by row against each row's own data (see [`Residual`]), verify; otherwise the
//! status says the engine failed ([`LcpStatus::NumericalFailure`],
//! [`PathStatus::NumericalFailure`]) — never a NaN "solved".

#![warn(missing_docs)]

pub mod binary;
mod error;
mod evolution;
mod lemke;
mod parametric;
mod path;
mod pivoting;
mod problem;
mod progress;
mod residual;
mod schur;
mod settings;
mod solution;
mod solver;
mod sweep;
mod tableau;
mod var;

pub use error::{LcpError, SettingsError};
pub use evolution::{
    EvolutionPoint, EvolutionProblem, EvolutionSolver, EvolutionState, RefinedEnd, StageEnding,
    StageRun,
};
pub use lemke::solve_lcp;
pub use path::{
    basic_after, first_different_step, BasisVerdict, Breakpoint, Follow, LoadPath, MechanismMode,
    PathOptions, PathPoint, PathStatus, Step, Tightening, Unreported,
};
pub use problem::{Lcp, ParametricLcp};
pub use progress::{Phase, Progress, Snapshot};
pub use residual::Residual;
pub use schur::{follow_schur_path, SchurLcp, SchurOptions, SchurPath, StructureJudge};
pub use settings::{RowRelation, Settings, ACCEPT_RESIDUAL};
pub use solution::{LcpPoint, LcpSolution, LcpStatus, Strategy};
pub use solver::{follow_path, solution_at, tableaux, PathSolver};
pub use tableau::Tableau;
pub use var::Var;
