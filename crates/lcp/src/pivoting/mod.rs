//! The pivoting machinery shared by both methods, private to the crate: the equilibration of
//! the data (`scaling`, `prepare`), the tableau's columns in scaled form (`columns`), the
//! revised basis and its kernel inverse (`basis`, `kernel`), the lexicographic ratio test and
//! the pivoting loop (`pivot`), their hot loops compiled for the machine's vectors (`simd`), and
//! the exhaustive enumeration of complementary bases for small problems (`enumerate`).

pub(crate) mod basis;
pub(crate) mod columns;
pub(crate) mod enumerate;
pub(crate) mod kernel;
pub(crate) mod pivot;
pub(crate) mod prepare;
pub(crate) mod relations;
pub(crate) mod scaling;
pub(crate) mod simd;
