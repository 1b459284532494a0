//! 2D structural finite elements (work in progress).
