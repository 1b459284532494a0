//! What every command shares in writing its answers: progress on a terminal, JSON documents,
//! the list of files written, the timings of the run.

use std::path::{Path, PathBuf};

use serde_json::Value;
use unilateral_analysis::Timings;

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
        println!("{text}");
        return Ok(());
    }
    std::fs::write(out, text + "\n")
        .map_err(|e| Failure::Input(format!("cannot write {}: {e}", out.display())))
}

/// The `timings` object of a result document: the seconds of each part of the run that
/// happened (`read`, `condense`, `solve`, `recover`, `write`, in that order of the run; the
/// keys of the parts that did not happen are absent). Durations are finite and non-negative by
/// construction, so no finite-number check is needed.
pub(crate) fn timings_json(t: &Timings) -> Value {
    Value::Object(
        t.present()
            .map(|(name, d)| (name.to_string(), Value::from(d.as_secs_f64())))
            .collect(),
    )
}

/// The result document with its `timings` added.
pub(crate) fn with_timings(mut doc: Value, t: &Timings) -> Value {
    if let Some(obj) = doc.as_object_mut() {
        obj.insert("timings".into(), timings_json(t));
    }
    doc
}

/// The closing paragraph of a summary: a blank line and `time: read 0.01 s, solve 0.20 s`, the
/// parts of the run done by the time the summary is printed.
pub(crate) fn timings_summary(t: &Timings) -> String {
    let parts: Vec<String> = t
        .present()
        .map(|(name, d)| format!("{name} {:.2} s", d.as_secs_f64()))
        .collect();
    format!("\ntime: {}\n", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;

    /// Hand-made timings: only the parts given appear, in the order of a run, in seconds.
    #[test]
    fn timings_are_written_in_seconds_for_the_parts_that_happened() {
        let t = Timings {
            read: Some(Duration::from_millis(12)),
            solve: Some(Duration::from_millis(1500)),
            write: Some(Duration::from_micros(250)),
            ..Timings::default()
        };
        assert_eq!(
            timings_json(&t),
            serde_json::json!({ "read": 0.012, "solve": 1.5, "write": 0.00025 })
        );
        assert_eq!(
            timings_summary(&t),
            "\ntime: read 0.01 s, solve 1.50 s, write 0.00 s\n"
        );
        let doc = with_timings(serde_json::json!({ "status": "solved" }), &t);
        assert_eq!(doc["status"], "solved");
        assert_eq!(doc["timings"]["solve"], 1.5);
        assert!(doc["timings"].get("condense").is_none());
    }
}
