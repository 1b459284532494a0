//! `unilateral tableau FILE`: the Lemke tableaux of the path, as in the paper's Tables 1–3.

use std::path::Path;

use crate::args::TableauArgs;
use crate::failure::{contact_failure, input_failure, outcome_failure, Failure, ZoneOrigin};
use crate::output::write_json;

pub(crate) fn run(args: TableauArgs) -> Result<(), Failure> {
    let TableauArgs { file, steps, json } = args;
    let problem = unilateral_io::read_contact_zone(&file).map_err(input_failure)?;
    let sol = unilateral_contact::solve(&problem.zone, &problem.settings)
        .map_err(|e| contact_failure(&file, &e, ZoneOrigin::File))?;
    let tables = sol
        .tableaux(steps)
        .map_err(|e| contact_failure(&file, &e, ZoneOrigin::File))?;
    let label = |v| sol.lcp.label(v);
    if let Some(out) = &json {
        write_json(out, &unilateral_output::tableaux_json(&tables, &label)?)?;
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
        crate::output::outln!("{}", sol.outcome.reading(problem.settings.target));
    }
    outcome_failure(&file, &sol).map_or(Ok(()), Err)
}
