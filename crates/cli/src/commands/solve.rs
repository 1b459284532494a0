//! `unilateral solve FILE`: follow the load path of a contact-zone problem or a structural
//! model, print the summary and write the files asked for.
//!
//! The outputs are written in this order: the summary (stdout; it ends with the timings known
//! by then), the CSV tables, the ParaView files, the report, and the JSON document last, so
//! that its `timings.write` can cover the time spent writing all the others (the JSON cannot
//! contain the time of writing itself). The command line is checked before the solve, so a
//! bad one costs no work and writes nothing.

use std::path::Path;
use std::time::{Duration, Instant};

use unilateral_analysis::Timings;

use crate::args::{Overrides, SolveArgs};
use crate::failure::{
    analysis_failure, contact_failure, input_failure, outcome_failure, report_failure, Failure,
    ZoneOrigin,
};
use crate::output::{path_output_failure, report_files, write_document, Drawer};
use unilateral_lcp::Phase;
use unilateral_output::{timings_summary, with_timings};

pub(crate) fn run(args: SolveArgs) -> Result<(), Failure> {
    let overrides = Overrides {
        target: args.target,
        trace: args.trace,
        tightening: args.tightening,
    };
    let drawer = Drawer::start(args.progress);
    drawer.phase(Phase::Reading);
    let started = Instant::now();
    let problem = unilateral_io::read_problem(&args.file).map_err(input_failure)?;
    let read = started.elapsed();
    match problem {
        unilateral_io::Problem::ContactZone(mut problem) => match problem.history.take() {
            Some(stages) => {
                no_path_options(&overrides)?;
                no_breakpoints_option(&args)?;
                problem.settings.engine.progress = drawer.handle();
                crate::commands::history::zone(&args, &drawer, problem, stages, read)
            }
            None => {
                nodes_need_a_structural_history(&args, false, false)?;
                problem.settings.engine.progress = drawer.handle();
                contact_zone(&args, &drawer, &overrides, problem, read)
            }
        },
        unilateral_io::Problem::Structural(mut problem) => match problem.history.take() {
            Some(stages) => {
                no_path_options(&overrides)?;
                no_breakpoints_option(&args)?;
                problem.settings.engine.progress = drawer.handle();
                crate::commands::history::structural(&args, &drawer, problem, stages, read)
            }
            None => {
                nodes_need_a_structural_history(&args, true, false)?;
                problem.settings.engine.progress = drawer.handle();
                structural(&args, &drawer, &overrides, problem, read)
            }
        },
    }
}

/// The first lines of a structural model's summary: the program, the file and its title, the
/// model's size (`extra` after the pairs, e.g. the history's stages), and how many pairs each
/// `[[contact]]` entry made when there are several entries (the contract of surface matching:
/// a user sees what `nearest` and `surface` found; an entry that makes none is an error).
pub(crate) fn structural_title(
    problem: &unilateral_io::StructuralProblem,
    file: &Path,
    pairs: usize,
    extra: &str,
) -> String {
    let mut title = format!(
        "unilateral {} — {}{} ({} nodes, {} elements, {} contact pairs{extra})",
        env!("CARGO_PKG_VERSION"),
        file.display(),
        problem
            .title
            .as_deref()
            .map(|t| format!(": {t}"))
            .unwrap_or_default(),
        problem.model.names().nodes.len(),
        problem.model.names().elements.len(),
        pairs
    );
    if problem.contact_entries.len() > 1 {
        let parts: Vec<String> = problem
            .contact_entries
            .iter()
            .map(|(name, n)| format!("{name} {n}"))
            .collect();
        title.push_str(&format!(
            "\npairs by [[contact]] entry: {}",
            parts.join(", ")
        ));
    }
    title
}

/// What the writers of the paper's path are told: the file's title and units, whether the JSON
/// holds the values at every breakpoint, how much the summary lists.
fn writer_options(
    args: &SolveArgs,
    title: Option<String>,
    units: Option<String>,
) -> (
    unilateral_output::About,
    unilateral_output::PathJsonOptions,
    unilateral_output::Detail,
) {
    let about = unilateral_output::About { title, units };
    let json = unilateral_output::PathJsonOptions {
        breakpoints: args.json_breakpoints,
        about: about.clone(),
    };
    let detail = unilateral_output::Detail {
        verbose: args.verbose,
    };
    (about, json, detail)
}

/// `--report-nodes` charts a structural model's load history; anywhere else it would be
/// ignored, so it is refused, saying what the file lacks: `structural` whether it is a
/// structural model, `history` whether it has `[[history]]` stages.
pub(crate) fn nodes_need_a_structural_history(
    args: &SolveArgs,
    structural: bool,
    history: bool,
) -> Result<(), Failure> {
    if args.report_args.report_nodes.is_some() {
        let lacks = match (structural, history) {
            (true, _) => "this model has no [[history]] stages",
            (false, true) => "this file is a contact zone, whose history has pairs but no nodes",
            (false, false) => "this file is a contact zone, with no nodes and no [[history]]",
        };
        return Err(Failure::Input(format!(
            "--report-nodes charts the load history of a structural model ([[history]] stages); \
             {lacks} (its pairs are charted with --report-pairs)"
        )));
    }
    Ok(())
}

/// `--target`, `--trace` and `--tightening` belong to the paper's single load path; a file with
/// a `[[history]]` is followed stage by stage without them.
fn no_path_options(o: &Overrides) -> Result<(), Failure> {
    let given = crate::failure::given_options(&[
        ("--target", o.target.is_some()),
        ("--trace", o.trace.is_some()),
        ("--tightening", o.tightening.is_some()),
    ]);
    if given.is_empty() {
        return Ok(());
    }
    Err(Failure::Input(format!(
        "{} {} not apply to a file with a [[history]]: a load history is followed stage by \
         stage from the unloaded state, without a target load or a tightening",
        given.join(", "),
        if given.len() == 1 { "does" } else { "do" }
    )))
}

/// `--json-breakpoints` adds every pair at every step to the JSON of a single load path; a
/// history's JSON has them at every change of every stage already, so the option would be
/// ignored there: it is refused.
fn no_breakpoints_option(args: &SolveArgs) -> Result<(), Failure> {
    if args.json_breakpoints {
        return Err(Failure::Input(
            "--json-breakpoints does not apply to a file with a [[history]]: its JSON has every \
             pair at every change of every stage already (history[k].steps[j].pairs)"
                .into(),
        ));
    }
    Ok(())
}

/// The step every kind of problem shares: the summary on stdout (unless the JSON goes there)
/// with the timings so far, the other files (`files`: CSV, ParaView, report) while the JSON
/// document's values are formed beside them on the thread pool (`json`: nothing it forms
/// depends on the files), then the JSON document written with `timings.write` = the time spent
/// on the other files (present only when something was written before the JSON). The JSON is
/// written even when writing the other files failed; the first failure is the one returned.
pub(crate) fn write_outputs<'a, D: Into<unilateral_output::PathDocument<'a>> + Send>(
    args: &SolveArgs,
    mut timings: Timings,
    summary: impl FnOnce() -> Result<String, unilateral_output::NonFiniteOutput>,
    json: impl FnOnce() -> Result<D, Failure> + Send,
    files: impl FnOnce() -> Result<(), Failure> + Send,
) -> Result<(), Failure> {
    let started = Instant::now();
    let to_stdout = args.json.as_deref() == Some(Path::new("-"));
    if !to_stdout {
        crate::output::out(&format!("{}{}", summary()?, timings_summary(&timings)));
    }
    let wanted = args.json.is_some();
    let (written, doc) = rayon::join(
        || {
            let written = files();
            (written, started.elapsed())
        },
        || wanted.then(json),
    );
    let (written, elapsed) = written;
    if !to_stdout || args.csv.is_some() || args.vtk.is_some() || args.report.is_some() {
        timings.write = Some(elapsed);
    }
    let json_written = match (&args.json, doc) {
        (Some(out), Some(doc)) => doc
            .and_then(|doc| write_document(out, doc.into().map(|doc| with_timings(doc, &timings)))),
        _ => Ok(()),
    };
    written.and(json_written)
}

fn contact_zone(
    args: &SolveArgs,
    drawer: &Drawer,
    overrides: &Overrides,
    mut problem: unilateral_io::ContactZoneProblem,
    read: Duration,
) -> Result<(), Failure> {
    let file = &args.file;
    overrides.apply(&mut problem.settings)?;
    if args.vtk.is_some() {
        return Err(Failure::Input(
            "--vtk needs a structural model: a contact-zone problem has no mesh".into(),
        ));
    }
    args.report_args.no_structure_picture("a contact zone")?;
    if args.report.is_some() {
        args.report_args.check(&problem.zone.pair_names)?;
    }
    let started = Instant::now();
    // The solution keeps the zone: handed over, not copied (the zone of m pairs is 4m² numbers).
    let zone = std::sync::Arc::new(problem.zone);
    let sol = unilateral_contact::solve_shared(zone, &problem.settings)
        .map_err(|e| contact_failure(file, &e, ZoneOrigin::File))?;
    drawer.phase(Phase::Writing);
    let timings = Timings {
        read: Some(read),
        solve: Some(started.elapsed()),
        ..Timings::default()
    };
    let title = format!(
        "unilateral {} — {} (contact zone, {} pairs)",
        env!("CARGO_PKG_VERSION"),
        file.display(),
        sol.pairs()
    );
    let (about, json_options, detail) =
        writer_options(args, problem.title.clone(), problem.units.clone());
    write_outputs(
        args,
        timings,
        || unilateral_output::contact_summary_detail(&sol, &title, &about, detail),
        || {
            unilateral_output::PathDocument::contact(&sol, &json_options)
                .map_err(path_output_failure)
        },
        || {
            // The tables and the report side by side on the thread pool (the solve is over):
            // each is announced in that order; every failure is said, the most serious returned.
            let (csv, report) = rayon::join(
                || {
                    args.csv.as_ref().map(|dir| {
                        report_files(
                            unilateral_output::write_contact_csv_with(&sol, dir, &about),
                            dir,
                        )
                    })
                },
                || {
                    args.report.as_ref().map(|dir| {
                        let options = args
                            .report_args
                            .options(problem.title.clone(), problem.units.clone());
                        unilateral_output::write_path_report(&sol, dir, &options)
                            .map_err(|e| report_failure(&e))
                            .map(|files| (files, dir))
                    })
                },
            );
            let report = report.map(|r| r.and_then(|(files, dir)| report_files(Ok(files), dir)));
            Failure::all_of([csv.unwrap_or(Ok(())), report.unwrap_or(Ok(()))])
        },
    )?;
    outcome_failure(file, &sol).map_or(Ok(()), Err)
}

fn structural(
    args: &SolveArgs,
    drawer: &Drawer,
    overrides: &Overrides,
    mut problem: unilateral_io::StructuralProblem,
    read: Duration,
) -> Result<(), Failure> {
    let file = &args.file;
    overrides.apply(&mut problem.settings)?;
    if args.report.is_some() {
        let pairs: Vec<String> = (0..problem.model.pairs().len())
            .map(|i| problem.model.pair_name(i))
            .collect();
        args.report_args.check(&pairs)?;
    }
    let a = unilateral_analysis::analyze(&problem.model, &problem.settings)
        .map_err(|e| analysis_failure(file, &e))?;
    drawer.phase(Phase::Writing);
    let timings = Timings {
        read: Some(read),
        ..a.timings
    };
    let title = structural_title(&problem, file, a.zone.pairs(), "");
    let (about, json_options, detail) =
        writer_options(args, problem.title.clone(), problem.units.clone());
    write_outputs(
        args,
        timings,
        || unilateral_output::structural_summary_detail(&a, &title, &about, detail),
        || {
            unilateral_output::PathDocument::structural(&a, &json_options)
                .map_err(path_output_failure)
        },
        || {
            // The tables, the ParaView files and the report side by side on the thread pool
            // (the solve is over): each is announced in that order; every failure is said, the
            // most serious returned.
            let (csv, (vtk, report)) = rayon::join(
                || {
                    args.csv.as_ref().map(|dir| {
                        (
                            unilateral_output::write_structural_csv_with(&a, dir, &about),
                            dir,
                        )
                    })
                },
                || {
                    rayon::join(
                        || {
                            args.vtk.as_ref().map(|dir| {
                                let format = args.vtk_format.format();
                                (unilateral_output::write_vtk_with(&a, dir, format), dir)
                            })
                        },
                        || {
                            args.report.as_ref().map(|dir| {
                                let options = args
                                    .report_args
                                    .options(problem.title.clone(), problem.units.clone());
                                (
                                    unilateral_output::write_structural_report(&a, dir, &options)
                                        .map_err(|e| report_failure(&e)),
                                    dir,
                                )
                            })
                        },
                    )
                },
            );
            let csv = csv.map_or(Ok(()), |(w, dir)| report_files(w, dir));
            let vtk = vtk.map_or(Ok(()), |(w, dir)| report_files(w, dir));
            let report = report.map_or(Ok(()), |(w, dir)| {
                w.and_then(|files| report_files(Ok(files), dir))
            });
            Failure::all_of([csv, vtk, report])
        },
    )?;
    outcome_failure(file, &a.solution).map_or(Ok(()), Err)
}
