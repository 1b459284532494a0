//! Writing results (work in progress).
