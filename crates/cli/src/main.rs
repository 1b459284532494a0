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

/// A failure of the run: bad input (exit 2) or an internal failure (exit 1).
enum Failure {
    Input(String),
    Internal(String),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(msg)) => {
            eprintln!("error: {msg}");
            ExitCode::from(2)
        }
        Err(Failure::Internal(msg)) => {
            eprintln!("internal error: {msg}");
            ExitCode::from(1)
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
            let problem =
                unilateral_io::read_problem(&file).map_err(|e| Failure::Input(e.to_string()))?;
            let overrides = Overrides {
                target,
                trace,
                tightening,
            };
            match problem {
                unilateral_io::Problem::ContactZone(mut problem) => {
                    overrides.apply(&mut problem.settings)?;
                    let sol = unilateral_contact::solve(&problem.zone, &problem.settings)
                        .map_err(|e| Failure::Input(format!("{}: {e}", file.display())))?;
                    let title = format!(
                        "unilateral {} — {} (contact zone, {} pairs)",
                        env!("CARGO_PKG_VERSION"),
                        file.display(),
                        problem.zone.pairs()
                    );
                    if json.as_deref() != Some(Path::new("-")) {
                        print!("{}", unilateral_io::contact_summary(&sol, &title));
                    }
                    if let Some(out) = json {
                        write_json(&out, &unilateral_io::contact_json(&sol))?;
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
                        .map_err(|e| Failure::Input(e.to_string()))?;
                        report_files(Ok(files), &dir)?;
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
                    .map_err(|e| Failure::Input(format!("{}: {e}", file.display())))?;
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
                        print!("{}", unilateral_io::structural_summary(&a, &title));
                    }
                    if let Some(out) = json {
                        write_json(&out, &unilateral_io::structural_json(&a))?;
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
                                .map_err(|e| Failure::Input(e.to_string()))?;
                        report_files(Ok(files), &dir)?;
                    }
                }
            }
            Ok(())
        }
        Command::Tableau { file, steps, json } => {
            let problem = unilateral_io::read_contact_zone(&file)
                .map_err(|e| Failure::Input(e.to_string()))?;
            let sol = unilateral_contact::solve(&problem.zone, &problem.settings)
                .map_err(|e| Failure::Input(format!("{}: {e}", file.display())))?;
            let tables = sol.tableaux(steps);
            let label = |v| sol.lcp.label(v);
            if let Some(out) = &json {
                write_json(out, &unilateral_io::tableaux_json(&tables, &label))?;
            }
            if json.as_deref() != Some(Path::new("-")) {
                println!(
                    "{} — parametric Lemke tableaux (tightening c = {}); * marks the leading column and row\n",
                    file.display(),
                    problem.settings.tightening
                );
                for t in &tables {
                    println!("{}", unilateral_io::tableau_text(t, &label));
                }
                println!("{}", sol.outcome.reading(problem.settings.target));
            }
            Ok(())
        }
        Command::Lcp { file, json } => {
            let lcp = unilateral_io::read_lcp(&file).map_err(|e| Failure::Input(e.to_string()))?;
            let sol = unilateral_lcp::solve_lcp(&lcp, &unilateral_lcp::Settings::default())
                .map_err(|e| Failure::Input(format!("{}: {e}", file.display())))?;
            if json.as_deref() != Some(Path::new("-")) {
                let title = format!("{} (n = {})", file.display(), lcp.q.len());
                print!("{}", unilateral_io::lcp_summary(&sol, &title));
            }
            if let Some(out) = json {
                write_json(&out, &unilateral_io::lcp_json(&sol))?;
            }
            Ok(())
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
    let files =
        written.map_err(|e| Failure::Input(format!("cannot write into {}: {e}", dir.display())))?;
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
