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
        /// The block (`Rnn`, `Rnt`, `Rtn` or `Rtt`).
        name: &'static str,
        /// Its number of rows.
        rows: usize,
        /// Its number of columns.
        cols: usize,
        /// The number of pairs of the zone.
        pairs: usize,
    },
    /// A per-pair vector has the wrong length.
    #[error("{name} has {len} entries, but the contact zone has {pairs} pairs")]
    VectorSize {
        /// The vector (friction, gap, a load vector).
        name: String,
        /// Its length.
        len: usize,
        /// The number of pairs of the zone.
        pairs: usize,
    },
    /// A NaN or infinite value.
    #[error("{name}{index} is not a finite number")]
    NotFinite {
        /// The matrix or vector.
        name: String,
        /// The place in it, as printed (`[2]`, `[1, 3]`).
        index: String,
    },
    /// `Rnn` or `Rtt` is not symmetric.
    #[error("{name} must be symmetric, but entry ({row}, {col}) = {upper} differs from ({col}, {row}) = {lower}")]
    NotSymmetric {
        /// The matrix (`Rnn` or `Rtt`).
        name: &'static str,
        /// 1-based row of the upper entry.
        row: usize,
        /// 1-based column of the upper entry.
        col: usize,
        /// The entry `(row, col)`.
        upper: f64,
        /// The entry `(col, row)`.
        lower: f64,
    },
    /// A stiffness matrix has a negative diagonal entry (it cannot be positive semidefinite).
    #[error(
        "{name} must be positive semidefinite, but its diagonal entry for pair {pair} is {value}"
    )]
    NegativeDiagonal {
        /// The matrix (`Rnn` or `Rtt`).
        name: &'static str,
        /// 1-based pair.
        pair: usize,
        /// The diagonal entry.
        value: f64,
    },
    /// `Rnn` or `Rtt` is not positive semidefinite although its diagonal is: two pairs whose
    /// 2 × 2 block has a negative determinant, or (where every such block is sound) the first
    /// leading block that is not semidefinite.
    #[error("{name} must be positive semidefinite, but {why}")]
    NotSemidefinite {
        /// The matrix (`Rnn` or `Rtt`).
        name: &'static str,
        /// 1-based row and column of the entry that shows it: the off-diagonal entry of the
        /// two pairs, or the diagonal entry that ends the leading block.
        row: usize,
        /// See `row`.
        col: usize,
        /// What is wrong, in words.
        why: String,
    },
    /// Friction or gap is negative.
    #[error("{name} must be ≥ 0, but pair {pair} has {value}")]
    Negative {
        /// `friction` or `gap`.
        name: &'static str,
        /// 1-based pair.
        pair: usize,
        /// The value given.
        value: f64,
    },
    /// The data are finite but their combination is not representable: the formulation's
    /// products (friction times stiffness) or the answer's forces and displacements leave the
    /// floating-point range (about `1.8e308`).
    #[error("{0}")]
    OutOfRange(String),
    /// The engine rejected data that the contact formulation had already checked: a fault of
    /// the program, not of the model. The engine's own error is kept, typed.
    #[error("internal failure of the solver (the program's fault, not the model's): {0}")]
    Engine(#[from] unilateral_lcp::LcpError),
    /// A solve setting out of range, as the engine's check of it says.
    #[error("invalid solve setting: {0}")]
    Settings(#[from] unilateral_lcp::SettingsError),
}
