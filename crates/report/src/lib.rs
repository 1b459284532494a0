//! Pictures and reports of a contact analysis (work in progress).

use std::path::{Path, PathBuf};

/// What to draw.
#[derive(Debug, Clone, Default)]
pub struct ReportOptions {
    /// Pair names to show in the load-path charts (`None`: all).
    pub pairs: Option<Vec<String>>,
    /// Draw the bending moment diagram on frame members.
    pub moments: bool,
}

/// Errors of writing a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
}

/// Writes the pictures and `report.html` of an analysis into `dir`; returns the files written.
pub fn write_report(
    analysis: &unilateral_analysis::Analysis,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    let _ = (analysis, dir, options);
    Ok(Vec::new())
}

/// Writes the load-path charts and `report.html` of a contact-zone solve (no structure to draw)
/// into `dir`; returns the files written.
pub fn write_path_report(
    solution: &unilateral_contact::ContactSolution,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    let _ = (solution, dir, options);
    Ok(Vec::new())
}
