//! Errors: problems with the input, never statuses of a solve.

/// Invalid input to the engine. A solve that ends on a ray or at the pivot cap is not an error:
/// see [`crate::LcpStatus`] and [`crate::PathStatus`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LcpError {
    /// `M` is not square or a vector's length differs from `M`'s order.
    #[error("dimension mismatch: {0}")]
    Dimension(String),
    /// A NaN or infinite entry.
    #[error("{what} has a non-finite entry at {index}")]
    NotFinite {
        /// `M`, `q`, `q0` or `d`.
        what: &'static str,
        /// The place of the entry, as printed.
        index: String,
    },
    /// A setting out of range.
    #[error("invalid setting: {0}")]
    Settings(#[from] SettingsError),
    /// The problem is empty.
    #[error("the problem has no unknowns")]
    Empty,
}

/// A setting of the engine ([`crate::Settings`]) or of a path ([`crate::PathOptions`]) out of
/// its range. The message names the setting; [`SettingsError::key`] names it alone, for
/// readers that point at the place where the user wrote it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SettingsError {
    /// `pivot_tolerance` outside `(0, 0.01)`.
    #[error("pivot_tolerance must lie in (0, 0.01), got {0}")]
    PivotTolerance(f64),
    /// `max_pivots = 0`.
    #[error("max_pivots must be at least 1")]
    MaxPivots,
    /// `refactor_interval = 0`.
    #[error("refactor_interval must be at least 1")]
    RefactorInterval,
    /// `lexicographic_order` is not a permutation of `0..n`.
    #[error("lexicographic_order must be a permutation of 0..{0}")]
    LexicographicOrder(usize),
    /// An entry of the covering vector is not a finite number `> 0`.
    #[error("covering vector entry {entry} must be a finite number > 0, got {value}")]
    Covering {
        /// 0-based entry.
        entry: usize,
        /// The value given.
        value: f64,
    },
    /// The target load is not a finite number `> 0` (nor a subnormal one, below 2.2e-308).
    #[error("target must be a finite number > 0 (and not below 2.2e-308), got {0:e}")]
    Target(f64),
    /// The tightening is not a finite number `≥ 0`.
    #[error("tightening must be a finite number ≥ 0, got {0}")]
    Tightening(f64),
    /// An entry of the tightening direction is negative (1-based entry).
    #[error("tightening direction entry {0} is negative")]
    TighteningDirection(usize),
}

impl SettingsError {
    /// The name of the setting at fault, as in problem files (`"pivot_tolerance"`, `"target"`,
    /// …; `"tightening"` for its direction too).
    pub fn key(&self) -> &'static str {
        match self {
            SettingsError::PivotTolerance(_) => "pivot_tolerance",
            SettingsError::MaxPivots => "max_pivots",
            SettingsError::RefactorInterval => "refactor_interval",
            SettingsError::LexicographicOrder(_) => "lexicographic_order",
            SettingsError::Covering { .. } => "covering",
            SettingsError::Target(_) => "target",
            SettingsError::Tightening(_) | SettingsError::TighteningDirection(_) => "tightening",
        }
    }
}
