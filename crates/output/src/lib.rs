//! # unilateral-output — the answers turned into files
//!
//! * the summary, the JSON document and the CSV tables of a contact-zone solve, a structural
//!   analysis, the Lemke tableaux and a plain LCP ([`contact_summary`], [`structural_json`],
//!   [`write_structural_csv`], …) and ParaView files over the load path ([`write_vtk`]);
//!   none of them ever writes a number that is not finite: they return a [`NonFiniteOutput`]
//!   instead (an internal failure: the readers accept only finite data);
//! * load-path charts ([`load_path_svgs`]): the forces `x_n`, `x_t` and the mutual
//!   displacements `z_n`, `z_t` of the pairs against the load `p`, one small panel per pair,
//!   every event marked and numbered — the working scheme changing as the load grows;
//! * the structure picture ([`structure_svg`]): undeformed (grey) and deformed shape with an
//!   automatic, printed scale factor, bending moments of frames on request, plane elements
//!   coloured by a stress with a colour bar, the pairs as symbols coloured by their state and
//!   arrows for the contact forces;
//! * `report.html` ([`report_html`]): one self-contained file with the summary, the pictures
//!   inline and the tables of events and pairs.
//!
//! Everything is hand-written SVG. Text is drawn with a small built-in stroke font
//! ([`font`]) as SVG paths, so the pictures look the same on a machine without fonts.
//!
//! The structure is drawn from the finite-element model the analysis was condensed from
//! ([`write_structural_report`]); [`write_report`] writes the charts and the HTML without the
//! structure picture.

#![warn(missing_docs)]

use std::path::PathBuf;

use unilateral_analysis::Analysis;
use unilateral_contact::ContactSolution;
use unilateral_fem::Model;

mod chart;
mod csv;
mod decimal;
pub mod deflate;
mod finite;
pub mod font;
mod json;
mod overwrite;
#[cfg(test)]
mod replay;
mod report;
mod structure;
mod summary;
pub mod svg;
mod vtk;
mod zone_file;

pub use csv::{
    write_contact_csv, write_contact_csv_with, write_structural_csv, write_structural_csv_with,
    PATH_CSV,
};
pub use finite::NonFiniteOutput;
pub use json::{
    contact_json, contact_json_with, lcp_json, residual_json, structural_json,
    structural_json_with, tableaux_json, timings_json, with_provenance, with_timings, About,
    PathDocument, PathJsonOptions, PathOutputError, SCHEMA,
};
pub use report::{
    report_html, write_path_report, write_report, write_report_for, write_structural_report,
    Pictures,
};
pub use summary::{
    contact_summary, contact_summary_detail, contact_summary_with, lcp_summary, structural_summary,
    structural_summary_detail, structural_summary_with, tableau_text, timings_summary, Detail,
    SUMMARY_LIST_PAIRS,
};
#[allow(deprecated)]
pub use vtk::ZLIB_BLOCK;
pub use vtk::{write_vtk, write_vtk_for, write_vtk_with, VtkFormat, COMPRESSED_BLOCK, PVD_FILE};
pub use zone_file::zone_toml;

pub use chart::{event_word, samples, step_label, ChartKind, PathSamples};
pub use structure::state_style;

// The outputs of a load history (`history.md`): JSON, CSV, summary, pictures, ParaView.
mod history;
mod history_chart;
mod history_nodes;
mod history_report;
mod history_structure;
mod history_vtk;
pub use history::{
    change_word, history_csv, history_document, history_event_sentence, history_json,
    history_reading, history_summary, pseudo_time, stage_table_name, with_history,
    HISTORY_BREAKPOINTS_CSV, HISTORY_EVENTS_CSV, SUMMARY_PAIRS,
};
pub use history_chart::{
    busiest_case, curve_pairs, history_curves_svg, history_states_svg, state_runs, CurveKind,
    HistoryChartOptions, StateRun, CURVE_PAIRS,
};
pub use history_nodes::{node_curves, node_curves_svg, NodePoint};
pub use history_report::{history_pictures, write_history_report, HISTORY_REPORT_HTML};
pub use history_structure::history_structural_document;
pub use history_vtk::{history_vtk, history_vtk_with, HISTORY_PVD, HISTORY_VTK_STEPS};

/// The stress that colours plane elements.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum StressComponent {
    /// `σxx`.
    Sxx,
    /// `σyy`.
    Syy,
    /// The von Mises equivalent stress (with `σzz`).
    #[default]
    VonMises,
}

/// What to draw.
#[derive(Debug, Clone, Default)]
pub struct ReportOptions {
    /// Pair names to show in the load-path charts (`None`: all).
    pub pairs: Option<Vec<String>>,
    /// Draw the bending moment diagram on frame members.
    pub moments: bool,
    /// The stress that colours plane elements (default von Mises).
    pub stress: StressComponent,
    /// A title for the report (for instance the model file's `title`).
    pub title: Option<String>,
    /// The file's `units` (`"N, m"`): in the report's title and the headings of its tables.
    pub units: Option<String>,
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
    /// A picture would contain a number that is not finite. The results handed to the report
    /// are checked finite, so this is a fault of the program; nothing is written.
    #[error(
        "the picture {file} would contain `{token}`, not a finite number; this is a fault of \
         the program, not of the input, and no report was written"
    )]
    NonFinite {
        /// The picture.
        file: &'static str,
        /// The token found (`NaN`, `inf` or `-inf`).
        token: String,
    },
    /// The solution could not be evaluated at a load of the charts (its forces leave the
    /// floating-point range there, or the engine failed); nothing is written.
    #[error("the load-path charts could not be drawn: {0}")]
    Contact(#[from] unilateral_contact::ContactError),
}

/// The first `NaN` or `inf` that a drawing would print as a number, outside the `<title>`
/// texts (which hold the user's names, where such words may stand).
fn non_finite_token(svg: &str) -> Option<String> {
    let mut rest = svg;
    while !rest.is_empty() {
        let (drawn, after) = match rest.find("<title>") {
            Some(i) => {
                let end = rest[i..].find("</title>").map_or(rest.len(), |j| i + j);
                (&rest[..i], &rest[end..])
            }
            None => (rest, ""),
        };
        let bytes = drawn.as_bytes();
        for word in ["NaN", "inf"] {
            for (i, _) in drawn.match_indices(word) {
                let before = i.checked_sub(1).map(|k| bytes[k]);
                let next = bytes.get(i + word.len()).copied();
                let letter =
                    |b: Option<u8>| b.is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_');
                if !letter(before) && !letter(next) {
                    let sign = if before == Some(b'-') { "-" } else { "" };
                    return Some(format!("{sign}{word}"));
                }
            }
        }
        rest = after.strip_prefix("</title>").unwrap_or(after);
    }
    None
}

/// `Ok` when the picture `file` prints only finite numbers.
fn check_finite(file: &'static str, svg: &str) -> Result<(), ReportError> {
    match non_finite_token(svg) {
        Some(token) => Err(ReportError::NonFinite { file, token }),
        None => Ok(()),
    }
}

/// Names of the files written into the report directory.
pub const FORCES_SVG: &str = "load-path-forces.svg";
/// The chart of the mutual displacements.
pub const DISPLACEMENTS_SVG: &str = "load-path-displacements.svg";
/// The structure picture.
pub const STRUCTURE_SVG: &str = "structure.svg";
/// The HTML report.
pub const REPORT_HTML: &str = "report.html";

/// The two load-path charts (forces, mutual displacements) as SVG documents.
pub fn load_path_svgs(
    solution: &ContactSolution,
    options: &ReportOptions,
) -> Result<(String, String), ReportError> {
    let s = chart::samples(solution)?;
    let sel = chart::select(solution, &s, options.pairs.as_deref());
    Ok((
        chart::chart(
            solution,
            &s,
            &sel,
            ChartKind::Forces,
            options.units.as_deref(),
        ),
        chart::chart(
            solution,
            &s,
            &sel,
            ChartKind::Displacements,
            options.units.as_deref(),
        ),
    ))
}

/// The structure picture at the reported load as an SVG document.
pub fn structure_svg(model: &Model, analysis: &Analysis, options: &ReportOptions) -> String {
    structure::structure_svg(model, analysis, options)
}

#[cfg(test)]
mod tests {
    use super::non_finite_token;

    #[test]
    fn non_finite_numbers_are_found_outside_titles() {
        assert_eq!(
            non_finite_token(r#"<path d="M 0 0 L NaN 3"/>"#),
            Some("NaN".into())
        );
        assert_eq!(
            non_finite_token(r#"<circle cx="-inf" cy="1"/>"#),
            Some("-inf".into())
        );
        assert_eq!(
            non_finite_token(r#"<line x1="inf,2"/>"#),
            Some("inf".into())
        );
        // Names in titles, and words that merely contain the letters, are not numbers.
        assert_eq!(
            non_finite_token(
                r#"<path d="M 0 0"><title>pair inf.NaN</title></path><g class="info"/>"#
            ),
            None
        );
        assert_eq!(
            non_finite_token(r#"<path d="M 1e300 2.5e-3 L 0 0"/>"#),
            None
        );
    }
}
