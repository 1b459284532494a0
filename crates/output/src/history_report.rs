//! The report of a load history: one HTML page with the summary, the load–displacement curves
//! of the chosen pairs over the history, the curve of the busiest load case, and the map of
//! every pair's state over the history's pseudo-time; each picture also as an SVG file.

use std::path::{Path, PathBuf};

use unilateral_contact::HistorySolution;

use crate::{
    busiest_case, history_curves_svg, history_states_svg, history_summary, CurveKind,
    HistoryChartOptions, NonFiniteOutput,
};

/// File names of the history report.
pub const HISTORY_REPORT_HTML: &str = "report.html";

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The pictures of a history as `(file name, caption, svg)`.
pub fn history_pictures(
    h: &HistorySolution,
    options: &HistoryChartOptions,
) -> Result<Vec<(String, String, String)>, NonFiniteOutput> {
    let mut out = vec![(
        "history-curves.svg".to_string(),
        "Tangential force against accumulated slip of the chosen pairs over the whole history \
         (every breakpoint in order; a closed loop is a hysteresis loop)"
            .to_string(),
        history_curves_svg(h, options, &CurveKind::TangentialForce)?,
    )];
    if let Some(c) = busiest_case(h) {
        let case = h.cases[c].clone();
        out.push((
            "history-factor.svg".to_string(),
            format!(
                "The factor of load case `{case}` against the accumulated slip of the chosen pairs"
            ),
            history_curves_svg(h, options, &CurveKind::Factor(case))?,
        ));
    }
    out.push((
        "history-states.svg".to_string(),
        "The state of every pair over the history's pseudo-time (stage − 1 + s)".to_string(),
        history_states_svg(h)?,
    ));
    Ok(out)
}

/// Writes the history report into `dir`: `report.html` (the summary and every picture inline)
/// and each picture as an SVG file. Returns the files written.
///
/// `extra` are further pictures `(file name, caption, svg)` placed after the pairs' curves (the
/// node curves of a structural model, [`crate::node_curves_svg`]).
pub fn write_history_report(
    h: &HistorySolution,
    dir: &Path,
    title: &str,
    options: &HistoryChartOptions,
    extra: Vec<(String, String, String)>,
) -> std::io::Result<Vec<PathBuf>> {
    // Each picture twice: with the stroke font for its file (renders with no fonts), with
    // real text inline in the HTML (any script, searchable). The `extra` pictures come drawn.
    let mut pictures = history_pictures(h, options).map_err(std::io::Error::from)?;
    let mut inline =
        crate::svg::with_text_mode(crate::svg::TextMode::Real, || history_pictures(h, options))
            .map_err(std::io::Error::from)?;
    let at = pictures.len().saturating_sub(1);
    for (k, p) in extra.into_iter().enumerate() {
        inline.insert(at + k, p.clone());
        pictures.insert(at + k, p);
    }
    let summary = history_summary(h, title).map_err(std::io::Error::from)?;
    std::fs::create_dir_all(dir)?;
    let mut files = Vec::new();
    let mut html = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n\
         <style>body{{font-family:sans-serif;max-width:1200px;margin:2em auto}}\
         pre{{background:#f6f6f6;padding:1em;overflow-x:auto}}figure{{margin:2em 0}}\
         figcaption{{color:#444}}</style>\n</head>\n<body>\n<h1>{}</h1>\n<pre>{}</pre>\n",
        escape(title),
        escape(title),
        escape(&summary)
    );
    for ((name, caption, svg), (_, _, shown)) in pictures.iter().zip(&inline) {
        let path = dir.join(name);
        std::fs::write(&path, svg)?;
        files.push(path);
        html.push_str(&format!(
            "<figure>\n{shown}\n<figcaption>{}</figcaption>\n</figure>\n",
            escape(caption)
        ));
    }
    html.push_str("</body>\n</html>\n");
    let path = dir.join(HISTORY_REPORT_HTML);
    std::fs::write(&path, html)?;
    files.push(path);
    Ok(files)
}
