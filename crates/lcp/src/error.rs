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
    Settings(String),
    /// The problem is empty.
    #[error("the problem has no unknowns")]
    Empty,
}
