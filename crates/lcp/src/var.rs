//! Names of the tableau's variables.

use std::fmt;

/// A variable of the pivoting tableau: `x_i` (often called `w_i`), `z_i`, or the driving
/// variable (the load parameter `p` of a path, or Lemke's artificial `z0`). Indices are 0-based;
/// [`fmt::Display`] prints them 1-based as in the paper (`x1`, `z3`, `p`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Var {
    /// The `i`-th component of `x = q + M z`.
    X(usize),
    /// The `i`-th component of `z`.
    Z(usize),
    /// The driving variable.
    Driver,
}

impl Var {
    pub(crate) fn from_col(col: usize, n: usize) -> Self {
        if col < n {
            Var::X(col)
        } else if col < 2 * n {
            Var::Z(col - n)
        } else {
            Var::Driver
        }
    }

    /// The complementary variable (`x_i ↔ z_i`); the driver has none.
    pub fn complement(self) -> Option<Var> {
        match self {
            Var::X(i) => Some(Var::Z(i)),
            Var::Z(i) => Some(Var::X(i)),
            Var::Driver => None,
        }
    }
}

impl fmt::Display for Var {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Var::X(i) => write!(f, "x{}", i + 1),
            Var::Z(i) => write!(f, "z{}", i + 1),
            Var::Driver => write!(f, "p"),
        }
    }
}
