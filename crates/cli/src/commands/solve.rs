//! `unilateral solve FILE`: follow the load path of a contact-zone problem or a structural
//! model, print the summary and write the files asked for.

use std::path::{Path, PathBuf};

use crate::args::{Overrides, SolveArgs};
use crate::failure::{
    analysis_failure, contact_failure, input_failure, outcome_failure, report_failure, Failure,
    ZoneOrigin,
};
use crate::output::{report_files, write_json, Progress};

pub(crate) fn run(args: SolveArgs) -> Result<(), Failure> {
    let overrides = Overrides {
        target: args.target,
        trace: args.trace,
        tightening: args.tightening,
    };
    match unilateral_io::read_problem(&args.file).map_err(input_failure)? {
        unilateral_io::Problem::ContactZone(problem) => contact_zone(&args, &overrides, problem),
        unilateral_io::Problem::Structural(problem) => structural(&args, &overrides, problem),
    }
}

/// The summary on stdout (unless the JSON goes there), the JSON document and the CSV tables:
/// the step every kind of problem shares.
fn write_outputs(
    args: &SolveArgs,
    summary: impl FnOnce() -> Result<String, unilateral_output::NonFiniteOutput>,
    json: impl FnOnce() -> Result<serde_json::Value, unilateral_output::NonFiniteOutput>,
    csv: impl FnOnce(&Path) -> std::io::Result<Vec<PathBuf>>,
) -> Result<(), Failure> {
    if args.json.as_deref() != Some(Path::new("-")) {
        print!("{}", summary()?);
    }
    if let Some(out) = &args.json {
        write_json(out, &json()?)?;
    }
    if let Some(dir) = &args.csv {
        report_files(csv(dir), dir)?;
    }
    Ok(())
}

fn contact_zone(
    args: &SolveArgs,
    overrides: &Overrides,
    mut problem: unilateral_io::ContactZoneProblem,
) -> Result<(), Failure> {
    let file = &args.file;
    overrides.apply(&mut problem.settings)?;
    let sol = unilateral_contact::solve(&problem.zone, &problem.settings)
        .map_err(|e| contact_failure(file, &e, ZoneOrigin::File))?;
    let title = format!(
        "unilateral {} — {} (contact zone, {} pairs)",
        env!("CARGO_PKG_VERSION"),
        file.display(),
        problem.zone.pairs()
    );
    write_outputs(
        args,
        || unilateral_output::contact_summary(&sol, &title),
        || unilateral_output::contact_json(&sol),
        |dir| unilateral_output::write_contact_csv(&sol, dir),
    )?;
    if args.vtk.is_some() {
        return Err(Failure::Input(
            "--vtk needs a structural model: a contact-zone problem has no mesh".into(),
        ));
    }
    if let Some(dir) = &args.report {
        args.report_args.check(&sol.pairs)?;
        let files =
            unilateral_output::write_path_report(&sol, dir, &args.report_args.options(None))
                .map_err(|e| report_failure(&e))?;
        report_files(Ok(files), dir)?;
    }
    outcome_failure(file, &sol).map_or(Ok(()), Err)
}

fn structural(
    args: &SolveArgs,
    overrides: &Overrides,
    mut problem: unilateral_io::StructuralProblem,
) -> Result<(), Failure> {
    let file = &args.file;
    overrides.apply(&mut problem.settings)?;
    let progress = Progress::new();
    progress.say(&format!(
        "{} nodes, {} elements, {} contact pairs: condensing to the contact zone, following \
         the load path, recovering the results…",
        problem.model.names().nodes.len(),
        problem.model.names().elements.len(),
        problem.model.names().pairs.len()
    ));
    let a = unilateral_analysis::analyze(&problem.model, &problem.settings)
        .map_err(|e| analysis_failure(file, &e))?;
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
        problem.model.names().nodes.len(),
        problem.model.names().elements.len(),
        a.zone.pairs()
    );
    write_outputs(
        args,
        || unilateral_output::structural_summary(&a, &title),
        || unilateral_output::structural_json(&a),
        |dir| unilateral_output::write_structural_csv(&a, dir),
    )?;
    if let Some(dir) = &args.vtk {
        report_files(unilateral_output::write_vtk(&a, dir), dir)?;
    }
    if let Some(dir) = &args.report {
        args.report_args.check(&a.solution.pairs)?;
        let options = args.report_args.options(problem.title.clone());
        let files = unilateral_output::write_structural_report(&a, dir, &options)
            .map_err(|e| report_failure(&e))?;
        report_files(Ok(files), dir)?;
    }
    outcome_failure(file, &a.solution).map_or(Ok(()), Err)
}
