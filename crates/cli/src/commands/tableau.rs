//! `unilateral tableau FILE`: the Lemke tableaux of the path, as in the paper's Tables 1–3.

use std::path::Path;

use crate::args::TableauArgs;
use crate::failure::{
    analysis_failure, contact_failure, input_failure, outcome_failure, Failure, ZoneOrigin,
};

struct Problem {
    settings: unilateral_contact::SolveSettings,
}

/// The tableaux are those of the paper's single path: a load history has none.
fn no_history(file: &Path, history: bool) -> Result<(), Failure> {
    if history {
        return Err(Failure::Input(format!(
            "{}: the file has [[history]] stages; `tableau` prints the tableaux of the paper's \
             single load path (a file without a history)",
            file.display()
        )));
    }
    Ok(())
}
use crate::output::write_json;

pub(crate) fn run(args: TableauArgs) -> Result<(), Failure> {
    let TableauArgs { file, steps, json } = args;
    // A structural model is condensed to its contact zone first: the tableaux are those of
    // that zone's path, the pairs named as in the model.
    let (zone, settings, origin) =
        match unilateral_io::read_problem(&file).map_err(input_failure)? {
            unilateral_io::Problem::ContactZone(p) => {
                no_history(&file, p.history.is_some())?;
                (p.zone, p.settings, ZoneOrigin::File)
            }
            unilateral_io::Problem::Structural(p) => {
                no_history(&file, p.history.is_some())?;
                let (_, zone) = unilateral_analysis::contact_zone_of(&p.model)
                    .map_err(|e| analysis_failure(&file, &e))?;
                (zone, p.settings, ZoneOrigin::Condensed)
            }
        };
    let problem = Problem { settings };
    let sol = unilateral_contact::solve_shared(std::sync::Arc::new(zone), &problem.settings)
        .map_err(|e| contact_failure(&file, &e, origin))?;
    let tables = sol
        .tableaux(steps)
        .map_err(|e| contact_failure(&file, &e, origin))?;
    let label = |v| sol.label(v);
    if let Some(out) = &json {
        write_json(out, unilateral_output::tableaux_json(&tables, &label)?)?;
    }
    if json.as_deref() != Some(Path::new("-")) {
        crate::output::outln!(
            "{} — parametric Lemke tableaux (tightening c = {}); * marks the leading column and row\n",
            file.display(),
            problem.settings.tightening
        );
        for t in &tables {
            crate::output::outln!("{}", unilateral_output::tableau_text(t, &label)?);
        }
        crate::output::outln!("{}", sol.reading());
    }
    outcome_failure(&file, &sol).map_or(Ok(()), Err)
}
