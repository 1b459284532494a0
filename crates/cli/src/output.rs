//! What every command shares in writing its answers: progress on a terminal, JSON documents,
//! the list of files written.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::args::ProgressArg;
use crate::failure::Failure;

/// How long a run goes before its progress is shown; `UNILATERAL_PROGRESS_AFTER_MS` changes it
/// (for the tests, which cannot wait for long runs).
fn progress_delay() -> Duration {
    std::env::var("UNILATERAL_PROGRESS_AFTER_MS")
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .map_or(Duration::from_secs(1), Duration::from_millis)
}

/// The bar being drawn, if any: whatever the program writes to the terminal while it is shown
/// goes through [`ProgressBar::suspend`] so that no line is torn.
static BAR: Mutex<Option<ProgressBar>> = Mutex::new(None);

/// Runs `f` with the progress bar (if one is drawn) taken off the terminal.
fn suspended<R>(f: impl FnOnce() -> R) -> R {
    let bar = BAR.lock().ok().and_then(|b| b.clone());
    match bar {
        Some(bar) => bar.suspend(f),
        None => f(),
    }
}

/// Writes a line on stderr (with the progress bar, if any, out of the way).
pub(crate) fn note(line: &str) {
    suspended(|| err_line(line));
}

/// Progress of a run on stderr: the engine's [`unilateral_lcp::Progress`] counters read by a
/// drawing thread every 100 ms and shown, once the run has lasted [`progress_delay`], as an
/// `indicatif` spinner on a terminal or as plain lines (`--progress always` elsewhere). Dropping
/// it stops the thread and clears the bar; in plain lines it ends with one line of totals.
pub(crate) struct Drawer {
    handle: unilateral_lcp::Progress,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drawer {
    /// Starts drawing (or not, by `mode` and whether stderr is a terminal).
    pub(crate) fn start(mode: ProgressArg) -> Self {
        use std::io::IsTerminal;
        let terminal = std::io::stderr().is_terminal();
        let on = match mode {
            ProgressArg::Never => false,
            ProgressArg::Auto => terminal,
            ProgressArg::Always => true,
        };
        let stop = Arc::new(AtomicBool::new(false));
        if !on {
            return Self {
                handle: unilateral_lcp::Progress::default(),
                stop,
                thread: None,
            };
        }
        let handle = unilateral_lcp::Progress::new();
        let (h, s) = (handle.clone(), stop.clone());
        let delay = progress_delay();
        let thread = std::thread::Builder::new()
            .name("progress".into())
            .spawn(move || draw(&h, &s, delay, terminal))
            .ok();
        Self {
            handle,
            stop,
            thread,
        }
    }

    /// The handle to put into the engine's settings (inert when nothing is drawn).
    pub(crate) fn handle(&self) -> unilateral_lcp::Progress {
        self.handle.clone()
    }

    /// Tells what the program does now.
    pub(crate) fn phase(&self, phase: unilateral_lcp::Phase) {
        self.handle.phase(phase);
    }
}

impl Drop for Drawer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            t.thread().unpark();
            let _ = t.join();
        }
    }
}

/// The drawing thread's loop.
fn draw(h: &unilateral_lcp::Progress, stop: &AtomicBool, delay: Duration, terminal: bool) {
    let started = Instant::now();
    let tick = Duration::from_millis(100);
    let line_every = Duration::from_millis(250);
    let mut last_line: Option<Instant> = None;
    let mut shown = false;
    loop {
        // A tick first: nothing is drawn in the first 100 ms whatever the delay.
        if !stop.load(Ordering::Relaxed) {
            std::thread::park_timeout(tick);
        }
        let done = stop.load(Ordering::Relaxed);
        let elapsed = started.elapsed();
        if elapsed >= delay {
            if let Some(snap) = h.snapshot() {
                let text = progress_text(&snap);
                if terminal {
                    if !shown {
                        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
                        bar.set_style(
                            ProgressStyle::with_template("{spinner} {wide_msg}")
                                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
                        );
                        if let Ok(mut b) = BAR.lock() {
                            *b = Some(bar);
                        }
                        shown = true;
                    }
                    if let Some(bar) = BAR.lock().ok().and_then(|b| b.clone()) {
                        bar.set_message(format!(
                            "{:.1} s  {}: {text}",
                            elapsed.as_secs_f64(),
                            snap.phase.as_str()
                        ));
                        bar.tick();
                    }
                } else if done || last_line.is_none_or(|t| t.elapsed() >= line_every) {
                    let secs = elapsed.as_secs_f64();
                    if done {
                        err_line(&format!("unilateral: done in {secs:.1} s: {text}"));
                    } else {
                        err_line(&format!(
                            "unilateral: {secs:.1} s, {}: {text}",
                            snap.phase.as_str()
                        ));
                    }
                    last_line = Some(Instant::now());
                }
            }
        }
        if done {
            break;
        }
    }
    if let Some(bar) = BAR.lock().ok().and_then(|mut b| b.take()) {
        bar.finish_and_clear();
    }
}

/// `following the load path: 1021 steps, 3120 pivots, p = 0.734` (the phase is left out of
/// the final line, where it would be stale).
fn progress_text(s: &unilateral_lcp::Snapshot) -> String {
    let mut parts = Vec::new();
    if s.stage > 0 {
        parts.push(format!("stage {}", s.stage));
    }
    parts.push(format!(
        "{} step{}",
        s.steps,
        if s.steps == 1 { "" } else { "s" }
    ));
    parts.push(format!(
        "{} pivot{}",
        s.pivots,
        if s.pivots == 1 { "" } else { "s" }
    ));
    if let Some(p) = s.load {
        parts.push(format!(
            "{} = {}",
            if s.stage > 0 { "s" } else { "p" },
            short(p)
        ));
    }
    parts.join(", ")
}

/// Six significant digits, plainly.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-4..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        let t = format!("{v:.decimals$}");
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    } else {
        format!("{v:.5e}")
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
        note(&line);
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
pub(crate) fn write_json(out: &Path, value: serde_json::Value) -> Result<(), Failure> {
    write_document(out, value.into())
}

/// [`write_json`] for a document whose values at the breakpoints are formed as it is written
/// ([`unilateral_output::PathDocument`]). If forming them fails, what was at `out` stays and
/// the failure is that of the values (as [`path_output_failure`] says), not of the writing.
pub(crate) fn write_document(
    out: &Path,
    doc: unilateral_output::PathDocument<'_>,
) -> Result<(), Failure> {
    use std::io::Write;
    let doc = doc.map(unilateral_output::with_provenance);
    let failed = |e: serde_json::Error, otherwise: &dyn Fn(&dyn std::fmt::Display) -> Failure| {
        doc.take_error()
            .map_or_else(|| otherwise(&e), path_output_failure)
    };
    if out == Path::new("-") {
        let text = serde_json::to_string_pretty(&doc)
            .map_err(|e| failed(e, &|e| Failure::Internal(format!("JSON: {e}"))))?;
        self::out(&format!("{text}\n"));
        return Ok(());
    }
    // Streamed to the file: a long path's document is not held twice more as text. The values
    // at the breakpoints are formed while it is written, so a failure can come after the first
    // byte: a regular file is written beside its place and renamed into it when complete, so
    // that a failure leaves whatever was there before (a device or a pipe is written directly).
    let cannot =
        |e: &dyn std::fmt::Display| Failure::Input(format!("cannot write {}: {e}", out.display()));
    let direct = std::fs::metadata(out).is_ok_and(|m| !m.is_file());
    let part = if direct {
        out.to_path_buf()
    } else {
        let name = out.file_name().map_or_else(
            || std::ffi::OsString::from("out.json"),
            |n| n.to_os_string(),
        );
        let mut hidden = std::ffi::OsString::from(".");
        hidden.push(&name);
        hidden.push(format!(".{}.part", std::process::id()));
        out.with_file_name(hidden)
    };
    let file = std::fs::File::create(&part).map_err(|e| cannot(&e))?;
    let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
    let written = match serde_json::to_writer_pretty(&mut w, &doc) {
        Err(e) => Err(failed(e, &cannot)),
        Ok(()) => w
            .write_all(b"\n")
            .and_then(|()| w.flush())
            .map_err(|e| cannot(&e)),
    };
    drop(w);
    if direct {
        return written;
    }
    let placed = written.and_then(|()| std::fs::rename(&part, out).map_err(|e| cannot(&e)));
    if placed.is_err() {
        let _ = std::fs::remove_file(&part);
    }
    placed
}

/// Writes `text` to stdout. A reader that closed the pipe early (`unilateral solve … | head`)
/// is no failure: the rest is dropped quietly (the `print!` macros would panic there).
pub(crate) fn out(text: &str) {
    use std::io::Write;
    suspended(|| {
        let mut o = std::io::stdout().lock();
        let _ = o.write_all(text.as_bytes()).and_then(|()| o.flush());
    });
}

/// Writes one line to stderr: a closed stderr (`unilateral … 2>&1 | head -1`) is no failure
/// either (`eprintln!` would panic there, exit 101).
pub(crate) fn err_line(text: &str) {
    use std::io::Write;
    let mut e = std::io::stderr().lock();
    let _ = e
        .write_all(text.as_bytes())
        .and_then(|()| e.write_all(b"\n"))
        .and_then(|()| e.flush());
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
