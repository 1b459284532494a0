//! What every command shares in writing its answers: progress on a terminal, JSON documents,
//! the list of files written.

use std::path::{Path, PathBuf};

use crate::failure::Failure;

/// Progress messages on stderr, only when it is a terminal (never in pipes, files or tests).
pub(crate) struct Progress {
    start: std::time::Instant,
    on: bool,
}

impl Progress {
    pub(crate) fn new() -> Self {
        use std::io::IsTerminal;
        Self {
            start: std::time::Instant::now(),
            on: std::io::stderr().is_terminal(),
        }
    }

    pub(crate) fn say(&self, msg: &str) {
        if self.on {
            eprintln!("unilateral: {msg}");
        }
    }

    pub(crate) fn elapsed(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }
}

/// How many file names the line of the files written lists before `…`.
const NAMES_SHOWN: usize = 4;

/// One line on stderr for the files written into `dir`: `wrote 41 files in out/: report.html,
/// structure.svg, … (and 37 more)`, the names in the writer's order (its main file first).
pub(crate) fn report_files(
    written: std::io::Result<Vec<PathBuf>>,
    dir: &Path,
) -> Result<(), Failure> {
    let files = written.map_err(|e| {
        if let Some(n) = unilateral_output::NonFiniteOutput::in_io_error(&e) {
            return Failure::Internal(n.to_string());
        }
        match e
            .get_ref()
            .and_then(|c| c.downcast_ref::<unilateral_contact::ContactError>())
        {
            // Forces beyond the floating-point range at a breakpoint: the user's extreme
            // values, as at the reported load; anything else the solution refuses is ours.
            Some(c @ unilateral_contact::ContactError::OutOfRange(_)) => Failure::Input(format!(
                "the tables of the load path could not be written into {}: {c}",
                dir.display()
            )),
            Some(c) => Failure::Internal(format!(
                "the tables of the load path could not be written into {}: {c}",
                dir.display()
            )),
            None => Failure::Input(format!("cannot write into {}: {e}", dir.display())),
        }
    })?;
    if let Some(line) = files_line(&files, dir) {
        eprintln!("{line}");
    }
    Ok(())
}

/// The line of [`report_files`] (`None` when nothing was written).
fn files_line(files: &[PathBuf], dir: &Path) -> Option<String> {
    if files.is_empty() {
        return None;
    }
    let names: Vec<String> = files
        .iter()
        .take(NAMES_SHOWN)
        .map(|f| f.strip_prefix(dir).unwrap_or(f).display().to_string())
        .collect();
    let more = files.len().saturating_sub(NAMES_SHOWN);
    Some(format!(
        "wrote {} file{} in {}: {}{}",
        files.len(),
        if files.len() == 1 { "" } else { "s" },
        dir.display(),
        names.join(", "),
        if more > 0 {
            format!(", … (and {more} more)")
        } else {
            String::new()
        }
    ))
}

/// A table of the whole path that could not be made: a number that is not finite (ours), or
/// the solution at a breakpoint beyond the floating-point range (the user's extreme values, as
/// at the reported load) or refused by the engine (ours).
pub(crate) fn path_output_failure(e: unilateral_output::PathOutputError) -> Failure {
    use unilateral_contact::ContactError;
    use unilateral_output::PathOutputError as E;
    match e {
        E::NonFinite(n) => Failure::Internal(n.to_string()),
        E::Contact(ContactError::OutOfRange(_)) => Failure::Input(e.to_string()),
        E::Contact(_) => Failure::Internal(e.to_string()),
    }
}

/// Writes a JSON document (`-`: stdout), with `program`, `schema` and no negative zero
/// ([`unilateral_output::with_provenance`]): every document the program writes goes through
/// here.
pub(crate) fn write_json(out: &Path, value: &serde_json::Value) -> Result<(), Failure> {
    let value = unilateral_output::with_provenance(value.clone());
    let text = serde_json::to_string_pretty(&value)
        .map_err(|e| Failure::Internal(format!("JSON: {e}")))?;
    if out == Path::new("-") {
        self::out(&format!("{text}\n"));
        return Ok(());
    }
    std::fs::write(out, text + "\n")
        .map_err(|e| Failure::Input(format!("cannot write {}: {e}", out.display())))
}

/// Writes `text` to stdout. A reader that closed the pipe early (`unilateral solve … | head`)
/// is no failure: the rest is dropped quietly (the `print!` macros would panic there).
pub(crate) fn out(text: &str) {
    use std::io::Write;
    let mut o = std::io::stdout().lock();
    let _ = o.write_all(text.as_bytes()).and_then(|()| o.flush());
}

/// `println!` through [`out`]: no panic on a closed pipe.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::output::out(&format!("{}\n", format_args!($($arg)*)))
    };
}
pub(crate) use outln;

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    /// Hand-written expectations: one line, the count, the directory, at most four names.
    #[test]
    fn the_files_written_are_one_line() {
        let dir = Path::new("out");
        let files: Vec<PathBuf> = (1..=6).map(|k| dir.join(format!("f{k}.vtu"))).collect();
        assert_eq!(
            super::files_line(&files, dir).unwrap(),
            "wrote 6 files in out: f1.vtu, f2.vtu, f3.vtu, f4.vtu, … (and 2 more)"
        );
        assert_eq!(
            super::files_line(&files[..1], dir).unwrap(),
            "wrote 1 file in out: f1.vtu"
        );
        assert_eq!(super::files_line(&[], dir), None);
    }
}
