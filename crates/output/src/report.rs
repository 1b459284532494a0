//! The report directory: the pictures as SVG files and `report.html`, one self-contained page
//! with the summary, the pictures inline and the tables of events and pairs.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use unilateral_analysis::Analysis;
use unilateral_contact::ContactSolution;
use unilateral_fem::Model;

use crate::chart::{self, ChartKind};
use crate::svg::{self, TextMode};
use crate::{
    check_finite, state_style, structure_svg, ReportError, ReportOptions, DISPLACEMENTS_SVG,
    FORCES_SVG, REPORT_HTML, STRUCTURE_SVG,
};

/// The working-scheme map in the report directory.
pub const SCHEME_MAP_SVG: &str = "scheme-map.svg";

struct DrawnPictures {
    map: String,
    structure: Option<String>,
    forces: String,
    displacements: String,
}

/// Writes the pictures and `report.html` of an analysis into `dir`; returns the files written.
///
/// Without the structure picture: use [`write_structural_report`] for it.
pub fn write_report(
    analysis: &Analysis,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    write_all(None, Some(analysis), &analysis.solution, dir, options)
}

/// Writes the load-path charts, the structure picture and `report.html` of an analysis into
/// `dir`; returns the files written. The structure is the model the analysis was condensed
/// from ([`Condensed::model`](unilateral_fem::Condensed::model)).
pub fn write_structural_report(
    analysis: &Analysis,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    write_report_for(analysis.condensed.model(), analysis, dir, options)
}

/// Writes the load-path charts, the structure picture and `report.html` of an analysis of
/// `model` into `dir`; returns the files written. The analysis knows its model: prefer
/// [`write_structural_report`].
pub fn write_report_for(
    model: &Model,
    analysis: &Analysis,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    write_all(
        Some(model),
        Some(analysis),
        &analysis.solution,
        dir,
        options,
    )
}

/// Writes the load-path charts and `report.html` of a contact-zone solve (no structure to draw)
/// into `dir`; returns the files written.
pub fn write_path_report(
    solution: &ContactSolution,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    write_all(None, None, solution, dir, options)
}

fn write_all(
    model: Option<&Model>,
    analysis: Option<&Analysis>,
    solution: &ContactSolution,
    dir: &Path,
    options: &ReportOptions,
) -> Result<Vec<PathBuf>, ReportError> {
    std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::new();
    let mut put = |name: &str, text: &str| -> Result<(), ReportError> {
        let path = dir.join(name);
        crate::overwrite::write_over(&path, text.as_bytes()).map_err(|source| ReportError::Io {
            path: path.clone(),
            source,
        })?;
        written.push(path);
        Ok(())
    };
    // Everything is evaluated once; each picture is drawn twice: with the stroke font for
    // its standalone file (renders with no fonts), with real text inline in the HTML. The
    // path's two evaluations, and then the eight drawings, run side by side on the thread
    // pool; each drawing sets its text mode on the thread that draws it.
    let (samples, columns) = rayon::join(
        || chart::samples(solution),
        || chart::scheme_columns(solution),
    );
    let (samples, columns) = (samples?, columns?);
    let selected = chart::select(solution, &samples, options.pairs.as_deref());
    let draw = |mode: TextMode| {
        let chart = |kind: ChartKind| {
            svg::with_text_mode(mode, || {
                chart::chart(
                    solution,
                    &samples,
                    &selected,
                    kind,
                    options.units.as_deref(),
                )
            })
        };
        let ((map, structure), (forces, displacements)) = rayon::join(
            || {
                rayon::join(
                    || svg::with_text_mode(mode, || chart::scheme_map_svg(solution, &columns)),
                    || match (model, analysis) {
                        (Some(m), Some(a)) => {
                            Some(svg::with_text_mode(mode, || structure_svg(m, a, options)))
                        }
                        _ => None,
                    },
                )
            },
            || {
                rayon::join(
                    || chart(ChartKind::Forces),
                    || chart(ChartKind::Displacements),
                )
            },
        );
        DrawnPictures {
            map,
            structure,
            forces,
            displacements,
        }
    };
    let (files, inline) = rayon::join(|| draw(TextMode::Strokes), || draw(TextMode::Real));
    // Every picture is checked before any file is written (the inline ones draw the same
    // numbers).
    check_finite(SCHEME_MAP_SVG, &files.map)?;
    check_finite(FORCES_SVG, &files.forces)?;
    check_finite(DISPLACEMENTS_SVG, &files.displacements)?;
    if let Some(s) = &files.structure {
        check_finite(STRUCTURE_SVG, s)?;
    }
    put(SCHEME_MAP_SVG, &files.map)?;
    put(FORCES_SVG, &files.forces)?;
    put(DISPLACEMENTS_SVG, &files.displacements)?;
    if let Some(s) = &files.structure {
        put(STRUCTURE_SVG, s)?;
    }
    drop(files);
    let html = report_html(
        model,
        analysis,
        solution,
        options,
        &Pictures {
            structure: inline.structure.as_deref(),
            forces: &inline.forces,
            displacements: &inline.displacements,
            map: Some(&inline.map),
        },
    );
    put(REPORT_HTML, &html)?;
    Ok(written)
}

/// The SVG documents to put into the HTML report.
#[derive(Debug, Clone, Copy)]
pub struct Pictures<'a> {
    /// The structure picture (if there is a structure).
    pub structure: Option<&'a str>,
    /// The load-path chart of the forces.
    pub forces: &'a str,
    /// The load-path chart of the mutual displacements.
    pub displacements: &'a str,
    /// The working-scheme map (the first picture, when given).
    pub map: Option<&'a str>,
}

const CSS: &str = "body{font-family:sans-serif;margin:24px auto;max-width:1400px;color:#222;padding:0 16px}\
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ccc}\
table{border-collapse:collapse;font-size:.9em;margin:.5em 0}td,th{border:1px solid #ccc;padding:3px 8px}\
th{background:#f0f0f0}td.n{text-align:right;font-variant-numeric:tabular-nums;font-family:monospace}\
.pic{overflow-x:auto;margin:.6em 0}.pic svg{max-width:100%;height:auto}.sw{display:inline-block;width:.8em;height:.8em;border:1px solid #333;margin-right:.3em}\
dl{display:grid;grid-template-columns:max-content auto;gap:2px 16px}dt{font-weight:bold}";

/// The HTML report: summary, pictures inline, events and pairs tables.
pub fn report_html(
    model: Option<&Model>,
    analysis: Option<&Analysis>,
    sol: &ContactSolution,
    options: &ReportOptions,
    pics: &Pictures<'_>,
) -> String {
    use crate::finite::plain;
    use svg::esc;
    let title = options
        .title
        .clone()
        .unwrap_or_else(|| "unilateral — contact analysis report".into());
    let title = match &options.units {
        Some(u) => format!("{title} ({u})"),
        None => title,
    };
    // `[N]` after a force's heading, `[m]` after a length's, when the units are known.
    let about = crate::json::About {
        title: None,
        units: options.units.clone(),
    };
    let unit = |force: bool| match about.force_length() {
        Some((f, l)) => format!(" [{}]", esc(if force { f } else { l })),
        None => String::new(),
    };
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{CSS}</style>\n</head>\n<body>\n<h1>{}</h1>\n",
        esc(&title),
        esc(&title)
    );
    // summary
    h.push_str("<h2 id=\"summary\">Summary</h2>\n<dl>\n");
    let mut row = |k: &str, v: String| {
        let _ = writeln!(h, "<dt>{}</dt><dd>{}</dd>", esc(k), esc(&v));
    };
    if let Some(m) = model {
        row(
            "Model",
            format!(
                "{} nodes, {} elements, {} contact pairs",
                m.nodes().len(),
                m.elements().len(),
                m.pairs().len()
            ),
        );
    }
    if let Some(u) = &options.units {
        row("Units", u.clone());
    }
    row("Contact pairs", sol.pairs().to_string());
    if let Some(physical) = sol.physical_reading() {
        row("Physical path", physical);
    }
    row(
        "Status",
        format!("{} — {}", sol.outcome.status(), sol.reading()),
    );
    row(
        "Reported load p",
        sol.p.map(plain).unwrap_or_else(|| "none".into()),
    );
    row("Target p*", plain(sol.settings.target));
    row("Tightening c", plain(sol.tightening));
    row(
        "Steps of the load path",
        format!(
            "{} ({} before the target)",
            sol.steps.len(),
            sol.steps_before_target
        ),
    );
    if let Some(r) = &sol.residual {
        row(
            "Residuals",
            format!(
                "equation {:.2e}, sign conditions {:.2e}, complementarity {:.2e}",
                r.equation, r.feasibility, r.complementarity
            ),
        );
    }
    if let Some(ext) = analysis.and_then(|a| a.extremes()) {
        if let Some(d) = ext.displacement {
            row(
                "Largest displacement",
                format!("{} at node {}", plain(d.value), d.name),
            );
        }
        if let Some(m) = ext.moment {
            row(
                "Largest |M|",
                format!("{} in element {}", plain(m.value.abs()), m.name),
            );
        }
        if let Some(s) = ext.von_mises {
            row(
                "Largest von Mises stress",
                format!("{} in element {}", plain(s.value), s.name),
            );
        }
    }
    h.push_str("</dl>\n");
    if !sol.notes.is_empty() {
        h.push_str("<ul>\n");
        for n in &sol.notes {
            let _ = writeln!(h, "<li>{}</li>", esc(n));
        }
        h.push_str("</ul>\n");
    }
    // pictures: the working scheme first, the paper's central idea at a glance
    let tightened = sol.tightening > 0.0;
    let c_note = format!(
        "<p class=\"c-dependent\"><b>The paper's procedure, traced with the tightening c = {}:</b> the working-scheme map, the load-path charts and the table of events show the path with the tightening in it; their values, states and event loads depend on c. The table of pairs at the end is the solution without the tightening.</p>\n",
        esc(&plain(sol.tightening))
    );
    if let Some(map) = pics.map {
        h.push_str("<h2 id=\"scheme\">Working scheme</h2>\n");
        if tightened {
            h.push_str(&c_note);
        }
        let _ = writeln!(h, "<div class=\"pic\">{}</div>", strip_decl(map));
    }
    if let Some(s) = pics.structure {
        let _ = writeln!(
            h,
            "<h2 id=\"structure\">Structure</h2>\n<div class=\"pic\">{}</div>",
            strip_decl(s)
        );
    } else if analysis.is_some() {
        h.push_str("<h2 id=\"structure\">Structure</h2>\n<p>The structure picture needs the model (written by <code>write_report_for</code>).</p>\n");
    }
    h.push_str("<h2 id=\"load-path\">Load path</h2>\n");
    if tightened {
        h.push_str(&c_note);
    }
    let _ = writeln!(
        h,
        "<div class=\"pic\">{}</div>\n<div class=\"pic\">{}</div>",
        strip_decl(pics.forces),
        strip_decl(pics.displacements)
    );
    // events
    h.push_str("<h2 id=\"events\">Events</h2>\n");
    if tightened {
        let _ = writeln!(
            h,
            "<p>Events of the path traced with the tightening c = {}: their loads depend on c.</p>",
            esc(&plain(sol.tightening))
        );
    }
    h.push_str("<table class=\"events\">\n<tr><th>step</th><th>p</th><th>entering</th><th>leaving</th><th>events</th></tr>\n");
    for st in &sol.steps {
        let ev = if st.events.is_empty() {
            "—".to_string()
        } else {
            st.events
                .iter()
                .map(|e| e.to_string())
                .collect::<Vec<_>>()
                .join("; ")
        };
        let _ = writeln!(
            h,
            "<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td><td>{}</td><td>{}{}</td></tr>",
            st.index,
            plain(st.p),
            esc(&st.entering),
            esc(&st.leaving),
            esc(&ev),
            if st.settling {
                " (settles the start at p = 0: not an event)"
            } else if st.turning {
                " (turning point)"
            } else {
                ""
            }
        );
    }
    h.push_str("</table>\n");
    if sol.steps.is_empty() {
        h.push_str("<p>No events: the working scheme does not change along the path.</p>\n");
    }
    // pairs
    let _ = writeln!(
        h,
        "<h2 id=\"pairs\">Pairs at p = {}</h2>\n<table class=\"pairs\">\n<tr><th>pair</th><th>x<sub>n</sub>{f} (compression +)</th><th>x<sub>t</sub>{f}</th><th>z<sub>n</sub>{l} (opening +)</th><th>z<sub>t</sub>{l}</th><th>state</th></tr>",
        sol.p.map(plain).unwrap_or_else(|| "—".into()),
        f = unit(true),
        l = unit(false),
    );
    for r in &sol.pairs {
        let (c, _) = state_style(r.state);
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td><span class=\"sw\" style=\"background:{c}\"></span>{}</td></tr>",
            esc(&r.name), plain(r.x_n), plain(r.x_t), plain(r.z_n), plain(r.z_t), r.state
        );
    }
    h.push_str("</table>\n");
    if sol.pairs.is_empty() {
        h.push_str("<p>No solution reported.</p>\n");
    }
    let _ = writeln!(
        h,
        "<p style=\"color:#777;font-size:.8em\">unilateral-report {}</p>\n</body>\n</html>",
        env!("CARGO_PKG_VERSION")
    );
    h
}

fn strip_decl(s: &str) -> &str {
    s.trim_start_matches(|c: char| c != '<').trim_end()
}
