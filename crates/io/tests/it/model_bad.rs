//! Every file of `tests/data/bad-models/` must be refused with an `InputError` that names the
//! file, the place (line:column) and the key, and contains the fragment listed in
//! `tests/data/bad-models/EXPECTED.txt`; nothing may panic. Files whose location column says
//! `analysis` are valid input whose problem shows at analysis time (checked by
//! crates/analysis/tests/it/bad_models.rs): here they must read without error.

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use unilateral_io::read_problem;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/bad-models")
}

struct Expected {
    location: String,
    key: Option<String>,
    fragment: String,
}

fn expected_table() -> BTreeMap<String, Expected> {
    let text = std::fs::read_to_string(dir().join("EXPECTED.txt")).unwrap();
    let mut out = BTreeMap::new();
    for line in text.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line.splitn(4, " | ").map(str::trim).collect();
        assert_eq!(cols.len(), 4, "EXPECTED.txt: bad row {line:?}");
        let prev = out.insert(
            cols[0].to_string(),
            Expected {
                location: cols[1].to_string(),
                key: (cols[2] != "-").then(|| cols[2].to_string()),
                fragment: cols[3].to_string(),
            },
        );
        assert!(prev.is_none(), "{} listed twice", cols[0]);
    }
    out
}

#[test]
fn every_bad_model_gives_a_located_error() {
    let table = expected_table();
    let mut files: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|n| n != "EXPECTED.txt")
        .collect();
    files.sort();
    assert!(files.len() >= 15);
    let mut failures = Vec::new();
    for name in &files {
        let Some(exp) = table.get(name) else {
            failures.push(format!("{name}: not listed in EXPECTED.txt"));
            continue;
        };
        let path = dir().join(name);
        let result = catch_unwind(AssertUnwindSafe(|| read_problem(&path)));
        let Ok(result) = result else {
            failures.push(format!("{name}: panicked"));
            continue;
        };
        if exp.location == "analysis" {
            if let Err(e) = result {
                failures.push(format!("{name}: should read, but: {e}"));
            }
            continue;
        }
        let e = match result {
            Ok(_) => {
                failures.push(format!("{name}: accepted"));
                continue;
            }
            Err(e) => e,
        };
        let shown = e.to_string();
        println!("{shown}");
        let loc = e.location.to_string();
        if !loc.ends_with(&exp.location) || e.location.line.is_none() {
            failures.push(format!(
                "{name}: location {loc}, expected …{}",
                exp.location
            ));
        }
        if e.key != exp.key {
            failures.push(format!("{name}: key {:?}, expected {:?}", e.key, exp.key));
        }
        if !shown.contains(&exp.fragment) {
            failures.push(format!(
                "{name}: message {shown:?} lacks {:?}",
                exp.fragment
            ));
        }
        assert_eq!(e.file(), path.as_path());
    }
    for name in table.keys() {
        if !files.contains(name) {
            failures.push(format!("{name}: listed but missing"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A name of a megabyte that matches nothing is refused quickly, and the message quotes only
/// its beginning and its length (not the whole megabyte).
#[test]
fn a_huge_unknown_node_name_gives_a_short_message() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge-name.toml");
    let name = "n".repeat(1_000_000);
    let text = format!(
        "[[nodes]]\nid = \"a\"\nx = 0.0\ny = 0.0\n\n[[nodes]]\nid = \"b\"\nx = 1.0\ny = 0.0\n\n\
         [[sections]]\nname = \"s\"\nE = 1.0\nA = 1.0\nI = 1.0\n\n\
         [[elements]]\ntype = \"frame\"\nnodes = [\"a\", \"b\"]\nsection = \"s\"\n\n\
         [[supports]]\nnodes = \"{name}\"\nfixed = true\n"
    );
    std::fs::write(&path, text).unwrap();
    let msg = read_problem(&path).unwrap_err().to_string();
    assert!(msg.contains("huge-name.toml:"), "{msg}");
    assert!(
        msg.contains("(1000000 characters)"),
        "{}",
        &msg[..msg.len().min(300)]
    );
    assert!(msg.len() < 1000, "a message of {} bytes", msg.len());
}
