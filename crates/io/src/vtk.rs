//! ParaView output (work in progress).

use std::path::{Path, PathBuf};

/// Writes the model and its results as VTK XML files into `dir`; returns the files written.
pub fn write_vtk(
    analysis: &unilateral_analysis::Analysis,
    dir: &Path,
) -> std::io::Result<Vec<PathBuf>> {
    let _ = (analysis, dir);
    Ok(Vec::new())
}
