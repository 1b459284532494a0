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

pub(crate) fn report_files(
    written: std::io::Result<Vec<PathBuf>>,
    dir: &Path,
) -> Result<(), Failure> {
    let files = written.map_err(
        |e| match unilateral_output::NonFiniteOutput::in_io_error(&e) {
            Some(n) => Failure::Internal(n.to_string()),
            None => Failure::Input(format!("cannot write into {}: {e}", dir.display())),
        },
    )?;
    for f in files {
        eprintln!("wrote {}", f.display());
    }
    Ok(())
}

pub(crate) fn write_json(out: &Path, value: &serde_json::Value) -> Result<(), Failure> {
    let text =
        serde_json::to_string_pretty(value).map_err(|e| Failure::Internal(format!("JSON: {e}")))?;
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
