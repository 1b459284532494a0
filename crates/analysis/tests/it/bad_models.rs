//! Models that read correctly but cannot be analysed (rows `analysis` of
//! tests/data/bad-models/EXPECTED.txt): a clear error naming the offending nodes, no panic.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use unilateral_analysis::{analyze, AnalysisError};
use unilateral_io::read_model;

#[test]
fn analysis_time_errors_name_the_nodes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/bad-models");
    let table = std::fs::read_to_string(dir.join("EXPECTED.txt")).unwrap();
    let mut count = 0;
    for line in table.lines().map(str::trim) {
        if line.starts_with('#') || line.is_empty() {
            continue;
        }
        let cols: Vec<&str> = line.splitn(4, " | ").map(str::trim).collect();
        if cols[1] != "analysis" {
            continue;
        }
        count += 1;
        let p = read_model(&dir.join(cols[0])).unwrap();
        let r = catch_unwind(AssertUnwindSafe(|| analyze(&p.model, &p.settings)));
        let Ok(r) = r else {
            panic!("{}: panicked", cols[0])
        };
        let e = r
            .err()
            .unwrap_or_else(|| panic!("{}: analysed without error", cols[0]));
        let msg = e.to_string();
        println!("{}: {msg}", cols[0]);
        assert!(matches!(e, AnalysisError::Unstable { .. }), "{msg}");
        assert!(
            msg.contains(cols[3]),
            "{}: {msg:?} lacks {:?}",
            cols[0],
            cols[3]
        );
    }
    assert!(count >= 2);
}
