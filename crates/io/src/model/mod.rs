//! Structural model files (work in progress).
