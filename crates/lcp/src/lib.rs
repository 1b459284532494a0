//! Complementarity engine (work in progress).
mod problem;
pub use problem::{Lcp, ParametricLcp};
