//! Complementarity engine (work in progress).
