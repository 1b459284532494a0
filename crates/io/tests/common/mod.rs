//! Helpers shared by the integration tests of unilateral-io.

use std::path::{Path, PathBuf};

/// `shared/data/<sub>` beside the repository (as in CI); `None` (skip) when
/// missing, a failure when the environment variable `CI` is set.
pub fn shared(sub: &str) -> Option<PathBuf> {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let candidates = [
        std::env::var_os("UNILATERAL_SHARED_DATA").map(PathBuf::from),
        Some(repo.join("../shared/data")),
        Some(repo.join("shared/data")),
    ];
    let dir = candidates
        .into_iter()
        .flatten()
        .find(|d| d.join(sub).is_dir());
    if dir.is_none() {
        assert!(
            std::env::var_os("CI").is_none(),
            "shared/data/{sub} not found beside the repository, and CI is set"
        );
        eprintln!("shared/data/{sub} not found beside the repository: skipped");
    }
    dir.map(|d| d.join(sub))
}
