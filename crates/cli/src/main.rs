//! `unilateral`: frictional unilateral contact of 2D structures under a growing load.
//!
//! A thin front end: it parses arguments, calls the libraries and maps their answers to exit
//! codes (0 an answer, 2 bad input, 1 internal failure).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

mod examples;

/// Frictional unilateral contact of 2D structures under a growing load, followed exactly
/// from event to event by the parametric Lemke method.
#[derive(Parser, Debug)]
#[command(name = "unilateral", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum TraceArg {
    /// Stop at the target load (Criterion 1).
    Target,
    /// Follow the path until the scheme stops changing or a mechanism forms.
    End,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum StressArg {
    /// The von Mises equivalent stress.
    Vm,
    /// σxx.
    Sxx,
    /// σyy.
    Syy,
}

/// Options of `--report`.
#[derive(clap::Args, Debug, Clone)]
struct ReportArgs {
    /// Chart only these pairs (names, comma-separated; default: all).
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    report_pairs: Option<Vec<String>>,
    /// Draw the bending moment diagrams of frame members in the structure picture.
    #[arg(long)]
    moments: bool,
    /// The stress that colours plane elements.
    #[arg(long, value_enum, default_value = "vm")]
    stress: StressArg,
}

impl ReportArgs {
    /// Every name given to `--report-pairs` must be a pair of the problem.
    fn check(&self, pairs: &[unilateral_contact::PairResult]) -> Result<(), Failure> {
        for name in self.report_pairs.iter().flatten() {
            if !pairs.iter().any(|p| &p.name == name) {
                let known: Vec<&str> = pairs.iter().take(12).map(|p| p.name.as_str()).collect();
                return Err(Failure::Input(format!(
                    "--report-pairs: no pair named '{name}'; the pairs are {}{}",
                    known.join(", "),
                    if pairs.len() > 12 { ", …" } else { "" }
                )));
            }
        }
        Ok(())
    }

    fn options(&self, title: Option<String>) -> unilateral_report::ReportOptions {
        unilateral_report::ReportOptions {
            pairs: self.report_pairs.clone(),
            moments: self.moments,
            stress: match self.stress {
                StressArg::Vm => unilateral_report::StressComponent::VonMises,
                StressArg::Sxx => unilateral_report::StressComponent::Sxx,
                StressArg::Syy => unilateral_report::StressComponent::Syy,
            },
            title,
        }
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Follow the load path of a problem file and report the solution.
    Solve {
        /// A structural model or a contact-zone problem (.toml or .json).
        file: PathBuf,
        /// The load p* at which the solution is reported (default: the file's, else 1).
        #[arg(long, allow_negative_numbers = true)]
        target: Option<f64>,
        /// How far to follow the path.
        #[arg(long, value_enum)]
        trace: Option<TraceArg>,
        /// The artificial tightening c ≥ 0.
        #[arg(long, allow_negative_numbers = true)]
        tightening: Option<f64>,
        /// Write the result document as JSON to this file (`-` for stdout).
        #[arg(long, value_name = "OUT.json")]
        json: Option<PathBuf>,
        /// Write CSV tables (pairs.csv, steps.csv) into this directory.
        #[arg(long, value_name = "DIR")]
        csv: Option<PathBuf>,
        /// Write the load-path charts, the structure picture and report.html into this directory.
        #[arg(long, value_name = "DIR")]
        report: Option<PathBuf>,
        /// Write ParaView files (.vtu per event, .pvd collection) into this directory
        /// (structural models).
        #[arg(long, value_name = "DIR")]
        vtk: Option<PathBuf>,
        #[command(flatten)]
        report_args: ReportArgs,
    },
    /// Print the Lemke tableaux of the path, step by step, as in the paper's Tables 1-3.
    Tableau {
        /// A contact-zone problem (.toml or .json).
        file: PathBuf,
        /// Print at most this many steps.
        #[arg(long)]
        steps: Option<usize>,
        /// Write the tableaux as JSON to this file (`-` for stdout).
        #[arg(long, value_name = "OUT.json")]
        json: Option<PathBuf>,
    },
    /// Solve a plain LCP w = Mz + q (Siconos .dat, .toml or .json).
    Lcp {
        /// The problem file.
        file: PathBuf,
        /// Write the result as JSON to this file (`-` for stdout).
        #[arg(long, value_name = "OUT.json")]
        json: Option<PathBuf>,
    },
    /// List the bundled examples, or write one out to start from.
    Example {
        /// The example to write out.
        name: Option<String>,
        /// Directory to write into (default: the current directory).
        #[arg(long, value_name = "DIR", default_value = ".")]
        to: PathBuf,
        /// Overwrite an existing file.
        #[arg(long)]
        force: bool,
    },
}

/// Why a run did not end with an answer. [`Failure::exit_code`] is the only place where a
/// failure becomes an exit status, and the `*_failure` functions below the only places where a
/// library error becomes a failure: each matches its error's variants exhaustively, so a new
/// variant does not compile until it is classified.
#[derive(Debug)]
enum Failure {
    /// Bad input (exit 2): the message names the file, the place in it and what is wrong.
    Input(String),
    /// The program's fault (exit 1): the message says what failed.
    Internal(String),
}

impl Failure {
    /// The exit status of the contract: 2 bad input, 1 internal failure (0 is an answer).
    fn exit_code(&self) -> u8 {
        match self {
            Failure::Input(_) => 2,
            Failure::Internal(_) => 1,
        }
    }

    /// The message printed on stderr.
    fn message(&self) -> String {
        match self {
            Failure::Input(msg) => format!("error: {msg}"),
            Failure::Internal(msg) => format!(
                "internal error: {msg}\n\
                 This is a fault of unilateral {}, not of the input. Please report it, with the \
                 input file and the command line, to the maintainers of unilateral.",
                env!("CARGO_PKG_VERSION")
            ),
        }
    }
}

/// Where the contact zone handed to the contact solver comes from: the user typed it (a
/// contact-zone file), or the program computed it from a structural model (then a bad matrix is
/// the program's fault: the user never wrote it).
#[derive(Clone, Copy, Debug, PartialEq)]
enum ZoneOrigin {
    /// A contact-zone problem file.
    File,
    /// Condensed from a structural model.
    Condensed,
}

/// A reader's error: always bad input; the error names the file and the place.
fn input_failure(e: unilateral_io::InputError) -> Failure {
    Failure::Input(e.to_string())
}

/// An error of the contact solver for the problem in `file`.
fn contact_failure(
    file: &Path,
    e: &unilateral_contact::ContactError,
    origin: ZoneOrigin,
) -> Failure {
    use unilateral_contact::ContactError as E;
    let internal = match e {
        // The solve settings and the per-pair data copied from the user's file (friction, gap)
        // are the user's, whatever the origin of the zone; so is a problem without pairs.
        E::Settings(_) | E::Negative { .. } | E::Empty => false,
        // Numbers whose products leave double precision: the user's extreme values, whether
        // typed in a contact-zone file or entered as a model's properties.
        E::OutOfRange(_) => false,
        // The engine failed on data that passed every check.
        E::Internal(_) => true,
        // Matrices and load vectors: the user's in a contact-zone file, the program's when they
        // were condensed from a structural model.
        E::MatrixSize { .. }
        | E::VectorSize { .. }
        | E::NotFinite { .. }
        | E::NotSymmetric { .. }
        | E::NegativeDiagonal { .. } => origin == ZoneOrigin::Condensed,
    };
    if internal {
        Failure::Internal(format!(
            "{}: the contact zone condensed from the model was refused by the contact solver: {e}",
            file.display()
        ))
    } else {
        Failure::Input(format!("{}: {e}", file.display()))
    }
}

/// An error of the analysis of the structural model in `file`.
fn analysis_failure(file: &Path, e: &unilateral_analysis::AnalysisError) -> Failure {
    use unilateral_analysis::AnalysisError as E;
    match e {
        E::Model { .. } if e.is_internal() => Failure::Internal(format!("{}: {e}", file.display())),
        E::Model { .. } | E::Unstable { .. } | E::PulledApart { .. } => {
            Failure::Input(format!("{}: {e}", file.display()))
        }
        E::Contact(c) => contact_failure(file, c, ZoneOrigin::Condensed),
        // `NotOnPath` only arises where the program itself asked for a load of the path (the
        // events of a report), so it is the program's fault here.
        // The framing ("internal error", whose fault) is the CLI's; the analysis' own words for
        // it are not repeated.
        E::Internal { what, message } => {
            Failure::Internal(format!("{}: {what}: {message}", file.display()))
        }
        E::Recovery { .. } | E::Equilibrium { .. } | E::NotOnPath { .. } => {
            Failure::Internal(format!("{}: {e}", file.display()))
        }
    }
}

/// An error of the LCP engine on the plain LCP in `file`: the file's data was refused.
fn lcp_failure(file: &Path, e: &unilateral_lcp::LcpError) -> Failure {
    use unilateral_lcp::LcpError as E;
    match e {
        E::Dimension(_) | E::NotFinite { .. } | E::Settings(_) | E::Empty => {
            Failure::Input(format!("{}: {e}", file.display()))
        }
    }
}

/// A report that could not be written: the directory named on the command line.
fn report_failure(e: &unilateral_report::ReportError) -> Failure {
    match e {
        unilateral_report::ReportError::Io { .. } => Failure::Input(e.to_string()),
        unilateral_report::ReportError::NonFinite { .. } => Failure::Internal(e.to_string()),
    }
}

/// How a load path ended: every ending is an answer except a numerical failure, which is the
/// program's fault. What was computed before it is still printed and written; then the run
/// exits 1.
fn outcome_failure(file: &Path, sol: &unilateral_contact::ContactSolution) -> Option<Failure> {
    ending_failure(file, &sol.outcome, sol.steps.len())
}

/// [`outcome_failure`] for an outcome reached after `steps` steps.
fn ending_failure(
    file: &Path,
    outcome: &unilateral_contact::Outcome,
    steps: usize,
) -> Option<Failure> {
    use unilateral_contact::Outcome as O;
    match outcome {
        O::TargetReached
        | O::Ray { .. }
        | O::Mechanism { .. }
        | O::ReturnedToZero
        | O::IterationLimit
        | O::NoSolutionAtStart => None,
        O::NumericalFailure => Some(Failure::Internal(format!(
            "{}: the load path stopped at a numerically singular basis after {} steps (status \
             numerical_failure); the output holds the events before it, no solution is reported",
            file.display(),
            steps
        ))),
    }
}

/// How a plain LCP solve ended: every status is an answer except a numerical failure (exit 1).
fn lcp_status_failure(file: &Path, status: unilateral_lcp::LcpStatus) -> Option<Failure> {
    use unilateral_lcp::LcpStatus as S;
    match status {
        S::Solved | S::Ray | S::IterationLimit => None,
        S::NumericalFailure => Some(Failure::Internal(format!(
            "{}: the LCP engine could not produce a verified finite solution (status \
             numerical_failure)",
            file.display()
        ))),
    }
}

/// A non-finite result is the program's fault: exit 1.
impl From<unilateral_io::NonFiniteOutput> for Failure {
    fn from(e: unilateral_io::NonFiniteOutput) -> Self {
        Failure::Internal(e.to_string())
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            // Usage errors are bad input (2); --help and --version are answers (0).
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("{}", failure.message());
            ExitCode::from(failure.exit_code())
        }
    }
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Solve {
            file,
            target,
            trace,
            tightening,
            json,
            csv,
            report,
            vtk,
            report_args,
        } => {
            let problem = unilateral_io::read_problem(&file).map_err(input_failure)?;
            let overrides = Overrides {
                target,
                trace,
                tightening,
            };
            match problem {
                unilateral_io::Problem::ContactZone(mut problem) => {
                    overrides.apply(&mut problem.settings)?;
                    let sol = unilateral_contact::solve(&problem.zone, &problem.settings)
                        .map_err(|e| contact_failure(&file, &e, ZoneOrigin::File))?;
                    let title = format!(
                        "unilateral {} — {} (contact zone, {} pairs)",
                        env!("CARGO_PKG_VERSION"),
                        file.display(),
                        problem.zone.pairs()
                    );
                    if json.as_deref() != Some(Path::new("-")) {
                        print!("{}", unilateral_io::contact_summary(&sol, &title)?);
                    }
                    if let Some(out) = json {
                        write_json(&out, &unilateral_io::contact_json(&sol)?)?;
                    }
                    if let Some(dir) = csv {
                        report_files(unilateral_io::write_contact_csv(&sol, &dir), &dir)?;
                    }
                    if vtk.is_some() {
                        return Err(Failure::Input(
                            "--vtk needs a structural model: a contact-zone problem has no mesh"
                                .into(),
                        ));
                    }
                    if let Some(dir) = report {
                        report_args.check(&sol.pairs)?;
                        let files = unilateral_report::write_path_report(
                            &sol,
                            &dir,
                            &report_args.options(None),
                        )
                        .map_err(|e| report_failure(&e))?;
                        report_files(Ok(files), &dir)?;
                    }
                    if let Some(f) = outcome_failure(&file, &sol) {
                        return Err(f);
                    }
                }
                unilateral_io::Problem::Structural(mut problem) => {
                    overrides.apply(&mut problem.settings)?;
                    let progress = Progress::new();
                    progress.say(&format!(
                        "{} nodes, {} elements, {} contact pairs: condensing to the contact zone, \
                         following the load path, recovering the results…",
                        problem.names.nodes.len(),
                        problem.names.elements.len(),
                        problem.names.pairs.len()
                    ));
                    let names = unilateral_analysis::Names {
                        nodes: problem.names.nodes.clone(),
                        elements: problem.names.elements.clone(),
                    };
                    let a = unilateral_analysis::analyze_named(
                        &problem.model,
                        &problem.settings,
                        &names,
                    )
                    .map_err(|e| analysis_failure(&file, &e))?;
                    progress.say(&format!(
                        "done: {} steps of the load path, {:.2} s",
                        a.solution.steps.len(),
                        progress.elapsed()
                    ));
                    let title = format!(
                        "unilateral {} — {}{} ({} nodes, {} elements, {} contact pairs)",
                        env!("CARGO_PKG_VERSION"),
                        file.display(),
                        problem
                            .title
                            .as_deref()
                            .map(|t| format!(": {t}"))
                            .unwrap_or_default(),
                        problem.names.nodes.len(),
                        problem.names.elements.len(),
                        a.zone.pairs()
                    );
                    if json.as_deref() != Some(Path::new("-")) {
                        print!("{}", unilateral_io::structural_summary(&a, &title)?);
                    }
                    if let Some(out) = json {
                        write_json(&out, &unilateral_io::structural_json(&a)?)?;
                    }
                    if let Some(dir) = csv {
                        report_files(unilateral_io::write_structural_csv(&a, &dir), &dir)?;
                    }
                    if let Some(dir) = vtk {
                        report_files(unilateral_io::write_vtk_for(&problem.model, &a, &dir), &dir)?;
                    }
                    if let Some(dir) = report {
                        report_args.check(&a.solution.pairs)?;
                        let options = report_args.options(problem.title.clone());
                        let files =
                            unilateral_report::write_report_for(&problem.model, &a, &dir, &options)
                                .map_err(|e| report_failure(&e))?;
                        report_files(Ok(files), &dir)?;
                    }
                    if let Some(f) = outcome_failure(&file, &a.solution) {
                        return Err(f);
                    }
                }
            }
            Ok(())
        }
        Command::Tableau { file, steps, json } => {
            let problem = unilateral_io::read_contact_zone(&file).map_err(input_failure)?;
            let sol = unilateral_contact::solve(&problem.zone, &problem.settings)
                .map_err(|e| contact_failure(&file, &e, ZoneOrigin::File))?;
            let tables = sol.tableaux(steps);
            let label = |v| sol.lcp.label(v);
            if let Some(out) = &json {
                write_json(out, &unilateral_io::tableaux_json(&tables, &label)?)?;
            }
            if json.as_deref() != Some(Path::new("-")) {
                println!(
                    "{} — parametric Lemke tableaux (tightening c = {}); * marks the leading column and row\n",
                    file.display(),
                    problem.settings.tightening
                );
                for t in &tables {
                    println!("{}", unilateral_io::tableau_text(t, &label)?);
                }
                println!("{}", sol.outcome.reading(problem.settings.target));
            }
            outcome_failure(&file, &sol).map_or(Ok(()), Err)
        }
        Command::Lcp { file, json } => {
            let lcp = unilateral_io::read_lcp(&file).map_err(input_failure)?;
            let sol = unilateral_lcp::solve_lcp(&lcp, &unilateral_lcp::Settings::default())
                .map_err(|e| lcp_failure(&file, &e))?;
            if json.as_deref() != Some(Path::new("-")) {
                let title = format!("{} (n = {})", file.display(), lcp.q.len());
                print!("{}", unilateral_io::lcp_summary(&sol, &title)?);
            }
            if let Some(out) = json {
                write_json(&out, &unilateral_io::lcp_json(&sol)?)?;
            }
            lcp_status_failure(&file, sol.status).map_or(Ok(()), Err)
        }
        Command::Example { name, to, force } => examples::run(name.as_deref(), &to, force),
    }
}

/// Progress messages on stderr, only when it is a terminal (never in pipes, files or tests).
struct Progress {
    start: std::time::Instant,
    on: bool,
}

impl Progress {
    fn new() -> Self {
        use std::io::IsTerminal;
        Self {
            start: std::time::Instant::now(),
            on: std::io::stderr().is_terminal(),
        }
    }

    fn say(&self, msg: &str) {
        if self.on {
            eprintln!("unilateral: {msg}");
        }
    }

    fn elapsed(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }
}

/// Command-line values that override the file's `[solve]` table.
struct Overrides {
    target: Option<f64>,
    trace: Option<TraceArg>,
    tightening: Option<f64>,
}

impl Overrides {
    fn apply(&self, settings: &mut unilateral_contact::SolveSettings) -> Result<(), Failure> {
        if let Some(t) = self.target {
            settings.target = t;
        }
        if let Some(t) = self.trace {
            settings.trace = match t {
                TraceArg::Target => unilateral_contact::Trace::Target,
                TraceArg::End => unilateral_contact::Trace::End,
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

fn report_files(written: std::io::Result<Vec<PathBuf>>, dir: &Path) -> Result<(), Failure> {
    let files = written.map_err(|e| match unilateral_io::NonFiniteOutput::in_io_error(&e) {
        Some(n) => Failure::Internal(n.to_string()),
        None => Failure::Input(format!("cannot write into {}: {e}", dir.display())),
    })?;
    for f in files {
        eprintln!("wrote {}", f.display());
    }
    Ok(())
}

fn write_json(out: &Path, value: &serde_json::Value) -> Result<(), Failure> {
    let text =
        serde_json::to_string_pretty(value).map_err(|e| Failure::Internal(format!("JSON: {e}")))?;
    if out == Path::new("-") {
        println!("{text}");
        return Ok(());
    }
    std::fs::write(out, text + "\n")
        .map_err(|e| Failure::Input(format!("cannot write {}: {e}", out.display())))
}

/// The classification of every error variant and every ending into the exit statuses of the
/// contract (reference: the contract of `docs/contact-zone.md`, "Exit status": the user's data
/// → 2, the program's own computation → 1, an answer → 0). The binary-level tests in
/// `tests/cli.rs` show the same through real runs for bad input.
#[cfg(test)]
mod tests {
    use super::*;
    use unilateral_analysis::AnalysisError;
    use unilateral_contact::{ContactError, Outcome};
    use unilateral_fem::{DofLabel, ElementId, FemError};
    use unilateral_lcp::{LcpError, LcpStatus};

    fn file() -> PathBuf {
        PathBuf::from("dir/model.toml")
    }

    /// Exit status and stderr text of a failure; every message must name the file.
    fn check(f: Failure, code: u8) -> String {
        let msg = f.message();
        assert_eq!(f.exit_code(), code, "{msg}");
        assert!(
            msg.contains("dir/model.toml"),
            "the file is not named: {msg}"
        );
        match code {
            1 => {
                assert!(msg.starts_with("internal error: "), "{msg}");
                assert!(msg.contains("fault of unilateral"), "{msg}");
                assert!(msg.contains("report it"), "{msg}");
            }
            2 => {
                assert!(msg.starts_with("error: "), "{msg}");
                assert!(!msg.contains("fault of unilateral"), "{msg}");
            }
            _ => unreachable!(),
        }
        msg
    }

    fn every_contact_error() -> Vec<ContactError> {
        vec![
            ContactError::Empty,
            ContactError::MatrixSize {
                name: "Rnn",
                rows: 2,
                cols: 3,
                pairs: 3,
            },
            ContactError::VectorSize {
                name: "gap".into(),
                len: 2,
                pairs: 3,
            },
            ContactError::NotFinite {
                name: "Rnn".into(),
                index: "[1][2]".into(),
            },
            ContactError::NotSymmetric {
                name: "Rtt",
                row: 1,
                col: 2,
                upper: 1.0,
                lower: 2.0,
            },
            ContactError::NegativeDiagonal {
                name: "Rnn",
                pair: 1,
                value: -1.0,
            },
            ContactError::Negative {
                name: "friction",
                pair: 2,
                value: -0.1,
            },
            ContactError::Settings("target must be > 0".into()),
            ContactError::OutOfRange("friction × Rnn overflows".into()),
            ContactError::Internal("a verified basis could not be found".into()),
        ]
    }

    /// Whether a contact error is about data the user typed in every case (settings, friction,
    /// gaps, an empty zone), not about matrices or load vectors the program may have computed.
    fn always_the_users(e: &ContactError) -> bool {
        matches!(
            e,
            ContactError::Empty
                | ContactError::Negative { .. }
                | ContactError::Settings(_)
                | ContactError::OutOfRange(_)
        )
    }

    #[test]
    fn a_contact_zone_file_is_the_users_data() {
        for e in every_contact_error() {
            // ... except a failure of the engine itself on data that passed every check.
            let code = if matches!(e, ContactError::Internal(_)) {
                1
            } else {
                2
            };
            check(contact_failure(&file(), &e, ZoneOrigin::File), code);
        }
    }

    #[test]
    fn a_condensed_contact_zone_is_the_programs() {
        // "Rnn must be positive semidefinite" about a matrix the user never wrote is not a
        // message the user can act on: it is the program's fault.
        for e in every_contact_error() {
            let code = if always_the_users(&e) { 2 } else { 1 };
            let msg = check(contact_failure(&file(), &e, ZoneOrigin::Condensed), code);
            if code == 1 && !matches!(e, ContactError::Internal(_)) {
                assert!(msg.contains("condensed from the model"), "{msg}");
            }
            let msg = check(analysis_failure(&file(), &AnalysisError::Contact(e)), code);
            assert!(!msg.is_empty());
        }
    }

    #[test]
    fn analysis_errors() {
        let fem = FemError::NonPositiveProperty {
            element: ElementId(0),
            property: "E",
            value: -1.0,
        };
        let model = AnalysisError::Model {
            message: "element `AB`: E must be positive and finite, got -1".into(),
            source: fem.clone(),
        };
        check(analysis_failure(&file(), &model), 2);
        let unstable = AnalysisError::Unstable {
            free: vec![("beam.0".into(), DofLabel::Uy)],
        };
        let msg = check(analysis_failure(&file(), &unstable), 2);
        assert!(msg.contains("node `beam.0` uy"), "{msg}");
        // The program's own computations.
        let recovery = AnalysisError::Recovery {
            p: 1.0,
            source: FemError::LinearAlgebra("singular".into()),
        };
        check(analysis_failure(&file(), &recovery), 1);
        let balance = AnalysisError::Equilibrium {
            p: 1.0,
            relative: 0.3,
        };
        let msg = check(analysis_failure(&file(), &balance), 1);
        assert!(msg.contains("out of balance"), "{msg}");
        let off_path = AnalysisError::NotOnPath {
            p: 2.0,
            end: "p = 1".into(),
        };
        check(analysis_failure(&file(), &off_path), 1);
        let internal = AnalysisError::Internal {
            what: "the contact solver refused the condensed contact zone".into(),
            message: "Rnn is not symmetric".into(),
        };
        check(analysis_failure(&file(), &internal), 1);
        let pulled = AnalysisError::PulledApart {
            pairs: vec!["base.1".into()],
            forces: vec![-10.0],
            resultant: [0.0, 10.0],
        };
        let msg = check(analysis_failure(&file(), &pulled), 2);
        assert!(msg.contains("base.1"), "{msg}");
        // The CLI's classification agrees with the analysis' own.
        for e in [model, unstable, recovery, balance, internal, pulled] {
            let code = if e.is_internal() { 1 } else { 2 };
            check(analysis_failure(&file(), &e), code);
        }
    }

    #[test]
    fn lcp_errors_are_the_files() {
        for e in [
            LcpError::Dimension("M is 2×3".into()),
            LcpError::NotFinite {
                what: "q",
                index: "2".into(),
            },
            LcpError::Settings("covering must be positive".into()),
            LcpError::Empty,
        ] {
            check(lcp_failure(&file(), &e), 2);
        }
    }

    #[test]
    fn every_ending_but_a_numerical_failure_is_an_answer() {
        for o in [
            Outcome::TargetReached,
            Outcome::Ray { p_from: 1.0 },
            Outcome::Mechanism {
                p_limit: 2.0,
                mode: vec![(1.0, 0.0)],
            },
            Outcome::ReturnedToZero,
            Outcome::IterationLimit,
            Outcome::NoSolutionAtStart,
        ] {
            assert!(ending_failure(&file(), &o, 3).is_none(), "{o:?}");
        }
        let f = ending_failure(&file(), &Outcome::NumericalFailure, 3).unwrap();
        let msg = check(f, 1);
        assert!(
            msg.contains("numerical_failure") && msg.contains("3 steps"),
            "{msg}"
        );
        for s in [LcpStatus::Solved, LcpStatus::Ray, LcpStatus::IterationLimit] {
            assert!(lcp_status_failure(&file(), s).is_none(), "{s:?}");
        }
        let f = lcp_status_failure(&file(), LcpStatus::NumericalFailure).unwrap();
        let msg = check(f, 1);
        assert!(msg.contains("numerical_failure"), "{msg}");
    }

    #[test]
    fn a_report_that_cannot_be_written_is_the_users_a_non_finite_picture_the_programs() {
        let io = unilateral_report::ReportError::Io {
            path: PathBuf::from("/no/such/dir/forces.svg"),
            source: std::io::Error::from(std::io::ErrorKind::NotFound),
        };
        let f = report_failure(&io);
        let msg = f.message();
        assert_eq!(f.exit_code(), 2, "{msg}");
        assert!(msg.contains("/no/such/dir/forces.svg"), "{msg}");
        let nan = unilateral_report::ReportError::NonFinite {
            file: "forces.svg",
            token: "NaN".into(),
        };
        let f = report_failure(&nan);
        let msg = f.message();
        assert_eq!(f.exit_code(), 1, "{msg}");
        assert!(msg.contains("forces.svg") && msg.contains("fault"), "{msg}");
    }

    #[test]
    fn an_input_error_keeps_the_readers_place() {
        let dir = std::env::temp_dir().join(format!("unilateral-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("model.toml");
        std::fs::write(&path, "[contact_zone]\nRnn = [[1.0, 2.0], [3.0]]\n").unwrap();
        let e = unilateral_io::read_problem(&path).unwrap_err();
        let f = input_failure(e);
        let msg = f.message();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(f.exit_code(), 2);
        assert!(msg.contains(&format!("{}:2:", path.display())), "{msg}");
    }
}
