//! The command line: its arguments as clap types, and the `[solve]` values they override.

use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};

use crate::failure::Failure;

/// Frictional unilateral contact of 2D structures under a growing load, followed exactly
/// from event to event by the parametric Lemke method.
#[derive(Parser, Debug)]
#[command(name = "unilateral", version, about, long_about = None)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum TraceArg {
    /// Stop at the target load (Criterion 1).
    Target,
    /// Follow the path until the scheme stops changing or a mechanism forms.
    End,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum StressArg {
    /// The von Mises equivalent stress.
    Vm,
    /// σxx.
    Sxx,
    /// σyy.
    Syy,
}

/// How `--vtk` writes the data arrays of its `.vtu` files.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub(crate) enum VtkFormatArg {
    /// Every value as text (the default: readable, and read by scripts that parse it).
    Ascii,
    /// Raw little-endian bytes appended to the file: exact, smaller, faster to read.
    Binary,
    /// The binary arrays zlib-compressed (smallest; read by every VTK reader).
    Compressed,
    /// The binary arrays compressed by LZ4 (a few per cent larger than zlib's, a little faster
    /// to write and much faster to read; ParaView from 5.5, not meshio).
    Lz4,
}

impl VtkFormatArg {
    /// The writers' format.
    pub(crate) fn format(self) -> unilateral_output::VtkFormat {
        match self {
            VtkFormatArg::Ascii => unilateral_output::VtkFormat::Ascii,
            VtkFormatArg::Binary => unilateral_output::VtkFormat::Binary,
            VtkFormatArg::Compressed => unilateral_output::VtkFormat::Compressed,
            VtkFormatArg::Lz4 => unilateral_output::VtkFormat::Lz4,
        }
    }
}

/// When progress is drawn on stderr (`--progress`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub(crate) enum ProgressArg {
    /// A bar on stderr when it is a terminal and the run lasts more than a second.
    #[default]
    Auto,
    /// Also when stderr is not a terminal: plain lines, at most four a second.
    Always,
    /// Never.
    Never,
}

/// Options of `--report`.
#[derive(clap::Args, Debug, Clone)]
pub(crate) struct ReportArgs {
    /// Chart only these pairs (names, comma-separated; default: all).
    #[arg(long, value_name = "NAMES", value_delimiter = ',', requires = "report")]
    pub(crate) report_pairs: Option<Vec<String>>,
    /// Structural load histories: chart the load–displacement curves of these nodes (names,
    /// comma-separated; default: the node that moves most at the end).
    #[arg(long, value_name = "NAMES", value_delimiter = ',', requires = "report")]
    pub(crate) report_nodes: Option<Vec<String>>,
    /// Draw the bending moment diagrams of frame members in the structure picture.
    #[arg(long, requires = "report")]
    pub(crate) moments: bool,
    /// The stress that colours plane elements (default: vm).
    #[arg(long, value_enum, requires = "report")]
    pub(crate) stress: Option<StressArg>,
}

impl ReportArgs {
    /// Every name given to `--report-pairs` must be a pair of the problem (`pairs`: the names
    /// of its pairs, known before the solve, so that a bad name is refused before any work).
    pub(crate) fn check(&self, pairs: &[String]) -> Result<(), Failure> {
        for name in self.report_pairs.iter().flatten() {
            if !pairs.iter().any(|p| p == name) {
                let known: Vec<&str> = pairs.iter().take(12).map(String::as_str).collect();
                return Err(Failure::Input(format!(
                    "--report-pairs: no pair named '{name}'; the pairs are {}{}",
                    known.join(", "),
                    if pairs.len() > 12 { ", …" } else { "" }
                )));
            }
        }
        Ok(())
    }

    /// `--moments` and `--stress` draw on the structure picture of a structural model's
    /// report: where the report has none (a contact zone, a load history), they would be
    /// ignored, so they are refused; `what` says what the file is.
    pub(crate) fn no_structure_picture(&self, what: &str) -> Result<(), Failure> {
        let given = crate::failure::given_options(&[
            ("--moments", self.moments),
            ("--stress", self.stress.is_some()),
        ]);
        if given.is_empty() {
            return Ok(());
        }
        Err(Failure::Input(format!(
            "{} {} the structure picture of a structural model's report; the report of {what} \
             has none",
            given.join(" and "),
            if given.len() == 1 {
                "draws on"
            } else {
                "draw on"
            }
        )))
    }

    pub(crate) fn options(
        &self,
        title: Option<String>,
        units: Option<String>,
    ) -> unilateral_output::ReportOptions {
        unilateral_output::ReportOptions {
            pairs: self.report_pairs.clone(),
            moments: self.moments,
            stress: match self.stress.unwrap_or(StressArg::Vm) {
                StressArg::Vm => unilateral_output::StressComponent::VonMises,
                StressArg::Sxx => unilateral_output::StressComponent::Sxx,
                StressArg::Syy => unilateral_output::StressComponent::Syy,
            },
            title,
            units,
        }
    }
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Follow the load path of a problem file and report the solution.
    Solve(SolveArgs),
    /// Print the Lemke tableaux of the path, step by step, as in the paper's Tables 1-3.
    Tableau(TableauArgs),
    /// Solve a plain LCP w = Mz + q (Siconos .dat, .toml or .json).
    Lcp(LcpArgs),
    /// List the bundled examples, or write one out to start from.
    Example(ExampleArgs),
    /// Write a structural model's contact zone (R, loads, friction, gaps) as a contact-zone file.
    Zone(ZoneArgs),
}

/// The arguments of `unilateral zone`.
#[derive(clap::Args, Debug)]
pub(crate) struct ZoneArgs {
    /// A structural model (.toml or .json).
    pub(crate) model: PathBuf,
    /// The contact-zone file to write (`-` for stdout).
    #[arg(long, value_name = "ZONE.toml")]
    pub(crate) out: PathBuf,
}

/// The arguments of `unilateral solve`.
#[derive(clap::Args, Debug)]
pub(crate) struct SolveArgs {
    /// A structural model or a contact-zone problem (.toml or .json).
    pub(crate) file: PathBuf,
    /// The load p* at which the solution is reported (default: the file's, else 1).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) target: Option<f64>,
    /// How far to follow the path.
    #[arg(long, value_enum)]
    pub(crate) trace: Option<TraceArg>,
    /// The artificial tightening c ≥ 0.
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) tightening: Option<f64>,
    /// Write the result document as JSON to this file (`-` for stdout).
    #[arg(long, value_name = "OUT.json")]
    pub(crate) json: Option<PathBuf>,
    /// In the JSON document, every pair at every step of the load path (`steps[k].pairs`;
    /// traced with the tightening, the traced path's values, which depend on c).
    #[arg(long, requires = "json")]
    pub(crate) json_breakpoints: bool,
    /// Write CSV tables into this directory (pairs.csv, steps.csv, path.csv; for structural
    /// models also displacements, reactions, element forces and stresses; for a [[history]]
    /// the history_*.csv tables of its stages, breakpoints and events).
    #[arg(long, value_name = "DIR")]
    pub(crate) csv: Option<PathBuf>,
    /// Write the load-path charts, the structure picture and report.html into this directory.
    #[arg(long, value_name = "DIR")]
    pub(crate) report: Option<PathBuf>,
    /// Write ParaView files (.vtu per event, .pvd collection) into this directory
    /// (structural models).
    #[arg(long, value_name = "DIR")]
    pub(crate) vtk: Option<PathBuf>,
    /// How the .vtu files of --vtk hold their data arrays.
    #[arg(
        long,
        value_enum,
        value_name = "FORMAT",
        default_value = "ascii",
        requires = "vtk"
    )]
    pub(crate) vtk_format: VtkFormatArg,
    /// List every step and every pair in the summary, however many (by default a problem of
    /// more than 24 pairs gets counts of states, the first and last events, and the pairs with
    /// the largest forces and slips).
    #[arg(long)]
    pub(crate) verbose: bool,
    /// Progress on stderr (pivots, load, steps, elapsed time) for a run longer than a second.
    #[arg(long, value_enum, value_name = "WHEN", default_value = "auto")]
    pub(crate) progress: ProgressArg,
    #[command(flatten)]
    pub(crate) report_args: ReportArgs,
}

/// The arguments of `unilateral tableau`.
#[derive(clap::Args, Debug)]
pub(crate) struct TableauArgs {
    /// A contact-zone problem or a structural model (.toml or .json).
    pub(crate) file: PathBuf,
    /// Print at most this many steps.
    #[arg(long)]
    pub(crate) steps: Option<usize>,
    /// Write the tableaux as JSON to this file (`-` for stdout).
    #[arg(long, value_name = "OUT.json")]
    pub(crate) json: Option<PathBuf>,
}

/// The arguments of `unilateral lcp`.
#[derive(clap::Args, Debug)]
pub(crate) struct LcpArgs {
    /// The problem file.
    pub(crate) file: PathBuf,
    /// Write the result as JSON to this file (`-` for stdout).
    #[arg(long, value_name = "OUT.json")]
    pub(crate) json: Option<PathBuf>,
    /// Progress on stderr (pivots, elapsed time) for a run longer than a second.
    #[arg(long, value_enum, value_name = "WHEN", default_value = "auto")]
    pub(crate) progress: ProgressArg,
}

/// The arguments of `unilateral example`.
#[derive(clap::Args, Debug)]
pub(crate) struct ExampleArgs {
    /// The example to write out.
    pub(crate) name: Option<String>,
    /// Directory to write into (default: the current directory).
    #[arg(long, value_name = "DIR", default_value = ".")]
    pub(crate) to: PathBuf,
    /// Overwrite an existing file.
    #[arg(long)]
    pub(crate) force: bool,
}

/// Command-line values that override the file's `[solve]` table.
pub(crate) struct Overrides {
    pub(crate) target: Option<f64>,
    pub(crate) trace: Option<TraceArg>,
    pub(crate) tightening: Option<f64>,
}

impl Overrides {
    pub(crate) fn apply(
        &self,
        settings: &mut unilateral_contact::SolveSettings,
    ) -> Result<(), Failure> {
        if let Some(t) = self.target {
            settings.target = t;
        }
        if let Some(t) = self.trace {
            settings.follow = match t {
                TraceArg::Target => unilateral_contact::Follow::ToTarget,
                TraceArg::End => unilateral_contact::Follow::ToEnd,
            };
        }
        if let Some(c) = self.tightening {
            settings.tightening = c;
        }
        settings
            .validate()
            .map_err(|e| Failure::Input(format!("command line: {e}")))
    }
}

#[cfg(test)]
mod tests {
    /// clap's own check of the definitions (names that `requires` refers to exist, no two
    /// arguments share a flag).
    #[test]
    fn the_command_line_is_consistent() {
        use clap::CommandFactory;
        super::Cli::command().debug_assert();
    }
}
