//! Reference solvers (work in progress).
