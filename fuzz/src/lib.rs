//! What every fuzz target checks: the bytes are written to a file with the extension the
//! reader expects and read through the public entry point, as the program reads a user's
//! file. A reader may accept the bytes or refuse them, but it must not panic (libFuzzer
//! reports a panic as a crash), and a refusal must name the file it refuses.

use std::io::Write;
use std::path::Path;
use std::sync::OnceLock;

use unilateral_io::InputError;

/// Writes `data` to a temporary file named `input.<ext>` and reads it with `read`.
pub fn check<T>(data: &[u8], ext: &str, read: impl FnOnce(&Path) -> Result<T, InputError>) {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    let dir = DIR.get_or_init(|| tempfile::tempdir().expect("a temporary directory"));
    let path = dir.path().join(format!("input.{ext}"));
    std::fs::File::create(&path)
        .and_then(|mut f| f.write_all(data))
        .expect("the input file is written");
    if let Err(e) = read(&path) {
        let shown = e.to_string();
        assert!(
            shown.starts_with(&path.display().to_string()),
            "the error does not start with the file name: {shown}"
        );
        assert_eq!(e.file(), path, "the error names another file: {shown}");
    }
}
