//! Errors of the contact formulation.

/// What is wrong with a contact-zone problem. Indices in messages are 1-based, as in the paper.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// The problem has no contact pairs.
    #[error("the contact zone has no pairs (Rnn is empty)")]
    Empty,
    /// A matrix block has the wrong shape.
    #[error("{name} is {rows}×{cols}, but the contact zone has {pairs} pairs (expected {pairs}×{pairs})")]
    MatrixSize {
        name: &'static str,
        rows: usize,
        cols: usize,
        pairs: usize,
    },
    /// A per-pair vector has the wrong length.
    #[error("{name} has {len} entries, but the contact zone has {pairs} pairs")]
    VectorSize {
        name: String,
        len: usize,
        pairs: usize,
    },
    /// A NaN or infinite value.
    #[error("{name}{index} is not a finite number")]
    NotFinite { name: String, index: String },
    /// `Rnn` or `Rtt` is not symmetric.
    #[error("{name} must be symmetric, but entry ({row}, {col}) = {upper} differs from ({col}, {row}) = {lower}")]
    NotSymmetric {
        name: &'static str,
        row: usize,
        col: usize,
        upper: f64,
        lower: f64,
    },
    /// A stiffness matrix has a negative diagonal entry (it cannot be positive semidefinite).
    #[error(
        "{name} must be positive semidefinite, but its diagonal entry for pair {pair} is {value}"
    )]
    NegativeDiagonal {
        name: &'static str,
        pair: usize,
        value: f64,
    },
    /// Friction or gap is negative.
    #[error("{name} must be ≥ 0, but pair {pair} has {value}")]
    Negative {
        name: &'static str,
        pair: usize,
        value: f64,
    },
    /// The data are finite but their combination is not representable: the formulation's
    /// products (friction times stiffness) or the answer's forces and displacements leave the
    /// floating-point range (about `1.8e308`).
    #[error("{0}")]
    OutOfRange(String),
    /// The engine rejected data that the contact formulation had already checked: a fault of
    /// the program, not of the model.
    #[error("internal failure of the solver (the program's fault, not the model's): {0}")]
    Internal(String),
    /// Settings out of range.
    #[error("invalid solve setting: {0}")]
    Settings(String),
}
