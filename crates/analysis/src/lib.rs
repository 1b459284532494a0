//! Structural contact analysis (work in progress).
