//! What the contact crate's benchmarks share.

/// `f` with faer's global parallelism set to one thread: the yardstick is one dense LU on one
/// thread (issue 11), while the engine's refactorisations, run in the same process, use
/// faer's parallelism.
pub fn one_thread<T>(f: impl FnOnce() -> T) -> T {
    let before = faer::get_global_parallelism();
    faer::set_global_parallelism(faer::Par::Seq);
    let out = f();
    faer::set_global_parallelism(before);
    out
}
