//! `unilateral lcp FILE`: a plain LCP `w = Mz + q` by Lemke's method.

use std::path::Path;
use std::time::Instant;

use unilateral_analysis::Timings;

use crate::args::LcpArgs;
use crate::failure::{input_failure, lcp_failure, lcp_status_failure, Failure};
use crate::output::{write_json, Drawer};
use unilateral_output::{timings_summary, with_timings};

pub(crate) fn run(args: LcpArgs) -> Result<(), Failure> {
    let LcpArgs {
        file,
        json,
        progress,
    } = args;
    let drawer = Drawer::start(progress);
    drawer.phase(unilateral_lcp::Phase::Reading);
    let started = Instant::now();
    let lcp = unilateral_io::read_lcp(&file).map_err(input_failure)?;
    let mut timings = Timings {
        read: Some(started.elapsed()),
        ..Timings::default()
    };
    let started = Instant::now();
    let settings = unilateral_lcp::Settings {
        progress: drawer.handle(),
        ..unilateral_lcp::Settings::default()
    };
    let sol = unilateral_lcp::solve_lcp(&lcp, &settings).map_err(|e| lcp_failure(&file, &e))?;
    timings.solve = Some(started.elapsed());
    drawer.phase(unilateral_lcp::Phase::Writing);
    if json.as_deref() != Some(Path::new("-")) {
        // The summary with the timings so far, then the JSON with `write` = printing it.
        let started = Instant::now();
        let title = format!("{} (n = {})", file.display(), lcp.q.len());
        let summary = unilateral_output::lcp_summary(&sol, &title)?;
        crate::output::out(&format!("{summary}{}", timings_summary(&timings)));
        timings.write = Some(started.elapsed());
    }
    if let Some(out) = json {
        let doc = with_timings(unilateral_output::lcp_json(&sol)?, &timings);
        write_json(&out, doc)?;
    }
    lcp_status_failure(&file, sol.status).map_or(Ok(()), Err)
}
