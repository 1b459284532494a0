//! `unilateral lcp FILE`: a plain LCP `w = Mz + q` by Lemke's method.

use std::path::Path;

use crate::args::LcpArgs;
use crate::failure::{input_failure, lcp_failure, lcp_status_failure, Failure};
use crate::output::write_json;

pub(crate) fn run(args: LcpArgs) -> Result<(), Failure> {
    let LcpArgs { file, json } = args;
    let lcp = unilateral_io::read_lcp(&file).map_err(input_failure)?;
    let sol = unilateral_lcp::solve_lcp(&lcp, &unilateral_lcp::Settings::default())
        .map_err(|e| lcp_failure(&file, &e))?;
    if json.as_deref() != Some(Path::new("-")) {
        let title = format!("{} (n = {})", file.display(), lcp.q.len());
        print!("{}", unilateral_output::lcp_summary(&sol, &title)?);
    }
    if let Some(out) = json {
        write_json(&out, &unilateral_output::lcp_json(&sol)?)?;
    }
    lcp_status_failure(&file, sol.status).map_or(Ok(()), Err)
}
