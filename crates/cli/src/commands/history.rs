//! `unilateral solve FILE` on a file with `[[history]]` stages: the load history followed with
//! incremental friction on the contact zone (given, or condensed from the model), its summary,
//! and the files asked for (`docs/history.md`).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use unilateral_analysis::Timings;
use unilateral_contact::{History, HistorySolution, Stage, StageStatus};
use unilateral_output::HistoryChartOptions;

use crate::args::SolveArgs;
use crate::commands::solve::write_outputs;
use crate::failure::{analysis_failure, contact_failure, Failure, ZoneOrigin};
use crate::output::{report_files, Drawer};
use unilateral_lcp::Phase;

/// Writes named text files into `dir` (created if needed); returns their paths.
fn write_named<T: AsRef<[u8]>>(
    dir: &Path,
    files: Vec<(String, T)>,
) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut out = Vec::with_capacity(files.len());
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text)?;
        out.push(path);
    }
    Ok(out)
}

fn chart_options(args: &SolveArgs) -> HistoryChartOptions {
    HistoryChartOptions {
        pairs: args.report_args.report_pairs.clone(),
    }
}

/// The summary with the file's units under its first line (as the paper's path has them).
fn with_units_line(summary: String, units: Option<&str>) -> String {
    let Some(u) = units else { return summary };
    match summary.split_once('\n') {
        Some((first, rest)) => format!("{first}\nunits: {u}\n{rest}"),
        None => format!("{summary}\nunits: {u}\n"),
    }
}

/// The result document with the file's `title` and `units` (absent when the file has none, as
/// in the paper's path's documents).
fn with_about(
    mut doc: serde_json::Value,
    title: Option<&str>,
    units: Option<&str>,
) -> serde_json::Value {
    if let Some(obj) = doc.as_object_mut() {
        if let Some(t) = title {
            obj.insert("title".into(), t.into());
        }
        if let Some(u) = units {
            obj.insert("units".into(), u.into());
        }
    }
    doc
}

/// The file's title and units for the writers that label columns with them.
fn about(title: &Option<String>, units: &Option<String>) -> unilateral_output::About {
    unilateral_output::About {
        title: title.clone(),
        units: units.clone(),
    }
}

/// Exit status of a history: every status is an answer except a numerical failure (exit 1)
/// and a state beyond double precision (exit 2: the data's conditioning, which the user can
/// change).
fn history_failure(file: &Path, h: &HistorySolution) -> Option<Failure> {
    let last = h.stages.last()?;
    let reason = |or: &str| {
        format!(
            "{}: {}",
            file.display(),
            last.reason.as_deref().unwrap_or(or)
        )
    };
    match last.status {
        StageStatus::NumericalFailure => Some(Failure::Internal(reason(
            "the history stopped at a numerical failure",
        ))),
        StageStatus::Unresolved => Some(Failure::Input(reason(
            "the history reached a state beyond double precision",
        ))),
        _ => None,
    }
}

/// The load–displacement curves of `nodes` (default: the node that moves most at the end of
/// the history) against the factor of the case that changes most, as a report picture.
fn node_pictures(
    a: &unilateral_analysis::HistoryAnalysis,
    nodes: &[usize],
) -> Result<Vec<(String, String, String)>, Failure> {
    let Some(case) = unilateral_output::busiest_case(&a.history) else {
        return Ok(Vec::new());
    };
    let nodes: Vec<usize> = if nodes.is_empty() {
        let Some(r) = a.stage_results.last() else {
            return Ok(Vec::new());
        };
        let top = r
            .displacements
            .iter()
            .enumerate()
            .max_by(|x, y| x.1[0].hypot(x.1[1]).total_cmp(&y.1[0].hypot(y.1[1])))
            .map(|(k, _)| k);
        top.into_iter().collect()
    } else {
        nodes.to_vec()
    };
    let names: Vec<String> = nodes
        .iter()
        .map(|&n| a.condensed.model().names().node(unilateral_fem::NodeId(n)))
        .collect();
    let curves = unilateral_output::node_curves(a, &nodes, case).map_err(Failure::Internal)?;
    let case_name = &a.history.cases[case];
    let svg = unilateral_output::node_curves_svg(&names, case_name, &curves)?;
    Ok(vec![(
        "history-nodes.svg".into(),
        format!(
            "The factor of load case `{case_name}` against the displacements of node(s) {}",
            names.join(", ")
        ),
        svg,
    )])
}

/// A contact-zone problem with a history.
pub(crate) fn zone(
    args: &SolveArgs,
    drawer: &Drawer,
    problem: unilateral_io::ContactZoneProblem,
    stages: Vec<Stage>,
    read: Duration,
) -> Result<(), Failure> {
    let file = &args.file;
    if args.vtk.is_some() {
        return Err(Failure::Input(
            "--vtk needs a structural model: a contact-zone problem has no mesh".into(),
        ));
    }
    crate::commands::solve::nodes_need_a_structural_history(args, false, true)?;
    args.report_args
        .no_structure_picture("a contact zone's load history")?;
    if args.report.is_some() {
        args.report_args.check(&problem.zone.pair_names)?;
    }
    let started = Instant::now();
    let history = History {
        cases: problem.zone.cases.clone(),
        stages,
    };
    let h = unilateral_contact::follow_history(&problem.zone, &history, &problem.settings.engine)
        .map_err(|e| contact_failure(file, &e, ZoneOrigin::File))?;
    drawer.phase(Phase::Writing);
    let timings = Timings {
        read: Some(read),
        solve: Some(started.elapsed()),
        ..Timings::default()
    };
    let title = format!(
        "unilateral {} — {} (contact zone, {} pairs, load history of {} stages)",
        env!("CARGO_PKG_VERSION"),
        file.display(),
        problem.zone.pairs(),
        history.stages.len()
    );
    let written = write_outputs(
        args,
        timings,
        || {
            unilateral_output::history_summary(&h, &title)
                .map(|s| with_units_line(s, problem.units.as_deref()))
        },
        || {
            unilateral_output::history_document(&h)
                .map(|d| with_about(d, problem.title.as_deref(), problem.units.as_deref()))
                .map_err(Failure::from)
        },
        || {
            // Each output asked for is written whatever another's fate; every failure is said
            // ([`Failure::all_of`]).
            let csv = || -> Result<(), Failure> {
                let Some(dir) = &args.csv else { return Ok(()) };
                let files = about(&problem.title, &problem.units)
                    .history_csv(&h)
                    .map_err(Failure::from)?;
                report_files(write_named(dir, files), dir)
            };
            let report = || -> Result<(), Failure> {
                let Some(dir) = &args.report else {
                    return Ok(());
                };
                let written = unilateral_output::write_history_report(
                    &h,
                    dir,
                    &title,
                    &chart_options(args),
                    Vec::new(),
                );
                report_files(written, dir)
            };
            Failure::all_of([csv(), report()])
        },
    );
    // The stage's own failure is said too where an output failed (the program's first).
    Failure::all_of([written, history_failure(file, &h).map_or(Ok(()), Err)])
}

/// A structural model with a history.
pub(crate) fn structural(
    args: &SolveArgs,
    drawer: &Drawer,
    problem: unilateral_io::StructuralProblem,
    stages: Vec<Stage>,
    read: Duration,
) -> Result<(), Failure> {
    let file = &args.file;
    if args.report.is_some() {
        let pairs: Vec<String> = (0..problem.model.pairs().len())
            .map(|i| problem.model.pair_name(i))
            .collect();
        args.report_args.check(&pairs)?;
    }
    args.report_args.no_structure_picture("a load history")?;
    let nodes: Vec<usize> = match &args.report_args.report_nodes {
        Some(names) => names
            .iter()
            .map(|n| {
                problem
                    .model
                    .names()
                    .node_id(n)
                    .map(|id| id.0)
                    .ok_or_else(|| {
                        Failure::Input(format!("--report-nodes: no node named '{n}' in the model"))
                    })
            })
            .collect::<Result<_, _>>()?,
        None => Vec::new(),
    };
    let a = unilateral_analysis::analyze_history(&problem.model, &stages, &problem.settings.engine)
        .map_err(|e| analysis_failure(file, &e))?;
    drawer.phase(Phase::Writing);
    let timings = Timings {
        read: Some(read),
        ..a.timings
    };
    let title = crate::commands::solve::structural_title(
        &problem,
        file,
        a.zone.pairs(),
        &format!(", load history of {} stages", stages.len()),
    );
    let written = write_outputs(
        args,
        timings,
        || {
            unilateral_output::history_summary(&a.history, &title)
                .map(|s| with_units_line(s, problem.units.as_deref()))
        },
        || {
            unilateral_output::history_structural_document(&a)
                .map(|d| with_about(d, problem.title.as_deref(), problem.units.as_deref()))
                .map_err(Failure::from)
        },
        || {
            // Each output asked for is written whatever another's fate; every failure is said
            // ([`Failure::all_of`]): a history's ParaView frames refused at a state beyond
            // double precision left the report unwritten, and unmentioned.
            let csv = || -> Result<(), Failure> {
                let Some(dir) = &args.csv else { return Ok(()) };
                let files = about(&problem.title, &problem.units)
                    .history_csv(&a.history)
                    .map_err(Failure::from)?;
                report_files(write_named(dir, files), dir)
            };
            let vtk = || -> Result<(), Failure> {
                let Some(dir) = &args.vtk else { return Ok(()) };
                let files = unilateral_output::history_vtk_with(&a, args.vtk_format.format());
                report_files(files.and_then(|f| write_named(dir, f)), dir)
            };
            let report = || -> Result<(), Failure> {
                let Some(dir) = &args.report else {
                    return Ok(());
                };
                let extra = node_pictures(&a, &nodes)?;
                let written = unilateral_output::write_history_report(
                    &a.history,
                    dir,
                    &title,
                    &chart_options(args),
                    extra,
                );
                report_files(written, dir)
            };
            Failure::all_of([csv(), vtk(), report()])
        },
    );
    // The stage's own failure is said too where an output failed (the program's first).
    Failure::all_of([
        written,
        history_failure(file, &a.history).map_or(Ok(()), Err),
    ])
}
