//! `unilateral zone MODEL --out ZONE.toml`: a structural model's contact zone written as a
//! contact-zone file — for another program, for the paper's tables, or to solve the zone alone.

use crate::args::ZoneArgs;
use crate::failure::{analysis_failure, input_failure, Failure};

pub(crate) fn run(args: ZoneArgs) -> Result<(), Failure> {
    let file = &args.model;
    let problem = match unilateral_io::read_problem(file).map_err(input_failure)? {
        unilateral_io::Problem::Structural(p) => p,
        unilateral_io::Problem::ContactZone(_) => {
            return Err(Failure::Input(format!(
                "{}: `zone` writes the contact zone of a structural model; this file already is \
                 a contact-zone problem",
                file.display()
            )))
        }
    };
    let (_, zone) = unilateral_analysis::contact_zone_of(&problem.model)
        .map_err(|e| analysis_failure(file, &e))?;
    let mut header = vec![format!(
        "The contact zone of {} ({} pairs), written by unilateral {}: `unilateral solve` on \
         this file follows the same path as on the model.",
        file.display(),
        zone.pairs(),
        env!("CARGO_PKG_VERSION")
    )];
    header.push(
        "Rnn[i][j]: force in normal link i from a unit opening of normal link j, all other links \
         held (formulation §2); loads: link forces of the bonded structure per case."
            .into(),
    );
    let about = unilateral_output::About {
        title: problem.title.clone(),
        units: problem.units.clone(),
    };
    let text = unilateral_output::zone_toml(
        &zone,
        &problem.settings,
        problem.history.as_deref(),
        &header,
        &about,
    )?;
    if args.out == std::path::Path::new("-") {
        crate::output::out(&text);
        return Ok(());
    }
    std::fs::write(&args.out, text)
        .map_err(|e| Failure::Input(format!("cannot write {}: {e}", args.out.display())))?;
    crate::output::err_line(&format!("wrote {}", args.out.display()));
    Ok(())
}
