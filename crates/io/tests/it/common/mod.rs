//! Helpers shared by the integration tests of unilateral-io.

use std::path::{Path, PathBuf};

/// `tests/data/siconos/<sub>` of this repository: the Siconos test problems (Apache-2.0, see
/// `tests/data/siconos/README.md`). The data is part of the repository, so a missing directory is
/// a test failure, never a skip.
pub fn siconos(sub: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/siconos")
        .join(sub);
    assert!(
        dir.is_dir(),
        "{} is missing: the Siconos test data belongs to the repository",
        dir.display()
    );
    dir
}

/// The `.dat` files of `tests/data/siconos/<sub>`, sorted by name.
pub fn siconos_files(sub: &str) -> Vec<PathBuf> {
    let dir = siconos(sub);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dat"))
        .collect();
    files.sort();
    files
}
